// verify.h — checking a replay against a fresh simulation, and finding where
// two runs part (replay vs replay, replay vs a live run, snapshot vs
// snapshot): the first tick, then the body and the field.
//
// VERIFY runs the recorded inputs again from the initial keyframe (restore,
// then per tick: apply the commands, step, hash) and compares every recorded
// hash and every recorded keyframe. At the first mismatch it reports the
// tick with the expected and actual hashes. The file holds only a hash for
// that tick, not the state, so to name the body and the field verify keeps
// running to the first recorded keyframe at or after the mismatch and diffs
// the recorded state against the recomputed one (decode_world_state +
// diff_world_states): exact when a keyframe was recorded at the mismatch
// tick, otherwise the first difference at that later keyframe (in canonical
// order: world, bodies by index, shapes, contacts). It also restores the
// keyframe before the mismatch in a second world and re-runs to the mismatch
// tick: a different hash there means this machine does not reproduce its own
// run (a determinism bug here), not just a difference from the recording.
//
// DIFF finds the first tick whose state differs. Two replays: compare their
// hash chains (the tick-0 keyframes first); where either lacks hashes, both
// are re-simulated in lockstep and hashed. The states at that tick come from
// a keyframe recorded there or from a re-simulation whose hash matches the
// file's (a re-simulation that does not match its own file cannot stand for
// the recorded run); when neither replay can provide the state at the first
// differing tick, the first later tick where both can is used and the report
// says so. A replay vs a live run: the caller advances its world one tick at
// a time; its state is at hand, so the body and field are exact. Two
// snapshots: decode and diff.
//
// Reports are plain structs plus a text formatter; tools build JSON from
// the fields.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <string>

#include "physics/tandem.h"
#include "replay/replay_file.h"
#include "replay/state.h"

namespace tandem {

/// Called with (ticks done, ticks in total) while a long check runs.
using ProgressCallback = std::function<void(int64_t done, int64_t total)>;

/// The game's own logic after a tick's step, for checking recorded game
/// states (replay format 2): from the game state before `tick` and the world
/// after its step, the game state after it (*after is replaced). A pure
/// function of its arguments, as a session's after_step + save_game are.
using GameStep = std::function<Status(int64_t tick, WorldId world, std::span<const uint8_t> before,
                                      std::vector<uint8_t>* after)>;

/// Options of verify_replay.
struct VerifyOptions {
  PayloadHandler payloads;           ///< turns user payloads into commands; unset: payloads skipped
  GameStep game;                     ///< checks recorded game states (from the tick-0 keyframe's); unset: not checked
  int64_t max_ticks = INT64_MAX;     ///< check at most this many ticks (≥ 0)
  bool locate = true;                ///< on a mismatch, find the body and field (costs a re-run)
  ProgressCallback progress;         ///< optional
};

/// The outcome of verify_replay.
struct VerifyReport {
  Status error;                  ///< not ok: the check could not run (restore or a step refused)
  int64_t ticks_run = 0;         ///< ticks re-simulated
  uint64_t hashes_checked = 0;   ///< recorded tick hashes compared (until the first mismatch)
  uint64_t keyframes_checked = 0;
  uint64_t game_states_recorded = 0;  ///< ticks (run) whose game state the file holds
  uint64_t game_states_checked = 0;   ///< of those, compared with VerifyOptions::game's (until the first mismatch)
  bool game_state_mismatch = false;   ///< the mismatch is in the game state (the world matched)
  uint32_t refused_commands = 0; ///< commands refused while re-running (also refused when recorded)
  uint32_t skipped_payloads = 0; ///< user payloads skipped (no VerifyOptions::payloads handler)
  bool mismatch = false;
  int64_t mismatch_tick = 0;     ///< first tick whose recomputed state differs from the recording
  uint64_t expected_hash = 0;    ///< recorded hash at mismatch_tick (or the keyframe's; XXH3-64 of the game state bytes for a game state mismatch)
  uint64_t actual_hash = 0;      ///< recomputed hash
  bool located = false;          ///< `difference` is meaningful
  int64_t located_tick = 0;      ///< the tick where `difference` was taken (≥ mismatch_tick)
  StateDifference difference;    ///< a = recorded, b = recomputed
  bool self_consistent = true;   ///< re-running from the previous keyframe gave the same hash
  std::string note;              ///< extra explanation (why not located, ...)
  /// True when every check passed.
  bool ok() const { return error.ok() && !mismatch; }
};

/// Verifies a replay (see the file comment).
VerifyReport verify_replay(const Replay& replay, const VerifyOptions& options = {});
/// 0 all matched, 1 mismatch, 2 could not run.
int verify_exit_code(const VerifyReport& report);
/// Human-readable report, several lines, ending with a newline.
std::string format_verify_report(const VerifyReport& report);

/// Where two runs part.
struct DiffReport {
  Status error;                  ///< not ok: the comparison could not run
  bool differs = false;
  std::string method;            ///< "hash chain", "resimulation", "live run", "snapshot"
  int64_t ticks_compared = 0;    ///< ticks whose states were compared
  int64_t tick = 0;              ///< first tick whose states differ (0: the initial states)
  uint64_t hash_a = 0;           ///< state hashes at `tick`
  uint64_t hash_b = 0;
  bool located = false;          ///< `difference` is meaningful
  int64_t located_tick = 0;      ///< tick of the compared states (= tick unless noted)
  StateDifference difference;    ///< first differing record and field (a vs b)
  bool inputs_differ = false;    ///< replays: the recorded inputs differ
  int64_t inputs_differ_tick = 0;   ///< first tick whose commands differ
  bool length_differs = false;   ///< replays: different tick counts (and no state difference before)
  int64_t ticks_a = 0;
  int64_t ticks_b = 0;
  std::string note;
};

/// Options of the diffs.
struct DiffOptions {
  PayloadHandler payloads_a;     ///< payload handlers for each side (unset: skipped)
  PayloadHandler payloads_b;
  ProgressCallback progress;
};

/// The first difference between two replays (see the file comment).
DiffReport diff_replays(const Replay& a, const Replay& b, const DiffOptions& options = {});

/// Advances a live world by one tick: tick is 1-based.
using LiveTick = std::function<Status(int64_t tick)>;

/// The first difference between a replay (a) and a live run (b): `live` is in
/// the state of the replay's tick 0 (or not: then tick 0 differs); `advance`
/// runs one live tick. Compares up to `ticks` ticks (capped at the replay's;
/// a negative count is refused, naming it).
DiffReport diff_replay_live(const Replay& a, WorldId live, const LiveTick& advance, int64_t ticks,
                            const DiffOptions& options = {});

/// The difference between two state images.
DiffReport diff_snapshots(std::span<const uint8_t> a, std::span<const uint8_t> b);

/// 0 identical, 1 different, 2 could not run.
int diff_exit_code(const DiffReport& report);
/// Human-readable report, several lines, ending with a newline.
std::string format_diff_report(const DiffReport& report, const std::string& name_a = "A",
                               const std::string& name_b = "B");

/// "0x%016x".
std::string hash_text(uint64_t hash);

}  // namespace tandem
