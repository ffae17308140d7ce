// test_fixed_math.cpp — fixed_math: exactness of the integer square roots,
// accuracy of sin/cos/atan2 against a long double oracle, edge inputs, domain
// faults, and a golden hash that every platform (x86-64 native __int128,
// i686 / forced portable 128-bit path, big-endian s390x) must reproduce.
//
// Square roots are checked exactly with a small independent multi-word
// integer type (Big, below), never with floating point. sin/cos/atan2 use
// sinl/cosl/atan2l; that needs a long double of at least 64 mantissa bits
// (x86 80-bit, IEEE quad on s390x/aarch64 Linux); with a narrower one the
// oracle is too coarse for Q32.32 and those assertions are skipped with a
// warning.
//
// Random inputs are raw integers from a seeded std::mt19937_64 (fully
// specified), shifted right by a random amount so every magnitude is covered.
// The count is TANDEM_ACCURACY_SAMPLES when defined, else 10 million per
// function in NDEBUG builds and 200,000 in debug/sanitizer builds.
#include <catch2/catch.hpp>

#include <array>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>
#include <vector>

#include "fixed/fixed_math.h"

using namespace tandem;

namespace {

#if defined(TANDEM_ACCURACY_SAMPLES)
constexpr long k_samples = TANDEM_ACCURACY_SAMPLES;
#elif defined(NDEBUG)
constexpr long k_samples = 10'000'000;
#else
constexpr long k_samples = 200'000;
#endif

constexpr bool k_oracle_ok = LDBL_MANT_DIG >= 64;

// --- Big: 256-bit unsigned integers in 32-bit words (test-only oracle) -------

struct Big {
  std::array<uint32_t, 8> w{};  // little-endian words
};

Big big(uint64_t lo, uint64_t hi = 0) {
  Big b;
  b.w[0] = static_cast<uint32_t>(lo);
  b.w[1] = static_cast<uint32_t>(lo >> 32);
  b.w[2] = static_cast<uint32_t>(hi);
  b.w[3] = static_cast<uint32_t>(hi >> 32);
  return b;
}
Big big(wide::U128 v) { return big(v.lo, v.hi); }

Big operator+(const Big& a, const Big& b) {
  Big r;
  uint64_t carry = 0;
  for (size_t i = 0; i < 8; ++i) {
    const uint64_t s = uint64_t{a.w[i]} + b.w[i] + carry;
    r.w[i] = static_cast<uint32_t>(s);
    carry = s >> 32;
  }
  return r;
}

Big operator*(const Big& a, const Big& b) {  // modulo 2^256
  Big r;
  for (size_t i = 0; i < 8; ++i) {
    if (a.w[i] == 0) continue;
    uint64_t carry = 0;
    for (size_t j = 0; i + j < 8; ++j) {
      const uint64_t t = uint64_t{a.w[i]} * b.w[j] + r.w[i + j] + carry;
      r.w[i + j] = static_cast<uint32_t>(t);
      carry = t >> 32;
    }
  }
  return r;
}

/// a / 2^s, 0 ≤ s < 32·8.
Big shr(const Big& a, unsigned s) {
  Big r;
  const size_t words = s / 32;
  const unsigned bits = s % 32;
  for (size_t i = 0; i + words < 8; ++i) {
    uint64_t v = a.w[i + words];
    if (i + words + 1 < 8) v |= uint64_t{a.w[i + words + 1]} << 32;
    r.w[i] = static_cast<uint32_t>(v >> bits);
  }
  return r;
}

uint64_t low64(const Big& a) { return uint64_t{a.w[0]} | (uint64_t{a.w[1]} << 32); }

bool operator<(const Big& a, const Big& b) {
  for (size_t i = 8; i-- > 0;) {
    if (a.w[i] != b.w[i]) return a.w[i] < b.w[i];
  }
  return false;
}
bool operator<=(const Big& a, const Big& b) { return !(b < a); }

/// r == floor(√n) ⇔ r² ≤ n < (r + 1)².
bool is_floor_sqrt(const Big& n, uint64_t r) {
  const Big br = big(r), br1 = br + big(1);
  return br * br <= n && n < br1 * br1;
}

/// r == round(√n) ⇔ (r − ½)² ≤ n < (r + ½)² ⇔ (2r − 1)² ≤ 4n < (2r + 1)²,
/// written without subtraction: 4r² + 1 ≤ 4n + 4r and 4n < 4r² + 4r + 1.
bool is_round_sqrt(const Big& n, uint64_t r) {
  const Big four_n = n * big(4);
  const Big four_r = big(r) * big(4);
  const Big four_r2 = big(r) * big(r) * big(4);
  const bool below = four_n < four_r2 + four_r + big(1);
  return r == 0 ? below : below && four_r2 + big(1) <= four_n + four_r;
}

// --- random raw integers -----------------------------------------------------

/// A random int64 with a random magnitude (shifted right by 0..63).
int64_t draw_i64(std::mt19937_64& g) {
  const uint64_t v = g();
  const unsigned s = static_cast<unsigned>(g() % 64);
  return static_cast<int64_t>(v) >> s;
}
int32_t draw_i32(std::mt19937_64& g) {
  const uint64_t v = g();
  const unsigned s = static_cast<unsigned>(g() % 32);
  return static_cast<int32_t>(static_cast<uint32_t>(v >> 32)) >> s;
}
wide::U128 draw_u128(std::mt19937_64& g) {
  const wide::U128 v{g(), g()};
  return wide::shr_u(v, static_cast<unsigned>(g() % 128));
}

// --- edge inputs ---------------------------------------------------------------

// round(π/2·2^94) = k_half_pi_hp_hi·2^64 + k_half_pi_hp_lo (offline, exact).
constexpr uint64_t k_half_pi_hp_hi = 0x6487ED51u;
constexpr uint64_t k_half_pi_hp_lo = 0x10B4611A62633146u;

/// The raw value nearest to k·π/2 in a format with `frac` fraction bits.
uint64_t near_multiple_of_half_pi(uint64_t k, unsigned frac) {
  const Big p = big(k) * big(k_half_pi_hp_lo, k_half_pi_hp_hi);  // k·π/2·2^94
  const unsigned s = 94 - frac;
  return low64(shr(p + shr(big(0, uint64_t{1} << 63), 128 - s), s));  // + 2^(s−1), then / 2^s
}

// Numerators of the continued-fraction convergents of π/2·2^32 and
// π/2·2^16: the raw values that come closest to multiples of π/2 (computed
// offline from a 390-bit π; these are inputs, not expected results).
constexpr int64_t k_convergents_q32[] = {6746518852,          20239556557,         26986075409,
                                         128183858193,        155169933602,        1990223061417,
                                         2145392995019,       6281009051455,       33550438252294,
                                         39831447303749,      192876227467290,     1775717494509359,
                                         5520028710995367,    7295746205504726,    27407267327509545,
                                         34703013533014271,   62110280860523816,   904246945580347695,
                                         2774851117601566901};
constexpr int32_t k_convergents_q16[] = {102943,  102944,   308831,   720606,    1750043,   2470649,
                                         14103288, 16573937, 362155965, 378729902, 1498345671, 1877075573};

/// Edge raw values for Q32.32: 0, ±1, the extremes, powers of two and their
/// neighbours, and angles next to k·π/2 (small k, large k, convergents).
std::vector<int64_t> edge_raws_q32() {
  std::vector<int64_t> v;
  auto both = [&v](int64_t x) {
    v.push_back(x);
    v.push_back(x == INT64_MIN ? x : -x);
  };
  for (int64_t d = 0; d <= 3; ++d) {
    both(d);
    both(INT64_MAX - d);
  }
  v.push_back(INT64_MIN);
  for (unsigned k = 1; k < 63; ++k) {
    const int64_t p = int64_t{1} << k;
    both(p - 1);
    both(p);
    both(p + 1);
  }
  std::mt19937_64 g(0x51A7E5);
  std::vector<uint64_t> ks;
  for (uint64_t k = 1; k <= 4000; ++k) ks.push_back(k);
  for (int i = 0; i < 4000; ++i) ks.push_back(1 + g() % 1367130000u);  // k·π/2 < 2^31
  for (const uint64_t k : ks) {
    const int64_t c = static_cast<int64_t>(near_multiple_of_half_pi(k, 32));
    for (int64_t d = -3; d <= 3; ++d) {
      if (c > 3 && c <= INT64_MAX - 3) both(c + d);
    }
  }
  for (const int64_t c : k_convergents_q32) {
    for (int64_t d = -2; d <= 2; ++d) both(c + d);
  }
  return v;
}

/// Edge raw values for Q16.16, including every k·π/2 in range (±2 raw units).
std::vector<int32_t> edge_raws_q16() {
  std::vector<int32_t> v;
  auto both = [&v](int32_t x) {
    v.push_back(x);
    v.push_back(x == INT32_MIN ? x : -x);
  };
  for (int32_t d = 0; d <= 3; ++d) {
    both(d);
    both(INT32_MAX - d);
  }
  v.push_back(INT32_MIN);
  for (unsigned k = 1; k < 31; ++k) {
    const int32_t p = int32_t{1} << k;
    both(p - 1);
    both(p);
    both(p + 1);
  }
  for (uint64_t k = 1;; ++k) {
    const uint64_t c = near_multiple_of_half_pi(k, 16);
    if (c + 2 > static_cast<uint64_t>(INT32_MAX)) break;
    for (int d = -2; d <= 2; ++d) both(static_cast<int32_t>(static_cast<int64_t>(c) + d));
  }
  for (const int32_t c : k_convergents_q16) {
    for (int32_t d = -2; d <= 2; ++d) {
      if (d <= 0 || c <= INT32_MAX - d) both(c + d);
    }
  }
  return v;
}

// --- oracle error tracking ---------------------------------------------------------

/// The largest |got − truth·2^frac| seen, in raw units, and where.
struct MaxError {
  long double err = 0;
  int64_t at = 0;
  int64_t at2 = 0;
  void add(int64_t got, long double truth, int frac, int64_t input, int64_t input2 = 0) {
    const long double e = std::fabs(static_cast<long double>(got) - std::ldexp(truth, frac));
    if (e > err) {
      err = e;
      at = input;
      at2 = input2;
    }
  }
};

long double value_of(int64_t raw, int frac) { return std::ldexp(static_cast<long double>(raw), -frac); }

// --- fault counting ----------------------------------------------------------------

int g_domain_faults = 0;
int g_other_faults = 0;
void count_fault(FixedFault fault, const char*) {
  if (fault == FixedFault::domain) {
    ++g_domain_faults;
  } else {
    ++g_other_faults;
  }
}

struct CountingHandler {
  FixedFaultHandler old;
  CountingHandler() : old(set_fixed_fault_handler(&count_fault)) { g_domain_faults = g_other_faults = 0; }
  ~CountingHandler() { set_fixed_fault_handler(old); }
  CountingHandler(const CountingHandler&) = delete;
  CountingHandler& operator=(const CountingHandler&) = delete;
};

// --- hashing -------------------------------------------------------------------------

/// FNV-1a over the little-endian bytes of each value (independent of the
/// host's byte order).
struct Fnv {
  uint64_t h = 0xCBF29CE484222325u;
  void add(uint64_t v) {
    for (int i = 0; i < 8; ++i) {
      h ^= (v >> (8 * i)) & 0xFFu;
      h *= 0x100000001B3u;
    }
  }
  void add_signed(int64_t v) { add(static_cast<uint64_t>(v)); }
};

}  // namespace

// ====================================================================================

TEST_CASE("isqrt_floor and isqrt_round are exact on 128-bit integers", "[fixed][math]") {
  std::vector<wide::U128> inputs;
  const uint64_t all = ~uint64_t{0};
  for (uint64_t v = 0; v < 1000; ++v) inputs.push_back(wide::U128{v, 0});
  inputs.push_back(wide::U128{all, all});
  inputs.push_back(wide::U128{all - 1, all});
  inputs.push_back(wide::U128{0, uint64_t{1} << 63});
  inputs.push_back(wide::U128{all, all >> 1});
  inputs.push_back(wide::U128{all, 0});
  inputs.push_back(wide::U128{0, 1});
  for (unsigned k = 0; k < 128; ++k) {
    const wide::U128 p = wide::shl(wide::U128{1, 0}, k);
    inputs.push_back(p);
    inputs.push_back(wide::sub(p, wide::U128{1, 0}));
    inputs.push_back(wide::add(p, wide::U128{1, 0}));
  }
  // Perfect squares, squares ± 1, and the midpoints r² + r, r² + r + 1 where
  // rounding flips, for roots at every magnitude including 2^64 − 1.
  std::mt19937_64 g(0x15C0);
  std::vector<uint64_t> roots = {1, 2, 3, all, all - 1, uint64_t{1} << 63, (uint64_t{1} << 32) - 1, uint64_t{1} << 32};
  for (int i = 0; i < 20000; ++i) roots.push_back(g() >> (g() % 64));
  for (const uint64_t r : roots) {
    const wide::U128 sq = wide::mul_u64(r, r);
    const wide::U128 one{1, 0};
    inputs.push_back(sq);
    inputs.push_back(wide::sub(sq, one));
    inputs.push_back(wide::add(sq, one));
    const wide::U128 mid = wide::add(sq, wide::U128{r, 0});  // r² + r: rounds down; r² + r + 1 up
    inputs.push_back(mid);
    if (r != all) inputs.push_back(wide::add(mid, one));
  }
  long failures = 0;
  auto check = [&failures](wide::U128 n) {
    const uint64_t f = isqrt_floor(n);
    const uint64_t r = isqrt_round(n);
    const Big bn = big(n);
    bool ok = is_floor_sqrt(bn, f);
    // isqrt_round saturates at 2^64 − 1 (only for n ≥ (2^64 − ½)²).
    if (r == ~uint64_t{0} && !is_round_sqrt(bn, r)) {
      ok = ok && !(bn < big(0, ~uint64_t{0}));  // n ≥ 2^128 − 2^64: the exact answer is 2^64
    } else {
      ok = ok && is_round_sqrt(bn, r);
    }
    if (!ok && failures++ < 5) {
      INFO("n = " << n.hi << "·2^64 + " << n.lo << ", floor " << f << ", round " << r);
      CHECK(ok);
    }
  };
  for (const wide::U128 n : inputs) check(n);
  for (long i = 0; i < k_samples; ++i) check(draw_u128(g));
  CHECK(failures == 0);
  CHECK(isqrt_floor(wide::U128{~uint64_t{0}, ~uint64_t{0}}) == ~uint64_t{0});
  CHECK(isqrt_round(wide::U128{~uint64_t{0}, ~uint64_t{0}}) == ~uint64_t{0});  // saturated
  CHECK(isqrt_round(wide::U128{2, 0}) == 1);
  CHECK(isqrt_round(wide::U128{3, 0}) == 2);
  CHECK(isqrt_floor(wide::U128{0, 1}) == uint64_t{1} << 32);
}

TEST_CASE("sqrt is correctly rounded (error <= 0.5 raw unit)", "[fixed][math]") {
  std::mt19937_64 g(0x5E1);
  SECTION("Q32.32") {
    std::vector<int64_t> xs;
    for (const int64_t x : edge_raws_q32()) {
      if (x >= 0) xs.push_back(x);
    }
    long failures = 0;
    auto check = [&failures](int64_t raw) {
      const Q32 r = sqrt(Q32::from_raw(raw));
      // √(raw·2^-32) in Q32.32 is √(raw·2^32) in raw units.
      const Big n = big(static_cast<uint64_t>(raw)) * big(uint64_t{1} << 32);
      const bool ok = r.raw >= 0 && is_round_sqrt(n, static_cast<uint64_t>(r.raw));
      if (!ok && failures++ < 5) {
        INFO("raw " << raw << " -> " << r.raw);
        CHECK(ok);
      }
    };
    for (const int64_t x : xs) check(x);
    for (long i = 0; i < k_samples; ++i) check(draw_i64(g) & INT64_MAX);
    CHECK(failures == 0);
    CHECK(sqrt(Q32::from_raw(0)).raw == 0);
    CHECK(sqrt(Q32(4)) == Q32(2));
  }
  SECTION("Q16.16") {
    long failures = 0;
    auto check = [&failures](int32_t raw) {
      const Q16 r = sqrt(Q16::from_raw(raw));
      const Big n = big(static_cast<uint64_t>(raw)) * big(uint64_t{1} << 16);
      const bool ok = r.raw >= 0 && is_round_sqrt(n, static_cast<uint64_t>(r.raw));
      if (!ok && failures++ < 5) {
        INFO("raw " << raw << " -> " << r.raw);
        CHECK(ok);
      }
    };
    for (const int32_t x : edge_raws_q16()) {
      if (x >= 0) check(x);
    }
    for (long i = 0; i < k_samples; ++i) check(draw_i32(g) & INT32_MAX);
    CHECK(failures == 0);
    CHECK(sqrt(Q16(9)) == Q16(3));
  }
}

TEST_CASE("rsqrt is correctly rounded (error <= 0.5 raw unit)", "[fixed][math]") {
  std::mt19937_64 g(0x125);
  SECTION("Q32.32") {
    // r = round(2^48/√raw) ⇔ (2r − 1)²·raw ≤ 2^98 < (2r + 1)²·raw.
    const Big limit = shr(big(0, uint64_t{1} << 63), 29);  // 2^98
    long failures = 0;
    auto check = [&](int64_t raw) {
      const Q32 r = rsqrt(Q32::from_raw(raw));
      const Big braw = big(static_cast<uint64_t>(raw));
      const Big rr = big(static_cast<uint64_t>(r.raw));
      const Big four_r2 = rr * rr * big(4), four_r = rr * big(4);
      const bool ok = r.raw > 0 && (four_r2 + big(1)) * braw <= limit + four_r * braw &&
                      limit < (four_r2 + four_r + big(1)) * braw;
      if (!ok && failures++ < 5) {
        INFO("raw " << raw << " -> " << r.raw);
        CHECK(ok);
      }
    };
    for (const int64_t x : edge_raws_q32()) {
      if (x > 0) check(x);
    }
    for (long i = 0; i < k_samples; ++i) {
      const int64_t x = draw_i64(g) & INT64_MAX;
      check(x == 0 ? 1 : x);
    }
    CHECK(failures == 0);
    CHECK(rsqrt(Q32(4)) == Q32::half());
    CHECK(rsqrt(Q32::from_raw(1)).raw == int64_t{1} << 48);
  }
  SECTION("Q16.16") {
    const Big limit = big(uint64_t{1} << 50);
    long failures = 0;
    auto check = [&](int32_t raw) {
      const Q16 r = rsqrt(Q16::from_raw(raw));
      const Big braw = big(static_cast<uint64_t>(raw));
      const Big rr = big(static_cast<uint64_t>(r.raw));
      const Big four_r2 = rr * rr * big(4), four_r = rr * big(4);
      const bool ok = r.raw > 0 && (four_r2 + big(1)) * braw <= limit + four_r * braw &&
                      limit < (four_r2 + four_r + big(1)) * braw;
      if (!ok && failures++ < 5) {
        INFO("raw " << raw << " -> " << r.raw);
        CHECK(ok);
      }
    };
    for (const int32_t x : edge_raws_q16()) {
      if (x > 0) check(x);
    }
    for (long i = 0; i < k_samples; ++i) {
      const int32_t x = draw_i32(g) & INT32_MAX;
      check(x == 0 ? 1 : x);
    }
    CHECK(failures == 0);
    CHECK(rsqrt(Q16(16)) == Q16::from_raw(16384));
    CHECK(rsqrt(Q16::from_raw(1)).raw == int32_t{1} << 24);
  }
}

TEST_CASE("sin and cos: Q32.32 within 2 raw units, Q16.16 within 1, any angle", "[fixed][math]") {
  std::mt19937_64 g(0x5C05);
  SECTION("Q32.32") {
    MaxError es, ec;
    long bad_range = 0, bad_symmetry = 0;
    auto check = [&](int64_t raw) {
      const SinCos<Q32> sc = sincos(Q32::from_raw(raw));
      if (sc.sin.raw > (int64_t{1} << 32) || sc.sin.raw < -(int64_t{1} << 32) || sc.cos.raw > (int64_t{1} << 32) ||
          sc.cos.raw < -(int64_t{1} << 32)) {
        ++bad_range;
      }
      if (raw != INT64_MIN) {
        const SinCos<Q32> m = sincos(Q32::from_raw(-raw));
        if (m.sin.raw != -sc.sin.raw || m.cos.raw != sc.cos.raw) ++bad_symmetry;
      }
      if (k_oracle_ok) {
        const long double x = value_of(raw, 32);
        es.add(sc.sin.raw, std::sin(x), 32, raw);
        ec.add(sc.cos.raw, std::cos(x), 32, raw);
      }
    };
    for (const int64_t x : edge_raws_q32()) check(x);
    for (long i = 0; i < k_samples; ++i) check(draw_i64(g));
    CHECK(bad_range == 0);
    CHECK(bad_symmetry == 0);
    if (k_oracle_ok) {
      INFO("max sin error " << static_cast<double>(es.err) << " raw units at raw " << es.at);
      CHECK(es.err <= 2.0L);
      INFO("max cos error " << static_cast<double>(ec.err) << " raw units at raw " << ec.at);
      CHECK(ec.err <= 2.0L);
    } else {
      WARN("long double has " << LDBL_MANT_DIG << " mantissa bits (< 64): Q32.32 sin/cos accuracy not checked");
    }
    CHECK(sincos(Q32{}).sin == Q32{});
    CHECK(sincos(Q32{}).cos == Q32::one());
    CHECK(sin(k_half_pi) == Q32::one());
    CHECK(cos(k_pi) == -Q32::one());
    CHECK(sin(Q32::from_raw(12345)) == sincos(Q32::from_raw(12345)).sin);
    CHECK(cos(Q32::from_raw(-12345)) == sincos(Q32::from_raw(-12345)).cos);
  }
  SECTION("Q16.16") {
    MaxError es, ec;
    long bad_symmetry = 0;
    auto check = [&](int32_t raw) {
      const SinCos<Q16> sc = sincos(Q16::from_raw(raw));
      if (raw != INT32_MIN) {
        const SinCos<Q16> m = sincos(Q16::from_raw(-raw));
        if (m.sin.raw != -sc.sin.raw || m.cos.raw != sc.cos.raw) ++bad_symmetry;
      }
      if (k_oracle_ok) {
        const long double x = value_of(raw, 16);
        es.add(sc.sin.raw, std::sin(x), 16, raw);
        ec.add(sc.cos.raw, std::cos(x), 16, raw);
      }
    };
    for (const int32_t x : edge_raws_q16()) check(x);
    for (long i = 0; i < k_samples; ++i) check(draw_i32(g));
    CHECK(bad_symmetry == 0);
    if (k_oracle_ok) {
      INFO("max sin error " << static_cast<double>(es.err) << " raw units at raw " << es.at);
      CHECK(es.err <= 1.0L);
      INFO("max cos error " << static_cast<double>(ec.err) << " raw units at raw " << ec.at);
      CHECK(ec.err <= 1.0L);
    } else {
      WARN("long double has " << LDBL_MANT_DIG << " mantissa bits (< 64): Q16.16 sin/cos accuracy not checked");
    }
    CHECK(sincos(Q16{}).sin == Q16{});
    CHECK(sincos(Q16{}).cos == Q16::one());
    CHECK(sin(k_half_pi_q16) == Q16::one());
    CHECK(cos(k_pi_q16) == -Q16::one());
  }
}

TEST_CASE("atan2: Q32.32 within 2 raw units, Q16.16 within 1, whole input range", "[fixed][math]") {
  std::mt19937_64 g(0xA7A2);
  SECTION("Q32.32") {
    MaxError ea;
    long bad_range = 0, bad_symmetry = 0;
    auto check = [&](int64_t y, int64_t x) {
      const Q32 t = atan2(Q32::from_raw(y), Q32::from_raw(x));
      if (t.raw > k_pi.raw || t.raw < -k_pi.raw) ++bad_range;
      if (y != 0 && y != INT64_MIN && atan2(Q32::from_raw(-y), Q32::from_raw(x)).raw != -t.raw) ++bad_symmetry;
      if (k_oracle_ok && (x != 0 || y != 0)) {
        ea.add(t.raw, std::atan2(static_cast<long double>(y), static_cast<long double>(x)), 32, y, x);
      }
    };
    // Pairs of special values: zero, ±1, extremes, powers of two and neighbours.
    std::vector<int64_t> special = {0, 1, -1, 2, -2, INT64_MAX, -INT64_MAX, INT64_MIN, INT64_MAX - 1};
    for (unsigned k = 1; k < 63; ++k) {
      for (int64_t d = -1; d <= 1; ++d) {
        special.push_back((int64_t{1} << k) + d);
        special.push_back(-((int64_t{1} << k) + d));
      }
    }
    for (const int64_t y : special) {
      for (const int64_t x : special) check(y, x);
    }
    // Ratios at the polynomial segment ends (y/x = k/32) and the diagonal.
    for (int64_t k = 0; k <= 32; ++k) {
      for (const int64_t m : {int64_t{1}, int64_t{3}, int64_t{1} << 20, int64_t{1} << 57, (INT64_MAX / 32) - 5}) {
        for (int64_t d = -1; d <= 1; ++d) {
          check(k * m + d, 32 * m);
          check(32 * m, k * m + d);
          check(-(k * m) - d, -32 * m);
        }
      }
    }
    for (long i = 0; i < k_samples; ++i) {
      const int64_t y = draw_i64(g), x = draw_i64(g);
      check(y, x);
      if (i % 8 == 0) {
        const int64_t delta = static_cast<int64_t>(g() >> (41 + g() % 23));  // < 2^23
        check(x > 0 ? x - delta : x + delta, x);  // |y| ≈ |x|: ratio near 1
      }
    }
    CHECK(bad_range == 0);
    CHECK(bad_symmetry == 0);
    if (k_oracle_ok) {
      INFO("max atan2 error " << static_cast<double>(ea.err) << " raw units at y " << ea.at << ", x " << ea.at2);
      CHECK(ea.err <= 2.0L);
    } else {
      WARN("long double has " << LDBL_MANT_DIG << " mantissa bits (< 64): Q32.32 atan2 accuracy not checked");
    }
    CHECK(atan2(Q32{}, Q32{}) == Q32{});
    CHECK(atan2(Q32{}, Q32(5)) == Q32{});
    CHECK(atan2(Q32{}, Q32(-5)) == k_pi);
    CHECK(atan2(Q32::from_raw(1), Q32{}) == k_half_pi);
    CHECK(atan2(Q32::min(), Q32{}) == -k_half_pi);
    CHECK(atan2(Q32(7), Q32(7)).raw == 3373259426);  // round(π/4·2^32)
    CHECK(atan2(Q32::from_raw(INT64_MIN), Q32::from_raw(INT64_MIN)).raw == -10119778278);  // −round(3π/4·2^32)
  }
  SECTION("Q16.16") {
    MaxError ea;
    long bad_range = 0, bad_symmetry = 0;
    auto check = [&](int32_t y, int32_t x) {
      const Q16 t = atan2(Q16::from_raw(y), Q16::from_raw(x));
      if (t.raw > k_pi_q16.raw || t.raw < -k_pi_q16.raw) ++bad_range;
      if (y != 0 && y != INT32_MIN && atan2(Q16::from_raw(-y), Q16::from_raw(x)).raw != -t.raw) ++bad_symmetry;
      if (k_oracle_ok && (x != 0 || y != 0)) {
        ea.add(t.raw, std::atan2(static_cast<long double>(y), static_cast<long double>(x)), 16, y, x);
      }
    };
    std::vector<int32_t> special = {0, 1, -1, 2, -2, INT32_MAX, -INT32_MAX, INT32_MIN, INT32_MAX - 1};
    for (unsigned k = 1; k < 31; ++k) {
      for (int32_t d = -1; d <= 1; ++d) {
        special.push_back((int32_t{1} << k) + d);
        special.push_back(-((int32_t{1} << k) + d));
      }
    }
    for (const int32_t y : special) {
      for (const int32_t x : special) check(y, x);
    }
    for (long i = 0; i < k_samples; ++i) check(draw_i32(g), draw_i32(g));
    CHECK(bad_range == 0);
    CHECK(bad_symmetry == 0);
    if (k_oracle_ok) {
      INFO("max atan2 error " << static_cast<double>(ea.err) << " raw units at y " << ea.at << ", x " << ea.at2);
      CHECK(ea.err <= 1.0L);
    } else {
      WARN("long double has " << LDBL_MANT_DIG << " mantissa bits (< 64): Q16.16 atan2 accuracy not checked");
    }
    CHECK(atan2(Q16{}, Q16{}) == Q16{});
    CHECK(atan2(Q16{}, Q16(-5)) == k_pi_q16);
    CHECK(atan2(Q16(-3), Q16{}) == -k_half_pi_q16);
    CHECK(atan2(Q16(7), Q16(7)).raw == 51472);  // round(π/4·2^16)
  }
}

TEST_CASE("sqrt and rsqrt report domain faults and return defined values", "[fixed][math]") {
  const CountingHandler handler;
  CHECK(sqrt(Q32::from_raw(-1)) == Q32{});
  CHECK(sqrt(Q32::min()) == Q32{});
  CHECK(sqrt(Q16::from_raw(-1)) == Q16{});
  CHECK(sqrt(Q16::from_raw(INT32_MIN)) == Q16{});
  CHECK(rsqrt(Q32{}) == Q32::max());
  CHECK(rsqrt(Q32(-4)) == Q32::max());
  CHECK(rsqrt(Q16{}) == Q16::max());
  CHECK(rsqrt(Q16(-4)) == Q16::max());
  CHECK(g_domain_faults == (TANDEM_FIXED_CHECKS ? 8 : 0));
  // Valid inputs, extremes included, report nothing.
  g_domain_faults = 0;
  (void)sqrt(Q32{});
  (void)sqrt(Q32::max());
  (void)sqrt(Q16::max());
  (void)rsqrt(Q32::epsilon());
  (void)rsqrt(Q32::max());
  (void)rsqrt(Q16::epsilon());
  (void)sincos(Q32::from_raw(INT64_MIN));
  (void)sincos(Q16::from_raw(INT32_MIN));
  (void)atan2(Q32::from_raw(INT64_MIN), Q32::from_raw(INT64_MIN));
  (void)atan2(Q16::from_raw(INT32_MIN), Q16{});
  CHECK(g_domain_faults == 0);
  CHECK(g_other_faults == 0);
}

TEST_CASE("fixed_math gives the same bits on every platform (golden hash)", "[fixed][math]") {
  // The constant was computed once on x86-64 (native __int128 path); i686,
  // the forced portable path and big-endian s390x must reproduce it.
  constexpr uint64_t k_golden = 0x5FDCFBC42E2F0F40u;
  std::mt19937_64 g(0x601DE11);
  Fnv h;
  for (int i = 0; i < 100000; ++i) {
    const wide::U128 n = draw_u128(g);
    h.add(isqrt_floor(n));
    h.add(isqrt_round(n));
    const int64_t a = draw_i64(g), b = draw_i64(g);
    h.add_signed(sqrt(Q32::from_raw(a & INT64_MAX)).raw);
    h.add_signed(rsqrt(Q32::from_raw((a & INT64_MAX) | 1)).raw);
    const SinCos<Q32> sc = sincos(Q32::from_raw(a));
    h.add_signed(sc.sin.raw);
    h.add_signed(sc.cos.raw);
    h.add_signed(atan2(Q32::from_raw(a), Q32::from_raw(b)).raw);
    const int32_t c = draw_i32(g), d = draw_i32(g);
    h.add_signed(sqrt(Q16::from_raw(c & INT32_MAX)).raw);
    h.add_signed(rsqrt(Q16::from_raw((c & INT32_MAX) | 1)).raw);
    const SinCos<Q16> sc16 = sincos(Q16::from_raw(c));
    h.add_signed(sc16.sin.raw);
    h.add_signed(sc16.cos.raw);
    h.add_signed(atan2(Q16::from_raw(c), Q16::from_raw(d)).raw);
  }
  for (const int64_t x : edge_raws_q32()) {
    const SinCos<Q32> sc = sincos(Q32::from_raw(x));
    h.add_signed(sc.sin.raw);
    h.add_signed(sc.cos.raw);
  }
  for (const int32_t x : edge_raws_q16()) {
    const SinCos<Q16> sc = sincos(Q16::from_raw(x));
    h.add_signed(sc.sin.raw);
    h.add_signed(sc.cos.raw);
  }
  char text[32];
  std::snprintf(text, sizeof text, "0x%016llX", static_cast<unsigned long long>(h.h));
  INFO("hash of fixed_math outputs: " << text << " (portable path: " << (TANDEM_HAS_INT128 ? "no" : "yes") << ")");
  CHECK(h.h == k_golden);
}
