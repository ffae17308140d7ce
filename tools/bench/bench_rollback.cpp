// bench_rollback.cpp — cost of the rollback primitives on the 990-box pile
// of issue 15 (a pyramid of base 44, sleep off): the portable snapshot
// (replay/state.h: world_snapshot, world_restore, world_state_hash) next to
// the compact rollback snapshot (replay/rollback.h: rollback_save,
// rollback_restore, rollback_hash), one step, and one rollback of 8 ticks
// (snapshot + restore + 8 steps) with each. Google Benchmark; build Release.
//
// The scene: 0.5 m boxes (friction 0.6) stacked in a pyramid of base 44 on a
// static ground box, gravity −10 m/s², grid broad phase (results are the
// same for every kind), stepped k_settle_ticks at 1/60 s before timing so
// every box is in contact; with sleep off nothing ever sleeps. Counters:
// image bytes per moving body; the compact path also reports the bytes of
// the structure copy it keeps beside the image (shape geometry and body mass
// data, native copies, never hashed) per moving body.
// Goals (issue 15): ≤ 256 bytes per moving body (moonshot 128), snapshot
// and restore ≤ 0.1 ms each, world hash ≤ 0.05 ms, rollback of 8 ticks
// ≤ 12 ms (moonshot 4 ms).
#include <benchmark/benchmark.h>

#include <cstdint>
#include <vector>

#include "physics/collision.h"
#include "physics/tandem.h"
#include "replay/rollback.h"
#include "replay/state.h"

namespace {

using namespace tandem;
using namespace tandem::literals;

const Q32 k_dt = Q32::from_ratio(1, 60);
constexpr int32_t k_base = 44;
constexpr int32_t k_bodies = k_base * (k_base + 1) / 2;  // 990
constexpr int32_t k_settle_ticks = 60;

/// The pile world (the caller destroys it).
WorldId make_pile() {
  WorldDef def = default_world_def();
  def.broad_phase = BroadPhaseKind::grid;
  def.enable_sleep = false;
  def.gravity = {0_q32, -10_q32};
  const WorldId w = create_world(def).value;
  ShapeDef sd = default_shape_def();
  sd.friction = 0.6_q32;
  BodyDef ground = default_body_def();
  ground.position = {0_q32, -1_q32};
  const BodyId g = create_body(w, ground).value;
  Polygon box;
  (void)make_box(100_q32, 1_q32, &box);  // in range: cannot fail
  (void)create_polygon_shape(g, sd, box);
  (void)make_box(0.5_q32, 0.5_q32, &box);
  const Q32 a = 0.5_q32;
  for (int32_t i = 0; i < k_base; ++i) {
    for (int32_t j = i; j < k_base; ++j) {
      BodyDef bd = default_body_def();
      bd.type = BodyType::dynamic_body;
      bd.position = {Q32::from_int(i + 1) * a + Q32::from_int(2 * (j - i)) * a - a * Q32::from_int(k_base),
                     Q32::from_int(2 * i + 1) * a};
      (void)create_polygon_shape(create_body(w, bd).value, sd, box);
    }
  }
  for (int32_t t = 0; t < k_settle_ticks; ++t) (void)world_step(w, k_dt);
  return w;
}

void set_counters(benchmark::State& state, size_t bytes) {
  state.counters["bytes"] = static_cast<double>(bytes);
  state.counters["bytes_per_body"] = static_cast<double>(bytes) / k_bodies;
}

void set_compact_counters(benchmark::State& state, const RollbackBuffer& b) {
  set_counters(state, b.image.size());
  const double side = static_cast<double>(b.geometries.size() * sizeof(ShapeGeometry) +
                                          b.masses.size() * sizeof(RollbackBodyMass));
  state.counters["structure_copy_bytes_per_body"] = side / k_bodies;
}

// --- portable (state.h) ------------------------------------------------------

void BM_PortableSnapshot(benchmark::State& state) {
  const WorldId w = make_pile();
  std::vector<uint8_t> buffer(world_snapshot_size(w));
  size_t written = 0;
  for (auto _ : state) {
    (void)world_snapshot(w, buffer.data(), buffer.size(), &written);
    benchmark::DoNotOptimize(buffer.data());
  }
  set_counters(state, written);
  (void)destroy_world(w);
}

void BM_PortableRestore(benchmark::State& state) {
  const WorldId w = make_pile();
  std::vector<uint8_t> snap;
  (void)encode_world_state(w, &snap);
  for (auto _ : state) {
    const Status s = world_restore(w, snap.data(), snap.size());
    benchmark::DoNotOptimize(s.code);
  }
  set_counters(state, snap.size());
  (void)destroy_world(w);
}

void BM_PortableHash(benchmark::State& state) {
  const WorldId w = make_pile();
  for (auto _ : state) benchmark::DoNotOptimize(world_state_hash(w));
  (void)destroy_world(w);
}

// --- compact (rollback.h) ----------------------------------------------------

void BM_CompactSave(benchmark::State& state) {
  const WorldId w = make_pile();
  RollbackBuffer buffer;
  (void)rollback_save(w, &buffer);  // the first save sizes the buffer
  for (auto _ : state) {
    (void)rollback_save(w, &buffer);
    benchmark::DoNotOptimize(buffer.image.data());
  }
  set_compact_counters(state, buffer);
  (void)destroy_world(w);
}

void BM_CompactRestore(benchmark::State& state) {
  const WorldId w = make_pile();
  RollbackBuffer buffer;
  (void)rollback_save(w, &buffer);
  for (auto _ : state) {
    const Status s = rollback_restore(w, buffer);
    benchmark::DoNotOptimize(s.code);
  }
  set_compact_counters(state, buffer);
  (void)destroy_world(w);
}

/// Hash of a saved image (what a peer compares per tick).
void BM_CompactHash(benchmark::State& state) {
  const WorldId w = make_pile();
  RollbackBuffer buffer;
  (void)rollback_save(w, &buffer);
  for (auto _ : state) benchmark::DoNotOptimize(rollback_hash(buffer));
  set_compact_counters(state, buffer);
  (void)destroy_world(w);
}

/// A world hash without a save already made: save + hash.
void BM_CompactSaveAndHash(benchmark::State& state) {
  const WorldId w = make_pile();
  RollbackBuffer buffer;
  (void)rollback_save(w, &buffer);
  for (auto _ : state) {
    (void)rollback_save(w, &buffer);
    benchmark::DoNotOptimize(rollback_hash(buffer));
  }
  (void)destroy_world(w);
}

// --- stepping ----------------------------------------------------------------

void BM_Step(benchmark::State& state) {
  const WorldId w = make_pile();
  RollbackBuffer snap;
  (void)rollback_save(w, &snap);
  int32_t n = 0;
  for (auto _ : state) {
    (void)world_step(w, k_dt);
    if (++n == 8) {  // keep the scene near the measured state
      state.PauseTiming();
      (void)rollback_restore(w, snap);
      n = 0;
      state.ResumeTiming();
    }
  }
  (void)destroy_world(w);
}

/// Snapshot, restore and resimulate 8 ticks: one rollback of a rollback
/// netcode session, through the portable image.
void BM_Rollback8Portable(benchmark::State& state) {
  const WorldId w = make_pile();
  std::vector<uint8_t> snap(world_snapshot_size(w));
  size_t written = 0;
  for (auto _ : state) {
    (void)world_snapshot(w, snap.data(), snap.size(), &written);
    (void)world_restore(w, snap.data(), written);
    for (int32_t t = 0; t < 8; ++t) (void)world_step(w, k_dt);
    state.PauseTiming();
    (void)world_restore(w, snap.data(), written);  // the same 8 ticks every iteration
    state.ResumeTiming();
  }
  set_counters(state, written);
  (void)destroy_world(w);
}

/// The same rollback through the compact snapshot.
void BM_Rollback8Compact(benchmark::State& state) {
  const WorldId w = make_pile();
  RollbackBuffer snap;
  (void)rollback_save(w, &snap);
  for (auto _ : state) {
    (void)rollback_save(w, &snap);
    (void)rollback_restore(w, snap);
    for (int32_t t = 0; t < 8; ++t) (void)world_step(w, k_dt);
    state.PauseTiming();
    (void)rollback_restore(w, snap);
    state.ResumeTiming();
  }
  set_compact_counters(state, snap);
  (void)destroy_world(w);
}

BENCHMARK(BM_PortableSnapshot)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_PortableRestore)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_PortableHash)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_CompactSave)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_CompactRestore)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_CompactHash)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_CompactSaveAndHash)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Step)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Rollback8Portable)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Rollback8Compact)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
