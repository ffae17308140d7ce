// peers.cpp — the peer list when the peers are linked in (TANDEM_BUILD_BENCH).
#include "peers.h"

namespace tandem::bench {

std::vector<Engine> peer_engines() { return {box2d24_engine(), chipmunk_engine()}; }

const char* peers_unavailable_reason() { return ""; }

}  // namespace tandem::bench
