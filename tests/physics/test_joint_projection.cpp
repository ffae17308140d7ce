// test_joint_projection.cpp — the revolute joints' rigid position pass
// (joint_solver.cpp, stage_project_joints) on a body of small rotational
// inertia created far from its joint's anchor.
//
// Found by the random-world stress with joint inputs (seed 32): the pass
// turned such a body by i⁻¹·(r × P), tens of radians for a few metres of
// gap, through integrate_rotation, which is only accurate for small turns;
// the rotation left unit length, grew every sub-step and overflowed (a
// fixed-point fault, which aborts a release build by default). The pass now
// scales a correction that would turn a body by more than 1 rad down to that
// turn (k_max_projection_turn) and lets later passes and steps remove the
// rest, and turns a body by more than 1/16 rad exactly (as the solver's fast
// spins), so no step ends with a rotation off unit length.
#include <catch2/catch.hpp>

#include <cstdint>

#include "ignore_fixed_faults.h"
#include "physics/tandem.h"

using namespace tandem;
using namespace tandem::literals;

using tandem::test_support::CountFixedFaults;

TEST_CASE("joint: a revolute joint created metres from its anchor on a body of small inertia keeps the rotation "
          "unit and closes the gap",
          "[physics][joint]") {
  for (const Q32 gap : {0.5_q32, 2_q32, 5_q32}) {
    CountFixedFaults faults;
    WorldDef wd = default_world_def();
    wd.gravity = Vec2{};
    Result<WorldId> w = create_world(wd);
    REQUIRE(w.ok());
    Result<BodyId> ground = create_body(w.value, default_body_def());
    REQUIRE(ground.ok());
    Polygon box;
    REQUIRE(make_box(1_q32, 1_q32, &box).ok());
    REQUIRE(create_polygon_shape(ground.value, default_shape_def(), box).ok());
    // A 1 cm circle of 29.8 kg: rotational inertia 0.0015 kg·m², its radius
    // of gyration 7 mm; the joint's anchor on it is 1 cm from its centre.
    BodyDef bd = default_body_def();
    bd.type = BodyType::dynamic_body;
    bd.position = Vec2{0_q32, 20_q32};
    Result<BodyId> body = create_body(w.value, bd);
    REQUIRE(body.ok());
    ShapeDef sd = default_shape_def();
    sd.density = 95000_q32;
    REQUIRE(create_circle_shape(body.value, sd, Circle{Vec2{}, 0.01_q32}).ok());
    REQUIRE(body_rotational_inertia(body.value) < 0.002_q32);
    RevoluteJointDef jd = default_revolute_joint_def();
    jd.base.body_a = ground.value;
    jd.base.body_b = body.value;
    jd.base.local_anchor_a = Vec2{gap, 20_q32};  // `gap` metres to the right of the body's anchor
    jd.base.local_anchor_b = Vec2{0.009_q32, -0.004_q32};
    Result<JointId> joint = create_revolute_joint(w.value, jd);
    REQUIRE(joint.ok());
    Q32 worst_unit_error;
    for (int tick = 0; tick < 120; ++tick) {
      REQUIRE(world_step(w.value, Q32::from_ratio(1, 60)).ok());
      const Rot q = body_rotation(body.value);
      const Q32 unit_error = abs(q.c * q.c + q.s * q.s - Q32::one());
      worst_unit_error = max(worst_unit_error, unit_error);
    }
    const Vec2 apart = joint_world_anchor_b(joint.value) - joint_world_anchor_a(joint.value);
    INFO("gap " << gap.to_double() << " m: worst |q|² − 1 " << worst_unit_error.to_double() << ", anchors "
                << length(apart).to_double() << " m apart after 2 s, " << faults.count() << " faults");
    CHECK(faults.count() == 0);
    // Turns above 1/16 rad are exact and normalised, smaller ones first-order
    // with two normalisation steps: |q|² stays within raw units of 1 at the
    // end of every step (world_restore refuses more than 2^-16).
    CHECK(worst_unit_error <= Q32::from_raw(16));
    CHECK(length(apart) < 0.01_q32);                // the joint has pulled the body onto its anchor
    REQUIRE(destroy_world(w.value).ok());
  }
}
