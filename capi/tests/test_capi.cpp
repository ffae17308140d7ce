// test_capi.cpp — the C API (tandem_c.h) through libtandem.so: every function
// is called here (capi/tests/check_coverage.py checks that), with its error
// paths — NULL pointers, null and stale handles, too-small buffers — each
// giving a status and a message naming the culprit, never a crash. The last
// cases drive the same worlds through the C API and the C++ API (the static
// modules linked into this test, a separate copy from the one inside the
// shared library) and compare the state hash after every tick: the C layer
// adds no arithmetic.
#include <catch2/catch.hpp>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "physics/tandem.h"
#include "replay/state.h"
#include "scene/scene.h"
#include "tandem_c.h"

#ifndef TANDEM_SOURCE_DIR
#define TANDEM_SOURCE_DIR "."
#endif

namespace {

tandem_q32 qi(int32_t v) { return tandem_q32_from_int(v); }
tandem_q32 qt(const char* text) {
  tandem_q32 v = 0;
  REQUIRE(tandem_q32_from_text(text, &v) == TANDEM_OK);
  return v;
}
tandem_vec2 v2(int32_t x, int32_t y) { return {qi(x), qi(y)}; }
std::string last_message() { return tandem_last_error_message(); }

// The last error is `code` and its message contains `part`.
void require_error(tandem_status got, tandem_status code, const std::string& part) {
  INFO("message: " << last_message());
  REQUIRE(got == code);
  REQUIRE(tandem_last_error_code() == code);
  REQUIRE(last_message().find(part) != std::string::npos);
}

struct CWorld {
  tandem_world_id id{};
  CWorld() {
    const tandem_world_def def = tandem_default_world_def();
    REQUIRE(tandem_create_world(&def, &id) == TANDEM_OK);
  }
  ~CWorld() {
    if (tandem_world_is_valid(id)) tandem_destroy_world(id);
  }
};

tandem_body_id add_box(tandem_world_id world, int32_t type, tandem_vec2 position, tandem_q32 half) {
  tandem_body_def def = tandem_default_body_def();
  def.type = type;
  def.position = position;
  tandem_body_id body{};
  REQUIRE(tandem_create_body(world, &def, &body) == TANDEM_OK);
  tandem_polygon box;
  REQUIRE(tandem_make_box(half, half, &box) == TANDEM_OK);
  const tandem_shape_def sd = tandem_default_shape_def();
  tandem_shape_id shape{};
  REQUIRE(tandem_create_polygon_shape(body, &sd, &box, &shape) == TANDEM_OK);
  return body;
}

tandem_body_id add_ground(tandem_world_id world) {
  tandem_body_def def = tandem_default_body_def();
  tandem_body_id body{};
  REQUIRE(tandem_create_body(world, &def, &body) == TANDEM_OK);
  tandem_polygon box;
  REQUIRE(tandem_make_offset_box(qi(20), qi(1), v2(0, -1), 0, 0, &box) == TANDEM_OK);
  const tandem_shape_def sd = tandem_default_shape_def();
  tandem_shape_id shape{};
  REQUIRE(tandem_create_polygon_shape(body, &sd, &box, &shape) == TANDEM_OK);
  return body;
}

std::vector<uint8_t> snapshot(tandem_world_id world) {
  size_t size = 0;
  REQUIRE(tandem_world_snapshot(world, nullptr, 0, &size) == TANDEM_OK);
  REQUIRE(size == tandem_world_snapshot_size(world));
  std::vector<uint8_t> bytes(size);
  REQUIRE(tandem_world_snapshot(world, bytes.data(), bytes.size(), &size) == TANDEM_OK);
  REQUIRE(size == bytes.size());
  return bytes;
}

}  // namespace

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
  CHECK(tandem_world_get_broad_phase(world) == TANDEM_BROAD_PHASE_TREE);
  REQUIRE(tandem_world_set_broad_phase(world, TANDEM_BROAD_PHASE_GRID) == TANDEM_OK);
  CHECK(tandem_world_get_broad_phase(world) == TANDEM_BROAD_PHASE_GRID);
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
  const tandem_broad_phase_stats stats = tandem_world_get_broad_phase_stats(world);
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
  REQUIRE(tandem_body_disable(body) == TANDEM_OK);
  CHECK(!tandem_body_is_enabled(body));
  REQUIRE(tandem_body_enable(body) == TANDEM_OK);
  CHECK(tandem_body_is_enabled(body));
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

TEST_CASE("snapshots, restore, hashes and snapshot diffs", "[capi]") {
  CWorld w;
  add_ground(w.id);
  const tandem_body_id box = add_box(w.id, TANDEM_BODY_DYNAMIC, v2(0, 3), qt("0.5"));
  const std::vector<uint8_t> start = snapshot(w.id);
  const uint64_t start_hash = tandem_world_state_hash(w.id);
  std::vector<uint64_t> trail;
  for (int i = 0; i < 30; ++i) {
    REQUIRE(tandem_world_step(w.id, qt("0.0166"), nullptr) == TANDEM_OK);
    trail.push_back(tandem_world_state_hash(w.id));
  }
  const std::vector<uint8_t> end = snapshot(w.id);

  size_t size = 0;
  std::vector<uint8_t> small(10);
  require_error(tandem_world_snapshot(w.id, small.data(), small.size(), &size), TANDEM_ERROR_BUFFER_TOO_SMALL,
                "needs " + std::to_string(end.size()));
  CHECK(size == end.size());
  require_error(tandem_world_snapshot(w.id, small.data(), small.size(), nullptr), TANDEM_ERROR_NULL_POINTER, "out_size");
  require_error(tandem_world_snapshot(w.id, nullptr, 5, &size), TANDEM_ERROR_NULL_POINTER, "out_bytes");

  // Restore and re-run: the same hashes.
  REQUIRE(tandem_world_restore(w.id, start.data(), start.size()) == TANDEM_OK);
  CHECK(tandem_world_state_hash(w.id) == start_hash);
  for (uint64_t expected : trail) {
    REQUIRE(tandem_world_step(w.id, qt("0.0166"), nullptr) == TANDEM_OK);
    REQUIRE(tandem_world_state_hash(w.id) == expected);
  }
  // A corrupt image is refused and leaves the world unchanged.
  std::vector<uint8_t> corrupt = end;
  corrupt[0] = 'X';
  require_error(tandem_world_restore(w.id, corrupt.data(), corrupt.size()), TANDEM_ERROR_INVALID_ARGUMENT, "offset");
  require_error(tandem_world_restore(w.id, end.data(), end.size() - 3), TANDEM_ERROR_INVALID_ARGUMENT, "");
  require_error(tandem_world_restore(w.id, nullptr, 4), TANDEM_ERROR_NULL_POINTER, "bytes");
  CHECK(tandem_world_state_hash(w.id) == trail.back());

  tandem_world_id copy{};
  REQUIRE(tandem_create_world_from_snapshot(end.data(), end.size(), &copy) == TANDEM_OK);
  CHECK(tandem_world_state_hash(copy) == trail.back());
  require_error(tandem_create_world_from_snapshot(corrupt.data(), corrupt.size(), &copy), TANDEM_ERROR_INVALID_ARGUMENT,
                "");
  require_error(tandem_create_world_from_snapshot(end.data(), end.size(), nullptr), TANDEM_ERROR_NULL_POINTER,
                "out_world");

  // Body hashes.
  const uint64_t bh = tandem_body_state_hash(box);
  CHECK(bh != 0);
  int32_t count = 0;
  REQUIRE(tandem_world_body_hashes(w.id, nullptr, 0, &count) == TANDEM_OK);
  CHECK(count == 2);
  uint64_t hashes[2];
  REQUIRE(tandem_world_body_hashes(w.id, hashes, 2, &count) == TANDEM_OK);
  CHECK(hashes[1] == bh);
  uint64_t one[1];
  require_error(tandem_world_body_hashes(w.id, one, 1, &count), TANDEM_ERROR_BUFFER_TOO_SMALL, "result has 2");

  // Deltas: end as a delta against start, rebuilt exactly.
  size_t delta_size = 0;
  REQUIRE(tandem_encode_state_delta(start.data(), start.size(), end.data(), end.size(), nullptr, 0, &delta_size) ==
          TANDEM_OK);
  CHECK(delta_size < end.size());
  std::vector<uint8_t> delta(delta_size);
  REQUIRE(tandem_encode_state_delta(start.data(), start.size(), end.data(), end.size(), delta.data(), delta.size(),
                                    &delta_size) == TANDEM_OK);
  require_error(tandem_encode_state_delta(start.data(), start.size(), end.data(), end.size(), delta.data(), 2, &delta_size),
                TANDEM_ERROR_BUFFER_TOO_SMALL, "");
  std::vector<uint8_t> rebuilt(end.size());
  size_t rebuilt_size = 0;
  REQUIRE(tandem_apply_state_delta(start.data(), start.size(), delta.data(), delta.size(), rebuilt.data(), rebuilt.size(),
                                   &rebuilt_size) == TANDEM_OK);
  CHECK(rebuilt == end);
  require_error(tandem_apply_state_delta(end.data(), end.size(), delta.data(), delta.size(), rebuilt.data(),
                                         rebuilt.size(), &rebuilt_size),
                TANDEM_ERROR_PARSE, "");  // another base
  require_error(tandem_apply_state_delta(start.data(), start.size(), delta.data(), delta.size(), rebuilt.data(), 3,
                                         &rebuilt_size),
                TANDEM_ERROR_BUFFER_TOO_SMALL, "");
  require_error(tandem_apply_state_delta(start.data(), start.size(), nullptr, 4, rebuilt.data(), rebuilt.size(),
                                         &rebuilt_size),
                TANDEM_ERROR_NULL_POINTER, "");
  require_error(tandem_encode_state_delta(nullptr, 4, end.data(), end.size(), nullptr, 0, &delta_size),
                TANDEM_ERROR_NULL_POINTER, "");

  // Diffs.
  tandem_diff_report report;
  REQUIRE(tandem_diff_snapshots(start.data(), start.size(), end.data(), end.size(), &report) == TANDEM_OK);
  CHECK(report.differs);
  CHECK(report.located);
  INFO(report.difference_text);
  CHECK(std::string(report.difference_text).find(" a = ") != std::string::npos);
  CHECK(std::string(report.text).size() > 10);
  tandem_free_diff_report(&report);
  CHECK(report.text == nullptr);
  tandem_free_diff_report(&report);  // twice: harmless
  tandem_free_diff_report(nullptr);
  REQUIRE(tandem_diff_snapshots(end.data(), end.size(), end.data(), end.size(), &report) == TANDEM_OK);
  CHECK(!report.differs);
  tandem_free_diff_report(&report);
  CHECK(tandem_diff_snapshots(corrupt.data(), corrupt.size(), end.data(), end.size(), &report) != TANDEM_OK);
  CHECK(report.error != TANDEM_OK);
  tandem_free_diff_report(&report);
  require_error(tandem_diff_snapshots(nullptr, 3, end.data(), end.size(), &report), TANDEM_ERROR_NULL_POINTER, "");
  require_error(tandem_diff_snapshots(end.data(), end.size(), end.data(), end.size(), nullptr),
                TANDEM_ERROR_NULL_POINTER, "out_report");
  REQUIRE(tandem_destroy_world(copy) == TANDEM_OK);
}

TEST_CASE("commands, recorders, replays: record, verify, diff", "[capi]") {
  CWorld w;
  add_ground(w.id);
  tandem_recorder_id rec{};
  const tandem_recorder_options options = tandem_default_recorder_options();
  REQUIRE(tandem_recorder_create_memory(&options, &rec) == TANDEM_OK);
  require_error(tandem_recorder_create_memory(&options, nullptr), TANDEM_ERROR_NULL_POINTER, "out_recorder");
  const char scene[] = "{}";
  REQUIRE(tandem_recorder_begin(rec, w.id, reinterpret_cast<const uint8_t*>(scene), 2) == TANDEM_OK);

  // create_body with a box and a chain, through the recorder.
  tandem_shape_spec shapes[2] = {tandem_default_shape_spec(TANDEM_SHAPE_KIND_POLYGON),
                                 tandem_default_shape_spec(TANDEM_SHAPE_KIND_CHAIN)};
  REQUIRE(tandem_make_box(qt("0.5"), qt("0.5"), &shapes[0].polygon) == TANDEM_OK);
  const tandem_vec2 chain[] = {v2(-3, 1), v2(-2, 0), v2(2, 0), v2(3, 1)};
  shapes[1].chain_points = chain;
  shapes[1].chain_point_count = 4;
  tandem_command create = tandem_default_command(TANDEM_COMMAND_CREATE_BODY);
  create.body_def.type = TANDEM_BODY_DYNAMIC;
  create.body_def.position = v2(0, 3);
  create.shapes = shapes;
  create.shape_count = 2;
  REQUIRE(tandem_recorder_submit(rec, &create) == TANDEM_OK);
  uint32_t flags = 1;
  REQUIRE(tandem_recorder_step(rec, &flags) == TANDEM_OK);
  CHECK(tandem_recorder_tick_count(rec) == 1);
  CHECK(tandem_recorder_last_hash(rec) == tandem_world_state_hash(w.id));
  tandem_command push = tandem_default_command(TANDEM_COMMAND_APPLY_LINEAR_IMPULSE);
  push.body_index = 1;
  push.body_generation = 1;
  push.vector = v2(1, 0);
  REQUIRE(tandem_recorder_submit(rec, &push) == TANDEM_OK);
  const uint8_t payload[] = {1, 2, 3};
  REQUIRE(tandem_recorder_submit_payload(rec, payload, 3) == TANDEM_OK);
  require_error(tandem_recorder_submit_payload(rec, nullptr, 3), TANDEM_ERROR_NULL_POINTER, "payload");
  for (int i = 0; i < 20; ++i) REQUIRE(tandem_recorder_step(rec, nullptr) == TANDEM_OK);
  tandem_command bad = tandem_default_command(99);
  require_error(tandem_recorder_submit(rec, &bad), TANDEM_ERROR_INVALID_ARGUMENT, "command type 99");
  require_error(tandem_recorder_submit(rec, nullptr), TANDEM_ERROR_NULL_POINTER, "command");
  REQUIRE(tandem_recorder_finish(rec) == TANDEM_OK);
  size_t size = 0;
  REQUIRE(tandem_recorder_memory(rec, nullptr, 0, &size) == TANDEM_OK);
  std::vector<uint8_t> bytes(size);
  uint8_t tiny[4];
  require_error(tandem_recorder_memory(rec, tiny, 4, &size), TANDEM_ERROR_BUFFER_TOO_SMALL, "");
  REQUIRE(tandem_recorder_memory(rec, bytes.data(), bytes.size(), &size) == TANDEM_OK);
  REQUIRE(tandem_recorder_destroy(rec) == TANDEM_OK);
  require_error(tandem_recorder_destroy(rec), TANDEM_ERROR_INVALID_HANDLE, "recorder");
  require_error(tandem_recorder_step(rec, nullptr), TANDEM_ERROR_INVALID_HANDLE, "recorder");
  require_error(tandem_recorder_step(tandem_recorder_id{}, nullptr), TANDEM_ERROR_NULL_HANDLE, "null recorder");
  CHECK(tandem_recorder_tick_count(rec) == 0);
  CHECK(tandem_recorder_last_hash(rec) == 0);

  // Load, inspect, verify.
  tandem_replay_id replay{};
  REQUIRE(tandem_replay_load_memory(bytes.data(), bytes.size(), &replay) == TANDEM_OK);
  CHECK(tandem_replay_tick_count(replay) == 21);
  uint64_t h = 0;
  REQUIRE(tandem_replay_tick_hash(replay, 21, &h) == TANDEM_OK);
  CHECK(h == tandem_world_state_hash(w.id));
  require_error(tandem_replay_tick_hash(replay, 22, &h), TANDEM_ERROR_INVALID_ARGUMENT, "outside 1");
  require_error(tandem_replay_tick_hash(replay, 1, nullptr), TANDEM_ERROR_NULL_POINTER, "out_hash");
  tandem_world_id at10{};
  REQUIRE(tandem_replay_create_world_at(replay, 10, &at10) == TANDEM_OK);
  REQUIRE(tandem_replay_tick_hash(replay, 10, &h) == TANDEM_OK);
  CHECK(tandem_world_state_hash(at10) == h);
  // Seek an existing world back to tick 4, then forward to tick 10.
  REQUIRE(tandem_replay_seek(replay, at10, 4) == TANDEM_OK);
  REQUIRE(tandem_replay_tick_hash(replay, 4, &h) == TANDEM_OK);
  CHECK(tandem_world_state_hash(at10) == h);
  require_error(tandem_replay_seek(replay, at10, 99), TANDEM_ERROR_INVALID_ARGUMENT, "");
  REQUIRE(tandem_destroy_world(at10) == TANDEM_OK);
  require_error(tandem_replay_seek(replay, at10, 4), TANDEM_ERROR_INVALID_HANDLE, "world");
  require_error(tandem_replay_seek(tandem_replay_id{}, at10, 4), TANDEM_ERROR_NULL_HANDLE, "null replay");
  tandem_verify_report vr;
  REQUIRE(tandem_verify_replay(replay, UINT64_MAX, true, &vr) == TANDEM_OK);
  CHECK(vr.ok);
  CHECK(vr.hashes_checked == 21);
  CHECK(std::string(vr.text).find("21") != std::string::npos);
  tandem_free_verify_report(&vr);
  tandem_free_verify_report(nullptr);

  // A tampered replay: verify names the tick; diff finds where the runs part.
  std::vector<uint8_t> other_bytes;
  {
    CWorld w2;
    add_ground(w2.id);
    tandem_recorder_id r2{};
    REQUIRE(tandem_recorder_create_memory(nullptr, &r2) == TANDEM_OK);
    REQUIRE(tandem_recorder_begin(r2, w2.id, nullptr, 0) == TANDEM_OK);
    REQUIRE(tandem_recorder_submit(r2, &create) == TANDEM_OK);
    for (int i = 0; i < 5; ++i) REQUIRE(tandem_recorder_step(r2, nullptr) == TANDEM_OK);
    push.vector = v2(2, 0);  // different input from tick 6 on
    REQUIRE(tandem_recorder_submit(r2, &push) == TANDEM_OK);
    for (int i = 0; i < 16; ++i) REQUIRE(tandem_recorder_step(r2, nullptr) == TANDEM_OK);
    REQUIRE(tandem_recorder_finish(r2) == TANDEM_OK);
    REQUIRE(tandem_recorder_memory(r2, nullptr, 0, &size) == TANDEM_OK);
    other_bytes.resize(size);
    REQUIRE(tandem_recorder_memory(r2, other_bytes.data(), size, &size) == TANDEM_OK);
    REQUIRE(tandem_recorder_destroy(r2) == TANDEM_OK);
  }
  tandem_replay_id other{};
  REQUIRE(tandem_replay_load_memory(other_bytes.data(), other_bytes.size(), &other) == TANDEM_OK);
  tandem_diff_report dr;
  REQUIRE(tandem_diff_replays(replay, other, &dr) == TANDEM_OK);
  CHECK(dr.differs);
  CHECK(dr.tick == 2);  // first input difference: tick 2 in one, tick 6 in the other
  tandem_free_diff_report(&dr);
  require_error(tandem_diff_replays(replay, tandem_replay_id{}, &dr), TANDEM_ERROR_NULL_HANDLE, "null replay");

  std::vector<uint8_t> broken = bytes;
  broken.resize(broken.size() / 2);
  broken[5] ^= 0xFF;
  tandem_replay_id nope{};
  require_error(tandem_replay_load_memory(broken.data(), broken.size(), &nope), TANDEM_ERROR_PARSE, "offset");
  require_error(tandem_replay_load_memory(bytes.data(), bytes.size(), nullptr), TANDEM_ERROR_NULL_POINTER, "out_replay");

  REQUIRE(tandem_replay_destroy(other) == TANDEM_OK);
  REQUIRE(tandem_replay_destroy(replay) == TANDEM_OK);
  require_error(tandem_replay_destroy(replay), TANDEM_ERROR_INVALID_HANDLE, "replay");
  CHECK(tandem_replay_tick_count(replay) == 0);
  require_error(tandem_verify_replay(replay, UINT64_MAX, true, &vr), TANDEM_ERROR_INVALID_HANDLE, "replay");
  require_error(tandem_replay_create_world_at(replay, 1, &at10), TANDEM_ERROR_INVALID_HANDLE, "replay");

  // Files: record to a file, load it back.
  const std::string path = "capi_test_replay.tndr";
  tandem_recorder_id fr{};
  REQUIRE(tandem_recorder_create_file(path.c_str(), nullptr, &fr) == TANDEM_OK);
  REQUIRE(tandem_recorder_begin(fr, w.id, nullptr, 0) == TANDEM_OK);
  REQUIRE(tandem_recorder_step(fr, nullptr) == TANDEM_OK);
  REQUIRE(tandem_recorder_finish(fr) == TANDEM_OK);
  REQUIRE(tandem_recorder_destroy(fr) == TANDEM_OK);
  REQUIRE(tandem_replay_load_file(path.c_str(), &replay) == TANDEM_OK);
  CHECK(tandem_replay_tick_count(replay) == 1);
  REQUIRE(tandem_replay_destroy(replay) == TANDEM_OK);
  std::remove(path.c_str());
  require_error(tandem_replay_load_file("/nonexistent/x.tndr", &replay), TANDEM_ERROR_IO, "/nonexistent/x.tndr");
  require_error(tandem_recorder_create_file("/nonexistent/dir/x.tndr", nullptr, &fr), TANDEM_ERROR_IO, "/nonexistent");
  require_error(tandem_replay_load_file(nullptr, &replay), TANDEM_ERROR_NULL_POINTER, "path");

  // apply_command without a recorder.
  tandem_body_id created{};
  REQUIRE(tandem_apply_command(w.id, &create, &created) == TANDEM_OK);
  CHECK(tandem_body_is_valid(created));
  CHECK(tandem_body_shape_count(created) == 2);  // the box and the chain's one segment (4 points, open)
  tandem_command gravity = tandem_default_command(TANDEM_COMMAND_SET_GRAVITY);
  gravity.vector = v2(0, -3);
  REQUIRE(tandem_apply_command(w.id, &gravity, nullptr) == TANDEM_OK);
  CHECK(tandem_world_gravity(w.id).y == qi(-3));
  tandem_command destroy = tandem_default_command(TANDEM_COMMAND_DESTROY_BODY);
  destroy.body_index = 99;
  destroy.body_generation = 1;
  require_error(tandem_apply_command(w.id, &destroy, nullptr), TANDEM_ERROR_INVALID_HANDLE, "destroy_body");
  create.shape_count = 1;
  create.shapes = nullptr;
  require_error(tandem_apply_command(w.id, &create, nullptr), TANDEM_ERROR_NULL_POINTER, "shapes");
}

namespace {
struct SyncInputs {
  tandem_body_id body;
  int calls = 0;
};
void sync_inputs(tandem_world_id, int64_t tick, void* context) {
  auto* in = static_cast<SyncInputs*>(context);
  ++in->calls;
  if (tick % 10 == 0) tandem_body_apply_linear_impulse_to_center(in->body, v2(0, 1), true);
}
}  // namespace

TEST_CASE("the sync test through C", "[capi]") {
  CWorld w;
  add_ground(w.id);
  SyncInputs inputs{add_box(w.id, TANDEM_BODY_DYNAMIC, v2(0, 2), qt("0.5"))};
  tandem_synctest_options options = tandem_default_synctest_options();
  options.ticks = 40;
  options.rollback = 4;
  tandem_synctest_report report;
  REQUIRE(tandem_run_synctest(w.id, &options, &sync_inputs, &inputs, &report) == TANDEM_OK);
  CHECK(report.passed);
  CHECK(report.ticks_run == 40);
  CHECK(report.resimulated_ticks > 40);
  CHECK(inputs.calls > 40);
  CHECK(std::string(report.message).find("passed") != std::string::npos);
  tandem_free_synctest_report(&report);
  tandem_free_synctest_report(nullptr);
  options.rollback = 0;
  require_error(tandem_run_synctest(w.id, &options, nullptr, nullptr, &report), TANDEM_ERROR_INVALID_ARGUMENT, "rollback");
  tandem_free_synctest_report(&report);
  require_error(tandem_run_synctest(w.id, nullptr, nullptr, nullptr, &report), TANDEM_ERROR_NULL_POINTER, "options");
  require_error(tandem_run_synctest(w.id, &options, nullptr, nullptr, nullptr), TANDEM_ERROR_NULL_POINTER, "out_report");
}

TEST_CASE("scenes: load, build, inputs, errors", "[capi]") {
  tandem_scene_id scene{};
  const std::string path = std::string(TANDEM_SOURCE_DIR) + "/scenes/impulses.json";
  REQUIRE(tandem_scene_load_file(path.c_str(), &scene) == TANDEM_OK);
  tandem_scene_info info;
  REQUIRE(tandem_scene_get_info(scene, &info) == TANDEM_OK);
  CHECK(info.step_hz == 60);
  CHECK(info.ticks == 300);
  CHECK(info.input_count == 9);
  tandem_world_id world{};
  REQUIRE(tandem_scene_build(scene, &world) == TANDEM_OK);
  tandem_body_id first{};
  REQUIRE(tandem_scene_body(scene, world, 0, &first) == TANDEM_OK);
  CHECK(tandem_body_is_valid(first));
  require_error(tandem_scene_body(scene, world, info.body_count, &first), TANDEM_ERROR_INVALID_ARGUMENT, "body index");
  for (int64_t tick = 0; tick < 20; ++tick) {
    REQUIRE(tandem_scene_apply_inputs(scene, world, tick) == TANDEM_OK);
    REQUIRE(tandem_world_step(world, info.time_step, nullptr) == TANDEM_OK);
  }
  CWorld stranger;
  require_error(tandem_scene_apply_inputs(scene, stranger.id, 0), TANDEM_ERROR_INVALID_ARGUMENT, "not built");
  require_error(tandem_scene_body(scene, stranger.id, 0, &first), TANDEM_ERROR_INVALID_ARGUMENT, "not built");
  REQUIRE(tandem_destroy_world(world) == TANDEM_OK);
  REQUIRE(tandem_scene_destroy(scene) == TANDEM_OK);
  require_error(tandem_scene_destroy(scene), TANDEM_ERROR_INVALID_HANDLE, "scene");
  require_error(tandem_scene_get_info(scene, &info), TANDEM_ERROR_INVALID_HANDLE, "scene");
  require_error(tandem_scene_build(scene, &world), TANDEM_ERROR_INVALID_HANDLE, "scene");
  require_error(tandem_scene_get_info(tandem_scene_id{}, &info), TANDEM_ERROR_NULL_HANDLE, "null scene");

  const char text[] = R"({"bodies": [{"type": "dynamic", "positon": [0, 1]}]})";
  require_error(tandem_scene_load_text(text, sizeof text - 1, "bad.json", &scene), TANDEM_ERROR_PARSE, "bad.json");
  const char good[] = R"({"bodies": [{"type": "dynamic", "position": [0, 1], "shapes": [{"type": "circle", "radius": 0.5}]}]})";
  REQUIRE(tandem_scene_load_text(good, sizeof good - 1, nullptr, &scene) == TANDEM_OK);
  REQUIRE(tandem_scene_destroy(scene) == TANDEM_OK);
  require_error(tandem_scene_load_file("/nonexistent.json", &scene), TANDEM_ERROR_PARSE, "/nonexistent.json");
  require_error(tandem_scene_load_file(nullptr, &scene), TANDEM_ERROR_NULL_POINTER, "path");
  require_error(tandem_scene_load_text(good, sizeof good - 1, nullptr, nullptr), TANDEM_ERROR_NULL_POINTER, "out_scene");
}

// --- the C layer adds no arithmetic: C and C++ give the same hash every tick ---

TEST_CASE("the same world through C and C++ hashes the same every tick", "[capi][determinism]") {
  using namespace tandem;
  // C++ world (the static modules in this executable).
  const WorldId cw = create_world(default_world_def()).value;
  {
    const BodyId ground = create_body(cw, default_body_def()).value;
    Polygon g;
    REQUIRE(make_offset_box(Q32::from_int(20), Q32::from_int(1), vec2(0, -1), Q32{}, Q32{}, &g).ok);
    REQUIRE(create_polygon_shape(ground, default_shape_def(), g).ok());
    const Vec2 chain[] = {vec2(-12, 4), vec2(-10, 0), vec2(-6, 0), vec2(-4, 1)};
    REQUIRE(create_chain_shapes(ground, default_shape_def(), chain, 4, false, nullptr).ok());
  }
  // C world (inside libtandem.so).
  CWorld c;
  add_ground(c.id);
  {
    tandem_body_id ground{};
    REQUIRE(tandem_world_bodies(c.id, &ground, 1, nullptr) == TANDEM_ERROR_NULL_POINTER);
    int32_t n = 0;
    REQUIRE(tandem_world_bodies(c.id, &ground, 1, &n) == TANDEM_OK);
    const tandem_vec2 chain[] = {v2(-12, 4), v2(-10, 0), v2(-6, 0), v2(-4, 1)};
    const tandem_shape_def sd = tandem_default_shape_def();
    REQUIRE(tandem_create_chain_shapes(ground, &sd, chain, 4, false, nullptr, 0, &n) == TANDEM_OK);
  }
  std::vector<BodyId> cpp_bodies;
  std::vector<tandem_body_id> c_bodies;
  for (int i = 0; i < 6; ++i) {
    BodyDef def = default_body_def();
    def.type = BodyType::dynamic_body;
    def.position = Vec2{Q32::from_ratio(i * 7 - 18, 10), Q32::from_int(1 + i)};
    def.angular_velocity = Q32::from_ratio(i, 3);
    const BodyId b = create_body(cw, def).value;
    tandem_body_def cdef = tandem_default_body_def();
    cdef.type = TANDEM_BODY_DYNAMIC;
    cdef.position = {def.position.x.raw, def.position.y.raw};
    cdef.angular_velocity = def.angular_velocity.raw;
    tandem_body_id cb{};
    REQUIRE(tandem_create_body(c.id, &cdef, &cb) == TANDEM_OK);
    ShapeDef sd = default_shape_def();
    sd.restitution = Q32::from_ratio(i, 10);
    tandem_shape_def csd = tandem_default_shape_def();
    csd.restitution = sd.restitution.raw;
    tandem_shape_id cs{};
    if (i % 3 == 0) {
      REQUIRE(create_circle_shape(b, sd, Circle{Vec2{}, Q32::from_ratio(2, 5)}).ok());
      const tandem_circle circle = {{0, 0}, Q32::from_ratio(2, 5).raw};
      REQUIRE(tandem_create_circle_shape(cb, &csd, &circle, &cs) == TANDEM_OK);
    } else if (i % 3 == 1) {
      const Capsule cap{vec2(0, 0), Vec2{Q32::from_ratio(1, 2), Q32{}}, Q32::from_ratio(1, 4)};
      REQUIRE(create_capsule_shape(b, sd, cap).ok());
      const tandem_capsule ccap = {{0, 0}, {cap.center2.x.raw, 0}, cap.radius.raw};
      REQUIRE(tandem_create_capsule_shape(cb, &csd, &ccap, &cs) == TANDEM_OK);
    } else {
      Polygon p;
      REQUIRE(make_offset_box(Q32::from_ratio(3, 10), Q32::from_ratio(2, 10), Vec2{}, Q32::from_ratio(1, 5), Q32{}, &p).ok);
      REQUIRE(create_polygon_shape(b, sd, p).ok());
      tandem_polygon cp;
      REQUIRE(tandem_make_offset_box(Q32::from_ratio(3, 10).raw, Q32::from_ratio(2, 10).raw, {0, 0}, Q32::from_ratio(1, 5).raw, 0, &cp) == TANDEM_OK);
      REQUIRE(tandem_create_polygon_shape(cb, &csd, &cp, &cs) == TANDEM_OK);
    }
    cpp_bodies.push_back(b);
    c_bodies.push_back(cb);
  }
  REQUIRE(world_state_hash(cw) == tandem_world_state_hash(c.id));
  const Q32 dt = Q32::from_ratio(1, 60);
  for (int tick = 0; tick < 300; ++tick) {
    // The same inputs through both APIs.
    const size_t k = static_cast<size_t>(tick) % cpp_bodies.size();
    if (tick % 7 == 0) {
      const Vec2 j{Q32::from_ratio(tick % 5 - 2, 3), Q32::from_ratio(3, 2)};
      REQUIRE(body_apply_linear_impulse(cpp_bodies[k], j, body_world_center(cpp_bodies[k]), true).ok());
      const tandem_vec2 center = tandem_body_world_center(c_bodies[k]);
      REQUIRE(tandem_body_apply_linear_impulse(c_bodies[k], {j.x.raw, j.y.raw}, center, true) == TANDEM_OK);
    }
    if (tick % 11 == 0) {
      REQUIRE(body_apply_torque(cpp_bodies[k], Q32::from_ratio(tick, 40), true).ok());
      REQUIRE(tandem_body_apply_torque(c_bodies[k], Q32::from_ratio(tick, 40).raw, true) == TANDEM_OK);
    }
    if (tick == 150) {
      REQUIRE(world_set_gravity(cw, vec2(2, -10)).ok());
      REQUIRE(tandem_world_set_gravity(c.id, v2(2, -10)) == TANDEM_OK);
    }
    REQUIRE(world_step(cw, dt).ok());
    REQUIRE(tandem_world_step(c.id, dt.raw, nullptr) == TANDEM_OK);
    INFO("tick " << tick + 1);
    REQUIRE(world_state_hash(cw) == tandem_world_state_hash(c.id));
  }
  CHECK(destroy_world(cw).ok());
}

TEST_CASE("every bundled scene through the C scene API hashes as through C++", "[capi][determinism]") {
  using namespace tandem;
  for (const char* name : {"card_house", "circles", "dominoes", "impulses", "pyramid", "rain", "stack", "tumbler"}) {
    const std::string path = std::string(TANDEM_SOURCE_DIR) + "/scenes/" + name + ".json";
    INFO(path);
    Result<scene::Scene> loaded = scene::load_scene_file(path);
    REQUIRE(loaded.ok());
    Result<scene::BuiltScene> built = scene::build_world(loaded.value);
    REQUIRE(built.ok());
    tandem_scene_id cs{};
    REQUIRE(tandem_scene_load_file(path.c_str(), &cs) == TANDEM_OK);
    tandem_world_id cw{};
    REQUIRE(tandem_scene_build(cs, &cw) == TANDEM_OK);
    tandem_scene_info info;
    REQUIRE(tandem_scene_get_info(cs, &info) == TANDEM_OK);
    REQUIRE(info.time_step == loaded.value.time_step.raw);
    const int64_t ticks = std::min<int64_t>(info.ticks, 240);
    for (int64_t tick = 0; tick < ticks; ++tick) {
      REQUIRE(scene::apply_scene_inputs(built.value, loaded.value, tick).ok());
      REQUIRE(world_step(built.value.world, loaded.value.time_step).ok());
      REQUIRE(tandem_scene_apply_inputs(cs, cw, tick) == TANDEM_OK);
      REQUIRE(tandem_world_step(cw, info.time_step, nullptr) == TANDEM_OK);
      INFO("tick " << tick + 1);
      REQUIRE(world_state_hash(built.value.world) == tandem_world_state_hash(cw));
    }
    (void)destroy_world(built.value.world);
    REQUIRE(tandem_destroy_world(cw) == TANDEM_OK);
    REQUIRE(tandem_scene_destroy(cs) == TANDEM_OK);
  }
}

// --- every handle-taking function refuses null and stale handles ------------------

TEST_CASE("every status function refuses null and stale handles with a message", "[capi]") {
  tandem_world_id stale_world{};
  tandem_body_id stale_body{};
  tandem_shape_id stale_shape{};
  {
    CWorld w;
    stale_body = add_box(w.id, TANDEM_BODY_DYNAMIC, v2(0, 0), qi(1));
    tandem_shape_id s{};
    int32_t n = 0;
    REQUIRE(tandem_body_shapes(stale_body, &s, 1, &n) == TANDEM_OK);
    stale_shape = s;
    stale_world = w.id;
  }  // the world, its body and its shape are gone
  tandem_ray_hit hit;
  int32_t n = 0;
  tandem_shape_id ids[4];
  const tandem_circle circle = {{0, 0}, qi(1)};
  const tandem_body_def bdef = tandem_default_body_def();
  tandem_body_id out_body{};
  uint64_t h[4];
  uint8_t bytes[8] = {0};
  size_t size = 0;
  const std::vector<std::pair<const char*, std::function<tandem_status(tandem_world_id)>>> world_fns = {
      {"destroy_world", [](tandem_world_id w) { return tandem_destroy_world(w); }},
      {"world_check", [](tandem_world_id w) { return tandem_world_check(w); }},
      {"world_step", [](tandem_world_id w) { return tandem_world_step(w, 0, nullptr); }},
      {"set_gravity", [](tandem_world_id w) { return tandem_world_set_gravity(w, v2(0, 0)); }},
      {"set_sub_step_count", [](tandem_world_id w) { return tandem_world_set_sub_step_count(w, 4); }},
      {"set_contact_tuning", [](tandem_world_id w) { return tandem_world_set_contact_tuning(w, qi(30), qi(10), qi(3)); }},
      {"set_joint_tuning", [](tandem_world_id w) { return tandem_world_set_joint_tuning(w, qi(60), qi(2)); }},
      {"set_restitution_threshold", [](tandem_world_id w) { return tandem_world_set_restitution_threshold(w, qi(1)); }},
      {"set_hit_event_threshold", [](tandem_world_id w) { return tandem_world_set_hit_event_threshold(w, qi(1)); }},
      {"set_max_linear_speed", [](tandem_world_id w) { return tandem_world_set_max_linear_speed(w, qi(100)); }},
      {"enable_sleep", [](tandem_world_id w) { return tandem_world_enable_sleep(w, true); }},
      {"enable_continuous", [](tandem_world_id w) { return tandem_world_enable_continuous(w, true); }},
      {"set_user_data", [](tandem_world_id w) { return tandem_world_set_user_data(w, 1); }},
      {"world_bodies", [&](tandem_world_id w) { return tandem_world_bodies(w, nullptr, 0, &n); }},
      {"set_broad_phase", [](tandem_world_id w) { return tandem_world_set_broad_phase(w, 0); }},
      {"set_custom_filter", [](tandem_world_id w) { return tandem_world_set_custom_filter(w, nullptr, nullptr); }},
      {"create_body", [&](tandem_world_id w) { return tandem_create_body(w, &bdef, &out_body); }},
      {"cast_ray_closest", [&](tandem_world_id w) { return tandem_world_cast_ray_closest(w, v2(0, 0), v2(1, 0), nullptr, &hit); }},
      {"cast_ray_all", [&](tandem_world_id w) { return tandem_world_cast_ray_all(w, v2(0, 0), v2(1, 0), nullptr, nullptr, 0, &n); }},
      {"overlap_aabb", [&](tandem_world_id w) { return tandem_world_overlap_aabb(w, {v2(0, 0), v2(1, 1)}, nullptr, ids, 4, &n); }},
      {"overlap_point", [&](tandem_world_id w) { return tandem_world_overlap_point(w, v2(0, 0), nullptr, ids, 4, &n); }},
      {"overlap_circle", [&](tandem_world_id w) {
         return tandem_world_overlap_circle(w, &circle, {v2(0, 0), tandem_rot_identity()}, nullptr, ids, 4, &n);
       }},
      {"contact_begin_events", [&](tandem_world_id w) { return tandem_world_contact_begin_events(w, nullptr, 0, &n); }},
      {"body_move_events", [&](tandem_world_id w) { return tandem_world_body_move_events(w, nullptr, 0, &n); }},
      {"snapshot", [&](tandem_world_id w) { return tandem_world_snapshot(w, nullptr, 0, &size); }},
      {"restore", [&](tandem_world_id w) { return tandem_world_restore(w, bytes, sizeof bytes); }},
      {"body_hashes", [&](tandem_world_id w) { return tandem_world_body_hashes(w, h, 4, &n); }},
      {"apply_command", [&](tandem_world_id w) {
         const tandem_command c = tandem_default_command(TANDEM_COMMAND_SET_GRAVITY);
         return tandem_apply_command(w, &c, nullptr);
       }},
      {"run_synctest", [&](tandem_world_id w) {
         const tandem_synctest_options o = tandem_default_synctest_options();
         tandem_synctest_report r;
         const tandem_status s = tandem_run_synctest(w, &o, nullptr, nullptr, &r);
         tandem_free_synctest_report(&r);
         return s;
       }},
  };
  for (const auto& [name, fn] : world_fns) {
    INFO(name);
    require_error(fn(tandem_world_id{}), TANDEM_ERROR_NULL_HANDLE, "world");
    require_error(fn(stale_world), TANDEM_ERROR_INVALID_HANDLE, "world");
  }
  const std::vector<std::pair<const char*, std::function<tandem_status(tandem_body_id)>>> body_fns = {
      {"destroy_body", [](tandem_body_id b) { return tandem_destroy_body(b); }},
      {"body_check", [](tandem_body_id b) { return tandem_body_check(b, tandem_world_id{}); }},
      {"set_type", [](tandem_body_id b) { return tandem_body_set_type(b, TANDEM_BODY_DYNAMIC); }},
      {"set_transform", [](tandem_body_id b) { return tandem_body_set_transform(b, v2(0, 0), tandem_rot_identity()); }},
      {"set_linear_velocity", [](tandem_body_id b) { return tandem_body_set_linear_velocity(b, v2(0, 0)); }},
      {"set_angular_velocity", [](tandem_body_id b) { return tandem_body_set_angular_velocity(b, 0); }},
      {"apply_force", [](tandem_body_id b) { return tandem_body_apply_force(b, v2(1, 0), v2(0, 0), true); }},
      {"apply_force_to_center", [](tandem_body_id b) { return tandem_body_apply_force_to_center(b, v2(1, 0), true); }},
      {"apply_torque", [](tandem_body_id b) { return tandem_body_apply_torque(b, qi(1), true); }},
      {"apply_linear_impulse", [](tandem_body_id b) { return tandem_body_apply_linear_impulse(b, v2(1, 0), v2(0, 0), true); }},
      {"apply_linear_impulse_to_center", [](tandem_body_id b) { return tandem_body_apply_linear_impulse_to_center(b, v2(1, 0), true); }},
      {"apply_angular_impulse", [](tandem_body_id b) { return tandem_body_apply_angular_impulse(b, qi(1), true); }},
      {"set_linear_damping", [](tandem_body_id b) { return tandem_body_set_linear_damping(b, 0); }},
      {"set_angular_damping", [](tandem_body_id b) { return tandem_body_set_angular_damping(b, 0); }},
      {"set_gravity_scale", [](tandem_body_id b) { return tandem_body_set_gravity_scale(b, qi(1)); }},
      {"set_fixed_rotation", [](tandem_body_id b) { return tandem_body_set_fixed_rotation(b, false); }},
      {"set_bullet", [](tandem_body_id b) { return tandem_body_set_bullet(b, false); }},
      {"enable", [](tandem_body_id b) { return tandem_body_enable(b); }},
      {"disable", [](tandem_body_id b) { return tandem_body_disable(b); }},
      {"set_awake", [](tandem_body_id b) { return tandem_body_set_awake(b, true); }},
      {"enable_sleep", [](tandem_body_id b) { return tandem_body_enable_sleep(b, true); }},
      {"set_user_data", [](tandem_body_id b) { return tandem_body_set_user_data(b, 1); }},
      {"body_shapes", [&](tandem_body_id b) { return tandem_body_shapes(b, ids, 4, &n); }},
      {"create_circle_shape", [&](tandem_body_id b) {
         const tandem_shape_def d = tandem_default_shape_def();
         return tandem_create_circle_shape(b, &d, &circle, &ids[0]);
       }},
      {"create_chain_shapes", [&](tandem_body_id b) {
         const tandem_shape_def d = tandem_default_shape_def();
         const tandem_vec2 pts[] = {v2(0, 0), v2(1, 0), v2(1, 1)};
         return tandem_create_chain_shapes(b, &d, pts, 3, true, ids, 4, &n);
       }},
  };
  for (const auto& [name, fn] : body_fns) {
    INFO(name);
    require_error(fn(tandem_body_id{}), TANDEM_ERROR_NULL_HANDLE, "body");
    require_error(fn(stale_body), TANDEM_ERROR_INVALID_HANDLE, "body");
  }
  const std::vector<std::pair<const char*, std::function<tandem_status(tandem_shape_id)>>> shape_fns = {
      {"destroy_shape", [](tandem_shape_id s) { return tandem_destroy_shape(s); }},
      {"shape_check", [](tandem_shape_id s) { return tandem_shape_check(s, tandem_world_id{}); }},
      {"set_friction", [](tandem_shape_id s) { return tandem_shape_set_friction(s, 0); }},
      {"set_restitution", [](tandem_shape_id s) { return tandem_shape_set_restitution(s, 0); }},
      {"set_density", [](tandem_shape_id s) { return tandem_shape_set_density(s, qi(1)); }},
      {"set_filter", [](tandem_shape_id s) { return tandem_shape_set_filter(s, tandem_default_filter()); }},
      {"set_user_data", [](tandem_shape_id s) { return tandem_shape_set_user_data(s, 1); }},
  };
  for (const auto& [name, fn] : shape_fns) {
    INFO(name);
    require_error(fn(tandem_shape_id{}), TANDEM_ERROR_NULL_HANDLE, "shape");
    require_error(fn(stale_shape), TANDEM_ERROR_INVALID_HANDLE, "shape");
  }
  // Getters of stale handles: the documented defaults, the last error untouched.
  require_error(tandem_world_check(stale_world), TANDEM_ERROR_INVALID_HANDLE, "world");
  CHECK(tandem_body_type(stale_body) == TANDEM_BODY_STATIC);
  CHECK(tandem_body_transform(stale_body).q.c == qi(1));
  CHECK(tandem_body_linear_velocity(stale_body).x == 0);
  CHECK(tandem_body_mass_data(stale_body).mass == 0);
  CHECK(!tandem_body_is_awake(stale_body));
  CHECK(tandem_shape_type(stale_shape) == TANDEM_SHAPE_CIRCLE);
  CHECK(tandem_shape_aabb(stale_shape).upper.x == 0);
  CHECK(tandem_shape_geometry_of(stale_shape).type == TANDEM_SHAPE_CIRCLE);
  CHECK(tandem_world_get_broad_phase(stale_world) == TANDEM_BROAD_PHASE_NAIVE);
  CHECK(tandem_world_get_broad_phase_stats(stale_world).pairs == 0);
  CHECK(!tandem_world_is_locked(stale_world));
  CHECK(tandem_last_error_code() == TANDEM_ERROR_INVALID_HANDLE);
}

TEST_CASE("the last error is per thread", "[capi]") {
  require_error(tandem_world_check(tandem_world_id{}), TANDEM_ERROR_NULL_HANDLE, "null");
  std::string other_message;
  tandem_status other_code = -1;
  std::thread other([&] {
    tandem_q32 v = 0;
    tandem_q32_from_text("oops", &v);  // a different error on another thread
    other_code = tandem_last_error_code();
    other_message = tandem_last_error_message();
  });
  other.join();
  CHECK(other_code == TANDEM_ERROR_PARSE);
  CHECK(other_message.find("oops") != std::string::npos);
  // This thread's last error is still its own.
  CHECK(tandem_last_error_code() == TANDEM_ERROR_NULL_HANDLE);
  CHECK(last_message().find("null") != std::string::npos);
}
