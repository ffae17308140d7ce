// cli.h — how the `tandem` command line is put together (tools only).
//
// main.cpp builds one CLI11 app and asks each command family to register its
// subcommands; each family lives in its own file and returns the exit code of
// the subcommand that ran through the `run` callback it stores:
//   cmd_scene.cpp    run, render, demo           (scene files, tools/scene)
//   cmd_replay.cpp   record, replay, verify, diff, synctest (replay/)
//   cmd_bench.cpp    bench                       (tools/bench scenes and peers)
//   cmd_state.cpp    state                       (bodies at one tick, exact)
//   cmd_session.cpp  session, netplay, session-bench (replay/session.h over tools/net)
// Exit codes: 0 success, 1 the check failed (verify mismatch, diff found a
// difference), 2 bad usage or bad input (missing file, malformed scene).
#pragma once

#include <CLI/CLI.hpp>

#include <functional>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace tandem::cli {

/// Options every command shares.
struct GlobalOptions {
  bool quiet = false;  ///< --quiet: no progress bar, only errors and the final result
  bool json = false;   ///< --json: machine-readable output on stdout
  scene::SceneLimits scene_limits;  ///< --max-bodies / --max-shapes: what a scene file may ask for
};

/// One registered subcommand: its CLI11 node and what runs when it parsed.
struct Command {
  CLI::App* app = nullptr;
  std::function<int()> run;
};

/// Adds run, render and demo to `app` (cmd_scene.cpp).
void register_scene_commands(CLI::App& app, const GlobalOptions& options, std::vector<Command>* commands);
/// Adds record, replay, verify, diff and synctest to `app` (cmd_replay.cpp).
void register_replay_commands(CLI::App& app, const GlobalOptions& options, std::vector<Command>* commands);
/// Adds bench to `app` (cmd_bench.cpp).
void register_bench_commands(CLI::App& app, const GlobalOptions& options, std::vector<Command>* commands);
/// Adds state to `app` (cmd_state.cpp).
void register_state_commands(CLI::App& app, const GlobalOptions& options, std::vector<Command>* commands);
/// Adds session, netplay and session-bench to `app` (cmd_session.cpp).
void register_session_commands(CLI::App& app, const GlobalOptions& options, std::vector<Command>* commands);

}  // namespace tandem::cli
