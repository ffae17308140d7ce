// golden_joint_scenes.cpp — golden scenes with joints (physics/joint.h),
// built like golden_scenes.cpp's from integer and fixed-point inputs only.
// Together they use every joint kind with limits, motors, springs and
// breaking, joints created and destroyed mid-run, joint setters driven by a
// script, bodies destroyed with their joints, and joined bodies sleeping.
//
// Changing a scene changes its golden file: regenerate it in the same commit
// (docs/determinism.md).
#include <cstdint>

#include "golden_support.h"

namespace tandem::golden {
namespace {

using namespace tandem::literals;

Q32 q(int64_t num, int64_t den = 1) { return Q32::from_ratio(num, den); }
Vec2 v(Q32 x, Q32 y) { return {x, y}; }

BodyId make_body(SceneContext& c, BodyType type, Vec2 position) {
  BodyDef def = default_body_def();
  def.type = type;
  def.position = position;
  return c.value(create_body(c.world, def), "create_body");
}
BodyId dyn(SceneContext& c, Vec2 p) { return make_body(c, BodyType::dynamic_body, p); }

void box(SceneContext& c, BodyId b, Q32 hw, Q32 hh, Q32 density = Q32::one()) {
  Polygon p;
  const Status g = make_box(hw, hh, &p);
  if (!g.ok()) c.check({StatusCode::invalid_argument, g.message}, "make_box");
  ShapeDef sd = default_shape_def();
  sd.density = density;
  c.check(create_polygon_shape(b, sd, p).status, "create_polygon_shape");
}
void offset_box(SceneContext& c, BodyId b, Q32 hw, Q32 hh, Vec2 center) {
  Polygon p;
  const Status g = make_offset_box(hw, hh, center, Q32::zero(), Q32::zero(), &p);
  if (!g.ok()) c.check({StatusCode::invalid_argument, g.message}, "make_offset_box");
  c.check(create_polygon_shape(b, default_shape_def(), p).status, "create_polygon_shape");
}
void circle(SceneContext& c, BodyId b, Q32 r, Q32 density = Q32::one()) {
  ShapeDef sd = default_shape_def();
  sd.density = density;
  c.check(create_circle_shape(b, sd, Circle{Vec2{}, r}).status, "create_circle_shape");
}
void capsule(SceneContext& c, BodyId b, Vec2 p1, Vec2 p2, Q32 r) {
  c.check(create_capsule_shape(b, default_shape_def(), Capsule{p1, p2, r}).status, "create_capsule_shape");
}

JointBaseDef base(BodyId a, BodyId b, Vec2 world_anchor) {
  JointBaseDef d;
  d.body_a = a;
  d.body_b = b;
  d.local_anchor_a = body_local_point(a, world_anchor);
  d.local_anchor_b = body_local_point(b, world_anchor);
  return d;
}

/// A revolute joint; with `limit`, also limits and joint friction (a motor
/// at speed 0 with a small torque, so limbs come to rest and sleep).
JointId revolute(SceneContext& c, BodyId a, BodyId b, Vec2 anchor, Q32 lo = Q32::zero(), Q32 hi = Q32::zero(),
                 bool limit = false) {
  RevoluteJointDef d = default_revolute_joint_def();
  d.base = base(a, b, anchor);
  d.enable_limit = limit;
  d.lower_angle = lo;
  d.upper_angle = hi;
  d.enable_motor = limit;
  d.max_motor_torque = Q32::from_ratio(1, 20);
  return c.value(create_revolute_joint(c.world, d), "create_revolute_joint");
}

// --- joints_bridge_chain: revolute bridge and hanging chain ------------------
// A 20-plank bridge, a 30-link chain with a heavy ball, boxes dropped on the
// bridge every 2 s; at tick 1500 a chain joint is destroyed (the lower part
// falls onto the bridge), at 2400 a plank body is destroyed (its two joints go
// with it).
void build_bridge_chain(SceneContext& c) {
  const BodyId ground = make_body(c, BodyType::static_body, Vec2{});
  offset_box(c, ground, 30_q32, 1_q32, v(0_q32, -16_q32));
  c.bodies.push_back(ground);
  BodyId prev = ground;
  for (int64_t i = 0; i < 20; ++i) {
    const BodyId plank = dyn(c, v(q(-10) + q(i) + q(1, 2), 0_q32));
    box(c, plank, q(1, 2), q(1, 8), 20_q32);
    c.joints.push_back(revolute(c, prev, plank, v(q(-10) + q(i), 0_q32)));
    c.bodies.push_back(plank);
    prev = plank;
  }
  c.joints.push_back(revolute(c, prev, ground, v(10_q32, 0_q32)));
  // The chain hangs from (14, 10) with a ball at its end.
  prev = ground;
  for (int64_t i = 0; i < 30; ++i) {
    const BodyId link = dyn(c, v(14_q32 + q(i, 4) + q(1, 8), 10_q32));
    capsule(c, link, v(q(-1, 8), 0_q32), v(q(1, 8), 0_q32), q(1, 20));
    c.joints.push_back(revolute(c, prev, link, v(14_q32 + q(i, 4), 10_q32)));
    prev = link;
  }
  const BodyId ball = dyn(c, v(14_q32 + q(30, 4) + q(1, 2), 10_q32));
  circle(c, ball, q(1, 2), 4_q32);
  c.joints.push_back(revolute(c, prev, ball, v(14_q32 + q(30, 4), 10_q32)));
}
void script_bridge_chain(SceneContext& c, int32_t tick) {
  if (tick % 120 == 0 && tick <= 1200) {
    const BodyId b = dyn(c, v(q(-8) + q((tick / 120) % 8 * 2), 4_q32));
    box(c, b, q(2, 5), q(2, 5), 5_q32);
  }
  if (tick == 1500) c.check(destroy_joint(c.joints[36]), "destroy_joint(chain link)");
  if (tick == 2400) c.check(destroy_body(c.bodies[10]), "destroy_body(plank)");
}

// --- joints_machines: motors, limits, springs, sliders, a car ------------------
// A revolute arm driven into its limits by a motor reversed every 4 s, a
// prismatic piston with motor, limits and spring, a car (chassis + two wheel
// joints with suspension springs and motors) on bumpy ground, a soft weld, a
// motor joint carrying a box around a circle of offsets, and a mouse joint
// whose target moves every tick.
void build_machines(SceneContext& c) {
  const BodyId ground = make_body(c, BodyType::static_body, Vec2{});
  offset_box(c, ground, 40_q32, 1_q32, v(0_q32, -1_q32));
  for (int64_t i = 0; i < 12; ++i) offset_box(c, ground, q(1, 2), q(1, 10), v(q(-20) + q(i * 3), q(1, 10)));
  c.bodies.push_back(ground);

  // Arm on a revolute motor with limits.
  const BodyId arm = dyn(c, v(q(-30) + 1_q32, 6_q32));
  box(c, arm, 1_q32, q(1, 10));
  RevoluteJointDef rd = default_revolute_joint_def();
  rd.base = base(ground, arm, v(-30_q32, 6_q32));
  rd.enable_limit = true;
  rd.lower_angle = q(-3, 4);
  rd.upper_angle = q(3, 4);
  rd.enable_motor = true;
  rd.motor_speed = 2_q32;
  rd.max_motor_torque = 40_q32;
  rd.enable_spring = true;
  rd.hertz = 1_q32;
  rd.damping_ratio = q(1, 5);
  c.joints.push_back(c.value(create_revolute_joint(c.world, rd), "create_revolute_joint(arm)"));  // 0

  // Piston.
  const BodyId piston = dyn(c, v(-25_q32, 4_q32));
  box(c, piston, q(1, 2), q(1, 4));
  PrismaticJointDef pd = default_prismatic_joint_def();
  pd.base = base(ground, piston, v(-25_q32, 4_q32));
  pd.local_axis_a = v(0_q32, 1_q32);
  pd.enable_limit = true;
  pd.lower_translation = -2_q32;
  pd.upper_translation = 2_q32;
  pd.enable_motor = true;
  pd.motor_speed = 1_q32;
  pd.max_motor_force = 50_q32;
  pd.enable_spring = true;
  pd.hertz = 2_q32;
  pd.damping_ratio = q(1, 10);
  c.joints.push_back(c.value(create_prismatic_joint(c.world, pd), "create_prismatic_joint"));  // 1

  // Car.
  const BodyId chassis = dyn(c, v(-18_q32, 2_q32));
  box(c, chassis, q(3, 2), q(1, 4), 2_q32);
  c.bodies.push_back(chassis);  // 1
  for (int64_t side = -1; side <= 1; side += 2) {
    const BodyId wheel = dyn(c, v(-18_q32 + q(side), 1_q32));
    circle(c, wheel, q(2, 5), 2_q32);
    WheelJointDef wd = default_wheel_joint_def();
    wd.base = base(chassis, wheel, v(-18_q32 + q(side), 1_q32));
    wd.local_axis_a = v(0_q32, 1_q32);
    wd.hertz = 4_q32;
    wd.damping_ratio = q(7, 10);
    wd.enable_limit = true;
    wd.lower_translation = q(-1, 4);
    wd.upper_translation = q(1, 4);
    wd.enable_motor = true;
    wd.motor_speed = -8_q32;
    wd.max_motor_torque = 30_q32;
    c.joints.push_back(c.value(create_wheel_joint(c.world, wd), "create_wheel_joint"));  // 2, 3
  }

  // Soft weld: a beam welded to a post.
  const BodyId post = dyn(c, v(25_q32, 1_q32));
  box(c, post, q(1, 4), 1_q32);
  const BodyId beam = dyn(c, v(26_q32 + q(1, 4), 2_q32));
  box(c, beam, 1_q32, q(1, 8));
  WeldJointDef wd = default_weld_joint_def();
  wd.base = base(post, beam, v(q(25) + q(1, 4), 2_q32));
  wd.angular_hertz = 3_q32;
  wd.angular_damping_ratio = q(1, 2);
  c.joints.push_back(c.value(create_weld_joint(c.world, wd), "create_weld_joint"));  // 4

  // Motor joint carrying a box.
  const BodyId carried = dyn(c, v(30_q32, 5_q32));
  box(c, carried, q(1, 2), q(1, 2));
  MotorJointDef md = default_motor_joint_def();
  md.base.body_a = ground;
  md.base.body_b = carried;
  md.linear_offset = v(30_q32, 5_q32);
  md.max_force = 200_q32;
  md.max_torque = 20_q32;
  c.joints.push_back(c.value(create_motor_joint(c.world, md), "create_motor_joint"));  // 5

  // Mouse joint.
  const BodyId dragged = dyn(c, v(10_q32, 3_q32));
  box(c, dragged, q(1, 3), q(1, 3));
  MouseJointDef ms = default_mouse_joint_def();
  ms.base.body_a = ground;
  ms.base.body_b = dragged;
  ms.target = v(10_q32, 3_q32);
  ms.max_force = 300_q32;
  c.joints.push_back(c.value(create_mouse_joint(c.world, ms), "create_mouse_joint"));  // 6
}
void script_machines(SceneContext& c, int32_t tick) {
  if (tick % 240 == 0) {
    const Q32 s = (tick / 240) % 2 == 0 ? -2_q32 : 2_q32;
    c.check(joint_set_motor_speed(c.joints[0], s), "joint_set_motor_speed(arm)");
    c.check(joint_set_motor_speed(c.joints[1], -s / 2), "joint_set_motor_speed(piston)");
  }
  if (tick == 1200) {
    c.check(joint_set_motor_speed(c.joints[2], 6_q32), "joint_set_motor_speed(wheel)");
    c.check(joint_set_motor_speed(c.joints[3], 6_q32), "joint_set_motor_speed(wheel)");
  }
  if (tick == 2000) c.check(joint_enable_limit(c.joints[0], false), "joint_enable_limit(arm)");
  // The motor joint's offset goes round a circle of radius 2 m every 6 s.
  const SinCos<Q32> sc = sincos(q(tick % 360, 360) * k_two_pi);
  c.check(joint_set_offsets(c.joints[5], v(30_q32 + 2_q32 * sc.cos, 5_q32 + 2_q32 * sc.sin), q(tick % 120, 120)),
          "joint_set_offsets");
  c.check(joint_set_target(c.joints[6], v(10_q32 + q(tick % 600, 100), 3_q32 + sc.sin)), "joint_set_target");
}

// --- joints_ropes_breaking: ropes, springs, breaking, a grappling hook ---------
// Three ropes with loads swinging, two distance springs, breakable welds and
// revolutes loaded until they break, and a hook attached, reeled in and out
// and released by the script.
void build_ropes_breaking(SceneContext& c) {
  const BodyId ceiling = make_body(c, BodyType::static_body, v(0_q32, 20_q32));
  offset_box(c, ceiling, 30_q32, q(1, 2), v(0_q32, q(1, 2)));
  const BodyId floor = make_body(c, BodyType::static_body, Vec2{});
  offset_box(c, floor, 30_q32, 1_q32, v(0_q32, -1_q32));
  c.bodies.push_back(ceiling);  // 0
  for (int64_t i = 0; i < 3; ++i) {
    const BodyId load = dyn(c, v(q(-15) + q(i * 4) + 3_q32, 16_q32));
    circle(c, load, q(1, 2), q(5 + 5 * i));
    DistanceJointDef d = default_distance_joint_def();
    d.base.body_a = ceiling;
    d.base.body_b = load;
    d.base.local_anchor_a = v(q(-15) + q(i * 4), 0_q32);
    d.length = q(5 + i);
    d.enable_spring = true;
    d.enable_limit = true;
    d.max_length = q(5 + i);
    c.joints.push_back(c.value(create_distance_joint(c.world, d), "create_distance_joint(rope)"));  // 0..2
  }
  for (int64_t i = 0; i < 2; ++i) {
    const BodyId bob = dyn(c, v(q(i * 3), 15_q32));
    box(c, bob, q(1, 3), q(1, 3));
    DistanceJointDef d = default_distance_joint_def();
    d.base.body_a = ceiling;
    d.base.body_b = bob;
    d.base.local_anchor_a = v(q(i * 3), 0_q32);
    d.length = 3_q32;
    d.enable_spring = true;
    d.hertz = q(1 + i);
    d.damping_ratio = q(1, 10);
    d.enable_limit = true;
    d.min_length = 1_q32;
    d.max_length = 6_q32;
    c.joints.push_back(c.value(create_distance_joint(c.world, d), "create_distance_joint(spring)"));  // 3, 4
  }
  // Breakable: a shelf welded to the ceiling, a lamp on a revolute.
  const BodyId shelf = dyn(c, v(10_q32, 18_q32));
  box(c, shelf, 1_q32, q(1, 4));
  WeldJointDef wd = default_weld_joint_def();
  wd.base = base(ceiling, shelf, v(10_q32, q(18) + q(1, 4)));
  wd.base.break_force = 300_q32;
  wd.base.break_torque = 400_q32;
  c.joints.push_back(c.value(create_weld_joint(c.world, wd), "create_weld_joint(shelf)"));  // 5
  const BodyId lamp = dyn(c, v(15_q32, 18_q32));
  circle(c, lamp, q(1, 2));
  RevoluteJointDef rd = default_revolute_joint_def();
  rd.base = base(ceiling, lamp, v(15_q32, 19_q32));
  rd.base.break_force = 200_q32;
  c.joints.push_back(c.value(create_revolute_joint(c.world, rd), "create_revolute_joint(lamp)"));  // 6
  c.bodies.push_back(shelf);   // 1
  c.bodies.push_back(lamp);    // 2
  const BodyId player = dyn(c, v(20_q32, 2_q32));
  circle(c, player, q(2, 5));
  c.bodies.push_back(player);  // 3
}
void script_ropes_breaking(SceneContext& c, int32_t tick) {
  // Load the shelf and the lamp more and more until they break.
  if (tick >= 600 && tick < 1800 && tick % 60 == 0) {
    if (joint_is_valid(c.joints[5])) {
      c.check(body_apply_force_to_center(c.bodies[1], v(0_q32, q(-(tick - 540) / 2)), true), "load shelf");
    }
    if (joint_is_valid(c.joints[6])) {
      c.check(body_apply_force_to_center(c.bodies[2], v(q(tick - 600) / 4, q(-(tick - 540) / 3)), true), "load lamp");
    }
  }
  // The grappling hook: fire at 900, reel in 1000..1120, out 1500..1560, release 2200.
  if (tick == 900) {
    DistanceJointDef d = default_distance_joint_def();
    d.base.body_a = c.bodies[0];
    d.base.body_b = c.bodies[3];
    d.base.local_anchor_a = v(22_q32, 0_q32);
    const Q32 len = max(distance(v(22_q32, 20_q32), body_position(c.bodies[3])), 1_q32);
    d.length = len;
    d.enable_spring = true;
    d.enable_limit = true;
    d.max_length = len;
    c.joints.push_back(c.value(create_distance_joint(c.world, d), "create_distance_joint(hook)"));  // 7
    c.counter = len.raw;
  }
  const auto reel = [&](int64_t delta_cm) {
    const Q32 len = clamp(Q32::from_raw(c.counter) + q(delta_cm, 100), 1_q32, 20_q32);
    c.counter = len.raw;
    c.check(joint_set_limits(c.joints[7], 0_q32, len), "joint_set_limits(hook)");
  };
  if (tick > 1000 && tick <= 1120) reel(-5);
  if (tick > 1500 && tick <= 1560) reel(5);
  if (tick == 2200) c.check(destroy_joint(c.joints[7]), "destroy_joint(hook)");
  if (tick == 2600) c.check(destroy_body(c.bodies[0]), "destroy_body(ceiling)");  // every rope goes with it
}

// --- joints_ragdolls: ragdolls tumbling down stairs, then sleeping -------------
void build_ragdolls(SceneContext& c) {
  const BodyId stairs = make_body(c, BodyType::static_body, Vec2{});
  for (int64_t i = 0; i < 10; ++i) offset_box(c, stairs, 1_q32, q(1, 2) + q(i, 2), v(q(i * 2), q(i, 2)));
  offset_box(c, stairs, 20_q32, q(1, 2), v(-10_q32, q(-1, 2)));
  for (int64_t r = 0; r < 5; ++r) {
    const Q32 x = q(14) + q(r, 2), y = q(11) + q(r * 3);
    const auto part = [&](Vec2 p, Vec2 e, Q32 radius) {
      const BodyId b = dyn(c, p);
      capsule(c, b, -e, e, radius);
      return b;
    };
    const BodyId torso = part(v(x, y), v(0_q32, q(3, 10)), q(3, 20));
    const BodyId head = part(v(x, y + q(3, 5)), v(0_q32, q(1, 20)), q(3, 25));
    revolute(c, torso, head, v(x, y + q(9, 20)), q(-1, 2), q(1, 2), true);
    for (int64_t side = -1; side <= 1; side += 2) {
      const BodyId upper = part(v(x + q(side * 35, 100), y + q(3, 10)), v(q(3, 20), 0_q32), q(3, 50));
      revolute(c, torso, upper, v(x + q(side * 15, 100), y + q(3, 10)), q(-3, 2), q(3, 2), true);
      const BodyId lower = part(v(x + q(side * 70, 100), y + q(3, 10)), v(q(3, 20), 0_q32), q(1, 20));
      revolute(c, upper, lower, v(x + q(side * 52, 100), y + q(3, 10)), q(-3, 2), 0_q32, true);
      const BodyId thigh = part(v(x + q(side, 10), y - q(13, 20)), v(0_q32, q(1, 5)), q(2, 25));
      revolute(c, torso, thigh, v(x + q(side, 10), y - q(21, 50)), -1_q32, 1_q32, true);
      const BodyId shin = part(v(x + q(side, 10), y - q(23, 20)), v(0_q32, q(1, 5)), q(7, 100));
      revolute(c, thigh, shin, v(x + q(side, 10), y - q(9, 10)), q(-3, 2), 0_q32, true);
    }
    c.bodies.push_back(torso);
  }
}
void script_ragdolls(SceneContext& c, int32_t tick) {
  if (tick == 2400) {  // wake the pile with a kick
    c.check(body_apply_linear_impulse_to_center(c.bodies[2], v(-3_q32, 2_q32), true), "kick");
  }
}

}  // namespace

// The joint scenes, appended to scenes() by golden_scenes.cpp.
extern const Scene k_joint_scenes[4];
const Scene k_joint_scenes[4] = {
    {"joints_bridge_chain", "revolute bridge and chain, boxes dropped, a joint and a body destroyed mid-run",
     build_bridge_chain, script_bridge_chain},
    {"joints_machines", "motors, limits, springs: revolute arm, prismatic piston, wheel-joint car, soft weld, "
                        "motor joint and mouse joint driven by the script",
     build_machines, script_machines},
    {"joints_ropes_breaking", "ropes, distance springs, breaking weld and revolute, a grappling hook attached, "
                              "reeled and released, the rope anchor destroyed",
     build_ropes_breaking, script_ropes_breaking},
    {"joints_ragdolls", "ragdolls with limited revolute joints tumbling down stairs, sleeping, woken by a kick",
     build_ragdolls, script_ragdolls},
};

}  // namespace tandem::golden
