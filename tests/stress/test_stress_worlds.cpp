// test_stress_worlds.cpp — the short ctest slice of the random-world stress
// (stress_world.h): a fixed range of seeds, each world run with every broad
// phase and once through a snapshot/restore, checked for faults, escapes from
// the container and hash-chain agreement. scripts/stress.sh runs the long
// version (10,000 worlds × 600 ticks by default) through tandem_stress.
//
// The slice is split into four test cases so `ctest -j` runs them in
// parallel; together they take ~30–60 s in the sanitizer builds.
#include <catch2/catch.hpp>

#include "tests/stress/stress_world.h"

namespace {

using tandem::stress::StressConfig;
using tandem::stress::StressResult;

// Worlds per test case and ticks per world of the slice.
constexpr uint64_t k_worlds_per_case = 6;
constexpr int32_t k_slice_ticks = 240;

void run_seeds(uint64_t first) {
  for (uint64_t seed = first; seed < first + k_worlds_per_case; ++seed) {
    StressConfig config;
    config.seed = seed;
    config.ticks = k_slice_ticks;
    const StressResult r = tandem::stress::run_stress_world(config);
    INFO(tandem::stress::describe(seed, r));
    CHECK(r.ok());
    CHECK(r.faults == 0);
    CHECK(r.escapes == 0);
    // The generator must really exercise the engine.
    CHECK(r.bodies_created > 0);
    CHECK(r.inputs_applied > 0);
  }
}

}  // namespace

TEST_CASE("random worlds: seeds 1-6 agree across broad phases and restore, stay contained, no fault", "[stress]") {
  run_seeds(1);
}
TEST_CASE("random worlds: seeds 7-12 agree across broad phases and restore, stay contained, no fault", "[stress]") {
  run_seeds(7);
}
TEST_CASE("random worlds: seeds 13-18 agree across broad phases and restore, stay contained, no fault", "[stress]") {
  run_seeds(13);
}
TEST_CASE("random worlds: seeds 19-24 agree across broad phases and restore, stay contained, no fault", "[stress]") {
  run_seeds(19);
}
