// test_stress_worlds.cpp — the short ctest slice of the random-world stress
// (stress_world.h): a fixed range of seeds, each world run with every broad
// phase and once through a snapshot/restore, checked for faults, escapes from
// the container and hash-chain agreement. scripts/stress.sh runs the long
// version (10,000 worlds × 600 ticks by default) through tandem_stress.
//
// The slice is split into four test cases so `ctest -j` runs them in
// parallel; together they take ~30–60 s in the sanitizer builds. The slice
// has joint inputs (StressConfig::joints); the tests of single seeds below
// turn them off, so each seed still names the world it was found in.
#include <catch2/catch.hpp>

#include "tests/stress/stress_world.h"

namespace {

using tandem::stress::StressConfig;
using tandem::stress::StressResult;

// Worlds per test case and ticks per world of the slice.
constexpr uint64_t k_worlds_per_case = 6;
constexpr int32_t k_slice_ticks = 240;

void run_seeds(uint64_t first) {
  int32_t joints = 0;
  for (uint64_t seed = first; seed < first + k_worlds_per_case; ++seed) {
    StressConfig config;
    config.seed = seed;
    config.ticks = k_slice_ticks;
    const StressResult r = tandem::stress::run_stress_world(config);
    INFO(tandem::stress::describe(seed, r));
    CHECK(r.ok());
    // Faults fail unless the world has known issue 8 (joints; counted).
    CHECK((r.faults == 0 || !r.joint_issue.empty()));
    if (!r.joint_issue.empty()) WARN("known issue 8: " << tandem::stress::describe(seed, r));
    // The generator must really exercise the engine.
    CHECK(r.bodies_created > 0);
    CHECK(r.inputs_applied > 0);
    joints += r.joints_created;
  }
  CHECK(joints > 0);  // joint inputs (StressConfig::joints) created some
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

// KNOWN ISSUES found by the stress (engine bugs, reported, not fixed here; the
// slice above does not fail on them: StressConfig::fail_on_known_escapes is
// off). Hidden ([.]) so the default runs stay green; run by name to reproduce,
// or TANDEM_STRESS_TRACE=<body index> tandem_stress --first-seed S --worlds 1
// to print the body's inputs and path.
//
// KNOWN ISSUE 1: in "fast" worlds (inputs up to the world's max_linear_speed)
// a contact step can leave a body spinning far above k_max_angular_speed
// (100 rad/s; the clamp acts only where velocities are integrated), and the
// body then passes through a 1 m static wall. Seed 94: a 0.04 kg body whose
// solid shape is a segment, at 400 m/s, is stopped at the wall by continuous
// collision (tick 280); the next step leaves it at ω = −4,144 rad/s and
// 231 m/s, and at tick 282 its centre is past the wall's middle. Seed 34: a
// 0.005 m circle of 2.5 kg resting on the floor jumps in one step (tick 249)
// to ω = 51,293 rad/s and 335 m/s and goes through the floor. About 1.4 % of
// all worlds (40 % of worlds are fast).
//
// Known issue 1, status (November 2026): still open. Clamping ω to the limit
// after every contact solve (before positions are integrated, as the
// integrate-velocities clamp does) keeps seed 94's body at 47 rad/s instead
// of 4,144, but the body still leaves the contact at 146 m/s into the wall
// (the solver's effective mass counts on the rotation the clamp then
// removes, so the passes cannot stop the contact point through the linear
// velocity), and the next step's continuous collision cannot stop a body
// that starts the step touching the wall with its centre 1 mm from it. The
// clamp also changed three golden scenes (ragdolls, bridge, random_mix: the
// joint solver is not clamped), so it was not kept. A fix needs the solve to
// treat a saturated angular velocity as a constraint (or time-of-impact
// sub-steps, continuous.cpp "LIMITS").
TEST_CASE("known issue 1: fast bodies go through 1 m walls after a spinning impact (stress seeds 94, 34)",
          "[.][known-issue][stress]") {
  for (uint64_t seed : {94u, 34u}) {
    StressConfig config;
    config.seed = seed;
    config.ticks = 600;

    config.joints = false;  // the world this seed named before joint inputs existed
    config.fail_on_known_escapes = true;
    const StressResult r = tandem::stress::run_stress_world(config);
    INFO(tandem::stress::describe(seed, r));
    CHECK(r.ok());
  }
}

// Formerly KNOWN ISSUE 7 (the 10,000-world run of 2026-11-28, seed 8724, a
// slow world): a 1 kg body whose only solid shape is a 4.1 m segment (no
// rotational inertia), spinning at 59 rad/s and moving at 229 m/s along a
// side wall it touches, was held in place by continuous collision for 26
// steps (ticks 286-311), its segment's middle halfway nearer the wall's face
// each step, until it was on the face and could no longer be held; at tick
// 312 it swung through the wall's middle. A hold within half the slop of the
// wall now also takes the body's spin relative to the wall, so the next sweep
// is the body's translation (continuous.cpp; small-world test in
// test_held_bodies.cpp).
TEST_CASE("random world seed 8724 (a spinning segment body sliding along a wall at 229 m/s) stays contained",
          "[stress]") {
  StressConfig config;
  config.seed = 8724;
  config.ticks = 600;

  config.joints = false;  // the world this seed named before joint inputs existed
  const StressResult r = tandem::stress::run_stress_world(config);
  INFO(tandem::stress::describe(8724, r));
  CHECK(r.ok());
  CHECK(r.escapes == 0);
}

// Seeds 3769 and 6309 (fast worlds; the 10,000-world release run after the
// seed-8724 fix): a 1 kg segment body resting on the floor, its segment's
// middle a millimetre inside the floor's face, is given 1,000 m/s (3769:
// along the floor, then driven down through it in the step; 6309: past the
// floor's corner). The centroid core had no distance to the floor, so no
// hold. Now a centroid that starts inside a polygon obstacle is held where it
// would sink half the slop deeper behind the face it rests on
// (continuous.cpp inside_hold; small-world test in test_held_bodies.cpp).
TEST_CASE("random worlds 3769 and 6309 (segment bodies resting inside the floor's face, flung at 1,000 m/s) stay "
          "contained",
          "[stress]") {
  for (const uint64_t seed : {3769ull, 6309ull}) {
    StressConfig config;
    config.seed = seed;
    config.ticks = 600;

    config.joints = false;  // the world this seed named before joint inputs existed
    const StressResult r = tandem::stress::run_stress_world(config);
    INFO(tandem::stress::describe(seed, r));
    CHECK(r.ok());
    CHECK(r.escapes == 0);
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
// contained. Seed 6 still loses a 1 cm body (a segment and chain segments,
// the default 1 kg, spinning at the angular limit in the container's corner):
// its centre jumps 0.4 m into the wall in one tick (352) at 0.2 m/s and it
// leaves at tick 375; cause not found yet (1 of seeds 1-200 after the fix,
// counted as a chain-body escape because the body carries chain segments).
TEST_CASE("regression: bodies with chain segments stay out of static boxes (stress seeds 19, 22, 44)", "[stress]") {
  for (uint64_t seed : {19u, 22u, 44u}) {
    StressConfig config;
    config.seed = seed;
    config.ticks = 600;

    config.joints = false;  // the world this seed named before joint inputs existed
    config.fail_on_known_escapes = true;
    const StressResult r = tandem::stress::run_stress_world(config);
    INFO(tandem::stress::describe(seed, r));
    CHECK(r.ok());
    CHECK(r.escapes == 0);
  }
}

// Formerly open (README "Range and limits"): stress seed 572, a fast world in
// which a bullet whose only solid shape is a 0.5 m segment (its 10.8 kg are a
// sensor box below the segment) was counted as gone through the floor at
// 14 m/s. Two causes: (1) continuous collision stopped the segment on a
// static chain segment every step (ticks 55-78), although no contact exists
// between two segment kinds, so nothing took its velocity away: the body
// hung there while gravity took it to 12.8 m/s, then slipped off and hit the
// floor; continuous.cpp now sweeps only pairs a contact can take over (no
// two segment kinds, no one-sided chain segment from behind). (2) The
// containment rule checked the centre of mass, which for this body lies
// 0.55 m from the segment: resting on the floor with one end, the body
// swung its mass 0.7 m into the floor while the segment stayed on it
// (deepest point 0.17 m in). The rule now checks the centre of the body's
// solid shapes (stress_world.cpp, solid_centre).
TEST_CASE("regression: stress seed 572 stays contained (segment held on a chain segment by continuous collision)",
          "[stress]") {
  StressConfig config;
  config.seed = 572;
  config.ticks = 600;

  config.joints = false;  // the world this seed named before joint inputs existed
  config.fail_on_known_escapes = true;
  const StressResult r = tandem::stress::run_stress_world(config);
  INFO(tandem::stress::describe(572, r));
  CHECK(r.ok());
  CHECK(r.escapes == 0);
  CHECK(r.faults == 0);
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

    config.joints = false;  // the world this seed named before joint inputs existed
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
  // preset (the i686/wasm32 path) must give these final hashes. Re-recorded
  // 2026-11-28 when continuous collision stopped sweeping pairs no contact
  // can take over (two segment kinds, a chain segment from behind): all four
  // worlds have such pairs. Re-recorded 2026-11-28 for the contact mass-ratio
  // cap (issue 14, contact_prepare.cpp): seeds 94, 9 and 34 have resting
  // contacts between bodies more than 100 times apart in mass (55 has none:
  // unchanged). Re-recorded 2026-11-28 (session 8) for continuous collision's
  // hold, which now also takes away a held body's velocity towards the
  // obstacle (stress seed 1104), and the capped contacts' bounded warm start
  // (stress seed 6298): all four final hashes changed. Re-recorded
  // 2026-11-28 (session 10) for continuous collision's hold, which within
  // half the slop of the obstacle also takes the body's spin (stress seed
  // 8724): seeds 94, 9 and 34 hold a thin body there (55 unchanged).
  // Re-recorded 2026-11-28 (session 11) for the hold of a centroid that
  // starts inside a polygon obstacle (stress seeds 3769, 6309): seed 34
  // changed (94, 55, 9 unchanged).
  struct Expected {
    uint64_t seed;
    uint64_t final_hash;
  };
  // Re-recorded 2026-11-29 (session 14) for the speed clamps before
  // positions are integrated and when a step stores its velocities
  // (solver.cpp; known issue 8): all four worlds have bodies that a solve
  // left above the limits.
  for (const Expected& e : {Expected{94, 0x738798e3089ce1eaull}, Expected{55, 0xb331868b88b0463eull},
                            Expected{9, 0x261997715df18461ull}, Expected{34, 0x085541583c07b6aeull}}) {
    StressConfig config;
    config.seed = e.seed;
    config.ticks = 600;

    config.joints = false;  // the world this seed named before joint inputs existed
    config.compare_broad_phases = false;
    config.check_restore = false;
    const StressResult r = tandem::stress::run_stress_world(config);
    INFO(tandem::stress::describe(e.seed, r));
    CHECK(r.faults == 0);
    CHECK(r.steps == config.ticks);
    CHECK(r.final_hash == e.final_hash);
  }
}

// KNOWN ISSUE 5 (found 2026-11-25 by the sanitizer run after the fixes above;
// open): seed 776, a fast world with a ±1,500 m container, reports 1,905
// fixed-point faults in builds with fault checks, the first in the contact
// solve's relative velocity (velocities beyond 2^31 m/s inside the solve;
// every build still saturates the same way). With the angular-speed clamp
// tried for known issue 1 the seed had none, so a runaway spin in the contact
// solve is the likely start. TANDEM_STRESS_LOG_FAULTS=1 tandem_stress
// --first-seed 776 --worlds 1 lists the faults.
TEST_CASE("known issue 5: fixed-point overflow in the contact solve (stress seed 776)", "[.][known-issue][stress]") {
  StressConfig config;
  config.seed = 776;
  config.ticks = 600;

  config.joints = false;  // the world this seed named before joint inputs existed
  const StressResult r = tandem::stress::run_stress_world(config);
  INFO(tandem::stress::describe(776, r));
  CHECK(r.faults == 0);
}

// KNOWN ISSUE 8 (found 2026-11-29 when the generator gained joint inputs;
// open). With joints, 55 of seeds 1-1,000 × 600 ticks (g++ release) first
// failed in ways the same worlds without joint inputs did not: bodies at
// 10^4-10^8 m/s (the contact and joint solves ran after the sub-step's speed
// clamp, and nothing bounded them), rotations off unit length (the revolute
// position pass's first-order turns), bodies out of the world, fixed-point
// faults, joint impulses beyond the restorable range; the snapshot of such
// a step was refused by world_restore, so a rollback game could lose its
// state. Fixed the same day (speeds held to the limits before positions are
// integrated and when a step stores them, exact turns and a turn cap in the
// position pass, joint impulses held to the restorable range): 7 worlds
// left. Six are slow worlds where a jointed body ends beyond a wall's middle
// (seed 73: a 1 kg segment body at tick 462, 0.12 m past the floor's
// middle at 9 m/s), one a contact whose stored impulses would change a
// light body's velocity by 1.5·10^8 m/s in the warm start, beyond what
// restore accepts (seed 732, tick 318). A separate cause, outside what the
// generator does: a long massless lever on a body of small inertia (a 30 kg,
// 1 cm circle welded to the ground through an anchor 100 m from its centre)
// is unstable.
TEST_CASE("known issue 8: joint inputs push a body through a wall or store a contact impulse restore refuses "
          "(stress seeds 73, 732)",
          "[.][known-issue][stress]") {
  for (const uint64_t seed : {73ull, 732ull}) {
    StressConfig config;
    config.seed = seed;
    config.ticks = 600;
    config.fail_on_joint_issues = true;
    const StressResult r = tandem::stress::run_stress_world(config);
    INFO(tandem::stress::describe(seed, r));
    CHECK(r.ok());
    CHECK(r.faults == 0);
  }
}
