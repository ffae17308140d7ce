// fixed_math.h — square roots and trigonometry on Q32.32 and Q16.16, integer
// only. No floating point, no table larger than a few KB.
//
// Accuracy (asserted by tests/fixed/test_fixed_math.cpp against a long double
// oracle; measured maxima are in the README):
//   sqrt          correctly rounded (error ≤ 0.5 raw unit), both formats
//   sin, cos      Q32.32 within 2 raw units; Q16.16 within 1 raw unit
//   atan2         Q32.32 within 2 raw units; Q16.16 within 1 raw unit
// Angles are radians. Domain faults (sqrt of a negative, rsqrt of ≤ 0) return
// a defined value and are reported through TANDEM_FIXED_FAULT.
#pragma once

#include "fixed/fixed.h"

namespace tandem {

/// π, π/2 and 2π, each rounded to nearest.
inline constexpr Q32 k_pi = Q32::from_raw(13493037705);          // round(π·2^32)
inline constexpr Q32 k_half_pi = Q32::from_raw(6746518852);      // round(π/2·2^32)
inline constexpr Q32 k_two_pi = Q32::from_raw(26986075409);      // round(2π·2^32)
inline constexpr Q16 k_pi_q16 = Q16::from_raw(205887);           // round(π·2^16)
inline constexpr Q16 k_half_pi_q16 = Q16::from_raw(102944);      // round(π/2·2^16)
inline constexpr Q16 k_two_pi_q16 = Q16::from_raw(411775);       // round(2π·2^16)

/// A sine and cosine computed together.
template <typename F>
struct SinCos {
  F sin;
  F cos;
};

/// floor(√n) of an unsigned 128-bit integer; the result fits 64 bits.
uint64_t isqrt_floor(wide::U128 n);
/// √n of an unsigned 128-bit integer rounded to nearest (no ties occur for
/// integers); saturates at 2^64 − 1.
uint64_t isqrt_round(wide::U128 n);

/// √x, correctly rounded. x < 0 gives 0 (domain fault).
Q32 sqrt(Q32 x);
/// √x, correctly rounded. x < 0 gives 0 (domain fault).
Q16 sqrt(Q16 x);

/// 1/√x, within 1 raw unit; saturates for tiny x. x ≤ 0 gives max (domain
/// fault).
Q32 rsqrt(Q32 x);
/// 1/√x, within 1 raw unit; saturates for tiny x. x ≤ 0 gives max (domain
/// fault).
Q16 rsqrt(Q16 x);

/// sin and cos of an angle in radians (any value: reduced exactly modulo 2π
/// against a 128-bit π).
SinCos<Q32> sincos(Q32 angle);
/// sin and cos of an angle in radians.
SinCos<Q16> sincos(Q16 angle);

/// sin(angle), radians.
inline Q32 sin(Q32 angle) { return sincos(angle).sin; }
/// cos(angle), radians.
inline Q32 cos(Q32 angle) { return sincos(angle).cos; }
/// sin(angle), radians.
inline Q16 sin(Q16 angle) { return sincos(angle).sin; }
/// cos(angle), radians.
inline Q16 cos(Q16 angle) { return sincos(angle).cos; }

/// The angle of (x, y) in radians, in [−π, π]; atan2(0, 0) = 0. Signs of zero
/// do not exist in fixed point: atan2(0, x < 0) = +π.
Q32 atan2(Q32 y, Q32 x);
/// The angle of (x, y) in radians, in [−π, π]; atan2(0, 0) = 0.
Q16 atan2(Q16 y, Q16 x);

}  // namespace tandem
