// profile_stats.h — per-stage statistics of world_profile() over many steps
// (tools only; doubles here are display values, never fed back).
//
// A ProfileSeries keeps every step's WorldProfile (physics/tandem.h) and
// reports, per stage, the median and mean in milliseconds per step. The
// `tandem run --profile` command and the benchmark suite (--profile, and the
// "profile" object of its JSON) print the same stages in the same order.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "physics/tandem.h"

namespace tandem::bench {

/// One stage's statistics over the recorded steps, ms per step.
struct StageStat {
  const char* name = "";  ///< e.g. "broad_phase"; "total" for the whole step
  double median_ms = 0;
  double mean_ms = 0;
};

/// The stage names of WorldProfile with the value of each in `p`, ns, in
/// the order the step runs them; the last entry is "total".
std::vector<std::pair<const char*, int64_t>> profile_stages(const WorldProfile& p);

/// Every step's profile, in order.
class ProfileSeries {
 public:
  /// Records one step's profile.
  void add(const WorldProfile& p) { steps_.push_back(p); }
  /// Appends another series' steps.
  void append(const ProfileSeries& other) { steps_.insert(steps_.end(), other.steps_.begin(), other.steps_.end()); }
  /// Steps recorded.
  size_t size() const { return steps_.size(); }
  bool empty() const { return steps_.empty(); }
  /// Median and mean of each stage (profile_stages order, "total" last);
  /// empty when no step was recorded.
  std::vector<StageStat> stats() const;

 private:
  std::vector<WorldProfile> steps_;
};

/// A text table: stage, median ms, mean ms, share of the mean total (%).
std::string profile_table(const std::vector<StageStat>& stats);

/// A JSON object {"stage": {"median_ms": m, "mean_ms": a}, ...} (no
/// trailing newline).
std::string profile_json(const std::vector<StageStat>& stats);

}  // namespace tandem::bench
