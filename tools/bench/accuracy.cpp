// accuracy.cpp — tandem_fixed_accuracy: the largest error of Tandem's sqrt,
// sin, cos and atan2 in Q32.32 and Q16.16, and of libfixmath's fix16_sqrt,
// fix16_sin, fix16_cos and fix16_atan2, against a long double oracle. Prints a
// Markdown table.
//
// Usage: tandem_fixed_accuracy [--samples N] [--seed S]   (N default 10000000)
//
// Method:
// * Each row draws N inputs as Q32.32 raw integers from a seeded
//   std::mt19937_64 (raw integers only, no std distribution). Q16.16 and fix16
//   get the same value rounded to Q16.16 (tandem::to_q16: nearest, ties away),
//   so all three see the same inputs up to their resolution.
// * Half the inputs are uniform over the row's range, half are "log-scaled":
//   a uniform value shifted right by a random amount, so small magnitudes
//   (where relative precision runs out) are covered too.
// * Each format is compared with the exact function of the input it was
//   actually given: the oracle is the long double (64-bit mantissa) sqrtl,
//   sinl, cosl, atan2l of the exact raw value. Errors are in raw units of that
//   format's output: 2^-32 for Q32.32, 2^-16 for Q16.16 and fix16. The oracle's
//   own error is below 10^-8 raw units.
// * atan2(0, 0) has no true value; inputs that are (0, 0) in Q16.16 are skipped
//   for every format (libfixmath returns garbage there: it divides 0 by 0).
//
// Ranges stay inside what every format represents: sqrt [0, 32767), angles
// ±2π and |angle| < 32000, atan2 x, y ∈ ±1000.
#include <libfixmath/fix16.h>

#include <cinttypes>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>

#include "fixed/fixed.h"
#include "fixed/fixed_math.h"

namespace {

using tandem::Q16;
using tandem::Q32;

__extension__ typedef unsigned __int128 U128;

/// Running maximum and mean of |error| for one format in one row.
struct ErrorStats {
  long double max = 0;
  long double sum = 0;
  uint64_t count = 0;
  long double worst_x = 0;  // the input (real value) that gave the maximum
  long double worst_y = 0;  // second input for atan2, else 0

  void add(long double err, long double x, long double y = 0) {
    if (err > max || count == 0) {
      max = err;
      worst_x = x;
      worst_y = y;
    }
    sum += err;
    ++count;
  }
  long double mean() const { return count == 0 ? 0 : sum / static_cast<long double>(count); }
};

struct Row {
  const char* function;
  const char* inputs;
  ErrorStats q32, q16, fix16;
};

/// A uniform integer in [0, limit).
uint64_t below(std::mt19937_64& rng, uint64_t limit) { return static_cast<uint64_t>((static_cast<U128>(rng()) * limit) >> 64); }

/// A Q32.32 raw magnitude in [0, limit): uniform for even i, log-scaled (shifted
/// right by 0 .. max_shift − 1 bits) for odd i.
int64_t magnitude(std::mt19937_64& rng, uint64_t limit, unsigned max_shift, uint64_t i) {
  uint64_t m = below(rng, limit);
  if ((i & 1) != 0) m >>= below(rng, max_shift);
  return static_cast<int64_t>(m);
}

/// A signed Q32.32 raw value with |value| < limit.
int64_t signed_value(std::mt19937_64& rng, uint64_t limit, unsigned max_shift, uint64_t i) {
  const int64_t m = magnitude(rng, limit, max_shift, i);
  return (rng() & 1) != 0 ? -m : m;
}

constexpr long double k_q32_one = 4294967296.0L;
constexpr long double k_q16_one = 65536.0L;

long double real_q32(int64_t raw) { return static_cast<long double>(raw) / k_q32_one; }
long double real_q16(int32_t raw) { return static_cast<long double>(raw) / k_q16_one; }

/// |got − exact·scale| in raw units.
long double err(int64_t got, long double exact, long double scale) { return std::fabs(static_cast<long double>(got) - exact * scale); }

// Limits in Q32.32 raw units.
constexpr uint64_t k_sqrt_limit = uint64_t{32767} << 32;
constexpr uint64_t k_two_pi_limit = 26986075409u;  // round(2π·2^32)
constexpr uint64_t k_wide_angle_limit = uint64_t{32000} << 32;
constexpr uint64_t k_atan_limit = uint64_t{1000} << 32;

void run_sqrt(Row* row, uint64_t n, uint64_t seed) {
  std::mt19937_64 rng(seed);
  for (uint64_t i = 0; i < n; ++i) {
    const Q32 x = Q32::from_raw(magnitude(rng, k_sqrt_limit, 40, i));
    const Q16 x16 = tandem::to_q16(x);
    const long double r32 = static_cast<long double>(x.raw);
    const long double r16 = static_cast<long double>(x16.raw);
    // √(raw/2^f)·2^f = √(raw·2^f): exact arguments, scale 1.
    row->q32.add(err(tandem::sqrt(x).raw, std::sqrt(r32 * k_q32_one), 1), real_q32(x.raw));
    row->q16.add(err(tandem::sqrt(x16).raw, std::sqrt(r16 * k_q16_one), 1), real_q16(x16.raw));
    row->fix16.add(err(fix16_sqrt(x16.raw), std::sqrt(r16 * k_q16_one), 1), real_q16(x16.raw));
  }
}

void run_sincos(Row* sin_row, Row* cos_row, uint64_t n, uint64_t seed, uint64_t limit, unsigned max_shift) {
  std::mt19937_64 rng(seed);
  for (uint64_t i = 0; i < n; ++i) {
    const Q32 a = Q32::from_raw(signed_value(rng, limit, max_shift, i));
    const Q16 a16 = tandem::to_q16(a);
    const long double x32 = real_q32(a.raw);
    const long double x16 = real_q16(a16.raw);
    const long double s32 = std::sin(x32), c32 = std::cos(x32);
    const long double s16 = std::sin(x16), c16 = std::cos(x16);
    const auto sc32 = tandem::sincos(a);
    const auto sc16 = tandem::sincos(a16);
    sin_row->q32.add(err(sc32.sin.raw, s32, k_q32_one), x32);
    cos_row->q32.add(err(sc32.cos.raw, c32, k_q32_one), x32);
    sin_row->q16.add(err(sc16.sin.raw, s16, k_q16_one), x16);
    cos_row->q16.add(err(sc16.cos.raw, c16, k_q16_one), x16);
    sin_row->fix16.add(err(fix16_sin(a16.raw), s16, k_q16_one), x16);
    cos_row->fix16.add(err(fix16_cos(a16.raw), c16, k_q16_one), x16);
  }
}

uint64_t run_atan2(Row* row, uint64_t n, uint64_t seed) {
  std::mt19937_64 rng(seed);
  uint64_t skipped = 0;
  for (uint64_t i = 0; i < n; ++i) {
    const Q32 y = Q32::from_raw(signed_value(rng, k_atan_limit, 24, i));
    const Q32 x = Q32::from_raw(signed_value(rng, k_atan_limit, 24, i));
    const Q16 y16 = tandem::to_q16(y), x16 = tandem::to_q16(x);
    if (y16.raw == 0 && x16.raw == 0) {
      ++skipped;
      continue;
    }
    // The angle does not depend on the common scale: use the raw integers.
    const long double t32 = std::atan2(static_cast<long double>(y.raw), static_cast<long double>(x.raw));
    const long double t16 = std::atan2(static_cast<long double>(y16.raw), static_cast<long double>(x16.raw));
    row->q32.add(err(tandem::atan2(y, x).raw, t32, k_q32_one), real_q32(x.raw), real_q32(y.raw));
    row->q16.add(err(tandem::atan2(y16, x16).raw, t16, k_q16_one), real_q16(x16.raw), real_q16(y16.raw));
    row->fix16.add(err(fix16_atan2(y16.raw, x16.raw), t16, k_q16_one), real_q16(x16.raw), real_q16(y16.raw));
  }
  return skipped;
}

void print_cell(const ErrorStats& s) { std::printf(" %.4Lf | %.3Lf |", s.max, s.mean()); }

void print_worst(const char* function, const char* format, const ErrorStats& s, bool two_inputs) {
  if (two_inputs) {
    std::printf("- %s %s: %.4Lf raw units at x = %.12Lg, y = %.12Lg\n", function, format, s.max, s.worst_x, s.worst_y);
  } else {
    std::printf("- %s %s: %.4Lf raw units at x = %.12Lg\n", function, format, s.max, s.worst_x);
  }
}

bool parse_u64(const char* text, uint64_t* out) {
  char* end = nullptr;
  const unsigned long long v = std::strtoull(text, &end, 0);
  if (end == text || *end != '\0') return false;
  *out = static_cast<uint64_t>(v);
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  uint64_t n = 10'000'000;
  uint64_t seed = 0x7a4d656d'00000002;
  for (int i = 1; i < argc; ++i) {
    const bool has_value = i + 1 < argc;
    if ((std::strcmp(argv[i], "--samples") == 0 || std::strcmp(argv[i], "-n") == 0) && has_value) {
      if (!parse_u64(argv[++i], &n) || n == 0) {
        std::fprintf(stderr, "tandem_fixed_accuracy: --samples needs a positive integer, got '%s'\n", argv[i]);
        return 2;
      }
    } else if (std::strcmp(argv[i], "--seed") == 0 && has_value) {
      if (!parse_u64(argv[++i], &seed)) {
        std::fprintf(stderr, "tandem_fixed_accuracy: --seed needs an integer, got '%s'\n", argv[i]);
        return 2;
      }
    } else {
      std::fprintf(stderr,
                   "usage: tandem_fixed_accuracy [--samples N] [--seed S]\n"
                   "  Max error (raw units) of sqrt, sin, cos, atan2 in Q32.32, Q16.16 and libfixmath fix16\n"
                   "  against a long double oracle over N seeded inputs per row (default 10000000).\n");
      return std::strcmp(argv[i], "--help") == 0 || std::strcmp(argv[i], "-h") == 0 ? 0 : 2;
    }
  }

  Row rows[] = {
      {"sqrt", "[0, 32767)", {}, {}, {}},
      {"sin", "±2π", {}, {}, {}},
      {"cos", "±2π", {}, {}, {}},
      {"sin", "±32000", {}, {}, {}},
      {"cos", "±32000", {}, {}, {}},
      {"atan2", "x, y ∈ ±1000", {}, {}, {}},
  };
  run_sqrt(&rows[0], n, seed);
  run_sincos(&rows[1], &rows[2], n, seed + 1, k_two_pi_limit, 32);
  run_sincos(&rows[3], &rows[4], n, seed + 2, k_wide_angle_limit, 16);
  const uint64_t skipped = run_atan2(&rows[5], n, seed + 3);

  std::printf("Max and mean |error| in raw units of each format's output (Q32.32: 2^-32; Q16.16 and fix16: 2^-16)\n");
  std::printf("against a long double oracle; %" PRIu64 " seeded inputs per row (seed 0x%" PRIx64
              "), half uniform, half log-scaled.\n\n",
              n, seed);
  std::printf("| function | inputs | Q32.32 max | Q32.32 mean | Q16.16 max | Q16.16 mean | fix16 max | fix16 mean |\n");
  std::printf("|---|---|--:|--:|--:|--:|--:|--:|\n");
  for (const Row& r : rows) {
    std::printf("| %s | %s |", r.function, r.inputs);
    print_cell(r.q32);
    print_cell(r.q16);
    print_cell(r.fix16);
    std::printf("\n");
  }
  std::printf("\natan2: %" PRIu64 " inputs that round to (0, 0) in Q16.16 skipped.\n", skipped);
  std::printf("\nWorst inputs:\n\n");
  for (const Row& r : rows) {
    const bool two = std::strcmp(r.function, "atan2") == 0;
    std::string f = std::string(r.function) + " (" + r.inputs + ")";
    print_worst(f.c_str(), "Q32.32", r.q32, two);
    print_worst(f.c_str(), "Q16.16", r.q16, two);
    print_worst(f.c_str(), "fix16", r.fix16, two);
  }
  return 0;
}
