// tandem_c.cpp — the C API (include/tandem_c.h) over the C++ API.
//
// DESIGN. Every entry point is one line of conversion, one call of the C++
// function, one line of conversion back; the only logic here is argument
// checking the C++ API cannot do for a C caller (NULL pointers, buffer
// capacities, handle registries for recorders, replays and scenes) and
// catching every exception at the boundary (guard()). No arithmetic on
// simulation values happens here: a world driven through this file computes
// the same bits as one driven from C++ (tests/capi checks every tick).
//
// Adding a C function for a new C++ one (joints, the world profile, the
// session): declare it in tandem_c.h with a doc comment, convert its structs
// with a to_cpp()/to_c() pair below, and write it in the style of its
// neighbours — a getter is one `return to_c(cpp_getter(to_cpp(id)));`, a
// setter `return guard(fn, [&] { return status(cpp_setter(...)); });`, a
// list getter goes through fill(). tests/capi/check_coverage.py fails until a
// test calls it.
//
// Registries. Recorders, loaded replays and loaded scenes are owned here and
// named by {index1, generation} handles like worlds, so a stale or forged
// handle is an error, never a dangling pointer. Rejected: returning opaque
// pointers (a stale pointer cannot be detected, only crashed on).
//
// The last error is thread-local (one code and one std::string per thread).
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

#ifndef TANDEM_C_VERSION_STRING
#define TANDEM_C_VERSION_STRING "0.0.0"
#endif

using namespace tandem;

namespace {

// --- layout checks: the C structs mirror the C++ ones ------------------------
static_assert(sizeof(tandem_world_id) == sizeof(WorldId) && sizeof(tandem_body_id) == sizeof(BodyId) &&
              sizeof(tandem_shape_id) == sizeof(ShapeId) && sizeof(tandem_joint_id) == sizeof(JointId));
static_assert(sizeof(tandem_vec2) == sizeof(Vec2) && sizeof(tandem_rot) == sizeof(Rot));
static_assert(std::is_same_v<tandem_q32, Q32::raw_type> && std::is_same_v<tandem_q16, Q16::raw_type>);
static_assert(TANDEM_MAX_POLYGON_VERTICES == k_max_polygon_vertices);

// --- last error ----------------------------------------------------------------
thread_local tandem_status t_code = TANDEM_OK;
thread_local std::string t_message;

tandem_status fail(tandem_status code, const std::string& message) noexcept {
  t_code = code;
  try {
    t_message = message;
  } catch (...) {
    t_message.clear();  // out of memory while reporting: the code still says what happened
  }
  return code;
}

tandem_status succeed() noexcept {
  t_code = TANDEM_OK;
  t_message.clear();
  return TANDEM_OK;
}

tandem_status code_of(StatusCode c) {
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
tandem_status status(const Status& s) { return s.ok() ? succeed() : fail(code_of(s.code), s.message); }

// Runs `body` (returning a tandem_status), turning any exception into one.
template <typename F>
tandem_status guard(const char* fn, F&& body) noexcept {
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
T guard_value(T fallback, F&& body) noexcept {
  try {
    return body();
  } catch (...) {
    return fallback;
  }
}

tandem_status null_pointer(const char* fn, const char* param) {
  return fail(TANDEM_ERROR_NULL_POINTER, std::string(fn) + ": " + param + " is NULL");
}

// The buffer rule (tandem_c.h): size query, too small, or copy with `conv`.
template <typename Src, typename Dst, typename Count, typename Conv>
tandem_status fill(const char* fn, std::span<const Src> src, Dst* out, Count capacity, Count* out_count, Conv conv) {
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
T same(const T& v) { return v; }

char* dup_text(const std::string& s) {
  char* p = static_cast<char*>(std::malloc(s.size() + 1));
  if (p == nullptr) throw std::bad_alloc();
  std::memcpy(p, s.c_str(), s.size() + 1);
  return p;
}

// --- conversions ----------------------------------------------------------------
Q32 q(tandem_q32 raw) { return Q32::from_raw(raw); }
Vec2 to_cpp(tandem_vec2 v) { return {q(v.x), q(v.y)}; }
tandem_vec2 to_c(Vec2 v) { return {v.x.raw, v.y.raw}; }
Rot to_cpp(tandem_rot r) { return {q(r.c), q(r.s)}; }
tandem_rot to_c(Rot r) { return {r.c.raw, r.s.raw}; }
Transform to_cpp(tandem_transform t) { return {to_cpp(t.p), to_cpp(t.q)}; }
tandem_transform to_c(Transform t) { return {to_c(t.p), to_c(t.q)}; }
AABB to_cpp(tandem_aabb b) { return {to_cpp(b.lower), to_cpp(b.upper)}; }
tandem_aabb to_c(AABB b) { return {to_c(b.lower), to_c(b.upper)}; }
tandem_mass_data to_c(const MassData& m) { return {m.mass.raw, to_c(m.center), m.rotational_inertia.raw}; }

WorldId to_cpp(tandem_world_id w) { return {w.index1, w.generation}; }
tandem_world_id to_c(WorldId w) { return {w.index1, w.generation}; }
BodyId to_cpp(tandem_body_id b) { return {b.index1, b.generation, to_cpp(b.world)}; }
tandem_body_id to_c(BodyId b) { return {b.index1, b.generation, to_c(b.world)}; }
ShapeId to_cpp(tandem_shape_id s) { return {s.index1, s.generation, to_cpp(s.world)}; }
tandem_shape_id to_c(ShapeId s) { return {s.index1, s.generation, to_c(s.world)}; }

Filter to_cpp(const tandem_filter& f) { return {f.category_bits, f.mask_bits, f.group_index}; }
tandem_filter to_c(const Filter& f) { return {f.category_bits, f.mask_bits, f.group_index}; }

WorldDef to_cpp(const tandem_world_def& d) {
  WorldDef w;
  w.gravity = to_cpp(d.gravity);
  w.sub_step_count = d.sub_step_count;
  w.contact_hertz = q(d.contact_hertz);
  w.contact_damping_ratio = q(d.contact_damping_ratio);
  w.max_contact_push_speed = q(d.max_contact_push_speed);
  w.joint_hertz = q(d.joint_hertz);
  w.joint_damping_ratio = q(d.joint_damping_ratio);
  w.restitution_threshold = q(d.restitution_threshold);
  w.hit_event_threshold = q(d.hit_event_threshold);
  w.max_linear_speed = q(d.max_linear_speed);
  w.bounds = to_cpp(d.bounds);
  w.enable_sleep = d.enable_sleep;
  w.enable_continuous = d.enable_continuous;
  w.broad_phase = static_cast<BroadPhaseKind>(d.broad_phase);
  w.user_data = d.user_data;
  w.internal_cookie = d.internal_cookie;
  return w;
}

tandem_world_def to_c(const WorldDef& w) {
  tandem_world_def d;
  std::memset(&d, 0, sizeof d);
  d.gravity = to_c(w.gravity);
  d.sub_step_count = w.sub_step_count;
  d.contact_hertz = w.contact_hertz.raw;
  d.contact_damping_ratio = w.contact_damping_ratio.raw;
  d.max_contact_push_speed = w.max_contact_push_speed.raw;
  d.joint_hertz = w.joint_hertz.raw;
  d.joint_damping_ratio = w.joint_damping_ratio.raw;
  d.restitution_threshold = w.restitution_threshold.raw;
  d.hit_event_threshold = w.hit_event_threshold.raw;
  d.max_linear_speed = w.max_linear_speed.raw;
  d.bounds = to_c(w.bounds);
  d.enable_sleep = w.enable_sleep;
  d.enable_continuous = w.enable_continuous;
  d.broad_phase = static_cast<int32_t>(w.broad_phase);
  d.user_data = w.user_data;
  d.internal_cookie = w.internal_cookie;
  return d;
}

BodyDef to_cpp(const tandem_body_def& d) {
  BodyDef b;
  b.type = static_cast<BodyType>(d.type);
  b.position = to_cpp(d.position);
  b.rotation = to_cpp(d.rotation);
  b.linear_velocity = to_cpp(d.linear_velocity);
  b.angular_velocity = q(d.angular_velocity);
  b.linear_damping = q(d.linear_damping);
  b.angular_damping = q(d.angular_damping);
  b.gravity_scale = q(d.gravity_scale);
  b.user_data = d.user_data;
  b.enable_sleep = d.enable_sleep;
  b.is_awake = d.is_awake;
  b.fixed_rotation = d.fixed_rotation;
  b.is_bullet = d.is_bullet;
  b.is_enabled = d.is_enabled;
  b.internal_cookie = d.internal_cookie;
  return b;
}

tandem_body_def to_c(const BodyDef& b) {
  tandem_body_def d;
  std::memset(&d, 0, sizeof d);
  d.type = static_cast<int32_t>(b.type);
  d.position = to_c(b.position);
  d.rotation = to_c(b.rotation);
  d.linear_velocity = to_c(b.linear_velocity);
  d.angular_velocity = b.angular_velocity.raw;
  d.linear_damping = b.linear_damping.raw;
  d.angular_damping = b.angular_damping.raw;
  d.gravity_scale = b.gravity_scale.raw;
  d.user_data = b.user_data;
  d.enable_sleep = b.enable_sleep;
  d.is_awake = b.is_awake;
  d.fixed_rotation = b.fixed_rotation;
  d.is_bullet = b.is_bullet;
  d.is_enabled = b.is_enabled;
  d.internal_cookie = b.internal_cookie;
  return d;
}

ShapeDef to_cpp(const tandem_shape_def& d) {
  ShapeDef s;
  s.friction = q(d.friction);
  s.restitution = q(d.restitution);
  s.density = q(d.density);
  s.filter = to_cpp(d.filter);
  s.user_data = d.user_data;
  s.is_sensor = d.is_sensor;
  s.enable_hit_events = d.enable_hit_events;
  s.internal_cookie = d.internal_cookie;
  return s;
}

tandem_shape_def to_c(const ShapeDef& s) {
  tandem_shape_def d;
  std::memset(&d, 0, sizeof d);
  d.friction = s.friction.raw;
  d.restitution = s.restitution.raw;
  d.density = s.density.raw;
  d.filter = to_c(s.filter);
  d.user_data = s.user_data;
  d.is_sensor = s.is_sensor;
  d.enable_hit_events = s.enable_hit_events;
  d.internal_cookie = s.internal_cookie;
  return d;
}

Circle to_cpp(const tandem_circle& c) { return {to_cpp(c.center), q(c.radius)}; }
tandem_circle to_c(const Circle& c) { return {to_c(c.center), c.radius.raw}; }
Capsule to_cpp(const tandem_capsule& c) { return {to_cpp(c.center1), to_cpp(c.center2), q(c.radius)}; }
tandem_capsule to_c(const Capsule& c) { return {to_c(c.center1), to_c(c.center2), c.radius.raw}; }
Segment to_cpp(const tandem_segment& s) { return {to_cpp(s.point1), to_cpp(s.point2)}; }
tandem_segment to_c(const Segment& s) { return {to_c(s.point1), to_c(s.point2)}; }

Polygon to_cpp(const tandem_polygon& p) {
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

tandem_polygon to_c(const Polygon& p) {
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

tandem_chain_segment to_c(const ChainSegment& c) {
  return {to_c(c.ghost1), to_c(c.segment), to_c(c.ghost2), c.chain_id};
}

tandem_shape_geometry to_c(const ShapeGeometry& g) {
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

QueryFilter to_cpp(const tandem_query_filter* f) {
  QueryFilter o;
  if (f != nullptr) {
    o.category_bits = f->category_bits;
    o.mask_bits = f->mask_bits;
    o.include_sensors = f->include_sensors;
  }
  return o;
}

tandem_ray_hit to_c(const RayHit& h) {
  tandem_ray_hit o;
  std::memset(&o, 0, sizeof o);
  o.shape = to_c(h.shape);
  o.point = to_c(h.point);
  o.normal = to_c(h.normal);
  o.fraction = h.fraction.raw;
  o.hit = h.hit;
  return o;
}

tandem_manifold to_c(const Manifold& m) {
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

tandem_status geometry(const char* fn, const GeometryStatus& g) {
  return g.ok ? succeed() : fail(TANDEM_ERROR_INVALID_ARGUMENT, std::string(fn) + ": " + g.message);
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

Registry<RecorderObject>& recorders() {
  static Registry<RecorderObject> r("recorder");
  return r;
}
Registry<ReplayObject>& replays() {
  static Registry<ReplayObject> r("replay");
  return r;
}
Registry<SceneObject>& scenes() {
  static Registry<SceneObject> r("scene");
  return r;
}

// Custom filters: the C function and context per world slot.
struct FilterSlot {
  tandem_custom_filter_fn fn = nullptr;
  void* context = nullptr;
};
FilterSlot g_filters[k_max_worlds + 1];

bool filter_trampoline(ShapeId a, ShapeId b, void* context) {
  const auto* slot = static_cast<const FilterSlot*>(context);
  return slot->fn(to_c(a), to_c(b), slot->context);
}

// Converts a C command; a non-ok status names what is wrong.
tandem_status command_to_cpp(const char* fn, const tandem_command* c, Command* out) {
  if (c == nullptr) return null_pointer(fn, "command");
  if (c->type < TANDEM_COMMAND_CREATE_BODY || c->type > TANDEM_COMMAND_SET_GRAVITY) {
    return fail(TANDEM_ERROR_INVALID_ARGUMENT,
                std::string(fn) + ": command type " + std::to_string(c->type) + " is not 1…12 (TANDEM_COMMAND_*)");
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

void fill_diff_report(const DiffReport& r, tandem_diff_report* out) {
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
}

}  // namespace

// Definitions of the functions tandem_c.h declares extern "C" (they keep C
// linkage from the declaration).

// --- status, version ------------------------------------------------------------
const char* tandem_status_name(tandem_status s) {
  switch (s) {
    case TANDEM_OK: return "ok";
    case TANDEM_ERROR_NULL_HANDLE: return "null handle";
    case TANDEM_ERROR_INVALID_HANDLE: return "invalid handle";
    case TANDEM_ERROR_FOREIGN_HANDLE: return "foreign handle";
    case TANDEM_ERROR_WORLD_LOCKED: return "world locked";
    case TANDEM_ERROR_INVALID_DEFINITION: return "invalid definition";
    case TANDEM_ERROR_INVALID_ARGUMENT: return "invalid argument";
    case TANDEM_ERROR_CAPACITY_EXCEEDED: return "capacity exceeded";
    case TANDEM_ERROR_NULL_POINTER: return "null pointer";
    case TANDEM_ERROR_BUFFER_TOO_SMALL: return "buffer too small";
    case TANDEM_ERROR_PARSE: return "parse error";
    case TANDEM_ERROR_IO: return "i/o error";
    case TANDEM_ERROR_UNSUPPORTED: return "unsupported";
    case TANDEM_ERROR_OUT_OF_MEMORY: return "out of memory";
    case TANDEM_ERROR_INTERNAL: return "internal error";
    default: return "unknown";
  }
}
tandem_status tandem_last_error_code(void) { return t_code; }
const char* tandem_last_error_message(void) { return t_message.c_str(); }
const char* tandem_version_string(void) { return TANDEM_C_VERSION_STRING; }
int32_t tandem_abi_version(void) { return TANDEM_C_ABI_VERSION; }

// --- numbers ---------------------------------------------------------------------
tandem_q32 tandem_q32_from_int(int32_t value) { return Q32::from_int(value).raw; }

tandem_status tandem_q32_from_ratio(int64_t num, int64_t den, tandem_q32* out_value) {
  static const char* fn = "tandem_q32_from_ratio";
  if (out_value == nullptr) return null_pointer(fn, "out_value");
  if (den == 0) return fail(TANDEM_ERROR_INVALID_ARGUMENT, std::string(fn) + ": den is 0");
  const uint64_t an = num < 0 ? 0 - static_cast<uint64_t>(num) : static_cast<uint64_t>(num);
  const uint64_t ad = den < 0 ? 0 - static_cast<uint64_t>(den) : static_cast<uint64_t>(den);
  if (an / ad >= (uint64_t{1} << 31) - 1) {  // range check only; Q32::from_ratio does the arithmetic
    return fail(TANDEM_ERROR_INVALID_ARGUMENT, std::string(fn) + ": " + std::to_string(num) + "/" + std::to_string(den) +
                                                   " is outside ±(2^31 − 1)");
  }
  *out_value = Q32::from_ratio(num, den).raw;
  return succeed();
}

tandem_q32 tandem_q32_from_q16(tandem_q16 value) { return to_q32(Q16::from_raw(value)).raw; }

tandem_status tandem_q32_to_q16(tandem_q32 value, tandem_q16* out_value) {
  static const char* fn = "tandem_q32_to_q16";
  if (out_value == nullptr) return null_pointer(fn, "out_value");
  const uint64_t mag = value < 0 ? 0 - static_cast<uint64_t>(value) : static_cast<uint64_t>(value);
  if (mag > (uint64_t{0x7FFFFFFF} << 16) + 0x7FFF) {  // what to_q16 would saturate
    return guard(fn, [&] {
      return fail(TANDEM_ERROR_INVALID_ARGUMENT, std::string(fn) + ": " + to_string(q(value)) +
                                                     " is outside the Q16.16 range ±32768");
    });
  }
  *out_value = to_q16(q(value)).raw;
  return succeed();
}

tandem_status tandem_q32_from_text(const char* text, tandem_q32* out_value) {
  static const char* fn = "tandem_q32_from_text";
  if (text == nullptr) return null_pointer(fn, "text");
  if (out_value == nullptr) return null_pointer(fn, "out_value");
  return guard(fn, [&] {
    const std::string_view sv(text);
    const FixedParse<Q32> p = parse_q32(sv);
    if (p.error != nullptr) {
      return fail(TANDEM_ERROR_PARSE, std::string(fn) + ": " + describe_parse_error(sv, p.error, p.error_offset));
    }
    *out_value = p.value.raw;
    return succeed();
  });
}

tandem_status tandem_q32_to_text(tandem_q32 value, char* out_text, size_t capacity, size_t* out_length) {
  static const char* fn = "tandem_q32_to_text";
  if (out_length == nullptr) return null_pointer(fn, "out_length");
  return guard(fn, [&] {
    const std::string s = to_string(q(value));
    *out_length = s.size();
    if (out_text == nullptr && capacity == 0) return succeed();
    if (out_text == nullptr) return null_pointer(fn, "out_text (with a non-zero capacity)");
    if (capacity < s.size() + 1) {
      return fail(TANDEM_ERROR_BUFFER_TOO_SMALL, std::string(fn) + ": the buffer holds " + std::to_string(capacity) +
                                                     " bytes, the text needs " + std::to_string(s.size() + 1));
    }
    std::memcpy(out_text, s.c_str(), s.size() + 1);
    return succeed();
  });
}

double tandem_q32_to_double(tandem_q32 value) { return q(value).to_double(); }  // tandem-edge: display only

tandem_rot tandem_rot_identity(void) { return to_c(rot_identity()); }
tandem_rot tandem_rot_from_angle(tandem_q32 angle) { return to_c(rot_from_angle(q(angle))); }
tandem_q32 tandem_rot_angle(tandem_rot rotation) { return rot_angle(to_cpp(rotation)).raw; }

// --- definitions ------------------------------------------------------------------
tandem_world_def tandem_default_world_def(void) { return to_c(default_world_def()); }
tandem_body_def tandem_default_body_def(void) { return to_c(default_body_def()); }
tandem_shape_def tandem_default_shape_def(void) { return to_c(default_shape_def()); }
tandem_filter tandem_default_filter(void) { return to_c(Filter{}); }

// --- geometry ----------------------------------------------------------------------
tandem_status tandem_make_box(tandem_q32 half_width, tandem_q32 half_height, tandem_polygon* out_polygon) {
  static const char* fn = "tandem_make_box";
  if (out_polygon == nullptr) return null_pointer(fn, "out_polygon");
  return guard(fn, [&] {
    Polygon p;
    const GeometryStatus g = make_box(q(half_width), q(half_height), &p);
    if (g.ok) *out_polygon = to_c(p);
    return geometry(fn, g);
  });
}

tandem_status tandem_make_offset_box(tandem_q32 half_width, tandem_q32 half_height, tandem_vec2 center, tandem_q32 angle,
                                     tandem_q32 radius, tandem_polygon* out_polygon) {
  static const char* fn = "tandem_make_offset_box";
  if (out_polygon == nullptr) return null_pointer(fn, "out_polygon");
  return guard(fn, [&] {
    Polygon p;
    const GeometryStatus g = make_offset_box(q(half_width), q(half_height), to_cpp(center), q(angle), q(radius), &p);
    if (g.ok) *out_polygon = to_c(p);
    return geometry(fn, g);
  });
}

tandem_status tandem_make_polygon(const tandem_vec2* points, int32_t count, tandem_q32 radius, tandem_polygon* out_polygon) {
  static const char* fn = "tandem_make_polygon";
  if (out_polygon == nullptr) return null_pointer(fn, "out_polygon");
  if (points == nullptr && count != 0) return null_pointer(fn, "points");
  if (count < 0 || count > k_max_hull_input_points) {
    return fail(TANDEM_ERROR_INVALID_ARGUMENT,
                std::string(fn) + ": count " + std::to_string(count) + " is outside 3…" +
                    std::to_string(k_max_hull_input_points));
  }
  return guard(fn, [&] {
    std::vector<Vec2> pts;
    for (int32_t i = 0; i < count; ++i) pts.push_back(to_cpp(points[i]));
    Polygon p;
    const GeometryStatus g = make_polygon_from_points(pts.data(), count, q(radius), &p);
    if (g.ok) *out_polygon = to_c(p);
    return geometry(fn, g);
  });
}

// --- world ------------------------------------------------------------------------
tandem_status tandem_create_world(const tandem_world_def* def, tandem_world_id* out_world) {
  static const char* fn = "tandem_create_world";
  if (def == nullptr) return null_pointer(fn, "def");
  if (out_world == nullptr) return null_pointer(fn, "out_world");
  return guard(fn, [&] {
    const Result<WorldId> r = create_world(to_cpp(*def));
    if (r.ok()) {
      *out_world = to_c(r.value);
      g_filters[r.value.index1] = FilterSlot{};
    }
    return status(r.status);
  });
}

tandem_status tandem_destroy_world(tandem_world_id world) {
  return guard("tandem_destroy_world", [&] { return status(destroy_world(to_cpp(world))); });
}
bool tandem_world_is_valid(tandem_world_id world) { return world_is_valid(to_cpp(world)); }
tandem_status tandem_world_check(tandem_world_id world) {
  return guard("tandem_world_check", [&] { return status(world_check(to_cpp(world))); });
}

tandem_status tandem_world_step(tandem_world_id world, tandem_q32 time_step, uint32_t* out_flags) {
  return guard("tandem_world_step", [&] {
    const StepResult r = world_step(to_cpp(world), q(time_step));
    if (out_flags != nullptr) *out_flags = r.flags;
    return status(r.status);
  });
}

bool tandem_world_is_locked(tandem_world_id world) { return world_is_locked(to_cpp(world)); }
tandem_world_def tandem_world_get_def(tandem_world_id world) {
  return guard_value(tandem_default_world_def(), [&] { return to_c(world_def(to_cpp(world))); });
}
tandem_vec2 tandem_world_gravity(tandem_world_id world) { return to_c(world_gravity(to_cpp(world))); }
tandem_status tandem_world_set_gravity(tandem_world_id world, tandem_vec2 gravity) {
  return guard("tandem_world_set_gravity", [&] { return status(world_set_gravity(to_cpp(world), to_cpp(gravity))); });
}
tandem_status tandem_world_set_sub_step_count(tandem_world_id world, int32_t n) {
  return guard("tandem_world_set_sub_step_count", [&] { return status(world_set_sub_step_count(to_cpp(world), n)); });
}
tandem_status tandem_world_set_contact_tuning(tandem_world_id world, tandem_q32 hertz, tandem_q32 damping_ratio,
                                              tandem_q32 push_speed) {
  return guard("tandem_world_set_contact_tuning", [&] {
    return status(world_set_contact_tuning(to_cpp(world), q(hertz), q(damping_ratio), q(push_speed)));
  });
}
tandem_status tandem_world_set_joint_tuning(tandem_world_id world, tandem_q32 hertz, tandem_q32 damping_ratio) {
  return guard("tandem_world_set_joint_tuning",
               [&] { return status(world_set_joint_tuning(to_cpp(world), q(hertz), q(damping_ratio))); });
}
tandem_status tandem_world_set_restitution_threshold(tandem_world_id world, tandem_q32 threshold) {
  return guard("tandem_world_set_restitution_threshold",
               [&] { return status(world_set_restitution_threshold(to_cpp(world), q(threshold))); });
}
tandem_status tandem_world_set_hit_event_threshold(tandem_world_id world, tandem_q32 threshold) {
  return guard("tandem_world_set_hit_event_threshold",
               [&] { return status(world_set_hit_event_threshold(to_cpp(world), q(threshold))); });
}
tandem_status tandem_world_set_max_linear_speed(tandem_world_id world, tandem_q32 speed) {
  return guard("tandem_world_set_max_linear_speed",
               [&] { return status(world_set_max_linear_speed(to_cpp(world), q(speed))); });
}
tandem_status tandem_world_enable_sleep(tandem_world_id world, bool enable) {
  return guard("tandem_world_enable_sleep", [&] { return status(world_enable_sleep(to_cpp(world), enable)); });
}
tandem_status tandem_world_enable_continuous(tandem_world_id world, bool enable) {
  return guard("tandem_world_enable_continuous", [&] { return status(world_enable_continuous(to_cpp(world), enable)); });
}
tandem_status tandem_world_set_user_data(tandem_world_id world, uint64_t user_data) {
  return guard("tandem_world_set_user_data", [&] { return status(world_set_user_data(to_cpp(world), user_data)); });
}
uint64_t tandem_world_user_data(tandem_world_id world) { return world_user_data(to_cpp(world)); }
tandem_world_counters tandem_world_get_counters(tandem_world_id world) {
  const WorldCounters c = world_counters(to_cpp(world));
  return {c.body_count, c.shape_count, c.solver_body_count, c.step_count, c.arena_capacity};
}

tandem_status tandem_world_bodies(tandem_world_id world, tandem_body_id* out_bodies, int32_t capacity, int32_t* out_count) {
  static const char* fn = "tandem_world_bodies";
  return guard(fn, [&] {
    const WorldId w = to_cpp(world);
    if (const Status s = world_check(w); !s.ok()) return status(s);
    std::vector<BodyId> ids(static_cast<size_t>(world_bodies(w, nullptr, 0)));
    world_bodies(w, ids.data(), static_cast<int32_t>(ids.size()));
    return fill(fn, std::span<const BodyId>(ids), out_bodies, capacity, out_count, [](BodyId b) { return to_c(b); });
  });
}

tandem_status tandem_world_set_broad_phase(tandem_world_id world, int32_t kind) {
  return guard("tandem_world_set_broad_phase",
               [&] { return status(world_set_broad_phase(to_cpp(world), static_cast<BroadPhaseKind>(kind))); });
}
int32_t tandem_world_get_broad_phase(tandem_world_id world) {
  return static_cast<int32_t>(world_get_broad_phase(to_cpp(world)));
}
tandem_broad_phase_stats tandem_world_get_broad_phase_stats(tandem_world_id world) {
  const BroadPhaseStats s = world_get_broad_phase_stats(to_cpp(world));
  return {s.proxies, s.candidate_pairs, s.pairs, s.touching_pairs, s.update_nanoseconds};
}

tandem_status tandem_world_set_custom_filter(tandem_world_id world, tandem_custom_filter_fn filter, void* context) {
  return guard("tandem_world_set_custom_filter", [&] {
    const WorldId w = to_cpp(world);
    if (const Status s = world_check(w); !s.ok()) return status(s);
    FilterSlot& slot = g_filters[w.index1];  // world_check: 1 ≤ index1 ≤ k_max_worlds
    const Status s = world_set_custom_filter(w, filter != nullptr ? &filter_trampoline : nullptr,
                                             filter != nullptr ? &slot : nullptr);
    if (s.ok()) slot = FilterSlot{filter, context};
    return status(s);
  });
}

// --- bodies -------------------------------------------------------------------------
tandem_status tandem_create_body(tandem_world_id world, const tandem_body_def* def, tandem_body_id* out_body) {
  static const char* fn = "tandem_create_body";
  if (def == nullptr) return null_pointer(fn, "def");
  if (out_body == nullptr) return null_pointer(fn, "out_body");
  return guard(fn, [&] {
    const Result<BodyId> r = create_body(to_cpp(world), to_cpp(*def));
    if (r.ok()) *out_body = to_c(r.value);
    return status(r.status);
  });
}

tandem_status tandem_destroy_body(tandem_body_id body) {
  return guard("tandem_destroy_body", [&] { return status(destroy_body(to_cpp(body))); });
}
bool tandem_body_is_valid(tandem_body_id body) { return body_is_valid(to_cpp(body)); }
tandem_status tandem_body_check(tandem_body_id body, tandem_world_id expected_world) {
  return guard("tandem_body_check", [&] { return status(body_check(to_cpp(body), to_cpp(expected_world))); });
}
tandem_world_id tandem_body_world(tandem_body_id body) { return to_c(body_world(to_cpp(body))); }
int32_t tandem_body_type(tandem_body_id body) { return static_cast<int32_t>(body_type(to_cpp(body))); }
tandem_status tandem_body_set_type(tandem_body_id body, int32_t type) {
  return guard("tandem_body_set_type", [&] { return status(body_set_type(to_cpp(body), static_cast<BodyType>(type))); });
}
tandem_vec2 tandem_body_position(tandem_body_id body) { return to_c(body_position(to_cpp(body))); }
tandem_rot tandem_body_rotation(tandem_body_id body) { return to_c(body_rotation(to_cpp(body))); }
tandem_q32 tandem_body_angle(tandem_body_id body) { return body_angle(to_cpp(body)).raw; }
tandem_transform tandem_body_transform(tandem_body_id body) { return to_c(body_transform(to_cpp(body))); }
tandem_status tandem_body_set_transform(tandem_body_id body, tandem_vec2 position, tandem_rot rotation) {
  return guard("tandem_body_set_transform",
               [&] { return status(body_set_transform(to_cpp(body), to_cpp(position), to_cpp(rotation))); });
}
tandem_vec2 tandem_body_world_center(tandem_body_id body) { return to_c(body_world_center(to_cpp(body))); }
tandem_vec2 tandem_body_local_center(tandem_body_id body) { return to_c(body_local_center(to_cpp(body))); }
tandem_vec2 tandem_body_linear_velocity(tandem_body_id body) { return to_c(body_linear_velocity(to_cpp(body))); }
tandem_status tandem_body_set_linear_velocity(tandem_body_id body, tandem_vec2 velocity) {
  return guard("tandem_body_set_linear_velocity",
               [&] { return status(body_set_linear_velocity(to_cpp(body), to_cpp(velocity))); });
}
tandem_q32 tandem_body_angular_velocity(tandem_body_id body) { return body_angular_velocity(to_cpp(body)).raw; }
tandem_status tandem_body_set_angular_velocity(tandem_body_id body, tandem_q32 w) {
  return guard("tandem_body_set_angular_velocity", [&] { return status(body_set_angular_velocity(to_cpp(body), q(w))); });
}
tandem_vec2 tandem_body_point_velocity(tandem_body_id body, tandem_vec2 p) {
  return to_c(body_point_velocity(to_cpp(body), to_cpp(p)));
}
tandem_status tandem_body_apply_force(tandem_body_id body, tandem_vec2 force, tandem_vec2 point, bool wake) {
  return guard("tandem_body_apply_force",
               [&] { return status(body_apply_force(to_cpp(body), to_cpp(force), to_cpp(point), wake)); });
}
tandem_status tandem_body_apply_force_to_center(tandem_body_id body, tandem_vec2 force, bool wake) {
  return guard("tandem_body_apply_force_to_center",
               [&] { return status(body_apply_force_to_center(to_cpp(body), to_cpp(force), wake)); });
}
tandem_status tandem_body_apply_torque(tandem_body_id body, tandem_q32 torque, bool wake) {
  return guard("tandem_body_apply_torque", [&] { return status(body_apply_torque(to_cpp(body), q(torque), wake)); });
}
tandem_status tandem_body_apply_linear_impulse(tandem_body_id body, tandem_vec2 impulse, tandem_vec2 point, bool wake) {
  return guard("tandem_body_apply_linear_impulse",
               [&] { return status(body_apply_linear_impulse(to_cpp(body), to_cpp(impulse), to_cpp(point), wake)); });
}
tandem_status tandem_body_apply_linear_impulse_to_center(tandem_body_id body, tandem_vec2 impulse, bool wake) {
  return guard("tandem_body_apply_linear_impulse_to_center",
               [&] { return status(body_apply_linear_impulse_to_center(to_cpp(body), to_cpp(impulse), wake)); });
}
tandem_status tandem_body_apply_angular_impulse(tandem_body_id body, tandem_q32 impulse, bool wake) {
  return guard("tandem_body_apply_angular_impulse",
               [&] { return status(body_apply_angular_impulse(to_cpp(body), q(impulse), wake)); });
}
tandem_q32 tandem_body_mass(tandem_body_id body) { return body_mass(to_cpp(body)).raw; }
tandem_q32 tandem_body_rotational_inertia(tandem_body_id body) { return body_rotational_inertia(to_cpp(body)).raw; }
tandem_mass_data tandem_body_mass_data(tandem_body_id body) { return to_c(body_mass_data(to_cpp(body))); }
tandem_q32 tandem_body_linear_damping(tandem_body_id body) { return body_linear_damping(to_cpp(body)).raw; }
tandem_status tandem_body_set_linear_damping(tandem_body_id body, tandem_q32 d) {
  return guard("tandem_body_set_linear_damping", [&] { return status(body_set_linear_damping(to_cpp(body), q(d))); });
}
tandem_q32 tandem_body_angular_damping(tandem_body_id body) { return body_angular_damping(to_cpp(body)).raw; }
tandem_status tandem_body_set_angular_damping(tandem_body_id body, tandem_q32 d) {
  return guard("tandem_body_set_angular_damping", [&] { return status(body_set_angular_damping(to_cpp(body), q(d))); });
}
tandem_q32 tandem_body_gravity_scale(tandem_body_id body) { return body_gravity_scale(to_cpp(body)).raw; }
tandem_status tandem_body_set_gravity_scale(tandem_body_id body, tandem_q32 s) {
  return guard("tandem_body_set_gravity_scale", [&] { return status(body_set_gravity_scale(to_cpp(body), q(s))); });
}
bool tandem_body_is_fixed_rotation(tandem_body_id body) { return body_is_fixed_rotation(to_cpp(body)); }
tandem_status tandem_body_set_fixed_rotation(tandem_body_id body, bool fixed) {
  return guard("tandem_body_set_fixed_rotation", [&] { return status(body_set_fixed_rotation(to_cpp(body), fixed)); });
}
bool tandem_body_is_bullet(tandem_body_id body) { return body_is_bullet(to_cpp(body)); }
tandem_status tandem_body_set_bullet(tandem_body_id body, bool bullet) {
  return guard("tandem_body_set_bullet", [&] { return status(body_set_bullet(to_cpp(body), bullet)); });
}
bool tandem_body_is_enabled(tandem_body_id body) { return body_is_enabled(to_cpp(body)); }
tandem_status tandem_body_enable(tandem_body_id body) {
  return guard("tandem_body_enable", [&] { return status(body_enable(to_cpp(body))); });
}
tandem_status tandem_body_disable(tandem_body_id body) {
  return guard("tandem_body_disable", [&] { return status(body_disable(to_cpp(body))); });
}
bool tandem_body_is_awake(tandem_body_id body) { return body_is_awake(to_cpp(body)); }
tandem_status tandem_body_set_awake(tandem_body_id body, bool awake) {
  return guard("tandem_body_set_awake", [&] { return status(body_set_awake(to_cpp(body), awake)); });
}
bool tandem_body_is_sleep_enabled(tandem_body_id body) { return body_is_sleep_enabled(to_cpp(body)); }
tandem_status tandem_body_enable_sleep(tandem_body_id body, bool enable) {
  return guard("tandem_body_enable_sleep", [&] { return status(body_enable_sleep(to_cpp(body), enable)); });
}
uint64_t tandem_body_user_data(tandem_body_id body) { return body_user_data(to_cpp(body)); }
tandem_status tandem_body_set_user_data(tandem_body_id body, uint64_t user_data) {
  return guard("tandem_body_set_user_data", [&] { return status(body_set_user_data(to_cpp(body), user_data)); });
}
tandem_vec2 tandem_body_world_point(tandem_body_id body, tandem_vec2 p) { return to_c(body_world_point(to_cpp(body), to_cpp(p))); }
tandem_vec2 tandem_body_local_point(tandem_body_id body, tandem_vec2 p) { return to_c(body_local_point(to_cpp(body), to_cpp(p))); }
tandem_vec2 tandem_body_world_vector(tandem_body_id body, tandem_vec2 v) {
  return to_c(body_world_vector(to_cpp(body), to_cpp(v)));
}
tandem_vec2 tandem_body_local_vector(tandem_body_id body, tandem_vec2 v) {
  return to_c(body_local_vector(to_cpp(body), to_cpp(v)));
}
int32_t tandem_body_shape_count(tandem_body_id body) { return body_shape_count(to_cpp(body)); }

tandem_status tandem_body_shapes(tandem_body_id body, tandem_shape_id* out_shapes, int32_t capacity, int32_t* out_count) {
  static const char* fn = "tandem_body_shapes";
  return guard(fn, [&] {
    const BodyId b = to_cpp(body);
    if (const Status s = body_check(b); !s.ok()) return status(s);
    std::vector<ShapeId> ids(static_cast<size_t>(body_shape_count(b)));
    body_shapes(b, ids.data(), static_cast<int32_t>(ids.size()));
    return fill(fn, std::span<const ShapeId>(ids), out_shapes, capacity, out_count, [](ShapeId s) { return to_c(s); });
  });
}

// --- shapes --------------------------------------------------------------------------
namespace {
template <typename CGeom, typename Create>
tandem_status create_shape(const char* fn, const tandem_shape_def* def, const CGeom* geom, tandem_shape_id* out,
                           Create&& create) {
  if (def == nullptr) return null_pointer(fn, "def");
  if (geom == nullptr) return null_pointer(fn, "the geometry");
  if (out == nullptr) return null_pointer(fn, "out_shape");
  return guard(fn, [&] {
    const Result<ShapeId> r = create(to_cpp(*def), to_cpp(*geom));
    if (r.ok()) *out = to_c(r.value);
    return status(r.status);
  });
}
}  // namespace

tandem_status tandem_create_circle_shape(tandem_body_id body, const tandem_shape_def* def, const tandem_circle* circle,
                                         tandem_shape_id* out_shape) {
  return create_shape("tandem_create_circle_shape", def, circle, out_shape,
                      [&](const ShapeDef& d, const Circle& g) { return create_circle_shape(to_cpp(body), d, g); });
}
tandem_status tandem_create_capsule_shape(tandem_body_id body, const tandem_shape_def* def, const tandem_capsule* capsule,
                                          tandem_shape_id* out_shape) {
  return create_shape("tandem_create_capsule_shape", def, capsule, out_shape,
                      [&](const ShapeDef& d, const Capsule& g) { return create_capsule_shape(to_cpp(body), d, g); });
}
tandem_status tandem_create_polygon_shape(tandem_body_id body, const tandem_shape_def* def, const tandem_polygon* polygon,
                                          tandem_shape_id* out_shape) {
  return create_shape("tandem_create_polygon_shape", def, polygon, out_shape,
                      [&](const ShapeDef& d, const Polygon& g) { return create_polygon_shape(to_cpp(body), d, g); });
}
tandem_status tandem_create_segment_shape(tandem_body_id body, const tandem_shape_def* def, const tandem_segment* segment,
                                          tandem_shape_id* out_shape) {
  return create_shape("tandem_create_segment_shape", def, segment, out_shape,
                      [&](const ShapeDef& d, const Segment& g) { return create_segment_shape(to_cpp(body), d, g); });
}

tandem_status tandem_create_chain_shapes(tandem_body_id body, const tandem_shape_def* def, const tandem_vec2* points,
                                         int32_t count, bool loop, tandem_shape_id* out_shapes, int32_t capacity,
                                         int32_t* out_count) {
  static const char* fn = "tandem_create_chain_shapes";
  if (def == nullptr) return null_pointer(fn, "def");
  if (points == nullptr && count != 0) return null_pointer(fn, "points");
  if (out_count == nullptr) return null_pointer(fn, "out_count");
  if (count < 0) return fail(TANDEM_ERROR_INVALID_ARGUMENT, std::string(fn) + ": count is negative");
  if (capacity < 0) return fail(TANDEM_ERROR_INVALID_ARGUMENT, std::string(fn) + ": capacity is negative");
  if (out_shapes == nullptr && capacity != 0) return null_pointer(fn, "out_shapes (with a non-zero capacity)");
  return guard(fn, [&] {
    // The segment count make_chain_segments will produce (checked there too).
    const int32_t needed = loop ? count : (count >= 3 ? count - 3 : 0);
    if (out_shapes != nullptr && capacity < needed) {
      *out_count = needed;
      return fail(TANDEM_ERROR_BUFFER_TOO_SMALL, std::string(fn) + ": the buffer holds " + std::to_string(capacity) +
                                                     " shapes, the chain has " + std::to_string(needed) +
                                                     " segments; nothing was created");
    }
    std::vector<Vec2> pts;
    pts.reserve(static_cast<size_t>(count));
    for (int32_t i = 0; i < count; ++i) pts.push_back(to_cpp(points[i]));
    std::vector<ShapeId> ids;
    const Status s = create_chain_shapes(to_cpp(body), to_cpp(*def), pts.data(), count, loop, &ids);
    if (!s.ok()) return status(s);
    *out_count = static_cast<int32_t>(ids.size());
    if (out_shapes != nullptr)
      for (size_t i = 0; i < ids.size(); ++i) out_shapes[i] = to_c(ids[i]);
    return succeed();
  });
}

tandem_status tandem_destroy_shape(tandem_shape_id shape) {
  return guard("tandem_destroy_shape", [&] { return status(destroy_shape(to_cpp(shape))); });
}
bool tandem_shape_is_valid(tandem_shape_id shape) { return shape_is_valid(to_cpp(shape)); }
tandem_status tandem_shape_check(tandem_shape_id shape, tandem_world_id expected_world) {
  return guard("tandem_shape_check", [&] { return status(shape_check(to_cpp(shape), to_cpp(expected_world))); });
}
int32_t tandem_shape_type(tandem_shape_id shape) { return static_cast<int32_t>(shape_type(to_cpp(shape))); }
tandem_body_id tandem_shape_body(tandem_shape_id shape) { return to_c(shape_body(to_cpp(shape))); }
tandem_shape_geometry tandem_shape_geometry_of(tandem_shape_id shape) { return to_c(shape_geometry(to_cpp(shape))); }
tandem_aabb tandem_shape_aabb(tandem_shape_id shape) { return to_c(shape_aabb(to_cpp(shape))); }
tandem_mass_data tandem_shape_mass_data(tandem_shape_id shape) { return to_c(shape_mass_data(to_cpp(shape))); }
tandem_q32 tandem_shape_friction(tandem_shape_id shape) { return shape_friction(to_cpp(shape)).raw; }
tandem_status tandem_shape_set_friction(tandem_shape_id shape, tandem_q32 v) {
  return guard("tandem_shape_set_friction", [&] { return status(shape_set_friction(to_cpp(shape), q(v))); });
}
tandem_q32 tandem_shape_restitution(tandem_shape_id shape) { return shape_restitution(to_cpp(shape)).raw; }
tandem_status tandem_shape_set_restitution(tandem_shape_id shape, tandem_q32 v) {
  return guard("tandem_shape_set_restitution", [&] { return status(shape_set_restitution(to_cpp(shape), q(v))); });
}
tandem_q32 tandem_shape_density(tandem_shape_id shape) { return shape_density(to_cpp(shape)).raw; }
tandem_status tandem_shape_set_density(tandem_shape_id shape, tandem_q32 v) {
  return guard("tandem_shape_set_density", [&] { return status(shape_set_density(to_cpp(shape), q(v))); });
}
bool tandem_shape_is_sensor(tandem_shape_id shape) { return shape_is_sensor(to_cpp(shape)); }
tandem_filter tandem_shape_filter(tandem_shape_id shape) { return to_c(shape_filter(to_cpp(shape))); }
tandem_status tandem_shape_set_filter(tandem_shape_id shape, tandem_filter filter) {
  return guard("tandem_shape_set_filter", [&] { return status(shape_set_filter(to_cpp(shape), to_cpp(filter))); });
}
uint64_t tandem_shape_user_data(tandem_shape_id shape) { return shape_user_data(to_cpp(shape)); }
tandem_status tandem_shape_set_user_data(tandem_shape_id shape, uint64_t user_data) {
  return guard("tandem_shape_set_user_data", [&] { return status(shape_set_user_data(to_cpp(shape), user_data)); });
}

// --- queries ----------------------------------------------------------------------------
tandem_query_filter tandem_default_query_filter(void) {
  const QueryFilter f;
  tandem_query_filter o;
  std::memset(&o, 0, sizeof o);
  o.category_bits = f.category_bits;
  o.mask_bits = f.mask_bits;
  o.include_sensors = f.include_sensors;
  return o;
}

tandem_status tandem_world_cast_ray_closest(tandem_world_id world, tandem_vec2 origin, tandem_vec2 translation,
                                            const tandem_query_filter* filter, tandem_ray_hit* out_hit) {
  static const char* fn = "tandem_world_cast_ray_closest";
  if (out_hit == nullptr) return null_pointer(fn, "out_hit");
  return guard(fn, [&] {
    const Result<RayHit> r = world_cast_ray_closest(to_cpp(world), to_cpp(origin), to_cpp(translation), to_cpp(filter));
    if (r.ok()) *out_hit = to_c(r.value);
    return status(r.status);
  });
}

tandem_status tandem_world_cast_ray_all(tandem_world_id world, tandem_vec2 origin, tandem_vec2 translation,
                                        const tandem_query_filter* filter, tandem_ray_hit* out_hits, int32_t capacity,
                                        int32_t* out_count) {
  static const char* fn = "tandem_world_cast_ray_all";
  return guard(fn, [&] {
    std::vector<RayHit> hits;
    const Status s = world_cast_ray_all(to_cpp(world), to_cpp(origin), to_cpp(translation), to_cpp(filter), &hits);
    if (!s.ok()) return status(s);
    return fill(fn, std::span<const RayHit>(hits), out_hits, capacity, out_count, [](const RayHit& h) { return to_c(h); });
  });
}

namespace {
// Runs a shape-list query and copies the result (buffer rule).
template <typename Query>
tandem_status shape_query(const char* fn, tandem_shape_id* out, int32_t capacity, int32_t* out_count, Query&& query) {
  return guard(fn, [&] {
    std::vector<ShapeId> ids;
    const Status s = query(&ids);
    if (!s.ok()) return status(s);
    return fill(fn, std::span<const ShapeId>(ids), out, capacity, out_count, [](ShapeId id) { return to_c(id); });
  });
}
}  // namespace

tandem_status tandem_world_overlap_aabb(tandem_world_id world, tandem_aabb box, const tandem_query_filter* filter,
                                        tandem_shape_id* out_shapes, int32_t capacity, int32_t* out_count) {
  return shape_query("tandem_world_overlap_aabb", out_shapes, capacity, out_count, [&](std::vector<ShapeId>* ids) {
    return world_overlap_aabb(to_cpp(world), to_cpp(box), to_cpp(filter), ids);
  });
}
tandem_status tandem_world_overlap_point(tandem_world_id world, tandem_vec2 point, const tandem_query_filter* filter,
                                         tandem_shape_id* out_shapes, int32_t capacity, int32_t* out_count) {
  return shape_query("tandem_world_overlap_point", out_shapes, capacity, out_count, [&](std::vector<ShapeId>* ids) {
    return world_overlap_point(to_cpp(world), to_cpp(point), to_cpp(filter), ids);
  });
}
tandem_status tandem_world_overlap_circle(tandem_world_id world, const tandem_circle* circle, tandem_transform transform,
                                          const tandem_query_filter* filter, tandem_shape_id* out_shapes, int32_t capacity,
                                          int32_t* out_count) {
  if (circle == nullptr) return null_pointer("tandem_world_overlap_circle", "circle");
  return shape_query("tandem_world_overlap_circle", out_shapes, capacity, out_count, [&](std::vector<ShapeId>* ids) {
    return world_overlap_circle(to_cpp(world), to_cpp(*circle), to_cpp(transform), to_cpp(filter), ids);
  });
}
tandem_status tandem_world_overlap_capsule(tandem_world_id world, const tandem_capsule* capsule, tandem_transform transform,
                                           const tandem_query_filter* filter, tandem_shape_id* out_shapes, int32_t capacity,
                                           int32_t* out_count) {
  if (capsule == nullptr) return null_pointer("tandem_world_overlap_capsule", "capsule");
  return shape_query("tandem_world_overlap_capsule", out_shapes, capacity, out_count, [&](std::vector<ShapeId>* ids) {
    return world_overlap_capsule(to_cpp(world), to_cpp(*capsule), to_cpp(transform), to_cpp(filter), ids);
  });
}
tandem_status tandem_world_overlap_polygon(tandem_world_id world, const tandem_polygon* polygon, tandem_transform transform,
                                           const tandem_query_filter* filter, tandem_shape_id* out_shapes, int32_t capacity,
                                           int32_t* out_count) {
  if (polygon == nullptr) return null_pointer("tandem_world_overlap_polygon", "polygon");
  return shape_query("tandem_world_overlap_polygon", out_shapes, capacity, out_count, [&](std::vector<ShapeId>* ids) {
    return world_overlap_polygon(to_cpp(world), to_cpp(*polygon), to_cpp(transform), to_cpp(filter), ids);
  });
}

// --- events --------------------------------------------------------------------------------
tandem_status tandem_world_contact_begin_events(tandem_world_id world, tandem_contact_begin_event* out, int32_t capacity,
                                                int32_t* out_count) {
  static const char* fn = "tandem_world_contact_begin_events";
  return guard(fn, [&] {
    const Result<ContactEvents> r = world_contact_events(to_cpp(world));
    if (!r.ok()) return status(r.status);
    return fill(fn, r.value.begin, out, capacity, out_count, [](const ContactBeginEvent& e) {
      return tandem_contact_begin_event{to_c(e.shape_a), to_c(e.shape_b), to_c(e.manifold)};
    });
  });
}
tandem_status tandem_world_contact_end_events(tandem_world_id world, tandem_contact_end_event* out, int32_t capacity,
                                              int32_t* out_count) {
  static const char* fn = "tandem_world_contact_end_events";
  return guard(fn, [&] {
    const Result<ContactEvents> r = world_contact_events(to_cpp(world));
    if (!r.ok()) return status(r.status);
    return fill(fn, r.value.end, out, capacity, out_count, [](const ContactEndEvent& e) {
      return tandem_contact_end_event{to_c(e.shape_a), to_c(e.shape_b)};
    });
  });
}
tandem_status tandem_world_contact_hit_events(tandem_world_id world, tandem_contact_hit_event* out, int32_t capacity,
                                              int32_t* out_count) {
  static const char* fn = "tandem_world_contact_hit_events";
  return guard(fn, [&] {
    const Result<ContactEvents> r = world_contact_events(to_cpp(world));
    if (!r.ok()) return status(r.status);
    return fill(fn, r.value.hit, out, capacity, out_count, [](const ContactHitEvent& e) {
      return tandem_contact_hit_event{to_c(e.shape_a), to_c(e.shape_b), to_c(e.point), to_c(e.normal),
                                      e.approach_speed.raw};
    });
  });
}
tandem_status tandem_world_sensor_begin_events(tandem_world_id world, tandem_sensor_event* out, int32_t capacity,
                                               int32_t* out_count) {
  static const char* fn = "tandem_world_sensor_begin_events";
  return guard(fn, [&] {
    const Result<SensorEvents> r = world_sensor_events(to_cpp(world));
    if (!r.ok()) return status(r.status);
    return fill(fn, r.value.begin, out, capacity, out_count,
                [](const SensorEvent& e) { return tandem_sensor_event{to_c(e.sensor), to_c(e.visitor)}; });
  });
}
tandem_status tandem_world_sensor_end_events(tandem_world_id world, tandem_sensor_event* out, int32_t capacity,
                                             int32_t* out_count) {
  static const char* fn = "tandem_world_sensor_end_events";
  return guard(fn, [&] {
    const Result<SensorEvents> r = world_sensor_events(to_cpp(world));
    if (!r.ok()) return status(r.status);
    return fill(fn, r.value.end, out, capacity, out_count,
                [](const SensorEvent& e) { return tandem_sensor_event{to_c(e.sensor), to_c(e.visitor)}; });
  });
}
tandem_status tandem_world_body_move_events(tandem_world_id world, tandem_body_move_event* out, int32_t capacity,
                                            int32_t* out_count) {
  static const char* fn = "tandem_world_body_move_events";
  return guard(fn, [&] {
    const Result<BodyEvents> r = world_body_events(to_cpp(world));
    if (!r.ok()) return status(r.status);
    return fill(fn, r.value.move, out, capacity, out_count, [](const BodyMoveEvent& e) {
      tandem_body_move_event o;
      std::memset(&o, 0, sizeof o);
      o.body = to_c(e.body);
      o.transform = to_c(e.transform);
      o.fell_asleep = e.fell_asleep;
      return o;
    });
  });
}

// --- snapshots and hashes ---------------------------------------------------------------------
size_t tandem_world_snapshot_size(tandem_world_id world) {
  return guard_value(size_t{0}, [&] { return world_snapshot_size(to_cpp(world)); });
}

tandem_status tandem_world_snapshot(tandem_world_id world, uint8_t* out_bytes, size_t capacity, size_t* out_size) {
  static const char* fn = "tandem_world_snapshot";
  if (out_size == nullptr) return null_pointer(fn, "out_size");
  if (out_bytes == nullptr && capacity != 0) return null_pointer(fn, "out_bytes (with a non-zero capacity)");
  return guard(fn, [&] {
    const WorldId w = to_cpp(world);
    if (const Status s = world_check(w); !s.ok()) return status(s);
    const size_t needed = world_snapshot_size(w);
    *out_size = needed;
    if (out_bytes == nullptr) return succeed();  // size query
    if (capacity < needed) {
      return fail(TANDEM_ERROR_BUFFER_TOO_SMALL, std::string(fn) + ": the buffer holds " + std::to_string(capacity) +
                                                     " bytes, the snapshot needs " + std::to_string(needed));
    }
    size_t written = 0;
    const Status s = world_snapshot(w, out_bytes, capacity, &written);
    *out_size = written;
    return status(s);
  });
}

tandem_status tandem_world_restore(tandem_world_id world, const uint8_t* bytes, size_t size) {
  static const char* fn = "tandem_world_restore";
  if (bytes == nullptr && size != 0) return null_pointer(fn, "bytes");
  return guard(fn, [&] { return status(world_restore(to_cpp(world), bytes, size)); });
}

tandem_status tandem_create_world_from_snapshot(const uint8_t* bytes, size_t size, tandem_world_id* out_world) {
  static const char* fn = "tandem_create_world_from_snapshot";
  if (bytes == nullptr && size != 0) return null_pointer(fn, "bytes");
  if (out_world == nullptr) return null_pointer(fn, "out_world");
  return guard(fn, [&] {
    const Result<WorldId> r = create_world_from_snapshot(bytes, size);
    if (r.ok()) {
      *out_world = to_c(r.value);
      g_filters[r.value.index1] = FilterSlot{};
    }
    return status(r.status);
  });
}

uint64_t tandem_world_state_hash(tandem_world_id world) {
  return guard_value(uint64_t{0}, [&] { return world_state_hash(to_cpp(world)); });
}
uint64_t tandem_body_state_hash(tandem_body_id body) {
  return guard_value(uint64_t{0}, [&] { return body_state_hash(to_cpp(body)); });
}

tandem_status tandem_world_body_hashes(tandem_world_id world, uint64_t* out_hashes, int32_t capacity, int32_t* out_count) {
  static const char* fn = "tandem_world_body_hashes";
  return guard(fn, [&] {
    std::vector<uint64_t> hashes;
    const Status s = world_body_hashes(to_cpp(world), &hashes);
    if (!s.ok()) return status(s);
    return fill(fn, std::span<const uint64_t>(hashes), out_hashes, capacity, out_count, same<uint64_t>);
  });
}

tandem_status tandem_encode_state_delta(const uint8_t* base, size_t base_size, const uint8_t* image, size_t image_size,
                                        uint8_t* out_delta, size_t capacity, size_t* out_size) {
  static const char* fn = "tandem_encode_state_delta";
  if ((base == nullptr && base_size != 0) || (image == nullptr && image_size != 0)) return null_pointer(fn, "an image");
  return guard(fn, [&] {
    std::vector<uint8_t> delta;
    encode_state_delta(base, base_size, image, image_size, &delta);
    return fill(fn, std::span<const uint8_t>(delta), out_delta, capacity, out_size, same<uint8_t>);
  });
}

tandem_status tandem_apply_state_delta(const uint8_t* base, size_t base_size, const uint8_t* delta, size_t delta_size,
                                       uint8_t* out_image, size_t capacity, size_t* out_size) {
  static const char* fn = "tandem_apply_state_delta";
  if ((base == nullptr && base_size != 0) || (delta == nullptr && delta_size != 0)) return null_pointer(fn, "an input");
  return guard(fn, [&] {
    std::vector<uint8_t> image;
    if (const Status s = apply_state_delta(base, base_size, delta, delta_size, &image); !s.ok()) {
      return fail(TANDEM_ERROR_PARSE, std::string(fn) + ": " + s.message);
    }
    return fill(fn, std::span<const uint8_t>(image), out_image, capacity, out_size, same<uint8_t>);
  });
}

tandem_status tandem_diff_snapshots(const uint8_t* a, size_t a_size, const uint8_t* b, size_t b_size,
                                    tandem_diff_report* out_report) {
  static const char* fn = "tandem_diff_snapshots";
  if (out_report == nullptr) return null_pointer(fn, "out_report");
  std::memset(out_report, 0, sizeof *out_report);
  if ((a == nullptr && a_size != 0) || (b == nullptr && b_size != 0)) return null_pointer(fn, "a snapshot");
  return guard(fn, [&] {
    const DiffReport r = diff_snapshots(std::span<const uint8_t>(a, a_size), std::span<const uint8_t>(b, b_size));
    fill_diff_report(r, out_report);
    return status(r.error);
  });
}

void tandem_free_diff_report(tandem_diff_report* report) {
  if (report == nullptr) return;
  std::free(report->difference_text);
  std::free(report->text);
  std::memset(report, 0, sizeof *report);
}

// --- commands ------------------------------------------------------------------------------------
tandem_command tandem_default_command(int32_t type) {
  tandem_command c;
  std::memset(&c, 0, sizeof c);
  c.type = type;
  c.body_def = tandem_default_body_def();
  c.at_center = true;
  c.rotation = tandem_rot_identity();
  c.flag = true;
  return c;
}

tandem_shape_spec tandem_default_shape_spec(int32_t kind) {
  tandem_shape_spec s;
  std::memset(&s, 0, sizeof s);
  s.kind = kind;
  s.def = tandem_default_shape_def();
  return s;
}

tandem_status tandem_apply_command(tandem_world_id world, const tandem_command* command, tandem_body_id* out_created) {
  static const char* fn = "tandem_apply_command";
  return guard(fn, [&] {
    Command c;
    if (const tandem_status s = command_to_cpp(fn, command, &c); s != TANDEM_OK) return s;
    BodyId created;
    const Status s = apply_command(to_cpp(world), c, &created);
    if (out_created != nullptr) *out_created = to_c(created);
    return status(s);
  });
}

// --- recorders -------------------------------------------------------------------------------------
tandem_recorder_options tandem_default_recorder_options(void) {
  const RecorderOptions o;
  tandem_recorder_options c;
  std::memset(&c, 0, sizeof c);
  c.keyframe_interval = o.keyframe_interval;
  c.record_hashes = o.record_hashes;
  c.flush_every = o.flush_every;
  c.time_step = o.time_step.raw;
  return c;
}

namespace {
RecorderOptions to_cpp(const tandem_recorder_options* o) {
  RecorderOptions r;
  if (o != nullptr) {
    r.keyframe_interval = o->keyframe_interval;
    r.record_hashes = o->record_hashes;
    r.flush_every = o->flush_every;
    r.time_step = q(o->time_step);
  }
  return r;
}

tandem_status add_recorder(std::unique_ptr<RecorderObject> rec, tandem_recorder_id* out) {
  const auto [index1, generation] = recorders().add(std::move(rec));
  *out = tandem_recorder_id{index1, generation};
  return succeed();
}
}  // namespace

tandem_status tandem_recorder_create_memory(const tandem_recorder_options* options, tandem_recorder_id* out_recorder) {
  static const char* fn = "tandem_recorder_create_memory";
  if (out_recorder == nullptr) return null_pointer(fn, "out_recorder");
  return guard(fn, [&] {
    auto rec = std::make_unique<RecorderObject>();
    rec->recorder.open_memory(to_cpp(options));
    return add_recorder(std::move(rec), out_recorder);
  });
}

tandem_status tandem_recorder_create_file(const char* path, const tandem_recorder_options* options,
                                          tandem_recorder_id* out_recorder) {
  static const char* fn = "tandem_recorder_create_file";
  if (path == nullptr) return null_pointer(fn, "path");
  if (out_recorder == nullptr) return null_pointer(fn, "out_recorder");
  return guard(fn, [&] {
    auto rec = std::make_unique<RecorderObject>();
    const Status s = rec->recorder.open_file(path, to_cpp(options));
    if (!s.ok()) return fail(TANDEM_ERROR_IO, std::string(fn) + ": " + s.message);
    return add_recorder(std::move(rec), out_recorder);
  });
}

tandem_status tandem_recorder_destroy(tandem_recorder_id recorder) {
  return guard("tandem_recorder_destroy",
               [&] { return recorders().remove("tandem_recorder_destroy", recorder.index1, recorder.generation); });
}

#define TANDEM_C_GET_RECORDER(fn, id)                                          \
  RecorderObject* rec = recorders().get(fn, (id).index1, (id).generation);    \
  if (rec == nullptr) return t_code

tandem_status tandem_recorder_begin(tandem_recorder_id recorder, tandem_world_id world, const uint8_t* scene,
                                    size_t scene_size) {
  static const char* fn = "tandem_recorder_begin";
  if (scene == nullptr && scene_size != 0) return null_pointer(fn, "scene");
  return guard(fn, [&] {
    TANDEM_C_GET_RECORDER(fn, recorder);
    return status(rec->recorder.begin(to_cpp(world), std::span<const uint8_t>(scene, scene_size)));
  });
}

tandem_status tandem_recorder_submit(tandem_recorder_id recorder, const tandem_command* command) {
  static const char* fn = "tandem_recorder_submit";
  return guard(fn, [&] {
    TANDEM_C_GET_RECORDER(fn, recorder);
    Command c;
    if (const tandem_status s = command_to_cpp(fn, command, &c); s != TANDEM_OK) return s;
    return status(rec->recorder.submit(c));
  });
}

tandem_status tandem_recorder_submit_payload(tandem_recorder_id recorder, const uint8_t* payload, size_t size) {
  static const char* fn = "tandem_recorder_submit_payload";
  if (payload == nullptr && size != 0) return null_pointer(fn, "payload");
  return guard(fn, [&] {
    TANDEM_C_GET_RECORDER(fn, recorder);
    if (size > k_max_user_payload_bytes) {
      return fail(TANDEM_ERROR_INVALID_ARGUMENT, std::string(fn) + ": " + std::to_string(size) + " bytes exceed " +
                                                     std::to_string(k_max_user_payload_bytes));
    }
    rec->recorder.submit_payload(std::vector<uint8_t>(payload, payload + size));
    return succeed();
  });
}

tandem_status tandem_recorder_step(tandem_recorder_id recorder, uint32_t* out_flags) {
  static const char* fn = "tandem_recorder_step";
  return guard(fn, [&] {
    TANDEM_C_GET_RECORDER(fn, recorder);
    const StepResult r = rec->recorder.step();
    if (out_flags != nullptr) *out_flags = r.flags;
    return status(r.status);
  });
}

tandem_status tandem_recorder_finish(tandem_recorder_id recorder) {
  static const char* fn = "tandem_recorder_finish";
  return guard(fn, [&] {
    TANDEM_C_GET_RECORDER(fn, recorder);
    return status(rec->recorder.finish());
  });
}

uint64_t tandem_recorder_tick_count(tandem_recorder_id recorder) {
  return guard_value(uint64_t{0}, [&] {
    const tandem_status saved = t_code;
    const std::string message = t_message;
    RecorderObject* rec = recorders().get("tandem_recorder_tick_count", recorder.index1, recorder.generation);
    t_code = saved;  // getters leave the last error alone
    t_message = message;
    return rec != nullptr ? rec->recorder.tick_count() : 0;
  });
}

uint64_t tandem_recorder_last_hash(tandem_recorder_id recorder) {
  return guard_value(uint64_t{0}, [&] {
    const tandem_status saved = t_code;
    const std::string message = t_message;
    RecorderObject* rec = recorders().get("tandem_recorder_last_hash", recorder.index1, recorder.generation);
    t_code = saved;
    t_message = message;
    return rec != nullptr ? rec->recorder.last_hash() : 0;
  });
}

tandem_status tandem_recorder_memory(tandem_recorder_id recorder, uint8_t* out_bytes, size_t capacity, size_t* out_size) {
  static const char* fn = "tandem_recorder_memory";
  return guard(fn, [&] {
    TANDEM_C_GET_RECORDER(fn, recorder);
    const std::vector<uint8_t>& m = rec->recorder.memory();
    return fill(fn, std::span<const uint8_t>(m), out_bytes, capacity, out_size, same<uint8_t>);
  });
}

// --- replays ------------------------------------------------------------------------------------------
namespace {
tandem_status add_replay(std::unique_ptr<ReplayObject> r, tandem_replay_id* out) {
  const auto [index1, generation] = replays().add(std::move(r));
  *out = tandem_replay_id{index1, generation};
  return succeed();
}

// A getter's replay lookup that leaves the last error alone.
ReplayObject* peek_replay(tandem_replay_id id) {
  const tandem_status saved = t_code;
  const std::string message = t_message;
  ReplayObject* r = replays().get("", id.index1, id.generation);
  t_code = saved;
  t_message = message;
  return r;
}
}  // namespace

tandem_status tandem_replay_load_memory(const uint8_t* bytes, size_t size, tandem_replay_id* out_replay) {
  static const char* fn = "tandem_replay_load_memory";
  if (bytes == nullptr && size != 0) return null_pointer(fn, "bytes");
  if (out_replay == nullptr) return null_pointer(fn, "out_replay");
  return guard(fn, [&] {
    auto r = std::make_unique<ReplayObject>();
    const Status s = read_replay(std::span<const uint8_t>(bytes, size), &r->replay);
    if (!s.ok()) return fail(TANDEM_ERROR_PARSE, std::string(fn) + ": " + s.message);
    return add_replay(std::move(r), out_replay);
  });
}

tandem_status tandem_replay_load_file(const char* path, tandem_replay_id* out_replay) {
  static const char* fn = "tandem_replay_load_file";
  if (path == nullptr) return null_pointer(fn, "path");
  if (out_replay == nullptr) return null_pointer(fn, "out_replay");
  return guard(fn, [&] {
    std::vector<uint8_t> bytes;
    if (const Status s = read_file_bytes(path, &bytes); !s.ok())
      return fail(TANDEM_ERROR_IO, std::string(fn) + ": " + s.message);
    auto r = std::make_unique<ReplayObject>();
    const Status s = read_replay(bytes, &r->replay);
    if (!s.ok()) return fail(TANDEM_ERROR_PARSE, std::string(fn) + ": " + path + ": " + s.message);
    return add_replay(std::move(r), out_replay);
  });
}

tandem_status tandem_replay_destroy(tandem_replay_id replay) {
  return guard("tandem_replay_destroy",
               [&] { return replays().remove("tandem_replay_destroy", replay.index1, replay.generation); });
}

uint64_t tandem_replay_tick_count(tandem_replay_id replay) {
  return guard_value(uint64_t{0}, [&] {
    const ReplayObject* r = peek_replay(replay);
    return r != nullptr ? r->replay.tick_count() : 0;
  });
}

#define TANDEM_C_GET_REPLAY(var, fn, id)                                   \
  ReplayObject* var = replays().get(fn, (id).index1, (id).generation);    \
  if (var == nullptr) return t_code

tandem_status tandem_replay_tick_hash(tandem_replay_id replay, uint64_t tick, uint64_t* out_hash) {
  static const char* fn = "tandem_replay_tick_hash";
  if (out_hash == nullptr) return null_pointer(fn, "out_hash");
  return guard(fn, [&] {
    TANDEM_C_GET_REPLAY(r, fn, replay);
    if (tick < 1 || tick > r->replay.tick_count()) {
      return fail(TANDEM_ERROR_INVALID_ARGUMENT, std::string(fn) + ": tick " + std::to_string(tick) + " is outside 1…" +
                                                     std::to_string(r->replay.tick_count()));
    }
    const TickRecord& t = r->replay.tick_record(tick);
    if (!t.has_hash) {
      return fail(TANDEM_ERROR_INVALID_ARGUMENT, std::string(fn) + ": tick " + std::to_string(tick) + " has no hash");
    }
    *out_hash = t.hash;
    return succeed();
  });
}

tandem_status tandem_replay_create_world_at(tandem_replay_id replay, uint64_t tick, tandem_world_id* out_world) {
  static const char* fn = "tandem_replay_create_world_at";
  if (out_world == nullptr) return null_pointer(fn, "out_world");
  return guard(fn, [&] {
    TANDEM_C_GET_REPLAY(r, fn, replay);
    const Result<WorldId> w = r->replay.create_world_at(tick);
    if (w.ok()) {
      *out_world = to_c(w.value);
      g_filters[w.value.index1] = FilterSlot{};
    }
    return status(w.status);
  });
}

tandem_status tandem_replay_seek(tandem_replay_id replay, tandem_world_id world, uint64_t tick) {
  static const char* fn = "tandem_replay_seek";
  return guard(fn, [&] {
    TANDEM_C_GET_REPLAY(r, fn, replay);
    return status(r->replay.seek(to_cpp(world), tick));
  });
}

tandem_status tandem_verify_replay(tandem_replay_id replay, uint64_t max_ticks, bool locate,
                                   tandem_verify_report* out_report) {
  static const char* fn = "tandem_verify_replay";
  if (out_report == nullptr) return null_pointer(fn, "out_report");
  std::memset(out_report, 0, sizeof *out_report);
  return guard(fn, [&] {
    TANDEM_C_GET_REPLAY(r, fn, replay);
    VerifyOptions options;
    options.max_ticks = max_ticks;
    options.locate = locate;
    const VerifyReport v = verify_replay(r->replay, options);
    tandem_verify_report o;
    std::memset(&o, 0, sizeof o);
    o.error = code_of(v.error.code);
    o.ok = v.ok();
    o.ticks_run = v.ticks_run;
    o.hashes_checked = v.hashes_checked;
    o.keyframes_checked = v.keyframes_checked;
    o.mismatch = v.mismatch;
    o.mismatch_tick = v.mismatch_tick;
    o.expected_hash = v.expected_hash;
    o.actual_hash = v.actual_hash;
    o.located = v.located;
    o.located_tick = v.located_tick;
    o.self_consistent = v.self_consistent;
    std::unique_ptr<char, decltype(&std::free)> diff(dup_text(v.located ? v.difference.describe() : std::string()),
                                                     &std::free);
    o.text = dup_text(format_verify_report(v));
    o.difference_text = diff.release();
    *out_report = o;
    return status(v.error);
  });
}

void tandem_free_verify_report(tandem_verify_report* report) {
  if (report == nullptr) return;
  std::free(report->difference_text);
  std::free(report->text);
  std::memset(report, 0, sizeof *report);
}

tandem_status tandem_diff_replays(tandem_replay_id a, tandem_replay_id b, tandem_diff_report* out_report) {
  static const char* fn = "tandem_diff_replays";
  if (out_report == nullptr) return null_pointer(fn, "out_report");
  std::memset(out_report, 0, sizeof *out_report);
  return guard(fn, [&] {
    TANDEM_C_GET_REPLAY(ra, fn, a);
    TANDEM_C_GET_REPLAY(rb, fn, b);
    const DiffReport r = diff_replays(ra->replay, rb->replay);
    fill_diff_report(r, out_report);
    return status(r.error);
  });
}

// --- sync test -----------------------------------------------------------------------------------------
tandem_synctest_options tandem_default_synctest_options(void) {
  const SyncTestOptions o;
  tandem_synctest_options c;
  std::memset(&c, 0, sizeof c);
  c.ticks = o.ticks;
  c.rollback = o.rollback;
  c.time_step = o.time_step.raw;
  return c;
}

tandem_status tandem_run_synctest(tandem_world_id world, const tandem_synctest_options* options,
                                  tandem_synctest_input_fn inputs, void* context, tandem_synctest_report* out_report) {
  static const char* fn = "tandem_run_synctest";
  if (options == nullptr) return null_pointer(fn, "options");
  if (out_report == nullptr) return null_pointer(fn, "out_report");
  std::memset(out_report, 0, sizeof *out_report);
  return guard(fn, [&] {
    SyncTestOptions o;
    o.ticks = options->ticks;
    o.rollback = options->rollback;
    o.time_step = q(options->time_step);
    SyncTestReport r;
    const Status s = run_synctest(to_cpp(world), o, [&](WorldId w, int64_t tick) {
      if (inputs != nullptr) inputs(to_c(w), tick, context);
    }, &r);
    tandem_synctest_report c;
    std::memset(&c, 0, sizeof c);
    c.passed = r.passed;
    c.ticks_run = r.ticks_run;
    c.resimulated_ticks = r.resimulated_ticks;
    c.first_mismatch_tick = r.first_mismatch_tick;
    c.detected_at_tick = r.detected_at_tick;
    c.expected_hash = r.expected_hash;
    c.actual_hash = r.actual_hash;
    c.message = dup_text(s.ok() ? r.message : s.message);
    *out_report = c;
    return status(s);
  });
}

void tandem_free_synctest_report(tandem_synctest_report* report) {
  if (report == nullptr) return;
  std::free(report->message);
  std::memset(report, 0, sizeof *report);
}

// --- scenes ----------------------------------------------------------------------------------------------
#if TANDEM_C_HAS_SCENES
namespace {
tandem_status add_scene(Result<scene::Scene> loaded, const char* fn, tandem_scene_id* out) {
  if (!loaded.ok()) return fail(TANDEM_ERROR_PARSE, std::string(fn) + ": " + loaded.status.message);
  auto obj = std::make_unique<SceneObject>();
  obj->scene = std::move(loaded.value);
  const auto [index1, generation] = scenes().add(std::move(obj));
  *out = tandem_scene_id{index1, generation};
  return succeed();
}

#define TANDEM_C_GET_SCENE(var, fn, id)                                   \
  SceneObject* var = scenes().get(fn, (id).index1, (id).generation);     \
  if (var == nullptr) return t_code

const scene::BuiltScene* find_build(const SceneObject* s, tandem_world_id world) {
  for (const scene::BuiltScene& b : s->builds)
    if (b.world == to_cpp(world)) return &b;
  return nullptr;
}

tandem_status not_built(const char* fn, tandem_world_id world) {
  return fail(TANDEM_ERROR_INVALID_ARGUMENT,
              std::string(fn) + ": " + describe(to_cpp(world)) + " was not built from this scene (tandem_scene_build)");
}
}  // namespace

tandem_status tandem_scene_load_file(const char* path, tandem_scene_id* out_scene) {
  static const char* fn = "tandem_scene_load_file";
  if (path == nullptr) return null_pointer(fn, "path");
  if (out_scene == nullptr) return null_pointer(fn, "out_scene");
  return guard(fn, [&] { return add_scene(scene::load_scene_file(path), fn, out_scene); });
}

tandem_status tandem_scene_load_text(const char* text, size_t size, const char* name, tandem_scene_id* out_scene) {
  static const char* fn = "tandem_scene_load_text";
  if (text == nullptr && size != 0) return null_pointer(fn, "text");
  if (out_scene == nullptr) return null_pointer(fn, "out_scene");
  return guard(fn, [&] {
    return add_scene(scene::load_scene_text(std::string_view(text, size), name != nullptr ? name : "scene"), fn, out_scene);
  });
}

tandem_status tandem_scene_destroy(tandem_scene_id scene) {
  return guard("tandem_scene_destroy", [&] { return scenes().remove("tandem_scene_destroy", scene.index1, scene.generation); });
}

tandem_status tandem_scene_get_info(tandem_scene_id scene, tandem_scene_info* out_info) {
  static const char* fn = "tandem_scene_get_info";
  if (out_info == nullptr) return null_pointer(fn, "out_info");
  return guard(fn, [&] {
    TANDEM_C_GET_SCENE(s, fn, scene);
    tandem_scene_info i;
    std::memset(&i, 0, sizeof i);
    i.step_hz = s->scene.step_hz;
    i.time_step = s->scene.time_step.raw;
    i.ticks = s->scene.ticks;
    i.body_count = static_cast<int32_t>(s->scene.bodies.size());
    i.input_count = static_cast<int32_t>(s->scene.inputs.size());
    *out_info = i;
    return succeed();
  });
}

tandem_status tandem_scene_build(tandem_scene_id scene, tandem_world_id* out_world) {
  static const char* fn = "tandem_scene_build";
  if (out_world == nullptr) return null_pointer(fn, "out_world");
  return guard(fn, [&] {
    TANDEM_C_GET_SCENE(s, fn, scene);
    std::erase_if(s->builds, [](const scene::BuiltScene& b) { return !world_is_valid(b.world); });
    Result<scene::BuiltScene> built = scene::build_world(s->scene);
    if (!built.ok()) return status(built.status);
    *out_world = to_c(built.value.world);
    g_filters[built.value.world.index1] = FilterSlot{};
    s->builds.push_back(std::move(built.value));
    return succeed();
  });
}

tandem_status tandem_scene_body(tandem_scene_id scene, tandem_world_id world, int32_t index, tandem_body_id* out_body) {
  static const char* fn = "tandem_scene_body";
  if (out_body == nullptr) return null_pointer(fn, "out_body");
  return guard(fn, [&] {
    TANDEM_C_GET_SCENE(s, fn, scene);
    const scene::BuiltScene* b = find_build(s, world);
    if (b == nullptr) return not_built(fn, world);
    if (index < 0 || static_cast<size_t>(index) >= b->bodies.size()) {
      return fail(TANDEM_ERROR_INVALID_ARGUMENT, std::string(fn) + ": body index " + std::to_string(index) +
                                                     " is outside 0…" + std::to_string(b->bodies.size()) + " − 1");
    }
    *out_body = to_c(b->bodies[static_cast<size_t>(index)]);
    return succeed();
  });
}

tandem_status tandem_scene_apply_inputs(tandem_scene_id scene, tandem_world_id world, int64_t tick) {
  static const char* fn = "tandem_scene_apply_inputs";
  return guard(fn, [&] {
    TANDEM_C_GET_SCENE(s, fn, scene);
    const scene::BuiltScene* b = find_build(s, world);
    if (b == nullptr) return not_built(fn, world);
    return status(scene::apply_scene_inputs(*b, s->scene, tick));
  });
}
#else
namespace {
tandem_status no_scenes(const char* fn) {
  return fail(TANDEM_ERROR_UNSUPPORTED, std::string(fn) + ": this build has no scene loader (TANDEM_BUILD_TOOLS=OFF)");
}
}  // namespace
tandem_status tandem_scene_load_file(const char*, tandem_scene_id*) { return no_scenes("tandem_scene_load_file"); }
tandem_status tandem_scene_load_text(const char*, size_t, const char*, tandem_scene_id*) {
  return no_scenes("tandem_scene_load_text");
}
tandem_status tandem_scene_destroy(tandem_scene_id) { return no_scenes("tandem_scene_destroy"); }
tandem_status tandem_scene_get_info(tandem_scene_id, tandem_scene_info*) { return no_scenes("tandem_scene_get_info"); }
tandem_status tandem_scene_build(tandem_scene_id, tandem_world_id*) { return no_scenes("tandem_scene_build"); }
tandem_status tandem_scene_body(tandem_scene_id, tandem_world_id, int32_t, tandem_body_id*) {
  return no_scenes("tandem_scene_body");
}
tandem_status tandem_scene_apply_inputs(tandem_scene_id, tandem_world_id, int64_t) {
  return no_scenes("tandem_scene_apply_inputs");
}
#endif
