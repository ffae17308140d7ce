// suite.h — the physics benchmark suite: runs scenes × engines, prints the
// table and writes CSV, JSON and an SVG plot (tools only). Used by the
// tandem_bench_physics driver and by `tandem bench` (tools/cli/cmd_bench.cpp).
//
// For each scene and engine: `runs` fresh worlds, each stepped `warmup`
// untimed and `steps` timed steps. Reported: median ms/step and min–max over
// the runs, each Tandem row's ratio to each peer's median (Tandem / peer:
// above 1 means Tandem is slower), and the quality probes of the first run
// (harness.h; every engine here is deterministic run to run). Tandem rows of
// one scene must end in identical states whatever the broad phase: the suite
// compares their fingerprints and warns when they differ.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "harness.h"

namespace tandem::bench {

/// What to run and where to write it.
struct BenchOptions {
  std::vector<std::string> scenes;        ///< scene names (scenes.h); empty: default_scene_names()
  int32_t runs = 5;                       ///< runs per scene and engine, ≥ 1
  int32_t runs_large = 0;                 ///< runs for scenes of > 4000 dynamic bodies; 0: same as runs
  int32_t steps = 0;                      ///< timed steps; 0: the scene's default
  int32_t warmup = -1;                    ///< warm-up steps; −1: the scene's default
  std::vector<std::string> broad_phases;  ///< Tandem broad phases (naive, sap, grid, tree, all); empty: all
  bool peers = false;                     ///< also run the peer engines (when linked in)
  std::vector<std::string> engines;       ///< run only these rows ("tandem/grid", "box2d24", "box2d3-w1", ...);
                                          ///< empty: all that the options above select
  int32_t naive_max = 4000;               ///< skip the naive broad phase above this many dynamic bodies
  int32_t max_run_seconds = 60;           ///< a run whose timed steps take longer ends that row after
                                          ///< it and skips the engine for larger scenes of the family; 0: off
  std::string csv, json, svg;             ///< output files; empty: not written
  bool quiet = false;                     ///< no progress lines on stderr
  int32_t workers = 1;                    ///< Tandem's WorldDef::worker_count, 1…16 (built-in pool)
  bool profile = false;                   ///< also print Tandem's per-stage profile (median ms per
                                          ///< stage, world_profile()) as a Markdown table
  bool cpu_clock = false;                 ///< time single-threaded rows by the process's CPU time instead of
                                          ///< the wall clock (--clock cpu: steadier on a shared machine);
                                          ///< rows with more than one worker keep the wall clock
  int32_t rays = 0;                       ///< > 0: run the ray-cast benchmark (ray_bench.cpp) with this many
                                          ///< rays per batch instead of the stepping one; default scene rain-4000
};

/// Runs the suite: progress on stderr, the table on stdout, the files asked
/// for. Returns 0 on success, 1 when Tandem's broad phases ended a scene in
/// different states (after writing everything), 2 on bad options (an unknown scene or broad
/// phase, runs < 1, a file that cannot be written) with the reason on stderr.
int run_bench_suite(const BenchOptions& options);

/// The ray-cast benchmark's rays for a scene (ray_bench.cpp: fixed seed,
/// inside the scene's container, never zero length).
std::vector<RaySpec> make_rays(const SceneSpec& scene, int32_t count);

/// The ray-cast benchmark (ray_bench.cpp) over scenes × engines (those with
/// Engine::cast_rays); `machine` is printed in the header. Called by
/// run_bench_suite when options.rays > 0; returns as it does (1: Tandem's
/// broad phases disagreed on a hit).
int run_ray_bench(const BenchOptions& options, const std::vector<SceneSpec>& scenes,
                  const std::vector<Engine>& engines, const std::string& machine);

}  // namespace tandem::bench
