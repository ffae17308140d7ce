// cli_util.h — small pieces every command family shares (tools only): the
// progress bar, the error printer, the --json/--quiet flags and a world that
// is destroyed at scope end.
#pragma once

#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdint>
#include <string>

#include "physics/tandem.h"

namespace tandem::cli {

/// Progress of a long job on stderr: drawn only when stderr is a terminal, the
/// job has run for more than a second and `off` is false; redrawn at most every
/// 100 ms; erased by finish() (and the destructor).
class ProgressBar {
 public:
  /// `label` (may be empty) is printed before the bar and `unit` ("tick",
  /// "file") before the count; both must outlive the bar.
  ProgressBar(const char* label, bool off, const char* unit = "tick");
  ~ProgressBar() { finish(); }
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;
  /// Shows `done` of `total` units (nothing when total is 0).
  void update(uint64_t done, uint64_t total);
  /// Erases the bar if it was drawn.
  void finish();

 private:
  using Clock = std::chrono::steady_clock;
  const char* label_;
  const char* unit_;
  bool enabled_;
  bool shown_ = false;
  Clock::time_point start_ = Clock::now(), last_ = start_;
};

/// Prints "tandem COMMAND: MESSAGE" on stderr and returns exit code 2 (bad
/// usage or bad input, cli.h).
int fail(const char* command, const std::string& message);

/// Adds the per-command --json and --quiet,-q flags (`quiet_help` says what
/// --quiet leaves).
void add_output_flags(CLI::App* command, bool* json, bool* quiet, const char* quiet_help);

/// A world destroyed at the end of the scope: the public owning wrapper.
using OwnedWorld = UniqueWorld;

}  // namespace tandem::cli
