// golden_support.h — golden hash chains: scenes built from the public API,
// a runner that steps a scene and hashes every tick, and the golden files
// the hashes are compared against (tests/golden/<scene>.txt).
//
// DESIGN. A scene is a build function (creates bodies and shapes in a fresh
// world) and a script function (called before every step with the tick
// number: impulses, forces, velocity sets, creations and destructions). Both
// use integer and fixed-point inputs only, so every platform feeds the world
// the same bits. Scene state outside the world (the handles a script keeps)
// lives in SceneContext, a plain copyable struct, so a snapshot/restore run
// can roll it back together with the world.
//
// The hash of a tick is world_state_hash (replay/state.h: XXH3-64 of the
// world's canonical little-endian state image, which includes the touching
// pairs and sensor overlaps, so events are covered) after that tick's step.
// Runs with another broad phase hash the same image with its broad-phase
// byte set to naive's: every kind must give the same state otherwise. The
// chain hash is XXH3-64 of all the tick hashes (8 little-endian bytes each,
// in order), so a mismatch anywhere in the run, recorded tick or not,
// changes it. k_hash_source names the recipe and every golden file states
// it. Golden files record every 60th tick (to find the first recorded tick
// that differs) and the chain.
//
// The golden files are text, one record per line:
//   # comments
//   scene <name>
//   hash <k_hash_source>
//   ticks <n>
//   tick <t> <16 hex digits>        every k_record_interval ticks
//   chain <16 hex digits>
// Regeneration (docs/determinism.md): run tandem_tests_golden with
// TANDEM_GOLDEN_REGENERATE=1; it rewrites the files from this build's run.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "physics/tandem.h"

namespace tandem::golden {

/// Ticks every scene runs (60 s at 60 Hz).
inline constexpr int32_t k_scene_ticks = 3600;
/// Golden files record the hash of every k_record_interval-th tick.
inline constexpr int32_t k_record_interval = 60;

/// What a scene keeps outside the world: the handles its script uses, a
/// counter, and the first API failure (scenes never expect one).
struct SceneContext {
  WorldId world;
  std::vector<BodyId> bodies;   ///< named by the scene (index = the scene's own numbering)
  std::vector<ShapeId> shapes;  ///< likewise
  std::vector<JointId> joints;  ///< likewise (golden_joint_scenes.cpp)
  int64_t counter = 0;          ///< any scene state (spawn count, ...)
  std::string error;            ///< the first failed call, "" when none

  /// Records the first failure: "<what>: <message>".
  void check(const Status& s, const char* what);
  /// The value of r, recording a failure.
  template <typename T>
  T value(const Result<T>& r, const char* what) {
    check(r.status, what);
    return r.value;
  }
};

/// A golden scene.
struct Scene {
  const char* name;                          ///< file name stem, [a-z0-9_]
  const char* covers;                        ///< what it exercises (for the docs and messages)
  void (*build)(SceneContext& ctx);          ///< fills ctx.world (created from default_world_def())
  void (*script)(SceneContext& ctx, int32_t tick);  ///< before step `tick` (1-based); may be null
};

/// All golden scenes, in a fixed order.
std::span<const Scene> scenes();

/// The recipe of the per-tick hash (written to and checked in every file).
extern const std::string k_hash_source;

/// How to run a chain.
struct ChainOptions {
  BroadPhaseKind broad_phase = BroadPhaseKind::naive;
  /// Start naive and switch kinds with world_set_broad_phase every 300 ticks.
  bool cycle_broad_phase = false;
  int32_t ticks = k_scene_ticks;
  /// Snapshot/restore round trips at seeded random ticks: after the tick,
  /// encode the state, run a detour of 1..40 ticks, then restore (into the
  /// same world, or every other time into a new world) and go on. 0: none.
  int32_t restore_count = 0;
  uint64_t restore_seed = 0;
  /// Round trips through the compact rollback snapshot (replay/rollback.h:
  /// rollback_save / rollback_restore) instead of the portable image; the
  /// restored world is then checked by the rollback hash of a new save.
  bool compact = false;
  /// Called after every tick's step (tests that check what a scene does).
  std::function<void(SceneContext&, int32_t tick)> observe;
  /// WorldDef::worker_count and the task callbacks of the scene's world
  /// (test_golden_workers.cpp); a step reporting k_step_flag_task_failure
  /// ends the run with an error.
  int32_t worker_count = 1;
  EnqueueTaskFunction enqueue_task = nullptr;
  FinishTaskFunction finish_task = nullptr;
  void* user_task_context = nullptr;
};

/// One recorded tick.
struct TickHash {
  int32_t tick = 0;
  uint64_t hash = 0;
};

/// The outcome of a run (or the content of a golden file).
struct Chain {
  std::string error;              ///< "" when the run (or parse) succeeded
  std::string hash_source;        ///< k_hash_source for a run
  int32_t ticks = 0;              ///< ticks run
  std::vector<TickHash> records;  ///< every k_record_interval-th tick
  uint64_t chain = 0;             ///< fold of every tick's hash
  int32_t restores = 0;           ///< snapshot/restore round trips done
};

/// Builds the scene in a new world and runs it (the world is destroyed at
/// the end). Stops at the first failed API call (Chain::error names the
/// tick and the call).
Chain run_chain(const Scene& scene, const ChainOptions& options);

/// The golden directory: $TANDEM_GOLDEN_DIR, else the source folder.
std::string golden_dir();
/// Reads <dir>/<scene>.txt; Chain::error says what is wrong (file, line).
Chain read_golden(const std::string& scene);
/// Writes <dir>/<scene>.txt; returns "" or an error message.
std::string write_golden(const std::string& scene, const Scene& info, const Chain& chain);

/// Compares a run with a golden chain: "" when equal, else a message naming
/// the first differing recorded tick (or the chain when only unrecorded
/// ticks differ) with both values. A run shorter than the golden (a tick
/// cap) compares its records only.
std::string compare(const Chain& golden, const Chain& run);

/// The tick cap from $TANDEM_GOLDEN_TICKS (k_scene_ticks when unset).
int32_t tick_cap();
/// True when $TANDEM_GOLDEN_REGENERATE is set to a non-empty value other than 0.
bool regenerate_mode();

}  // namespace tandem::golden
