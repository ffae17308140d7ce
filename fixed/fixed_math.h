// fixed_math.h — square roots and trigonometry on Q32.32 and Q16.16, integer
// only. No floating point, no table larger than a few KB.
//
// Accuracy (asserted by tests/fixed/test_fixed_math.cpp: square roots exactly
// in integer arithmetic, the rest against an extended-precision oracle; measured
// maxima are in the README):
//   sqrt, rsqrt   correctly rounded (error ≤ 0.5 raw unit), both formats
//   sin, cos      Q32.32 within 2 raw units; Q16.16 within 1 raw unit
//   atan2         Q32.32 within 2 raw units; Q16.16 within 1 raw unit
// All results are pure functions of the input bits: the same on every
// platform, compiler and 128-bit path (see fixed_math.cpp for the methods).
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

/// floor(√n) of an unsigned 128-bit integer, exact; the result fits 64 bits.
uint64_t isqrt_floor(wide::U128 n);
/// √n of an unsigned 128-bit integer rounded to nearest, exact (no ties occur
/// for integers); saturates at 2^64 − 1 (only for n ≥ (2^64 − ½)²).
uint64_t isqrt_round(wide::U128 n);

/// √x, correctly rounded. x < 0 gives 0 (domain fault).
Q32 sqrt(Q32 x);
/// √x, correctly rounded. x < 0 gives 0 (domain fault).
Q16 sqrt(Q16 x);

/// 1/√x, correctly rounded (error ≤ 0.5 raw unit). Never saturates for
/// x > 0 (the largest result, at x = 2^-32, is 2^16). x ≤ 0 gives max
/// (domain fault).
Q32 rsqrt(Q32 x);
/// 1/√x, correctly rounded (error ≤ 0.5 raw unit). Never saturates for
/// x > 0 (the largest result, at x = 2^-16, is 2^8). x ≤ 0 gives max (domain
/// fault).
Q16 rsqrt(Q16 x);

/// sin and cos of an angle in radians, each within 2 raw units (in practice
/// 0.5 + 2^-10). Any angle: reduced modulo 2π against 2/π held to 94
/// fraction bits, far beyond the output precision. sin(−a) = −sin(a) and
/// cos(−a) = cos(a) exactly; |sin|, |cos| ≤ 1.
SinCos<Q32> sincos(Q32 angle);
/// sin and cos of an angle in radians, each within 1 raw unit (in practice
/// correctly rounded but for ~2^-26 of a unit). Same reduction and symmetry.
SinCos<Q16> sincos(Q16 angle);

/// sin(angle), radians.
inline Q32 sin(Q32 angle) { return sincos(angle).sin; }
/// cos(angle), radians.
inline Q32 cos(Q32 angle) { return sincos(angle).cos; }
/// sin(angle), radians.
inline Q16 sin(Q16 angle) { return sincos(angle).sin; }
/// cos(angle), radians.
inline Q16 cos(Q16 angle) { return sincos(angle).cos; }

/// The angle of (x, y) in radians, in [−π, π], within 2 raw units (in
/// practice 0.5 + 2^-10); any inputs. atan2(0, 0) = 0. Signs of zero do not
/// exist in fixed point: atan2(0, x < 0) = +π. atan2(−y, x) = −atan2(y, x).
Q32 atan2(Q32 y, Q32 x);
/// The angle of (x, y) in radians, in [−π, π], within 1 raw unit; any
/// inputs. atan2(0, 0) = 0; atan2(0, x < 0) = +π.
Q16 atan2(Q16 y, Q16 x);

}  // namespace tandem
