// fixed_math.cpp — square roots, sine/cosine and atan2 on Q32.32 and Q16.16
// with integer arithmetic only (see fixed_math.h for the contracts).
//
// Design notes
// ------------
// One core per function works in a high-precision internal format and rounds
// once to the caller's format, so Q32.32 and Q16.16 share code and the error
// of every result is "final rounding (½ raw unit) + a few 2^-40". Every step
// is integer arithmetic on 64-bit words and 64×64→128 products
// (wide::mul_u64 / wide::mul_s64), which give the same bits on the native
// __int128 path and the portable limb path (i686, wasm32, big-endian s390x).
//
// Square roots. A bit-by-bit 128-bit square root costs 64 dependent
// iterations, and clang 14 compiles it far worse than g++ 12 (measured on the
// prototype), so instead:
//   1. normalise n by an even shift so that its top word x lies in
//      [2^62, 2^64);
//   2. estimate 1/√x from a 384-entry table of 16-bit values (768 bytes,
//      built at compile time from exact integer square roots, ~9 bits);
//   3. two Newton steps for 1/√x, y ← y·(3 − x·y²)/2 (the first in 32-bit
//      words, the second in 64-bit words: 9 → 17 → 34 bits), multiplications
//      only — no division;
//   4. s0 = x·y ≈ √x; for 128-bit inputs one more Newton step for √n that
//      uses the full 128-bit residual, s = s0 + (n − s0²)·y/2 (≈ 64 bits);
//   5. an exact fix-up on the remainder n − r²: loops that make the result
//      exact whatever the estimate was; the estimate is within ±2 and almost
//      always right, so they sit behind [[unlikely]] tests.
// Rejected: Newton with a 128/64 division per step (2–3 divisions, each
// slower than the whole multiply chain, and a long software division on
// the portable path); a bigger table (fewer steps but > a few KB).
// isqrt_round uses floor plus the remainder: round(√n) = f + (n − f² > f).
// rsqrt: the same estimate (plus a third Newton step, ≈ 59 bits, for
// Q32.32) lands within 2^-10 of a unit of 2^48/√raw (2^24/√raw); one exact
// integer product on the side it was rounded to fixes the last bit, so it is
// correctly rounded.
//
// sin/cos. The angle a·2^-32 rad is multiplied by 2/π held to 94 fraction
// bits (K = round(2/π·2^94)); bits 62..125 of a·K are the angle in quarter
// turns modulo 4 as Q2.62 with an error below 2^-61 quarter turn for every
// |a| < 2^63 — an exact reduction modulo 2π to far beyond the output
// precision, with two multiplications. Rounding to the nearest quarter turn
// gives the quadrant and f ∈ [−½, ½] (|angle| ≤ π/4); sin(π/2·f) and
// cos(π/2·f) are odd/even polynomials in f of degree 11 and 10 evaluated by
// Horner in Q2.62 (approximation error < 2^-43, evaluation error < 2^-58);
// the quadrant swaps/negates them without branches. Symmetry is exact:
// sin(−x) = −sin(x), cos(−x) = cos(x) (the core works on |a|).
//
// atan2. Octant symmetry reduces to atan(r), r = min(|x|,|y|)/max(|x|,|y|)
// ∈ [0, 1], computed as Q1.63 with one 128/64 division (Q32.32) or one 64/64
// division (Q16.16, whose inputs are 32-bit). [0, 1] is split into 32
// segments; on each, atan is a degree-5 polynomial in the local variable
// u = 64·(r − centre) ∈ [−1, 1] (table: 32 × 6 words = 1.5 KB). Then
// θ ← π/2 − θ, π − θ, −θ as the octant requires, in Q2.62, rounded once.
//
// Constants. All were computed with exact rational arithmetic (Python 3
// fractions.Fraction and big integers, no floating point) by the script
// reproduced at the end of this file: π from Machin's formula to 390 bits;
// sin/cos/atan polynomials by Chebyshev economisation of the exact Taylor
// series (degree 33) — near-minimax, with a rigorous bound on the dropped
// part — and then rounded to nearest in Q2.62.
//
// Rounding of results: sqrt and rsqrt are correctly rounded (no ties exist).
// sin, cos and atan2 round their Q2.62 value once to nearest, ties upwards
// (the Q2.62 value itself is within 2^-42 of the truth).
#include "fixed/fixed_math.h"

#include <array>
#include <cstddef>
#include <cstdint>

namespace tandem {
namespace {

constexpr uint64_t k_bit62 = uint64_t{1} << 62;

/// High 64 bits of the unsigned product a·b.
constexpr uint64_t mulhi_u64(uint64_t a, uint64_t b) { return wide::mul_u64(a, b).hi; }

/// (a·b) / 2^62 rounded towards −∞, for signed Q2.62 operands whose product
/// is below 2 in magnitude (so the result fits int64).
constexpr int64_t mul_q62(int64_t a, int64_t b) {
  const wide::U128 p = wide::mul_s64(a, b);
  return static_cast<int64_t>((p.hi << 2) | (p.lo >> 62));  // modular conversion (C++20)
}

/// (a·b) / 2^s rounded towards −∞ for signed a, b; 1 ≤ s ≤ 63 and the
/// result must fit int64.
constexpr int64_t mul_shift_s(int64_t a, int64_t b, unsigned s) {
  const wide::U128 p = wide::mul_s64(a, b);
  return static_cast<int64_t>((p.hi << (64 - s)) | (p.lo >> s));
}

// --- reciprocal square root estimate ------------------------------------------

/// floor(√n) by the bit-by-bit method; only used at compile time for the
/// table below.
constexpr uint64_t isqrt_slow(uint64_t n) {
  uint64_t r = 0;
  for (int b = 31; b >= 0; --b) {
    const uint64_t t = r | (uint64_t{1} << b);
    if (t * t <= n) r = t;
  }
  return r;
}

/// k_rsqrt_table[j] ≈ 2^15/√X at the centre X = (2i + 1)/1024 of bucket
/// i = j + 128 (X ∈ [i/512, (i+1)/512) ⊂ [¼, 1)): floor(√floor(2^40/(2i+1))).
/// Values lie in (2^15, 2^16); 768 bytes.
constexpr std::array<uint16_t, 384> make_rsqrt_table() {
  std::array<uint16_t, 384> t{};
  for (size_t j = 0; j < t.size(); ++j) {
    const uint64_t i = j + 128;
    t[j] = static_cast<uint16_t>(isqrt_slow((uint64_t{1} << 40) / (2 * i + 1)));
  }
  return t;
}
constexpr std::array<uint16_t, 384> k_rsqrt_table = make_rsqrt_table();
static_assert(k_rsqrt_table[0] == 65408 && k_rsqrt_table[383] == 32784);

/// One Newton step y ← y + y·(1 − X·y²)/2 for 1/√X, where x = X·2^64 and
/// y is Q2.62 (1/√X ∈ (1, 2]). Doubles the number of correct bits up to ≈ 59.
constexpr uint64_t rsqrt_step(uint64_t x, uint64_t y) {
  const uint64_t y2 = mulhi_u64(y, y);                                 // Q4.60, < 2^62
  const uint64_t xy2 = mulhi_u64(x, y2);                               // Q4.60, ≈ 2^60
  const int64_t e = static_cast<int64_t>((uint64_t{1} << 60) - xy2);  // 1 − X·y², Q.60, small
  return y + static_cast<uint64_t>(mul_shift_s(static_cast<int64_t>(y), e, 61));
}

/// 1/√X as Q2.62 for x = X·2^64 ∈ [2^62, 2^64), relative error below 2^-33
/// (from the table and two Newton steps; the result is almost always low).
constexpr uint64_t rsqrt_estimate(uint64_t x) {
  const uint64_t y0 = k_rsqrt_table[static_cast<size_t>((x >> 55) - 128)];  // Q1.15
  // First step in 32-bit words: Q1.15 → Q1.31.
  const uint64_t t = ((x >> 32) * (y0 * y0)) >> 32;                 // X·y0², Q2.30
  const uint64_t y1 = (y0 * ((uint64_t{3} << 30) - t)) >> 15;      // y0·(3 − X·y0²)/2, Q1.31
  return rsqrt_step(x, y1 << 31);
}

// --- integer square roots ------------------------------------------------------

/// floor(√n) for n < 2^64, with *out_rem = n − floor(√n)².
constexpr uint64_t isqrt64_rem(uint64_t n, uint64_t* out_rem) {
  if (n == 0) {
    *out_rem = 0;
    return 0;
  }
  const unsigned sh = static_cast<unsigned>(__builtin_clzll(n)) & ~1u;
  const uint64_t x = n << sh;                          // [2^62, 2^64)
  const uint64_t s = mulhi_u64(x, rsqrt_estimate(x));  // √X as Q2.62
  uint64_t r = s >> (30 + sh / 2);                     // ≈ √n, within ±1
  if (r > 0xFFFFFFFFu) r = 0xFFFFFFFFu;
  // Exact fix-up: find r with r² ≤ n < (r + 1)². The loops are written
  // behind [[unlikely]] tests so that the common case (no correction) is
  // straight-line code for both g++ and clang.
  uint64_t sq = r * r;
  if (sq > n) [[unlikely]] {
    do {
      --r;
      sq = r * r;
    } while (sq > n);
  }
  uint64_t rem = n - sq;
  if (rem > 2 * r) [[unlikely]] {  // (r + 1)² ≤ n
    do {
      rem -= 2 * r + 1;
      ++r;
    } while (rem > 2 * r);
  }
  *out_rem = rem;
  return r;
}

/// floor(√n) for any 128-bit n, with *out_rem = n − floor(√n)² (≤ 2^65).
constexpr uint64_t isqrt128_rem(wide::U128 n, wide::U128* out_rem) {
  if (n.hi == 0) {
    uint64_t rem = 0;
    const uint64_t r = isqrt64_rem(n.lo, &rem);
    *out_rem = wide::U128{rem, 0};
    return r;
  }
  const unsigned sh = static_cast<unsigned>(__builtin_clzll(n.hi)) & ~1u;
  const wide::U128 m = wide::shl(n, sh);  // top word in [2^62, 2^64)
  const uint64_t x = m.hi;
  const uint64_t y = rsqrt_estimate(x);
  // s0 ≈ √m from the top word: √X·2^64 where X = x/2^64 (relative error
  // < 2^-33, so |m − s0²| < 2^98).
  const uint64_t s_q62 = mulhi_u64(x, y);
  const uint64_t s0 = s_q62 >= k_bit62 ? ~uint64_t{0} : s_q62 << 2;
  // Newton step with the full residual: s = s0 + (m − s0²)/(2√m), where
  // 1/(2√m) = y·2^-127. The residual's low 40 bits are dropped (worth
  // < 2^-23 of a unit in s).
  const wide::U128 d = wide::sub(m, wide::mul_u64(s0, s0));  // signed, |d| < 2^98
  const int64_t dd = static_cast<int64_t>((d.hi << 24) | (d.lo >> 40));
  const int64_t delta = static_cast<int64_t>(wide::mul_s64(dd, static_cast<int64_t>(y)).hi) >> 23;
  // s = s0 + delta, saturated at 2^64 − 1 (s0 ≥ 2^63 ≫ |delta|, so only a
  // positive delta can wrap). Branch-free: delta's sign is unpredictable.
  const uint64_t s_wrapped = s0 + static_cast<uint64_t>(delta);
  const uint64_t wrapped = static_cast<uint64_t>(delta > 0) & static_cast<uint64_t>(s_wrapped < s0);
  const uint64_t s = s_wrapped | (0u - wrapped);
  uint64_t r = s >> (sh / 2);  // ≈ √n, within ±2
  wide::U128 sq = wide::mul_u64(r, r);
  while (wide::less_u(n, sq)) {
    --r;
    sq = wide::mul_u64(r, r);
  }
  wide::U128 rem = wide::sub(n, sq);
  for (;;) {
    const wide::U128 step{2 * r + 1, r >> 63};
    if (wide::less_u(rem, step)) break;
    rem = wide::sub(rem, step);
    ++r;
  }
  *out_rem = rem;
  return r;
}

// --- sine and cosine --------------------------------------------------------------

// 2/π·2^94 rounded to nearest, split in words: K = k_two_over_pi_hi·2^64 + _lo.
constexpr uint64_t k_two_over_pi_hi = 683565275u;              // 0x28BE60DB
constexpr uint64_t k_two_over_pi_lo = 10633286012715521524u;   // 0x9391054A7F09D5F4

// sin(π/2·f) ≈ f·Σ k_sin[i]·f^(2i), f ∈ [−½, ½]; Q2.62; |error| < 2^-48.
constexpr std::array<int64_t, 6> k_sin = {7244019458076921496, -2978983596853064559, 367517369509091705,
                                          -21590770178367351,  739838241900101,      -16384710018584};
// cos(π/2·f) ≈ Σ k_cos[i]·f^(2i), f ∈ [−½, ½]; Q2.62; |error| < 2^-43.
constexpr std::array<int64_t, 6> k_cos = {4611686018427131759, -5689439577915358675, 1169844119443494867,
                                          -96215763697429770,  4238885402159624,     -114604954135358};

struct SinCosQ62 {
  int64_t sin;  // Q2.62, in [−2^62, 2^62] up to the approximation error
  int64_t cos;
};

/// sin and cos of the angle mag·2^-32 radians (mag ≤ 2^63), in Q2.62.
constexpr SinCosQ62 sincos_core(uint64_t mag) {
  // Quarter turns modulo 4, Q2.62: bits 64..127 of mag·K (K·2^-126 = 2/π·2^-32).
  const uint64_t t = mulhi_u64(mag, k_two_over_pi_lo) + mag * k_two_over_pi_hi;
  const uint64_t u = t + (uint64_t{1} << 61);  // round to the nearest quarter turn
  const unsigned quadrant = static_cast<unsigned>(u >> 62);
  const int64_t f = static_cast<int64_t>(u & (k_bit62 - 1)) - (int64_t{1} << 61);  // [−½, ½), Q2.62
  const int64_t z = mul_q62(f, f);
  int64_t ps = k_sin[5];
  int64_t pc = k_cos[5];
  for (int i = 4; i >= 0; --i) {
    ps = k_sin[static_cast<size_t>(i)] + mul_q62(z, ps);
    pc = k_cos[static_cast<size_t>(i)] + mul_q62(z, pc);
  }
  const int64_t s = mul_q62(f, ps);
  const int64_t c = pc;
  // Rotate by the quadrant: (sin, cos) of q·π/2 + θ is (s, c), (c, −s),
  // (−s, −c), (−c, s) for q = 0..3. Branch-free.
  const bool swap = (quadrant & 1u) != 0;
  const int64_t s1 = swap ? c : s;
  const int64_t c1 = swap ? s : c;
  const bool neg_s = (quadrant & 2u) != 0;
  const bool neg_c = ((quadrant + 1u) & 2u) != 0;
  return SinCosQ62{neg_s ? -s1 : s1, neg_c ? -c1 : c1};
}

/// v / 2^s rounded to nearest (ties up), for Q2.62 values v (|v| ≤ 2^63 − 2^s).
constexpr int64_t round_q62(int64_t v, unsigned s) { return (v + (int64_t{1} << (s - 1))) >> s; }

// --- arctangent ----------------------------------------------------------------

// atan(c + u/64) ≈ Σ k_atan[k][i]·u^i for u ∈ [−1, 1], c = (2k+1)/64 the
// centre of segment k of [0, 1]; Q2.62; |error| < 2^-43.
constexpr int64_t k_atan[32][6] = {
    {72051730834724142, 72040006145786230, -17583598666270, -5855477190569, 4288159160, 855591021},
    {216014660847652148, 71899611493127810, -52545390344924, -5787175417963, 12739589482, 830724086},
    {359557635144616724, 71620457456757183, -86896936619367, -5652553369993, 20823105269, 782330533},
    {502406099870076939, 71205767232643121, -120250990429905, -5455467492331, 28315346701, 712975863},
    {644293462209320610, 70660259798735248, -152248580266111, -5201445207382, 35023865697, 626234857},
    {784963956008356448, 69990017827680750, -182568218017160, -4897400637434, 40795814204, 526401166},
    {924175208791583539, 69202322433609069, -210933216757372, -4551293055759, 45523495957, 418156269},
    {1061700451812451690, 68305462897328213, -237116852748074, -4171754337262, 49146556240, 306233890},
    {1197330331911260659, 67308530257552253, -260945266111865, -3767712059646, 51650934593, 195113083},
    {1330874301941493738, 66221203764724346, -282298148990362, -3348032655841, 53065004397, 88766023},
    {1462161584136344548, 65053538721486490, -301107404296750, -2921204698113, 53453536983, -9523053},
    {1591041716952801548, 63815763282030234, -317354062214746, -2495076763499, 52910240517, -97261644},
    {1717384709823084782, 62518090484938211, -331063809964495, -2076658203495, 51549637192, -172778709},
    {1841080841315869011, 61170550296247610, -342301522360678, -1671985257649, 49498972218, -235190716},
    {1962040144204315465, 59782844881384308, -351165179604290, -1286049882647, 46890719552, -284318883},
    {2080191625859047080, 58364228827247862, -357779530653663, -922784773717, 43856089767, -320574226},
    {2195482274451519181, 56923414692264102, -362289812983223, -585095476712, 40519780355, -344826491},
    {2307875901041787079, 55468503134633614, -364855780416178, -274929186484, 36996058110, -358270823},
    {2417351865202619900, 54006935988907781, -365646227198017, 6630372575, 33386139944, -362302868},
    {2523903727903470017, 52545470033714855, -364834134458410, 259251933037, 29776748669, -358409581},
    {2627537870436260139, 51090168803768677, -362592509000148, 483238250538, 26239664272, -348079733},
    {2728272112658171383, 49646409618060072, -359090936657329, 679407401372, 22832065231, -332735414},
    {2826134358135342092, 48218902986336042, -354492834548187, 848979296259, 19597452473, -313683743},
    {2921161288198885540, 46811721677931658, -348953358528163, 993471286079, 16566963780, -292086641},
    {3013397121695545585, 45428336952340427, -342617903318277, 1114605295305, 13760912299, -268945727},
    {3102892452481100136, 44071659725153484, -335621121921015, 1214227709736, 11190413724, -245099166},
    {3189703172553182439, 42744084747190512, -328086386570749, 1294242289475, 8858998510, -221227329},
    {3273889485187455688, 41447536185837460, -320125614083235, 1356555670004, 6764135138, -197864501},
    {3355515009523055799, 40183513298753851, -311839382650172, 1403034529182, 4898616314, -175414247},
    {3434645975707285496, 38953135169505860, -303317273631860, 1435473201626, 3251781193, -154166564},
    {3511350507904322705, 37757183725130498, -294638379715366, 1455570376194, 1810563237, -134315413},
    {3585697991136210477, 36596144473570316, -285871929135086, 1464913480408, 560365322, -115975606},
};

constexpr uint64_t k_pi_q62 = 14488038916154245685u;      // round(π·2^62)
constexpr uint64_t k_half_pi_q62 = 7244019458077122842u;  // round(π/2·2^62)

/// atan(r) for r ∈ [0, 1] given as Q1.63 (r ≤ 2^63); Q2.62 in [0, π/4·2^62].
constexpr uint64_t atan_unit_q62(uint64_t r) {
  uint64_t k = r >> 58;
  if (k > 31) k = 31;  // r = 1 exactly: the right end of the last segment
  const int64_t u = static_cast<int64_t>(r - ((2 * k + 1) << 57)) * 32;  // [−1, 1], Q2.62
  const int64_t* a = k_atan[static_cast<size_t>(k)];
  int64_t p = a[5];
  for (int i = 4; i >= 0; --i) p = a[i] + mul_q62(u, p);
  return p < 0 ? 0u : static_cast<uint64_t>(p);  // p(0) is 0 up to 2^-43 (in fact +30350·2^-62)
}

/// atan2 of magnitudes folded back to the full circle: θ in Q2.62 ∈ [0, π]
/// from atan(min/max) = at; the caller applies the sign of y.
constexpr uint64_t atan2_unfold(uint64_t at, bool steep, bool x_negative) {
  uint64_t theta = steep ? k_half_pi_q62 - at : at;
  if (x_negative) theta = k_pi_q62 - theta;
  return theta;
}

}  // namespace

// --- public functions ------------------------------------------------------------

uint64_t isqrt_floor(wide::U128 n) {
  wide::U128 rem;
  return isqrt128_rem(n, &rem);
}

uint64_t isqrt_round(wide::U128 n) {
  wide::U128 rem;
  const uint64_t f = isqrt128_rem(n, &rem);
  // √n ≥ f + ½ ⇔ n ≥ f² + f + ¼ ⇔ rem > f (integers); rem ≤ 2f, so the
  // sign of f − rem decides (branch-free: the outcome is a coin toss).
  const bool up = wide::is_negative(wide::sub(wide::U128{f, 0}, rem));
  return f + ((up && f != ~uint64_t{0}) ? 1u : 0u);
}

Q32 sqrt(Q32 x) {
  if (x.raw < 0) {
    TANDEM_FIXED_FAULT(FixedFault::domain, "Q32.32 sqrt");
    return Q32{};
  }
  const uint64_t v = static_cast<uint64_t>(x.raw);
  // √(raw·2^-32)·2^32 = √(raw·2^32) < 2^47.5.
  return Q32::from_raw(static_cast<int64_t>(isqrt_round(wide::U128{v << 32, v >> 32})));
}

Q16 sqrt(Q16 x) {
  if (x.raw < 0) {
    TANDEM_FIXED_FAULT(FixedFault::domain, "Q16.16 sqrt");
    return Q16{};
  }
  const uint64_t n = static_cast<uint64_t>(x.raw) << 16;  // < 2^47
  uint64_t rem = 0;
  const uint64_t f = isqrt64_rem(n, &rem);
  return Q16::from_raw(static_cast<int32_t>(f + (rem > f ? 1u : 0u)));
}

Q32 rsqrt(Q32 x) {
  if (x.raw <= 0) {
    TANDEM_FIXED_FAULT(FixedFault::domain, "Q32.32 rsqrt");
    return Q32::max();
  }
  // Result 2^48/√raw ∈ (2^16.5, 2^48]: never saturates.
  const uint64_t raw = static_cast<uint64_t>(x.raw);
  const unsigned sh = static_cast<unsigned>(__builtin_clzll(raw)) & ~1u;
  const uint64_t xn = raw << sh;
  const uint64_t y = rsqrt_step(xn, rsqrt_estimate(xn));  // Q2.62, error < 2^-58
  // 2^48/√raw = Y·2^(16 + sh/2) with Y = y·2^-62.
  const unsigned shift = 46 - sh / 2;
  uint64_t r = (y + (uint64_t{1} << (shift - 1))) >> shift;
  // Exact last bit: r = round(√(2^96/raw)) ⇔ (2r − 1)²·raw < 2^98 < (2r + 1)²·raw
  // (equality is impossible). y is within 2^-10 of a unit, so r can only be
  // one too large when y was rounded up, one too small when rounded down:
  // one product decides, chosen without a branch. It is ≈ 2^98, so 128 bits
  // hold it.
  const uint64_t rounded_up = (y >> (shift - 1)) & 1u;
  const uint64_t odd = 2 * r + 1 - 2 * rounded_up;  // 2r − 1 or 2r + 1, < 2^50
  const wide::U128 sq = wide::mul_u64(odd, odd);
  wide::U128 p = wide::mul_u64(sq.lo, raw);
  p.hi += sq.hi * raw;
  const uint64_t above = wide::less_u(wide::U128{0, uint64_t{1} << 34}, p) ? 1u : 0u;  // p > 2^98
  r = r - (rounded_up & above) + ((rounded_up ^ 1u) & (above ^ 1u));
  return Q32::from_raw(static_cast<int64_t>(r));
}

Q16 rsqrt(Q16 x) {
  if (x.raw <= 0) {
    TANDEM_FIXED_FAULT(FixedFault::domain, "Q16.16 rsqrt");
    return Q16::max();
  }
  // Result 2^24/√raw ∈ (2^8.5, 2^24]: never saturates.
  const uint64_t raw = static_cast<uint64_t>(x.raw);
  const unsigned sh = static_cast<unsigned>(__builtin_clzll(raw)) & ~1u;  // ≥ 32
  const uint64_t xn = raw << sh;
  const uint64_t y = rsqrt_estimate(xn);  // error < 2^-33: < 2^-9 of a unit here
  // 2^24/√raw = Y·2^(sh/2 − 8) with Y = y·2^-62.
  const unsigned shift = 70 - sh / 2;
  uint64_t r = (y + (uint64_t{1} << (shift - 1))) >> shift;
  // Exact last bit, as for Q32.32: (2r − 1)²·raw < 2^50 < (2r + 1)²·raw, one
  // product ≈ 2^50 (fits 64 bits) checked on the side y was rounded to.
  const uint64_t rounded_up = (y >> (shift - 1)) & 1u;
  const uint64_t odd = 2 * r + 1 - 2 * rounded_up;  // < 2^26
  const uint64_t above = odd * odd * raw > (uint64_t{1} << 50) ? 1u : 0u;
  r = r - (rounded_up & above) + ((rounded_up ^ 1u) & (above ^ 1u));
  return Q16::from_raw(static_cast<int32_t>(r));
}

SinCos<Q32> sincos(Q32 angle) {
  const bool negative = angle.raw < 0;
  const SinCosQ62 v = sincos_core(detail::magnitude(angle.raw));
  const int64_t s = round_q62(v.sin, 30);
  return SinCos<Q32>{Q32::from_raw(negative ? -s : s), Q32::from_raw(round_q62(v.cos, 30))};
}

SinCos<Q16> sincos(Q16 angle) {
  const bool negative = angle.raw < 0;
  const SinCosQ62 v = sincos_core(detail::magnitude(angle.raw) << 16);
  const int32_t s = static_cast<int32_t>(round_q62(v.sin, 46));
  return SinCos<Q16>{Q16::from_raw(negative ? -s : s), Q16::from_raw(static_cast<int32_t>(round_q62(v.cos, 46)))};
}

Q32 atan2(Q32 y, Q32 x) {
  const uint64_t ax = detail::magnitude(x.raw), ay = detail::magnitude(y.raw);
  if (ax == 0 && ay == 0) return Q32{};
  const bool steep = ay > ax;
  const uint64_t num = steep ? ax : ay, den = steep ? ay : ax;
  // r = num/den as Q1.63: (num·2^63)/den, quotient ≤ 2^63 fits.
  uint64_t rem = 0;
  const uint64_t r = wide::div_u128_u64(wide::U128{num << 63, num >> 1}, den, &rem);
  const uint64_t theta = atan2_unfold(atan_unit_q62(r), steep, x.raw < 0);
  const int64_t m = static_cast<int64_t>((theta + (uint64_t{1} << 29)) >> 30);
  return Q32::from_raw(y.raw < 0 ? -m : m);
}

Q16 atan2(Q16 y, Q16 x) {
  const uint64_t ax = detail::magnitude(x.raw), ay = detail::magnitude(y.raw);
  if (ax == 0 && ay == 0) return Q16{};
  const bool steep = ay > ax;
  const uint64_t num = steep ? ax : ay, den = steep ? ay : ax;
  // r = num/den as Q1.63 from a 64-bit division (num ≤ 2^31): 32 exact bits,
  // an error below 2^-32 rad, far under the Q16.16 unit.
  const uint64_t r = ((num << 32) / den) << 31;
  const uint64_t theta = atan2_unfold(atan_unit_q62(r), steep, x.raw < 0);
  const int32_t m = static_cast<int32_t>((theta + (uint64_t{1} << 45)) >> 46);
  return Q16::from_raw(y.raw < 0 ? -m : m);
}

}  // namespace tandem

/* Generator for the constants above: python3, exact rational arithmetic
   (fractions.Fraction, big integers; no floating point). Prints k_sin, k_cos
   and the k_atan rows, each with a bound on the economisation error, then
   round(π·2^62), round(π/2·2^62) and round(2/π·2^94).

from fractions import Fraction as F
from math import comb, factorial
P = 400                                      # bits of working precision
def atan_inv(n):                             # atan(1/n)·2^P, alternating series
    s, t, k, sg = 0, (1 << P) // n, 1, 1
    while t: s += sg * (t // k); t //= n * n; k += 2; sg = -sg
    return s
PI = F(16 * atan_inv(5) - 4 * atan_inv(239), 1 << P)          # Machin
def rnd(x): return (2 * x.numerator + x.denominator) // (2 * x.denominator)  # nearest, ties up
def economize(mono, deg):                    # Taylor coeffs in w on [-1,1] -> degree deg
    N = len(mono) - 1; ch = [F(0)] * (N + 1)
    for n, a in enumerate(mono):             # w^n = 2^(1-n)·Σ C(n,k)·T_{n-2k} (T_0 halved)
        for k in range(n // 2 + 1):
            c = F(comb(n, k), 1 << (n - 1)) if n else F(1)
            ch[n - 2 * k] += a * (c / 2 if n and n == 2 * k else c)
    T = [[F(1)], [F(0), F(1)]]
    while len(T) <= deg:                     # T_{m+1} = 2w·T_m − T_{m−1}
        nxt = [F(0)] + [2 * x for x in T[-1]]
        for i, x in enumerate(T[-2]): nxt[i] -= x
        T.append(nxt)
    out = [sum((ch[m] * T[m][i] for m in range(i, deg + 1) if i < len(T[m])), F(0)) for i in range(deg + 1)]
    return out, sum(abs(c) for c in ch[deg + 1:])  # coefficients, bound on the dropped part
N = 33                                       # Taylor degree before economisation (tail < 2^-90)
Q = lambda x: rnd(x * (1 << 62))             # Q2.62
for name, par, deg in (("k_sin", 1, 11), ("k_cos", 0, 10)):   # f ∈ [-1/2, 1/2], w = 2f
    mono = [(-1) ** (n // 2) * (PI / 4) ** n / factorial(n) if n % 2 == par else F(0) for n in range(N + 1)]
    c, err = economize(mono, deg)
    print(name, [Q(c[n] * 2 ** n) for n in range(par, deg + 1, 2)], 'error < 2^-%d' % (err.denominator.bit_length() - err.numerator.bit_length() - 1))
def atan(x):                                 # Euler: Σ 2^2n (n!)^2/(2n+1)! · x^(2n+1)/(1+x²)^(n+1)
    y, t, s, n = x * x / (1 + x * x), x / (1 + x * x), F(0), 0
    while t > F(1, 1 << P): s += t; n += 1; t = t * y * 2 * n / (2 * n + 1)
    return s
for k in range(32):                          # atan(c + u/64), u ∈ [-1, 1], c = (2k+1)/64
    c = F(2 * k + 1, 64); inv = []           # series of 1/(1+(c+t)^2) = atan'(c+t)
    for n in range(N):
        inv.append(((1 if n == 0 else 0) - 2 * c * (inv[n - 1] if n else 0) - (inv[n - 2] if n > 1 else 0)) / (1 + c * c))
    mono = [atan(c)] + [inv[n - 1] / n / F(64) ** n for n in range(1, N)]
    cc, err = economize(mono, 5)
    print([Q(x) for x in cc], 'error < 2^-%d' % (err.denominator.bit_length() - err.numerator.bit_length() - 1))
print("pi", Q(PI), "pi/2", Q(PI / 2), "2/pi*2^94", rnd(2 / PI * (1 << 94)))
*/
