// stress_main.cpp — tandem_stress: runs many seeded random worlds
// (tests/stress/stress_world.h) and reports every failure with its seed.
//
//   tandem_stress [--worlds N] [--ticks T] [--first-seed S] [--max-bodies B]
//                 [--no-joints] [--log FILE] [--quiet]
//
// --no-joints turns the joint inputs off (StressConfig::joints), which
// reproduces the worlds of runs before 2026-11-29 seed for seed.
//
// Seeds S, S+1, …, S+N−1. Each world is run with all four broad phases and
// once through a snapshot/restore. A world that fails only with joint inputs
// (known issue 8, stress_world.h) is run again without them and listed as
// KNOWN, not failed. Before a world starts its seed is written
// to the log (flushed), so a crash or a sanitizer report names the seed that
// caused it. Prints a summary: worlds, ticks, steps, failures, faults,
// escapes, bodies, inputs and the wall time. Exit 0 when every world passed,
// 1 when some failed, 2 on bad arguments.
#include <chrono>
#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "tests/stress/stress_world.h"

namespace {

bool parse_u64(const char* text, uint64_t* out) {
  char* end = nullptr;
  const unsigned long long v = std::strtoull(text, &end, 10);
  if (end == text || *end != '\0') return false;
  *out = v;
  return true;
}

int usage(const char* why) {
  std::fprintf(stderr, "tandem_stress: %s\nusage: tandem_stress [--worlds N] [--ticks T] [--first-seed S] "
               "[--max-bodies B] [--no-joints] [--log FILE] [--quiet]\n", why);
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  uint64_t worlds = 100, ticks = 600, first = 1, max_bodies = 48;
  const char* log_path = nullptr;
  bool quiet = false, joints = true;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&](uint64_t* out) {
      if (i + 1 >= argc || !parse_u64(argv[i + 1], out)) return false;
      ++i;
      return true;
    };
    if (a == "--worlds") { if (!value(&worlds)) return usage("--worlds needs a number"); }
    else if (a == "--ticks") { if (!value(&ticks) || ticks == 0 || ticks > 1000000) return usage("--ticks needs 1…1000000"); }
    else if (a == "--first-seed") { if (!value(&first)) return usage("--first-seed needs a number"); }
    else if (a == "--max-bodies") { if (!value(&max_bodies) || max_bodies < 3 || max_bodies > 100000) return usage("--max-bodies needs 3…100000"); }
    else if (a == "--log") { if (i + 1 >= argc) return usage("--log needs a file"); log_path = argv[++i]; }
    else if (a == "--quiet") quiet = true;
    else if (a == "--no-joints") joints = false;
    else if (a == "-h" || a == "--help") {
      std::printf("usage: tandem_stress [--worlds N] [--ticks T] [--first-seed S] [--max-bodies B] [--no-joints] "
                  "[--log FILE] [--quiet]\n(see tests/stress/tools/stress_main.cpp and scripts/stress.sh)\n");
      return 0;
    }
    else return usage(("unknown argument " + a).c_str());
  }
  std::FILE* log = log_path != nullptr ? std::fopen(log_path, "w") : nullptr;
  if (log_path != nullptr && log == nullptr) return usage("cannot open the log file");
  const auto t0 = std::chrono::steady_clock::now();
  uint64_t failed = 0, steps = 0, created = 0, applied = 0, refused = 0, joints_created = 0;
  int64_t faults = 0, escapes = 0;
  uint64_t escape_kinds[4] = {0, 0, 0, 0};
  uint64_t joint_issues = 0;  // worlds with known issue 8 (StressResult::joint_issue)
  for (uint64_t seed = first; seed < first + worlds; ++seed) {
    if (log != nullptr) { std::fprintf(log, "start seed %" PRIu64 "\n", seed); std::fflush(log); }
    tandem::stress::StressConfig c;
    c.seed = seed;
    c.ticks = static_cast<int32_t>(ticks);
    c.max_bodies = static_cast<int32_t>(max_bodies);
    c.joints = joints;
    const tandem::stress::StressResult r = tandem::stress::run_stress_world(c);
    const std::string line = tandem::stress::describe(seed, r);
    if (log != nullptr) { std::fprintf(log, "%s\n", line.c_str()); std::fflush(log); }
    if (!r.ok()) { ++failed; std::printf("FAIL %s\n", line.c_str()); std::fflush(stdout); }
    else if (!quiet || r.escapes != 0 || !r.joint_issue.empty()) {
      std::printf("%s%s\n", r.escapes != 0 || !r.joint_issue.empty() ? "KNOWN " : "", line.c_str());
      std::fflush(stdout);
    }
    if (r.ok() && !r.joint_issue.empty()) ++joint_issues;
    if (r.escapes != 0 && r.joint_issue.empty()) ++escape_kinds[static_cast<int>(r.escape_kind)];
    steps += static_cast<uint64_t>(r.steps);
    created += static_cast<uint64_t>(r.bodies_created);
    applied += static_cast<uint64_t>(r.inputs_applied);
    refused += static_cast<uint64_t>(r.inputs_refused);
    joints_created += static_cast<uint64_t>(r.joints_created);
    faults += r.faults;
    escapes += r.escapes;
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("summary: %" PRIu64 " worlds (seeds %" PRIu64 "-%" PRIu64 ") x %" PRIu64 " ticks, %" PRIu64
              " steps in all runs; %" PRIu64 " failed, %" PRId64 " faults, %" PRId64 " escapes; %" PRIu64
              " bodies created, %" PRIu64 " joints created%s, %" PRIu64 " inputs applied, %" PRIu64
              " refused; %.1f s\n",
              worlds, first, first + worlds - 1, ticks, steps, failed, faults, escapes, created, joints_created,
              joints ? "" : " (joint inputs off)", applied, refused, seconds);
  std::printf("escapes by kind: slow world %" PRIu64 " (failures), fast world %" PRIu64 " (counted), body with chain "
              "segments %" PRIu64 " (counted)\n", escape_kinds[1], escape_kinds[2], escape_kinds[3]);
  std::printf("known issue 8 (a failure only with joint inputs, counted): %" PRIu64 " worlds\n", joint_issues);
  if (log != nullptr) std::fclose(log);
  return failed == 0 ? 0 : 1;
}
