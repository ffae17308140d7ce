// peers_none.cpp — the peer list of a build without TANDEM_BUILD_BENCH: the
// `tandem` CLI then carries no Box2D or Chipmunk code.
#include "harness.h"

namespace tandem::bench {

std::vector<Engine> peer_engines() { return {}; }

const char* peers_unavailable_reason() {
  return "this build has no peer engines (configure with -DTANDEM_BUILD_BENCH=ON, or run tandem_bench_physics)";
}

}  // namespace tandem::bench
