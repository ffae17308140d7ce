// profile_stats.cpp — per-stage medians and means of world_profile() (see
// profile_stats.h).
#include "profile_stats.h"

#include <algorithm>
#include <cstdio>

namespace tandem::bench {

std::vector<std::pair<const char*, int64_t>> profile_stages(const WorldProfile& p) {
  return {{"broad_phase", p.broad_phase_ns},
          {"narrow_phase", p.narrow_phase_ns},
          {"islands", p.islands_ns},
          {"events", p.events_ns},
          {"prepare", p.prepare_ns},
          {"integrate_velocities", p.integrate_velocities_ns},
          {"warm_start", p.warm_start_ns},
          {"solve", p.solve_ns},
          {"integrate_positions", p.integrate_positions_ns},
          {"relax", p.relax_ns},
          {"restitution", p.restitution_ns},
          {"store_impulses", p.store_impulses_ns},
          {"continuous", p.continuous_ns},
          {"finalize", p.finalize_ns},
          {"total", p.total_ns}};
}

std::vector<StageStat> ProfileSeries::stats() const {
  std::vector<StageStat> out;
  if (steps_.empty()) return out;
  const size_t stage_count = profile_stages(WorldProfile{}).size();
  std::vector<int64_t> values(steps_.size());
  for (size_t s = 0; s < stage_count; ++s) {
    double sum = 0;
    for (size_t i = 0; i < steps_.size(); ++i) {
      values[i] = profile_stages(steps_[i])[s].second;
      sum += static_cast<double>(values[i]);
    }
    std::sort(values.begin(), values.end());
    const size_t n = values.size();
    const double median = n % 2 ? static_cast<double>(values[n / 2])
                                : 0.5 * (static_cast<double>(values[n / 2 - 1]) + static_cast<double>(values[n / 2]));
    StageStat st;
    st.name = profile_stages(WorldProfile{})[s].first;
    st.median_ms = median * 1e-6;
    st.mean_ms = sum / static_cast<double>(n) * 1e-6;
    out.push_back(st);
  }
  return out;
}

std::string profile_table(const std::vector<StageStat>& stats) {
  std::string out;
  char line[160];
  std::snprintf(line, sizeof line, "%-22s %12s %12s %7s\n", "stage", "median ms", "mean ms", "% mean");
  out += line;
  const double total = stats.empty() ? 0 : stats.back().mean_ms;
  for (const StageStat& s : stats) {
    std::snprintf(line, sizeof line, "%-22s %12.4f %12.4f %6.1f%%\n", s.name, s.median_ms, s.mean_ms,
                  total > 0 ? 100.0 * s.mean_ms / total : 0.0);
    out += line;
  }
  return out;
}

std::string profile_json(const std::vector<StageStat>& stats) {
  std::string out = "{";
  char item[160];
  for (size_t i = 0; i < stats.size(); ++i) {
    std::snprintf(item, sizeof item, "%s\"%s\": {\"median_ms\": %.6f, \"mean_ms\": %.6f}", i ? ", " : "",
                  stats[i].name, stats[i].median_ms, stats[i].mean_ms);
    out += item;
  }
  return out + "}";
}

}  // namespace tandem::bench
