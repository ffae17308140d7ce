// tandem_c_core.cpp — the C API (include/tandem_c.h) over the C++ API: status,
// version, numbers, definitions, geometry and worlds. The other parts:
// tandem_c_body.cpp (bodies, shapes, queries, events), tandem_c_joint.cpp,
// tandem_c_replay.cpp (snapshots, commands, recorders, replays, sync test,
// scenes), tandem_c_verify.cpp (decoded states, verify/diff with payload
// handlers), tandem_c_session.cpp; shared helpers in tandem_c_internal.h.
//
// DESIGN. Every entry point is one line of conversion, one call of the C++
// function, one line of conversion back; the only logic here is argument
// checking the C++ API cannot do for a C caller (NULL pointers, buffer
// capacities, handle registries for recorders, replays and scenes) and
// catching every exception at the boundary (guard()). No arithmetic on
// simulation values happens here: a world driven through this file computes
// the same bits as one driven from C++ (capi/tests checks every tick).
//
// Adding a C function for a new C++ one (joints, the world profile, the
// session): declare it in its part of include/tandem_c*.h with a doc comment, convert its structs
// with a to_cpp()/to_c() pair (in tandem_c_internal.h when shared), and write it in the style of its
// neighbours — a getter is one `return to_c(cpp_getter(to_cpp(id)));`, a
// setter `return guard(fn, [&] { return status(cpp_setter(...)); });`, a
// list getter goes through fill(). capi/tests/check_coverage.py fails until a
// test calls it.
//
// Registries. Recorders, loaded replays and loaded scenes are owned here and
// named by {index1, generation} handles like worlds, so a stale or forged
// handle is an error, never a dangling pointer. Rejected: returning opaque
// pointers (a stale pointer cannot be detected, only crashed on).
//
// The last error is thread-local (one code and one std::string per thread).
#include "tandem_c_internal.h"

#include <algorithm>

#ifndef TANDEM_C_VERSION_STRING
#define TANDEM_C_VERSION_STRING "0.0.0"
#endif

using namespace tandem_c_internal;

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
  return guard(fn, [&] { return copy_text(fn, to_string(q(value)), out_text, capacity, out_length); });
}

double tandem_q32_to_double(tandem_q32 value) { return q(value).to_double(); }  // tandem-edge: display only

tandem_rot tandem_rot_identity(void) { return to_c(rot_identity()); }
tandem_rot tandem_rot_from_angle(tandem_q32 angle) { return to_c(rot_from_angle(q(angle))); }
tandem_q32 tandem_rot_angle(tandem_rot rotation) { return rot_angle(to_cpp(rotation)).raw; }
tandem_q32 tandem_vec2_length(tandem_vec2 v) { return length(to_cpp(v)).raw; }
tandem_q32 tandem_vec2_distance(tandem_vec2 a, tandem_vec2 b) { return distance(to_cpp(a), to_cpp(b)).raw; }

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
    const Status g = make_box(q(half_width), q(half_height), &p);
    if (g.ok()) *out_polygon = to_c(p);
    return geometry(fn, g);
  });
}

tandem_status tandem_make_offset_box(tandem_q32 half_width, tandem_q32 half_height, tandem_vec2 center, tandem_q32 angle,
                                     tandem_q32 radius, tandem_polygon* out_polygon) {
  static const char* fn = "tandem_make_offset_box";
  if (out_polygon == nullptr) return null_pointer(fn, "out_polygon");
  return guard(fn, [&] {
    Polygon p;
    const Status g = make_offset_box(q(half_width), q(half_height), to_cpp(center), q(angle), q(radius), &p);
    if (g.ok()) *out_polygon = to_c(p);
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
    const Status g = make_polygon_from_points(pts.data(), count, q(radius), &p);
    if (g.ok()) *out_polygon = to_c(p);
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

tandem_status tandem_world_step_ex(tandem_world_id world, tandem_q32 time_step, tandem_step_result* out_result) {
  return guard("tandem_world_step_ex", [&] {
    if (out_result != nullptr) std::memset(out_result, 0, sizeof *out_result);
    const StepResult r = world_step(to_cpp(world), q(time_step));
    if (out_result != nullptr && r.ok()) {
      out_result->flags = r.flags;
      out_result->task_status = code_of(r.task_status.code);
      const size_t n = std::min(r.task_status.message.size(), sizeof out_result->task_message - 1);
      std::memcpy(out_result->task_message, r.task_status.message.data(), n);
    }
    return status(r.status);
  });
}
tandem_status tandem_world_set_worker_count(tandem_world_id world, int32_t worker_count) {
  return guard("tandem_world_set_worker_count",
               [&] { return status(world_set_worker_count(to_cpp(world), worker_count)); });
}
int32_t tandem_world_worker_count(tandem_world_id world) { return world_worker_count(to_cpp(world)); }
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
  return {c.body_count, c.shape_count, c.solver_body_count, c.step_count, c.arena_capacity, c.joint_count};
}
tandem_world_profile tandem_world_get_profile(tandem_world_id world) {
  const WorldProfile p = world_profile(to_cpp(world));
  return {p.broad_phase_ns, p.narrow_phase_ns, p.islands_ns, p.events_ns, p.prepare_ns, p.integrate_velocities_ns,
          p.warm_start_ns, p.solve_ns, p.integrate_positions_ns, p.relax_ns, p.restitution_ns, p.store_impulses_ns,
          p.continuous_ns, p.finalize_ns, p.total_ns};
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
int32_t tandem_world_broad_phase(tandem_world_id world) {
  return static_cast<int32_t>(world_broad_phase(to_cpp(world)));
}
tandem_broad_phase_stats tandem_world_broad_phase_stats(tandem_world_id world) {
  const BroadPhaseStats s = world_broad_phase_stats(to_cpp(world));
  return {s.proxies, s.candidate_pairs, s.pairs, s.touching_pairs, s.update_nanoseconds};
}
// Deprecated names, kept for one release.
int32_t tandem_world_get_broad_phase(tandem_world_id world) { return tandem_world_broad_phase(world); }
tandem_broad_phase_stats tandem_world_get_broad_phase_stats(tandem_world_id world) {
  return tandem_world_broad_phase_stats(world);
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
