// fuzz_targets.h — the bodies of the libFuzzer targets (tests/fuzz/), shared
// with the ordinary regression test that replays saved inputs
// (tests/tools/test_fuzz_regressions.cpp), so a crash found by the fuzzer is
// replayed by every native build, not only the fuzz build.
//
// Each target takes arbitrary bytes, hands them to one parser, and, when the
// parser accepts them, uses the result the way a program would (steps the
// restored world, builds and steps the scene, applies the commands). It
// returns what happened instead of asserting, so the regression test can
// check that a refusal is clean (a non-empty message naming where). A target
// aborts only on a broken invariant of our own (a round trip that differs):
// that is a finding, like a sanitizer report.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

namespace tandem::fuzz {

/// What one input did.
struct Outcome {
  bool accepted = false;  ///< the parser accepted the input
  std::string error;      ///< the refusal message (empty when accepted)
};

/// One fuzz target: its name (also the folder of its corpus and regression
/// files) and its body.
struct Target {
  const char* name;
  Outcome (*run)(std::span<const uint8_t> data);
};

/// read_replay of the bytes as given, then of a copy whose checksums (chunk
/// header checks, chunk checksums, keyframe image hashes) are rewritten to
/// match, so mutations get past them; when that is accepted, a world is made
/// at tick min(ticks, 30) (restore of the nearest keyframe, then the recorded
/// ticks) and stepped twice (not with TANDEM_FUZZ_REPLAY_READ_ONLY set in the
/// environment). The outcome is the second read's.
Outcome run_replay_file(std::span<const uint8_t> data);
/// create_world_from_snapshot; when accepted, 30 steps of 1/60 s.
Outcome run_snapshot(std::span<const uint8_t> data);
/// decode_commands; when accepted, the commands re-encode to the same bytes,
/// then they are applied to a small world that steps 3 times.
Outcome run_commands(std::span<const uint8_t> data);
/// load_scene_text (at most 300 bodies, 1200 shapes); when accepted,
/// build_world, then 5 steps with the scene's inputs.
Outcome run_scene(std::span<const uint8_t> data);
/// parse_q32 and parse_q16; an accepted value prints (to_string) as text that
/// parses back to the same raw value; a refusal's offset lies within the text.
Outcome run_decimal(std::span<const uint8_t> data);
/// decode_session_packet (any sender, any input size); when accepted, the
/// packet re-encodes to the same bytes. Then the bytes as given are handed to
/// a started 2-player rollback session (4-byte inputs, a small world) as if
/// from endpoint 1, which advances 3 frames: a refusal is counted, never a
/// crash. The outcome is the decoder's.
Outcome run_session_packet(std::span<const uint8_t> data);

/// All targets, in a fixed order.
std::span<const Target> all_targets();

}  // namespace tandem::fuzz
