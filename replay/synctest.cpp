// synctest.cpp — see synctest.h.
//
// Ring: slot (t mod (K + 1)) holds the state before tick t (= after tick
// t − 1) together with its hash. After the first-pass step of tick t the
// state before t + 1 is saved; then, once K ticks exist, the world is
// restored to the state before t + 1 − K and ticks t + 1 − K … t are stepped
// again, each resimulated state's hash compared with the saved one. The
// world then continues from the resimulated state (equal when it passed).
#include "replay/synctest.h"

#include <string>
#include <vector>

#include "replay/state.h"

namespace tandem {
namespace {

std::string hex64(uint64_t v) {
  static const char digits[] = "0123456789abcdef";
  std::string s = "0x";
  for (int i = 15; i >= 0; --i) s += digits[(v >> (4 * i)) & 0xF];
  return s;
}

}  // namespace

Status run_synctest(WorldId world, const SyncTestOptions& options,
                    const std::function<void(WorldId, int64_t)>& apply_inputs, SyncTestReport* report) {
  *report = SyncTestReport{};
  if (options.ticks < 0 || options.rollback < 1 || options.rollback > 1024) {
    return Status{StatusCode::invalid_argument, "run_synctest: ticks " + std::to_string(options.ticks) +
                                                    " must be ≥ 0 and rollback " + std::to_string(options.rollback) +
                                                    " in [1, 1024]"};
  }
  const size_t ring = static_cast<size_t>(options.rollback) + 1;
  std::vector<std::vector<uint8_t>> snapshots(ring);
  std::vector<uint64_t> hashes(ring, 0);
  const auto slot = [&](int64_t t) { return static_cast<size_t>(t % static_cast<int64_t>(ring)); };

  Status s = encode_world_state(world, &snapshots[0]);
  if (!s.ok()) return Status{s.code, "run_synctest: " + s.message};
  hashes[0] = world_state_hash(world);

  const auto step = [&](int64_t t, const char* pass) -> Status {
    if (apply_inputs) apply_inputs(world, t);
    const StepResult r = world_step(world, options.time_step);
    if (!r.ok()) return Status{r.status.code, "run_synctest: " + std::string(pass) + " tick " + std::to_string(t) +
                                                  ": " + r.status.message};
    return Status{};
  };

  std::vector<uint8_t> resim_state;
  for (int64_t t = 0; t < options.ticks; ++t) {
    s = step(t, "first pass");
    if (!s.ok()) return s;
    s = encode_world_state(world, &snapshots[slot(t + 1)]);
    if (!s.ok()) return s;
    hashes[slot(t + 1)] = world_state_hash(world);
    report->ticks_run = t + 1;

    const int64_t from = t + 1 - options.rollback;
    if (from < 0) continue;
    const std::vector<uint8_t>& base = snapshots[slot(from)];
    s = world_restore(world, base.data(), base.size());
    if (!s.ok()) return Status{s.code, "run_synctest: rollback to tick " + std::to_string(from) + ": " + s.message};
    for (int64_t r = from; r <= t; ++r) {
      s = step(r, "resimulated");
      if (!s.ok()) return s;
      ++report->resimulated_ticks;
      const uint64_t h = world_state_hash(world);
      if (h == hashes[slot(r + 1)]) continue;
      report->first_mismatch_tick = r;
      report->detected_at_tick = t;
      report->expected_hash = hashes[slot(r + 1)];
      report->actual_hash = h;
      const std::vector<uint8_t>& expected = snapshots[slot(r + 1)];
      s = encode_world_state(world, &resim_state);
      if (!s.ok()) return s;
      DecodedState a;
      DecodedState b;
      Status da = decode_world_state(expected.data(), expected.size(), &a);
      Status db = decode_world_state(resim_state.data(), resim_state.size(), &b);
      std::string what;
      if (da.ok() && db.ok()) {
        report->difference = diff_world_states(a, b);
        what = report->difference.describe() + " (a = first pass, b = resimulated)";
      } else {
        what = "could not decode for a diff: " + (da.ok() ? db.message : da.message);
      }
      report->message = "mismatch: tick " + std::to_string(r) + " resimulated after a rollback of " +
                        std::to_string(t - from + 1) + " ticks (at first-pass tick " + std::to_string(t) +
                        ") hashes " + hex64(h) + ", the first pass " + hex64(hashes[slot(r + 1)]) + "; " + what;
      return Status{};
    }
  }
  report->passed = true;
  report->message = "passed: " + std::to_string(report->ticks_run) + " ticks, rollback " +
                    std::to_string(options.rollback) + ", " + std::to_string(report->resimulated_ticks) +
                    " ticks resimulated, every hash matched";
  return Status{};
}

}  // namespace tandem
