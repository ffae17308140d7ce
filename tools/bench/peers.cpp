// peers.cpp — the peer list when the peers are linked in (TANDEM_BUILD_BENCH).
#include "peers.h"

namespace tandem::bench {

std::vector<Engine> peer_engines() {
#ifdef TANDEM_HAVE_BOX2D_V3
  return {box2d24_engine(), chipmunk_engine(), box2d3_engine(1), box2d3_engine(2)};
#else
  return {box2d24_engine(), chipmunk_engine()};
#endif
}

const char* peers_unavailable_reason() { return ""; }

}  // namespace tandem::bench
