// verify.cpp — verify_replay and the diffs (verify.h explains the method).
#define XXH_INLINE_ALL
#include <xxhash.h>

#include "replay/verify.h"

#include <algorithm>
#include <cinttypes>
#include <optional>
#include <vector>

namespace tandem {

namespace {

using OwnedWorld = UniqueWorld;

Status fail(const std::string& message) { return Status{StatusCode::invalid_argument, message}; }

// Index of the keyframe recorded exactly at `tick`, if any.
std::optional<size_t> keyframe_index_at(const Replay& r, int64_t tick) {
  for (size_t i = 0; i < r.keyframes.size(); ++i)
    if (r.keyframes[i].tick == tick) return i;
  return std::nullopt;
}

// Decodes both images and diffs them (a vs b). Errors go to *out_error.
bool diff_images(std::span<const uint8_t> a, std::span<const uint8_t> b, StateDifference* out, Status* out_error,
                 const char* name_a, const char* name_b) {
  DecodedState da, db;
  Status s = decode_world_state(a.data(), a.size(), &da);
  if (!s.ok()) {
    *out_error = fail(std::string(name_a) + " state: " + s.message);
    return false;
  }
  s = decode_world_state(b.data(), b.size(), &db);
  if (!s.ok()) {
    *out_error = fail(std::string(name_b) + " state: " + s.message);
    return false;
  }
  *out = diff_world_states(da, db);
  return true;
}

// The recorded run's state after `tick`: a keyframe recorded there, or a
// re-simulation whose hash matches the recorded one (or that has none to
// match). nullopt when the replay cannot stand for its recorded run there.
std::optional<std::vector<uint8_t>> trusted_state_at(const Replay& r, int64_t tick, const PayloadHandler& payloads) {
  if (const auto k = keyframe_index_at(r, tick)) return r.keyframes[*k].state;
  if (tick > r.tick_count()) return std::nullopt;
  Result<WorldId> w = r.create_world_at(tick, payloads);
  if (!w.ok()) return std::nullopt;
  OwnedWorld world(w.value);
  if (tick > 0 && r.tick_record(tick).has_hash && world_state_hash(world.id) != r.tick_record(tick).hash)
    return std::nullopt;
  std::vector<uint8_t> state;
  if (!encode_world_state(world.id, &state).ok()) return std::nullopt;
  return state;
}

// world_state_hash of the world an image restores to (0 if it does not).
uint64_t image_state_hash(const std::vector<uint8_t>& image) {
  Result<WorldId> w = create_world_from_snapshot(image.data(), image.size());
  if (!w.ok()) return 0;
  OwnedWorld world(w.value);
  return world_state_hash(world.id);
}

void report_progress(const ProgressCallback& progress, int64_t done, int64_t total) {
  if (progress && (done % 64 == 0 || done == total)) progress(done, total);
}

}  // namespace

std::string hash_text(uint64_t hash) {
  char buf[24];
  std::snprintf(buf, sizeof buf, "0x%016" PRIx64, hash);
  return buf;
}

// --- verify -------------------------------------------------------------------

namespace {

// The index of the first differing byte (the shorter size when one is a prefix).
size_t first_difference(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
  const size_t n = std::min(a.size(), b.size());
  for (size_t i = 0; i < n; ++i)
    if (a[i] != b[i]) return i;
  return n;
}

}  // namespace

VerifyReport verify_replay(const Replay& replay, const VerifyOptions& options) {
  VerifyReport rep;
  if (options.max_ticks < 0) {
    rep.error = fail("verify: max_ticks " + std::to_string(options.max_ticks) + " is negative");
    return rep;
  }
  if (replay.keyframes.empty()) {
    rep.error = fail("verify: the replay has no initial keyframe");
    return rep;
  }
  const Keyframe& k0 = replay.keyframes[0];
  Result<WorldId> created = create_world_from_snapshot(k0.state.data(), k0.state.size());
  if (!created.ok()) {
    rep.error = fail("verify: initial keyframe: " + created.status.message);
    return rep;
  }
  OwnedWorld world(created.value);
  const Q32 dt = replay.header.time_step;

  // The restored initial state must encode to the recorded image.
  {
    std::vector<uint8_t> now;
    Status s = encode_world_state(world.id, &now);
    if (!s.ok()) {
      rep.error = fail("verify: " + s.message);
      return rep;
    }
    if (now != k0.state) {
      rep.mismatch = true;
      rep.mismatch_tick = 0;
      rep.expected_hash = k0.hash;
      rep.actual_hash = XXH3_64bits(now.data(), now.size());
      if (diff_images(k0.state, now, &rep.difference, &rep.error, "recorded", "recomputed")) {
        rep.located = true;
        rep.located_tick = 0;
      }
      return rep;
    }
    rep.keyframes_checked = 1;
  }

  const int64_t n = std::min<int64_t>(replay.tick_count(), options.max_ticks);
  size_t next_key = 1;
  uint64_t hash_after_mismatch = 0;
  // The game state, recomputed tick by tick from the tick-0 keyframe's.
  std::vector<uint8_t> game = k0.game_state, game_next;
  for (int64_t t = 1; t <= n; ++t) {
    const TickRecord& rec = replay.tick_record(t);
    Status s = run_tick(world.id, rec, dt, options.payloads, &rep.refused_commands, &rep.skipped_payloads);
    if (!s.ok()) {
      rep.error = fail("verify: " + s.message);
      return rep;
    }
    rep.ticks_run = t;
    if (rec.has_game_state) ++rep.game_states_recorded;
    if (options.game) {
      game_next.clear();
      s = options.game(t, world.id, game, &game_next);
      if (!s.ok()) {
        rep.error = fail("verify: tick " + std::to_string(t) + ": game logic: " + s.message);
        return rep;
      }
      game.swap(game_next);
    }
    while (next_key < replay.keyframes.size() && replay.keyframes[next_key].tick < t) ++next_key;
    const Keyframe* key =
        next_key < replay.keyframes.size() && replay.keyframes[next_key].tick == t ? &replay.keyframes[next_key] : nullptr;
    if (!rec.has_hash && key == nullptr) {
      report_progress(options.progress, t, n);
      continue;
    }
    const uint64_t h = world_state_hash(world.id);
    if (key != nullptr) {
      // Keyframes are compared byte for byte (their stored hash is of the image).
      std::vector<uint8_t> now;
      Status es = encode_world_state(world.id, &now);
      if (!es.ok()) {
        rep.error = fail("verify: tick " + std::to_string(t) + ": " + es.message);
        return rep;
      }
      if (now != key->state) {
        rep.mismatch = true;
        rep.mismatch_tick = t;
        rep.expected_hash = rec.has_hash ? rec.hash : key->hash;
        rep.actual_hash = rec.has_hash ? h : XXH3_64bits(now.data(), now.size());
        hash_after_mismatch = h;
        break;
      }
      ++rep.keyframes_checked;
    }
    if (rec.has_hash) {
      if (rec.hash != h) {
        rep.mismatch = true;
        rep.mismatch_tick = t;
        rep.expected_hash = rec.hash;
        rep.actual_hash = h;
        hash_after_mismatch = h;
        break;
      }
      ++rep.hashes_checked;
    }
    if (options.game && rec.has_game_state) {
      if (game != rec.game_state) {
        rep.mismatch = true;
        rep.game_state_mismatch = true;
        rep.mismatch_tick = t;
        rep.expected_hash = XXH3_64bits(rec.game_state.data(), rec.game_state.size());
        rep.actual_hash = XXH3_64bits(game.data(), game.size());
        rep.note = "the world matches; the game state after tick " + std::to_string(t) + " (" +
                   std::to_string(rec.game_state.size()) + " bytes recorded, " + std::to_string(game.size()) +
                   " recomputed) differs from the first byte " + std::to_string(first_difference(rec.game_state, game));
        break;
      }
      ++rep.game_states_checked;
    }
    report_progress(options.progress, t, n);
  }
  if (!rep.mismatch || !options.locate || rep.game_state_mismatch) return rep;

  const int64_t t = rep.mismatch_tick;
  // Does this machine reproduce its own run from the previous keyframe?
  {
    const Keyframe& prev = replay.keyframe_at_or_before(t - 1);
    Result<WorldId> w2 = create_world_from_snapshot(prev.state.data(), prev.state.size());
    if (w2.ok()) {
      OwnedWorld second(w2.value);
      bool ran = true;
      for (int64_t u = prev.tick + 1; u <= t && ran; ++u)
        ran = run_tick(second.id, replay.tick_record(u), dt, options.payloads).ok();
      if (ran && world_state_hash(second.id) != hash_after_mismatch) {
        rep.self_consistent = false;
        rep.note += "re-running from the keyframe at tick " + std::to_string(prev.tick) + " gives yet another hash at tick " +
                    std::to_string(t) + ": this build does not reproduce its own run (determinism bug). ";
      }
    }
  }
  // The first recorded keyframe at or after the mismatch.
  const Keyframe* target = nullptr;
  for (const Keyframe& k : replay.keyframes)
    if (k.tick >= t) {
      target = &k;
      break;
    }
  if (target == nullptr) {
    rep.note += "no keyframe recorded at or after tick " + std::to_string(t) +
                ", so the differing body and field cannot be named (record with a smaller keyframe interval)";
    return rep;
  }
  for (int64_t u = t + 1; u <= target->tick; ++u) {
    Status s = run_tick(world.id, replay.tick_record(u), dt, options.payloads);
    if (!s.ok()) {
      rep.note += "could not re-run to the keyframe at tick " + std::to_string(target->tick) + ": " + s.message;
      return rep;
    }
  }
  std::vector<uint8_t> now;
  Status s = encode_world_state(world.id, &now);
  Status diff_error;
  if (s.ok() && diff_images(target->state, now, &rep.difference, &diff_error, "recorded", "recomputed")) {
    rep.located = true;
    rep.located_tick = target->tick;
    if (target->tick != t)
      rep.note += "no keyframe at tick " + std::to_string(t) + "; the states were compared at the next keyframe, tick " +
                  std::to_string(target->tick);
  } else {
    rep.note += "could not compare states: " + (s.ok() ? diff_error.message : s.message);
  }
  return rep;
}

int verify_exit_code(const VerifyReport& report) {
  if (!report.error.ok()) return 2;
  return report.mismatch ? 1 : 0;
}

std::string format_verify_report(const VerifyReport& r) {
  std::string s;
  if (!r.error.ok()) {
    s += "error: " + r.error.message + "\n";
    s += "ran " + std::to_string(r.ticks_run) + " ticks before the error\n";
    return s;
  }
  s += "ticks re-simulated: " + std::to_string(r.ticks_run) + ", tick hashes checked: " +
       std::to_string(r.hashes_checked) + ", keyframes checked: " + std::to_string(r.keyframes_checked) + "\n";
  if (r.game_states_checked != 0 || r.game_state_mismatch)
    s += "game states checked: " + std::to_string(r.game_states_checked) + "\n";
  else if (r.game_states_recorded != 0)
    s += "game states recorded: " + std::to_string(r.game_states_recorded) +
         " (not checked: the game's logic is not known here)\n";
  if (r.refused_commands != 0)
    s += "commands refused (as when recorded): " + std::to_string(r.refused_commands) + "\n";
  if (r.skipped_payloads != 0)
    s += "user input payloads skipped (no handler to turn them into commands): " +
         std::to_string(r.skipped_payloads) + "\n";
  if (!r.mismatch) {
    s += "OK: every recorded hash matches\n";
    return s;
  }
  s += "MISMATCH at tick " + std::to_string(r.mismatch_tick) + ": recorded " + hash_text(r.expected_hash) +
       ", recomputed " + hash_text(r.actual_hash) + "\n";
  if (r.located)
    s += "first difference (tick " + std::to_string(r.located_tick) + ", a = recorded, b = recomputed): " +
         r.difference.describe() + "\n";
  if (!r.note.empty()) s += "note: " + r.note + "\n";
  return s;
}

// --- diffs --------------------------------------------------------------------

namespace {

void locate_between_replays(const Replay& a, const Replay& b, int64_t tick, const DiffOptions& o, DiffReport* rep) {
  std::vector<int64_t> candidates{tick};
  const int64_t n = std::min(a.tick_count(), b.tick_count());
  for (const Replay* r : {&a, &b})
    for (const Keyframe& k : r->keyframes)
      if (k.tick > tick && k.tick <= n) candidates.push_back(k.tick);
  std::sort(candidates.begin(), candidates.end());
  candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
  for (int64_t k : candidates) {
    const auto sa = trusted_state_at(a, k, o.payloads_a);
    if (!sa) continue;
    const auto sb = trusted_state_at(b, k, o.payloads_b);
    if (!sb) continue;
    Status err;
    if (!diff_images(*sa, *sb, &rep->difference, &err, "A", "B")) {
      rep->note += err.message + ". ";
      return;
    }
    rep->located = true;
    rep->located_tick = k;
    if (k != tick)
      rep->note += "the state at tick " + std::to_string(tick) +
                   " could not be rebuilt for both runs (a re-simulation does not match its own recorded hash); "
                   "compared at tick " + std::to_string(k) + " instead. ";
    return;
  }
  rep->note += "neither a keyframe nor a matching re-simulation gives both states at or after tick " +
               std::to_string(tick) + "; the body and field cannot be named. ";
}

void compare_inputs(const Replay& a, const Replay& b, DiffReport* rep) {
  const int64_t n = std::min(a.tick_count(), b.tick_count());
  for (int64_t t = 1; t <= n; ++t) {
    const auto& ca = a.tick_record(t).commands;
    const auto& cb = b.tick_record(t).commands;
    bool same = ca.size() == cb.size();
    for (size_t i = 0; same && i < ca.size(); ++i) same = ca[i] == cb[i];
    if (!same) {
      rep->inputs_differ = true;
      rep->inputs_differ_tick = t;
      return;
    }
  }
}

}  // namespace

DiffReport diff_replays(const Replay& a, const Replay& b, const DiffOptions& o) {
  DiffReport rep;
  rep.ticks_a = a.tick_count();
  rep.ticks_b = b.tick_count();
  if (a.keyframes.empty() || b.keyframes.empty()) {
    rep.error = fail(std::string("diff: replay ") + (a.keyframes.empty() ? "A" : "B") + " has no initial keyframe");
    return rep;
  }
  compare_inputs(a, b, &rep);
  if (a.header.time_step != b.header.time_step)
    rep.note += "the replays use different time steps (" + q32_raw_text(a.header.time_step.raw) + " s and " +
                q32_raw_text(b.header.time_step.raw) + " s). ";
  // Tick 0: the initial states, by world_state_hash (as the tick hashes).
  const uint64_t h0a = image_state_hash(a.keyframes[0].state), h0b = image_state_hash(b.keyframes[0].state);
  if (h0a != h0b) {
    rep.differs = true;
    rep.method = "hash chain";
    rep.tick = 0;
    rep.hash_a = h0a;
    rep.hash_b = h0b;
    Status err;
    if (diff_images(a.keyframes[0].state, b.keyframes[0].state, &rep.difference, &err, "A", "B")) {
      rep.located = true;
      rep.located_tick = 0;
    } else {
      rep.error = err;
    }
    return rep;
  }
  const int64_t n = std::min(a.tick_count(), b.tick_count());
  bool all_hashes = true;
  for (int64_t t = 1; t <= n && all_hashes; ++t) all_hashes = a.tick_record(t).has_hash && b.tick_record(t).has_hash;
  if (all_hashes) {
    rep.method = "hash chain";
    for (int64_t t = 1; t <= n; ++t) {
      rep.ticks_compared = t;
      if (a.tick_record(t).hash != b.tick_record(t).hash) {
        rep.differs = true;
        rep.tick = t;
        rep.hash_a = a.tick_record(t).hash;
        rep.hash_b = b.tick_record(t).hash;
        locate_between_replays(a, b, t, o, &rep);
        return rep;
      }
    }
  } else {
    rep.method = "resimulation";
    Result<WorldId> wa = create_world_from_snapshot(a.keyframes[0].state.data(), a.keyframes[0].state.size());
    if (!wa.ok()) {
      rep.error = fail("diff: A: initial keyframe: " + wa.status.message);
      return rep;
    }
    OwnedWorld world_a(wa.value);
    Result<WorldId> wb = create_world_from_snapshot(b.keyframes[0].state.data(), b.keyframes[0].state.size());
    if (!wb.ok()) {
      rep.error = fail("diff: B: initial keyframe: " + wb.status.message);
      return rep;
    }
    OwnedWorld world_b(wb.value);
    for (int64_t t = 1; t <= n; ++t) {
      Status s = run_tick(world_a.id, a.tick_record(t), a.header.time_step, o.payloads_a);
      if (!s.ok()) {
        rep.error = fail("diff: A: " + s.message);
        return rep;
      }
      s = run_tick(world_b.id, b.tick_record(t), b.header.time_step, o.payloads_b);
      if (!s.ok()) {
        rep.error = fail("diff: B: " + s.message);
        return rep;
      }
      rep.ticks_compared = t;
      const uint64_t ha = world_state_hash(world_a.id), hb = world_state_hash(world_b.id);
      if (ha != hb) {
        rep.differs = true;
        rep.tick = t;
        rep.hash_a = ha;
        rep.hash_b = hb;
        std::vector<uint8_t> sa, sb;
        Status err;
        if (encode_world_state(world_a.id, &sa).ok() && encode_world_state(world_b.id, &sb).ok() &&
            diff_images(sa, sb, &rep.difference, &err, "A", "B")) {
          rep.located = true;
          rep.located_tick = t;
        }
        return rep;
      }
      report_progress(o.progress, t, n);
    }
  }
  if (a.tick_count() != b.tick_count()) {
    rep.differs = true;
    rep.length_differs = true;
    rep.tick = n + 1;
    rep.note += "the states agree for the " + std::to_string(n) + " ticks both hold; A has " +
                std::to_string(a.tick_count()) + " ticks, B " + std::to_string(b.tick_count()) + ". ";
  }
  return rep;
}

DiffReport diff_replay_live(const Replay& a, WorldId live, const LiveTick& advance, int64_t ticks,
                            const DiffOptions& o) {
  DiffReport rep;
  rep.method = "live run";
  rep.ticks_a = a.tick_count();
  if (ticks < 0) {
    rep.error = fail("diff: tick count " + std::to_string(ticks) + " is negative");
    return rep;
  }
  if (a.keyframes.empty()) {
    rep.error = fail("diff: the replay has no initial keyframe");
    return rep;
  }
  Result<WorldId> wa = create_world_from_snapshot(a.keyframes[0].state.data(), a.keyframes[0].state.size());
  if (!wa.ok()) {
    rep.error = fail("diff: replay: initial keyframe: " + wa.status.message);
    return rep;
  }
  OwnedWorld world_a(wa.value);
  const int64_t n = std::min(ticks, a.tick_count());
  for (int64_t t = 0; t <= n; ++t) {
    if (t > 0) {
      Status s = run_tick(world_a.id, a.tick_record(t), a.header.time_step, o.payloads_a);
      if (!s.ok()) {
        rep.error = fail("diff: replay: " + s.message);
        return rep;
      }
      s = advance(t);
      if (!s.ok()) {
        rep.error = fail("diff: live run: tick " + std::to_string(t) + ": " + s.message);
        return rep;
      }
      rep.ticks_compared = t;
    }
    const uint64_t ha = world_state_hash(world_a.id), hb = world_state_hash(live);
    if (t > 0 && a.tick_record(t).has_hash && a.tick_record(t).hash != ha)
      rep.note += "the replay does not verify at tick " + std::to_string(t) +
                  " (its re-simulation is compared, not the recorded run). ";
    if (ha != hb) {
      rep.differs = true;
      rep.tick = t;
      rep.hash_a = ha;
      rep.hash_b = hb;
      std::vector<uint8_t> sa, sb;
      Status err;
      Status ea = encode_world_state(world_a.id, &sa), eb = encode_world_state(live, &sb);
      if (!eb.ok()) {
        rep.error = fail("diff: live run: " + eb.message);
        return rep;
      }
      if (ea.ok() && diff_images(sa, sb, &rep.difference, &err, "replay", "live")) {
        rep.located = true;
        rep.located_tick = t;
      }
      return rep;
    }
    report_progress(o.progress, t, n);
  }
  return rep;
}

DiffReport diff_snapshots(std::span<const uint8_t> a, std::span<const uint8_t> b) {
  DiffReport rep;
  rep.method = "snapshot";
  rep.hash_a = XXH3_64bits(a.data(), a.size());
  rep.hash_b = XXH3_64bits(b.data(), b.size());
  Status err;
  if (!diff_images(a, b, &rep.difference, &err, "A", "B")) {
    rep.error = err;
    return rep;
  }
  rep.ticks_compared = 1;
  rep.differs = rep.difference.differs;
  rep.located = rep.differs;
  return rep;
}

int diff_exit_code(const DiffReport& report) {
  if (!report.error.ok()) return 2;
  return report.differs ? 1 : 0;
}

std::string format_diff_report(const DiffReport& r, const std::string& name_a, const std::string& name_b) {
  std::string s;
  if (!r.error.ok()) return "error: " + r.error.message + "\n";
  s += "A = " + name_a + "\nB = " + name_b + "\n";
  s += "method: " + r.method + ", ticks compared: " + std::to_string(r.ticks_compared) + "\n";
  if (r.inputs_differ) s += "recorded inputs first differ at tick " + std::to_string(r.inputs_differ_tick) + "\n";
  if (!r.differs) {
    s += "IDENTICAL\n";
  } else if (r.length_differs) {
    s += "DIFFERENT LENGTHS: A has " + std::to_string(r.ticks_a) + " ticks, B has " + std::to_string(r.ticks_b) + "\n";
  } else {
    if (r.method == "snapshot")
      s += "DIFFERENT: state hashes " + hash_text(r.hash_a) + " vs " + hash_text(r.hash_b) + "\n";
    else
      s += "DIFFERENT from tick " + std::to_string(r.tick) + ": hashes " + hash_text(r.hash_a) + " vs " +
           hash_text(r.hash_b) + "\n";
    if (r.located) {
      if (r.method != "snapshot") s += "at tick " + std::to_string(r.located_tick) + ": ";
      s += r.difference.describe() + "\n";
    }
  }
  if (!r.note.empty()) s += "note: " + r.note + "\n";
  return s;
}

}  // namespace tandem
