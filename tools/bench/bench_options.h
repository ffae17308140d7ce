// bench_options.h — the command-line options of the physics benchmark,
// shared by the tandem_bench_physics driver and `tandem bench` so both take
// the same flags (CLI11; tools only).
#pragma once

#include <CLI/CLI.hpp>

#include "suite.h"

namespace tandem::bench {

/// Adds the suite's options to `app`, writing into *o (which must outlive
/// parsing). `peers_default`: whether peers run unless --no-peers is given.
inline void add_bench_options(CLI::App& app, BenchOptions* o, bool peers_default) {
  o->peers = peers_default;
  app.add_option("scenes", o->scenes,
                 "scenes: circles-N (N or Nk), pyramid-B, rain-N, large_pyramid, many_pyramids, smash, joint_grid[-N], "
                 "tumbler[-G], spinner[-N]; default circles-1k..32k, pyramid-20, pyramid-100, rain-4000, many_pyramids, "
                 "smash, joint_grid, tumbler");
  app.add_option("--runs", o->runs, "runs per scene and engine (median, min-max)")->check(CLI::Range(1, 1000));
  app.add_option("--runs-large", o->runs_large, "runs for scenes of more than 4000 bodies (default: --runs)")
      ->check(CLI::Range(1, 1000));
  app.add_option("--steps", o->steps, "timed steps (default: the scene's: circles 300, pyramid 500, rain 600)")
      ->check(CLI::Range(1, 1000000));
  app.add_option("--warmup", o->warmup, "untimed steps first (default: circles 60, others 0)")
      ->check(CLI::Range(0, 1000000));
  app.add_option("--broadphase", o->broad_phases, "Tandem broad phases: naive, sap, grid, tree, all (default all)")
      ->delimiter(',');
  app.add_option("--naive-max", o->naive_max, "skip the naive broad phase above this many bodies (O(n^2))");
  app.add_option("--max-run-seconds", o->max_run_seconds,
                 "a run slower than this (timed steps, s) is not repeated, and its engine skips larger scenes of "
                 "the family; 0: no limit")
      ->check(CLI::Range(0, 1000000));
  app.add_flag("--peers,!--no-peers", o->peers, "also run Box2D 2.4 and Chipmunk2D (when linked in)");
  app.add_option("--engines", o->engines,
                 "run only these engines, e.g. tandem/grid,box2d3-w1 (names as in the table; peers need --peers)")
      ->delimiter(',');
  app.add_option("--workers", o->workers,
                 "Tandem's worker threads (WorldDef::worker_count, built-in pool), 1-16; results are identical for "
                 "every count (default 1)")
      ->check(CLI::Range(1, 16));
  app.add_option_function<std::string>(
         "--clock", [o](const std::string& v) { o->cpu_clock = v == "cpu"; },
         "wall (default) or cpu: time single-threaded rows by the process's CPU time (CLOCK_PROCESS_CPUTIME_ID), "
         "which a busy machine disturbs far less than the wall clock; rows with more than one worker stay on the "
         "wall clock (CPU time sums the threads)")
      ->check(CLI::IsMember({"wall", "cpu"}));
  app.add_flag("--profile", o->profile,
               "print Tandem's per-stage profile (median ms/step per stage over all timed steps) as a Markdown "
               "table; the JSON always has it");
  app.add_option("--rays", o->rays,
                 "run the ray-cast benchmark instead: this many closest-hit rays per batch, --runs batches, in each "
                 "engine (default scene rain-4000; Box2D 2.4 with --peers)")
      ->check(CLI::Range(1, 100000000));
  app.add_option("--csv", o->csv, "write the results as CSV to this file");
  app.add_option("--json", o->json, "write the results as JSON to this file");
  app.add_option("--svg", o->svg, "write a plot of circles-N step time against N to this SVG file");
}

}  // namespace tandem::bench
