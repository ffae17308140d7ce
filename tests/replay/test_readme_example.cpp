// The README's replay example (snapshot/restore for rollback, a recorded and
// verified replay, a sync test), compiled and checked so the README cannot
// drift from the API. Keep the block between the markers identical to the
// README's "Replay" example.
#include <catch2/catch.hpp>

#include <cstdio>

#include <cstdint>
#include <vector>

#include "physics/tandem.h"
#include "replay/replay_file.h"
#include "replay/rollback.h"
#include "replay/state.h"
#include "replay/synctest.h"
#include "replay/verify.h"

using namespace tandem;
using namespace tandem::literals;

TEST_CASE("the README replay example runs as written", "[replay][readme]") {
  WorldId world = create_world(default_world_def()).value;
  BodyDef ground_def = default_body_def();
  BodyId ground = create_body(world, ground_def).value;
  Polygon ground_box;
  REQUIRE(make_offset_box(20_q32, 1_q32, Vec2{0_q32, -1_q32}, 0_q32, 0_q32, &ground_box).ok());
  REQUIRE(create_polygon_shape(ground, default_shape_def(), ground_box).ok());
  BodyDef ball_def = default_body_def();
  ball_def.type = BodyType::dynamic_body;
  ball_def.position = Vec2{0_q32, 4_q32};
  BodyId ball = create_body(world, ball_def).value;
  REQUIRE(create_circle_shape(ball, default_shape_def(), Circle{Vec2{}, 0.5_q32}).ok());
  const Q32 dt = Q32::from_ratio(1, 60);

  // --- README replay example begins ---
  // Fallible calls return a [[nodiscard]] Status; `check` prints its message.
  auto check = [](const Status& s) { if (!s.ok()) std::fprintf(stderr, "%s\n", s.message.c_str()); return s.ok(); };

  // Rollback: snapshot into a caller-supplied buffer, step ahead, restore.
  std::vector<uint8_t> snapshot(world_snapshot_size(world));
  size_t written = 0;
  check(world_snapshot(world, snapshot.data(), snapshot.size(), &written));
  const uint64_t before = world_state_hash(world);     // XXH3-64 of the canonical little-endian state
  for (int i = 0; i < 8; ++i) world_step(world, dt);
  check(world_restore(world, snapshot.data(), written));  // same handles, same free lists, same bits
  const bool restored = world_state_hash(world) == before;

  // Rollback every tick: the compact snapshot (replay/rollback.h), a fifth of
  // the portable image, for the same build only.
  RollbackBuffer saved;                                // reused: saves after the first do not allocate
  check(rollback_save(world, &saved));
  const uint64_t tick_hash = rollback_hash(saved);     // what peers compare per tick
  for (int i = 0; i < 8; ++i) world_step(world, dt);
  check(rollback_restore(world, saved));               // every later step bit-identical
  check(rollback_save(world, &saved));
  const bool same_tick = rollback_hash(saved) == tick_hash;

  // Record a replay (commands + a hash per tick + keyframes), then verify it.
  ReplayRecorder recorder;
  recorder.open_memory();                              // or open_file("run.tandem-replay")
  check(recorder.begin(world, {}));                    // header + the tick-0 keyframe
  check(recorder.submit(make_apply_linear_impulse_to_center(body_ref(ball), Vec2{2_q32, 0_q32})));
  for (int i = 0; i < 120; ++i) recorder.step();      // a StepResult, like world_step
  check(recorder.finish());
  Replay replay;
  check(read_replay(recorder.memory(), &replay));
  const VerifyReport report = verify_replay(replay);   // re-simulates, compares every tick's hash
  // format_verify_report(report) says where a run first differed: tick, body, field

  // Sync test (as rollback netcode libraries offer): roll back 8 ticks after
  // every tick, re-simulate, and check the hashes match.
  SyncTestOptions sync;
  sync.ticks = 60;
  SyncTestReport sync_report;
  check(run_synctest(world, sync, [](WorldId, int64_t) {}, &sync_report));
  // --- README replay example ends ---

  CHECK(written == snapshot.size());
  CHECK(restored);
  CHECK(same_tick);
  CHECK(recorder.tick_count() == 120);
  CHECK(replay.tick_count() == 120);
  INFO(format_verify_report(report));
  CHECK(report.ok());
  CHECK(report.hashes_checked == 120);
  INFO(sync_report.message);
  CHECK(sync_report.passed);
  CHECK(destroy_world(world).ok());
}
