// replay_file.h — the replay file: a self-contained record of a simulation
// (initial state + every tick's inputs + a hash after every tick), written
// append-only so that a crash loses nothing already flushed.
//
// TICKS. Tick numbers are int64_t in this API, as everywhere in Tandem; the
// file stores them as u64, and a tick above INT64_MAX read from a file, or a
// negative one passed in, is refused with a Status naming it. Tick t
// (t = 1, 2, ...) is: apply tick t's commands to the state
// after tick t − 1, then world_step(world, time_step); the recorded hash is
// world_state_hash() after that step. Tick 0 is the initial state (the first
// keyframe). A keyframe "at tick k" is the world snapshot after tick k.
//
// FILE LAYOUT (every integer little-endian; offsets from the file start):
//   0   8  magic "TANDREPL"
//   8   4  u32 format version (k_replay_format_version = 2 written; 1 and 2
//          read — version 1 lacks the game states below)
//   12 ... chunks, back to back, until the end of the file
// Chunk:
//   +0  4  u32 type: four ASCII bytes, first byte lowest ("HEAD", "KEYF",
//          "TICK", "END ")
//   +4  4  u32 payload length L (bytes)
//   +8  4  u32 header check: low 32 bits of XXH3-64 (seed 0) of bytes +0..+7,
//          so a corrupt type or length is caught before the length is used
//   +12 L  payload
//   +12+L 8 u64 XXH3-64 (seed 0) of the payload
// The first chunk must be HEAD, the second the KEYF at tick 0. Then TICK and
// KEYF chunks in tick order, and an END chunk when the writer closed cleanly.
//
// HEAD payload:
//   u32 engine version (k_engine_version: major << 16 | minor << 8 | patch)
//   u32 fixed-point format id (k_fixed_format_q32_32 = 0x20200000: "Q32.32")
//   u32 state format version: the version of the tick-0 keyframe's image
//       (replay/state.h: 1 without joints, 2 with); later keyframes may use
//       either (each image names its own). Version 1 files always say 1.
//   i64 time step, Q32.32 raw (seconds)
//   u32 keyframe interval in ticks (0: only the initial keyframe)
//   u8  flags: bit 0 = the writer records a hash after each tick
//   u8  scene flags: bit 0 = scene bytes present, bit 1 = scene hash present
//   u64 scene hash (0 when absent; by default XXH3-64 of the scene bytes)
//   u32 scene byte count S, then S bytes (opaque: e.g. the scene's JSON text)
// KEYF payload: u64 tick, u64 image hash (XXH3-64 of the N image bytes: an
//   integrity check, not world_state_hash, which ignores the broad-phase
//   kind), u32 image byte count N, N bytes of state image (replay/state.h).
//   A keyframe's tick equals the number of ticks before it.
//   Version 2 adds: u32 game state byte count G, G bytes (the game's own
//   state after that tick, e.g. a session's save_game bytes; G = 0: none).
// TICK payload: u32 record count, then per record: u64 tick (consecutive from
//   1), u8 flags (bit 0: hash present), commands (u32 count + each command,
//   replay/commands.h; user input payloads are user_input commands, in the
//   order the game submitted them), then u64 world hash if flag bit 0.
//   Version 2 adds flag bit 1: after the hash, u32 game state byte count G
//   and G bytes (the game's state after the tick; verify_replay checks it
//   when given the game's logic, VerifyOptions::game).
// END payload: u64 tick count (must equal the ticks read).
//
// READING. read_replay() validates everything and fails with a message that
// names the byte offset and what was expected: wrong magic, unknown format
// version, a truncated or corrupt header (HEAD or the first KEYF), a corrupt
// chunk (header check or payload checksum), malformed payloads, ticks out of
// order, data after END. A file cut after the first keyframe — mid-chunk, or
// at a chunk boundary before END — reads back up to its last complete chunk
// with ReplayReadInfo::truncated set and a warning naming the byte offset of
// the cut and the last complete tick. Every count is checked against the
// bytes that remain before anything is allocated for it; payloads are spans
// into the file buffer until decoded.
//
// WRITING. ReplayWriter appends to a file (or to memory) and flushes
// (fflush) after every `flush_every` ticks: pending tick records are written
// as one TICK chunk per flush. A keyframe or the END chunk first flushes the
// pending ticks.
//
// Rejected: one big checksum over the whole file (a cut or a flipped bit
// would lose everything instead of the tail), and chunk lengths without
// their own check (a flipped length bit would read as a truncation).
#pragma once

#include <cstdint>
#include <cstdio>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "physics/tandem.h"
#include "replay/commands.h"

namespace tandem {

/// The 8 magic bytes at the start of every replay file.
inline constexpr uint8_t k_replay_magic[8] = {'T', 'A', 'N', 'D', 'R', 'E', 'P', 'L'};
/// The version written into replay files; read: k_replay_format_version_min…this.
inline constexpr uint32_t k_replay_format_version = 2;
/// The oldest version read (1: no game states).
inline constexpr uint32_t k_replay_format_version_min = 1;
/// The engine version written into replays (0.1.0).
inline constexpr uint32_t k_engine_version = (0u << 16) | (1u << 8) | 0u;
/// Fixed-point format id: integer bits << 24 | fraction bits << 16 (Q32.32).
inline constexpr uint32_t k_fixed_format_q32_32 = (32u << 24) | (32u << 16);
/// Size of the file prelude (magic + version) and of a chunk's framing.
inline constexpr size_t k_replay_prelude_bytes = 12;
inline constexpr size_t k_chunk_header_bytes = 12;
inline constexpr size_t k_chunk_trailer_bytes = 8;

/// Chunk type codes (four ASCII characters, first character lowest).
inline constexpr uint32_t chunk_code(char a, char b, char c, char d) {
  return static_cast<uint32_t>(static_cast<uint8_t>(a)) | static_cast<uint32_t>(static_cast<uint8_t>(b)) << 8 |
         static_cast<uint32_t>(static_cast<uint8_t>(c)) << 16 | static_cast<uint32_t>(static_cast<uint8_t>(d)) << 24;
}
inline constexpr uint32_t k_chunk_head = chunk_code('H', 'E', 'A', 'D');
inline constexpr uint32_t k_chunk_keyframe = chunk_code('K', 'E', 'Y', 'F');
inline constexpr uint32_t k_chunk_tick = chunk_code('T', 'I', 'C', 'K');
inline constexpr uint32_t k_chunk_end = chunk_code('E', 'N', 'D', ' ');

/// The fixed fields of a replay (HEAD chunk).
struct ReplayHeader {
  uint32_t format_version = k_replay_format_version;
  uint32_t engine_version = k_engine_version;
  uint32_t fixed_format = k_fixed_format_q32_32;
  uint32_t state_format_version = 0;  ///< the tick-0 keyframe image's version (filled by the writer)
  Q32 time_step = Q32::from_ratio(1, 60);  ///< seconds per tick
  uint32_t keyframe_interval = 600;   ///< ticks between keyframes; 0: only the initial one
  bool tick_hashes = true;            ///< a world hash is recorded after each tick
  bool has_scene_bytes = false;
  std::vector<uint8_t> scene_bytes;   ///< opaque (for example the scene JSON text)
  bool has_scene_hash = false;
  uint64_t scene_hash = 0;            ///< by default XXH3-64 of scene_bytes
};

/// One tick's inputs and the hash after it.
struct TickRecord {
  int64_t tick = 0;               ///< 1-based
  std::vector<Command> commands;  ///< in submission order (user_input commands carry game payloads)
  bool has_hash = false;
  uint64_t hash = 0;              ///< world_state_hash after the step
  bool has_game_state = false;    ///< format 2: the game's own state after the tick is recorded
  std::vector<uint8_t> game_state;
};

/// A world snapshot after `tick` ticks.
struct Keyframe {
  int64_t tick = 0;
  uint64_t hash = 0;           ///< XXH3-64 of the bytes of `state` (not world_state_hash)
  std::vector<uint8_t> state;  ///< state image (replay/state.h)
  std::vector<uint8_t> game_state;  ///< format 2: the game's own state after `tick` (empty: none)
};

/// Turns a game's opaque payload (recorded at `tick`) into engine commands;
/// appends them to *out_commands. A non-ok status stops the run.
using PayloadHandler =
    std::function<Status(int64_t tick, std::span<const uint8_t> payload, std::vector<Command>* out_commands)>;

/// Applies one tick's commands (user_input ones through `payloads` when set,
/// skipped otherwise) and steps the world by `time_step`. A refused command
/// does not stop the tick (it was refused the same way when recorded); the
/// count of refused commands is added to *out_refused when given, and the
/// count of payloads skipped for want of a handler to *out_skipped. Returns a
/// non-ok status only when the payload handler fails or the step is refused.
Status run_tick(WorldId world, const TickRecord& record, Q32 time_step, const PayloadHandler& payloads = {},
                uint32_t* out_refused = nullptr, uint32_t* out_skipped = nullptr);

/// A whole replay in memory.
struct Replay {
  ReplayHeader header;
  std::vector<Keyframe> keyframes;  ///< ascending tick; keyframes[0] is tick 0
  std::vector<TickRecord> ticks;    ///< ticks[i].tick == i + 1

  /// Number of ticks recorded.
  int64_t tick_count() const { return static_cast<int64_t>(ticks.size()); }
  /// The record of `tick` (1 ≤ tick ≤ tick_count(); not checked).
  const TickRecord& tick_record(int64_t tick) const { return ticks[static_cast<size_t>(tick - 1)]; }
  /// The last keyframe with tick ≤ `tick` (keyframes[0] if none is; an empty
  /// keyframe with no state when there are no keyframes).
  const Keyframe& keyframe_at_or_before(int64_t tick) const;
  /// Puts `world` into the state after `tick` ticks: restores the nearest
  /// keyframe ≤ tick, then runs the ticks after it (run_tick). Refuses a
  /// tick outside 0…tick_count() (naming it) and a world that cannot be
  /// restored.
  Status seek(WorldId world, int64_t tick, const PayloadHandler& payloads = {}) const;
  /// A new world in the state after `tick` ticks (seek on a fresh world).
  Result<WorldId> create_world_at(int64_t tick, const PayloadHandler& payloads = {}) const;
};

/// What read_replay found besides the replay itself.
struct ReplayReadInfo {
  bool truncated = false;       ///< the file ends without an END chunk
  size_t truncated_at = 0;      ///< byte offset of the first byte not read (the cut)
  int64_t last_complete_tick = 0;
  bool closed = false;          ///< an END chunk was read
  std::string warning;          ///< "file cut at byte 1234 after tick 56 (...)"; empty when whole
  uint64_t chunk_count = 0;
};

/// Reads a replay from memory (see the file comment). On error `out` is
/// unspecified and the status message starts with "offset N: ".
Status read_replay(std::span<const uint8_t> data, Replay* out, ReplayReadInfo* info = nullptr);
/// Reads a whole file and read_replay()s it; errors start with the path.
Status read_replay_file(const std::string& path, Replay* out, ReplayReadInfo* info = nullptr);
/// Encodes a whole replay as a file image (HEAD, keyframes and ticks in tick
/// order, END) in format `format_version` (1 or 2; version 1 cannot hold game
/// states, which are left out, and says state format 1 as version-1 writers
/// did). Other versions are written as k_replay_format_version.
std::vector<uint8_t> encode_replay(const Replay& replay, uint32_t ticks_per_chunk = 1,
                                   uint32_t format_version = k_replay_format_version);

/// Reads a file into memory; errors name the path.
Status read_file_bytes(const std::string& path, std::vector<uint8_t>* out);
/// True when the bytes start with the replay magic.
bool is_replay_image(std::span<const uint8_t> data);

/// Options of a writer.
struct ReplayWriterOptions {
  uint32_t flush_every = 1;  ///< ticks per TICK chunk and per fflush; ≥ 1
};

/// Appends a replay to a file or to memory (see the file comment).
class ReplayWriter {
 public:
  ReplayWriter() = default;
  ~ReplayWriter();
  ReplayWriter(const ReplayWriter&) = delete;
  ReplayWriter& operator=(const ReplayWriter&) = delete;

  /// Creates (truncates) the file. Errors name the path.
  Status open_file(const std::string& path, const ReplayWriterOptions& options = {});
  /// Writes into memory (memory()).
  void open_memory(const ReplayWriterOptions& options = {});
  /// Writes the prelude, HEAD and the tick-0 keyframe (with the game's
  /// initial state, may be empty). The header's state format version is
  /// taken from the image. Call once, first.
  Status write_header(const ReplayHeader& header, std::span<const uint8_t> initial_state,
                      std::span<const uint8_t> initial_game_state = {});
  /// Queues a tick record (its tick must follow the last one); writes a TICK
  /// chunk and flushes when flush_every records are pending.
  Status append_tick(TickRecord record);
  /// Writes pending ticks, then a keyframe at `tick` (= ticks appended), with
  /// the game's own state then (may be empty).
  Status append_keyframe(int64_t tick, std::span<const uint8_t> state, std::span<const uint8_t> game_state = {});
  /// Writes pending ticks as one chunk and flushes the file.
  Status flush();
  /// Flushes, writes END and closes the file. Later appends are refused.
  Status finish();
  /// The bytes written so far in memory mode (empty in file mode).
  const std::vector<uint8_t>& memory() const { return memory_; }
  /// Ticks appended so far.
  int64_t tick_count() const { return ticks_; }

 private:
  Status write_chunk(uint32_t type, const std::vector<uint8_t>& payload);
  Status emit(const std::vector<uint8_t>& bytes);

  std::FILE* file_ = nullptr;
  std::string path_;
  bool memory_mode_ = false;
  bool header_written_ = false;
  bool finished_ = false;
  ReplayWriterOptions options_;
  std::vector<uint8_t> memory_;
  std::vector<TickRecord> pending_;
  int64_t ticks_ = 0;
  uint64_t bytes_written_ = 0;
};

/// Options of a recorder.
struct RecorderOptions {
  uint32_t keyframe_interval = 600;  ///< ticks between keyframes; 0: only the initial one
  bool record_hashes = true;         ///< hash after each tick
  uint32_t flush_every = 1;          ///< ticks per flush
  Q32 time_step = Q32::from_ratio(1, 60);  ///< seconds per tick
};

/// Records a world: begin() writes the header and the tick-0 keyframe; per
/// tick, submit() applies and records commands and payloads, step() steps,
/// hashes and records the tick (plus a keyframe when due); finish() closes.
class ReplayRecorder {
 public:
  /// Records to a file (created/truncated at begin()).
  Status open_file(const std::string& path, const RecorderOptions& options = {});
  /// Records to memory (memory()).
  void open_memory(const RecorderOptions& options = {});
  /// Starts recording `world` in its current state. `scene` (may be empty) is
  /// embedded as is; its XXH3-64 is the scene hash unless `scene_hash` is given.
  Status begin(WorldId world, std::span<const uint8_t> scene, std::optional<uint64_t> scene_hash = std::nullopt,
               bool embed_scene = true);
  /// Applies `command` to the world and records it for the current tick
  /// (also when refused: the refusal replays identically). Returns apply_command's status.
  Status submit(const Command& command);
  /// Records an opaque user payload for the current tick (not applied).
  /// Refused before begin() and above k_max_user_payload_bytes (the file
  /// could not be read back); nothing is recorded then. (Returned nothing
  /// before this release.)
  Status submit_payload(std::vector<uint8_t> payload);
  /// Steps the world, records the tick (and its hash), writes a keyframe when due.
  StepResult step();
  /// Flushes, writes END, closes.
  Status finish();
  /// The world being recorded.
  WorldId world() const { return world_; }
  /// Ticks recorded.
  int64_t tick_count() const { return writer_.tick_count(); }
  /// The bytes written in memory mode.
  const std::vector<uint8_t>& memory() const { return writer_.memory(); }
  /// The hash recorded after the last step (0 before the first, or without hashes).
  uint64_t last_hash() const { return last_hash_; }

 private:
  ReplayWriter writer_;
  RecorderOptions options_;
  WorldId world_;
  TickRecord current_;
  uint64_t last_hash_ = 0;
  bool begun_ = false;
};

}  // namespace tandem
