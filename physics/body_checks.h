// body_checks.h — internal: the argument checks and accessors shared by the
// body API's translation units (body.cpp, body_motion.cpp). Not installed.
//
// Every check returns true when the value is allowed; otherwise it stores a
// Status naming the function, the value and the allowed range in *out and
// returns false. A check's value name may be a callable that makes the text,
// so a check that passes builds no string (command application allocates
// nothing when it succeeds).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <type_traits>

#include "physics/body.h"
#include "physics/world.h"

namespace tandem::body_checks {

/// A Q32 as decimal text.
inline std::string q32_text(Q32 v) { return to_string(v); }

/// An invalid_argument Status: "function: what why".
inline Status invalid_argument(const char* function, const std::string& what, const std::string& why) {
  return make_status(StatusCode::invalid_argument, std::string(function) + ": " + what + " " + why);
}

/// The body / body sim at a live index.
inline Body& body_at(World* w, int32_t i) { return w->bodies[static_cast<size_t>(i)]; }
inline const Body& body_at(const World* w, int32_t i) { return w->bodies[static_cast<size_t>(i)]; }
inline BodySim& sim_at(World* w, int32_t i) { return w->body_sims[static_cast<size_t>(i)]; }
inline const BodySim& sim_at(const World* w, int32_t i) { return w->body_sims[static_cast<size_t>(i)]; }

/// Refuses a point outside the world bounds.
inline bool check_in_bounds(const World& w, const char* function, const char* what, Vec2 p, Status* out) {
  if (aabb_contains_point(w.def.bounds, p)) return true;
  *out = make_status(StatusCode::invalid_argument,
                     std::string(function) + ": " + what + " " + format_vec2(p) + " m is outside the world bounds [" +
                         format_vec2(w.def.bounds.lower) + ", " + format_vec2(w.def.bounds.upper) + "] m");
  return false;
}

/// The text of a checked value's name: a string, or a callable making it (so
/// that a check that passes builds no text: command application allocates
/// nothing on success).
template <class What>
std::string what_text(const What& what) {
  if constexpr (std::is_invocable_v<const What&>) {
    return what();
  } else {
    return std::string(what);
  }
}

/// Refuses a speed above the world's maximum.
template <class What>
bool check_speed(const World& w, const char* function, const What& what, Vec2 v, Status* out) {
  if (!length_exceeds(v, w.def.max_linear_speed)) return true;
  *out = invalid_argument(function, what_text(what), "is faster than the world's maximum linear speed " +
                                              q32_text(w.def.max_linear_speed) + " m/s");
  return false;
}

/// Refuses |ω| above k_max_angular_speed.
template <class What>
bool check_angular_speed(const char* function, const What& what, Q32 w, Status* out) {
  if (abs(w) <= k_max_angular_speed) return true;
  *out = invalid_argument(function, what_text(what),
                          q32_text(w) + " rad/s is outside [−" + q32_text(k_max_angular_speed) + ", " +
                              q32_text(k_max_angular_speed) + "] rad/s");
  return false;
}

/// Refuses a value outside [lo, hi].
template <class What>
bool check_closed(const char* function, const What& what, Q32 v, Q32 lo, Q32 hi, const char* unit, Status* out) {
  if (lo <= v && v <= hi) return true;
  *out = invalid_argument(function, what_text(what),
                          q32_text(v) + " " + unit + " is outside [" + q32_text(lo) + ", " + q32_text(hi) + "] " + unit);
  return false;
}


}  // namespace tandem::body_checks
