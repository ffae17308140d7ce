// test_capi_joint.cpp — joints and the world profile through the C API
// (tandem_c_joint.h): defaults equal C++'s, every kind created, every getter
// and setter, events, errors for NULL / stale / foreign handles and too-small
// buffers, and a scene with joints of every kind driven through C and C++
// (including joint commands) hashing the same every tick.
#include "capi_test_util.h"

#include "replay/commands.h"

namespace {

// The C handle of a C++ one and back (the same bits: index, generation).
tandem_body_id c_of(tandem::BodyId b) { return {b.index1, b.generation, {b.world.index1, b.world.generation}}; }

tandem_joint_base_def base(tandem_body_id a, tandem_body_id b) {
  tandem_joint_base_def d = tandem_default_revolute_joint_def().base;
  d.body_a = a;
  d.body_b = b;
  return d;
}

tandem_joint_id create_revolute(tandem_world_id w, tandem_body_id a, tandem_body_id b, tandem_vec2 anchor_a) {
  tandem_revolute_joint_def d = tandem_default_revolute_joint_def();
  d.base = base(a, b);
  d.base.local_anchor_a = anchor_a;
  tandem_joint_id j{};
  REQUIRE(tandem_create_revolute_joint(w, &d, &j) == TANDEM_OK);
  return j;
}

}  // namespace

TEST_CASE("joint definitions: the C defaults are the C++ defaults", "[capi][joint]") {
  using namespace tandem;
  const tandem_revolute_joint_def r = tandem_default_revolute_joint_def();
  CHECK(r.internal_cookie == default_revolute_joint_def().internal_cookie);
  CHECK(r.internal_cookie != 0);
  CHECK_FALSE(r.base.collide_connected);
  const tandem_distance_joint_def d = tandem_default_distance_joint_def();
  CHECK(d.length == default_distance_joint_def().length.raw);
  CHECK(d.max_length == default_distance_joint_def().max_length.raw);
  CHECK(d.internal_cookie == default_distance_joint_def().internal_cookie);
  const tandem_weld_joint_def w = tandem_default_weld_joint_def();
  CHECK(w.internal_cookie == default_weld_joint_def().internal_cookie);
  const tandem_prismatic_joint_def p = tandem_default_prismatic_joint_def();
  CHECK(p.local_axis_a.x == default_prismatic_joint_def().local_axis_a.x.raw);
  CHECK(p.internal_cookie == default_prismatic_joint_def().internal_cookie);
  const tandem_mouse_joint_def m = tandem_default_mouse_joint_def();
  CHECK(m.hertz == default_mouse_joint_def().hertz.raw);
  CHECK(m.damping_ratio == default_mouse_joint_def().damping_ratio.raw);
  CHECK(m.max_force == default_mouse_joint_def().max_force.raw);
  const tandem_wheel_joint_def wh = tandem_default_wheel_joint_def();
  CHECK(wh.local_axis_a.y == default_wheel_joint_def().local_axis_a.y.raw);
  CHECK(wh.enable_spring);
  CHECK(wh.hertz == default_wheel_joint_def().hertz.raw);
  const tandem_motor_joint_def mo = tandem_default_motor_joint_def();
  CHECK(mo.correction_factor == default_motor_joint_def().correction_factor.raw);
  CHECK(mo.max_torque == default_motor_joint_def().max_torque.raw);
  CHECK(mo.internal_cookie == default_motor_joint_def().internal_cookie);
}

TEST_CASE("joints: every kind, getters, setters, lists, events and errors", "[capi][joint]") {
  CWorld c;
  const tandem_world_id w = c.id;
  const tandem_body_id ground = add_ground(w);
  const tandem_body_id a = add_box(w, TANDEM_BODY_DYNAMIC, v2(0, 4), qt("0.5"));
  const tandem_body_id b = add_box(w, TANDEM_BODY_DYNAMIC, v2(2, 4), qt("0.5"));
  const tandem_body_id e = add_box(w, TANDEM_BODY_DYNAMIC, v2(-3, 4), qt("0.5"));

  // Revolute: pinned to the ground, with a motor.
  const tandem_joint_id rev = create_revolute(w, ground, a, v2(0, 4));
  CHECK(tandem_joint_is_valid(rev));
  CHECK(tandem_joint_check(rev) == TANDEM_OK);
  CHECK(tandem_joint_type(rev) == TANDEM_JOINT_REVOLUTE);
  CHECK(tandem_joint_body_a(rev).index1 == ground.index1);
  CHECK(tandem_joint_body_b(rev).index1 == a.index1);
  REQUIRE(tandem_joint_enable_motor(rev, true) == TANDEM_OK);
  REQUIRE(tandem_joint_set_motor_speed(rev, qi(2)) == TANDEM_OK);
  REQUIRE(tandem_joint_set_max_motor_force(rev, qi(50)) == TANDEM_OK);
  REQUIRE(tandem_joint_enable_limit(rev, true) == TANDEM_OK);
  REQUIRE(tandem_joint_set_limits(rev, qt("-1"), qt("1")) == TANDEM_OK);
  require_error(tandem_joint_set_limits(rev, qt("1"), qt("-1")), TANDEM_ERROR_INVALID_ARGUMENT, "");
  REQUIRE(tandem_joint_enable_spring(rev, false) == TANDEM_OK);
  REQUIRE(tandem_joint_set_spring(rev, qi(2), qt("0.5")) == TANDEM_OK);
  // Kinds without the setting refuse it.
  require_error(tandem_joint_set_target(rev, v2(1, 1)), TANDEM_ERROR_INVALID_ARGUMENT, "");
  require_error(tandem_joint_set_length(rev, qi(1)), TANDEM_ERROR_INVALID_ARGUMENT, "");
  require_error(tandem_joint_set_offsets(rev, v2(0, 0), 0), TANDEM_ERROR_INVALID_ARGUMENT, "");

  // Distance as a rope (spring with hertz 0, limit [0, 3]), user data, break thresholds.
  tandem_distance_joint_def dd = tandem_default_distance_joint_def();
  dd.base = base(a, b);
  dd.base.user_data = 77;
  dd.length = qi(2);
  dd.enable_spring = true;
  dd.enable_limit = true;
  dd.min_length = 0;
  dd.max_length = qi(3);
  tandem_joint_id rope{};
  REQUIRE(tandem_create_distance_joint(w, &dd, &rope) == TANDEM_OK);
  CHECK(tandem_joint_type(rope) == TANDEM_JOINT_DISTANCE);
  CHECK(tandem_joint_user_data(rope) == 77);
  REQUIRE(tandem_joint_set_length(rope, qt("2.5")) == TANDEM_OK);
  REQUIRE(tandem_joint_set_break_thresholds(rope, 0, 0) == TANDEM_OK);

  // Weld, prismatic, wheel, motor, mouse.
  tandem_weld_joint_def wd = tandem_default_weld_joint_def();
  wd.base = base(b, e);
  wd.base.collide_connected = true;
  tandem_joint_id weld{};
  REQUIRE(tandem_create_weld_joint(w, &wd, &weld) == TANDEM_OK);
  tandem_prismatic_joint_def pd = tandem_default_prismatic_joint_def();
  pd.base = base(ground, e);
  pd.enable_limit = true;
  pd.lower_translation = qi(-1);
  pd.upper_translation = qi(1);
  tandem_joint_id prism{};
  REQUIRE(tandem_create_prismatic_joint(w, &pd, &prism) == TANDEM_OK);
  tandem_wheel_joint_def whd = tandem_default_wheel_joint_def();
  whd.base = base(a, e);
  tandem_joint_id wheel{};
  REQUIRE(tandem_create_wheel_joint(w, &whd, &wheel) == TANDEM_OK);
  tandem_motor_joint_def md = tandem_default_motor_joint_def();
  md.base = base(ground, b);
  tandem_joint_id motor{};
  REQUIRE(tandem_create_motor_joint(w, &md, &motor) == TANDEM_OK);
  REQUIRE(tandem_joint_set_offsets(motor, v2(2, 4), qt("0.1")) == TANDEM_OK);
  tandem_mouse_joint_def mdd = tandem_default_mouse_joint_def();
  mdd.base = base(ground, b);
  mdd.target = v2(2, 4);
  tandem_joint_id mouse{};
  REQUIRE(tandem_create_mouse_joint(w, &mdd, &mouse) == TANDEM_OK);
  REQUIRE(tandem_joint_set_target(mouse, v2(3, 5)) == TANDEM_OK);
  CHECK(tandem_joint_world_anchor_a(mouse).x == qi(3));
  CHECK(tandem_world_get_counters(w).joint_count == 7);

  // Lists (buffer rule).
  int32_t n = 0;
  REQUIRE(tandem_world_joints(w, nullptr, 0, &n) == TANDEM_OK);
  CHECK(n == 7);
  tandem_joint_id ids[8]{};
  require_error(tandem_world_joints(w, ids, 3, &n), TANDEM_ERROR_BUFFER_TOO_SMALL, "7");
  REQUIRE(tandem_world_joints(w, ids, 8, &n) == TANDEM_OK);
  CHECK(ids[0].index1 == rev.index1);
  REQUIRE(tandem_body_joints(a, ids, 8, &n) == TANDEM_OK);
  CHECK(n == 3);  // revolute, rope, wheel
  require_error(tandem_body_joints(a, ids, 8, nullptr), TANDEM_ERROR_NULL_POINTER, "out_count");

  // Describe (text rule).
  size_t length = 0;
  REQUIRE(tandem_joint_describe(rev, nullptr, 0, &length) == TANDEM_OK);
  std::string text(length + 1, '\0');
  REQUIRE(tandem_joint_describe(rev, text.data(), text.size(), &length) == TANDEM_OK);
  CHECK(std::string(text.c_str()).find("joint {index 0") != std::string::npos);
  char tiny[2];
  require_error(tandem_joint_describe(rev, tiny, 2, &length), TANDEM_ERROR_BUFFER_TOO_SMALL, "");

  // Step: reactions, anchors, angles, translations, the profile.
  const tandem_world_profile before = tandem_world_get_profile(w);
  CHECK(before.total_ns == 0);
  for (int i = 0; i < 30; ++i) REQUIRE(tandem_world_step(w, qt("0.0166666667"), nullptr) == TANDEM_OK);
  const tandem_vec2 f = tandem_joint_reaction_force(rev);
  CHECK((f.x != 0 || f.y != 0));
  (void)tandem_joint_reaction_torque(rev);
  CHECK(tandem_joint_world_anchor_a(rev).y == qi(4));
  CHECK(tandem_joint_world_anchor_b(rev).y != 0);
  const tandem_q32 angle = tandem_joint_angle(rev);
  CHECK(angle >= qi(-1) - qt("0.1"));
  CHECK(angle <= qi(1) + qt("0.1"));
  CHECK(tandem_joint_translation(rope) > 0);
  const tandem_world_profile p = tandem_world_get_profile(w);
  CHECK(p.total_ns > 0);
  CHECK(p.broad_phase_ns + p.narrow_phase_ns + p.islands_ns + p.events_ns + p.prepare_ns + p.integrate_velocities_ns +
            p.warm_start_ns + p.solve_ns + p.integrate_positions_ns + p.relax_ns + p.restitution_ns +
            p.store_impulses_ns + p.continuous_ns + p.finalize_ns <=
        p.total_ns);
  CHECK(tandem_world_get_profile(tandem_world_id{}).total_ns == 0);

  // A tiny break force breaks the rope at the next step: one event, stale handle.
  REQUIRE(tandem_joint_set_break_thresholds(rope, 1, 0) == TANDEM_OK);
  REQUIRE(tandem_world_step(w, qt("0.0166666667"), nullptr) == TANDEM_OK);
  tandem_joint_event events[4]{};
  REQUIRE(tandem_world_joint_events(w, nullptr, 0, &n) == TANDEM_OK);
  REQUIRE(n == 1);
  REQUIRE(tandem_world_joint_events(w, events, 4, &n) == TANDEM_OK);
  CHECK(events[0].kind == TANDEM_JOINT_EVENT_BROKE);
  CHECK(events[0].joint.index1 == rope.index1);
  CHECK(events[0].user_data == 77);
  CHECK((events[0].force.x != 0 || events[0].force.y != 0));
  CHECK_FALSE(tandem_joint_is_valid(rope));
  require_error(tandem_joint_check(rope), TANDEM_ERROR_INVALID_HANDLE, "");
  require_error(tandem_joint_set_motor_speed(rope, 0), TANDEM_ERROR_INVALID_HANDLE, "");

  // Destroying a body destroys its joints (reported at the next step).
  REQUIRE(tandem_destroy_body(e) == TANDEM_OK);
  CHECK_FALSE(tandem_joint_is_valid(weld));
  REQUIRE(tandem_world_step(w, qt("0.0166666667"), nullptr) == TANDEM_OK);
  REQUIRE(tandem_world_joint_events(w, events, 4, &n) == TANDEM_OK);
  REQUIRE(n == 3);  // weld, prismatic, wheel
  CHECK(events[0].kind == TANDEM_JOINT_EVENT_DESTROYED_WITH_BODY);
  require_error(tandem_world_joint_events(tandem_world_id{}, events, 4, &n), TANDEM_ERROR_NULL_HANDLE, "");

  // Destroy, stale, null, invalid definitions.
  REQUIRE(tandem_destroy_joint(motor) == TANDEM_OK);
  require_error(tandem_destroy_joint(motor), TANDEM_ERROR_INVALID_HANDLE, "");
  require_error(tandem_joint_check(tandem_joint_id{}), TANDEM_ERROR_NULL_HANDLE, "");
  CHECK(tandem_joint_type(motor) == TANDEM_JOINT_REVOLUTE);
  CHECK(tandem_joint_body_a(motor).index1 == 0);
  CHECK(tandem_joint_user_data(motor) == 0);
  CHECK(tandem_joint_reaction_torque(motor) == 0);
  tandem_joint_id j{};
  tandem_revolute_joint_def bad = tandem_default_revolute_joint_def();
  bad.base = base(a, a);
  require_error(tandem_create_revolute_joint(w, &bad, &j), TANDEM_ERROR_INVALID_ARGUMENT, "body");
  bad.base = base(a, b);
  bad.internal_cookie = 0;
  require_error(tandem_create_revolute_joint(w, &bad, &j), TANDEM_ERROR_INVALID_DEFINITION, "");
  require_error(tandem_create_revolute_joint(w, nullptr, &j), TANDEM_ERROR_NULL_POINTER, "def");
  require_error(tandem_create_distance_joint(w, &dd, nullptr), TANDEM_ERROR_NULL_POINTER, "out_joint");
  require_error(tandem_create_weld_joint(w, nullptr, &j), TANDEM_ERROR_NULL_POINTER, "def");
  require_error(tandem_create_prismatic_joint(w, nullptr, &j), TANDEM_ERROR_NULL_POINTER, "def");
  require_error(tandem_create_wheel_joint(w, nullptr, &j), TANDEM_ERROR_NULL_POINTER, "def");
  require_error(tandem_create_motor_joint(w, nullptr, &j), TANDEM_ERROR_NULL_POINTER, "def");
  require_error(tandem_create_mouse_joint(w, nullptr, &j), TANDEM_ERROR_NULL_POINTER, "def");
  tandem_mouse_joint_def far = tandem_default_mouse_joint_def();
  far.base = base(ground, b);
  far.max_force = qi(-1);
  require_error(tandem_create_mouse_joint(w, &far, &j), TANDEM_ERROR_INVALID_ARGUMENT, "max_force");
  require_error(tandem_world_joints(tandem_world_id{}, ids, 8, &n), TANDEM_ERROR_NULL_HANDLE, "");
  require_error(tandem_body_joints(e, ids, 8, &n), TANDEM_ERROR_INVALID_HANDLE, "");
}

TEST_CASE("collide_connected decides whether joined bodies touch", "[capi][joint]") {
  for (const bool collide : {false, true}) {
    CWorld c;
    REQUIRE(tandem_world_set_gravity(c.id, v2(0, 0)) == TANDEM_OK);
    const tandem_body_id a = add_box(c.id, TANDEM_BODY_DYNAMIC, v2(0, 2), qt("0.5"));
    const tandem_body_id b = add_box(c.id, TANDEM_BODY_DYNAMIC, {qt("0.5"), qi(2)}, qt("0.5"));  // overlaps a by half
    tandem_revolute_joint_def d = tandem_default_revolute_joint_def();
    d.base = base(a, b);
    d.base.collide_connected = collide;
    tandem_joint_id j{};
    REQUIRE(tandem_create_revolute_joint(c.id, &d, &j) == TANDEM_OK);
    REQUIRE(tandem_world_step(c.id, qt("0.0166666667"), nullptr) == TANDEM_OK);
    int32_t n = -1;
    REQUIRE(tandem_world_contact_begin_events(c.id, nullptr, 0, &n) == TANDEM_OK);
    INFO("collide_connected " << collide);
    CHECK((n > 0) == collide);
  }
}

TEST_CASE("a scene with every joint kind through C and C++ hashes the same every tick", "[capi][joint][determinism]") {
  using namespace tandem;
  const WorldId cw = create_world(default_world_def()).value;
  CWorld c;
  // The same bodies in both worlds.
  const BodyId g = create_body(cw, default_body_def()).value;
  const tandem_body_id cg = add_ground(c.id);
  {
    Polygon box;
    REQUIRE(make_offset_box(Q32::from_int(20), Q32::from_int(1), vec2(0, -1), Q32{}, Q32{}, &box).ok());
    REQUIRE(create_polygon_shape(g, default_shape_def(), box).ok());
  }
  std::vector<BodyId> cpp;
  std::vector<tandem_body_id> cb;
  for (int i = 0; i < 7; ++i) {
    BodyDef def = default_body_def();
    def.type = BodyType::dynamic_body;
    def.position = Vec2{Q32::from_int(i * 2 - 6), Q32::from_int(3 + i % 2)};
    const BodyId b = create_body(cw, def).value;
    Polygon box;
    REQUIRE(make_box(Q32::from_ratio(1, 2), Q32::from_ratio(1, 2), &box).ok());
    REQUIRE(create_polygon_shape(b, default_shape_def(), box).ok());
    cpp.push_back(b);
    cb.push_back(add_box(c.id, TANDEM_BODY_DYNAMIC, {def.position.x.raw, def.position.y.raw}, qt("0.5")));
  }
  REQUIRE(c_of(cpp[3]).index1 == cb[3].index1);

  // One joint of each kind, through both APIs (C definitions from the C
  // defaults, C++ ones from the C++ defaults, same settings).
  RevoluteJointDef rd = default_revolute_joint_def();
  rd.base.body_a = g, rd.base.body_b = cpp[0], rd.base.local_anchor_a = vec2(-6, 3);
  rd.enable_motor = true, rd.motor_speed = Q32::from_int(3), rd.max_motor_torque = Q32::from_int(40);
  const JointId rev = create_revolute_joint(cw, rd).value;
  tandem_revolute_joint_def crd = tandem_default_revolute_joint_def();
  crd.base = base(cg, cb[0]), crd.base.local_anchor_a = v2(-6, 3);
  crd.enable_motor = true, crd.motor_speed = qi(3), crd.max_motor_torque = qi(40);
  tandem_joint_id crev{};
  REQUIRE(tandem_create_revolute_joint(c.id, &crd, &crev) == TANDEM_OK);

  DistanceJointDef dd = default_distance_joint_def();  // a rope
  dd.base.body_a = cpp[0], dd.base.body_b = cpp[1], dd.length = Q32::from_int(2);
  dd.enable_spring = true, dd.enable_limit = true, dd.min_length = Q32{}, dd.max_length = Q32::from_int(3);
  REQUIRE(create_distance_joint(cw, dd).ok());
  tandem_distance_joint_def cdd = tandem_default_distance_joint_def();
  cdd.base = base(cb[0], cb[1]), cdd.length = qi(2);
  cdd.enable_spring = true, cdd.enable_limit = true, cdd.min_length = 0, cdd.max_length = qi(3);
  tandem_joint_id cj{};
  REQUIRE(tandem_create_distance_joint(c.id, &cdd, &cj) == TANDEM_OK);

  WeldJointDef wd = default_weld_joint_def();
  wd.base.body_a = cpp[1], wd.base.body_b = cpp[2], wd.base.local_anchor_a = vec2(1, 0), wd.base.local_anchor_b = vec2(-1, 0);
  wd.angular_hertz = Q32::from_int(4);
  REQUIRE(create_weld_joint(cw, wd).ok());
  tandem_weld_joint_def cwd = tandem_default_weld_joint_def();
  cwd.base = base(cb[1], cb[2]), cwd.base.local_anchor_a = v2(1, 0), cwd.base.local_anchor_b = v2(-1, 0);
  cwd.angular_hertz = qi(4);
  REQUIRE(tandem_create_weld_joint(c.id, &cwd, &cj) == TANDEM_OK);

  PrismaticJointDef pd = default_prismatic_joint_def();
  pd.base.body_a = g, pd.base.body_b = cpp[3], pd.base.local_anchor_a = vec2(0, 4);
  pd.enable_spring = true, pd.hertz = Q32::from_int(1), pd.damping_ratio = Q32::from_ratio(1, 2);
  REQUIRE(create_prismatic_joint(cw, pd).ok());
  tandem_prismatic_joint_def cpd = tandem_default_prismatic_joint_def();
  cpd.base = base(cg, cb[3]), cpd.base.local_anchor_a = v2(0, 4);
  cpd.enable_spring = true, cpd.hertz = qi(1), cpd.damping_ratio = qt("0.5");
  REQUIRE(tandem_create_prismatic_joint(c.id, &cpd, &cj) == TANDEM_OK);

  WheelJointDef whd = default_wheel_joint_def();
  whd.base.body_a = cpp[3], whd.base.body_b = cpp[4], whd.enable_motor = true;
  whd.motor_speed = Q32::from_int(-2), whd.max_motor_torque = Q32::from_int(10);
  REQUIRE(create_wheel_joint(cw, whd).ok());
  tandem_wheel_joint_def cwh = tandem_default_wheel_joint_def();
  cwh.base = base(cb[3], cb[4]), cwh.enable_motor = true, cwh.motor_speed = qi(-2), cwh.max_motor_torque = qi(10);
  REQUIRE(tandem_create_wheel_joint(c.id, &cwh, &cj) == TANDEM_OK);

  MotorJointDef mod = default_motor_joint_def();
  mod.base.body_a = g, mod.base.body_b = cpp[5], mod.linear_offset = vec2(4, 4), mod.max_force = Q32::from_int(200);
  REQUIRE(create_motor_joint(cw, mod).ok());
  tandem_motor_joint_def cmod = tandem_default_motor_joint_def();
  cmod.base = base(cg, cb[5]), cmod.linear_offset = v2(4, 4), cmod.max_force = qi(200);
  REQUIRE(tandem_create_motor_joint(c.id, &cmod, &cj) == TANDEM_OK);

  MouseJointDef md = default_mouse_joint_def();
  md.base.body_a = g, md.base.body_b = cpp[6], md.target = vec2(6, 6);
  const JointId mouse = create_mouse_joint(cw, md).value;
  tandem_mouse_joint_def cmd = tandem_default_mouse_joint_def();
  cmd.base = base(cg, cb[6]), cmd.target = v2(6, 6);
  tandem_joint_id cmouse{};
  REQUIRE(tandem_create_mouse_joint(c.id, &cmd, &cmouse) == TANDEM_OK);

  REQUIRE(world_state_hash(cw) == tandem_world_state_hash(c.id));
  const Q32 dt = Q32::from_ratio(1, 60);
  for (int tick = 1; tick <= 240; ++tick) {
    if (tick % 20 == 0) {  // the same runtime settings through both APIs
      const Vec2 t{Q32::from_int(6 - tick / 40), Q32::from_ratio(tick % 7 + 3, 1)};
      REQUIRE(joint_set_target(mouse, t).ok());
      REQUIRE(tandem_joint_set_target(cmouse, {t.x.raw, t.y.raw}) == TANDEM_OK);
      REQUIRE(joint_set_motor_speed(rev, Q32::from_ratio(tick % 9 - 4, 2)).ok());
      REQUIRE(tandem_joint_set_motor_speed(crev, Q32::from_ratio(tick % 9 - 4, 2).raw) == TANDEM_OK);
    }
    if (tick == 100) {  // a joint command (create_joint: a revolute between bodies 4 and 5)
      Command command;
      command.type = CommandType::create_joint;
      command.joint_spec.type = JointType::revolute;
      command.joint_spec.body_a = body_ref(cpp[4]);
      command.joint_spec.body_b = body_ref(cpp[5]);
      command.joint_spec.local_anchor_a = vec2(1, 0);
      REQUIRE(apply_command(cw, command).ok());
      tandem_command cc = tandem_default_command(TANDEM_COMMAND_CREATE_JOINT);
      cc.joint_spec.type = TANDEM_JOINT_REVOLUTE;
      cc.joint_spec.body_a_index = cb[4].index1 - 1, cc.joint_spec.body_a_generation = cb[4].generation;
      cc.joint_spec.body_b_index = cb[5].index1 - 1, cc.joint_spec.body_b_generation = cb[5].generation;
      cc.joint_spec.local_anchor_a = v2(1, 0);
      REQUIRE(tandem_apply_command(c.id, &cc, nullptr) == TANDEM_OK);
    }
    if (tick == 160) {  // set_joint_limits and set_joint_length commands on the rope (joint 1)
      Command limits;
      limits.type = CommandType::set_joint_limits;
      limits.joint = JointRef{1, 1};
      limits.scalar = Q32{};
      limits.scalar2 = Q32::from_ratio(5, 2);
      REQUIRE(apply_command(cw, limits).ok());
      tandem_command cl = tandem_default_command(TANDEM_COMMAND_SET_JOINT_LIMITS);
      cl.joint_index = 1, cl.joint_generation = 1, cl.scalar = 0, cl.scalar2 = qt("2.5");
      REQUIRE(tandem_apply_command(c.id, &cl, nullptr) == TANDEM_OK);
    }
    REQUIRE(world_step(cw, dt).ok());
    REQUIRE(tandem_world_step(c.id, dt.raw, nullptr) == TANDEM_OK);
    INFO("tick " << tick);
    REQUIRE(world_state_hash(cw) == tandem_world_state_hash(c.id));
    REQUIRE(joint_reaction_force(rev).x.raw == tandem_joint_reaction_force(crev).x);
  }
  CHECK(tandem_world_get_counters(c.id).joint_count == 8);
  tandem_command bad = tandem_default_command(TANDEM_COMMAND_CREATE_JOINT);
  bad.joint_spec.type = 9;
  require_error(tandem_apply_command(c.id, &bad, nullptr), TANDEM_ERROR_INVALID_ARGUMENT, "joint_spec.type");
  bad = tandem_default_command(13);
  require_error(tandem_apply_command(c.id, &bad, nullptr), TANDEM_ERROR_INVALID_ARGUMENT, "14…19");
  CHECK(destroy_world(cw).ok());
}
