// tandem — the command line.
//
// Subcommands here:
//   tandem fixed-demo           what the fixed-point library does, against exact values
//   tandem fixed FUNC ARGS...   evaluate one fixed-point function and show every bit
//   tandem version              engine and format versions
// and, registered by their families (cli.h): run, render, demo (cmd_scene.cpp),
// record, replay, verify, diff, synctest (cmd_replay.cpp), bench (cmd_bench.cpp),
// state (cmd_state.cpp).
// Usage errors exit with 2 (CLI11's own codes are mapped), --help with 0.
//
// Doubles appear here only to print exact-value oracles; nothing computed in
// floating point flows back into fixed-point values.
#include <CLI/CLI.hpp>

#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <algorithm>
#include <functional>
#include <string>
#include <vector>

#include "fixed/fixed.h"
#include "fixed/fixed_math.h"
#include "fixed/splitmix64.h"
#include "fixed/vec2.h"
#include "physics/tandem.h"
#include "cli.h"

namespace {

using namespace tandem;
using namespace tandem::literals;

constexpr const char* k_version = "0.1.0";

long double exact_of(Q32 v) { return static_cast<long double>(v.raw) / 4294967296.0L; }
long double exact_of(Q16 v) { return static_cast<long double>(v.raw) / 65536.0L; }

// Error of `got` against a real value, in raw units of its format.
template <typename F>
long double raw_error(F got, long double truth) {
  return (exact_of(got) - truth) * static_cast<long double>(F::k_raw_one);
}

// 64-bit FNV-1a over raw values: a fingerprint of many results.
struct Fingerprint {
  uint64_t h = 1469598103934665603ull;
  void add(int64_t raw) {
    auto u = static_cast<uint64_t>(raw);
    for (int i = 0; i < 8; ++i) {
      h ^= (u >> (8 * i)) & 0xFF;
      h *= 1099511628211ull;
    }
  }
};

uint64_t determinism_fingerprint(int count) {
  // splitmix64: fully specified, so every platform draws the same inputs.
  uint64_t state = 0x7A4D3E11u;
  auto next = [&state] { return tandem::splitmix64_next(&state); };
  Fingerprint fp;
  for (int i = 0; i < count; ++i) {
    const Q32 a = Q32::from_raw(static_cast<int64_t>(next() >> 20) - (int64_t{1} << 43));  // ±2048
    const Q32 b = Q32::from_raw(static_cast<int64_t>(next() >> 20) - (int64_t{1} << 43));
    fp.add((a * b).raw);
    fp.add((a / b).raw);
    fp.add(sqrt(abs(a)).raw);
    const SinCos<Q32> sc = sincos(a);
    fp.add(sc.sin.raw);
    fp.add(sc.cos.raw);
    fp.add(atan2(a, b).raw);
    fp.add(length(Vec2{a, b}).raw);
  }
  return fp.h;
}


// Total energy ½mv² + ½Iω² + m·g·h of one body (a report: doubles allowed here).
double body_energy(BodyId b, double g) {
  const Vec2 v = body_linear_velocity(b);
  const double m = body_mass(b).to_double(), w = body_angular_velocity(b).to_double();
  const double vx = v.x.to_double(), vy = v.y.to_double();
  return 0.5 * m * (vx * vx + vy * vy) + 0.5 * body_rotational_inertia(b).to_double() * w * w +
         m * g * body_world_center(b).y.to_double();
}

// Section 5 of the demo: two small scenes on the physics module.
void run_physics_preview() {
  const Q32 dt = Q32::from_ratio(1, 60);
  // Building this fixed scene cannot fail; if it ever does, say so.
  auto check = [](const Status& s) { if (!s.ok()) std::printf("  setup failed: %s\n", s.message.c_str()); };
  WorldId world = create_world(default_world_def()).value;
  BodyId ground = create_body(world, default_body_def()).value;
  Polygon ground_box;
  check(make_offset_box(40_q32, 1_q32, Vec2{0_q32, -1_q32}, 0_q32, 0_q32, &ground_box));
  check(create_polygon_shape(ground, default_shape_def(), ground_box).status);

  // An elastic ball dropped from 10 m (the report's accuracy test).
  BodyDef ball_def = default_body_def();
  ball_def.type = BodyType::dynamic_body;
  ball_def.position = Vec2{Q32(-10), 10_q32};
  BodyId ball = create_body(world, ball_def).value;
  ShapeDef bouncy = default_shape_def();
  bouncy.restitution = 1_q32;
  bouncy.friction = 0_q32;
  check(create_circle_shape(ball, bouncy, Circle{Vec2{}, 0.5_q32}).status);

  // A stack of ten 1 m boxes.
  std::vector<BodyId> stack;
  Polygon box;
  check(make_box(0.5_q32, 0.5_q32, &box));
  for (int i = 0; i < 10; ++i) {
    BodyDef d = default_body_def();
    d.type = BodyType::dynamic_body;
    d.position = Vec2{Q32(5), Q32::from_ratio(2 * i + 1, 2)};
    stack.push_back(create_body(world, d).value);
    check(create_polygon_shape(stack.back(), default_shape_def(), box).status);
  }
  const double e0 = body_energy(ball, 10.0);
  double e_min = e0, e_max = e0;
  const int ticks = 60 * 60;
  Fingerprint fp;
  for (int tick = 1; tick <= ticks; ++tick) {
    const StepResult r = world_step(world, dt);
    if (!r.ok()) {
      std::printf("  step %d failed: %s\n", tick, r.status.message.c_str());
      break;
    }
    const double e = body_energy(ball, 10.0);
    e_min = std::min(e_min, e);
    e_max = std::max(e_max, e);
    fp.add(body_position(ball).y.raw);
    fp.add(body_position(stack.back()).x.raw);
  }
  const Vec2 top = body_position(stack.back());
  std::printf("  %d ticks of 1/60 s (one simulated minute), 4 sub-steps, soft contacts:\n", ticks);
  std::printf("  - ball, restitution 1, dropped from 10 m: energy now %.4f of the start (range %.4f .. %.4f)\n",
              body_energy(ball, 10.0) / e0, e_min / e0, e_max / e0);
  std::printf("  - stack of 10 boxes: top box centre at (%s, %s) m (started at (5, 9.5))\n",
              to_string(top.x).substr(0, 12).c_str(), to_string(top.y).substr(0, 12).c_str());
  std::printf("  - fingerprint of both trajectories: 0x%016" PRIx64 "\n", fp.h);
  check(destroy_world(world));
}

void print_rule(char c = '-') {
  std::string line(96, c);
  std::printf("%s\n", line.c_str());
}

int run_demo() {
  std::printf("Tandem %s - deterministic fixed-point 2D physics. Demo of the fixed-point core (fixed/).\n", k_version);
  std::printf("Physics runs on Q32.32 (int64, 1 raw unit = 2^-32 ~ 2.3e-10); Q16.16 (int32) is the compact format.\n\n");

  std::printf("1. Decimal text converts exactly, never through a double (round to nearest, ties away from zero)\n");
  print_rule();
  std::printf("  %-20s %-14s %-40s %s\n", "text", "Q32.32 raw", "stored value, exact decimal", "error");
  for (const char* text : {"0.1", "1.5", "-2.75", "0.016666666666666666", "3.14159265358979"}) {
    const auto p = parse_q32(text);
    const long double truth = std::strtold(text, nullptr);
    std::printf("  %-20s %-14" PRId64 " %-40s %+.3Lf raw\n", text, p.value.raw, to_string(p.value).c_str(),
                raw_error(p.value, truth));
  }
  std::printf("\n2. Functions against their exact values (long double oracle), error in raw units\n");
  print_rule();
  std::printf("  %-16s %-36s %-24s %-10s %s\n", "function", "Q32.32 result (exact decimal)", "true value", "Q32 err",
              "Q16 err");
  struct Row {
    const char* name;
    std::function<Q32()> q32;
    std::function<Q16()> q16;
    long double truth;
  };
  const Row rows[] = {
      {"sqrt(2)", [] { return sqrt(2_q32); }, [] { return sqrt(2_q16); }, std::sqrt(2.0L)},
      {"sqrt(10000.5)", [] { return sqrt(10000.5_q32); }, [] { return sqrt(10000.5_q16); }, std::sqrt(10000.5L)},
      {"1/sqrt(3)", [] { return rsqrt(3_q32); }, [] { return rsqrt(3_q16); }, 1.0L / std::sqrt(3.0L)},
      {"sin(1)", [] { return sin(1_q32); }, [] { return sin(1_q16); }, std::sin(1.0L)},
      {"cos(1)", [] { return cos(1_q32); }, [] { return cos(1_q16); }, std::cos(1.0L)},
      {"sin(1000)", [] { return sin(1000_q32); }, [] { return sin(1000_q16); }, std::sin(1000.0L)},
      {"atan2(1, 1)*4", [] { return atan2(1_q32, 1_q32) * 4; }, [] { return atan2(1_q16, 1_q16) * 4; },
       4.0L * std::atan2(1.0L, 1.0L)},
      {"atan2(-3, -4)", [] { return atan2(Q32(-3), Q32(-4)); }, [] { return atan2(Q16(-3), Q16(-4)); },
       std::atan2(-3.0L, -4.0L)},
      {"|(3e4, 4e4)|", [] { return length(Vec2{Q32(30000), Q32(40000)}); }, [] { return Q16::max(); }, 50000.0L},
  };
  for (const Row& r : rows) {
    const Q32 v = r.q32();
    const Q16 w = r.q16();
    std::string v_text = to_string(v);
    if (v_text.size() > 34) v_text = v_text.substr(0, 33) + "~";
    char q16_err[32];
    if (r.truth < 32768.0L)
      std::snprintf(q16_err, sizeof q16_err, "%+.3Lf", raw_error(w, r.truth));
    else
      std::snprintf(q16_err, sizeof q16_err, "(range)");
    std::printf("  %-16s %-36s %-24.18Lf %+-10.3Lf %s\n", r.name, v_text.c_str(), r.truth, raw_error(v, r.truth),
                q16_err);
  }
  std::printf("  (the last row's squares reach 2.5e9, beyond Q32.32: lengths use exact 128-bit intermediates)\n");

  std::printf("\n3. Overflow saturates and division by zero has a defined result (never undefined behaviour)\n");
  print_rule();
  std::printf("  50000 * 50000  = %s  (saturated to the largest Q32.32)\n", to_string(Q32::max()).c_str());
  std::printf("  -1 / 0         = %s  (-max; 0/0 = 0)\n", to_string(Q32::min()).c_str());
  std::printf("  Debug builds also stop at the first such fault and name the operation.\n");

  std::printf("\n4. Same bits everywhere\n");
  print_rule();
  const int n = 200000;
  std::printf("  Fingerprint of %d evaluations each of *, /, sqrt, sincos, atan2, length: 0x%016" PRIx64 "\n", n,
              determinism_fingerprint(n));
  std::printf("  The test suite checks values like this one on x86-64, i686 (no __int128) and s390x (big-endian).\n");

  std::printf("\n5. Physics preview (physics/): integer-only soft-step solver\n");
  print_rule();
  run_physics_preview();
  std::printf("\nNext: tandem demo (a scene run, hashed and drawn), tandem run / render SCENE; see README.md.\n");
  return 0;
}

// `tandem fixed FUNC ARGS...`
int run_fixed(const std::string& func, const std::vector<std::string>& args, bool q16) {
  auto parse_arg = [&](size_t i, Q32* out) -> bool {
    const auto p = parse_q32(args[i]);
    if (!p.ok()) {
      std::fprintf(stderr, "tandem fixed: argument %zu: %s\n", i + 1,
                   describe_parse_error(args[i], p.error, p.error_offset).c_str());
      return false;
    }
    *out = p.value;
    return true;
  };
  struct Func {
    const char* name;
    size_t arity;
  };
  static const Func funcs[] = {{"parse", 1}, {"add", 2}, {"sub", 2}, {"mul", 2}, {"div", 2},  {"sqrt", 1},
                               {"rsqrt", 1}, {"sin", 1}, {"cos", 1}, {"atan2", 2}, {"floor", 1}, {"round", 1}};
  size_t arity = 0;
  for (const Func& f : funcs)
    if (func == f.name) arity = f.arity;
  if (arity == 0) {
    std::fprintf(stderr, "tandem fixed: unknown function '%s'; expected one of:", func.c_str());
    for (const Func& f : funcs) std::fprintf(stderr, " %s", f.name);
    std::fprintf(stderr, "\n");
    return 2;
  }
  if (args.size() != arity) {
    std::fprintf(stderr, "tandem fixed: '%s' takes %zu argument%s, got %zu\n", func.c_str(), arity,
                 arity == 1 ? "" : "s", args.size());
    return 2;
  }
  Q32 a, b;
  if (!parse_arg(0, &a)) return 2;
  if (arity == 2 && !parse_arg(1, &b)) return 2;
  const long double x = exact_of(a), y = exact_of(b);
  Q32 r;
  long double truth = 0;
  // Faults (saturation) are reported by the library itself in debug builds.
  if (func == "parse") r = a, truth = std::strtold(args[0].c_str(), nullptr);
  else if (func == "add") r = a + b, truth = x + y;
  else if (func == "sub") r = a - b, truth = x - y;
  else if (func == "mul") r = a * b, truth = x * y;
  else if (func == "div") r = a / b, truth = x / y;
  else if (func == "sqrt") r = sqrt(a), truth = std::sqrt(x);
  else if (func == "rsqrt") r = rsqrt(a), truth = 1.0L / std::sqrt(x);
  else if (func == "sin") r = sin(a), truth = std::sin(x);
  else if (func == "cos") r = cos(a), truth = std::cos(x);
  else if (func == "atan2") r = atan2(a, b), truth = std::atan2(x, y);
  else if (func == "floor") r = floor(a), truth = std::floor(x);
  else r = round(a), truth = std::round(x);
  if (q16) {
    Q16 a16 = to_q16(a), b16 = to_q16(b), w;
    if (func == "parse") w = parse_q16(args[0]).value;
    else if (func == "add") w = a16 + b16;
    else if (func == "sub") w = a16 - b16;
    else if (func == "mul") w = a16 * b16;
    else if (func == "div") w = a16 / b16;
    else if (func == "sqrt") w = sqrt(a16);
    else if (func == "rsqrt") w = rsqrt(a16);
    else if (func == "sin") w = sin(a16);
    else if (func == "cos") w = cos(a16);
    else if (func == "atan2") w = atan2(a16, b16);
    else if (func == "floor") w = floor(a16);
    else w = round(a16);
    std::printf("Q16.16 %s = %s\n  raw %" PRId32 " (0x%08" PRIx32 ")\n  error vs exact: %+.4Lf raw units\n",
                func.c_str(), to_string(w).c_str(), w.raw, static_cast<uint32_t>(w.raw), raw_error(w, truth));
    return 0;
  }
  std::printf("Q32.32 %s = %s\n  raw %" PRId64 " (0x%016" PRIx64 ")\n  error vs exact: %+.4Lf raw units\n",
              func.c_str(), to_string(r).c_str(), r.raw, static_cast<uint64_t>(r.raw), raw_error(r, truth));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"tandem: deterministic fixed-point 2D physics"};
  app.require_subcommand(1);
  app.fallthrough();  // --json / --quiet may follow the subcommand
  app.footer("Examples:\n  tandem demo\n  tandem run scenes/pyramid.json\n  tandem render scenes/rain.json --every 60 -o out\n"
             "  tandem fixed sqrt 2\n  tandem fixed atan2 -- -3 -4\n\nExit codes: 0 ok, 1 a check failed, 2 bad usage or input.");

  auto* demo = app.add_subcommand("fixed-demo", "Show what the fixed-point core computes, against exact values");
  demo->footer("Example:\n  tandem fixed-demo");

  auto* fixed = app.add_subcommand("fixed", "Evaluate one fixed-point function exactly and show its bits");
  std::string func;
  std::vector<std::string> args;
  bool q16 = false;
  fixed->add_option("function", func, "parse, add, sub, mul, div, sqrt, rsqrt, sin, cos, atan2, floor, round")->required();
  fixed->add_option("args", args, "decimal numbers (exact; put -- before negative numbers)");
  fixed->add_flag("--q16", q16, "compute in Q16.16 instead of Q32.32");
  fixed->footer("Examples:\n  tandem fixed sqrt 2\n  tandem fixed sin 1e3\n  tandem fixed atan2 -- -3 -4\n  tandem fixed div 1 3 --q16");

  auto* version = app.add_subcommand("version", "Print the engine and number-format versions");

  tandem::cli::GlobalOptions options;
  app.add_flag("--quiet,-q", options.quiet, "no progress output; only errors and the final result");
  app.add_flag("--json", options.json, "machine-readable output on stdout");
  app.add_option("--max-bodies", options.scene_limits.max_bodies,
                 "most bodies a scene file may have, generated ones included (default " +
                     std::to_string(tandem::scene::k_default_scene_max_bodies) + ")")
      ->check(CLI::Range(int64_t{0}, int64_t{tandem::k_max_bodies}));
  app.add_option("--max-shapes", options.scene_limits.max_shapes,
                 "most shapes a scene file may have (default " +
                     std::to_string(tandem::scene::k_default_scene_max_shapes) + ")")
      ->check(CLI::Range(int64_t{0}, int64_t{tandem::k_max_shapes}));
  std::vector<tandem::cli::Command> commands;
  tandem::cli::register_scene_commands(app, options, &commands);
  tandem::cli::register_replay_commands(app, options, &commands);
  tandem::cli::register_bench_commands(app, options, &commands);
  tandem::cli::register_state_commands(app, options, &commands);
  tandem::cli::register_session_commands(app, options, &commands);

  if (argc > 1 && argv[1][0] != '-') {  // CLI11 alone would only say "A subcommand is required"
    const std::string name = argv[1];
    const auto known = app.get_subcommands([&](CLI::App* sub) { return sub->check_name(name); });  // names and aliases
    if (known.empty()) {
      std::fprintf(stderr, "tandem: unknown command '%s'; run tandem --help for the list\n", name.c_str());
      return 2;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);  // prints the message to stderr
    return 2;
  }
  for (const tandem::cli::Command& command : commands)
    if (command.app->parsed()) return command.run();
  if (demo->parsed()) return run_demo();
  if (fixed->parsed()) return run_fixed(func, args, q16);
  if (version->parsed()) {
    std::printf("tandem %s (Q32.32 physics, Q16.16 compact format)\n", k_version);
    return 0;
  }
  return 0;
}
