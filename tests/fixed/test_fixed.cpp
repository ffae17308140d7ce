// Tests for fixed/fixed.h: construction, parsing, the rounding rule, the
// overflow rule, conversions, and fault reporting.
#include <catch2/catch.hpp>

#include <cstdint>
#include <random>
#include <string>

#include "fixed/fixed.h"

using namespace tandem;
using namespace tandem::literals;

namespace {

// A fault handler that counts instead of aborting. Installed per test case.
int g_faults = 0;
FixedFault g_last_fault = FixedFault::overflow;
std::string g_last_operation;
void counting_handler(FixedFault fault, const char* operation) {
  ++g_faults;
  g_last_fault = fault;
  g_last_operation = operation;
}

struct CountFaults {
  FixedFaultHandler old;
  CountFaults() : old(set_fixed_fault_handler(&counting_handler)) { g_faults = 0; }
  ~CountFaults() { set_fixed_fault_handler(old); }
  // In builds without checks nothing is reported; the results are the same.
  static int expected(int n) { return TANDEM_FIXED_CHECKS ? n : 0; }
};

#if defined(__SIZEOF_INT128__)
__extension__ typedef __int128 s128;
// Round a/2^s to nearest, ties away from zero: the documented rule.
s128 round_shift(s128 v, int s) {
  const s128 half = s128{1} << (s - 1);
  if (v >= 0) return (v + half) >> s;
  return -((-v + half) >> s);
}
s128 round_div(s128 n, s128 d) {
  const bool negative = (n < 0) != (d < 0);
  const s128 an = n < 0 ? -n : n, ad = d < 0 ? -d : d;
  s128 q = an / ad;
  if (2 * (an - q * ad) >= ad) ++q;
  return negative ? -q : q;
}
int64_t saturate(s128 v) { return v > INT64_MAX ? INT64_MAX : (v < -INT64_MAX ? -INT64_MAX : static_cast<int64_t>(v)); }
#endif

// Raw values with a mix of magnitudes: uniformly random bits shifted right by
// a random amount, random sign.
int64_t random_raw(std::mt19937_64& rng) {
  const uint64_t bits = rng();
  const unsigned shift = static_cast<unsigned>(rng() % 63);
  const int64_t mag = static_cast<int64_t>((bits >> 1) >> shift);
  return (rng() & 1) ? -mag : mag;
}

}  // namespace

TEST_CASE("literals and construction are exact", "[fixed]") {
  STATIC_REQUIRE((1.5_q32).raw == 0x180000000);
  STATIC_REQUIRE((1.5_q16).raw == 0x18000);
  STATIC_REQUIRE((0.1_q32).raw == 429496730);  // 0.1·2^32 = 429496729.6
  STATIC_REQUIRE((2.5e-3_q32).raw == 10737418);  // 0.0025·2^32 = 10737418.24
  STATIC_REQUIRE((3_q32).raw == int64_t{3} << 32);
  STATIC_REQUIRE(Q32(7).raw == int64_t{7} << 32);
  STATIC_REQUIRE(Q32(-7).raw == -(int64_t{7} << 32));
  STATIC_REQUIRE(Q16(-2).raw == -131072);
  CHECK(Q32::from_int(2147483647).raw == int64_t{2147483647} << 32);
  CHECK(Q32::one().raw == int64_t{1} << 32);
  CHECK(Q32::half().raw == int64_t{1} << 31);
  CHECK(Q32::epsilon().raw == 1);
  CHECK(Q32::max().raw == INT64_MAX);
  CHECK(Q32::min().raw == -INT64_MAX);
  CHECK(Q16::min().raw == -INT32_MAX);
}

TEST_CASE("from_ratio rounds to nearest, ties away from zero", "[fixed]") {
  CHECK(Q32::from_ratio(1, 3).raw == 1431655765);    // 1431655765.33
  CHECK(Q32::from_ratio(2, 3).raw == 2863311531);    // 2863311530.67
  CHECK(Q32::from_ratio(-2, 3).raw == -2863311531);
  CHECK(Q32::from_ratio(1, int64_t{1} << 33).raw == 1);    // exactly half a raw unit: away from zero
  CHECK(Q32::from_ratio(-1, int64_t{1} << 33).raw == -1);
  CHECK(Q32::from_ratio(1, (int64_t{1} << 33) + 1).raw == 0);  // just under half
  CHECK(Q32::from_ratio(3, int64_t{1} << 33).raw == 2);    // 1.5 raw units
  CHECK(Q32::from_ratio(1, 60).raw == 71582788);     // the tick: 71582788.27
  CHECK(Q16::from_ratio(1, 60).raw == 1092);         // 1092.27
  CHECK(Q16::from_ratio(-1, 3).raw == -21845);
  CHECK(Q32::from_ratio(INT64_MAX, INT64_MAX) == Q32::one());
  CHECK(Q32::from_ratio(INT64_MIN, INT64_MIN) == Q32::one());
}

TEST_CASE("faults: saturation results and reports", "[fixed]") {
  CountFaults faults;
  CHECK(Q32::from_int(int64_t{1} << 31) == Q32::max());
  CHECK(Q32::from_int(-(int64_t{1} << 31)) == Q32::min());
  CHECK(Q16::from_int(40000) == Q16::max());
  CHECK(g_faults == CountFaults::expected(3));
  if (TANDEM_FIXED_CHECKS) {
    CHECK(g_last_fault == FixedFault::out_of_range);
    CHECK(g_last_operation == "Q16.16 from integer");
  }
  g_faults = 0;
  CHECK(Q32::max() + Q32::epsilon() == Q32::max());
  CHECK(Q32::min() - Q32::epsilon() == Q32::min());
  CHECK(Q32::min() + Q32::min() == Q32::min());
  CHECK(Q32::max() - Q32::min() == Q32::max());
  CHECK(Q16::max() + Q16::one() == Q16::max());
  CHECK(g_faults == CountFaults::expected(5));
  g_faults = 0;
  CHECK(Q32(50000) * Q32(50000) == Q32::max());
  CHECK(Q32(-50000) * Q32(50000) == Q32::min());
  CHECK(Q16(300) * Q16(300) == Q16::max());
  CHECK(Q32::max() * 2 == Q32::max());
  CHECK(Q32::max() * -2 == Q32::min());
  CHECK(g_faults == CountFaults::expected(5));
  if (TANDEM_FIXED_CHECKS) CHECK(g_last_operation == "Q32.32 multiply by integer");
  g_faults = 0;
  CHECK(Q32(5) / Q32(0) == Q32::max());
  CHECK(Q32(-5) / Q32(0) == Q32::min());
  CHECK(Q32(0) / Q32(0) == Q32(0));
  CHECK(Q16(5) / Q16(0) == Q16::max());
  CHECK(Q32(1) / 0 == Q32::max());
  CHECK(mod(Q32(3), Q32(0)) == Q32(0));
  CHECK(Q32::from_ratio(1, 0) == Q32::max());
  CHECK(g_faults == CountFaults::expected(7));
  if (TANDEM_FIXED_CHECKS) CHECK(g_last_fault == FixedFault::divide_by_zero);
  g_faults = 0;
  CHECK(Q32(30000) / Q32::epsilon() == Q32::max());
  CHECK(Q32(-30000) / Q32::epsilon() == Q32::min());
  CHECK(to_q16(Q32(40000)) == Q16::max());
  CHECK(to_q16(Q32(-40000)) == Q16::min());
  CHECK(g_faults == CountFaults::expected(4));
  g_faults = 0;
  // Negating the integer minimum (only reachable through from_raw) saturates.
  CHECK(-Q32::from_raw(INT64_MIN) == Q32::max());
  CHECK(abs(Q32::from_raw(INT64_MIN)) == Q32::max());
  CHECK(mod(Q32::from_raw(INT64_MIN), Q32::from_raw(-1)) == Q32(0));
  // In range: no reports.
  CHECK(Q32(46340) * Q32(46340) == Q32(2147395600));
  CHECK(g_faults == 0);
}

TEST_CASE("default fault handler names the operation", "[fixed]") {
  // Only the message format can be checked without aborting the process.
  CHECK(std::string(fixed_fault_name(FixedFault::overflow)) == "overflow");
  CHECK(std::string(fixed_fault_name(FixedFault::divide_by_zero)) == "division by zero");
  CHECK(std::string(fixed_fault_name(FixedFault::out_of_range)) == "out-of-range conversion");
  CHECK(std::string(fixed_fault_name(FixedFault::domain)) == "domain error");
}

TEST_CASE("multiply and divide follow the rounding rule exactly", "[fixed]") {
  // Hand-checked ties: raw products that land exactly on half a raw unit.
  CHECK((Q32::from_raw(1) * Q32::half()).raw == 1);    // 0.5 raw → 1
  CHECK((Q32::from_raw(-1) * Q32::half()).raw == -1);  // −0.5 raw → −1
  CHECK((Q32::from_raw(3) * Q32::half()).raw == 2);    // 1.5 raw → 2
  CHECK((Q32::from_raw(1) * Q32::from_raw(1)).raw == 0);
  CHECK((Q16::from_raw(1) * Q16::half()).raw == 1);
  CHECK((Q16::from_raw(-3) * Q16::half()).raw == -2);
  CHECK((Q32(1) / Q32(3)).raw == 1431655765);
  CHECK((Q32(-2) / Q32(3)).raw == -2863311531);
  CHECK((Q32::from_raw(1) / Q32(2)).raw == 1);   // half → away
  CHECK((Q32::from_raw(-1) / Q32(2)).raw == -1);
  CHECK((Q32::from_raw(5) / 2).raw == 3);
  CHECK((Q32::from_raw(-5) / 2).raw == -3);
  CHECK((Q32(7) * 3) == Q32(21));
  CHECK((3 * Q32(7)) == Q32(21));

  std::mt19937_64 rng(20261122);
#ifdef NDEBUG
  const int n = 2000000;
#else
  const int n = 100000;
#endif
  CountFaults faults;  // saturating cases are part of the sample
  for (int i = 0; i < n; ++i) {
    const int64_t a = random_raw(rng), b = random_raw(rng);
    const Q32 qa = Q32::from_raw(a), qb = Q32::from_raw(b);
    // Symmetry of the rule: (−a)·b = −(a·b), a·b = b·a.
    REQUIRE((-qa * qb) == -(qa * qb));
    REQUIRE((qa * qb) == (qb * qa));
#if defined(__SIZEOF_INT128__)
    REQUIRE((qa * qb).raw == saturate(round_shift(static_cast<s128>(a) * b, 32)));
    if (b != 0) REQUIRE((qa / qb).raw == saturate(round_div(static_cast<s128>(a) * (s128{1} << 32), b)));
    REQUIRE(mul_portable(qa, qb) == mul_native(qa, qb));
#endif
    // Q16.16 against a 64-bit oracle.
    const int32_t a16 = static_cast<int32_t>(a >> 32), b16 = static_cast<int32_t>(b >> 32);
    if (a16 == INT32_MIN || b16 == INT32_MIN) continue;
    const Q16 x = Q16::from_raw(a16), y = Q16::from_raw(b16);
    const int64_t p = static_cast<int64_t>(a16) * b16;
    const int64_t half = int64_t{1} << 15;
    int64_t expect = p >= 0 ? (p + half) >> 16 : -((-p + half) >> 16);
    expect = expect > INT32_MAX ? INT32_MAX : (expect < -INT32_MAX ? -INT32_MAX : expect);
    REQUIRE((x * y).raw == expect);
    if (b16 != 0) {
      const int64_t num = static_cast<int64_t>(a16) * 65536;
      const int64_t an = num < 0 ? -num : num, ad = b16 < 0 ? -int64_t{b16} : int64_t{b16};
      int64_t q = an / ad;
      if (2 * (an - q * ad) >= ad) ++q;
      if (q > INT32_MAX) q = INT32_MAX;
      REQUIRE((x / y).raw == (((num < 0) != (b16 < 0)) ? -q : q));
    }
  }
}

TEST_CASE("floor, ceil, round, mod, abs, min, max, clamp, sign", "[fixed]") {
  CHECK(floor(2.75_q32) == 2_q32);
  CHECK(floor(-2.25_q32) == Q32(-3));
  CHECK(floor(Q32(-3)) == Q32(-3));
  CHECK(ceil(2.25_q32) == 3_q32);
  CHECK(ceil(-2.75_q32) == Q32(-2));
  CHECK(ceil(Q32(4)) == Q32(4));
  CHECK(round(2.5_q32) == 3_q32);
  CHECK(round(-2.5_q32) == Q32(-3));
  CHECK(round(2.4999999_q32) == 2_q32);
  CHECK(round(-0.4_q32) == Q32(0));
  CHECK(round(1.5_q16) == 2_q16);
  CHECK(floor(-0.5_q16) == Q16(-1));
  CHECK(mod(7.5_q32, 2_q32) == 1.5_q32);
  CHECK(mod(-7.5_q32, 2_q32) == -1.5_q32);
  CHECK(mod(7.5_q32, Q32(-2)) == 1.5_q32);
  CHECK(abs(-3.25_q32) == 3.25_q32);
  CHECK(min(1_q32, 2_q32) == 1_q32);
  CHECK(max(1_q32, 2_q32) == 2_q32);
  CHECK(clamp(5_q32, 0_q32, 2_q32) == 2_q32);
  CHECK(clamp(-5_q32, 0_q32, 2_q32) == 0_q32);
  CHECK(clamp(1.5_q32, 0_q32, 2_q32) == 1.5_q32);
  CHECK(sign(-0.001_q32) == -1);
  CHECK(sign(0_q32) == 0);
  CHECK(sign(Q32::epsilon()) == 1);
  CHECK(Q32(-3).floor_int() == -3);
  CHECK((-2.5_q32).floor_int() == -3);
  CountFaults faults;
  CHECK(ceil(Q32::max()) == floor(Q32::max()));  // 2^31 itself is not representable
  CHECK(round(Q32::max()) == floor(Q32::max()));
  CHECK(round(Q32::min()) == -floor(Q32::max()));
  CHECK(g_faults == CountFaults::expected(3));
}

TEST_CASE("Q16.16 <-> Q32.32 conversions", "[fixed]") {
  CHECK(to_q32(1.5_q16) == 1.5_q32);
  CHECK(to_q32(Q16::min()).raw == -(int64_t{INT32_MAX} << 16));
  CHECK(to_q16(Q32::from_raw(0x8000)).raw == 1);     // exactly half: away from zero
  CHECK(to_q16(Q32::from_raw(-0x8000)).raw == -1);
  CHECK(to_q16(Q32::from_raw(0x7FFF)).raw == 0);
  CHECK(to_q16(Q32::from_raw(0x18000)).raw == 2);
  CHECK(to_q16(0.1_q32) == 0.1_q16);
  std::mt19937_64 rng(7);
  for (int i = 0; i < 100000; ++i) {
    const auto r = static_cast<int32_t>(rng() >> 33);  // ≥ 0, < 2^31
    const Q16 v = Q16::from_raw((rng() & 1) ? -r : r);
    REQUIRE(to_q16(to_q32(v)) == v);  // widening is exact, narrowing undoes it
  }
}

TEST_CASE("decimal text parses exactly", "[fixed]") {
  CHECK(parse_q32("0.1").value.raw == 429496730);
  CHECK(parse_q32("-0.1").value.raw == -429496730);
  CHECK(parse_q32("1e-1").value.raw == 429496730);
  CHECK(parse_q32("0.01E1").value.raw == 429496730);
  CHECK(parse_q32("+3").value == 3_q32);
  CHECK(parse_q32("007.500").value == 7.5_q32);
  CHECK(parse_q32(".5").value == 0.5_q32);
  CHECK(parse_q32("5.").value == 5_q32);
  CHECK(parse_q32("1.5e3").value == 1500_q32);
  CHECK(parse_q32("15000e-1").value == 1500_q32);
  CHECK(parse_q32("-0").value == 0_q32);
  CHECK(parse_q32("0e99999999").value == 0_q32);
  CHECK(parse_q32("1e-400").value == 0_q32);
  // 2^-33 is exactly half a raw unit: ties away from zero.
  CHECK(parse_q32("0.000000000116415321826934814453125").value.raw == 1);
  CHECK(parse_q32("-0.000000000116415321826934814453125").value.raw == -1);
  CHECK(parse_q32("0.000000000116415321826934814453124").value.raw == 0);
  // Digits far beyond the tie still decide it.
  CHECK(parse_q32("0.0000000001164153218269348144531240000000000000000000000000000000000001").value.raw == 0);
  CHECK(parse_q32("0.0000000001164153218269348144531250000000000000000000000000000000000001").value.raw == 1);
  // Extremes.
  CHECK(parse_q32("2147483647.99999999976716935634613037109375").value == Q32::max());
  CHECK(parse_q32("-2147483647.99999999976716935634613037109375").value == Q32::min());
  CHECK(parse_q16("32767.9999847412109375").value == Q16::max());
  CHECK(parse_q16("0.1").value.raw == 6554);  // 6553.6
}

TEST_CASE("malformed decimal text names the character", "[fixed]") {
  struct Case {
    const char* text;
    size_t offset;
    const char* message;
  };
  const Case cases[] = {
      {"", 0, "empty text: expected a number"},
      {"-", 1, "expected a digit"},
      {"1.2.3", 3, "unexpected second '.'"},
      {"1x", 1, "unexpected character"},
      {"12 ", 2, "unexpected character"},
      {"abc", 0, "unexpected character: expected a digit"},
      {"1e", 2, "expected a digit in the exponent"},
      {"1e+", 3, "expected a digit in the exponent"},
      {"1ex", 2, "unexpected character: expected a digit in the exponent"},
      {"--1", 1, "unexpected character: expected a digit"},
      {"0x10", 1, "unexpected character"},
      {"2147483648", 0, "out of range"},
      {"-2147483648", 0, "out of range"},
      {"2147483647.9999999999", 0, "out of range"},  // rounds up past max
      {"1e10", 0, "out of range"},
  };
  for (const Case& c : cases) {
    INFO(c.text);
    const auto r = parse_q32(c.text);
    CHECK_FALSE(r.ok());
    CHECK(r.error_offset == c.offset);
    CHECK(std::string(r.error) == c.message);
    CHECK(r.value == Q32{});
  }
  CHECK(describe_parse_error("1.2x", parse_q32("1.2x").error, 3) == "unexpected character 'x' at offset 3 in \"1.2x\"");
  CHECK_FALSE(parse_q16("32768").ok());
  CHECK_FALSE(parse_q32(std::string(400, '1').insert(1, ".")).ok());
}

TEST_CASE("to_string is exact and parse round-trips it", "[fixed]") {
  CHECK(to_string(-1.5_q32) == "-1.5");
  CHECK(to_string(Q32::epsilon()) == "0.00000000023283064365386962890625");
  CHECK(to_string(Q16::epsilon()) == "0.0000152587890625");
  CHECK(to_string(Q32(0)) == "0");
  CHECK(to_string(Q32::max()) == "2147483647.99999999976716935634613037109375");
  std::mt19937_64 rng(11);
  for (int i = 0; i < 20000; ++i) {
    const Q32 v = Q32::from_raw(random_raw(rng));
    REQUIRE(parse_q32(to_string(v)).value == v);
    const Q16 w = Q16::from_raw(static_cast<int32_t>(random_raw(rng) >> 32));
    REQUIRE(parse_q16(to_string(w)).value == w);
  }
}

TEST_CASE("comparisons and to_double", "[fixed]") {
  CHECK(1_q32 < 2_q32);
  CHECK(Q32(-1) < Q32(0));
  CHECK(2_q32 >= 2_q32);
  CHECK(1.5_q32 != 1.25_q32);
  CHECK((0.25_q32).to_double() == 0.25);
  CHECK((-0.25_q16).to_double() == -0.25);
}
