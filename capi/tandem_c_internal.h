// tandem_c_internal.h — what the C API's sources share (not installed):
// the last error, guard()/fill() and the status helpers, the C <-> C++
// struct conversions, the registries of library-owned objects, custom
// filter slots, command conversion. Everything is inline in namespace
// tandem_c_internal (hidden: the version script exports only tandem_*).
#pragma once

#include "tandem_c.h"

#include <cstdlib>
#include <limits>
#include <cstring>
#include <memory>
#include <mutex>
#include <new>
#include <optional>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include "physics/tandem.h"
#include "replay/commands.h"
#include "replay/replay_file.h"
#include "replay/state.h"
#include "replay/synctest.h"
#include "replay/verify.h"
#if TANDEM_C_HAS_SCENES
#include "scene/scene.h"
#endif

using namespace tandem;

namespace tandem_c_internal {

// --- layout checks: the C structs mirror the C++ ones ------------------------
static_assert(sizeof(tandem_world_id) == sizeof(WorldId) && sizeof(tandem_body_id) == sizeof(BodyId) &&
              sizeof(tandem_shape_id) == sizeof(ShapeId) && sizeof(tandem_joint_id) == sizeof(JointId));
static_assert(sizeof(tandem_vec2) == sizeof(Vec2) && sizeof(tandem_rot) == sizeof(Rot));
static_assert(std::is_same_v<tandem_q32, Q32::raw_type> && std::is_same_v<tandem_q16, Q16::raw_type>);
static_assert(TANDEM_MAX_POLYGON_VERTICES == k_max_polygon_vertices);

// --- last error ----------------------------------------------------------------
inline thread_local tandem_status t_code = TANDEM_OK;
inline thread_local std::string t_message;

inline tandem_status fail(tandem_status code, const std::string& message) noexcept {
  t_code = code;
  try {
    t_message = message;
  } catch (...) {
    t_message.clear();  // out of memory while reporting: the code still says what happened
  }
  return code;
}

inline tandem_status succeed() noexcept {
  t_code = TANDEM_OK;
  t_message.clear();
  return TANDEM_OK;
}

inline tandem_status code_of(StatusCode c) {
  switch (c) {
    case StatusCode::ok: return TANDEM_OK;
    case StatusCode::null_handle: return TANDEM_ERROR_NULL_HANDLE;
    case StatusCode::invalid_handle: return TANDEM_ERROR_INVALID_HANDLE;
    case StatusCode::foreign_handle: return TANDEM_ERROR_FOREIGN_HANDLE;
    case StatusCode::world_locked: return TANDEM_ERROR_WORLD_LOCKED;
    case StatusCode::invalid_definition: return TANDEM_ERROR_INVALID_DEFINITION;
    case StatusCode::invalid_argument: return TANDEM_ERROR_INVALID_ARGUMENT;
    case StatusCode::capacity_exceeded: return TANDEM_ERROR_CAPACITY_EXCEEDED;
  }
  return TANDEM_ERROR_INTERNAL;
}

// Records a C++ Status as the last error and returns its code.
inline tandem_status status(const Status& s) { return s.ok() ? succeed() : fail(code_of(s.code), s.message); }

// Runs `body` (returning a tandem_status), turning any exception into one.
template <typename F>
inline tandem_status guard(const char* fn, F&& body) noexcept {
  try {
    return body();
  } catch (const std::bad_alloc&) {
    return fail(TANDEM_ERROR_OUT_OF_MEMORY, std::string(fn) + ": out of memory");
  } catch (const std::exception& e) {
    return fail(TANDEM_ERROR_INTERNAL, std::string(fn) + ": unexpected exception: " + e.what());
  } catch (...) {
    return fail(TANDEM_ERROR_INTERNAL, std::string(fn) + ": unexpected exception");
  }
}

// Runs a getter; any exception gives the default.
template <typename T, typename F>
inline T guard_value(T fallback, F&& body) noexcept {
  try {
    return body();
  } catch (...) {
    return fallback;
  }
}

inline tandem_status null_pointer(const char* fn, const char* param) {
  return fail(TANDEM_ERROR_NULL_POINTER, std::string(fn) + ": " + param + " is NULL");
}

// The buffer rule (tandem_c.h): size query, too small, or copy with `conv`.
template <typename Src, typename Dst, typename Count, typename Conv>
inline tandem_status fill(const char* fn, std::span<const Src> src, Dst* out, Count capacity, Count* out_count, Conv conv) {
  if (out_count == nullptr) return null_pointer(fn, "out_count");
  if constexpr (std::is_signed_v<Count>) {
    if (capacity < 0) {
      return fail(TANDEM_ERROR_INVALID_ARGUMENT, std::string(fn) + ": capacity " + std::to_string(capacity) +
                                                     " is negative");
    }
  }
  if (out == nullptr && capacity != 0) return null_pointer(fn, "the output buffer (with a non-zero capacity)");
  if (src.size() > static_cast<size_t>(std::numeric_limits<Count>::max()))
    return fail(TANDEM_ERROR_CAPACITY_EXCEEDED, std::string(fn) + ": the result does not fit the count type");
  const auto n = static_cast<Count>(src.size());
  *out_count = n;
  if (out == nullptr) return succeed();  // size query
  if (capacity < n) {
    return fail(TANDEM_ERROR_BUFFER_TOO_SMALL, std::string(fn) + ": the buffer holds " + std::to_string(capacity) +
                                                   " elements, the result has " + std::to_string(n));
  }
  for (size_t i = 0; i < src.size(); ++i) out[i] = conv(src[i]);
  return succeed();
}

template <typename T>
inline T same(const T& v) { return v; }

// The text rule (tandem_q32_to_text): *out_length = length without the NUL;
// out NULL with capacity 0 asks only for the length; else the text and its
// NUL must fit.
inline tandem_status copy_text(const char* fn, const std::string& s, char* out, size_t capacity, size_t* out_length) {
  if (out_length == nullptr) return null_pointer(fn, "out_length");
  *out_length = s.size();
  if (out == nullptr && capacity == 0) return succeed();
  if (out == nullptr) return null_pointer(fn, "out_text (with a non-zero capacity)");
  if (capacity < s.size() + 1) {
    return fail(TANDEM_ERROR_BUFFER_TOO_SMALL, std::string(fn) + ": the buffer holds " + std::to_string(capacity) +
                                                   " bytes, the text needs " + std::to_string(s.size() + 1));
  }
  std::memcpy(out, s.c_str(), s.size() + 1);
  return succeed();
}

inline char* dup_text(const std::string& s) {
  char* p = static_cast<char*>(std::malloc(s.size() + 1));
  if (p == nullptr) throw std::bad_alloc();
  std::memcpy(p, s.c_str(), s.size() + 1);
  return p;
}

// --- conversions ----------------------------------------------------------------
inline Q32 q(tandem_q32 raw) { return Q32::from_raw(raw); }
inline Vec2 to_cpp(tandem_vec2 v) { return {q(v.x), q(v.y)}; }
inline tandem_vec2 to_c(Vec2 v) { return {v.x.raw, v.y.raw}; }
inline Rot to_cpp(tandem_rot r) { return {q(r.c), q(r.s)}; }
inline tandem_rot to_c(Rot r) { return {r.c.raw, r.s.raw}; }
inline Transform to_cpp(tandem_transform t) { return {to_cpp(t.p), to_cpp(t.q)}; }
inline tandem_transform to_c(Transform t) { return {to_c(t.p), to_c(t.q)}; }
inline AABB to_cpp(tandem_aabb b) { return {to_cpp(b.lower), to_cpp(b.upper)}; }
inline tandem_aabb to_c(AABB b) { return {to_c(b.lower), to_c(b.upper)}; }
inline tandem_mass_data to_c(const MassData& m) { return {m.mass.raw, to_c(m.center), m.rotational_inertia.raw}; }

inline WorldId to_cpp(tandem_world_id w) { return {w.index1, w.generation}; }
inline tandem_world_id to_c(WorldId w) { return {w.index1, w.generation}; }
inline BodyId to_cpp(tandem_body_id b) { return {b.index1, b.generation, to_cpp(b.world)}; }
inline tandem_body_id to_c(BodyId b) { return {b.index1, b.generation, to_c(b.world)}; }
inline ShapeId to_cpp(tandem_shape_id s) { return {s.index1, s.generation, to_cpp(s.world)}; }
inline tandem_shape_id to_c(ShapeId s) { return {s.index1, s.generation, to_c(s.world)}; }
inline JointId to_cpp(tandem_joint_id j) { return {j.index1, j.generation, to_cpp(j.world)}; }
inline tandem_joint_id to_c(JointId j) { return {j.index1, j.generation, to_c(j.world)}; }

inline Filter to_cpp(const tandem_filter& f) { return {f.category_bits, f.mask_bits, f.group_index}; }
inline tandem_filter to_c(const Filter& f) { return {f.category_bits, f.mask_bits, f.group_index}; }

// --- definitions: one field list per struct for both directions ----------------
// f<ToCpp>(cpp_field, c_field) copies one field C → C++ (ToCpp) or C++ → C;
// map<ToCpp>(cpp_struct, c_struct) lists a struct's fields once (here and in
// tandem_c_joint.cpp, tandem_c_session.cpp); def_to_cpp / def_to_c run it.
template <bool ToCpp>
void f(Q32& a, tandem_q32& b) {
  if constexpr (ToCpp) a = q(b); else b = a.raw;
}
template <bool ToCpp, typename Cpp, typename C>
  requires(std::is_class_v<Cpp> && !std::is_same_v<Cpp, Q32>)
void f(Cpp& a, C& b) {  // Vec2, Rot, AABB, Filter, BodyId: their to_cpp / to_c
  if constexpr (ToCpp) a = to_cpp(b); else b = to_c(a);
}
template <bool ToCpp, typename T>
  requires(std::is_integral_v<T>)
void f(T& a, T& b) {
  if constexpr (ToCpp) a = b; else b = a;
}
template <bool ToCpp, typename E, typename I>
  requires(std::is_enum_v<E> && std::is_integral_v<I>)
void f(E& a, I& b) {  // enums cross as their number
  if constexpr (ToCpp) a = static_cast<E>(b); else b = static_cast<I>(a);
}

template <bool ToCpp, typename T>
void f(T*& a, T*& b) {  // function and context pointers cross unchanged
  if constexpr (ToCpp) a = b; else b = a;
}
// The C callback types are the C++ ones (plain function pointers, no C++ type).
static_assert(std::is_same_v<tandem_task_fn, TaskFunction> && std::is_same_v<tandem_enqueue_task_fn, EnqueueTaskFunction> &&
              std::is_same_v<tandem_finish_task_fn, FinishTaskFunction>);
static_assert(TANDEM_MAX_WORKERS == k_max_workers && TANDEM_STEP_FLAG_TASK_FAILURE == k_step_flag_task_failure);

template <bool D>
void map(WorldDef& a, tandem_world_def& b) {
  f<D>(a.gravity, b.gravity), f<D>(a.sub_step_count, b.sub_step_count);
  f<D>(a.contact_hertz, b.contact_hertz), f<D>(a.contact_damping_ratio, b.contact_damping_ratio);
  f<D>(a.max_contact_push_speed, b.max_contact_push_speed);
  f<D>(a.joint_hertz, b.joint_hertz), f<D>(a.joint_damping_ratio, b.joint_damping_ratio);
  f<D>(a.restitution_threshold, b.restitution_threshold), f<D>(a.hit_event_threshold, b.hit_event_threshold);
  f<D>(a.max_linear_speed, b.max_linear_speed), f<D>(a.bounds, b.bounds);
  f<D>(a.enable_sleep, b.enable_sleep), f<D>(a.enable_continuous, b.enable_continuous);
  f<D>(a.broad_phase, b.broad_phase), f<D>(a.user_data, b.user_data), f<D>(a.internal_cookie, b.internal_cookie);
  f<D>(a.worker_count, b.worker_count), f<D>(a.enqueue_task, b.enqueue_task), f<D>(a.finish_task, b.finish_task);
  f<D>(a.user_task_context, b.user_task_context);
}
template <bool D>
void map(BodyDef& a, tandem_body_def& b) {
  f<D>(a.type, b.type), f<D>(a.position, b.position), f<D>(a.rotation, b.rotation);
  f<D>(a.linear_velocity, b.linear_velocity), f<D>(a.angular_velocity, b.angular_velocity);
  f<D>(a.linear_damping, b.linear_damping), f<D>(a.angular_damping, b.angular_damping);
  f<D>(a.gravity_scale, b.gravity_scale), f<D>(a.user_data, b.user_data);
  f<D>(a.enable_sleep, b.enable_sleep), f<D>(a.is_awake, b.is_awake), f<D>(a.fixed_rotation, b.fixed_rotation);
  f<D>(a.is_bullet, b.is_bullet), f<D>(a.is_enabled, b.is_enabled), f<D>(a.internal_cookie, b.internal_cookie);
}
template <bool D>
void map(ShapeDef& a, tandem_shape_def& b) {
  f<D>(a.friction, b.friction), f<D>(a.restitution, b.restitution), f<D>(a.density, b.density);
  f<D>(a.filter, b.filter), f<D>(a.user_data, b.user_data), f<D>(a.is_sensor, b.is_sensor);
  f<D>(a.enable_hit_events, b.enable_hit_events), f<D>(a.internal_cookie, b.internal_cookie);
}

// C++ → C (padding zeroed) and C → C++ through map().
template <typename C, typename Cpp>
C def_to_c(Cpp a) {
  C b;
  std::memset(&b, 0, sizeof b);
  map<false>(a, b);
  return b;
}
template <typename Cpp, typename C>
Cpp def_to_cpp(C b) {
  Cpp a{};
  map<true>(a, b);
  return a;
}

inline WorldDef to_cpp(const tandem_world_def& d) { return def_to_cpp<WorldDef>(d); }
inline tandem_world_def to_c(const WorldDef& w) { return def_to_c<tandem_world_def>(w); }
inline BodyDef to_cpp(const tandem_body_def& d) { return def_to_cpp<BodyDef>(d); }
inline tandem_body_def to_c(const BodyDef& b) { return def_to_c<tandem_body_def>(b); }
inline ShapeDef to_cpp(const tandem_shape_def& d) { return def_to_cpp<ShapeDef>(d); }
inline tandem_shape_def to_c(const ShapeDef& s) { return def_to_c<tandem_shape_def>(s); }

inline Circle to_cpp(const tandem_circle& c) { return {to_cpp(c.center), q(c.radius)}; }
inline tandem_circle to_c(const Circle& c) { return {to_c(c.center), c.radius.raw}; }
inline Capsule to_cpp(const tandem_capsule& c) { return {to_cpp(c.center1), to_cpp(c.center2), q(c.radius)}; }
inline tandem_capsule to_c(const Capsule& c) { return {to_c(c.center1), to_c(c.center2), c.radius.raw}; }
inline Segment to_cpp(const tandem_segment& s) { return {to_cpp(s.point1), to_cpp(s.point2)}; }
inline tandem_segment to_c(const Segment& s) { return {to_c(s.point1), to_c(s.point2)}; }

inline Polygon to_cpp(const tandem_polygon& p) {
  Polygon o;
  for (int i = 0; i < k_max_polygon_vertices; ++i) {
    o.vertices[static_cast<size_t>(i)] = to_cpp(p.vertices[i]);
    o.normals[static_cast<size_t>(i)] = to_cpp(p.normals[i]);
  }
  o.centroid = to_cpp(p.centroid);
  o.radius = q(p.radius);
  o.count = p.count;
  return o;
}

inline tandem_polygon to_c(const Polygon& p) {
  tandem_polygon o;
  std::memset(&o, 0, sizeof o);
  for (int i = 0; i < k_max_polygon_vertices; ++i) {
    o.vertices[i] = to_c(p.vertices[static_cast<size_t>(i)]);
    o.normals[i] = to_c(p.normals[static_cast<size_t>(i)]);
  }
  o.centroid = to_c(p.centroid);
  o.radius = p.radius.raw;
  o.count = p.count;
  return o;
}

inline ChainSegment to_cpp(const tandem_chain_segment& c) {
  return {to_cpp(c.ghost1), to_cpp(c.segment), to_cpp(c.ghost2), c.chain_id};
}
inline tandem_chain_segment to_c(const ChainSegment& c) {
  return {to_c(c.ghost1), to_c(c.segment), to_c(c.ghost2), c.chain_id};
}

inline tandem_shape_geometry to_c(const ShapeGeometry& g) {
  tandem_shape_geometry o;
  std::memset(&o, 0, sizeof o);
  o.type = static_cast<int32_t>(g.type);
  o.circle = to_c(g.circle);
  o.capsule = to_c(g.capsule);
  o.segment = to_c(g.segment);
  o.polygon = to_c(g.polygon);
  o.chain_segment = to_c(g.chain_segment);
  return o;
}

inline QueryFilter to_cpp(const tandem_query_filter* f) {
  QueryFilter o;
  if (f != nullptr) {
    o.category_bits = f->category_bits;
    o.mask_bits = f->mask_bits;
    o.include_sensors = f->include_sensors;
  }
  return o;
}

inline tandem_ray_hit to_c(const RayHit& h) {
  tandem_ray_hit o;
  std::memset(&o, 0, sizeof o);
  o.shape = to_c(h.shape);
  o.point = to_c(h.point);
  o.normal = to_c(h.normal);
  o.fraction = h.fraction.raw;
  o.hit = h.hit;
  return o;
}

inline tandem_manifold to_c(const Manifold& m) {
  tandem_manifold o;
  std::memset(&o, 0, sizeof o);
  o.normal = to_c(m.normal);
  for (size_t i = 0; i < 2; ++i) {
    const ManifoldPoint& p = m.points[i];
    o.points[i].point = to_c(p.point);
    o.points[i].anchor_a = to_c(p.anchor_a);
    o.points[i].anchor_b = to_c(p.anchor_b);
    o.points[i].separation = p.separation.raw;
    o.points[i].id = p.id;
  }
  o.point_count = m.point_count;
  return o;
}

inline tandem_status geometry(const char* fn, const Status& g) {
  return g.ok() ? succeed() : fail(TANDEM_ERROR_INVALID_ARGUMENT, std::string(fn) + ": " + g.message);
}

// --- registries for library-owned objects ----------------------------------------
template <typename T>
class Registry {
 public:
  explicit Registry(const char* kind) : kind_(kind) {}

  // Adds an object; returns {index1, generation}.
  std::pair<uint32_t, uint32_t> add(std::unique_ptr<T> object) {
    std::lock_guard<std::mutex> lock(mutex_);
    for (size_t i = 0; i < slots_.size(); ++i) {
      if (!slots_[i].object) {
        slots_[i].object = std::move(object);
        return {static_cast<uint32_t>(i + 1), slots_[i].generation};
      }
    }
    slots_.push_back(Slot{1, std::move(object)});
    return {static_cast<uint32_t>(slots_.size()), 1};
  }

  // The object of a handle, or null with the last error set.
  T* get(const char* fn, uint32_t index1, uint32_t generation) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (index1 == 0) {
      fail(TANDEM_ERROR_NULL_HANDLE, std::string(fn) + ": null " + kind_);
      return nullptr;
    }
    if (index1 > slots_.size() || !slots_[index1 - 1].object || slots_[index1 - 1].generation != generation) {
      fail(TANDEM_ERROR_INVALID_HANDLE, std::string(fn) + ": " + kind_ + " {index " + std::to_string(index1 - 1) +
                                            ", generation " + std::to_string(generation) +
                                            "} was destroyed or never existed");
      return nullptr;
    }
    return slots_[index1 - 1].object.get();
  }

  // Destroys the object of a handle (status as get()).
  tandem_status remove(const char* fn, uint32_t index1, uint32_t generation) {
    std::unique_ptr<T> doomed;
    {
      if (get(fn, index1, generation) == nullptr) return t_code;
      std::lock_guard<std::mutex> lock(mutex_);
      Slot& slot = slots_[index1 - 1];
      doomed = std::move(slot.object);
      slot.generation = slot.generation == UINT32_MAX ? 1 : slot.generation + 1;
    }
    return succeed();
  }

 private:
  struct Slot {
    uint32_t generation = 1;
    std::unique_ptr<T> object;
  };
  const char* kind_;
  std::mutex mutex_;
  std::vector<Slot> slots_;
};

struct RecorderObject {
  ReplayRecorder recorder;
};
struct ReplayObject {
  Replay replay;
};
#if TANDEM_C_HAS_SCENES
struct SceneObject {
  scene::Scene scene;
  std::vector<scene::BuiltScene> builds;  // worlds built from it (pruned of dead worlds on each build)
};
#else
struct SceneObject {};
#endif

inline Registry<RecorderObject>& recorders() {
  static Registry<RecorderObject> r("recorder");
  return r;
}
#define TANDEM_C_GET_REPLAY(var, fn, id)                                   \
  ReplayObject* var = replays().get(fn, (id).index1, (id).generation);    \
  if (var == nullptr) return t_code

inline Registry<ReplayObject>& replays() {
  static Registry<ReplayObject> r("replay");
  return r;
}
inline Registry<SceneObject>& scenes() {
  static Registry<SceneObject> r("scene");
  return r;
}

// Custom filters: the C function and context per world slot.
struct FilterSlot {
  tandem_custom_filter_fn fn = nullptr;
  void* context = nullptr;
};
inline FilterSlot g_filters[k_max_worlds + 1];

inline bool filter_trampoline(ShapeId a, ShapeId b, void* context) {
  const auto* slot = static_cast<const FilterSlot*>(context);
  return slot->fn(to_c(a), to_c(b), slot->context);
}

inline JointSpec to_cpp(const tandem_joint_spec& c) {
  JointSpec o;
  o.type = static_cast<JointType>(c.type);
  o.body_a = BodyRef{c.body_a_index, c.body_a_generation};
  o.body_b = BodyRef{c.body_b_index, c.body_b_generation};
  o.local_anchor_a = to_cpp(c.local_anchor_a);
  o.local_anchor_b = to_cpp(c.local_anchor_b);
  o.collide_connected = c.collide_connected;
  o.break_force = q(c.break_force);
  o.break_torque = q(c.break_torque);
  o.user_data = c.user_data;
  o.local_axis = to_cpp(c.local_axis);
  o.reference_angle = q(c.reference_angle);
  o.enable_spring = c.enable_spring;
  o.enable_limit = c.enable_limit;
  o.enable_motor = c.enable_motor;
  o.hertz = q(c.hertz);
  o.damping_ratio = q(c.damping_ratio);
  o.angular_hertz = q(c.angular_hertz);
  o.angular_damping_ratio = q(c.angular_damping_ratio);
  o.length = q(c.length);
  o.lower = q(c.lower);
  o.upper = q(c.upper);
  o.motor_speed = q(c.motor_speed);
  o.motor_force = q(c.motor_force);
  o.target = to_cpp(c.target);
  o.angular_offset = q(c.angular_offset);
  o.max_force = q(c.max_force);
  o.max_torque = q(c.max_torque);
  o.correction_factor = q(c.correction_factor);
  return o;
}

// Converts a C command; a non-ok status names what is wrong.
inline tandem_status command_to_cpp(const char* fn, const tandem_command* c, Command* out) {
  if (c == nullptr) return null_pointer(fn, "command");
  if (c->type < TANDEM_COMMAND_CREATE_BODY || c->type > TANDEM_COMMAND_SET_JOINT_LIMITS || c->type == 13) {
    return fail(TANDEM_ERROR_INVALID_ARGUMENT, std::string(fn) + ": command type " + std::to_string(c->type) +
                                                   " is not 1…12 or 14…19 (TANDEM_COMMAND_*)");
  }
  Command o;
  o.type = static_cast<CommandType>(c->type);
  o.body = BodyRef{c->body_index, c->body_generation};
  o.vector = to_cpp(c->vector);
  o.point = to_cpp(c->point);
  o.at_center = c->at_center;
  o.scalar = q(c->scalar);
  o.rotation = to_cpp(c->rotation);
  o.flag = c->flag;
  o.joint = JointRef{c->joint_index, c->joint_generation};
  o.scalar2 = q(c->scalar2);
  if (o.type == CommandType::create_joint) {
    if (c->joint_spec.type < TANDEM_JOINT_REVOLUTE || c->joint_spec.type > TANDEM_JOINT_MOTOR) {
      return fail(TANDEM_ERROR_INVALID_ARGUMENT, std::string(fn) + ": joint_spec.type " +
                                                     std::to_string(c->joint_spec.type) + " is not 0…6 (TANDEM_JOINT_*)");
    }
    o.joint_spec = to_cpp(c->joint_spec);
  }
  if (o.type == CommandType::create_body) {
    o.body_def = to_cpp(c->body_def);
    if (c->shape_count < 0) return fail(TANDEM_ERROR_INVALID_ARGUMENT, std::string(fn) + ": shape_count is negative");
    if (c->shape_count > 0 && c->shapes == nullptr) return null_pointer(fn, "command.shapes");
    for (int32_t i = 0; i < c->shape_count; ++i) {
      const tandem_shape_spec& s = c->shapes[i];
      if (s.kind < TANDEM_SHAPE_KIND_CIRCLE || s.kind > TANDEM_SHAPE_KIND_CHAIN) {
        return fail(TANDEM_ERROR_INVALID_ARGUMENT, std::string(fn) + ": shapes[" + std::to_string(i) + "].kind " +
                                                       std::to_string(s.kind) + " is not 0…4 (TANDEM_SHAPE_KIND_*)");
      }
      ShapeSpec spec;
      spec.kind = static_cast<ShapeKind>(s.kind);
      spec.def = to_cpp(s.def);
      spec.circle = to_cpp(s.circle);
      spec.capsule = to_cpp(s.capsule);
      spec.segment = to_cpp(s.segment);
      spec.polygon = to_cpp(s.polygon);
      if (s.kind == TANDEM_SHAPE_KIND_CHAIN) {
        if (s.chain_point_count < 0)
          return fail(TANDEM_ERROR_INVALID_ARGUMENT, std::string(fn) + ": chain_point_count is negative");
        if (s.chain_point_count > 0 && s.chain_points == nullptr) return null_pointer(fn, "shapes[i].chain_points");
        for (int32_t k = 0; k < s.chain_point_count; ++k) spec.chain_points.push_back(to_cpp(s.chain_points[k]));
        spec.chain_loop = s.chain_loop;
      }
      o.shapes.push_back(std::move(spec));
    }
  }
  *out = std::move(o);
  return succeed();
}

inline void fill_diff_report(const DiffReport& r, tandem_diff_report* out) {
  std::memset(out, 0, sizeof *out);
  out->error = code_of(r.error.code);
  out->differs = r.differs;
  out->tick = r.tick;
  out->hash_a = r.hash_a;
  out->hash_b = r.hash_b;
  out->located = r.located;
  out->located_tick = r.located_tick;
  std::unique_ptr<char, decltype(&std::free)> diff(dup_text(r.located ? r.difference.describe() : std::string()),
                                                   &std::free);
  out->text = dup_text(format_diff_report(r));
  out->difference_text = diff.release();
  out->ticks_compared = r.ticks_compared;
  out->inputs_differ = r.inputs_differ;
  out->inputs_differ_tick = r.inputs_differ_tick;
  out->length_differs = r.length_differs;
  out->ticks_a = r.ticks_a;
  out->ticks_b = r.ticks_b;
}

}  // namespace tandem_c_internal

// The opaque sinks of tandem_c_replay.h / tandem_c_session.h: views of a C++
// vector, alive during one callback.
struct tandem_command_list {
  std::vector<tandem::Command>* out;
};
struct tandem_bytes {
  std::vector<uint8_t>* out;
};
