// limits.h — the engine's range and precision limits, in one place.
//
// Q32.32 holds ±2^31 with a resolution of 2^-32, but the solver multiplies
// quantities together (mass × velocity, inertia × angular velocity, lever arm
// × impulse), and a Q32.32 product saturates above 2^31 ≈ 2.1e9. The limits
// below keep every such product at least ~20× inside the range, so a scene
// that respects them never saturates. Geometry (dot, cross, lengths,
// distances) uses exact 128-bit intermediates and is not the binding limit.
//
// The limits are enforced where values enter: shape and body definitions,
// applied forces and impulses, velocities set by the user, scene files. The
// README's "Range and precision" table is generated from this header's
// numbers (keep them in step).
#pragma once

#include <string>

#include "fixed/fixed.h"

namespace tandem {

using namespace tandem::literals;

/// Largest |coordinate| of a body position or shape vertex, m.
inline constexpr Q32 k_max_world_coordinate = 1000000_q32;
/// Largest |linear velocity| component a user may set, m/s.
inline constexpr Q32 k_max_linear_speed = 1000_q32;
/// Largest |angular velocity| a user may set, rad/s.
inline constexpr Q32 k_max_angular_speed = 100_q32;
/// Body mass range, kg.
inline constexpr Q32 k_min_body_mass = 0.001_q32;
inline constexpr Q32 k_max_body_mass = 100000_q32;
/// Largest rotational inertia about the centre of mass, kg·m².
inline constexpr Q32 k_max_rotational_inertia = 1000000_q32;
/// Shape density range, kg/m² (2D densities).
inline constexpr Q32 k_max_density = 100000_q32;
/// Smallest shape feature (radius, half width, edge length), m. The number
/// format itself resolves 2^-32 m ≈ 2.3e-10 m.
inline constexpr Q32 k_min_shape_size = 0.005_q32;
/// Largest shape extent from its body origin, m.
inline constexpr Q32 k_max_shape_size = 10000_q32;

/// Joints (joint.h): largest motor, break and mouse/motor-joint force, N,
/// and torque, N·m; largest spring stiffness, Hz, and damping ratio; the
/// range of distance-joint lengths and prismatic/wheel translations, m.
inline constexpr Q32 k_max_joint_force = 100000000_q32;
inline constexpr Q32 k_max_joint_torque = 100000000_q32;
inline constexpr Q32 k_max_joint_hertz = 10000_q32;
inline constexpr Q32 k_max_joint_damping_ratio = 10000_q32;
inline constexpr Q32 k_min_joint_length = 0.005_q32;
inline constexpr Q32 k_max_joint_length = 10000_q32;

/// Checks lo ≤ value ≤ hi. On failure returns false and writes a message that
/// names the quantity, the value and the range, e.g. "body 3 mass 0.0001 kg
/// is outside [0.001, 100000] kg".
bool check_limit(const std::string& what, Q32 value, Q32 lo, Q32 hi, const char* unit, std::string* out_message);

}  // namespace tandem
