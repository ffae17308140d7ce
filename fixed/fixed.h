// fixed.h — Tandem's fixed-point scalars: Q32.32 (physics) and Q16.16 (inputs,
// network messages, exported transforms).
//
// A value is a signed integer `raw` read as raw / 2^Frac. Everything here is
// integer arithmetic; the only floating point is `to_double`, for debug output
// and reports at the edge, never fed back into state.
//
// Rounding rule (one rule everywhere): × and ÷, conversions that drop bits,
// ratio construction and decimal parsing round to the NEAREST representable
// value, ties AWAY FROM ZERO. The rule is symmetric, so (−a)×b == −(a×b)
// exactly, and it carries no bias towards zero (truncation would bleed
// energy out of every product).
//
// Overflow rule (one rule everywhere): results SATURATE to the symmetric range
// [−max, +max] with max = 2^(bits−1) − 1 raw units. The most negative raw value
// is never produced by an operation, so negation and abs are always exact.
// Division by zero gives 0 for 0/0 and ±max (the sign of the dividend)
// otherwise. Each saturation is also reported through TANDEM_FIXED_FAULT
// (fault.h), which in debug builds names the operation and aborts.
//
// Q32.32: range ±2147483648 (exclusive), resolution 2^-32 ≈ 2.33e-10.
// Q16.16: range ±32768 (exclusive),      resolution 2^-16 ≈ 1.53e-5.
#pragma once

#include <array>
#include <compare>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>

#include "fixed/fault.h"
#include "fixed/wide.h"

namespace tandem {

/// A signed fixed-point number: Raw is the storage integer (int32_t or
/// int64_t), Frac the number of fraction bits (16 or 32).
template <typename Raw, int Frac>
struct Fixed {
  static_assert(std::is_same_v<Raw, int32_t> || std::is_same_v<Raw, int64_t>);
  static_assert(Frac == 16 || Frac == 32);
  static_assert(Frac * 2 == static_cast<int>(sizeof(Raw)) * 8, "integer and fraction halves are equal");

  using raw_type = Raw;
  static constexpr int k_frac_bits = Frac;
  static constexpr int k_int_bits = static_cast<int>(sizeof(Raw)) * 8 - Frac;
  static constexpr Raw k_raw_max = std::numeric_limits<Raw>::max();
  static constexpr Raw k_raw_min = -k_raw_max;  // symmetric: −max, not the type's minimum
  static constexpr Raw k_raw_one = Raw{1} << Frac;
  static constexpr const char* k_name = Frac == 32 ? "Q32.32" : "Q16.16";

  /// The raw integer: the value times 2^Frac. Public, plain data.
  Raw raw = 0;

  /// Zero.
  constexpr Fixed() = default;

  /// From an integer: exact when it fits the integer range, else saturated
  /// (with a fault report).
  template <std::integral I>
  explicit constexpr Fixed(I v) : raw(from_int(static_cast<int64_t>(v)).raw) {}

  /// From a raw integer (value = raw / 2^Frac). Exact.
  static constexpr Fixed from_raw(Raw r) {
    Fixed f;
    f.raw = r;
    return f;
  }

  /// From an integer; saturates and reports out_of_range when |v| ≥ 2^k_int_bits.
  static constexpr Fixed from_int(int64_t v) {
    constexpr int64_t lim = int64_t{1} << (k_int_bits - 1);  // exclusive
    if (v >= lim || v <= -lim) {
      TANDEM_FIXED_FAULT(FixedFault::out_of_range, Frac == 32 ? "Q32.32 from integer" : "Q16.16 from integer");
      return from_raw(v > 0 ? k_raw_max : k_raw_min);
    }
    // Multiply instead of left-shifting a possibly negative value.
    return from_raw(static_cast<Raw>(v * static_cast<int64_t>(k_raw_one)));
  }

  /// num / den rounded to nearest (ties away from zero), saturated. den == 0
  /// gives 0 for 0/0, else ±max, with a divide_by_zero report.
  static constexpr Fixed from_ratio(int64_t num, int64_t den);

  /// The largest and smallest values, and the smallest positive one.
  static constexpr Fixed max() { return from_raw(k_raw_max); }
  static constexpr Fixed min() { return from_raw(k_raw_min); }
  static constexpr Fixed epsilon() { return from_raw(1); }
  static constexpr Fixed zero() { return {}; }
  static constexpr Fixed one() { return from_raw(k_raw_one); }
  static constexpr Fixed half() { return from_raw(k_raw_one / 2); }

  /// The value in binary64 floating point (tandem-edge): debug output and reports only. Exact for Q16.16;
  /// for Q32.32 rounded to 53 bits.
  double to_double() const { return static_cast<double>(raw) / static_cast<double>(k_raw_one); }  // tandem-edge: debug/report conversion

  /// The integer part, rounded towards negative infinity.
  constexpr int64_t floor_int() const { return raw >> Frac; }  // arithmetic shift: defined in C++20

  friend constexpr bool operator==(Fixed, Fixed) = default;
  friend constexpr auto operator<=>(Fixed a, Fixed b) { return a.raw <=> b.raw; }

  // --- arithmetic ---------------------------------------------------------

  /// −a; exact (the range is symmetric). −(raw minimum) saturates to +max.
  friend constexpr Fixed operator-(Fixed a) {
    if (a.raw == std::numeric_limits<Raw>::min()) return from_raw(k_raw_max);
    return from_raw(static_cast<Raw>(-a.raw));
  }
  friend constexpr Fixed operator+(Fixed a) { return a; }

  /// a + b, saturating.
  friend constexpr Fixed operator+(Fixed a, Fixed b) {
    Raw r;
    if (__builtin_add_overflow(a.raw, b.raw, &r) || r == std::numeric_limits<Raw>::min()) {
      TANDEM_FIXED_FAULT(FixedFault::overflow, Frac == 32 ? "Q32.32 add" : "Q16.16 add");
      return from_raw(a.raw > 0 ? k_raw_max : k_raw_min);
    }
    return from_raw(r);
  }

  /// a − b, saturating.
  friend constexpr Fixed operator-(Fixed a, Fixed b) {
    Raw r;
    if (__builtin_sub_overflow(a.raw, b.raw, &r) || r == std::numeric_limits<Raw>::min()) {
      TANDEM_FIXED_FAULT(FixedFault::overflow, Frac == 32 ? "Q32.32 subtract" : "Q16.16 subtract");
      return from_raw(a.raw >= 0 ? k_raw_max : k_raw_min);
    }
    return from_raw(r);
  }

  // a × b and a ÷ b: namespace-scope templates below.

  /// a × n for an integer n, exact unless it saturates.
  template <std::integral I>
  friend constexpr Fixed operator*(Fixed a, I n) {
    const int64_t nn = static_cast<int64_t>(n);
    if constexpr (sizeof(Raw) == 8) {
      Raw r;
      if (__builtin_mul_overflow(a.raw, nn, &r) || r == std::numeric_limits<Raw>::min()) {
        TANDEM_FIXED_FAULT(FixedFault::overflow, "Q32.32 multiply by integer");
        return from_raw(((a.raw < 0) != (nn < 0)) ? k_raw_min : k_raw_max);
      }
      return from_raw(r);
    } else {
      int64_t r;
      if (__builtin_mul_overflow(static_cast<int64_t>(a.raw), nn, &r) || r > k_raw_max || r < k_raw_min) {
        TANDEM_FIXED_FAULT(FixedFault::overflow, "Q16.16 multiply by integer");
        return from_raw(((a.raw < 0) != (nn < 0)) ? k_raw_min : k_raw_max);
      }
      return from_raw(static_cast<Raw>(r));
    }
  }
  template <std::integral I>
  friend constexpr Fixed operator*(I n, Fixed a) { return a * n; }

  /// a ÷ n for an integer n, rounded to nearest, ties away from zero.
  template <std::integral I>
  friend constexpr Fixed operator/(Fixed a, I n) {
    const int64_t nn = static_cast<int64_t>(n);
    if (nn == 0) {
      TANDEM_FIXED_FAULT(FixedFault::divide_by_zero, Frac == 32 ? "Q32.32 divide by integer" : "Q16.16 divide by integer");
      return from_raw(a.raw == 0 ? Raw{0} : (a.raw > 0 ? k_raw_max : k_raw_min));
    }
    const bool negative = (a.raw < 0) != (nn < 0);
    const uint64_t ua = a.raw < 0 ? 0u - static_cast<uint64_t>(static_cast<int64_t>(a.raw)) : static_cast<uint64_t>(a.raw);
    const uint64_t un = nn < 0 ? 0u - static_cast<uint64_t>(nn) : static_cast<uint64_t>(nn);
    uint64_t q = ua / un;
    const uint64_t rem = ua - q * un;
    if (rem >= un - rem) ++q;  // 2·rem ≥ n without overflow
    if (q > static_cast<uint64_t>(k_raw_max)) q = static_cast<uint64_t>(k_raw_max);  // only |raw min| / 1
    const Raw m = static_cast<Raw>(q);
    return from_raw(negative ? static_cast<Raw>(-m) : m);
  }

  constexpr Fixed& operator+=(Fixed b) { return *this = *this + b; }
  constexpr Fixed& operator-=(Fixed b) { return *this = *this - b; }
  constexpr Fixed& operator*=(Fixed b) { return *this = *this * b; }
  constexpr Fixed& operator/=(Fixed b) { return *this = *this / b; }
};

/// Q32.32: int64 raw, 32 fraction bits. The physics format.
using Q32 = Fixed<int64_t, 32>;
/// Q16.16: int32 raw, 16 fraction bits. The compact format.
using Q16 = Fixed<int32_t, 16>;

namespace detail {

/// Magnitude of a signed 64-bit value as unsigned (well defined for INT64_MIN).
constexpr uint64_t magnitude(int64_t v) { return v < 0 ? 0u - static_cast<uint64_t>(v) : static_cast<uint64_t>(v); }

/// Rounds |n| / |d| to nearest (ties away from zero) for a 128-bit numerator
/// magnitude and 64-bit divisor; sets *out_overflow if the quotient exceeds
/// max_mag, returning max_mag then.
constexpr uint64_t div_round_mag(wide::U128 n, uint64_t d, uint64_t max_mag, bool* out_overflow) {
  if (n.hi >= d) {
    *out_overflow = true;
    return max_mag;
  }
  uint64_t rem = 0;
  uint64_t q = wide::div_u128_u64(n, d, &rem);
  if (rem >= d - rem) ++q;  // 2·rem ≥ d; q < 2^64 − 1 here because n.hi < d
  if (q > max_mag) {
    *out_overflow = true;
    return max_mag;
  }
  return q;
}

}  // namespace detail

template <typename Raw, int Frac>
constexpr Fixed<Raw, Frac> Fixed<Raw, Frac>::from_ratio(int64_t num, int64_t den) {
  using F = Fixed<Raw, Frac>;
  if (den == 0) {
    TANDEM_FIXED_FAULT(FixedFault::divide_by_zero, Frac == 32 ? "Q32.32 from ratio" : "Q16.16 from ratio");
    return F::from_raw(num == 0 ? Raw{0} : (num > 0 ? k_raw_max : k_raw_min));
  }
  const bool negative = (num < 0) != (den < 0);
  const wide::U128 n = wide::shl(wide::U128{detail::magnitude(num), 0}, Frac);
  bool overflow = false;
  const uint64_t q = detail::div_round_mag(n, detail::magnitude(den), static_cast<uint64_t>(k_raw_max), &overflow);
  if (overflow) TANDEM_FIXED_FAULT(FixedFault::out_of_range, Frac == 32 ? "Q32.32 from ratio" : "Q16.16 from ratio");
  const Raw m = static_cast<Raw>(q);
  return F::from_raw(negative ? static_cast<Raw>(-m) : m);
}

// --- × and ÷ ---------------------------------------------------------------

/// Q32.32 product, portable limb path (exposed so tests can compare paths).
constexpr Q32 mul_portable(Q32 a, Q32 b) {
  bool overflow = false;
  const int64_t r = wide::round_shift_saturate(wide::portable::mul_s64(a.raw, b.raw), 32, &overflow);
  if (overflow) TANDEM_FIXED_FAULT(FixedFault::overflow, "Q32.32 multiply");
  return Q32::from_raw(r);
}

#if defined(__SIZEOF_INT128__)
/// Q32.32 product through the compiler's __int128 (same bits as mul_portable).
constexpr Q32 mul_native(Q32 a, Q32 b) {
  __extension__ typedef __int128 s128;
  s128 p = static_cast<s128>(a.raw) * b.raw;          // |p| ≤ 2^126: no overflow
  p += (s128{1} << 31) - (p < 0 ? 1 : 0);            // half, less one ulp when negative
  const s128 q = p >> 32;                             // floor: arithmetic shift (C++20)
  if (q > INT64_MAX || q < -INT64_MAX) {
    TANDEM_FIXED_FAULT(FixedFault::overflow, "Q32.32 multiply");
    return Q32::from_raw(q > 0 ? INT64_MAX : -INT64_MAX);
  }
  return Q32::from_raw(static_cast<int64_t>(q));
}
#endif

/// a × b rounded to nearest, ties away from zero; saturating.
template <typename Raw, int Frac>
constexpr Fixed<Raw, Frac> operator*(Fixed<Raw, Frac> a, Fixed<Raw, Frac> b) {
  using F = Fixed<Raw, Frac>;
  if constexpr (Frac == 32) {
#if TANDEM_HAS_INT128
    return mul_native(a, b);
#else
    return mul_portable(a, b);
#endif
  } else {
    int64_t p = static_cast<int64_t>(a.raw) * b.raw;  // |p| ≤ 2^62
    p += (int64_t{1} << 15) - (p < 0 ? 1 : 0);
    const int64_t q = p >> 16;
    if (q > F::k_raw_max || q < F::k_raw_min) {
      TANDEM_FIXED_FAULT(FixedFault::overflow, "Q16.16 multiply");
      return F::from_raw(q > 0 ? F::k_raw_max : F::k_raw_min);
    }
    return F::from_raw(static_cast<Raw>(q));
  }
}

/// a ÷ b rounded to nearest, ties away from zero; saturating. b == 0 gives
/// 0 for 0/0, else ±max with the sign of a.
template <typename Raw, int Frac>
constexpr Fixed<Raw, Frac> operator/(Fixed<Raw, Frac> a, Fixed<Raw, Frac> b) {
  using F = Fixed<Raw, Frac>;
  if (b.raw == 0) {
    TANDEM_FIXED_FAULT(FixedFault::divide_by_zero, Frac == 32 ? "Q32.32 divide" : "Q16.16 divide");
    return F::from_raw(a.raw == 0 ? Raw{0} : (a.raw > 0 ? F::k_raw_max : F::k_raw_min));
  }
  const bool negative = (a.raw < 0) != (b.raw < 0);
  const uint64_t ua = detail::magnitude(a.raw), ub = detail::magnitude(b.raw);
  uint64_t q;
  bool overflow = false;
  if constexpr (Frac == 32) {
    q = detail::div_round_mag(wide::U128{ua << 32, ua >> 32}, ub, static_cast<uint64_t>(F::k_raw_max), &overflow);
  } else {
    const uint64_t n = ua << 16;  // ua ≤ 2^31: fits
    q = n / ub;
    const uint64_t rem = n - q * ub;
    if (rem >= ub - rem) ++q;
    if (q > static_cast<uint64_t>(F::k_raw_max)) {
      overflow = true;
      q = static_cast<uint64_t>(F::k_raw_max);
    }
  }
  if (overflow) TANDEM_FIXED_FAULT(FixedFault::overflow, Frac == 32 ? "Q32.32 divide" : "Q16.16 divide");
  const Raw m = static_cast<Raw>(q);
  return F::from_raw(negative ? static_cast<Raw>(-m) : m);
}

// --- helpers ---------------------------------------------------------------

/// |a|; exact.
template <typename R, int F>
constexpr Fixed<R, F> abs(Fixed<R, F> a) { return a.raw < 0 ? -a : a; }
/// The smaller of a and b.
template <typename R, int F>
constexpr Fixed<R, F> min(Fixed<R, F> a, Fixed<R, F> b) { return b < a ? b : a; }
/// The larger of a and b.
template <typename R, int F>
constexpr Fixed<R, F> max(Fixed<R, F> a, Fixed<R, F> b) { return a < b ? b : a; }
/// a limited to [lo, hi] (requires lo ≤ hi).
template <typename R, int F>
constexpr Fixed<R, F> clamp(Fixed<R, F> a, Fixed<R, F> lo, Fixed<R, F> hi) { return a < lo ? lo : (hi < a ? hi : a); }
/// −1, 0 or +1 as an integer.
template <typename R, int F>
constexpr int sign(Fixed<R, F> a) { return (a.raw > 0) - (a.raw < 0); }

/// The largest integer value ≤ a. Exact.
template <typename R, int F>
constexpr Fixed<R, F> floor(Fixed<R, F> a) {
  using U = std::make_unsigned_t<R>;
  return Fixed<R, F>::from_raw(static_cast<R>(static_cast<U>(a.raw) & ~static_cast<U>(Fixed<R, F>::k_raw_one - 1)));
}
/// The smallest integer value ≥ a; saturates (to the largest integer) above
/// the largest integer value.
template <typename R, int F>
constexpr Fixed<R, F> ceil(Fixed<R, F> a) {
  using Fx = Fixed<R, F>;
  const Fx f = floor(a);
  if (f == a) return f;
  if (f.raw > Fx::k_raw_max - Fx::k_raw_one) {
    TANDEM_FIXED_FAULT(FixedFault::overflow, F == 32 ? "Q32.32 ceil" : "Q16.16 ceil");
    return f;  // the largest integer: the exact answer 2^(int bits − 1) is not representable
  }
  return Fx::from_raw(static_cast<R>(f.raw + Fx::k_raw_one));
}
/// a rounded to the nearest integer value, ties away from zero; saturates
/// like ceil.
template <typename R, int F>
constexpr Fixed<R, F> round(Fixed<R, F> a) {
  using Fx = Fixed<R, F>;
  const Fx m = abs(a);
  const Fx f = floor(m);
  Fx r = f;
  if (m.raw - f.raw >= Fx::k_raw_one / 2) {
    if (f.raw > Fx::k_raw_max - Fx::k_raw_one) {
      TANDEM_FIXED_FAULT(FixedFault::overflow, F == 32 ? "Q32.32 round" : "Q16.16 round");
    } else {
      r = Fx::from_raw(static_cast<R>(f.raw + Fx::k_raw_one));
    }
  }
  return a.raw < 0 ? -r : r;
}
/// Remainder of a ÷ b truncated towards zero (like C's fmod): the result has
/// the sign of a and |result| < |b|. Exact. b == 0 gives 0, reported as
/// divide_by_zero.
template <typename R, int F>
constexpr Fixed<R, F> mod(Fixed<R, F> a, Fixed<R, F> b) {
  if (b.raw == 0) {
    TANDEM_FIXED_FAULT(FixedFault::divide_by_zero, F == 32 ? "Q32.32 mod" : "Q16.16 mod");
    return {};
  }
  if (b.raw == -1) return {};  // avoids the one overflowing case of %
  return Fixed<R, F>::from_raw(static_cast<R>(a.raw % b.raw));
}

// --- conversions between formats --------------------------------------------

/// Q16.16 → Q32.32: exact.
constexpr Q32 to_q32(Q16 a) { return Q32::from_raw(static_cast<int64_t>(a.raw) * 65536); }

/// Q32.32 → Q16.16: rounds to nearest, ties away from zero; saturates (and
/// reports out_of_range) outside ±32768.
constexpr Q16 to_q16(Q32 a) {
  const bool negative = a.raw < 0;
  const uint64_t m = (detail::magnitude(a.raw) + (uint64_t{1} << 15)) >> 16;  // no wrap: ≤ 2^63 + 2^15
  if (m > static_cast<uint64_t>(Q16::k_raw_max)) {
    TANDEM_FIXED_FAULT(FixedFault::out_of_range, "Q32.32 to Q16.16");
    return Q16::from_raw(negative ? Q16::k_raw_min : Q16::k_raw_max);
  }
  const int32_t r = static_cast<int32_t>(m);
  return Q16::from_raw(negative ? -r : r);
}

// --- decimal text -----------------------------------------------------------

/// The outcome of parsing decimal text. On failure `value` is zero, `error`
/// says what was wrong and `error_offset` is the offset of the offending
/// character in the text (the text's length if it ended too early).
template <typename F>
struct FixedParse {
  F value{};
  const char* error = nullptr;  ///< nullptr on success
  size_t error_offset = 0;
  constexpr bool ok() const { return error == nullptr; }
};

/// Longest accepted run of significant fraction digits (after the decimal
/// point is placed and trailing zeros dropped). Far beyond what decides the
/// rounding of any value a person writes; longer text is rejected, not cut.
inline constexpr size_t k_max_fraction_digits = 320;

/// Parses decimal text exactly, never through binary floating point: an optional sign,
/// digits with at most one '.', and an optional exponent (e or E, optional
/// sign, digits) — the JSON number grammar, plus a leading '+' and leading
/// zeros. The exact decimal value is rounded once to the nearest raw value,
/// ties away from zero. Out-of-range values are an error (not saturated).
template <typename F>
constexpr FixedParse<F> parse_fixed(std::string_view text) {
  FixedParse<F> out;
  auto fail = [&](const char* message, size_t offset) {
    out.value = F{};
    out.error = message;
    out.error_offset = offset;
    return out;
  };
  size_t i = 0;
  const size_t n = text.size();
  if (n == 0) return fail("empty text: expected a number", 0);
  bool negative = false;
  if (text[i] == '+' || text[i] == '-') {
    negative = text[i] == '-';
    ++i;
  }
  // Significant digits, leading zeros dropped; point = digits before the '.'.
  std::array<char, 2 * k_max_fraction_digits + 64> digits{};
  size_t count = 0;
  int64_t point = 0;
  bool seen_digit = false, seen_dot = false, too_long = false;
  for (; i < n; ++i) {
    const char c = text[i];
    if (c >= '0' && c <= '9') {
      seen_digit = true;
      if (count == 0 && c == '0') {
        if (seen_dot) --point;  // a leading zero after the point shifts it
        continue;
      }
      if (count < digits.size()) {
        digits[count++] = static_cast<char>(c - '0');
        if (!seen_dot) ++point;
      } else if (c != '0') {
        too_long = true;
      } else if (!seen_dot) {
        ++point;  // a zero beyond the buffer in the integer part still counts
      }
    } else if (c == '.') {
      if (seen_dot) return fail("unexpected second '.'", i);
      seen_dot = true;
    } else {
      break;
    }
  }
  if (!seen_digit) return fail(i < n ? "unexpected character: expected a digit" : "expected a digit", i);
  if (i < n && (text[i] == 'e' || text[i] == 'E')) {
    ++i;
    bool exp_negative = false;
    if (i < n && (text[i] == '+' || text[i] == '-')) {
      exp_negative = text[i] == '-';
      ++i;
    }
    if (i >= n) return fail("expected a digit in the exponent", i);
    if (text[i] < '0' || text[i] > '9') return fail("unexpected character: expected a digit in the exponent", i);
    int64_t e = 0;
    for (; i < n && text[i] >= '0' && text[i] <= '9'; ++i) {
      if (e < 100000) e = e * 10 + (text[i] - '0');
    }
    point += exp_negative ? -e : e;
  }
  if (i < n) return fail("unexpected character", i);
  if (too_long) return fail("too many significant digits", n);
  // Drop trailing zeros.
  while (count > 0 && digits[count - 1] == 0) --count;
  if (count == 0) return out;  // zero (either sign)
  // Integer part: the digits before the point.
  constexpr uint64_t int_limit = uint64_t{1} << (F::k_int_bits - 1);  // exclusive
  if (point > static_cast<int64_t>(F::k_int_bits)) return fail("out of range", 0);
  uint64_t integer = 0;
  for (int64_t k = 0; k < point; ++k) {
    integer = integer * 10 + (k < static_cast<int64_t>(count) ? static_cast<uint64_t>(digits[static_cast<size_t>(k)]) : 0u);
    if (integer >= int_limit) return fail("out of range", 0);
  }
  // Fraction digits: digits[point..count), preceded by −point zeros if point < 0.
  std::array<char, 2 * k_max_fraction_digits + 64> frac{};
  size_t frac_count = 0;
  if (point < 0) {
    if (-point > 20) return out;  // value < 10^-20: far below half a raw unit, rounds to zero
    for (int64_t k = 0; k < -point; ++k) frac[frac_count++] = 0;
  }
  for (size_t k = point > 0 ? static_cast<size_t>(point) : 0; k < count; ++k) {
    if (frac_count >= k_max_fraction_digits) return fail("too many significant digits", n);
    frac[frac_count++] = digits[k];
  }
  // Binary fraction by repeated doubling of the decimal fraction.
  uint64_t bits = 0;
  for (int b = 0; b < F::k_frac_bits; ++b) {
    int carry = 0;
    for (size_t k = frac_count; k-- > 0;) {
      const int v = frac[k] * 2 + carry;
      frac[k] = static_cast<char>(v % 10);
      carry = v / 10;
    }
    bits = (bits << 1) | static_cast<uint64_t>(carry);
  }
  // Round: what remains is ≥ 1/2 exactly when its first digit is ≥ 5; a tie
  // (exactly 1/2) rounds away from zero, so the first digit decides alone.
  if (frac_count > 0 && frac[0] >= 5) ++bits;
  const uint64_t magnitude = (integer << F::k_frac_bits) + bits;
  if (magnitude > static_cast<uint64_t>(F::k_raw_max)) return fail("out of range", 0);
  const auto m = static_cast<typename F::raw_type>(magnitude);
  out.value = F::from_raw(negative ? static_cast<typename F::raw_type>(-m) : m);
  return out;
}

/// Parses Q32.32 decimal text; see parse_fixed.
constexpr FixedParse<Q32> parse_q32(std::string_view text) { return parse_fixed<Q32>(text); }
/// Parses Q16.16 decimal text; see parse_fixed.
constexpr FixedParse<Q16> parse_q16(std::string_view text) { return parse_fixed<Q16>(text); }

/// A one-line description of a parse failure that shows the offending
/// character, e.g. `unexpected character 'x' at offset 3 in "1.2x"`.
std::string describe_parse_error(std::string_view text, const char* error, size_t offset);

/// Formats a value as exact decimal text (every binary fraction has a finite
/// decimal expansion): "-1.5", "0.0000152587890625". Integer arithmetic only.
template <typename R, int F>
std::string to_string(Fixed<R, F> a);

extern template std::string to_string(Q32);
extern template std::string to_string(Q16);

namespace detail {
void literal_error(const char* message);  // not constexpr: a call makes the literal ill-formed
template <typename F>
consteval F parse_literal(const char* s) {
  size_t len = 0;
  while (s[len] != '\0') ++len;
  const FixedParse<F> p = parse_fixed<F>(std::string_view(s, len));
  if (!p.ok()) literal_error(p.error);
  return p.value;
}
}  // namespace detail

namespace literals {
/// Q32.32 literal: 1.5_q32, 0.016666_q32, 3_q32, 2.5e-3_q32. Parsed exactly at
/// compile time; malformed or out-of-range text does not compile.
consteval Q32 operator""_q32(const char* s) { return detail::parse_literal<Q32>(s); }
/// Q16.16 literal: 1.5_q16. Parsed exactly at compile time.
consteval Q16 operator""_q16(const char* s) { return detail::parse_literal<Q16>(s); }
}  // namespace literals

}  // namespace tandem
