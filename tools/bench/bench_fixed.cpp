// bench_fixed.cpp — ns per operation of Tandem's Q32.32 and Q16.16 next to
// float, double and libfixmath's fix16 (Q16.16), in one Google Benchmark run.
//
// Benchmarks are named "<op>/<type>": op ∈ {mul, mul_latency, div, sqrt,
// sincos, atan2}, type ∈ {q32, q16, float, double, fix16}. The counter "s/op"
// is seconds per operation (the console shows e.g. "1.23n" for 1.23 ns).
//
// Method:
// * Throughput: each benchmark iteration runs one operation over every element
//   of a pre-generated input array and hands each result to
//   benchmark::DoNotOptimize, so nothing is folded away, but independent
//   operations may overlap in the pipeline. Results are not stored, so the
//   compiler cannot vectorise float/double either: this is scalar throughput.
// * Latency (mul only): a chain x = x × c of dependent products, c = 1 hidden
//   from the optimiser, so the value never drifts, overflows or goes
//   subnormal.
// * Inputs: one seeded std::mt19937_64 draws each real value once (53 random
//   bits → [0, 1) by hand, not a std distribution), and every type gets that
//   value rounded to its own format, so all five see the same numbers.
//   Ranges: mul operands ±100 (products stay within ±10000, inside Q16.16, so
//   no type times its saturation path); div dividend ±1000, divisor magnitude
//   in [1, 1000); sqrt [0, 10000); angles ±2π; atan2 x and y in ±1000.
// * Array sizes: 1024 for mul and div (L1-resident); 65536 for sqrt, sincos
//   and atan2. The large size matters for fix16: libfixmath (as Debian builds
//   it) memoises fix16_sin and fix16_atan2 in 4096-entry direct-mapped
//   caches, and a small array cycled through would be answered from them.
//   With 16 inputs per cache slot on average, nearly every call misses, as it
//   would in a physics step.
// * sincos: Tandem computes both in one call; float/double call std::sin and
//   std::cos (GCC merges them into one sincos call where it can); libfixmath
//   has no sincos, so fix16 times fix16_sin + fix16_cos.
// * fix16 calls go into Debian's liblibfixmath.a, which is compiled without
//   optimisation and cannot be inlined; Tandem's sqrt/sincos/atan2 are out of
//   line too (tandem_fixed), while × and ÷ are inline templates.
//
// The context line "checksum" is an FNV-1a hash of every Q32.32/Q16.16 result
// over the inputs: a speed-up that changes results changes it.
#include <benchmark/benchmark.h>
#include <libfixmath/fix16.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "fixed/fixed.h"
#include "fixed/fixed_math.h"

namespace {

using tandem::Q16;
using tandem::Q32;

constexpr std::size_t k_small = 1024;   // mul, div
constexpr std::size_t k_large = 65536;  // sqrt, sincos, atan2
constexpr uint64_t k_seed = 0x7a4d656d'00000001;
constexpr double k_two_pi = 6.283185307179586476925;

// --- inputs ------------------------------------------------------------------

/// A uniform double in [lo, hi) from 53 random bits (portable, unlike
/// std::uniform_real_distribution).
double uniform(std::mt19937_64& rng, double lo, double hi) {
  const double u = static_cast<double>(rng() >> 11) * 0x1.0p-53;
  return lo + u * (hi - lo);
}

/// The real-valued inputs of every benchmark, shared by all types.
struct Inputs {
  std::vector<double> mul_a, mul_b, div_a, div_b, sqrt_x, angle, atan_y, atan_x;
};

const Inputs& inputs() {
  static const Inputs in = [] {
    Inputs r;
    std::mt19937_64 rng(k_seed);
    for (std::size_t i = 0; i < k_small; ++i) {
      r.mul_a.push_back(uniform(rng, -100.0, 100.0));
      r.mul_b.push_back(uniform(rng, -100.0, 100.0));
      r.div_a.push_back(uniform(rng, -1000.0, 1000.0));
      const double d = uniform(rng, 1.0, 1000.0);
      r.div_b.push_back((rng() & 1) != 0 ? -d : d);
    }
    for (std::size_t i = 0; i < k_large; ++i) {
      r.sqrt_x.push_back(uniform(rng, 0.0, 10000.0));
      r.angle.push_back(uniform(rng, -k_two_pi, k_two_pi));
      r.atan_y.push_back(uniform(rng, -1000.0, 1000.0));
      r.atan_x.push_back(uniform(rng, -1000.0, 1000.0));
    }
    return r;
  }();
  return in;
}

// --- the five types ------------------------------------------------------------
// Each: T, a name, from(double) (round to nearest), and the operations. sincos
// returns a pair so the benchmark can hand both halves to DoNotOptimize.

template <typename T>
struct Pair {
  T sin;
  T cos;
};

struct OpsQ32 {
  using T = Q32;
  static constexpr const char* k_name = "q32";
  static T from(double v) { return Q32::from_raw(std::llround(std::ldexp(v, 32))); }
  static T mul(T a, T b) { return a * b; }
  static T div(T a, T b) { return a / b; }
  static T sqrt(T x) { return tandem::sqrt(x); }
  static Pair<T> sincos(T a) {
    const auto sc = tandem::sincos(a);
    return {sc.sin, sc.cos};
  }
  static T atan2(T y, T x) { return tandem::atan2(y, x); }
};

struct OpsQ16 {
  using T = Q16;
  static constexpr const char* k_name = "q16";
  static T from(double v) { return Q16::from_raw(static_cast<int32_t>(std::lround(std::ldexp(v, 16)))); }
  static T mul(T a, T b) { return a * b; }
  static T div(T a, T b) { return a / b; }
  static T sqrt(T x) { return tandem::sqrt(x); }
  static Pair<T> sincos(T a) {
    const auto sc = tandem::sincos(a);
    return {sc.sin, sc.cos};
  }
  static T atan2(T y, T x) { return tandem::atan2(y, x); }
};

struct OpsFloat {
  using T = float;
  static constexpr const char* k_name = "float";
  static T from(double v) { return static_cast<float>(v); }
  static T mul(T a, T b) { return a * b; }
  static T div(T a, T b) { return a / b; }
  static T sqrt(T x) { return std::sqrt(x); }
  static Pair<T> sincos(T a) { return {std::sin(a), std::cos(a)}; }
  static T atan2(T y, T x) { return std::atan2(y, x); }
};

struct OpsDouble {
  using T = double;
  static constexpr const char* k_name = "double";
  static T from(double v) { return v; }
  static T mul(T a, T b) { return a * b; }
  static T div(T a, T b) { return a / b; }
  static T sqrt(T x) { return std::sqrt(x); }
  static Pair<T> sincos(T a) { return {std::sin(a), std::cos(a)}; }
  static T atan2(T y, T x) { return std::atan2(y, x); }
};

struct OpsFix16 {
  using T = fix16_t;
  static constexpr const char* k_name = "fix16";
  static T from(double v) { return static_cast<fix16_t>(std::lround(std::ldexp(v, 16))); }
  static T mul(T a, T b) { return fix16_mul(a, b); }
  static T div(T a, T b) { return fix16_div(a, b); }
  static T sqrt(T x) { return fix16_sqrt(x); }
  static Pair<T> sincos(T a) { return {fix16_sin(a), fix16_cos(a)}; }
  static T atan2(T y, T x) { return fix16_atan2(y, x); }
};

/// The inputs converted to one type, built on first use.
template <typename Ops>
struct Data {
  using T = typename Ops::T;
  std::vector<T> mul_a, mul_b, div_a, div_b, sqrt_x, angle, atan_y, atan_x;

  static const Data& get() {
    static const Data d = [] {
      const Inputs& in = inputs();
      auto conv = [](const std::vector<double>& v) {
        std::vector<T> out;
        out.reserve(v.size());
        for (double x : v) out.push_back(Ops::from(x));
        return out;
      };
      Data r;
      r.mul_a = conv(in.mul_a);
      r.mul_b = conv(in.mul_b);
      r.div_a = conv(in.div_a);
      r.div_b = conv(in.div_b);
      r.sqrt_x = conv(in.sqrt_x);
      r.angle = conv(in.angle);
      r.atan_y = conv(in.atan_y);
      r.atan_x = conv(in.atan_x);
      return r;
    }();
    return d;
  }
};

// --- benchmarks ----------------------------------------------------------------

/// Reports seconds per operation as the counter "s/op".
void set_per_op(benchmark::State& state, std::size_t ops_per_iteration) {
  state.counters["s/op"] = benchmark::Counter(static_cast<double>(ops_per_iteration),
                                              benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

template <typename Ops>
void bm_mul(benchmark::State& state) {
  const auto& d = Data<Ops>::get();
  const auto* a = d.mul_a.data();
  const auto* b = d.mul_b.data();
  for (auto _ : state) {
    for (std::size_t i = 0; i < k_small; ++i) benchmark::DoNotOptimize(Ops::mul(a[i], b[i]));
  }
  set_per_op(state, k_small);
}

template <typename Ops>
void bm_mul_latency(benchmark::State& state) {
  constexpr std::size_t k_chain = 256;
  typename Ops::T x = Ops::from(1.2345);
  typename Ops::T c = Ops::from(1.0);
  // Hide c == 1 from the optimiser: c's address escapes into an asm with a
  // memory clobber, so c must be stored first and reloaded after. (Not
  // DoNotOptimize(c): g++ 12 dropped the store of 1.0 through the
  // read-write "+m,r" operand, leaving c uninitialised.)
  benchmark::DoNotOptimize(&c);
  for (auto _ : state) {
    for (std::size_t i = 0; i < k_chain; ++i) x = Ops::mul(x, c);
    benchmark::DoNotOptimize(std::as_const(x));
  }
  set_per_op(state, k_chain);
}

template <typename Ops>
void bm_div(benchmark::State& state) {
  const auto& d = Data<Ops>::get();
  const auto* a = d.div_a.data();
  const auto* b = d.div_b.data();
  for (auto _ : state) {
    for (std::size_t i = 0; i < k_small; ++i) benchmark::DoNotOptimize(Ops::div(a[i], b[i]));
  }
  set_per_op(state, k_small);
}

template <typename Ops>
void bm_sqrt(benchmark::State& state) {
  const auto* x = Data<Ops>::get().sqrt_x.data();
  for (auto _ : state) {
    for (std::size_t i = 0; i < k_large; ++i) benchmark::DoNotOptimize(Ops::sqrt(x[i]));
  }
  set_per_op(state, k_large);
}

template <typename Ops>
void bm_sincos(benchmark::State& state) {
  const auto* x = Data<Ops>::get().angle.data();
  for (auto _ : state) {
    for (std::size_t i = 0; i < k_large; ++i) {
      const auto sc = Ops::sincos(x[i]);
      benchmark::DoNotOptimize(sc.sin);
      benchmark::DoNotOptimize(sc.cos);
    }
  }
  set_per_op(state, k_large);
}

template <typename Ops>
void bm_atan2(benchmark::State& state) {
  const auto& d = Data<Ops>::get();
  const auto* y = d.atan_y.data();
  const auto* x = d.atan_x.data();
  for (auto _ : state) {
    for (std::size_t i = 0; i < k_large; ++i) benchmark::DoNotOptimize(Ops::atan2(y[i], x[i]));
  }
  set_per_op(state, k_large);
}

/// Registers in op-major order so the console groups each op's five types.
void register_all() {
  const char* ops[] = {"mul", "mul_latency", "div", "sqrt", "sincos", "atan2"};
  for (const char* op : ops) {
    const std::string o = op;
    auto reg = [&]<typename Ops>(Ops) {
      const std::string name = o + "/" + Ops::k_name;
      if (o == "mul") benchmark::RegisterBenchmark(name.c_str(), bm_mul<Ops>);
      if (o == "mul_latency") benchmark::RegisterBenchmark(name.c_str(), bm_mul_latency<Ops>);
      if (o == "div") benchmark::RegisterBenchmark(name.c_str(), bm_div<Ops>);
      if (o == "sqrt") benchmark::RegisterBenchmark(name.c_str(), bm_sqrt<Ops>);
      if (o == "sincos") benchmark::RegisterBenchmark(name.c_str(), bm_sincos<Ops>);
      if (o == "atan2") benchmark::RegisterBenchmark(name.c_str(), bm_atan2<Ops>);
    };
    reg(OpsQ32{});
    reg(OpsQ16{});
    reg(OpsFloat{});
    reg(OpsDouble{});
    reg(OpsFix16{});
  }
}

// --- checksum of the fixed-point results ------------------------------------------

struct Fnv {
  uint64_t h = 0xcbf29ce484222325u;
  void add(int64_t v) {
    const auto u = static_cast<uint64_t>(v);
    for (int i = 0; i < 8; ++i) {
      h ^= (u >> (8 * i)) & 0xffu;
      h *= 0x100000001b3u;
    }
  }
};

template <typename Ops>
void checksum(Fnv* f) {
  const auto& d = Data<Ops>::get();
  for (std::size_t i = 0; i < k_small; ++i) {
    f->add(Ops::mul(d.mul_a[i], d.mul_b[i]).raw);
    f->add(Ops::div(d.div_a[i], d.div_b[i]).raw);
  }
  for (std::size_t i = 0; i < k_large; ++i) {
    f->add(Ops::sqrt(d.sqrt_x[i]).raw);
    const auto sc = Ops::sincos(d.angle[i]);
    f->add(sc.sin.raw);
    f->add(sc.cos.raw);
    f->add(Ops::atan2(d.atan_y[i], d.atan_x[i]).raw);
  }
}

}  // namespace

int main(int argc, char** argv) {
  Fnv f;
  checksum<OpsQ32>(&f);
  checksum<OpsQ16>(&f);
  char hex[32];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(f.h));
  benchmark::AddCustomContext("checksum", hex);
  benchmark::AddCustomContext("libfixmath", "Debian liblibfixmath.a (built -O0, caches on, overflow checks on)");
  register_all();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
