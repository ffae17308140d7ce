// joint.cpp — joint definitions, creation and destruction, the
// collide_connected filter and joint events (design in joint.h; queries and
// setters are joint_api.cpp, the solver joint_solver.cpp).
//
// Every mutating function resolves the handle (refusing null, stale, foreign
// and locked), checks every value, and only then writes: a refused call
// changes nothing. Joint slots come from an IdPool (lowest free index first),
// so joint indices — the solve order — depend only on the order of calls.
#include <algorithm>

#include "physics/island.h"
#include "physics/world.h"

namespace tandem {

namespace joint_detail {

Joint& joint_at(World* w, int32_t i) { return w->joints.joints[static_cast<size_t>(i)]; }

std::string q(Q32 v) { return to_string(v); }

/// "function: Def.field value unit is outside [lo, hi] unit".
bool check_range(const char* function, const char* def_name, const char* field, Q32 value, Q32 lo, Q32 hi,
                 const char* unit, Status* out) {
  if (lo <= value && value <= hi) return true;
  std::string u = *unit != 0 ? std::string(" ") + unit : std::string();
  *out = make_status(StatusCode::invalid_argument, std::string(function) + ": " + def_name + "." + field + " " +
                                                       q(value) + u + " is outside [" + q(lo) + ", " + q(hi) + "]" + u);
  return false;
}

bool check_vec(const char* function, const char* def_name, const char* field, Vec2 v, Q32 limit, const char* unit,
               Status* out) {
  if (-limit <= v.x && v.x <= limit && -limit <= v.y && v.y <= limit) return true;
  *out = make_status(StatusCode::invalid_argument, std::string(function) + ": " + def_name + "." + field + " " +
                                                       format_vec2(v) + " " + unit + " has a component outside [" +
                                                       q(-limit) + ", " + q(limit) + "] " + unit);
  return false;
}

bool check_order(const char* function, const char* def_name, const char* lo_name, Q32 lo, const char* hi_name, Q32 hi,
                 Status* out) {
  if (lo <= hi) return true;
  *out = make_status(StatusCode::invalid_argument, std::string(function) + ": " + def_name + "." + lo_name + " " +
                                                       q(lo) + " is above " + def_name + "." + hi_name + " " + q(hi));
  return false;
}

bool check_angle(const char* function, const char* def_name, const char* field, Q32 angle, Status* s) {
  return check_range(function, def_name, field, angle, -k_pi, k_pi, "rad", s);
}

Status resolve_joint(JointId id, const char* function, bool mutating, World** out_world, int32_t* out_index) {
  return resolve_handle(function, "joint", id.index1, id.generation, id.world, WorldId{}, mutating,
                        &World::joint_pool, out_world, out_index);
}

}  // namespace joint_detail

using joint_detail::check_angle;
using joint_detail::check_order;
using joint_detail::check_range;
using joint_detail::check_vec;
using joint_detail::joint_at;
using joint_detail::q;
using joint_detail::resolve_joint;

namespace {

/// A unit axis: |axis|² within 2e-6 of 1 (so |axis| within 1e-6).
bool check_axis(const char* function, const char* def_name, Vec2 axis, Status* out) {
  const Q32 tolerance = Q32::from_ratio(2, 1000000);
  const bool finite = abs(axis.x) <= Q32::from_int(2) && abs(axis.y) <= Q32::from_int(2);
  if (finite && abs(length_squared(axis) - Q32::one()) <= tolerance) return true;
  *out = make_status(StatusCode::invalid_argument, std::string(function) + ": " + def_name + ".local_axis_a " +
                                                       format_vec2(axis) +
                                                       " must be a unit vector (|axis| within 1e-6 of 1)");
  return false;
}

/// lower_translation and upper_translation of a prismatic or wheel joint: each
/// within ±k_max_joint_length m, lower ≤ upper.
bool check_translation_limits(const char* function, const char* def_name, Q32 lower, Q32 upper, Status* out) {
  return check_range(function, def_name, "lower_translation", lower, -k_max_joint_length, k_max_joint_length, "m",
                     out) &&
         check_range(function, def_name, "upper_translation", upper, -k_max_joint_length, k_max_joint_length, "m",
                     out) &&
         check_order(function, def_name, "lower_translation", lower, "upper_translation", upper, out);
}

/// Resolves the base's bodies and checks the shared fields. Writes the world
/// and body indices.
Status check_base(WorldId world_id, const JointBaseDef& base, int32_t cookie, const char* function,
                  const char* def_name, World** out_world, int32_t* out_a, int32_t* out_b) {
  World* w = nullptr;
  Status s = resolve_world(world_id, function, true, &w);
  if (!s.ok()) return s;
  if (cookie != k_def_cookie) {
    return make_status(StatusCode::invalid_definition, std::string(function) + ": the " + def_name +
                                                           " was not made by its default_*_joint_def()");
  }
  int32_t a = 0, b = 0;
  World* wa = nullptr;
  s = resolve_body(base.body_a, (std::string(function) + ": " + def_name + ".base.body_a").c_str(), true, world_id, &wa,
                   &a);
  if (!s.ok()) return s;
  s = resolve_body(base.body_b, (std::string(function) + ": " + def_name + ".base.body_b").c_str(), true, world_id, &wa,
                   &b);
  if (!s.ok()) return s;
  if (a == b) {
    return make_status(StatusCode::invalid_argument, std::string(function) + ": " + def_name +
                                                         ".base.body_a and base.body_b are the same " +
                                                         describe(base.body_a) + "; a joint needs two bodies");
  }
  if (w->bodies[static_cast<size_t>(a)].type == BodyType::static_body &&
      w->bodies[static_cast<size_t>(b)].type == BodyType::static_body) {
    return make_status(StatusCode::invalid_argument, std::string(function) + ": " + def_name +
                                                         ".base.body_a and base.body_b are both static");
  }
  if (!check_vec(function, def_name, "base.local_anchor_a", base.local_anchor_a, k_max_shape_size, "m", &s)) return s;
  if (!check_vec(function, def_name, "base.local_anchor_b", base.local_anchor_b, k_max_shape_size, "m", &s)) return s;
  if (!check_range(function, def_name, "base.break_force", base.break_force, Q32::zero(), k_max_joint_force, "N", &s))
    return s;
  if (!check_range(function, def_name, "base.break_torque", base.break_torque, Q32::zero(), k_max_joint_torque, "N·m",
                   &s))
    return s;
  if (w->joint_pool.alive_count >= k_max_bodies) {
    return make_status(StatusCode::capacity_exceeded, std::string(function) + ": " + describe(world_id) +
                                                          " already has " + std::to_string(k_max_bodies) + " joints");
  }
  *out_world = w;
  *out_a = a;
  *out_b = b;
  return s;
}

bool check_spring(const char* function, const char* def_name, const char* hertz_name, Q32 hertz,
                  const char* ratio_name, Q32 ratio, Status* s) {
  return check_range(function, def_name, hertz_name, hertz, Q32::zero(), k_max_joint_hertz, "Hz", s) &&
         check_range(function, def_name, ratio_name, ratio, Q32::zero(), k_max_joint_damping_ratio, "", s);
}

/// Allocates the slot and fills the shared fields.
Result<JointId> add_joint(World* w, int32_t a, int32_t b, const JointBaseDef& base, JointType type, Joint joint) {
  joint.type = type;
  joint.body_a = a;
  joint.body_b = b;
  joint.local_anchor_a = base.local_anchor_a;
  joint.local_anchor_b = base.local_anchor_b;
  joint.collide_connected = base.collide_connected;
  joint.break_force = base.break_force;
  joint.break_torque = base.break_torque;
  joint.user_data = base.user_data;
  const int32_t index = id_pool_allocate(&w->joint_pool);
  if (static_cast<size_t>(index) >= w->joints.joints.size()) w->joints.joints.resize(static_cast<size_t>(index) + 1);
  joint_at(w, index) = joint;
  // Nothing grows inside a step when joints break: room in the event list
  // for every joint, and in the pool's free list for every slot.
  const size_t room = static_cast<size_t>(w->joint_pool.alive_count) + w->joints.pending.size();
  if (w->joints.events.capacity() < room) w->joints.events.reserve(room * 2);
  const size_t slots = static_cast<size_t>(id_pool_capacity(w->joint_pool));
  if (w->joint_pool.free_heap.capacity() < slots) w->joint_pool.free_heap.reserve(slots * 2);
  rebuild_joint_filter(w);
  wake_body_island(w, a);
  wake_body_island(w, b);
  Result<JointId> r;
  r.value = make_joint_id(*w, index);
  return r;
}

/// What every create_*_joint starts with: the function and def names its
/// messages use, the result (whose status the checks write), and the world
/// and body indices that check_base resolved.
struct JointCreation {
  const char* fn;
  const char* dn;
  Result<JointId> r;
  World* w = nullptr;
  int32_t a = 0, b = 0;

  template <typename Def>
  JointCreation(WorldId world, const Def& def, const char* function, const char* def_name)
      : fn(function), dn(def_name) {
    r.status = check_base(world, def.base, def.internal_cookie, fn, dn, &w, &a, &b);
  }
  Result<JointId> add(const JointBaseDef& base, JointType type, const Joint& j) {
    return add_joint(w, a, b, base, type, j);
  }
};

/// A motor's speed (within ±max_speed) and its largest force or torque.
bool check_motor(const char* function, const char* def_name, Q32 speed, Q32 max_speed, const char* speed_unit,
                 const char* max_name, Q32 max_value, Q32 max_limit, const char* max_unit, Status* s) {
  return check_range(function, def_name, "motor_speed", speed, -max_speed, max_speed, speed_unit, s) &&
         check_range(function, def_name, max_name, max_value, Q32::zero(), max_limit, max_unit, s);
}

// The setting groups several joint kinds share (their def members differ).
void set_limit(Joint* j, bool enable, Q32 lower, Q32 upper) {
  j->enable_limit = enable;
  j->lower = lower;
  j->upper = upper;
}
void set_motor(Joint* j, bool enable, Q32 speed, Q32 max_force_or_torque) {
  j->enable_motor = enable;
  j->motor_speed = speed;
  j->max_motor_force = max_force_or_torque;
}
void set_spring(Joint* j, bool enable, Q32 hertz, Q32 damping_ratio) {
  j->enable_spring = enable;
  j->hertz = hertz;
  j->damping_ratio = damping_ratio;
}

}  // namespace

// ---------------------------------------------------------------------------
// Defaults
// ---------------------------------------------------------------------------

RevoluteJointDef default_revolute_joint_def() {
  RevoluteJointDef d{};
  d.internal_cookie = k_def_cookie;
  return d;
}

DistanceJointDef default_distance_joint_def() {
  DistanceJointDef d{};
  d.length = 1_q32;
  d.min_length = 0_q32;
  d.max_length = k_max_joint_length;
  d.internal_cookie = k_def_cookie;
  return d;
}

WeldJointDef default_weld_joint_def() {
  WeldJointDef d{};
  d.internal_cookie = k_def_cookie;
  return d;
}

PrismaticJointDef default_prismatic_joint_def() {
  PrismaticJointDef d{};
  d.local_axis_a = {1_q32, 0_q32};
  d.internal_cookie = k_def_cookie;
  return d;
}

MouseJointDef default_mouse_joint_def() {
  MouseJointDef d{};
  d.hertz = 5_q32;
  d.damping_ratio = 0.7_q32;
  d.max_force = 1000_q32;
  d.internal_cookie = k_def_cookie;
  return d;
}

WheelJointDef default_wheel_joint_def() {
  WheelJointDef d{};
  d.local_axis_a = {0_q32, 1_q32};
  d.enable_spring = true;
  d.hertz = 1_q32;
  d.damping_ratio = 0.7_q32;
  d.internal_cookie = k_def_cookie;
  return d;
}

MotorJointDef default_motor_joint_def() {
  MotorJointDef d{};
  d.max_force = 1_q32;
  d.max_torque = 1_q32;
  d.correction_factor = 0.3_q32;
  d.internal_cookie = k_def_cookie;
  return d;
}

// ---------------------------------------------------------------------------
// Creation
// ---------------------------------------------------------------------------

Result<JointId> create_revolute_joint(WorldId world, const RevoluteJointDef& def) {
  JointCreation c(world, def, "create_revolute_joint", "RevoluteJointDef");
  const char *fn = c.fn, *dn = c.dn;
  Status* s = &c.r.status;
  if (!s->ok() || !check_angle(fn, dn, "reference_angle", def.reference_angle, s) ||
      !check_angle(fn, dn, "lower_angle", def.lower_angle, s) ||
      !check_angle(fn, dn, "upper_angle", def.upper_angle, s) ||
      !check_order(fn, dn, "lower_angle", def.lower_angle, "upper_angle", def.upper_angle, s) ||
      !check_motor(fn, dn, def.motor_speed, k_max_angular_speed, "rad/s", "max_motor_torque", def.max_motor_torque,
                   k_max_joint_torque, "N·m", s) ||
      !check_spring(fn, dn, "hertz", def.hertz, "damping_ratio", def.damping_ratio, s)) {
    return c.r;
  }
  Joint j;
  j.reference_angle = def.reference_angle;
  set_limit(&j, def.enable_limit, def.lower_angle, def.upper_angle);
  set_motor(&j, def.enable_motor, def.motor_speed, def.max_motor_torque);
  set_spring(&j, def.enable_spring, def.hertz, def.damping_ratio);
  return c.add(def.base, JointType::revolute, j);
}

Result<JointId> create_distance_joint(WorldId world, const DistanceJointDef& def) {
  JointCreation c(world, def, "create_distance_joint", "DistanceJointDef");
  const char *fn = c.fn, *dn = c.dn;
  Status* s = &c.r.status;
  if (!s->ok() || !check_range(fn, dn, "length", def.length, k_min_joint_length, k_max_joint_length, "m", s) ||
      !check_range(fn, dn, "max_length", def.max_length, k_min_joint_length, k_max_joint_length, "m", s) ||
      !check_range(fn, dn, "min_length", def.min_length, Q32::zero(), def.max_length, "m", s) ||
      !check_spring(fn, dn, "hertz", def.hertz, "damping_ratio", def.damping_ratio, s) ||
      !check_motor(fn, dn, def.motor_speed, k_max_linear_speed, "m/s", "max_motor_force", def.max_motor_force,
                   k_max_joint_force, "N", s)) {
    return c.r;
  }
  Joint j;
  j.length = def.length;
  set_spring(&j, def.enable_spring, def.hertz, def.damping_ratio);
  set_limit(&j, def.enable_limit, def.min_length, def.max_length);
  set_motor(&j, def.enable_motor, def.motor_speed, def.max_motor_force);
  return c.add(def.base, JointType::distance, j);
}

Result<JointId> create_weld_joint(WorldId world, const WeldJointDef& def) {
  JointCreation c(world, def, "create_weld_joint", "WeldJointDef");
  const char *fn = c.fn, *dn = c.dn;
  Status* s = &c.r.status;
  if (!s->ok() || !check_angle(fn, dn, "reference_angle", def.reference_angle, s) ||
      !check_spring(fn, dn, "linear_hertz", def.linear_hertz, "linear_damping_ratio", def.linear_damping_ratio, s) ||
      !check_spring(fn, dn, "angular_hertz", def.angular_hertz, "angular_damping_ratio", def.angular_damping_ratio,
                    s)) {
    return c.r;
  }
  Joint j;
  j.reference_angle = def.reference_angle;
  j.hertz = def.linear_hertz;
  j.damping_ratio = def.linear_damping_ratio;
  j.angular_hertz = def.angular_hertz;
  j.angular_damping_ratio = def.angular_damping_ratio;
  return c.add(def.base, JointType::weld, j);
}

Result<JointId> create_prismatic_joint(WorldId world, const PrismaticJointDef& def) {
  JointCreation c(world, def, "create_prismatic_joint", "PrismaticJointDef");
  const char *fn = c.fn, *dn = c.dn;
  Status* s = &c.r.status;
  if (!s->ok() || !check_axis(fn, dn, def.local_axis_a, s) || !check_angle(fn, dn, "reference_angle", def.reference_angle, s) ||
      !check_translation_limits(fn, dn, def.lower_translation, def.upper_translation, s) ||
      !check_motor(fn, dn, def.motor_speed, k_max_linear_speed, "m/s", "max_motor_force", def.max_motor_force,
                   k_max_joint_force, "N", s) ||
      !check_spring(fn, dn, "hertz", def.hertz, "damping_ratio", def.damping_ratio, s)) {
    return c.r;
  }
  Joint j;
  j.local_axis_a = normalize(def.local_axis_a);
  j.reference_angle = def.reference_angle;
  set_limit(&j, def.enable_limit, def.lower_translation, def.upper_translation);
  set_motor(&j, def.enable_motor, def.motor_speed, def.max_motor_force);
  set_spring(&j, def.enable_spring, def.hertz, def.damping_ratio);
  return c.add(def.base, JointType::prismatic, j);
}

Result<JointId> create_mouse_joint(WorldId world, const MouseJointDef& def) {
  JointCreation c(world, def, "create_mouse_joint", "MouseJointDef");
  const char *fn = c.fn, *dn = c.dn;
  Status* s = &c.r.status;
  if (!s->ok()) return c.r;
  if (!aabb_contains_point(c.w->def.bounds, def.target)) {
    *s = make_status(StatusCode::invalid_argument, std::string(fn) + ": " + dn + ".target " + format_vec2(def.target) +
                                                      " m is outside the world bounds");
    return c.r;
  }
  if (!check_range(fn, dn, "hertz", def.hertz, Q32::epsilon(), k_max_joint_hertz, "Hz", s) ||
      !check_range(fn, dn, "damping_ratio", def.damping_ratio, Q32::zero(), k_max_joint_damping_ratio, "", s) ||
      !check_range(fn, dn, "max_force", def.max_force, Q32::zero(), k_max_joint_force, "N", s)) {
    return c.r;
  }
  Joint j;
  j.target = def.target;
  j.hertz = def.hertz;
  j.damping_ratio = def.damping_ratio;
  j.max_force = def.max_force;
  return c.add(def.base, JointType::mouse, j);
}

Result<JointId> create_wheel_joint(WorldId world, const WheelJointDef& def) {
  JointCreation c(world, def, "create_wheel_joint", "WheelJointDef");
  const char *fn = c.fn, *dn = c.dn;
  Status* s = &c.r.status;
  if (!s->ok() || !check_axis(fn, dn, def.local_axis_a, s) ||
      !check_spring(fn, dn, "hertz", def.hertz, "damping_ratio", def.damping_ratio, s) ||
      !check_translation_limits(fn, dn, def.lower_translation, def.upper_translation, s) ||
      !check_motor(fn, dn, def.motor_speed, k_max_angular_speed, "rad/s", "max_motor_torque", def.max_motor_torque,
                   k_max_joint_torque, "N·m", s)) {
    return c.r;
  }
  Joint j;
  j.local_axis_a = normalize(def.local_axis_a);
  set_spring(&j, def.enable_spring, def.hertz, def.damping_ratio);
  set_limit(&j, def.enable_limit, def.lower_translation, def.upper_translation);
  set_motor(&j, def.enable_motor, def.motor_speed, def.max_motor_torque);
  return c.add(def.base, JointType::wheel, j);
}

Result<JointId> create_motor_joint(WorldId world, const MotorJointDef& def) {
  JointCreation c(world, def, "create_motor_joint", "MotorJointDef");
  const char *fn = c.fn, *dn = c.dn;
  Status* s = &c.r.status;
  if (!s->ok() || !check_vec(fn, dn, "linear_offset", def.linear_offset, k_max_shape_size, "m", s) ||
      !check_angle(fn, dn, "angular_offset", def.angular_offset, s) ||
      !check_range(fn, dn, "max_force", def.max_force, Q32::zero(), k_max_joint_force, "N", s) ||
      !check_range(fn, dn, "max_torque", def.max_torque, Q32::zero(), k_max_joint_torque, "N·m", s) ||
      !check_range(fn, dn, "correction_factor", def.correction_factor, Q32::zero(), Q32::one(), "", s)) {
    return c.r;
  }
  Joint j;
  j.target = def.linear_offset;
  j.angular_offset = def.angular_offset;
  j.max_force = def.max_force;
  j.max_torque = def.max_torque;
  j.correction_factor = def.correction_factor;
  JointBaseDef base = def.base;
  base.local_anchor_a = {};
  base.local_anchor_b = {};
  return c.add(base, JointType::motor, j);
}

// ---------------------------------------------------------------------------
// Destruction, lookup
// ---------------------------------------------------------------------------

JointId make_joint_id(const World& world, int32_t index) {
  JointId id;
  id.index1 = static_cast<uint32_t>(index) + 1u;
  id.generation = id_pool_generation(world.joint_pool, index);
  id.world = world.id;
  return id;
}

std::string describe(JointId id) {
  if (is_null(id)) return "null joint";
  return "joint {index " + std::to_string(id.index1 - 1) + ", generation " + std::to_string(id.generation) + "}";
}

void free_joint(World* w, int32_t index) {
  joint_at(w, index) = Joint{};
  id_pool_free(&w->joint_pool, index);
}

Status destroy_joint(JointId id) {
  World* w = nullptr;
  int32_t i = 0;
  Status s = resolve_joint(id, "destroy_joint", true, &w, &i);
  if (!s.ok()) return s;
  const Joint j = joint_at(w, i);
  free_joint(w, i);
  rebuild_joint_filter(w);
  wake_body_island(w, j.body_a);
  wake_body_island(w, j.body_b);
  return s;
}

void destroy_body_joints(World* w, int32_t body_index) {
  if (w->joint_pool.alive_count == 0) return;
  const int32_t end = id_pool_capacity(w->joint_pool);
  bool any = false;
  for (int32_t i = 0; i < end; ++i) {
    if (!id_pool_is_alive(w->joint_pool, i)) continue;
    const Joint j = joint_at(w, i);
    if (j.body_a != body_index && j.body_b != body_index) continue;
    JointEvent e;
    e.joint = make_joint_id(*w, i);
    e.body_a = make_body_id(*w, j.body_a);
    e.body_b = make_body_id(*w, j.body_b);
    e.kind = JointEventKind::destroyed_with_body;
    e.user_data = j.user_data;
    w->joints.pending.push_back(e);
    free_joint(w, i);
    wake_body_island(w, j.body_a == body_index ? j.body_b : j.body_a);
    any = true;
  }
  if (any) rebuild_joint_filter(w);
  const size_t room = static_cast<size_t>(w->joint_pool.alive_count) + w->joints.pending.size();
  if (w->joints.events.capacity() < room) w->joints.events.reserve(room * 2);
}

// ---------------------------------------------------------------------------
// Collision filter, events
// ---------------------------------------------------------------------------

namespace {
uint64_t body_pair_key(int32_t a, int32_t b) {
  const uint32_t lo = static_cast<uint32_t>(a < b ? a : b), hi = static_cast<uint32_t>(a < b ? b : a);
  return (uint64_t{lo} << 32) | hi;
}
}  // namespace

void rebuild_joint_filter(World* w) {
  std::vector<uint64_t>& keys = w->joints.no_collide_keys;
  keys.clear();
  const int32_t end = id_pool_capacity(w->joint_pool);
  for (int32_t i = 0; i < end; ++i) {
    if (!id_pool_is_alive(w->joint_pool, i)) continue;
    const Joint& j = w->joints.joints[static_cast<size_t>(i)];
    if (!j.collide_connected) keys.push_back(body_pair_key(j.body_a, j.body_b));
  }
  std::sort(keys.begin(), keys.end());  // integer keys: ties are equal values, so the order is unique
}

bool joint_blocks_collision(const World& w, int32_t body_a, int32_t body_b) {
  const std::vector<uint64_t>& keys = w.joints.no_collide_keys;
  if (keys.empty()) return false;
  return std::binary_search(keys.begin(), keys.end(), body_pair_key(body_a, body_b));
}

Result<std::span<const JointEvent>> world_joint_events(WorldId world) {
  Result<std::span<const JointEvent>> r;
  World* w = nullptr;
  r.status = resolve_world(world, "world_joint_events", false, &w);
  if (!r.ok()) return r;
  r.value = std::span<const JointEvent>(w->joints.events.data(), w->joints.events.size());
  return r;
}

}  // namespace tandem
