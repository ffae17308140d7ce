// synctest.h — a rollback sync test (GGPO's "synctest" idea, written for
// Tandem): every tick, roll the world back K ticks, resimulate them with the
// same inputs, and check that every resimulated state hashes as it did the
// first time. Any state missing from snapshots, any nondeterminism in the
// step or in the input callback shows up as a mismatch at the first tick
// whose step it affects; the report names that tick and, by decoding both
// states and diffing them, the first differing record and field.
//
// Memory: a ring of K + 1 snapshots (vectors reused, so a warm run does not
// allocate for them). Time: about (K + 1) steps per tick.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "physics/tandem.h"
#include "replay/state.h"

namespace tandem {

/// Settings of run_synctest.
struct SyncTestOptions {
  int64_t ticks = 0;        ///< ticks to simulate (first pass), ≥ 0
  int64_t rollback = 8;     ///< K: ticks rolled back and resimulated after each tick, 1…1024
  Q32 time_step = Q32::from_ratio(1, 60);  ///< s, passed to world_step
};

/// What run_synctest found.
struct SyncTestReport {
  bool passed = false;             ///< every resimulated hash matched
  int64_t ticks_run = 0;           ///< first-pass ticks completed
  int64_t resimulated_ticks = 0;   ///< ticks stepped again after rollbacks
  int64_t first_mismatch_tick = -1;  ///< the tick (0-based, first pass numbering) whose step gave a different state
  int64_t detected_at_tick = -1;   ///< the first-pass tick after which the rollback found it
  uint64_t expected_hash = 0;      ///< first-pass state hash after first_mismatch_tick
  uint64_t actual_hash = 0;        ///< resimulated state hash after it
  StateDifference difference;      ///< first differing record and field (expected = a, resimulated = b)
  std::string message;             ///< one line: "passed: ..." or the mismatch with the diff
};

/// Runs the sync test on `world` from its current state for options.ticks
/// ticks. Before each step (first pass and resimulation alike) it calls
/// apply_inputs(world, tick) with the tick number counted from the start of
/// the test; the callback must make the same changes for the same tick. The
/// world ends in the state after the last tick. Returns an error Status for
/// an invalid or locked world, bad options or a failed step (its message
/// names the tick); a mismatch is not an error — it is reported in *report
/// (passed = false) and the test stops there.
Status run_synctest(WorldId world, const SyncTestOptions& options,
                    const std::function<void(WorldId, int64_t)>& apply_inputs, SyncTestReport* report);

}  // namespace tandem
