// cmd_replay.cpp — `tandem record`, `replay`, `verify`, `diff` and
// `synctest`: replay files (replay/replay_file.h), their verification and
// diffs (replay/verify.h) and the rollback sync test (replay/synctest.h).
// See cli.h for the exit codes.
//
// Tick convention (as `tandem run`): a scene's inputs for its tick T are
// applied just before step T + 1, so they are recorded in the replay's tick
// T + 1 record. The recording starts from the built scene: its initial
// keyframe is the world after build_world(), and the scene text is embedded
// for reference (the replay needs no scene loader to play).
//
// Output: results on stdout (text, or one JSON object with --json); errors
// on stderr, naming the file and the byte offset; warnings (a truncated
// replay) on stderr. The progress bar appears on stderr only when stderr is
// a terminal, the job has run for more than a second, and neither --quiet
// nor --json is given. `verify` takes many files and --jobs N (see below).
#define XXH_INLINE_ALL
#include <xxhash.h>

#include <nlohmann/json.hpp>

#include <chrono>
#include <cinttypes>
#include <cstdio>
#include <algorithm>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "cli.h"
#include "cli_util.h"
#include "replay/commands.h"
#include "replay/replay_file.h"
#include "replay/state.h"
#include "replay/synctest.h"
#include "replay/verify.h"
#include "scene/scene.h"
#include "tools/net/arena_game.h"

namespace tandem::cli {
namespace {

using Clock = std::chrono::steady_clock;
using Json = nlohmann::ordered_json;

// Reads a replay file; prints the error (exit 2) or the truncation warning.
int load_replay(const char* command, const std::string& path, Replay* out, ReplayReadInfo* info) {
  const Status s = read_replay_file(path, out, info);
  if (!s.ok()) return fail(command, s.message);
  if (!info->warning.empty()) std::fprintf(stderr, "tandem %s: warning: %s\n", command, info->warning.c_str());
  return 0;
}

// A loaded and built scene (prints its errors).
struct LoadedScene {
  scene::Scene scene;
  scene::BuiltScene built;
  std::vector<uint8_t> text;
  ~LoadedScene() {
    if (world_is_valid(built.world)) (void)destroy_world(built.world);
  }
};

int load_scene(const char* command, const std::string& path, const scene::SceneLimits& limits, LoadedScene* out) {
  Status s = read_file_bytes(path, &out->text);
  if (!s.ok()) return fail(command, s.message);
  Result<scene::Scene> loaded =
      scene::load_scene_text(std::string_view(reinterpret_cast<const char*>(out->text.data()), out->text.size()), path, limits);
  if (!loaded.ok()) return fail(command, loaded.status.message);
  out->scene = std::move(loaded.value);
  Result<scene::BuiltScene> built = scene::build_world(out->scene);
  if (!built.ok()) return fail(command, built.status.message);
  out->built = std::move(built.value);
  return 0;
}

Json difference_json(const StateDifference& d) {
  Json j;
  j["record"] = d.kind;
  j["index"] = d.index;
  if (d.index2 >= 0) j["index2"] = d.index2;
  if (d.generation != 0) j["generation"] = d.generation;
  if (d.missing_in_a || d.missing_in_b) {
    j["only_in"] = d.missing_in_a ? "b" : "a";
    return j;
  }
  j["field"] = d.field;
  j["a"] = {{"raw", d.value_a}};
  j["b"] = {{"raw", d.value_b}};
  if (d.is_q32) {
    j["a"]["value"] = q32_raw_text(d.value_a);
    j["b"]["value"] = q32_raw_text(d.value_b);
  }
  j["text"] = d.describe();
  return j;
}

// --- record -------------------------------------------------------------------
struct RecordArgs {
  std::string scene;
  std::string out;
  int64_t ticks = -1;
  uint32_t keyframe_every = 600;
  uint32_t flush_every = 1;
  bool no_hash = false;
  bool no_embed = false;
  bool json = false, quiet = false;
};

int run_record(const RecordArgs& a, const GlobalOptions& g) {
  const bool json = a.json || g.json, quiet = a.quiet || g.quiet;
  LoadedScene s;
  if (int rc = load_scene("record", a.scene, g.scene_limits, &s)) return rc;
  const int64_t ticks = a.ticks >= 0 ? a.ticks : s.scene.ticks;
  RecorderOptions options;
  options.keyframe_interval = a.keyframe_every;
  options.record_hashes = !a.no_hash;
  options.flush_every = a.flush_every;
  options.time_step = s.scene.time_step;
  ReplayRecorder recorder;
  Status st = recorder.open_file(a.out, options);
  if (!st.ok()) return fail("record", st.message);
  st = recorder.begin(s.built.world, s.text, XXH3_64bits(s.text.data(), s.text.size()), !a.no_embed);
  if (!st.ok()) return fail("record", st.message);
  ProgressBar progress("record", quiet || json);
  for (int64_t t = 0; t < ticks; ++t) {
    for (const tandem::Command& c : scene::scene_inputs_at(s.built, s.scene, t)) {
      st = recorder.submit(c);
      if (!st.ok())
        return fail("record", a.scene + ": scripted input before step " + std::to_string(t + 1) + " refused: " + st.message);
    }
    const StepResult r = recorder.step();
    if (!r.ok()) return fail("record", a.scene + ": step " + std::to_string(t + 1) + ": " + r.status.message);
    progress.update(static_cast<uint64_t>(t + 1), static_cast<uint64_t>(ticks));
  }
  progress.finish();
  st = recorder.finish();
  if (!st.ok()) return fail("record", st.message);
  const uint64_t final_hash = world_state_hash(s.built.world);
  std::vector<uint8_t> written;
  (void)read_file_bytes(a.out, &written);
  if (json) {
    Json j;
    j["replay"] = a.out;
    j["scene"] = a.scene;
    j["ticks"] = ticks;
    j["bytes"] = written.size();
    j["keyframe_every"] = a.keyframe_every;
    j["tick_hashes"] = !a.no_hash;
    j["final_hash"] = hash_text(final_hash);
    std::printf("%s\n", j.dump().c_str());
    return 0;
  }
  if (!quiet)
    std::printf("recorded %s: %" PRId64 " ticks of %s, %zu bytes, keyframe every %u ticks%s\n", a.out.c_str(), ticks,
                a.scene.c_str(), written.size(), a.keyframe_every, a.no_hash ? ", no tick hashes" : "");
  std::printf("final tick %" PRId64 "  hash %s\n", ticks, hash_text(final_hash).c_str());
  return 0;
}

// --- replay -------------------------------------------------------------------
struct ReplayArgs {
  std::string file;
  int64_t ticks = -1;
  std::string save_state;
  bool json = false, quiet = false;
};

int run_replay(const ReplayArgs& a, const GlobalOptions& g) {
  const bool json = a.json || g.json, quiet = a.quiet || g.quiet;
  Replay replay;
  ReplayReadInfo info;
  if (int rc = load_replay("replay", a.file, &replay, &info)) return rc;
  const int64_t ticks = a.ticks >= 0 ? a.ticks : replay.tick_count();
  if (ticks > replay.tick_count())
    return fail("replay", a.file + ": --ticks " + std::to_string(ticks) + " is past the last recorded tick " +
                              std::to_string(replay.tick_count()));
  Result<WorldId> created = create_world_from_snapshot(replay.keyframes[0].state.data(), replay.keyframes[0].state.size());
  if (!created.ok()) return fail("replay", a.file + ": initial keyframe: " + created.status.message);
  OwnedWorld world{created.value};
  ProgressBar progress("replay", quiet || json);
  uint32_t refused = 0, skipped = 0;
  for (int64_t t = 1; t <= ticks; ++t) {
    const Status s = run_tick(world.id, replay.tick_record(t), replay.header.time_step, {}, &refused, &skipped);
    if (!s.ok()) return fail("replay", a.file + ": " + s.message);
    progress.update(static_cast<uint64_t>(t), static_cast<uint64_t>(ticks));
  }
  progress.finish();
  const uint64_t hash = world_state_hash(world.id);
  // Tick 0 has no recorded world_state_hash (the keyframe stores its image's hash).
  const bool has_recorded = ticks > 0 && replay.tick_record(ticks).has_hash;
  const uint64_t recorded = has_recorded ? replay.tick_record(ticks).hash : 0;
  if (!a.save_state.empty()) {
    std::vector<uint8_t> state;
    Status s = encode_world_state(world.id, &state);
    std::FILE* f = s.ok() ? std::fopen(a.save_state.c_str(), "wb") : nullptr;
    if (f == nullptr) return fail("replay", a.save_state + ": cannot write the state" + (s.ok() ? "" : ": " + s.message));
    const bool ok = std::fwrite(state.data(), 1, state.size(), f) == state.size();
    if (std::fclose(f) != 0 || !ok) return fail("replay", a.save_state + ": write failed");
  }
  if (json) {
    Json j;
    j["replay"] = a.file;
    j["ticks"] = ticks;
    j["recorded_ticks"] = replay.tick_count();
    j["truncated"] = info.truncated;
    j["final_hash"] = hash_text(hash);
    if (has_recorded) j["recorded_hash"] = hash_text(recorded);
    j["refused_commands"] = refused;
    j["skipped_payloads"] = skipped;
    std::printf("%s\n", j.dump().c_str());
    return 0;
  }
  if (!quiet) {
    std::printf("replay %s: %" PRId64 " of %" PRId64 " recorded ticks, %zu keyframes, time step %s s\n", a.file.c_str(),
                ticks, replay.tick_count(), replay.keyframes.size(), q32_raw_text(replay.header.time_step.raw).c_str());
    if (has_recorded)
      std::printf("recorded hash at tick %" PRId64 ": %s (%s)\n", ticks, hash_text(recorded).c_str(),
                  recorded == hash ? "matches" : "DIFFERS: run tandem verify");
    if (refused != 0) std::printf("commands refused (as when recorded): %u\n", refused);
    if (skipped != 0) std::printf("user input payloads skipped (the game's meaning is unknown here): %u\n", skipped);
    if (!a.save_state.empty()) std::printf("state written to %s\n", a.save_state.c_str());
  }
  std::printf("final tick %" PRId64 "  hash %s\n", ticks, hash_text(hash).c_str());
  return 0;
}

// --- verify -------------------------------------------------------------------
// One file: the report as before (text, --quiet line, or one JSON object);
// an unreadable file is an error on stderr, exit 2. Several files (or
// --jobs): `jobs` threads take the files in turn, each verified alone; the
// verdicts are printed in the order of the arguments as soon as every
// earlier file is done (one JSON object per file and line with --json; one
// text line per file otherwise, then a summary), and the exit code is 2 if
// any file could not be read or run, else 1 if any mismatched, else 0.
struct VerifyArgs {
  std::vector<std::string> files;
  uint32_t jobs = 0;
  bool jobs_given = false;
  bool json = false, quiet = false;
};

// The verdict on one file.
struct FileVerdict {
  std::string file;
  int rc = 0;              // 0 ok, 1 mismatch, 2 error
  std::string error;       // rc 2: why
  std::string warning;     // a truncated file
  bool truncated = false;
  VerifyReport report;
};

FileVerdict verify_file(const std::string& path, const ProgressCallback& progress) {
  FileVerdict v;
  v.file = path;
  Replay replay;
  ReplayReadInfo info;
  const Status s = read_replay_file(path, &replay, &info);
  if (!s.ok()) {
    v.rc = 2;
    v.error = s.message;
    return v;
  }
  v.warning = info.warning;
  v.truncated = info.truncated;
  VerifyOptions options;
  options.progress = progress;
  // A session recording of the bundled arena: its scores are checked too.
  uint32_t players = 0, first_disc = 0;
  if (replay.header.has_scene_bytes && arena::parse_replay_scene(replay.header.scene_bytes, &players, &first_disc)) {
    const Status g = arena::verify_game_step(players, first_disc, &options.game);
    if (!g.ok()) {
      v.rc = 2;
      v.error = path + ": arena game logic: " + g.message;
      return v;
    }
  }
  v.report = verify_replay(replay, options);
  v.rc = verify_exit_code(v.report);
  if (v.rc == 2) v.error = path + ": " + v.report.error.message;
  return v;
}

Json verdict_json(const FileVerdict& v) {
  Json j;
  j["replay"] = v.file;
  const VerifyReport& rep = v.report;
  if (v.rc == 2) {
    j["result"] = "error";
    j["error"] = v.error;
    return j;
  }
  j["result"] = rep.mismatch ? "mismatch" : "ok";
  j["truncated"] = v.truncated;
  j["ticks_run"] = rep.ticks_run;
  j["hashes_checked"] = rep.hashes_checked;
  j["keyframes_checked"] = rep.keyframes_checked;
  j["game_states_recorded"] = rep.game_states_recorded;
  j["game_states_checked"] = rep.game_states_checked;
  j["refused_commands"] = rep.refused_commands;
  j["skipped_payloads"] = rep.skipped_payloads;
  if (rep.mismatch) {
    j["mismatch_tick"] = rep.mismatch_tick;
    j["expected_hash"] = hash_text(rep.expected_hash);
    j["actual_hash"] = hash_text(rep.actual_hash);
    j["self_consistent"] = rep.self_consistent;
    if (rep.game_state_mismatch) j["game_state_mismatch"] = true;
    if (rep.located) {
      j["located_tick"] = rep.located_tick;
      j["difference"] = difference_json(rep.difference);
    }
    if (!rep.note.empty()) j["note"] = rep.note;
  }
  return j;
}

// One text line of the batch output.
std::string verdict_line(const FileVerdict& v) {
  const VerifyReport& rep = v.report;
  char buf[160];
  if (v.rc == 2) return "ERROR     " + v.error;  // the message names the file
  if (!rep.mismatch) {
    std::snprintf(buf, sizeof buf, ": %" PRId64 " ticks, %" PRIu64 " hashes, %" PRIu64 " keyframes", rep.ticks_run,
                  rep.hashes_checked, rep.keyframes_checked);
    return "OK        " + v.file + buf + (v.truncated ? " (truncated file)" : "");
  }
  std::snprintf(buf, sizeof buf, ": tick %" PRId64 ", expected %s, got %s", rep.mismatch_tick,
                hash_text(rep.expected_hash).c_str(), hash_text(rep.actual_hash).c_str());
  std::string line = "MISMATCH  " + v.file + buf;
  if (rep.located) line += "; at tick " + std::to_string(rep.located_tick) + ": " + rep.difference.describe();
  return line;
}

int run_verify_one(const std::string& file, bool json, bool quiet) {
  ProgressBar progress("verify", quiet || json);
  const FileVerdict v =
      verify_file(file, [&progress](int64_t done, int64_t total) { progress.update(static_cast<uint64_t>(done), static_cast<uint64_t>(total)); });
  progress.finish();
  if (v.rc == 2) return fail("verify", v.error);
  if (!v.warning.empty()) std::fprintf(stderr, "tandem verify: warning: %s\n", v.warning.c_str());
  const VerifyReport& rep = v.report;
  if (json) {
    std::printf("%s\n", verdict_json(v).dump().c_str());
    return v.rc;
  }
  if (quiet) {
    if (rep.mismatch)
      std::printf("MISMATCH at tick %" PRId64 "\n", rep.mismatch_tick);
    else
      std::printf("OK %" PRId64 " ticks\n", rep.ticks_run);
    return v.rc;
  }
  std::printf("verify %s\n%s", file.c_str(), format_verify_report(rep).c_str());
  return v.rc;
}

int run_verify_batch(const VerifyArgs& a, bool json, bool quiet) {
  const size_t n = a.files.size();
  uint32_t jobs = !a.jobs_given ? 1 : a.jobs != 0 ? a.jobs : std::max(1u, std::thread::hardware_concurrency());
  if (jobs > n) jobs = static_cast<uint32_t>(n);
  std::vector<FileVerdict> verdicts(n);
  std::vector<uint8_t> done(n, 0);
  std::mutex mutex;
  size_t next = 0, printed = 0, finished = 0;
  uint32_t ok = 0, mismatched = 0, errors = 0;
  ProgressBar progress("verify", quiet || json, "file");
  // Prints every verdict whose predecessors are printed (mutex held).
  auto flush = [&] {
    while (printed < n && done[printed] != 0) {
      const FileVerdict& v = verdicts[printed];
      progress.finish();
      if (!v.warning.empty()) std::fprintf(stderr, "tandem verify: warning: %s\n", v.warning.c_str());
      if (json)
        std::printf("%s\n", verdict_json(v).dump().c_str());
      else if (!quiet || v.rc != 0)
        std::printf("%s\n", verdict_line(v).c_str());
      std::fflush(stdout);
      (v.rc == 0 ? ok : v.rc == 1 ? mismatched : errors) += 1;
      verdicts[printed] = FileVerdict{};  // free the report
      ++printed;
    }
  };
  auto worker = [&] {
    for (;;) {
      size_t i;
      {
        std::lock_guard<std::mutex> lock(mutex);
        if (next == n) return;
        i = next++;
      }
      FileVerdict v = verify_file(a.files[i], {});
      std::lock_guard<std::mutex> lock(mutex);
      verdicts[i] = std::move(v);
      done[i] = 1;
      ++finished;
      flush();
      progress.update(finished, n);
    }
  };
  std::vector<std::thread> threads;
  for (uint32_t t = 1; t < jobs; ++t) threads.emplace_back(worker);
  worker();
  for (std::thread& t : threads) t.join();
  progress.finish();
  if (!json)
    std::printf("verified %zu file%s with %u job%s: %u ok, %u mismatched, %u not verified (bad file)\n", n,
                n == 1 ? "" : "s", jobs, jobs == 1 ? "" : "s", ok, mismatched, errors);
  return errors != 0 ? 2 : mismatched != 0 ? 1 : 0;
}

int run_verify(const VerifyArgs& a, const GlobalOptions& g) {
  const bool json = a.json || g.json, quiet = a.quiet || g.quiet;
  if (a.files.size() == 1 && !a.jobs_given) return run_verify_one(a.files[0], json, quiet);
  return run_verify_batch(a, json, quiet);
}

// --- diff ---------------------------------------------------------------------
struct DiffArgs {
  std::string a, b;
  bool json = false, quiet = false;
};

int run_diff(const DiffArgs& a, const GlobalOptions& g) {
  const bool json = a.json || g.json, quiet = a.quiet || g.quiet;
  std::vector<uint8_t> bytes_a, bytes_b;
  Status s = read_file_bytes(a.a, &bytes_a);
  if (!s.ok()) return fail("diff", s.message);
  s = read_file_bytes(a.b, &bytes_b);
  if (!s.ok()) return fail("diff", s.message);
  const bool replay_a = is_replay_image(bytes_a), replay_b = is_replay_image(bytes_b);
  DiffReport rep;
  ProgressBar progress("diff", quiet || json);
  if (replay_a && replay_b) {
    Replay ra, rb;
    ReplayReadInfo ia, ib;
    s = read_replay(bytes_a, &ra, &ia);
    if (!s.ok()) return fail("diff", a.a + ": " + s.message);
    s = read_replay(bytes_b, &rb, &ib);
    if (!s.ok()) return fail("diff", a.b + ": " + s.message);
    if (!ia.warning.empty()) std::fprintf(stderr, "tandem diff: warning: %s: %s\n", a.a.c_str(), ia.warning.c_str());
    if (!ib.warning.empty()) std::fprintf(stderr, "tandem diff: warning: %s: %s\n", a.b.c_str(), ib.warning.c_str());
    DiffOptions options;
    options.progress = [&progress](int64_t done, int64_t total) { progress.update(static_cast<uint64_t>(done), static_cast<uint64_t>(total)); };
    rep = diff_replays(ra, rb, options);
  } else if (!replay_a && !replay_b) {
    rep = diff_snapshots(bytes_a, bytes_b);
  } else {
    return fail("diff", "cannot compare a replay with a snapshot: " + (replay_a ? a.a : a.b) + " is a replay, " +
                            (replay_a ? a.b : a.a) + " is not (give two replays or two state snapshots)");
  }
  progress.finish();
  const int rc = diff_exit_code(rep);
  if (rc == 2) return fail("diff", rep.error.message);
  if (json) {
    Json j;
    j["a"] = a.a;
    j["b"] = a.b;
    j["method"] = rep.method;
    j["result"] = rep.differs ? "different" : "identical";
    j["ticks_compared"] = rep.ticks_compared;
    if (rep.inputs_differ) j["inputs_differ_tick"] = rep.inputs_differ_tick;
    if (rep.differs) {
      if (rep.length_differs) {
        j["ticks_a"] = rep.ticks_a;
        j["ticks_b"] = rep.ticks_b;
      } else {
        if (rep.method != "snapshot") j["tick"] = rep.tick;
        j["hash_a"] = hash_text(rep.hash_a);
        j["hash_b"] = hash_text(rep.hash_b);
        if (rep.located) {
          if (rep.method != "snapshot") j["located_tick"] = rep.located_tick;
          j["difference"] = difference_json(rep.difference);
        }
      }
    }
    if (!rep.note.empty()) j["note"] = rep.note;
    std::printf("%s\n", j.dump().c_str());
    return rc;
  }
  if (quiet) {
    std::printf("%s\n", rep.differs ? (rep.located ? rep.difference.describe().c_str() : "different") : "identical");
    return rc;
  }
  std::printf("%s", format_diff_report(rep, a.a, a.b).c_str());
  return rc;
}

// --- synctest -----------------------------------------------------------------
struct SyncArgs {
  std::string scene;
  int64_t ticks = -1;
  int32_t rollback = 8;
  bool json = false, quiet = false;
};

int run_sync(const SyncArgs& a, const GlobalOptions& g) {
  const bool json = a.json || g.json, quiet = a.quiet || g.quiet;
  LoadedScene s;
  if (int rc = load_scene("synctest", a.scene, g.scene_limits, &s)) return rc;
  const int64_t ticks = a.ticks >= 0 ? a.ticks : s.scene.ticks;
  SyncTestOptions options;
  options.ticks = ticks;
  options.rollback = a.rollback;
  options.time_step = s.scene.time_step;
  Status input_error;
  SyncTestReport rep;
  const Status st = run_synctest(
      s.built.world, options,
      [&](WorldId, int64_t tick) {
        const Status in = scene::apply_scene_inputs(s.built, s.scene, tick);
        if (!in.ok() && input_error.ok()) input_error = in;
      },
      &rep);
  if (!st.ok()) return fail("synctest", a.scene + ": " + st.message);
  if (!input_error.ok()) return fail("synctest", input_error.message);
  if (json) {
    Json j;
    j["scene"] = a.scene;
    j["ticks"] = ticks;
    j["rollback"] = a.rollback;
    j["result"] = rep.passed ? "passed" : "mismatch";
    j["ticks_run"] = rep.ticks_run;
    j["resimulated_ticks"] = rep.resimulated_ticks;
    if (!rep.passed) {
      j["first_mismatch_tick"] = rep.first_mismatch_tick;
      j["detected_at_tick"] = rep.detected_at_tick;
      j["expected_hash"] = hash_text(rep.expected_hash);
      j["actual_hash"] = hash_text(rep.actual_hash);
      if (rep.difference.differs) j["difference"] = difference_json(rep.difference);
    }
    j["final_hash"] = hash_text(world_state_hash(s.built.world));
    std::printf("%s\n", j.dump().c_str());
    return rep.passed ? 0 : 1;
  }
  if (!quiet)
    std::printf("synctest %s: %" PRId64 " ticks, rollback %d, %" PRId64 " ticks re-simulated\n", a.scene.c_str(),
                rep.ticks_run, a.rollback, rep.resimulated_ticks);
  std::printf("%s\n", rep.message.c_str());
  return rep.passed ? 0 : 1;
}

}  // namespace

void register_replay_commands(CLI::App& app, const GlobalOptions& options, std::vector<Command>* commands) {
  auto* record = app.add_subcommand("record", "Run a scene file and record every tick to a replay file");
  auto record_args = std::make_shared<RecordArgs>();
  record->add_option("scene", record_args->scene, "scene file (JSON, docs/scene-format.md)")->required();
  record->add_option("-o,--out", record_args->out, "replay file to write (created or replaced)")->required();
  record->add_option("--ticks,-n", record_args->ticks, "steps to record (default: the scene's \"ticks\")")
      ->check(CLI::Range(int64_t{0}, int64_t{1} << 40));
  record->add_option("--keyframe-every", record_args->keyframe_every,
                     "write a world snapshot every K ticks, for seeking and locating desyncs (0: only at tick 0; "
                     "default 600)");
  record->add_option("--flush-every", record_args->flush_every, "flush the file every K ticks (default 1)")
      ->check(CLI::Range(1u, 1u << 20));
  record->add_flag("--no-hash", record_args->no_hash, "do not record a state hash after each tick");
  record->add_flag("--no-embed", record_args->no_embed, "store only the scene's hash, not its text");
  add_output_flags(record, &record_args->json, &record_args->quiet, "print only the final hash");
  record->footer(
      "Examples:\n  tandem record scenes/pyramid.json -o pyramid.tnr\n"
      "  tandem record scenes/rain.json -o rain.tnr --ticks 3600 --keyframe-every 60\n"
      "  tandem record scenes/stack.json -o stack.tnr --no-hash --flush-every 60\n");
  commands->push_back({record, [record_args, &options] { return run_record(*record_args, options); }});

  auto* replay = app.add_subcommand("replay", "Play a replay file and print the final state hash");
  auto replay_args = std::make_shared<ReplayArgs>();
  replay->add_option("file", replay_args->file, "replay file (from tandem record)")->required();
  replay->add_option("--ticks,-n", replay_args->ticks, "stop after this tick (default: all recorded)")
      ->check(CLI::Range(int64_t{0}, int64_t{1} << 40));
  replay->add_option("--save-state", replay_args->save_state, "write the final world state (a snapshot) to this file");
  add_output_flags(replay, &replay_args->json, &replay_args->quiet, "print only the final hash");
  replay->footer(
      "Examples:\n  tandem replay pyramid.tnr\n  tandem replay pyramid.tnr --ticks 120 --save-state t120.state\n"
      "  tandem replay rain.tnr --json\n");
  commands->push_back({replay, [replay_args, &options] { return run_replay(*replay_args, options); }});

  auto* verify = app.add_subcommand(
      "verify", "Re-simulate replays and check every recorded hash (exit 0 match, 1 mismatch, 2 bad file)");
  auto verify_args = std::make_shared<VerifyArgs>();
  verify->add_option("files", verify_args->files, "replay files (one or more)")->required();
  verify->add_option("--jobs,-j", verify_args->jobs,
                     "verify this many files at once (0: one per CPU; default: one file at a time)")
      ->check(CLI::Range(0u, 1024u));
  add_output_flags(verify, &verify_args->json, &verify_args->quiet,
                   "one file: print only OK or the mismatching tick; several: only the failures and the summary");
  verify->footer(
      "On a mismatch, verify names the first tick whose hash differs and, from the\n"
      "next keyframe, the first differing body and field.\n"
      "Several files (or --jobs): one line per file in argument order (with --json\n"
      "one JSON object per line, errors included as \"result\":\"error\"), then a\n"
      "summary; exit 2 if any file is unreadable, else 1 if any mismatched, else 0.\n"
      "Examples:\n  tandem verify pyramid.tnr\n  tandem verify rain.tnr --json\n"
      "  tandem verify --jobs 8 --json matches/*.tnr > verdicts.jsonl\n");
  commands->push_back({verify, [verify, verify_args, &options] {
                         verify_args->jobs_given = verify->count("--jobs") > 0;
                         return run_verify(*verify_args, options);
                       }});

  auto* diff = app.add_subcommand(
      "diff", "Find the first tick, body and field where two replays (or two snapshots) differ");
  auto diff_args = std::make_shared<DiffArgs>();
  diff->add_option("a", diff_args->a, "replay or snapshot file")->required();
  diff->add_option("b", diff_args->b, "replay or snapshot file (the same kind as A)")->required();
  add_output_flags(diff, &diff_args->json, &diff_args->quiet, "print only the first difference");
  diff->footer(
      "Exit code 0 identical, 1 different, 2 bad input.\n"
      "Examples:\n  tandem diff mine.tnr theirs.tnr\n  tandem diff mine.tnr theirs.tnr --json\n"
      "  tandem replay a.tnr --save-state a.state && tandem replay b.tnr --save-state b.state && "
      "tandem diff a.state b.state\n");
  commands->push_back({diff, [diff_args, &options] { return run_diff(*diff_args, options); }});

  auto* sync = app.add_subcommand(
      "synctest", "Roll back K ticks after every tick, re-simulate and check the hashes (rollback netcode check)");
  auto sync_args = std::make_shared<SyncArgs>();
  sync->add_option("scene", sync_args->scene, "scene file (JSON)")->required();
  sync->add_option("--ticks,-n", sync_args->ticks, "ticks to run (default: the scene's \"ticks\")")
      ->check(CLI::Range(int64_t{0}, int64_t{INT32_MAX}));
  sync->add_option("--rollback,-k", sync_args->rollback, "ticks rolled back and re-simulated each tick (1-1024, default 8)")
      ->check(CLI::Range(1, 1024));
  add_output_flags(sync, &sync_args->json, &sync_args->quiet, "print only the result line");
  sync->footer(
      "Exit code 0 passed, 1 mismatch, 2 bad input.\n"
      "Examples:\n  tandem synctest scenes/pyramid.json --ticks 300\n"
      "  tandem synctest scenes/rain.json --ticks 600 --rollback 16 --json\n");
  commands->push_back({sync, [sync_args, &options] { return run_sync(*sync_args, options); }});
}

}  // namespace tandem::cli
