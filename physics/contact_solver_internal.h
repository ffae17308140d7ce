// contact_solver_internal.h — what the scalar contact solver
// (contact_solver.cpp) and its lane kernels (contact_lanes.cpp) share: the
// block size of the parallel loops, the in-range arithmetic, the two
// arithmetic policies of the inner loops, and the small body helpers.
// Internal: not installed, included only by those two files.
#pragma once

#include <cstdint>

#include "physics/contact_lanes.h"
#include "physics/fast_math.h"
#include "physics/world.h"

namespace tandem::contact_internal {

/// Constraints per block of the parallel loops (fixed: block boundaries
/// never depend on the worker count).
constexpr int32_t k_constraint_block = 32;

/// Loads a constraint's body: the solver state, or a zero-velocity dummy at
/// the origin with the identity rotation (writes to it leave it unchanged
/// because the inverse masses are zero).
inline BodyState* body_state(BodyState* states, int32_t index, BodyState* dummy) {
  return index >= 0 ? &states[index] : dummy;
}

// In-range arithmetic for the inner loops (solve, relax, warm start). Within
// the limits of limits.h every quantity here should stay far inside the
// Q32.32 range (see "Arithmetic" above; before the inertia bound the
// random-world stress, seeds 94, 55, 9, reached it). In release
// builds with a native 128-bit type these helpers skip the fault reports and
// sum products in one 128-bit value, with the same rounding (nearest, ties
// away from zero) and the same saturation as the checked operators, so the
// same bits in every build, in range or not. Debug and sanitizer builds (no
// NDEBUG) use the checked operators, which also report the fault.
namespace in_range {
#if TANDEM_HAS_INT128 && defined(NDEBUG)
// fast_math.h's helpers: same rounding and saturation as the checked
// operators, no fault report.
using fast::product;
using fast::round_shift;
using fast::u128;
inline Q32 mul(Q32 a, Q32 b) { return fast::mul(a, b); }
inline Q32 add(Q32 a, Q32 b) { return fast::add(a, b); }
inline Q32 sub(Q32 a, Q32 b) { return fast::sub(a, b); }
/// a·b + c·d, rounded once.
inline Q32 sum2(Q32 a, Q32 b, Q32 c, Q32 d) { return round_shift(product(a.raw, b.raw) + product(c.raw, d.raw)); }
/// a·b + c·d + e·f + g·h, rounded once.
inline Q32 sum4(Q32 a, Q32 b, Q32 c, Q32 d, Q32 e, Q32 f, Q32 g, Q32 h) {
  return round_shift(product(a.raw, b.raw) + product(c.raw, d.raw) + product(e.raw, f.raw) + product(g.raw, h.raw));
}
#else
inline Q32 mul(Q32 a, Q32 b) { return a * b; }
inline Q32 add(Q32 a, Q32 b) { return a + b; }
inline Q32 sub(Q32 a, Q32 b) { return a - b; }
inline Q32 sum2(Q32 a, Q32 b, Q32 c, Q32 d) { return detail::sum_products(a.raw, b.raw, c.raw, d.raw, "contact solve"); }
inline Q32 sum4(Q32 a, Q32 b, Q32 c, Q32 d, Q32 e, Q32 f, Q32 g, Q32 h) {
  const wide::U128 sum = wide::add(wide::add(wide::mul_s64(a.raw, b.raw), wide::mul_s64(c.raw, d.raw)),
                                   wide::add(wide::mul_s64(e.raw, f.raw), wide::mul_s64(g.raw, h.raw)));
  bool overflow = false;
  const int64_t r = wide::round_shift_saturate(sum, 32, &overflow);
  if (overflow) TANDEM_FIXED_FAULT(FixedFault::overflow, "contact relative velocity");
  return Q32::from_raw(r);
}
#endif
inline Q32 neg(Q32 a) { return sub(Q32::zero(), a); }
inline Vec2 add(Vec2 a, Vec2 b) { return {add(a.x, b.x), add(a.y, b.y)}; }
inline Vec2 sub(Vec2 a, Vec2 b) { return {sub(a.x, b.x), sub(a.y, b.y)}; }
inline Q32 dot(Vec2 a, Vec2 b) { return sum2(a.x, b.x, a.y, b.y); }
/// v rotated by q, each component rounded once (vec2.h's rotate).
inline Vec2 rotate(Rot q, Vec2 v) { return {sum2(q.c, v.x, neg(q.s), v.y), sum2(q.s, v.x, q.c, v.y)}; }
}  // namespace in_range

/// The arithmetic of solve_constraint and warm start, two ways. SaturatingOps: the in_range
/// helpers (the same bits in every build, saturating where the checked
/// operators do). WrappingOps (below): the same products and roundings with
/// no saturation test at all, plus a conservative witness that tells
/// afterwards whether any operation might have saturated.
struct SaturatingOps {
  static Q32 mul(Q32 a, Q32 b) { return in_range::mul(a, b); }
  static Q32 add(Q32 a, Q32 b) { return in_range::add(a, b); }
  static Q32 sub(Q32 a, Q32 b) { return in_range::sub(a, b); }
  static Q32 sum2(Q32 a, Q32 b, Q32 c, Q32 d) { return in_range::sum2(a, b, c, d); }
  static Q32 sum4(Q32 a, Q32 b, Q32 c, Q32 d, Q32 e, Q32 f, Q32 g, Q32 h) {
    return in_range::sum4(a, b, c, d, e, f, g, h);
  }
  static void vet(Q32) {}
  static bool clean() { return true; }
};

#if TANDEM_FAST_MATH_UNCHECKED && !TANDEM_FIXED_CHECKS
#define TANDEM_CONTACT_WRAP_FIRST 1
/// Wrapping arithmetic with a saturation witness (release builds with a
/// native 128-bit type and no fault reports). Each rounding is fast::
/// round_shift's in-range formula without its test; each add/sub wraps.
/// What it records, branch-free (an OR per operation):
///   wide   |= hi + 2^29 for each rounded 128-bit sum p (hi = p >> 64):
///          no bit ≥ 30 set ⇔ −2^93 ≤ p < 2^93, so the result is exact
///          round-to-nearest, |result| ≤ 2^61, and far from the
///          saturation threshold 2^95 − 2^31;
///   narrow |= r + 2^62 for each add/sub result r and each vetted operand:
///          bit 63 clear ⇔ −2^62 ≤ r < 2^62.
/// The proof that clean() means "the same bits as SaturatingOps": every
/// add/sub operand is a vetted input, a rounded result (|x| ≤ 2^61), an
/// earlier add/sub result (both: −2^62 ≤ x < 2^62) or a min/max/clamp of
/// those, so the exact sum lies in [−2^63, 2^63): no wrap; its one value
/// that saturates, the raw minimum −2^63, fails the result test. So every
/// add/sub with a clear witness is one where fixed.h's operator+/− does not
/// saturate (neg(x) = 0 − x
/// needs no vetted operand: its only saturating input, the raw minimum,
/// wraps to itself and is caught by the result test). Every rounding with
/// a clear witness is below the saturation threshold. A set witness may be
/// a false alarm (it is conservative); the caller then discards the result
/// and runs SaturatingOps.
struct WrappingOps {
  uint64_t wide = 0;
  uint64_t narrow = 0;
  Q32 round(fast::u128 sum) {
    const uint64_t hi = static_cast<uint64_t>(sum >> 64);
    wide |= hi + (uint64_t{1} << 29);
    return Q32::from_raw(fast::round_shift_words(static_cast<uint64_t>(sum), hi));
  }
  Q32 wrapped(uint64_t r) {
    narrow |= r + (uint64_t{1} << 62);
    return Q32::from_raw(static_cast<int64_t>(r));
  }
  Q32 mul(Q32 a, Q32 b) { return round(fast::product(a.raw, b.raw)); }
  Q32 add(Q32 a, Q32 b) { return wrapped(static_cast<uint64_t>(a.raw) + static_cast<uint64_t>(b.raw)); }
  Q32 sub(Q32 a, Q32 b) { return wrapped(static_cast<uint64_t>(a.raw) - static_cast<uint64_t>(b.raw)); }
  Q32 sum2(Q32 a, Q32 b, Q32 c, Q32 d) { return round(fast::product(a.raw, b.raw) + fast::product(c.raw, d.raw)); }
  Q32 sum4(Q32 a, Q32 b, Q32 c, Q32 d, Q32 e, Q32 f, Q32 g, Q32 h) {
    return round(fast::product(a.raw, b.raw) + fast::product(c.raw, d.raw) + fast::product(e.raw, f.raw) +
                 fast::product(g.raw, h.raw));
  }
  /// An input used as an add/sub operand: must satisfy |x| < 2^62.
  void vet(Q32 x) { narrow |= static_cast<uint64_t>(x.raw) + (uint64_t{1} << 62); }
  bool clean() const { return ((wide >> 30) | (narrow >> 63)) == 0; }
};
#else
#define TANDEM_CONTACT_WRAP_FIRST 0
#endif

/// The relative velocity of the contact point along a direction d (the
/// normal or the tangent): (v_B − v_A)·d + ω_B (r_B × d) − ω_A (r_A × d),
/// using (ω × r)·d = ω (r × d). The four products are summed exactly in 128
/// bits (wrapping, so no UB even far outside the limits) and rounded once.
inline Q32 relative_velocity(Vec2 dv, Vec2 d, Q32 wb, Q32 rd_b, Q32 wa, Q32 rd_a) {
  return in_range::sum4(dv.x, d.x, dv.y, d.y, wb, rd_b, in_range::neg(wa), rd_a);
}

/// Applies an impulse λ along d to both bodies: v_A −= (m_A⁻¹ λ) d,
/// ω_A −= λ · angular_a; v_B += (m_B⁻¹ λ) d, ω_B += λ · angular_b.
inline void apply_impulse(Q32 impulse, Vec2 d, Q32 inv_mass_a, Q32 angular_a, Q32 inv_mass_b, Q32 angular_b, Vec2* va,
                          Q32* wa, Vec2* vb, Q32* wb) {
  using namespace in_range;
  const Q32 ka = mul(inv_mass_a, impulse), kb = mul(inv_mass_b, impulse);
  *va = {sub(va->x, mul(ka, d.x)), sub(va->y, mul(ka, d.y))};
  *wa = sub(*wa, mul(impulse, angular_a));
  *vb = {add(vb->x, mul(kb, d.x)), add(vb->y, mul(kb, d.y))};
  *wb = add(*wb, mul(impulse, angular_b));
}

/// Writes a constraint's result back to one of its bodies, unless the body
/// is not movable (zero inverse mass and inertia: the result is the value
/// already there, and the body may be shared by other constraints of the
/// colour running on other threads).
inline void store_velocity(BodyState* body, Vec2 v, Q32 w, Q32 inv_mass, Q32 inv_inertia) {
  if (inv_mass == Q32::zero() && inv_inertia == Q32::zero()) return;
  body->linear_velocity = v;
  body->angular_velocity = w;
}

/// Marks a latched bounce: the same store from every writer (see "Workers").
inline void mark_bounce(int32_t* mark, int32_t sub_step) {
  atomic_store_relaxed(mark, sub_step);
}

/// The lane kernels (contact_lanes.cpp): each is the scalar function of the
/// same name in contact_solver.cpp with the constraint index turned into a
/// lane index (same operations, same order, branches as per-lane selects).
void record_approach_lanes(ContactLanes& cl, BodyState* states);
void warm_start_lanes(ContactLanes& cl, BodyState* states, int32_t previous);
/// use_bias: the solve pass (true) or a relax pass (false); enabled: per-lane
/// gate of the bounce relax passes, or nullptr for every lane.
template <bool use_bias>
void solve_lanes(ContactLanes& cl, StepContext* context, const int32_t* enabled);

}  // namespace tandem::contact_internal
