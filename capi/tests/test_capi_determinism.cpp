// test_capi_determinism.cpp — the same worlds through C and C++ hash the same
// every tick; every status function refuses null and stale handles; the
// last error is per thread (see test_capi.cpp).
#include "capi_test_util.h"

TEST_CASE("the same world through C and C++ hashes the same every tick", "[capi][determinism]") {
  using namespace tandem;
  // C++ world (the static modules in this executable).
  const WorldId cw = create_world(default_world_def()).value;
  {
    const BodyId ground = create_body(cw, default_body_def()).value;
    Polygon g;
    REQUIRE(make_offset_box(Q32::from_int(20), Q32::from_int(1), vec2(0, -1), Q32{}, Q32{}, &g).ok());
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
      REQUIRE(make_offset_box(Q32::from_ratio(3, 10), Q32::from_ratio(2, 10), Vec2{}, Q32::from_ratio(1, 5), Q32{}, &p).ok());
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
      {"enable", [](tandem_body_id b) { return tandem_body_set_enabled(b, true); }},
      {"disable", [](tandem_body_id b) { return tandem_body_set_enabled(b, false); }},
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
  CHECK(tandem_world_broad_phase(stale_world) == TANDEM_BROAD_PHASE_NAIVE);
  CHECK(tandem_world_broad_phase_stats(stale_world).pairs == 0);
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
