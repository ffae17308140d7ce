// test_capi.cpp — the C API (tandem_c.h) through libtandem.so: every function
// is called here (capi/tests/check_coverage.py checks that), with its error
// paths — NULL pointers, null and stale handles, too-small buffers — each
// giving a status and a message naming the culprit, never a crash. The last
// cases drive the same worlds through the C API and the C++ API (the static
// modules linked into this test, a separate copy from the one inside the
// shared library) and compare the state hash after every tick: the C layer
// adds no arithmetic.
//
// The cases are split by area: test_capi.cpp (status, numbers, worlds, bodies,
// shapes, queries, events), test_capi_replay.cpp, test_capi_determinism.cpp,
// test_capi_joint.cpp, test_capi_session.cpp, test_capi_verify.cpp; shared
// helpers in capi_test_util.h.
#include "capi_test_util.h"

TEST_CASE("status names, version and the last error", "[capi]") {
  CHECK(std::string(tandem_status_name(TANDEM_OK)) == "ok");
  for (tandem_status s = 1; s <= TANDEM_ERROR_INTERNAL; ++s) CHECK(std::string(tandem_status_name(s)) != "unknown");
  CHECK(std::string(tandem_status_name(999)) == "unknown");
  CHECK(tandem_abi_version() == TANDEM_C_ABI_VERSION);
  CHECK(std::string(tandem_version_string()).find('.') != std::string::npos);
  // A failure sets the last error; a success clears it.
  require_error(tandem_world_check(tandem_world_id{}), TANDEM_ERROR_NULL_HANDLE, "world handle is null");
  CWorld w;
  REQUIRE(tandem_world_check(w.id) == TANDEM_OK);
  CHECK(tandem_last_error_code() == TANDEM_OK);
  CHECK(last_message().empty());
}

TEST_CASE("number conversions are exact and checked", "[capi]") {
  CHECK(qi(3) == int64_t{3} << 32);
  CHECK(qi(-1) == -(int64_t{1} << 32));
  tandem_q32 v = 0;
  REQUIRE(tandem_q32_from_ratio(1, 60, &v) == TANDEM_OK);
  CHECK(v == tandem::Q32::from_ratio(1, 60).raw);
  require_error(tandem_q32_from_ratio(1, 0, &v), TANDEM_ERROR_INVALID_ARGUMENT, "den is 0");
  require_error(tandem_q32_from_ratio(INT64_MAX, 1, &v), TANDEM_ERROR_INVALID_ARGUMENT, "outside");
  require_error(tandem_q32_from_ratio(1, 2, nullptr), TANDEM_ERROR_NULL_POINTER, "out_value");

  CHECK(tandem_q32_from_q16(int32_t{3} << 16) == qi(3));
  tandem_q16 h = 0;
  REQUIRE(tandem_q32_to_q16(qt("1.5"), &h) == TANDEM_OK);
  CHECK(h == 0x18000);
  REQUIRE(tandem_q32_to_q16(qt("-32767.99999"), &h) == TANDEM_OK);
  CHECK(h == tandem::to_q16(tandem::parse_q32("-32767.99999").value).raw);
  require_error(tandem_q32_to_q16(qi(40000), &h), TANDEM_ERROR_INVALID_ARGUMENT, "Q16.16 range");
  require_error(tandem_q32_to_q16(qi(1), nullptr), TANDEM_ERROR_NULL_POINTER, "out_value");

  CHECK(qt("0.1") == tandem::parse_q32("0.1").value.raw);
  CHECK(qt("-2.5e-3") == tandem::parse_q32("-2.5e-3").value.raw);
  require_error(tandem_q32_from_text("1.2x", &v), TANDEM_ERROR_PARSE, "1.2x");
  require_error(tandem_q32_from_text(nullptr, &v), TANDEM_ERROR_NULL_POINTER, "text");
  require_error(tandem_q32_from_text("1", nullptr), TANDEM_ERROR_NULL_POINTER, "out_value");

  size_t length = 0;
  REQUIRE(tandem_q32_to_text(qt("-1.5"), nullptr, 0, &length) == TANDEM_OK);
  CHECK(length == 4);
  char small[4];
  require_error(tandem_q32_to_text(qt("-1.5"), small, sizeof small, &length), TANDEM_ERROR_BUFFER_TOO_SMALL, "needs 5");
  char text[64];
  REQUIRE(tandem_q32_to_text(qt("-1.5"), text, sizeof text, &length) == TANDEM_OK);
  CHECK(std::string(text) == "-1.5");
  REQUIRE(tandem_q32_to_text(1, text, sizeof text, &length) == TANDEM_OK);
  CHECK(std::string(text) == tandem::to_string(tandem::Q32::from_raw(1)));
  require_error(tandem_q32_to_text(1, text, sizeof text, nullptr), TANDEM_ERROR_NULL_POINTER, "out_length");
  require_error(tandem_q32_to_text(1, nullptr, 8, &length), TANDEM_ERROR_NULL_POINTER, "out_text");
  CHECK(tandem_q32_to_double(qt("0.25")) == 0.25);

  const tandem_rot id = tandem_rot_identity();
  CHECK(id.c == qi(1));
  CHECK(id.s == 0);
  const tandem_rot r = tandem_rot_from_angle(qt("0.5"));
  const tandem::Rot cr = tandem::rot_from_angle(tandem::parse_q32("0.5").value);
  CHECK(r.c == cr.c.raw);
  CHECK(r.s == cr.s.raw);
  CHECK(tandem_rot_angle(r) == tandem::rot_angle(cr).raw);
  CHECK(tandem_vec2_length(v2(3, 4)) == qi(5));
  const tandem::Vec2 a{tandem::Q32::from_ratio(1, 3), tandem::Q32::from_int(2)}, b = tandem::vec2(-7, 5);
  CHECK(tandem_vec2_distance({a.x.raw, a.y.raw}, {b.x.raw, b.y.raw}) == tandem::distance(a, b).raw);
}

TEST_CASE("default definitions equal the C++ defaults", "[capi]") {
  const tandem_world_def w = tandem_default_world_def();
  const tandem::WorldDef cw = tandem::default_world_def();
  CHECK(w.gravity.y == cw.gravity.y.raw);
  CHECK(w.sub_step_count == cw.sub_step_count);
  CHECK(w.contact_hertz == cw.contact_hertz.raw);
  CHECK(w.max_linear_speed == cw.max_linear_speed.raw);
  CHECK(w.bounds.upper.x == cw.bounds.upper.x.raw);
  CHECK(w.internal_cookie == cw.internal_cookie);
  CHECK(w.enable_sleep);
  const tandem_body_def b = tandem_default_body_def();
  CHECK(b.type == TANDEM_BODY_STATIC);
  CHECK(b.gravity_scale == qi(1));
  CHECK(b.rotation.c == qi(1));
  CHECK(b.internal_cookie == tandem::default_body_def().internal_cookie);
  const tandem_shape_def s = tandem_default_shape_def();
  CHECK(s.friction == tandem::default_shape_def().friction.raw);
  CHECK(s.density == qi(1));
  const tandem_filter f = tandem_default_filter();
  CHECK(f.category_bits == 1);
  CHECK(f.mask_bits == UINT64_MAX);
  const tandem_query_filter qf = tandem_default_query_filter();
  CHECK(qf.mask_bits == UINT64_MAX);
  CHECK(!qf.include_sensors);
  const tandem_command c = tandem_default_command(TANDEM_COMMAND_SET_GRAVITY);
  CHECK(c.type == TANDEM_COMMAND_SET_GRAVITY);
  CHECK(c.at_center);
  CHECK(c.flag);
  const tandem_shape_spec spec = tandem_default_shape_spec(TANDEM_SHAPE_KIND_CIRCLE);
  CHECK(spec.def.internal_cookie == s.internal_cookie);
  const tandem_recorder_options ro = tandem_default_recorder_options();
  CHECK(ro.keyframe_interval == 600);
  CHECK(ro.time_step == tandem::Q32::from_ratio(1, 60).raw);
  const tandem_synctest_options so = tandem_default_synctest_options();
  CHECK(so.rollback == 8);
}

TEST_CASE("worlds: create, settings, stale handles", "[capi]") {
  tandem_world_def def = tandem_default_world_def();
  tandem_world_id world{};
  require_error(tandem_create_world(nullptr, &world), TANDEM_ERROR_NULL_POINTER, "def");
  require_error(tandem_create_world(&def, nullptr), TANDEM_ERROR_NULL_POINTER, "out_world");
  tandem_world_def zero;
  std::memset(&zero, 0, sizeof zero);
  require_error(tandem_create_world(&zero, &world), TANDEM_ERROR_INVALID_DEFINITION, "default_world_def");
  def.sub_step_count = 0;
  require_error(tandem_create_world(&def, &world), TANDEM_ERROR_INVALID_ARGUMENT, "sub_step_count");

  def = tandem_default_world_def();
  def.user_data = 42;
  def.broad_phase = TANDEM_BROAD_PHASE_TREE;
  REQUIRE(tandem_create_world(&def, &world) == TANDEM_OK);
  CHECK(tandem_world_is_valid(world));
  CHECK(!tandem_world_is_locked(world));
  CHECK(tandem_world_user_data(world) == 42);
  CHECK(tandem_world_broad_phase(world) == TANDEM_BROAD_PHASE_TREE);
  REQUIRE(tandem_world_set_broad_phase(world, TANDEM_BROAD_PHASE_GRID) == TANDEM_OK);
  CHECK(tandem_world_broad_phase(world) == TANDEM_BROAD_PHASE_GRID);
  require_error(tandem_world_set_broad_phase(world, 9), TANDEM_ERROR_INVALID_ARGUMENT, "broad");
  REQUIRE(tandem_world_set_gravity(world, v2(0, -5)) == TANDEM_OK);
  CHECK(tandem_world_gravity(world).y == qi(-5));
  require_error(tandem_world_set_gravity(world, v2(0, 20000)), TANDEM_ERROR_INVALID_ARGUMENT, "gravity");
  REQUIRE(tandem_world_set_sub_step_count(world, 8) == TANDEM_OK);
  REQUIRE(tandem_world_set_contact_tuning(world, qi(25), qi(5), qi(2)) == TANDEM_OK);
  REQUIRE(tandem_world_set_joint_tuning(world, qi(50), qi(1)) == TANDEM_OK);
  REQUIRE(tandem_world_set_restitution_threshold(world, qi(2)) == TANDEM_OK);
  REQUIRE(tandem_world_set_hit_event_threshold(world, qi(3)) == TANDEM_OK);
  REQUIRE(tandem_world_set_max_linear_speed(world, qi(300)) == TANDEM_OK);
  REQUIRE(tandem_world_enable_sleep(world, false) == TANDEM_OK);
  REQUIRE(tandem_world_enable_continuous(world, false) == TANDEM_OK);
  REQUIRE(tandem_world_set_user_data(world, 7) == TANDEM_OK);
  const tandem_world_def got = tandem_world_get_def(world);
  CHECK(got.sub_step_count == 8);
  CHECK(got.contact_hertz == qi(25));
  CHECK(got.joint_hertz == qi(50));
  CHECK(got.restitution_threshold == qi(2));
  CHECK(got.hit_event_threshold == qi(3));
  CHECK(got.max_linear_speed == qi(300));
  CHECK(!got.enable_sleep);
  CHECK(!got.enable_continuous);
  CHECK(got.user_data == 7);
  CHECK(got.internal_cookie == def.internal_cookie);
  // A copy of a world's settings makes a world.
  tandem_world_id copy{};
  REQUIRE(tandem_create_world(&got, &copy) == TANDEM_OK);
  REQUIRE(tandem_destroy_world(copy) == TANDEM_OK);

  add_ground(world);
  add_box(world, TANDEM_BODY_DYNAMIC, v2(0, 1), qi(1));  // resting on the ground: one pair
  uint32_t flags = 99;
  REQUIRE(tandem_world_step(world, qt("0.0166"), &flags) == TANDEM_OK);
  CHECK(flags == 0);
  require_error(tandem_world_step(world, qi(2), nullptr), TANDEM_ERROR_INVALID_ARGUMENT, "time_step");
  const tandem_world_counters counters = tandem_world_get_counters(world);
  CHECK(counters.body_count == 2);
  CHECK(counters.shape_count == 2);
  CHECK(counters.step_count == 1);
  const tandem_broad_phase_stats stats = tandem_world_broad_phase_stats(world);
  CHECK(stats.proxies == 2);
  CHECK(stats.pairs == 1);

  int32_t count = -1;
  REQUIRE(tandem_world_bodies(world, nullptr, 0, &count) == TANDEM_OK);
  CHECK(count == 2);
  tandem_body_id one[1];
  require_error(tandem_world_bodies(world, one, 1, &count), TANDEM_ERROR_BUFFER_TOO_SMALL, "result has 2");
  tandem_body_id bodies[4];
  REQUIRE(tandem_world_bodies(world, bodies, 4, &count) == TANDEM_OK);
  CHECK(bodies[1].index1 == 2);
  require_error(tandem_world_bodies(world, bodies, 4, nullptr), TANDEM_ERROR_NULL_POINTER, "out_count");
  require_error(tandem_world_bodies(world, nullptr, 4, &count), TANDEM_ERROR_NULL_POINTER, "buffer");
  require_error(tandem_world_bodies(world, bodies, -1, &count), TANDEM_ERROR_INVALID_ARGUMENT, "negative");

  // Stale: every entry point refuses or returns its default.
  REQUIRE(tandem_destroy_world(world) == TANDEM_OK);
  CHECK(!tandem_world_is_valid(world));
  require_error(tandem_world_check(world), TANDEM_ERROR_INVALID_HANDLE, "world");
  require_error(tandem_destroy_world(world), TANDEM_ERROR_INVALID_HANDLE, "world");
  require_error(tandem_world_step(world, qt("0.01"), nullptr), TANDEM_ERROR_INVALID_HANDLE, "world");
  require_error(tandem_world_set_gravity(world, v2(0, 0)), TANDEM_ERROR_INVALID_HANDLE, "world");
  require_error(tandem_world_bodies(world, bodies, 4, &count), TANDEM_ERROR_INVALID_HANDLE, "world");
  require_error(tandem_world_set_custom_filter(world, nullptr, nullptr), TANDEM_ERROR_INVALID_HANDLE, "world");
  CHECK(tandem_world_gravity(world).y == 0);
  CHECK(tandem_world_user_data(world) == 0);
  CHECK(tandem_world_get_counters(world).body_count == 0);
  CHECK(tandem_world_state_hash(world) == 0);
  CHECK(tandem_world_snapshot_size(world) == 0);
  CHECK(tandem_world_get_def(world).sub_step_count == tandem_default_world_def().sub_step_count);
  // A forged handle (never valid) is refused too.
  require_error(tandem_world_check(tandem_world_id{100, 77}), TANDEM_ERROR_INVALID_HANDLE, "world");
}

TEST_CASE("bodies: every getter and setter", "[capi]") {
  CWorld w;
  tandem_body_def def = tandem_default_body_def();
  tandem_body_id body{};
  require_error(tandem_create_body(w.id, nullptr, &body), TANDEM_ERROR_NULL_POINTER, "def");
  require_error(tandem_create_body(w.id, &def, nullptr), TANDEM_ERROR_NULL_POINTER, "out_body");
  def.type = 7;
  require_error(tandem_create_body(w.id, &def, &body), TANDEM_ERROR_INVALID_ARGUMENT, "not a body type");
  def = tandem_default_body_def();
  def.type = TANDEM_BODY_DYNAMIC;
  def.position = v2(1, 2);
  def.user_data = 5;
  REQUIRE(tandem_create_body(w.id, &def, &body) == TANDEM_OK);
  tandem_polygon box;
  REQUIRE(tandem_make_box(qi(1), qi(1), &box) == TANDEM_OK);
  const tandem_shape_def sd = tandem_default_shape_def();
  tandem_shape_id shape{};
  REQUIRE(tandem_create_polygon_shape(body, &sd, &box, &shape) == TANDEM_OK);

  CHECK(tandem_body_is_valid(body));
  REQUIRE(tandem_body_check(body, w.id) == TANDEM_OK);
  REQUIRE(tandem_body_check(body, tandem_world_id{}) == TANDEM_OK);
  CHECK(tandem_body_world(body).index1 == w.id.index1);
  CHECK(tandem_body_type(body) == TANDEM_BODY_DYNAMIC);
  CHECK(tandem_body_position(body).x == qi(1));
  CHECK(tandem_body_rotation(body).c == qi(1));
  CHECK(tandem_body_angle(body) == 0);
  CHECK(tandem_body_transform(body).p.y == qi(2));
  CHECK(tandem_body_world_center(body).y == qi(2));
  CHECK(tandem_body_local_center(body).x == 0);
  CHECK(tandem_body_mass(body) == qi(4));  // 2 m × 2 m × 1 kg/m²
  CHECK(tandem_body_rotational_inertia(body) > 0);
  CHECK(tandem_body_mass_data(body).mass == qi(4));
  CHECK(tandem_body_user_data(body) == 5);

  REQUIRE(tandem_body_set_transform(body, v2(3, 4), tandem_rot_from_angle(qt("0.25"))) == TANDEM_OK);
  CHECK(tandem_body_position(body).x == qi(3));
  CHECK(tandem_body_world_point(body, v2(0, 0)).y == qi(4));
  CHECK(tandem_body_local_point(body, v2(3, 4)).x == 0);
  const tandem_vec2 wv = tandem_body_world_vector(body, v2(1, 0));
  CHECK(wv.x == tandem_body_rotation(body).c);
  CHECK(tandem_body_local_vector(body, wv).x > qt("0.9999"));
  REQUIRE(tandem_body_set_linear_velocity(body, v2(1, 0)) == TANDEM_OK);
  CHECK(tandem_body_linear_velocity(body).x == qi(1));
  REQUIRE(tandem_body_set_angular_velocity(body, qi(2)) == TANDEM_OK);
  CHECK(tandem_body_angular_velocity(body) == qi(2));
  CHECK(tandem_body_point_velocity(body, tandem_body_world_center(body)).x == qi(1));
  REQUIRE(tandem_body_apply_force(body, v2(1, 0), v2(3, 4), true) == TANDEM_OK);
  REQUIRE(tandem_body_apply_force_to_center(body, v2(1, 0), true) == TANDEM_OK);
  REQUIRE(tandem_body_apply_torque(body, qi(1), true) == TANDEM_OK);
  REQUIRE(tandem_body_apply_linear_impulse(body, v2(4, 0), v2(3, 4), true) == TANDEM_OK);
  CHECK(tandem_body_linear_velocity(body).x == qi(2));  // + 4 N·s / 4 kg
  REQUIRE(tandem_body_apply_linear_impulse_to_center(body, v2(-4, 0), true) == TANDEM_OK);
  REQUIRE(tandem_body_apply_angular_impulse(body, qt("0.1"), true) == TANDEM_OK);
  require_error(tandem_body_apply_force(body, v2(1, 0), v2(2000000000, 0), true), TANDEM_ERROR_INVALID_ARGUMENT, "");
  REQUIRE(tandem_body_set_linear_damping(body, qi(1)) == TANDEM_OK);
  CHECK(tandem_body_linear_damping(body) == qi(1));
  REQUIRE(tandem_body_set_angular_damping(body, qi(2)) == TANDEM_OK);
  CHECK(tandem_body_angular_damping(body) == qi(2));
  require_error(tandem_body_set_angular_damping(body, qi(-1)), TANDEM_ERROR_INVALID_ARGUMENT, "damping");
  REQUIRE(tandem_body_set_gravity_scale(body, qi(3)) == TANDEM_OK);
  CHECK(tandem_body_gravity_scale(body) == qi(3));
  REQUIRE(tandem_body_set_fixed_rotation(body, true) == TANDEM_OK);
  CHECK(tandem_body_is_fixed_rotation(body));
  REQUIRE(tandem_body_set_bullet(body, true) == TANDEM_OK);
  CHECK(tandem_body_is_bullet(body));
  REQUIRE(tandem_body_enable_sleep(body, false) == TANDEM_OK);
  CHECK(!tandem_body_is_sleep_enabled(body));
  REQUIRE(tandem_body_enable_sleep(body, true) == TANDEM_OK);
  REQUIRE(tandem_body_set_awake(body, false) == TANDEM_OK);
  CHECK(!tandem_body_is_awake(body));
  REQUIRE(tandem_body_set_awake(body, true) == TANDEM_OK);
  CHECK(tandem_body_is_awake(body));
  REQUIRE(tandem_body_set_enabled(body, false) == TANDEM_OK);
  CHECK(!tandem_body_is_enabled(body));
  REQUIRE(tandem_body_set_enabled(body, true) == TANDEM_OK);
  CHECK(tandem_body_is_enabled(body));
  // The names deprecated in this release still work (README "Naming and deprecations").
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wdeprecated-declarations"
  REQUIRE(tandem_body_disable(body) == TANDEM_OK);
  CHECK(!tandem_body_is_enabled(body));
  REQUIRE(tandem_body_enable(body) == TANDEM_OK);
  CHECK(tandem_body_is_enabled(body));
  CHECK(tandem_world_get_broad_phase(w.id) == tandem_world_broad_phase(w.id));
  CHECK(tandem_world_get_broad_phase_stats(w.id).pairs == tandem_world_broad_phase_stats(w.id).pairs);
#pragma GCC diagnostic pop
  REQUIRE(tandem_body_set_user_data(body, 9) == TANDEM_OK);
  CHECK(tandem_body_user_data(body) == 9);
  REQUIRE(tandem_body_set_type(body, TANDEM_BODY_KINEMATIC) == TANDEM_OK);
  CHECK(tandem_body_type(body) == TANDEM_BODY_KINEMATIC);
  require_error(tandem_body_set_type(body, 5), TANDEM_ERROR_INVALID_ARGUMENT, "not a body type");

  CHECK(tandem_body_shape_count(body) == 1);
  int32_t count = 0;
  REQUIRE(tandem_body_shapes(body, nullptr, 0, &count) == TANDEM_OK);
  CHECK(count == 1);
  tandem_shape_id shapes[2];
  REQUIRE(tandem_body_shapes(body, shapes, 2, &count) == TANDEM_OK);
  CHECK(shapes[0].index1 == shape.index1);

  // A handle of another world where one world is expected.
  CWorld other;
  require_error(tandem_body_check(body, other.id), TANDEM_ERROR_FOREIGN_HANDLE, "");
  // Null and stale bodies.
  require_error(tandem_body_check(tandem_body_id{}, tandem_world_id{}), TANDEM_ERROR_NULL_HANDLE, "body handle is null");
  require_error(tandem_body_set_linear_velocity(tandem_body_id{}, v2(0, 0)), TANDEM_ERROR_NULL_HANDLE, "body handle is null");
  REQUIRE(tandem_destroy_body(body) == TANDEM_OK);
  CHECK(!tandem_body_is_valid(body));
  require_error(tandem_destroy_body(body), TANDEM_ERROR_INVALID_HANDLE, "body");
  require_error(tandem_body_set_awake(body, true), TANDEM_ERROR_INVALID_HANDLE, "body");
  require_error(tandem_body_shapes(body, shapes, 2, &count), TANDEM_ERROR_INVALID_HANDLE, "body");
  CHECK(tandem_body_position(body).x == 0);
  CHECK(tandem_body_mass(body) == 0);
  CHECK(tandem_body_shape_count(body) == 0);
  CHECK(tandem_body_state_hash(body) == 0);
  CHECK(tandem_body_rotation(body).c == qi(1));
}

TEST_CASE("shapes: every kind, chains, materials, stale handles", "[capi]") {
  CWorld w;
  const tandem_body_id body = add_box(w.id, TANDEM_BODY_DYNAMIC, v2(0, 5), qt("0.5"));
  tandem_body_def gdef = tandem_default_body_def();
  tandem_body_id ground{};
  REQUIRE(tandem_create_body(w.id, &gdef, &ground) == TANDEM_OK);
  tandem_shape_def sd = tandem_default_shape_def();
  tandem_shape_id s{};

  const tandem_circle circle = {v2(1, 0), qt("0.25")};
  require_error(tandem_create_circle_shape(body, nullptr, &circle, &s), TANDEM_ERROR_NULL_POINTER, "def");
  require_error(tandem_create_circle_shape(body, &sd, nullptr, &s), TANDEM_ERROR_NULL_POINTER, "geometry");
  require_error(tandem_create_circle_shape(body, &sd, &circle, nullptr), TANDEM_ERROR_NULL_POINTER, "out_shape");
  const tandem_circle bad = {v2(0, 0), 0};
  require_error(tandem_create_circle_shape(body, &sd, &bad, &s), TANDEM_ERROR_INVALID_ARGUMENT, "radius");
  REQUIRE(tandem_create_circle_shape(body, &sd, &circle, &s) == TANDEM_OK);
  CHECK(tandem_shape_type(s) == TANDEM_SHAPE_CIRCLE);
  const tandem_shape_geometry g = tandem_shape_geometry_of(s);
  CHECK(g.type == TANDEM_SHAPE_CIRCLE);
  CHECK(g.circle.radius == qt("0.25"));
  CHECK(tandem_shape_mass_data(s).mass > 0);

  const tandem_capsule capsule = {v2(-1, 0), v2(-1, 1), qt("0.2")};
  REQUIRE(tandem_create_capsule_shape(body, &sd, &capsule, &s) == TANDEM_OK);
  CHECK(tandem_shape_type(s) == TANDEM_SHAPE_CAPSULE);
  const tandem_segment segment = {v2(-5, 0), v2(5, 0)};
  REQUIRE(tandem_create_segment_shape(ground, &sd, &segment, &s) == TANDEM_OK);
  CHECK(tandem_shape_geometry_of(s).segment.point2.x == qi(5));
  const tandem_vec2 points[] = {v2(0, 0), v2(1, 0), v2(0, 1), v2(1, 1), v2(0, 0)};
  tandem_polygon hull;
  REQUIRE(tandem_make_polygon(points, 5, 0, &hull) == TANDEM_OK);
  CHECK(hull.count == 4);
  require_error(tandem_make_polygon(points, 2, 0, &hull), TANDEM_ERROR_INVALID_ARGUMENT, "");
  require_error(tandem_make_polygon(nullptr, 3, 0, &hull), TANDEM_ERROR_NULL_POINTER, "points");
  require_error(tandem_make_polygon(points, 3, 0, nullptr), TANDEM_ERROR_NULL_POINTER, "out_polygon");
  require_error(tandem_make_box(0, qi(1), &hull), TANDEM_ERROR_INVALID_ARGUMENT, "");
  require_error(tandem_make_box(qi(1), qi(1), nullptr), TANDEM_ERROR_NULL_POINTER, "out_polygon");
  require_error(tandem_make_offset_box(qi(1), qi(1), v2(0, 0), 0, 0, nullptr), TANDEM_ERROR_NULL_POINTER, "out_polygon");
  tandem_polygon corrupt = hull;
  corrupt.count = 40;
  require_error(tandem_create_polygon_shape(ground, &sd, &corrupt, &s), TANDEM_ERROR_INVALID_ARGUMENT, "");

  // Chains: the buffer is checked before anything is created.
  const tandem_vec2 chain[] = {v2(-8, 2), v2(-6, 0), v2(0, -1), v2(6, 0), v2(8, 2)};
  int32_t count = 0;
  tandem_shape_id one[1];
  const int32_t shapes_before = tandem_world_get_counters(w.id).shape_count;
  require_error(tandem_create_chain_shapes(ground, &sd, chain, 5, false, one, 1, &count), TANDEM_ERROR_BUFFER_TOO_SMALL,
                "nothing was created");
  CHECK(count == 2);
  CHECK(tandem_world_get_counters(w.id).shape_count == shapes_before);
  tandem_shape_id links[8];
  REQUIRE(tandem_create_chain_shapes(ground, &sd, chain, 5, false, links, 8, &count) == TANDEM_OK);
  CHECK(count == 2);
  CHECK(tandem_shape_type(links[0]) == TANDEM_SHAPE_CHAIN_SEGMENT);
  CHECK(tandem_shape_geometry_of(links[1]).chain_segment.chain_id == static_cast<int32_t>(links[0].index1 - 1));
  REQUIRE(tandem_create_chain_shapes(ground, &sd, chain, 4, true, nullptr, 0, &count) == TANDEM_OK);
  CHECK(count == 4);
  require_error(tandem_create_chain_shapes(ground, &sd, chain, 2, false, links, 8, &count), TANDEM_ERROR_INVALID_ARGUMENT,
                "");
  require_error(tandem_create_chain_shapes(ground, &sd, nullptr, 4, false, links, 8, &count), TANDEM_ERROR_NULL_POINTER,
                "points");
  require_error(tandem_create_chain_shapes(ground, &sd, chain, 4, false, links, 8, nullptr), TANDEM_ERROR_NULL_POINTER,
                "out_count");

  REQUIRE(tandem_shape_is_valid(s));
  REQUIRE(tandem_shape_check(s, w.id) == TANDEM_OK);
  CHECK(tandem_shape_body(s).index1 == ground.index1);
  REQUIRE(tandem_shape_set_friction(s, qi(1)) == TANDEM_OK);
  CHECK(tandem_shape_friction(s) == qi(1));
  require_error(tandem_shape_set_friction(s, qi(-1)), TANDEM_ERROR_INVALID_ARGUMENT, "friction");
  REQUIRE(tandem_shape_set_restitution(s, qt("0.5")) == TANDEM_OK);
  CHECK(tandem_shape_restitution(s) == qt("0.5"));
  REQUIRE(tandem_shape_set_density(s, qi(2)) == TANDEM_OK);
  CHECK(tandem_shape_density(s) == qi(2));
  CHECK(!tandem_shape_is_sensor(s));
  tandem_filter f = tandem_default_filter();
  f.group_index = -3;
  REQUIRE(tandem_shape_set_filter(s, f) == TANDEM_OK);
  CHECK(tandem_shape_filter(s).group_index == -3);
  REQUIRE(tandem_shape_set_user_data(s, 11) == TANDEM_OK);
  CHECK(tandem_shape_user_data(s) == 11);
  REQUIRE(tandem_world_step(w.id, qt("0.01"), nullptr) == TANDEM_OK);
  const tandem_aabb box = tandem_shape_aabb(s);
  CHECK(box.lower.x == qi(-5));

  REQUIRE(tandem_destroy_shape(s) == TANDEM_OK);
  CHECK(!tandem_shape_is_valid(s));
  require_error(tandem_shape_check(s, tandem_world_id{}), TANDEM_ERROR_INVALID_HANDLE, "shape");
  require_error(tandem_destroy_shape(s), TANDEM_ERROR_INVALID_HANDLE, "shape");
  require_error(tandem_shape_set_friction(s, qi(1)), TANDEM_ERROR_INVALID_HANDLE, "shape");
  require_error(tandem_shape_set_filter(tandem_shape_id{}, f), TANDEM_ERROR_NULL_HANDLE, "shape handle is null");
  CHECK(tandem_shape_body(s).index1 == 0);
  CHECK(tandem_shape_friction(s) == 0);
  CHECK(tandem_shape_filter(s).category_bits == 1);
}

TEST_CASE("queries and events", "[capi]") {
  CWorld w;
  add_ground(w.id);
  const tandem_body_id box = add_box(w.id, TANDEM_BODY_DYNAMIC, v2(0, 1), qt("0.5"));
  tandem_body_def sdef = tandem_default_body_def();
  sdef.position = v2(5, 3);
  tandem_body_id sensor_body{};
  REQUIRE(tandem_create_body(w.id, &sdef, &sensor_body) == TANDEM_OK);
  tandem_shape_def sensor_def = tandem_default_shape_def();
  sensor_def.is_sensor = true;
  const tandem_circle sensor_circle = {v2(0, 0), qi(1)};
  tandem_shape_id sensor{};
  REQUIRE(tandem_create_circle_shape(sensor_body, &sensor_def, &sensor_circle, &sensor) == TANDEM_OK);
  tandem_body_def bdef = tandem_default_body_def();
  bdef.type = TANDEM_BODY_DYNAMIC;
  bdef.position = v2(5, 6);
  bdef.linear_velocity = v2(0, -8);
  tandem_body_id ball{};
  REQUIRE(tandem_create_body(w.id, &bdef, &ball) == TANDEM_OK);
  tandem_shape_def ball_def = tandem_default_shape_def();
  ball_def.enable_hit_events = true;
  const tandem_circle ball_circle = {v2(0, 0), qt("0.25")};
  tandem_shape_id ball_shape{};
  REQUIRE(tandem_create_circle_shape(ball, &ball_def, &ball_circle, &ball_shape) == TANDEM_OK);

  tandem_ray_hit hit;
  REQUIRE(tandem_world_cast_ray_closest(w.id, v2(0, 5), v2(0, -10), nullptr, &hit) == TANDEM_OK);
  CHECK(hit.hit);
  CHECK(std::llabs(hit.point.y - (qi(1) + qt("0.5"))) < 16);  // the box top, to a few raw units
  require_error(tandem_world_cast_ray_closest(w.id, v2(0, 5), v2(0, -10), nullptr, nullptr), TANDEM_ERROR_NULL_POINTER,
                "out_hit");
  int32_t count = 0;
  REQUIRE(tandem_world_cast_ray_all(w.id, v2(0, 5), v2(0, -10), nullptr, nullptr, 0, &count) == TANDEM_OK);
  CHECK(count == 2);  // the box, then the ground
  tandem_ray_hit hits[2];
  tandem_query_filter qf = tandem_default_query_filter();
  REQUIRE(tandem_world_cast_ray_all(w.id, v2(0, 5), v2(0, -10), &qf, hits, 2, &count) == TANDEM_OK);
  CHECK(hits[0].fraction < hits[1].fraction);
  require_error(tandem_world_cast_ray_all(w.id, v2(0, 5), v2(0, -10), &qf, hits, 1, &count),
                TANDEM_ERROR_BUFFER_TOO_SMALL, "result has 2");
  tandem_shape_id found[8];
  const tandem_aabb box_query = {v2(-1, 0), v2(1, 2)};
  REQUIRE(tandem_world_overlap_aabb(w.id, box_query, &qf, found, 8, &count) == TANDEM_OK);
  CHECK(count == 2);
  REQUIRE(tandem_world_overlap_point(w.id, v2(0, 1), &qf, found, 8, &count) == TANDEM_OK);
  CHECK(count == 1);
  qf.include_sensors = true;
  REQUIRE(tandem_world_overlap_point(w.id, v2(5, 3), &qf, found, 8, &count) == TANDEM_OK);
  CHECK(count == 1);
  CHECK(found[0].index1 == sensor.index1);
  const tandem_transform at = {v2(0, 1), tandem_rot_identity()};
  REQUIRE(tandem_world_overlap_circle(w.id, &ball_circle, at, nullptr, found, 8, &count) == TANDEM_OK);
  CHECK(count == 1);
  const tandem_capsule cap = {v2(-1, 0), v2(1, 0), qt("0.1")};
  REQUIRE(tandem_world_overlap_capsule(w.id, &cap, at, nullptr, found, 8, &count) == TANDEM_OK);
  CHECK(count == 1);
  tandem_polygon poly;
  REQUIRE(tandem_make_box(qi(10), qi(1), &poly) == TANDEM_OK);
  REQUIRE(tandem_world_overlap_polygon(w.id, &poly, at, nullptr, found, 8, &count) == TANDEM_OK);
  CHECK(count == 2);
  require_error(tandem_world_overlap_polygon(w.id, nullptr, at, nullptr, found, 8, &count), TANDEM_ERROR_NULL_POINTER,
                "polygon");
  require_error(tandem_world_overlap_circle(w.id, nullptr, at, nullptr, found, 8, &count), TANDEM_ERROR_NULL_POINTER,
                "circle");
  require_error(tandem_world_overlap_capsule(w.id, nullptr, at, nullptr, found, 8, &count), TANDEM_ERROR_NULL_POINTER,
                "capsule");
  require_error(tandem_world_overlap_aabb(w.id, box_query, &qf, found, 8, nullptr), TANDEM_ERROR_NULL_POINTER,
                "out_count");
  const tandem_aabb inverted = {v2(1, 1), v2(0, 0)};
  require_error(tandem_world_overlap_aabb(w.id, inverted, &qf, found, 8, &count), TANDEM_ERROR_INVALID_ARGUMENT, "");

  // Step until the ball has passed through the sensor and hit the ground.
  int begins = 0, ends = 0, hits_seen = 0, sensor_begins = 0, sensor_ends = 0, moves = 0;
  for (int tick = 0; tick < 120; ++tick) {
    REQUIRE(tandem_world_step(w.id, qt("0.0166"), nullptr) == TANDEM_OK);
    tandem_contact_begin_event b[16];
    tandem_contact_end_event e[16];
    tandem_contact_hit_event h[16];
    tandem_sensor_event sb[16], se[16];
    tandem_body_move_event m[16];
    REQUIRE(tandem_world_contact_begin_events(w.id, b, 16, &count) == TANDEM_OK);
    for (int i = 0; i < count; ++i) CHECK(b[i].manifold.point_count > 0);
    begins += count;
    REQUIRE(tandem_world_contact_end_events(w.id, e, 16, &count) == TANDEM_OK);
    ends += count;
    REQUIRE(tandem_world_contact_hit_events(w.id, h, 16, &count) == TANDEM_OK);
    for (int i = 0; i < count; ++i) CHECK(h[i].approach_speed > qi(1));
    hits_seen += count;
    REQUIRE(tandem_world_sensor_begin_events(w.id, sb, 16, &count) == TANDEM_OK);
    for (int i = 0; i < count; ++i) CHECK(sb[i].sensor.index1 == sensor.index1);
    sensor_begins += count;
    REQUIRE(tandem_world_sensor_end_events(w.id, se, 16, &count) == TANDEM_OK);
    sensor_ends += count;
    REQUIRE(tandem_world_body_move_events(w.id, m, 16, &count) == TANDEM_OK);
    moves += count;
    if (tick == 0) {
      int32_t n = 0;
      tandem_body_move_event tiny[1];
      REQUIRE(tandem_world_body_move_events(w.id, nullptr, 0, &n) == TANDEM_OK);
      CHECK(n == 2);
      require_error(tandem_world_body_move_events(w.id, tiny, 1, &n), TANDEM_ERROR_BUFFER_TOO_SMALL, "result has 2");
    }
  }
  CHECK(begins >= 2);
  CHECK(hits_seen >= 1);
  CHECK(sensor_begins == 1);
  CHECK(sensor_ends == 1);
  CHECK(moves > 0);
  (void)ends;
  (void)box;

  // Destroyed world: queries and events refuse.
  tandem_world_id dead = w.id;
  REQUIRE(tandem_destroy_world(dead) == TANDEM_OK);
  require_error(tandem_world_contact_begin_events(dead, nullptr, 0, &count), TANDEM_ERROR_INVALID_HANDLE, "world");
  require_error(tandem_world_contact_end_events(dead, nullptr, 0, &count), TANDEM_ERROR_INVALID_HANDLE, "world");
  require_error(tandem_world_contact_hit_events(dead, nullptr, 0, &count), TANDEM_ERROR_INVALID_HANDLE, "world");
  require_error(tandem_world_sensor_begin_events(dead, nullptr, 0, &count), TANDEM_ERROR_INVALID_HANDLE, "world");
  require_error(tandem_world_sensor_end_events(dead, nullptr, 0, &count), TANDEM_ERROR_INVALID_HANDLE, "world");
  require_error(tandem_world_cast_ray_all(dead, v2(0, 0), v2(1, 0), nullptr, nullptr, 0, &count),
                TANDEM_ERROR_INVALID_HANDLE, "world");
  require_error(tandem_world_overlap_point(dead, v2(0, 0), nullptr, nullptr, 0, &count), TANDEM_ERROR_INVALID_HANDLE,
                "world");
}

namespace {
int g_filter_calls = 0;
bool keep_apart(tandem_shape_id, tandem_shape_id, void* context) {
  ++g_filter_calls;
  return *static_cast<bool*>(context);
}
}  // namespace

TEST_CASE("a custom filter from C decides contacts", "[capi]") {
  CWorld w;
  add_ground(w.id);
  const tandem_body_id box = add_box(w.id, TANDEM_BODY_DYNAMIC, v2(0, 1), qt("0.5"));
  bool allow = false;
  REQUIRE(tandem_world_set_custom_filter(w.id, &keep_apart, &allow) == TANDEM_OK);
  for (int i = 0; i < 60; ++i) REQUIRE(tandem_world_step(w.id, qt("0.0166"), nullptr) == TANDEM_OK);
  CHECK(g_filter_calls > 0);
  CHECK(tandem_body_position(box).y < 0);  // fell through the ground
  REQUIRE(tandem_world_set_custom_filter(w.id, nullptr, nullptr) == TANDEM_OK);
}

