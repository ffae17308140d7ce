// cmd_state.cpp — `tandem state SCENE|REPLAY --tick N [--json]`: every body's
// position, angle, velocities (exact decimal and raw Q32.32) and sleep state at
// one tick — what a user diffing two machines by hand reaches for first.
//
// A scene file is built and stepped with its scripted inputs (as `tandem run`);
// a replay file is played from its initial keyframe (as `tandem replay`). Tick
// 0 is the world before the first step. Bodies are listed in handle order
// (world_bodies), each with its handle (index:generation), its type, and its
// canonical per-body hash (body_state_hash), so two outputs can be compared
// line by line. Doubles never appear: every number is printed exactly.
// See cli.h for the exit codes.
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cinttypes>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "cli.h"
#include "cli_util.h"
#include "replay/commands.h"
#include "replay/replay_file.h"
#include "replay/state.h"
#include "replay/verify.h"
#include "scene/scene.h"

namespace tandem::cli {
namespace {

using Json = nlohmann::ordered_json;

struct StateArgs {
  std::string file;
  int64_t tick = -1;
  bool json = false, quiet = false;
};

int fail(const std::string& message) { return cli::fail("state", message); }

// True when the file starts with the replay magic (replay_file.h), else a scene.
bool looks_like_replay(const std::vector<uint8_t>& bytes) {
  static constexpr char k_magic[] = "TANDREPL";
  return bytes.size() >= 8 && std::equal(k_magic, k_magic + 8, bytes.begin());
}

const char* type_name(BodyType t) {
  switch (t) {
    case BodyType::static_body: return "static";
    case BodyType::kinematic_body: return "kinematic";
    case BodyType::dynamic_body: return "dynamic";
  }
  return "unknown";
}

Json q32_json(Q32 v) { return Json{{"value", q32_raw_text(v.raw)}, {"raw", v.raw}}; }

// Prints (or writes as JSON) every body of `world` at `tick`.
int print_state(WorldId world, int64_t tick, const StateArgs& a, bool json) {
  std::vector<BodyId> bodies(static_cast<size_t>(world_counters(world).body_count));
  const int32_t n = world_bodies(world, bodies.data(), static_cast<int32_t>(bodies.size()));
  bodies.resize(static_cast<size_t>(n < 0 ? 0 : n));
  const uint64_t hash = world_state_hash(world);
  if (json) {
    Json j;
    j["tick"] = tick;
    j["world_hash"] = hash_text(hash);
    Json list = Json::array();
    for (const BodyId b : bodies) {
      const Vec2 p = body_position(b), v = body_linear_velocity(b);
      Json e;
      e["index"] = b.index1 - 1;
      e["generation"] = b.generation;
      e["type"] = type_name(body_type(b));
      e["position"] = {{"x", q32_json(p.x)}, {"y", q32_json(p.y)}};
      e["angle"] = q32_json(body_angle(b));
      e["linear_velocity"] = {{"x", q32_json(v.x)}, {"y", q32_json(v.y)}};
      e["angular_velocity"] = q32_json(body_angular_velocity(b));
      e["awake"] = body_is_awake(b);
      e["hash"] = hash_text(body_state_hash(b));
      list.push_back(std::move(e));
    }
    j["bodies"] = std::move(list);
    std::printf("%s\n", j.dump().c_str());
    return 0;
  }
  // The file name is left out so that a scene's and its replay's outputs compare equal.
  std::printf("tick %" PRId64 ": %zu bodies, world hash %s\n", tick, bodies.size(), hash_text(hash).c_str());
  if (a.quiet) return 0;
  std::printf("# body index:generation type awake | position x y | angle | velocity x y | angular velocity | body hash\n");
  std::printf("# each number as exact decimal [raw Q32.32]\n");
  auto q = [](Q32 v) { return q32_raw_text(v.raw) + " [" + std::to_string(v.raw) + "]"; };
  for (const BodyId b : bodies) {
    const Vec2 p = body_position(b), v = body_linear_velocity(b);
    std::printf("body %u:%u %s %s | p %s %s | a %s | v %s %s | w %s | %s\n", b.index1 - 1, b.generation,
                type_name(body_type(b)), body_is_awake(b) ? "awake" : "asleep", q(p.x).c_str(), q(p.y).c_str(),
                q(body_angle(b)).c_str(), q(v.x).c_str(), q(v.y).c_str(), q(body_angular_velocity(b)).c_str(),
                hash_text(body_state_hash(b)).c_str());
  }
  return 0;
}

int run_state(const StateArgs& a, const GlobalOptions& g) {
  const bool json = a.json || g.json;
  std::vector<uint8_t> bytes;
  if (Status s = read_file_bytes(a.file, &bytes); !s.ok()) return fail(s.message);
  if (looks_like_replay(bytes)) {
    Replay replay;
    ReplayReadInfo info;
    if (Status s = read_replay_file(a.file, &replay, &info); !s.ok()) return fail(s.message);
    if (!info.warning.empty()) std::fprintf(stderr, "tandem state: warning: %s\n", info.warning.c_str());
    const int64_t last = replay.tick_count();
    const int64_t tick = a.tick >= 0 ? a.tick : last;
    if (tick > last)
      return fail(a.file + ": --tick " + std::to_string(tick) + " is past the last recorded tick " +
                  std::to_string(last));
    Result<WorldId> created =
        create_world_from_snapshot(replay.keyframes[0].state.data(), replay.keyframes[0].state.size());
    if (!created.ok()) return fail(a.file + ": initial keyframe: " + created.status.message);
    const WorldId world = created.value;
    int rc = 0;
    for (int64_t t = 1; t <= tick && rc == 0; ++t) {
      const Status s = run_tick(world, replay.tick_record(t), replay.header.time_step);
      if (!s.ok()) rc = fail(a.file + ": tick " + std::to_string(t) + ": " + s.message);
    }
    if (rc == 0) rc = print_state(world, tick, a, json);
    (void)destroy_world(world);
    return rc;
  }
  Result<scene::Scene> loaded =
      scene::load_scene_text(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), a.file);
  if (!loaded.ok()) return fail(loaded.status.message);
  const scene::Scene& sc = loaded.value;
  Result<scene::BuiltScene> built = scene::build_world(sc);
  if (!built.ok()) return fail(built.status.message);
  const WorldId world = built.value.world;
  const int64_t tick = a.tick >= 0 ? a.tick : sc.ticks;
  int rc = 0;
  for (int64_t t = 0; t < tick && rc == 0; ++t) {
    if (Status s = scene::apply_scene_inputs(built.value, sc, t); !s.ok()) {
      rc = fail(s.message);
      break;
    }
    const StepResult r = world_step(world, sc.time_step);
    if (!r.ok()) rc = fail(a.file + ": step " + std::to_string(t + 1) + " refused: " + r.status.message);
  }
  if (rc == 0) rc = print_state(world, tick, a, json);
  (void)destroy_world(world);
  return rc;
}

}  // namespace

void register_state_commands(CLI::App& app, const GlobalOptions& options, std::vector<Command>* commands) {
  auto* state = app.add_subcommand("state", "Print every body's pose, velocities and sleep state at one tick");
  auto args = std::make_shared<StateArgs>();
  state->add_option("file", args->file, "scene file (JSON) or replay file (from tandem record)")->required();
  state->add_option("--tick,-t", args->tick, "tick to show: 0 is before the first step (default: the scene's "
                                             "\"ticks\", or a replay's last recorded tick)")
      ->check(CLI::Range(int64_t{0}, int64_t{1} << 40));  // the bound of run/record --ticks
  add_output_flags(state, &args->json, &args->quiet, "print only the summary line (tick, body count, world hash)");
  state->footer(
      "Numbers are exact decimals with their raw Q32.32 value; outputs from two machines diff line by line.\n"
      "Examples:\n"
      "  tandem state scenes/pyramid.json --tick 120\n"
      "  tandem state game.tnr --tick 3600 --json > tick3600.json");
  commands->push_back({state, [args, &options] { return run_state(*args, options); }});
}

}  // namespace tandem::cli
