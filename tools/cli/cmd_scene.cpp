// cmd_scene.cpp — `tandem run`, `tandem render` and `tandem demo`: scene
// files (tools/scene) stepped, hashed (replay/state.h) and drawn
// (tools/render). See cli.h for the exit codes.
//
// Tick convention (docs/scene-format.md): "tick T" is the state after T
// steps; the scene's inputs for tick T are applied just before step T + 1.
// Timing uses the steady clock around world_step only (inputs excluded).
//
// run: hashes with world_state_hash (replay/state.h) every K ticks and at the
// end, plus a "bodies hash" (world_body_hashes folded) that leaves out the
// world settings, so runs that differ only in the broad phase compare equal.
// render: a scene file, or a replay file (is_replay_image), whose ticks are
// played from its tick-0 keyframe. demo: rain.json for 5 s, recorded with
// ReplayRecorder, read back and checked with verify_replay, then drawn; exit
// code 1 when the verification fails.

#include <algorithm>
#include <chrono>
#include <cinttypes>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "cli.h"
#include "cli_util.h"
#include "profile_stats.h"
#include "render/render.h"
#include "replay/replay_file.h"
#include "replay/state.h"
#include "replay/verify.h"
#include "scene/scene.h"

#ifndef TANDEM_SCENES_DIR
#define TANDEM_SCENES_DIR "scenes"
#endif

namespace tandem::cli {
namespace {

using Clock = std::chrono::steady_clock;

// A hash of the bodies and shapes only (world_body_hashes folded in index
// order), without the world's settings: equal for runs that differ only in
// settings that must not change results, such as the broad phase.
uint64_t bodies_hash(WorldId world) {
  std::vector<uint64_t> hashes;
  if (!world_body_hashes(world, &hashes).ok()) return 0;
  uint64_t h = 0x9E3779B97F4A7C15ull;
  for (uint64_t v : hashes) {
    h ^= v + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
    h *= 0xBF58476D1CE4E5B9ull;
  }
  return h;
}

const char* broad_phase_name(BroadPhaseKind k) {
  switch (k) {
    case BroadPhaseKind::naive: return "naive";
    case BroadPhaseKind::sweep_and_prune: return "sap";
    case BroadPhaseKind::grid: return "grid";
    case BroadPhaseKind::tree: return "tree";
  }
  return "?";
}

std::string json_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\', out += c;
    else if (static_cast<unsigned char>(c) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", static_cast<unsigned>(c));
      out += buf;
    } else out += c;
  }
  return out;
}

// A scene loaded, its broad phase chosen, and built; prints errors itself.
struct SceneRun {
  scene::Scene scene;
  scene::BuiltScene built;
  bool from_replay = false;  // render only: the world comes from a replay file
  Replay replay;             // from_replay: its ticks drive the world
  int64_t tick = 0;
  uint32_t step_flags = 0;  // OR of every step's flags
  std::vector<double> step_seconds;
  bool profiling = false;               // run --profile: record world_profile() after every timed step
  bench::ProfileSeries profile;
  ~SceneRun() {
    if (!is_null(built.world)) (void)destroy_world(built.world);
  }
};

int open_session(const std::string& command, const std::string& path, const std::string& broad_phase,
                 const scene::SceneLimits& limits, SceneRun* s) {
  Result<scene::Scene> loaded = scene::load_scene_file(path, limits);
  if (!loaded.ok()) {
    std::fprintf(stderr, "tandem %s: %s\n", command.c_str(), loaded.status.message.c_str());
    return 2;
  }
  s->scene = std::move(loaded.value);
  if (broad_phase == "naive") s->scene.world.broad_phase = BroadPhaseKind::naive;
  else if (broad_phase == "sap") s->scene.world.broad_phase = BroadPhaseKind::sweep_and_prune;
  else if (broad_phase == "grid") s->scene.world.broad_phase = BroadPhaseKind::grid;
  else if (broad_phase == "tree") s->scene.world.broad_phase = BroadPhaseKind::tree;
  Result<scene::BuiltScene> built = scene::build_world(s->scene);
  if (!built.ok()) {
    std::fprintf(stderr, "tandem %s: %s\n", command.c_str(), built.status.message.c_str());
    return 2;
  }
  s->built = std::move(built.value);
  return 0;
}

// Applies the inputs of the current tick and steps once; prints errors itself.
int step_once(const std::string& command, SceneRun* s, bool timed) {
  if (s->from_replay) {
    if (s->tick >= s->replay.tick_count()) {
      std::fprintf(stderr, "tandem %s: %s: the replay ends at tick %" PRId64 "\n", command.c_str(), s->scene.name.c_str(),
                   s->replay.tick_count());
      return 2;
    }
    const Status st = run_tick(s->built.world, s->replay.ticks[static_cast<size_t>(s->tick)], s->replay.header.time_step);
    if (!st.ok()) {
      std::fprintf(stderr, "tandem %s: %s: tick %" PRId64 ": %s\n", command.c_str(), s->scene.name.c_str(), s->tick + 1,
                   st.message.c_str());
      return 2;
    }
    ++s->tick;
    return 0;
  }
  const Status in = scene::apply_scene_inputs(s->built, s->scene, s->tick);
  if (!in.ok()) {
    std::fprintf(stderr, "tandem %s: %s\n", command.c_str(), in.message.c_str());
    return 2;
  }
  const auto t0 = Clock::now();
  const StepResult r = world_step(s->built.world, s->scene.time_step);
  if (timed) s->step_seconds.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
  if (timed && s->profiling && r.ok()) s->profile.add(world_profile(s->built.world));
  if (!r.ok()) {
    std::fprintf(stderr, "tandem %s: %s: step %" PRId64 " refused: %s\n", command.c_str(), s->scene.name.c_str(),
                 s->tick + 1, r.status.message.c_str());
    return 2;
  }
  s->step_flags |= r.flags;
  ++s->tick;
  return 0;
}

int32_t shape_total(WorldId world) { return world_counters(world).shape_count; }

// --- run ---------------------------------------------------------------------
struct RunArgs {
  std::string scene;
  int64_t ticks = -1;
  std::string broad_phase;
  int64_t hash_every = 60;
  bool json = false, quiet = false, profile = false;
};

int run_run(const RunArgs& a, const GlobalOptions& g) {
  const bool json = a.json || g.json, quiet = a.quiet || g.quiet;
  SceneRun s;
  if (int rc = open_session("run", a.scene, a.broad_phase, g.scene_limits, &s)) return rc;
  s.profiling = a.profile;
  const int64_t ticks = a.ticks >= 0 ? a.ticks : s.scene.ticks;
  struct Mark {
    int64_t tick;
    uint64_t hash;
  };
  std::vector<Mark> marks;
  marks.push_back({0, world_state_hash(s.built.world)});
  s.step_seconds.reserve(static_cast<size_t>(std::min<int64_t>(ticks, 1 << 24)));
  ProgressBar progress("", quiet || json);
  const auto wall0 = Clock::now();
  while (s.tick < ticks) {
    if (int rc = step_once("run", &s, true)) return rc;
    if (a.hash_every > 0 && s.tick % a.hash_every == 0 && s.tick != ticks)
      marks.push_back({s.tick, world_state_hash(s.built.world)});
    progress.update(static_cast<uint64_t>(s.tick), static_cast<uint64_t>(ticks));
  }
  progress.finish();
  const double wall = std::chrono::duration<double>(Clock::now() - wall0).count();
  const uint64_t final_hash = world_state_hash(s.built.world);
  std::vector<double> sorted = s.step_seconds;
  std::sort(sorted.begin(), sorted.end());
  double total = 0;
  for (double t : sorted) total += t;
  const double median_ms = sorted.empty() ? 0 : sorted[sorted.size() / 2] * 1e3;
  const double mean_ms = sorted.empty() ? 0 : total / static_cast<double>(sorted.size()) * 1e3;
  const double max_ms = sorted.empty() ? 0 : sorted.back() * 1e3;
  const WorldCounters counters = world_counters(s.built.world);
  const bool left_bounds = (s.step_flags & k_step_flag_body_left_bounds) != 0;
  if (json) {
    std::printf("{\"scene\": \"%s\", \"ticks\": %" PRId64 ", \"step_hz\": %d, \"broad_phase\": \"%s\", \"bodies\": %d, "
                "\"shapes\": %d,\n \"hashes\": [",
                json_escape(s.scene.name).c_str(), ticks, s.scene.step_hz, broad_phase_name(s.scene.world.broad_phase),
                counters.body_count, counters.shape_count);
    for (size_t i = 0; i < marks.size(); ++i)
      std::printf("%s{\"tick\": %" PRId64 ", \"hash\": \"%s\"}", i ? ", " : "", marks[i].tick, hash_text(marks[i].hash).c_str());
    std::printf("],\n \"final_tick\": %" PRId64 ", \"final_hash\": \"%s\", \"bodies_hash\": \"%s\", "
                "\"body_left_bounds\": %s,\n"
                " \"step_ms\": {\"median\": %.6f, \"mean\": %.6f, \"max\": %.6f}, \"wall_s\": %.6f",
                ticks, hash_text(final_hash).c_str(), hash_text(bodies_hash(s.built.world)).c_str(), left_bounds ? "true" : "false",
                median_ms, mean_ms, max_ms, wall);
    if (a.profile) std::printf(",\n \"profile\": %s", bench::profile_json(s.profile.stats()).c_str());
    std::printf("}\n");
    return 0;
  }
  if (!quiet) {
    std::printf("scene %s: %d bodies, %d shapes; %" PRId64 " ticks of 1/%d s; broad phase %s\n", s.scene.name.c_str(),
                counters.body_count, shape_total(s.built.world), ticks, s.scene.step_hz,
                broad_phase_name(s.scene.world.broad_phase));
    for (const Mark& m : marks) std::printf("tick %8" PRId64 "  hash %s\n", m.tick, hash_text(m.hash).c_str());
    std::printf("step time: median %.3f ms, mean %.3f ms, max %.3f ms (%.2f s in all)\n", median_ms, mean_ms, max_ms, total);
    if (left_bounds) std::printf("note: a body left the world bounds and was disabled\n");
    if (a.profile) {
      std::printf("per-stage profile over %zu steps (world_profile(), ms per step):\n%s", s.profile.size(),
                  bench::profile_table(s.profile.stats()).c_str());
    }
    std::printf("bodies hash %s (bodies and shapes only: the same for every broad phase)\n",
                hash_text(bodies_hash(s.built.world)).c_str());
  }
  std::printf("final tick %" PRId64 "  hash %s\n", ticks, hash_text(final_hash).c_str());
  return 0;
}

// --- render --------------------------------------------------------------------
struct RenderArgs {
  std::string scene;
  int64_t tick = -1;
  int64_t every = 0;
  int64_t ticks = -1;
  std::string out_dir;
  std::string format = "png";
  bool aabbs = false, contacts = false, sheet = false, quiet = false, json = false;
  std::string size = "800x600";
};

bool parse_size(const std::string& text, int* w, int* h) {
  unsigned a = 0, b = 0;
  char x = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%u%c%u%c", &a, &x, &b, &extra) != 3 || x != 'x') return false;
  if (a < 16 || b < 16 || a > 16384 || b > 16384) return false;
  *w = static_cast<int>(a), *h = static_cast<int>(b);
  return true;
}

std::string stem_of(const std::string& path) { return std::filesystem::path(path).stem().string(); }

int run_render(const RenderArgs& a, const GlobalOptions& g) {
  const bool quiet = a.quiet || g.quiet, json = a.json || g.json;
  render::RenderOptions options;
  if (!parse_size(a.size, &options.width, &options.height)) {
    std::fprintf(stderr, "tandem render: --size: expected WIDTHxHEIGHT, each 16…16384 pixels, got \"%s\"\n",
                 a.size.c_str());
    return 2;
  }
  if (a.tick >= 0 && a.every > 0) {
    std::fprintf(stderr, "tandem render: give --tick or --every, not both\n");
    return 2;
  }
  options.aabbs = a.aabbs;
  options.contacts = a.contacts;
  SceneRun s;
  std::vector<uint8_t> bytes;
  if (read_file_bytes(a.scene, &bytes).ok() && is_replay_image(bytes)) {
    // A replay file: start from its tick-0 keyframe and play its ticks.
    s.from_replay = true;
    s.scene.name = a.scene;
    if (Status st = read_replay(bytes, &s.replay); !st.ok())
      return std::fprintf(stderr, "tandem render: %s: %s\n", a.scene.c_str(), st.message.c_str()), 2;
    Result<WorldId> w = s.replay.create_world_at(0);
    if (!w.ok()) return std::fprintf(stderr, "tandem render: %s: %s\n", a.scene.c_str(), w.status.message.c_str()), 2;
    s.built.world = w.value;
    s.scene.ticks = static_cast<int64_t>(s.replay.tick_count());
    if (s.replay.header.has_scene_bytes) {  // the embedded scene's view, if it parses
      const std::vector<uint8_t>& text = s.replay.header.scene_bytes;
      Result<scene::Scene> embedded =
          scene::load_scene_text(std::string_view(reinterpret_cast<const char*>(text.data()), text.size()), a.scene);
      if (embedded.ok()) s.scene.has_view = embedded.value.has_view, s.scene.view = embedded.value.view;
    }
  } else if (int rc = open_session("render", a.scene, "", g.scene_limits, &s)) {
    return rc;
  }
  const int64_t ticks = a.ticks >= 0 ? a.ticks : (a.tick >= 0 ? a.tick : s.scene.ticks);
  if (s.from_replay && ticks > s.scene.ticks) {
    std::fprintf(stderr, "tandem render: %s: the replay has %" PRId64 " ticks; asked for %" PRId64 "\n", a.scene.c_str(),
                 s.scene.ticks, ticks);
    return 2;
  }
  if (a.tick > ticks) {
    std::fprintf(stderr, "tandem render: --tick %" PRId64 " is after the last tick %" PRId64 "\n", a.tick, ticks);
    return 2;
  }
  std::error_code ec;
  std::filesystem::create_directories(a.out_dir, ec);
  if (ec) {
    std::fprintf(stderr, "tandem render: %s: cannot create the directory (%s)\n", a.out_dir.c_str(), ec.message().c_str());
    return 2;
  }
  render::View view;
  if (s.scene.has_view)
    view = render::View{s.scene.view.lower.x.to_double(), s.scene.view.lower.y.to_double(),
                        s.scene.view.upper.x.to_double(), s.scene.view.upper.y.to_double()};
  else
    view = render::fit_view(s.built.world);
  const std::string stem = stem_of(a.scene);
  const bool png = a.format == "png" || a.format == "both", svg = a.format == "svg" || a.format == "both";
  std::vector<std::string> written;
  render::ContactSheet sheet(4, std::max(16, options.width / 2), std::max(16, options.height / 2));
  auto frame_wanted = [&](int64_t t) {
    if (a.every > 0) return t % a.every == 0;
    return t == (a.tick >= 0 ? a.tick : ticks);
  };
  for (;;) {
    if (frame_wanted(s.tick)) {
      char name[64];
      std::snprintf(name, sizeof name, "-%06" PRId64, s.tick);
      const std::string base = (std::filesystem::path(a.out_dir) / (stem + name)).string();
      options.caption = stem + "  tick " + std::to_string(s.tick) + "  " + hash_text(world_state_hash(s.built.world));
      if (png) {
        const std::string err = render::render_png(s.built.world, view, options, base + ".png");
        if (!err.empty()) return std::fprintf(stderr, "tandem render: %s\n", err.c_str()), 2;
        written.push_back(base + ".png");
      }
      if (svg) {
        const std::string err = render::render_svg(s.built.world, view, options, base + ".svg");
        if (!err.empty()) return std::fprintf(stderr, "tandem render: %s\n", err.c_str()), 2;
        written.push_back(base + ".svg");
      }
      if (a.sheet) {
        render::RenderOptions small = options;
        small.caption = "tick " + std::to_string(s.tick);
        sheet.add(s.built.world, view, small);
      }
    }
    if (s.tick >= ticks) break;
    if (int rc = step_once("render", &s, false)) return rc;
  }
  if (a.sheet) {
    const std::string path = (std::filesystem::path(a.out_dir) / (stem + "-sheet.png")).string();
    const std::string err = sheet.write_png(path);
    if (!err.empty()) return std::fprintf(stderr, "tandem render: %s\n", err.c_str()), 2;
    written.push_back(path);
  }
  if (json) {
    std::printf("{\"scene\": \"%s\", \"final_tick\": %" PRId64 ", \"final_hash\": \"%s\", \"files\": [",
                json_escape(s.scene.name).c_str(), s.tick, hash_text(world_state_hash(s.built.world)).c_str());
    for (size_t i = 0; i < written.size(); ++i) std::printf("%s\"%s\"", i ? ", " : "", json_escape(written[i]).c_str());
    std::printf("]}\n");
  } else if (!quiet) {
    for (const std::string& f : written) std::printf("wrote %s\n", f.c_str());
  } else {
    std::printf("wrote %zu file%s to %s\n", written.size(), written.size() == 1 ? "" : "s", a.out_dir.c_str());
  }
  return 0;
}

// --- demo ------------------------------------------------------------------------
struct DemoArgs {
  std::string scene;
  std::string out_dir = "tandem-demo";  // scripts/demo.sh passes build/demo
  double seconds = 5;
};

int run_demo(const DemoArgs& a, const GlobalOptions& g) {
  std::string path = a.scene;
  if (path.empty()) {
    path = std::string(TANDEM_SCENES_DIR) + "/rain.json";
    if (!std::filesystem::exists(path)) path = "scenes/rain.json";
    std::error_code ec;  // show it relative to the current directory when it lies below it
    const std::string relative = std::filesystem::proximate(path, ec).string();
    if (!ec && relative.rfind("..", 0) != 0) path = relative;
  }
  SceneRun s;
  if (int rc = open_session("demo", path, "", g.scene_limits, &s)) return rc;
  if (!(a.seconds > 0 && a.seconds <= 3600)) {
    std::fprintf(stderr, "tandem demo: --seconds: expected a number in (0, 3600]\n");
    return 2;
  }
  const auto ticks = static_cast<int64_t>(a.seconds * s.scene.step_hz + 0.5);
  std::error_code ec;
  std::filesystem::create_directories(a.out_dir, ec);
  if (ec) {
    std::fprintf(stderr, "tandem demo: %s: cannot create the directory (%s)\n", a.out_dir.c_str(), ec.message().c_str());
    return 2;
  }
  const WorldCounters c0 = world_counters(s.built.world);
  std::printf("Tandem demo: scene %s (%s), %d bodies, %d shapes\n", s.scene.name.c_str(), s.scene.title.c_str(),
              c0.body_count, c0.shape_count);
  render::View view = s.scene.has_view ? render::View{s.scene.view.lower.x.to_double(), s.scene.view.lower.y.to_double(),
                                                      s.scene.view.upper.x.to_double(), s.scene.view.upper.y.to_double()}
                                       : render::fit_view(s.built.world);
  render::RenderOptions options;
  render::ContactSheet sheet(4, 400, 300);
  const int64_t frame_every = std::max<int64_t>(1, ticks / 7);
  const std::string stem = stem_of(path);

  // 1. Run the scene while recording a replay of it (scene text embedded).
  const std::string replay_path = (std::filesystem::path(a.out_dir) / (stem + ".tandem-replay")).string();
  std::vector<uint8_t> scene_bytes;
  if (Status st = read_file_bytes(path, &scene_bytes); !st.ok())
    return std::fprintf(stderr, "tandem demo: %s\n", st.message.c_str()), 2;
  RecorderOptions recorder_options;
  recorder_options.time_step = s.scene.time_step;
  recorder_options.keyframe_interval = 60;
  ReplayRecorder recorder;
  if (Status st = recorder.open_file(replay_path, recorder_options); !st.ok())
    return std::fprintf(stderr, "tandem demo: %s\n", st.message.c_str()), 2;
  if (Status st = recorder.begin(s.built.world, scene_bytes); !st.ok())
    return std::fprintf(stderr, "tandem demo: %s\n", st.message.c_str()), 2;
  const auto wall0 = Clock::now();
  ProgressBar progress("", g.quiet);
  while (true) {
    if (s.tick % frame_every == 0 || s.tick == ticks) {
      options.caption = "tick " + std::to_string(s.tick);
      sheet.add(s.built.world, view, options);
    }
    if (s.tick >= ticks) break;
    for (const tandem::Command& c : scene::scene_inputs_at(s.built, s.scene, s.tick))
      if (Status st = recorder.submit(c); !st.ok())
        return std::fprintf(stderr, "tandem demo: tick %" PRId64 ": %s\n", s.tick, st.message.c_str()), 2;
    const auto t0 = Clock::now();
    const StepResult r = recorder.step();
    s.step_seconds.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
    if (!r.ok()) return std::fprintf(stderr, "tandem demo: step %" PRId64 ": %s\n", s.tick + 1, r.status.message.c_str()), 2;
    ++s.tick;
    progress.update(static_cast<uint64_t>(s.tick), static_cast<uint64_t>(ticks));
  }
  progress.finish();
  if (Status st = recorder.finish(); !st.ok()) return std::fprintf(stderr, "tandem demo: %s\n", st.message.c_str()), 2;
  const double wall = std::chrono::duration<double>(Clock::now() - wall0).count();
  std::vector<double> sorted = s.step_seconds;
  std::sort(sorted.begin(), sorted.end());
  const uint64_t hash = world_state_hash(s.built.world);
  std::printf("  simulated %" PRId64 " ticks (%.1f s at %d Hz) in %.2f s (median step %.3f ms), recording every input\n"
              "  and the state hash after every tick\n",
              ticks, static_cast<double>(ticks) / s.scene.step_hz, s.scene.step_hz, wall,
              sorted.empty() ? 0.0 : sorted[sorted.size() / 2] * 1e3);
  std::printf("  final state hash (XXH3-64 of the canonical state): %s\n", hash_text(hash).c_str());

  // 2. Verify: read the replay back and re-simulate it from its keyframes.
  Replay replay;
  if (Status st = read_replay_file(replay_path, &replay); !st.ok())
    return std::fprintf(stderr, "tandem demo: %s\n", st.message.c_str()), 2;
  const VerifyReport report = verify_replay(replay);
  const int verify_rc = verify_exit_code(report);
  std::printf("  replay read back and re-simulated (tandem verify):%s\n", verify_rc == 0 ? "" : " FAILED");
  const std::string text = format_verify_report(report);
  for (size_t start = 0; start < text.size();) {
    const size_t end = std::min(text.find('\n', start), text.size());
    std::printf("    %s\n", text.substr(start, end - start).c_str());
    start = end + 1;
  }

  // 3. Draw the final state and the contact sheet.
  const std::string picture = (std::filesystem::path(a.out_dir) / (stem + "-final.png")).string();
  const std::string sheet_path = (std::filesystem::path(a.out_dir) / (stem + "-sheet.png")).string();
  options.caption = stem + "  tick " + std::to_string(s.tick) + "  " + hash_text(hash);
  options.width = 1000, options.height = 750;
  // Framed on where the bodies ended up, within the scene's view.
  render::View final_view = render::fit_view(s.built.world);
  if (s.scene.has_view) {
    final_view.min_x = std::max(final_view.min_x, view.min_x), final_view.max_x = std::min(final_view.max_x, view.max_x);
    final_view.min_y = std::max(final_view.min_y, view.min_y), final_view.max_y = std::min(final_view.max_y, view.max_y);
    if (final_view.min_x >= final_view.max_x || final_view.min_y >= final_view.max_y) final_view = view;
  }
  for (const std::string& err :
       {render::render_png(s.built.world, final_view, options, picture), sheet.write_png(sheet_path)})
    if (!err.empty()) return std::fprintf(stderr, "tandem demo: %s\n", err.c_str()), 2;
  std::printf("  picture:       %s\n  contact sheet: %s\n  replay:        %s\n", picture.c_str(), sheet_path.c_str(),
              replay_path.c_str());
  std::printf("Next: tandem run %s --ticks 600\n      tandem render %s --every 60 -o %s --sheet\n"
              "      tandem verify %s\n",
              path.c_str(), path.c_str(), a.out_dir.c_str(), replay_path.c_str());
  return verify_rc;
}

}  // namespace

void register_scene_commands(CLI::App& app, const GlobalOptions& options, std::vector<Command>* commands) {
  const std::vector<std::string> broad_phases = {"naive", "sap", "grid", "tree"};

  auto* run = app.add_subcommand("run", "Run a scene file and print its state hashes and step times");
  auto run_args = std::make_shared<RunArgs>();
  run->add_option("scene", run_args->scene, "scene file (JSON, docs/scene-format.md)")->required();
  run->add_option("--ticks,-n", run_args->ticks, "steps to run (default: the scene's \"ticks\")")
      ->check(CLI::Range(int64_t{0}, int64_t{1} << 40));
  run->add_option("--broadphase", run_args->broad_phase, "override the scene's broad phase")
      ->check(CLI::IsMember(broad_phases));
  run->add_option("--hash-every", run_args->hash_every, "print the state hash every K ticks (0: final only)")
      ->check(CLI::Range(int64_t{0}, int64_t{1} << 40));
  add_output_flags(run, &run_args->json, &run_args->quiet, "print only the final hash");
  run->add_flag("--profile", run_args->profile,
                "per-stage step times (world_profile()): median and mean ms per stage, as a table or in --json");
  run->footer(
      "Examples:\n  tandem run scenes/pyramid.json\n  tandem run scenes/circles.json --ticks 3600 --broadphase grid\n"
      "  tandem run scenes/rain.json --hash-every 0 --json\n"
      "  tandem run scenes/pyramid.json --profile\n");
  commands->push_back({run, [run_args, &options] { return run_run(*run_args, options); }});

  auto* render = app.add_subcommand("render", "Draw a scene at some ticks to PNG or SVG (Cairo)");
  auto render_args = std::make_shared<RenderArgs>();
  render->add_option("scene", render_args->scene, "scene file (JSON) or replay file (tandem record)")->required();
  auto* tick = render->add_option("--tick,-t", render_args->tick, "draw this tick only (default: the last)")
                   ->check(CLI::Range(int64_t{0}, int64_t{1} << 40));
  render->add_option("--every", render_args->every, "draw every K ticks, from tick 0")
      ->check(CLI::Range(int64_t{1}, int64_t{1} << 40))
      ->excludes(tick);
  render->add_option("--ticks,-n", render_args->ticks, "last tick (default: --tick, else the scene's \"ticks\")")
      ->check(CLI::Range(int64_t{0}, int64_t{1} << 40));
  render->add_option("-o,--out", render_args->out_dir, "output directory (created if missing)")->required();
  render->add_option("--format", render_args->format, "png, svg or both")
      ->check(CLI::IsMember({"png", "svg", "both"}));
  render->add_flag("--aabbs", render_args->aabbs, "draw shape bounding boxes");
  render->add_flag("--contacts", render_args->contacts, "draw contact points and normals");
  render->add_flag("--sheet", render_args->sheet, "also write SCENE-sheet.png: every drawn frame in one grid");
  render->add_option("--size", render_args->size, "picture size, WIDTHxHEIGHT pixels (default 800x600)");
  render->add_flag("--json", render_args->json, "list the written files as JSON");
  render->add_flag("--quiet,-q", render_args->quiet, "print only a one-line summary");
  render->footer(
      "Files are named DIR/SCENE-TICK.png (six-digit tick).\nExamples:\n"
      "  tandem render scenes/pyramid.json --tick 120 -o out\n"
      "  tandem render scenes/rain.json --every 60 --ticks 600 -o out --sheet --contacts\n"
      "  tandem render scenes/tumbler.json -o out --format svg --size 1200x900\n"
      "  tandem render build/demo/rain.tandem-replay --tick 200 -o out   (a replay: seeks to the tick)\n");
  commands->push_back({render, [render_args, &options] { return run_render(*render_args, options); }});

  auto* demo = app.add_subcommand("demo", "Run a bundled scene, record a replay, verify it, draw the result");
  auto demo_args = std::make_shared<DemoArgs>();
  demo->add_option("--scene", demo_args->scene, "scene file (default: the bundled scenes/rain.json)");
  demo->add_option("-o,--out", demo_args->out_dir, "output directory (default: tandem-demo; the last one given wins)")
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  demo->add_option("--seconds", demo_args->seconds, "simulated seconds (default 5)");
  demo->footer("Examples:\n  tandem demo\n  tandem demo --scene scenes/pyramid.json -o /tmp/demo --seconds 10\n");
  commands->push_back({demo, [demo_args, &options] { return run_demo(*demo_args, options); }});
}

}  // namespace tandem::cli
