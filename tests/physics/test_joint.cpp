// Tests for physics/joint.cpp and joint_solver.cpp through the public API:
// pendulum period and energy, rope length and slack, a 30-plank bridge under
// load, limits under driving motors, motor speed, breaking, ragdolls in a
// box, collide_connected, sleep, body destruction, bad input, determinism.
// Measured figures are printed with WARN so the report can quote them.
// Doubles appear only as test oracles (never fed back into the world).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <vector>

#include "physics/tandem.h"
#include "physics_test_support.h"

using namespace tandem;
using namespace tandem::test_support;

namespace {

constexpr double k_g = 10.0;
#if defined(NDEBUG)
constexpr bool k_fast = true;
#else
constexpr bool k_fast = false;  // Debug and sanitizer builds: shorter runs
#endif

double d(Q32 v) { return static_cast<double>(ld(v)); }
Q32 qd(double v) { return Q32::from_raw(static_cast<int64_t>(std::llround(v * 4294967296.0))); }  // test input only

BodyId add_static(WorldId w, Vec2 p = {}) {
  BodyDef def = default_body_def();
  def.position = p;
  Result<BodyId> b = create_body(w, def);
  REQUIRE(b.ok());
  return b.value;
}

BodyId add_ball(WorldId w, Vec2 p, Q32 radius, Q32 density, bool sleep = true) {
  BodyDef def = default_body_def();
  def.type = BodyType::dynamic_body;
  def.position = p;
  def.enable_sleep = sleep;
  Result<BodyId> b = create_body(w, def);
  REQUIRE(b.ok());
  ShapeDef sd = default_shape_def();
  sd.density = density;
  REQUIRE(create_circle_shape(b.value, sd, Circle{Vec2{}, radius}).ok());
  return b.value;
}

BodyId add_box(WorldId w, Vec2 p, Q32 hx, Q32 hy, Q32 density, bool sleep = true) {
  BodyDef def = default_body_def();
  def.type = BodyType::dynamic_body;
  def.position = p;
  def.enable_sleep = sleep;
  Result<BodyId> b = create_body(w, def);
  REQUIRE(b.ok());
  Polygon box;
  REQUIRE(make_box(hx, hy, &box).ok());
  ShapeDef sd = default_shape_def();
  sd.density = density;
  REQUIRE(create_polygon_shape(b.value, sd, box).ok());
  return b.value;
}

/// |world anchor B − world anchor A|, m.
double separation(BodyId a, Vec2 la, BodyId b, Vec2 lb) {
  const Vec2 pa = body_world_point(a, la), pb = body_world_point(b, lb);
  return std::hypot(d(pb.x - pa.x), d(pb.y - pa.y));
}

JointId revolute(WorldId w, BodyId a, BodyId b, Vec2 world_anchor) {
  RevoluteJointDef def = default_revolute_joint_def();
  def.base.body_a = a;
  def.base.body_b = b;
  def.base.local_anchor_a = body_local_point(a, world_anchor);
  def.base.local_anchor_b = body_local_point(b, world_anchor);
  Result<JointId> j = create_revolute_joint(w, def);
  REQUIRE(j.ok());
  return j.value;
}

/// A pendulum: a small ball on a revolute joint at the origin, length L,
/// released at angle theta0 (rad from straight down).
struct Pendulum {
  BodyId ground, bob;
  JointId joint;
};

Pendulum make_pendulum(WorldId w, double length, double theta0) {
  Pendulum p;
  p.ground = add_static(w);
  p.bob = add_ball(w, Vec2{qd(length * std::sin(theta0)), qd(-length * std::cos(theta0))}, 0.02_q32, 100_q32, false);
  RevoluteJointDef def = default_revolute_joint_def();
  def.base.body_a = p.ground;
  def.base.body_b = p.bob;
  def.base.local_anchor_a = {};
  def.base.local_anchor_b = body_local_point(p.bob, Vec2{});
  Result<JointId> j = create_revolute_joint(w, def);
  REQUIRE(j.ok());
  p.joint = j.value;
  return p;
}

double energy(BodyId b) {
  const Vec2 v = body_linear_velocity(b);
  const double m = d(body_mass(b)), inertia = d(body_rotational_inertia(b)), wv = d(body_angular_velocity(b));
  return 0.5 * m * (d(v.x) * d(v.x) + d(v.y) * d(v.y)) + 0.5 * inertia * wv * wv + m * k_g * d(body_world_center(b).y);
}

}  // namespace

TEST_CASE("joint: pendulum of 1 m swings with the small-angle period within 1 %", "[physics][joint]") {
  ScopedWorld world;
  const Pendulum p = make_pendulum(world.id, 1.0, 0.05);
  const double expected = 2.0 * M_PI * std::sqrt(1.0 / k_g);
  // Upward zero crossings of x (interpolated), over 10 periods.
  std::vector<double> crossings;
  double prev_x = d(body_world_center(p.bob).x), t = 0;
  const double dt = d(k_dt);
  for (int i = 0; i < 60 * 25 && crossings.size() < 11; ++i) {
    REQUIRE(world_step(world.id, k_dt).ok());
    t += dt;
    const double x = d(body_world_center(p.bob).x);
    if (prev_x < 0 && x >= 0) crossings.push_back(t - dt * x / (x - prev_x));
    prev_x = x;
  }
  REQUIRE(crossings.size() == 11);
  const double period = (crossings.back() - crossings.front()) / 10.0;
  // A physical pendulum of a 2 cm disc: √(1 + r²/2L²) longer than the point
  // mass; amplitude 0.05 rad: (1 + θ²/16). Both ≪ 1 %.
  WARN("pendulum period " << period << " s, 2π√(L/g) = " << expected << " s, error "
                          << 100.0 * (period / expected - 1.0) << " %");
  CHECK(std::abs(period / expected - 1.0) < 0.01);
}

TEST_CASE("joint: an undamped pendulum keeps its energy within 1 % over 60 s", "[physics][joint]") {
  ScopedWorld world;
  const Pendulum p = make_pendulum(world.id, 1.0, 0.5);
  const double e_bottom = energy(p.bob) - d(body_mass(p.bob)) * k_g * (1.0 - std::cos(0.5));  // reference: rest at the bottom
  const double e0 = energy(p.bob) - e_bottom;
  double worst = 0;
  const int steps = k_fast ? 3600 : 900;
  for (int i = 0; i < steps; ++i) {
    REQUIRE(world_step(world.id, k_dt).ok());
    worst = std::max(worst, std::abs(energy(p.bob) - e_bottom - e0) / e0);
  }
  WARN("pendulum energy drift over " << steps / 60 << " s: worst " << 100.0 * worst << " % of m·g·L(1 − cos θ0)");
  CHECK(worst < 0.01);
}

TEST_CASE("joint: rope of 5 m holds a 10 kg swinging load within 5.05 m and a slack rope pulls nothing",
          "[physics][joint]") {
  ScopedWorld world;
  const BodyId anchor = add_static(world.id, Vec2{0_q32, 10_q32});
  // 10 kg: a disc of radius 0.2 m, density 10/(π·0.04).
  const Q32 density = qd(10.0 / (M_PI * 0.04));
  // Start 3 m out to the side and 1 m down: slack (3.16 m), so it falls first
  // and then swings on the rope.
  const BodyId load = add_ball(world.id, Vec2{3_q32, 9_q32}, 0.2_q32, density, false);
  DistanceJointDef def = default_distance_joint_def();
  def.base.body_a = anchor;
  def.base.body_b = load;
  def.length = 5_q32;
  def.enable_spring = true;  // hertz 0: no spring force
  def.enable_limit = true;
  def.min_length = 0_q32;
  def.max_length = 5_q32;
  Result<JointId> rope = create_distance_joint(world.id, def);
  REQUIRE(rope.ok());
  REQUIRE(std::abs(d(body_mass(load)) - 10.0) < 1e-6);
  double longest = 0, slack_force = 0;
  int slack_steps = 0, taut_steps = 0;
  const int steps = k_fast ? 30 * 60 : 10 * 60;
  for (int i = 0; i < steps; ++i) {
    const double before = d(joint_translation(rope.value));
    REQUIRE(world_step(world.id, k_dt).ok());
    const double len = d(joint_translation(rope.value));
    longest = std::max(longest, len);
    const Vec2 f = joint_reaction_force(rope.value);
    if (before < 4.9 && len < 4.9) {
      ++slack_steps;
      slack_force = std::max(slack_force, std::hypot(d(f.x), d(f.y)));
    } else {
      ++taut_steps;
    }
  }
  WARN("rope: longest " << longest << " m over " << steps / 60 << " s; slack steps " << slack_steps
                        << " with largest force " << slack_force << " N; taut steps " << taut_steps);
  CHECK(longest <= 5.05);
  CHECK(slack_steps > 10);
  CHECK(taut_steps > 100);
  CHECK(slack_force == 0.0);
}

TEST_CASE("joint: a bridge of 30 planks holds a load of 10 plank masses", "[physics][joint]") {
  ScopedWorld world;
  const BodyId ground = add_static(world.id);
  const int n = 30;
  const Q32 hx = 0.5_q32, hy = 0.125_q32;
  std::vector<BodyId> planks;
  std::vector<JointId> joints;
  struct Link {
    BodyId a, b;
    Vec2 la, lb;
  };
  std::vector<Link> links;
  const double x0 = -15.0;
  BodyId prev = ground;
  for (int i = 0; i < n; ++i) {
    const BodyId plank = add_box(world.id, Vec2{qd(x0 + 0.5 + i), 0_q32}, hx, hy, 20_q32);
    planks.push_back(plank);
    const Vec2 pivot{qd(x0 + i), 0_q32};
    joints.push_back(revolute(world.id, prev, plank, pivot));
    links.push_back({prev, plank, body_local_point(prev, pivot), body_local_point(plank, pivot)});
    prev = plank;
  }
  const Vec2 end{qd(x0 + n), 0_q32};
  joints.push_back(revolute(world.id, prev, ground, end));
  links.push_back({prev, ground, body_local_point(prev, end), body_local_point(ground, end)});
  const double plank_mass = d(body_mass(planks[0]));
  // The load: a box of 10 plank masses dropped onto the middle.
  const BodyId load = add_box(world.id, Vec2{0_q32, 1_q32}, 0.5_q32, 0.5_q32, qd(10.0 * plank_mass), true);
  REQUIRE(std::abs(d(body_mass(load)) / plank_mass - 10.0) < 1e-6);
  double worst = 0;
  const int steps = k_fast ? 600 : 240;
  for (int i = 0; i < steps; ++i) {
    REQUIRE(world_step(world.id, k_dt).ok());
    for (const Link& l : links) worst = std::max(worst, separation(l.a, l.la, l.b, l.lb));
  }
  const double sag = -d(body_world_center(load).y);
  WARN("bridge: worst joint separation " << 1000.0 * worst << " mm over " << steps / 60 << " s; load sag " << sag
                                         << " m");
  for (const JointId j : joints) CHECK(joint_is_valid(j));
  // Stated figure: 4 cm. The bridge starts straight and taut, so the load
  // hangs on pure joint stretch; a soft joint at joint_hertz 60 stretches by
  // F/(m·(2π·60)²), about 3 cm for the 5 kg planks here.
  CHECK(worst < 0.04);
  CHECK(sag < 3.0);     // held up: the load rests on the bridge
  CHECK(std::abs(d(body_world_center(load).x)) < 1.0);
}

TEST_CASE("joint: revolute and prismatic limits hold against a driving motor", "[physics][joint]") {
  ScopedWorld world;
  const BodyId ground = add_static(world.id);
  const BodyId arm = add_box(world.id, Vec2{1_q32, 0_q32}, 1_q32, 0.1_q32, 1_q32, false);
  RevoluteJointDef rd = default_revolute_joint_def();
  rd.base.body_a = ground;
  rd.base.body_b = arm;
  rd.base.local_anchor_b = {-1_q32, 0_q32};
  rd.enable_limit = true;
  rd.lower_angle = qd(-0.5);
  rd.upper_angle = qd(0.5);
  rd.enable_motor = true;
  rd.motor_speed = 5_q32;
  rd.max_motor_torque = 50_q32;  // 12× the arm's gravity torque
  Result<JointId> rj = create_revolute_joint(world.id, rd);
  REQUIRE(rj.ok());

  const BodyId slider = add_box(world.id, Vec2{0_q32, 5_q32}, 0.25_q32, 0.25_q32, 1_q32, false);
  const BodyId rail = add_static(world.id, Vec2{0_q32, 5_q32});
  PrismaticJointDef pd = default_prismatic_joint_def();
  pd.base.body_a = rail;
  pd.base.body_b = slider;
  pd.local_axis_a = {1_q32, 0_q32};
  pd.enable_limit = true;
  pd.lower_translation = -1_q32;
  pd.upper_translation = 1_q32;
  pd.enable_motor = true;
  pd.motor_speed = 4_q32;
  pd.max_motor_force = 100_q32;  // 40× the slider's weight
  Result<JointId> pj = create_prismatic_joint(world.id, pd);
  REQUIRE(pj.ok());

  double worst_angle = 0, worst_translation = 0, worst_off_axis = 0;
  for (int i = 0; i < 180; ++i) {
    if (i == 90) {  // reverse both motors: the lower limits
      REQUIRE(joint_set_motor_speed(rj.value, -5_q32).ok());
      REQUIRE(joint_set_motor_speed(pj.value, -4_q32).ok());
    }
    REQUIRE(world_step(world.id, k_dt).ok());
    worst_angle = std::max(worst_angle, std::abs(d(joint_angle(rj.value))) - 0.5);
    worst_translation = std::max(worst_translation, std::abs(d(joint_translation(pj.value))) - 1.0);
    worst_off_axis = std::max(worst_off_axis, std::abs(d(body_world_center(slider).y) - 5.0));
  }
  WARN("limits under motors: revolute beyond limit " << worst_angle * 180.0 / M_PI << "°, prismatic beyond limit "
                                                     << 100.0 * worst_translation << " cm, off axis "
                                                     << 100.0 * worst_off_axis << " cm");
  CHECK(worst_angle < M_PI / 180.0);
  CHECK(worst_translation < 0.01);
  CHECK(worst_off_axis < 0.01);
  CHECK(d(joint_angle(rj.value)) < -0.45);  // it did reach the lower limit
  CHECK(d(joint_translation(pj.value)) < -0.95);
}

TEST_CASE("joint: an unloaded revolute motor reaches its target speed within 1 %", "[physics][joint]") {
  WorldDef wd = default_world_def();
  wd.gravity = {};
  ScopedWorld world(wd);
  const BodyId ground = add_static(world.id);
  const BodyId wheel = add_ball(world.id, Vec2{}, 0.5_q32, 1_q32, false);
  RevoluteJointDef rd = default_revolute_joint_def();
  rd.base.body_a = ground;
  rd.base.body_b = wheel;
  rd.enable_motor = true;
  rd.motor_speed = 3_q32;
  rd.max_motor_torque = 10_q32;
  Result<JointId> j = create_revolute_joint(world.id, rd);
  REQUIRE(j.ok());
  for (int i = 0; i < 60; ++i) REQUIRE(world_step(world.id, k_dt).ok());
  const double w = d(body_angular_velocity(wheel));
  WARN("revolute motor after 1 s: " << w << " rad/s (target 3)");
  CHECK(std::abs(w / 3.0 - 1.0) < 0.01);

  // Wheel joint motor too.
  const BodyId chassis = add_static(world.id, Vec2{5_q32, 0_q32});
  const BodyId tyre = add_ball(world.id, Vec2{5_q32, -1_q32}, 0.4_q32, 1_q32, false);
  WheelJointDef wdj = default_wheel_joint_def();
  wdj.base.body_a = chassis;
  wdj.base.body_b = tyre;
  wdj.base.local_anchor_a = {0_q32, -1_q32};
  wdj.enable_motor = true;
  wdj.motor_speed = -2_q32;
  wdj.max_motor_torque = 10_q32;
  Result<JointId> wj = create_wheel_joint(world.id, wdj);
  REQUIRE(wj.ok());
  for (int i = 0; i < 60; ++i) REQUIRE(world_step(world.id, k_dt).ok());
  CHECK(std::abs(d(body_angular_velocity(tyre)) / -2.0 - 1.0) < 0.01);
}

TEST_CASE("joint: a breakable joint fires exactly one event and is gone at the next step", "[physics][joint]") {
  ScopedWorld world;
  const BodyId ground = add_static(world.id);
  const BodyId weight = add_box(world.id, Vec2{0_q32, -1_q32}, 0.5_q32, 0.5_q32, 10_q32, false);  // 10 kg
  WeldJointDef wd = default_weld_joint_def();
  wd.base.body_a = ground;
  wd.base.body_b = weight;
  wd.base.local_anchor_b = {0_q32, 1_q32};
  wd.base.break_force = 150_q32;  // holds 100 N of weight
  wd.base.user_data = 77;
  Result<JointId> j = create_weld_joint(world.id, wd);
  REQUIRE(j.ok());
  for (int i = 0; i < 30; ++i) REQUIRE(world_step(world.id, k_dt).ok());
  REQUIRE(joint_is_valid(j.value));
  const double held = std::hypot(d(joint_reaction_force(j.value).x), d(joint_reaction_force(j.value).y));
  WARN("weld holding 10 kg: reaction " << held << " N");
  CHECK(std::abs(held - 100.0) < 1.0);
  CHECK(world_joint_events(world.id).value.empty());
  // 60 kg more: 600 N + 100 N breaks it.
  REQUIRE(body_apply_force_to_center(weight, Vec2{0_q32, -600_q32}, true).ok());
  REQUIRE(world_step(world.id, k_dt).ok());
  Result<std::span<const JointEvent>> ev = world_joint_events(world.id);
  REQUIRE(ev.ok());
  REQUIRE(ev.value.size() == 1);
  CHECK(ev.value[0].joint == j.value);
  CHECK(ev.value[0].kind == JointEventKind::broke);
  CHECK(ev.value[0].user_data == 77);
  CHECK(d(ev.value[0].force.y) > 150.0);
  CHECK_FALSE(joint_is_valid(j.value));
  CHECK(world_counters(world.id).joint_count == 0);
  REQUIRE(world_step(world.id, k_dt).ok());
  CHECK(world_joint_events(world.id).value.empty());
  CHECK(d(body_linear_velocity(weight).y) < -0.1);  // falling freely
}

TEST_CASE("joint: ragdolls piled in a box for 20 s stay together and inside", "[physics][joint]") {
  ScopedWorld world;
  // The box: 8 m wide, walls 10 m high.
  const BodyId box = add_static(world.id);
  Polygon wall;
  REQUIRE(make_offset_box(5_q32, 0.5_q32, Vec2{0_q32, -0.5_q32}, 0_q32, 0_q32, &wall).ok());
  REQUIRE(create_polygon_shape(box, default_shape_def(), wall).ok());
  REQUIRE(make_offset_box(0.5_q32, 6_q32, Vec2{-4.5_q32, 6_q32}, 0_q32, 0_q32, &wall).ok());
  REQUIRE(create_polygon_shape(box, default_shape_def(), wall).ok());
  REQUIRE(make_offset_box(0.5_q32, 6_q32, Vec2{4.5_q32, 6_q32}, 0_q32, 0_q32, &wall).ok());
  REQUIRE(create_polygon_shape(box, default_shape_def(), wall).ok());

  struct Link {
    BodyId a, b;
    Vec2 la, lb;
  };
  std::vector<Link> links;
  std::vector<BodyId> parts;
  const int ragdolls = k_fast ? 9 : 3;
  const auto capsule_body = [&](Vec2 c, Q32 half, Q32 radius, bool vertical) {
    BodyDef def = default_body_def();
    def.type = BodyType::dynamic_body;
    def.position = c;
    Result<BodyId> b = create_body(world.id, def);
    REQUIRE(b.ok());
    const Vec2 e = vertical ? Vec2{0_q32, half} : Vec2{half, 0_q32};
    REQUIRE(create_capsule_shape(b.value, default_shape_def(), Capsule{-e, e, radius}).ok());
    parts.push_back(b.value);
    return b.value;
  };
  const auto joint = [&](BodyId a, BodyId b, Vec2 pivot, double lo, double hi) {
    RevoluteJointDef rd = default_revolute_joint_def();
    rd.base.body_a = a;
    rd.base.body_b = b;
    rd.base.local_anchor_a = body_local_point(a, pivot);
    rd.base.local_anchor_b = body_local_point(b, pivot);
    rd.enable_limit = true;
    rd.lower_angle = qd(lo);
    rd.upper_angle = qd(hi);
    REQUIRE(create_revolute_joint(world.id, rd).ok());
    links.push_back({a, b, rd.base.local_anchor_a, rd.base.local_anchor_b});
  };
  for (int r = 0; r < ragdolls; ++r) {
    const double x = -2.4 + 2.4 * (r % 3) + 0.05 * (r / 3), y = 1.8 + 2.4 * (r / 3);  // 3 columns
    const BodyId torso = capsule_body(Vec2{qd(x), qd(y)}, 0.3_q32, 0.15_q32, true);
    const BodyId head = capsule_body(Vec2{qd(x), qd(y + 0.6)}, 0.05_q32, 0.12_q32, true);
    joint(torso, head, Vec2{qd(x), qd(y + 0.45)}, -0.5, 0.5);
    for (int side = -1; side <= 1; side += 2) {
      const BodyId upper_arm = capsule_body(Vec2{qd(x + side * 0.35), qd(y + 0.3)}, 0.15_q32, 0.06_q32, false);
      joint(torso, upper_arm, Vec2{qd(x + side * 0.15), qd(y + 0.3)}, -1.5, 1.5);
      const BodyId lower_arm = capsule_body(Vec2{qd(x + side * 0.7), qd(y + 0.3)}, 0.15_q32, 0.05_q32, false);
      joint(upper_arm, lower_arm, Vec2{qd(x + side * 0.52), qd(y + 0.3)}, -1.5, 0.0);
      const BodyId thigh = capsule_body(Vec2{qd(x + side * 0.1), qd(y - 0.65)}, 0.2_q32, 0.08_q32, true);
      joint(torso, thigh, Vec2{qd(x + side * 0.1), qd(y - 0.42)}, -1.0, 1.0);
      const BodyId shin = capsule_body(Vec2{qd(x + side * 0.1), qd(y - 1.15)}, 0.2_q32, 0.07_q32, true);
      joint(thigh, shin, Vec2{qd(x + side * 0.1), qd(y - 0.9)}, -1.5, 0.0);
    }
  }
  double worst = 0, resting = 0;  // over the run; over the last 5 s
  bool escaped = false;
  const int steps = k_fast ? 20 * 60 : 10 * 60;
  for (int i = 0; i < steps; ++i) {
    REQUIRE(world_step(world.id, k_dt).ok());
    double now = 0;
    for (const Link& l : links) now = std::max(now, separation(l.a, l.la, l.b, l.lb));
    worst = std::max(worst, now);
    if (i >= steps - 5 * 60) resting = std::max(resting, now);
    for (const BodyId b : parts) {
      const Vec2 c = body_world_center(b);
      if (std::abs(d(c.x)) > 4.0 || d(c.y) < 0.0 || d(c.y) > 40.0) escaped = true;
    }
  }
  WARN(ragdolls << " ragdolls (" << links.size() << " joints) in a box for " << steps / 60
                << " s: worst joint separation " << 1000.0 * worst << " mm (during the impacts), "
                << 1000.0 * resting << " mm over the last 5 s (piled at rest)");
  // Stated figures (the issue asks < 1 cm): the soft joints stretch at the
  // impacts, and the rigid position pass (joint_solver.cpp) closes every
  // revolute gap beyond its 3 mm slop once per step, after continuous
  // collision. Measured: 3.3 mm at the impacts, 3.0 mm at rest (61 mm and
  // 8.3 mm with the soft joints alone).
  CHECK(worst < 0.01);
  CHECK(resting < 0.004);
  CHECK_FALSE(escaped);
}

TEST_CASE("joint: collide_connected false keeps joined bodies from colliding", "[physics][joint]") {
  for (const bool collide : {false, true}) {
    WorldDef wd = default_world_def();
    wd.gravity = {};
    ScopedWorld world(wd);
    const BodyId a = add_box(world.id, Vec2{}, 0.5_q32, 0.5_q32, 1_q32, false);
    const BodyId b = add_box(world.id, Vec2{0.5_q32, 0_q32}, 0.5_q32, 0.5_q32, 1_q32, false);  // overlapping
    DistanceJointDef dd = default_distance_joint_def();
    dd.base.body_a = a;
    dd.base.body_b = b;
    dd.base.collide_connected = collide;
    dd.enable_spring = true;  // a free rope: no force at this length
    dd.enable_limit = true;
    dd.max_length = 10_q32;
    REQUIRE(create_distance_joint(world.id, dd).ok());
    for (int i = 0; i < 30; ++i) REQUIRE(world_step(world.id, k_dt).ok());
    const double gap = d(body_world_center(b).x - body_world_center(a).x);
    if (collide) {
      CHECK(gap > 0.9);  // pushed apart by the contact
    } else {
      CHECK(gap == 0.5);  // untouched
    }
  }
}

TEST_CASE("joint: joined bodies sleep together and wake together", "[physics][joint]") {
  ScopedWorld world;
  const BodyId ground = add_static(world.id);
  const BodyId a = add_ball(world.id, Vec2{0_q32, -1_q32}, 0.1_q32, 1_q32);
  const BodyId b = add_ball(world.id, Vec2{0_q32, -2_q32}, 0.1_q32, 1_q32);
  revolute(world.id, ground, a, Vec2{});
  revolute(world.id, a, b, Vec2{0_q32, -1_q32});
  int steps = 0;
  while (body_is_awake(a) && steps < 600) {
    REQUIRE(world_step(world.id, k_dt).ok());
    ++steps;
    CHECK(body_is_awake(a) == body_is_awake(b));
  }
  CHECK_FALSE(body_is_awake(a));
  CHECK_FALSE(body_is_awake(b));
  REQUIRE(body_apply_linear_impulse_to_center(b, Vec2{1_q32, 0_q32}, true).ok());
  CHECK(body_is_awake(a));  // one island
  REQUIRE(world_step(world.id, k_dt).ok());
  CHECK(body_is_awake(a));
  CHECK(body_is_awake(b));
}

TEST_CASE("joint: a body joined to a moving kinematic body never falls asleep", "[physics][joint]") {
  // A ball pinned at the centre of a slowly turning kinematic disc barely
  // moves (below the sleep tolerances), but the joint drives it: it must
  // stay awake for as long as the disc turns, and may sleep once it stops.
  ScopedWorld world;
  BodyDef kd = default_body_def();
  kd.type = BodyType::kinematic_body;
  kd.angular_velocity = 0.5_q32;
  const Result<BodyId> disc = create_body(world.id, kd);
  REQUIRE(disc.ok());
  REQUIRE(create_circle_shape(disc.value, default_shape_def(), Circle{{}, 1_q32}).ok());
  const BodyId ball = add_ball(world.id, Vec2{}, 0.1_q32, 1_q32, true);
  RevoluteJointDef rd = default_revolute_joint_def();
  rd.base.body_a = disc.value;
  rd.base.body_b = ball;
  REQUIRE(create_revolute_joint(world.id, rd).ok());
  int asleep_steps = 0;
  for (int i = 0; i < 180; ++i) {
    REQUIRE(world_step(world.id, k_dt).ok());
    if (!body_is_awake(ball)) ++asleep_steps;
  }
  CHECK(asleep_steps == 0);
  REQUIRE(body_set_angular_velocity(disc.value, 0_q32).ok());
  for (int i = 0; i < 120; ++i) REQUIRE(world_step(world.id, k_dt).ok());
  CHECK_FALSE(body_is_awake(ball));  // the disc stopped: the ball sleeps again
}

TEST_CASE("joint: destroying a body destroys its joints and reports them at the next step", "[physics][joint]") {
  ScopedWorld world;
  const BodyId ground = add_static(world.id);
  const BodyId a = add_ball(world.id, Vec2{0_q32, -1_q32}, 0.1_q32, 1_q32);
  const BodyId b = add_ball(world.id, Vec2{0_q32, -2_q32}, 0.1_q32, 1_q32);
  const JointId j1 = revolute(world.id, ground, a, Vec2{});
  const JointId j2 = revolute(world.id, a, b, Vec2{0_q32, -1_q32});
  const JointId j3 = revolute(world.id, ground, b, Vec2{1_q32, -2_q32});
  REQUIRE(world_step(world.id, k_dt).ok());
  REQUIRE(destroy_body(a).ok());
  CHECK_FALSE(joint_is_valid(j1));
  CHECK_FALSE(joint_is_valid(j2));
  CHECK(joint_is_valid(j3));
  CHECK(world_counters(world.id).joint_count == 1);
  REQUIRE(world_step(world.id, k_dt).ok());
  std::span<const JointEvent> ev = world_joint_events(world.id).value;
  REQUIRE(ev.size() == 2);
  CHECK(ev[0].joint == j1);
  CHECK(ev[1].joint == j2);
  CHECK(ev[0].kind == JointEventKind::destroyed_with_body);
  REQUIRE(world_step(world.id, k_dt).ok());
  CHECK(world_joint_events(world.id).value.empty());
  CHECK(destroy_joint(j3).ok());
  CHECK(destroy_joint(j3).code == StatusCode::invalid_handle);
}

TEST_CASE("joint: bad input is refused with the field and range named, nothing changed", "[physics][joint]") {
  ScopedWorld world;
  ScopedWorld other;
  const BodyId ground = add_static(world.id);
  const BodyId ground2 = add_static(world.id, Vec2{1_q32, 0_q32});
  const BodyId ball = add_ball(world.id, Vec2{0_q32, -1_q32}, 0.1_q32, 1_q32);
  const BodyId foreign = add_ball(other.id, Vec2{}, 0.1_q32, 1_q32);
  const BodyId dead = add_ball(world.id, Vec2{3_q32, 0_q32}, 0.1_q32, 1_q32);
  REQUIRE(destroy_body(dead).ok());
  const auto refused = [&](const Status& s, const char* needle) {
    INFO(s.message);
    CHECK_FALSE(s.ok());
    CHECK(s.message.find(needle) != std::string::npos);
    CHECK(world_counters(world.id).joint_count == 0);
  };
  RevoluteJointDef rd = default_revolute_joint_def();
  rd.base.body_a = ball;
  rd.base.body_b = ball;
  refused(create_revolute_joint(world.id, rd).status, "the same");
  rd.base.body_a = ground;
  rd.base.body_b = ground2;
  refused(create_revolute_joint(world.id, rd).status, "both static");
  rd.base.body_b = foreign;
  refused(create_revolute_joint(world.id, rd).status, "base.body_b");
  CHECK(create_revolute_joint(world.id, rd).status.code == StatusCode::foreign_handle);
  rd.base.body_b = dead;
  refused(create_revolute_joint(world.id, rd).status, "was destroyed");
  rd.base.body_b = ball;
  rd.enable_limit = true;
  rd.lower_angle = 1_q32;
  rd.upper_angle = 0_q32;
  refused(create_revolute_joint(world.id, rd).status, "RevoluteJointDef.lower_angle 1 is above");
  rd.lower_angle = -4_q32;
  refused(create_revolute_joint(world.id, rd).status, "RevoluteJointDef.lower_angle -4 rad is outside [");
  rd.lower_angle = 0_q32;
  rd.max_motor_torque = -1_q32;
  refused(create_revolute_joint(world.id, rd).status, "max_motor_torque");
  rd.max_motor_torque = 0_q32;
  rd.hertz = 20000_q32;
  refused(create_revolute_joint(world.id, rd).status, "RevoluteJointDef.hertz 20000 Hz is outside [0, 10000] Hz");
  RevoluteJointDef no_cookie{};
  no_cookie.base = rd.base;
  refused(create_revolute_joint(world.id, no_cookie).status, "default_");

  DistanceJointDef dd = default_distance_joint_def();
  dd.base.body_a = ground;
  dd.base.body_b = ball;
  dd.length = 0_q32;
  refused(create_distance_joint(world.id, dd).status, "DistanceJointDef.length 0 m is outside");
  dd.length = 1_q32;
  dd.max_length = -5_q32;
  refused(create_distance_joint(world.id, dd).status, "DistanceJointDef.max_length");
  dd.max_length = 5_q32;
  dd.min_length = 6_q32;
  refused(create_distance_joint(world.id, dd).status, "DistanceJointDef.min_length");

  PrismaticJointDef pd = default_prismatic_joint_def();
  pd.base.body_a = ground;
  pd.base.body_b = ball;
  pd.local_axis_a = {};
  refused(create_prismatic_joint(world.id, pd).status, "PrismaticJointDef.local_axis_a (0, 0)");
  pd.local_axis_a = {1_q32, 1_q32};
  refused(create_prismatic_joint(world.id, pd).status, "unit vector");
  pd.local_axis_a = {1_q32, 0_q32};
  pd.lower_translation = 2_q32;
  refused(create_prismatic_joint(world.id, pd).status, "lower_translation 2 is above");

  MouseJointDef md = default_mouse_joint_def();
  md.base.body_a = ground;
  md.base.body_b = ball;
  md.max_force = 200000000_q32;
  refused(create_mouse_joint(world.id, md).status, "MouseJointDef.max_force");
  MotorJointDef mo = default_motor_joint_def();
  mo.base.body_a = ground;
  mo.base.body_b = ball;
  mo.correction_factor = 2_q32;
  refused(create_motor_joint(world.id, mo).status, "correction_factor");

  // Setters: a good joint, bad values, nothing changed.
  dd.min_length = 0_q32;
  Result<JointId> j = create_distance_joint(world.id, dd);
  REQUIRE(j.ok());
  CHECK_FALSE(joint_set_length(j.value, -1_q32).ok());
  CHECK_FALSE(joint_set_limits(j.value, 3_q32, 2_q32).ok());
  CHECK_FALSE(joint_set_target(j.value, Vec2{}).ok());  // not a mouse joint
  CHECK(d(joint_translation(j.value)) == 1.0);
  CHECK(joint_set_length(j.value, 2_q32).ok());
}

TEST_CASE("joint: every kind steps deterministically and two runs agree bit for bit", "[physics][joint]") {
  const auto run = [](std::vector<int64_t>* out) {
    ScopedWorld world;
    const BodyId ground = add_static(world.id);
    std::vector<BodyId> bodies;
    for (int i = 0; i < 7; ++i) bodies.push_back(add_box(world.id, Vec2{qd(2.0 * i), -1_q32}, 0.3_q32, 0.2_q32, 1_q32));
    RevoluteJointDef r = default_revolute_joint_def();
    r.base.body_a = ground;
    r.base.body_b = bodies[0];
    r.base.local_anchor_b = {0_q32, 1_q32};
    r.enable_spring = true;
    r.hertz = 2_q32;
    r.damping_ratio = 0.1_q32;
    REQUIRE(create_revolute_joint(world.id, r).ok());
    DistanceJointDef ds = default_distance_joint_def();
    ds.base.body_a = ground;
    ds.base.body_b = bodies[1];
    ds.base.local_anchor_a = {2_q32, 0_q32};
    ds.length = 1_q32;
    ds.enable_spring = true;
    ds.hertz = 3_q32;
    ds.damping_ratio = 0.2_q32;
    REQUIRE(create_distance_joint(world.id, ds).ok());
    WeldJointDef wd = default_weld_joint_def();
    wd.base.body_a = bodies[1];
    wd.base.body_b = bodies[2];
    wd.base.local_anchor_a = {1_q32, 0_q32};
    wd.base.local_anchor_b = {-1_q32, 0_q32};
    wd.angular_hertz = 5_q32;
    wd.angular_damping_ratio = 0.5_q32;
    REQUIRE(create_weld_joint(world.id, wd).ok());
    PrismaticJointDef pd = default_prismatic_joint_def();
    pd.base.body_a = ground;
    pd.base.body_b = bodies[3];
    pd.base.local_anchor_a = {6_q32, -1_q32};
    pd.local_axis_a = {0_q32, 1_q32};
    pd.enable_spring = true;
    pd.hertz = 1_q32;
    pd.damping_ratio = 0.3_q32;
    REQUIRE(create_prismatic_joint(world.id, pd).ok());
    MouseJointDef md = default_mouse_joint_def();
    md.base.body_a = ground;
    md.base.body_b = bodies[4];
    md.target = {8_q32, 2_q32};
    Result<JointId> mouse = create_mouse_joint(world.id, md);
    REQUIRE(mouse.ok());
    WheelJointDef whd = default_wheel_joint_def();
    whd.base.body_a = ground;
    whd.base.body_b = bodies[5];
    whd.base.local_anchor_a = {10_q32, -1_q32};
    whd.enable_motor = true;
    whd.motor_speed = 2_q32;
    whd.max_motor_torque = 5_q32;
    REQUIRE(create_wheel_joint(world.id, whd).ok());
    MotorJointDef mo = default_motor_joint_def();
    mo.base.body_a = ground;
    mo.base.body_b = bodies[6];
    mo.linear_offset = {12_q32, 1_q32};
    mo.angular_offset = 1_q32;
    mo.max_force = 100_q32;
    mo.max_torque = 10_q32;
    REQUIRE(create_motor_joint(world.id, mo).ok());
    for (int i = 0; i < 120; ++i) {
      if (i == 60) REQUIRE(joint_set_target(mouse.value, Vec2{9_q32, 3_q32}).ok());
      REQUIRE(world_step(world.id, k_dt).ok());
    }
    for (const BodyId b : bodies) {
      const Transform t = body_transform(b);
      out->push_back(t.p.x.raw);
      out->push_back(t.p.y.raw);
      out->push_back(t.q.s.raw);
    }
    // Each joint did its job (loosely): the motor joint moved its body to the offset.
    CHECK(std::abs(d(body_position(bodies[6]).x) - 12.0) < 0.05);
    CHECK(std::abs(d(body_angle(bodies[6])) - 1.0) < 0.05);
    CHECK(std::abs(d(body_world_point(bodies[4], Vec2{}).x) - 9.0) < 0.2);  // mouse follows the target
    CHECK(std::abs(d(body_position(bodies[3]).x) - 6.0) < 0.001);         // prismatic stays on its axis
    CHECK(std::abs(d(body_position(bodies[5]).x) - 10.0) < 0.001);        // wheel stays on its axis
  };
  std::vector<int64_t> a, b;
  run(&a);
  run(&b);
  CHECK(a == b);
}
