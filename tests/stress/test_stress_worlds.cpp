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

// KNOWN ISSUES found by the stress (engine bugs): the slice above does not
// fail on escapes from fast worlds or of bodies with chain segments
// (StressConfig::fail_on_known_escapes is off), since a few seeds in a
// thousand still lose such a body (README "Range and limits"). Reproduce one
// with TANDEM_STRESS_TRACE=<body index> tandem_stress --first-seed S --worlds 1
// to print the body's inputs and path.
//
// Formerly KNOWN ISSUE 1: in "fast" worlds (inputs up to the world's
// max_linear_speed) a body went through a 1 m static wall after a contact
// step left it spinning far above k_max_angular_speed. Seed 94: a 0.04 kg
// body whose solid shape is a segment, stopped at the wall at 400 m/s by
// continuous collision (tick 280), left the next step at −4,144 rad/s and
// 231 m/s and was past the wall's middle at tick 282. Seed 34: a 0.005 m
// circle of 2.5 kg resting on the floor, struck by a 111 kg body at 392 m/s,
// left at 51,293 rad/s and 335 m/s (tick 249) and went through the floor.
// The spin was not the cause (a 5 mm ball rolling at 300 m/s does spin at
// 60,000 rad/s; the restore check allows rim speeds up to 4,000 m/s): in
// both, the body started the step touching the wall, and continuous.cpp then
// sweeps only a small core at the shape's centroid — whose default stopping
// distance (max(linear slop, radii − slop) = 5 mm) the centroid of a shape
// no thicker than the slop (a 5 mm circle, a segment) already lay within, so
// the core sweep reported a hit at t = 0, which is ignored, and nothing
// stopped the body. The core now stops halfway to the obstacle in that case
// (time_of_impact_to).
TEST_CASE("regression: fast bodies touching a wall do not pass through it (stress seeds 94, 34)", "[stress]") {
  for (uint64_t seed : {94u, 34u}) {
    StressConfig config;
    config.seed = seed;
    config.ticks = 600;
    config.fail_on_known_escapes = true;
    const StressResult r = tandem::stress::run_stress_world(config);
    INFO(tandem::stress::describe(seed, r));
    CHECK(r.ok());
    CHECK(r.escapes == 0);
    CHECK(r.faults == 0);
  }
}

// Formerly KNOWN ISSUE 2: a dynamic body carrying one-sided chain segments
// that rests against a static box sank into the box at about the contact
// push speed (3 m/s, while its velocity read zero) and came out beyond it, in
// slow worlds too (about 20 % of all worlds; 36 of seeds 1-200). The box is
// much larger than the segment: its centroid projected in front of the
// (tilted) segment, so the chain-vs-polygon manifold took the box to be in
// front and pushed it out through the segment's front by its whole depth
// behind the line. physics/manifold_chain.cpp now judges the side by the part
// of the box over the segment (regression test in
// tests/physics/test_chain_body.cpp). Seeds 19, 22, 44 must now stay
// contained. Seed 6 then still lost a 1 cm body (a segment and chain
// segments, the default 1 kg, spinning at the angular limit in the
// container's corner): its centre jumped 0.4 m into the wall in one tick
// (352) at 0.2 m/s. It is known issue 1's cause: the body touches the wall,
// its solid shape is a segment (thinnest extent = the slop), so the
// continuous core sweep stopped nothing; fixed with it.
TEST_CASE("regression: bodies with chain segments stay out of static boxes (stress seeds 19, 22, 44, 6)", "[stress]") {
  for (uint64_t seed : {19u, 22u, 44u, 6u}) {
    StressConfig config;
    config.seed = seed;
    config.ticks = 600;
    config.fail_on_known_escapes = true;
    const StressResult r = tandem::stress::run_stress_world(config);
    INFO(tandem::stress::describe(seed, r));
    CHECK(r.ok());
    CHECK(r.escapes == 0);
  }
}

// Formerly KNOWN ISSUE 4: fixed-point overflows in worlds the API accepted
// (seeds 55, 9, 94, found by the sanitizer build of scripts/stress.sh). A body
// of tiny rotational inertia whose contact points lie far from its centre of
// mass (a light circle or capsule carrying massless segments or chain
// segments) made inv_inertia × (r × n)² overflow in
// prepare_contact_constraints, and the contact solve after it (246 faults in
// seed 94). The preparation now bounds the angular term of the effective mass
// (contact_solver.cpp, "Range of the preparation"; docs/determinism.md), so
// these worlds run without a fault in builds with fault checks (debug,
// sanitizers; other builds count none).
TEST_CASE("regression: no fixed-point fault in contact preparation (stress seeds 55, 9, 94)", "[stress]") {
  for (uint64_t seed : {55u, 9u, 94u}) {
    StressConfig config;
    config.seed = seed;
    config.ticks = 600;
    const StressResult r = tandem::stress::run_stress_world(config);
    INFO(tandem::stress::describe(seed, r));
    CHECK(r.faults == 0);
    CHECK(r.steps > 0);
  }
}

TEST_CASE("random worlds that used to overflow (seeds 94, 55, 9, 34) compute the same bits in every build",
          "[stress]") {
  // Run 0 (naive broad phase) only, 600 ticks. Before the range bound these
  // worlds saturated (seed 94 first split g++ -O3 from the checked builds at
  // tick 512); now nothing saturates, and g++ release (native __int128, fast
  // paths), the sanitizer builds (checked operators) and the portable-int128
  // preset (the i686/wasm32 path) must give these final hashes.
  struct Expected {
    uint64_t seed;
    uint64_t final_hash;
  };
  for (const Expected& e : {Expected{94, 0x790a957269f3ed1full}, Expected{55, 0x1a1efef0253b878cull},
                            Expected{9, 0xa9e7af87b541354eull}, Expected{34, 0x44817f8f69353267ull}}) {
    StressConfig config;
    config.seed = e.seed;
    config.ticks = 600;
    config.compare_broad_phases = false;
    config.check_restore = false;
    const StressResult r = tandem::stress::run_stress_world(config);
    INFO(tandem::stress::describe(e.seed, r));
    CHECK(r.faults == 0);
    CHECK(r.steps == config.ticks);
    CHECK(r.final_hash == e.final_hash);
  }
}

// Formerly KNOWN ISSUE 5 (found 2026-11-25 by the sanitizer run): seed 776,
// a fast world with a ±1,500 m container, reported 1,905 fixed-point faults
// in builds with fault checks, the first in the contact solve's relative
// velocity. A 1 cm body (0.022 kg) carrying chain segments stood on the
// 3,300 m floor box, its segment nearly upright; the chain manifold snapped
// the normal to the segment's and clipped the box's top edge to the
// segment's slab, giving contact points 260 m and 760 m behind the segment,
// and the solve spun the body to 6·10^8 rad/s. physics/manifold_chain.cpp
// now drops a segment-reference contact off the SAT path when B lies mostly
// behind the segment where it is over it (as the SAT path already did).
// Faults are counted only in builds with fault checks (debug, sanitizers).
TEST_CASE("regression: no fixed-point fault or escape from a chain body on a huge wall box (stress seed 776)",
          "[stress]") {
  StressConfig config;
  config.seed = 776;
  config.ticks = 600;
  config.fail_on_known_escapes = true;
  const StressResult r = tandem::stress::run_stress_world(config);
  INFO(tandem::stress::describe(776, r));
  CHECK(r.ok());
  CHECK(r.faults == 0);
  CHECK(r.escapes == 0);
}
