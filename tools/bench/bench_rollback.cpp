// bench_rollback.cpp — cost of the rollback primitives (replay/state.h) on a
// 1000-body pile: snapshot, restore, hash, and a rollback of 8 ticks
// (restore + resimulate 8 steps). Google Benchmark; build Release.
//
// The scene: 1000 dynamic bodies (alternating 0.4 m boxes and 0.35 m
// circles) dropped in a 40 m wide walled pit and stepped 90 ticks at 1/60 s
// before timing, so most are in contact and none asleep yet. Counters give
// the snapshot size and bytes per dynamic body (static geometry included in
// the full image: 3 bodies). Goals (issue 7): snapshot < 0.05 ms, rollback
// of 8 ticks < 4 ms, ≤ 128 bytes per moving body. The compact form (a
// delta against a base image 1 or 8 ticks older, state.h) is measured too.
// The world uses the grid broad phase (same results as every kind).
#include <benchmark/benchmark.h>

#include <cstdint>
#include <cstdio>
#include <vector>

#include "physics/collision.h"
#include "physics/tandem.h"
#include "replay/state.h"

namespace {

using namespace tandem;
using namespace tandem::literals;

const Q32 k_dt = Q32::from_ratio(1, 60);
constexpr int32_t k_bodies = 1000;
constexpr int32_t k_settle_ticks = 90;

BodyId add_body(WorldId w, BodyType type, Vec2 p) {
  BodyDef bd = default_body_def();
  bd.type = type;
  bd.position = p;
  return create_body(w, bd).value;
}

void add_box(BodyId b, Q32 hw, Q32 hh) {
  Polygon poly;
  make_box(hw, hh, &poly);
  create_polygon_shape(b, default_shape_def(), poly);
}

/// The pile world (the caller destroys it).
WorldId make_pile() {
  WorldDef def = default_world_def();
  def.broad_phase = BroadPhaseKind::grid;  // many similar shapes; results identical for every kind
  WorldId w = create_world(def).value;
  const BodyId ground = add_body(w, BodyType::static_body, {0_q32, -1_q32});
  add_box(ground, 21_q32, 1_q32);
  const BodyId left = add_body(w, BodyType::static_body, {-20.5_q32, 20_q32});
  add_box(left, 0.5_q32, 21_q32);
  const BodyId right = add_body(w, BodyType::static_body, {20.5_q32, 20_q32});
  add_box(right, 0.5_q32, 21_q32);
  for (int32_t i = 0; i < k_bodies; ++i) {
    const int32_t col = i % 40;
    const int32_t row = i / 40;
    const Vec2 p{Q32::from_int(col - 20) + 0.5_q32 + Q32::from_ratio(row % 3, 10), 1_q32 + Q32::from_int(row)};
    const BodyId b = add_body(w, BodyType::dynamic_body, p);
    if (i % 2 == 0) {
      add_box(b, 0.4_q32, 0.4_q32);
    } else {
      Circle c;
      c.radius = 0.35_q32;
      create_circle_shape(b, default_shape_def(), c);
    }
  }
  for (int32_t t = 0; t < k_settle_ticks; ++t) world_step(w, k_dt);
  return w;
}

void set_counters(benchmark::State& state, size_t bytes) {
  state.counters["bytes"] = static_cast<double>(bytes);
  state.counters["bytes_per_body"] = static_cast<double>(bytes) / k_bodies;
}

void BM_Snapshot(benchmark::State& state) {
  const WorldId w = make_pile();
  std::vector<uint8_t> buffer(world_snapshot_size(w));
  size_t written = 0;
  for (auto _ : state) {
    world_snapshot(w, buffer.data(), buffer.size(), &written);
    benchmark::DoNotOptimize(buffer.data());
  }
  set_counters(state, written);
  destroy_world(w);
}

void BM_Restore(benchmark::State& state) {
  const WorldId w = make_pile();
  std::vector<uint8_t> snap;
  encode_world_state(w, &snap);
  for (auto _ : state) {
    const Status s = world_restore(w, snap.data(), snap.size());
    benchmark::DoNotOptimize(s.code);
  }
  set_counters(state, snap.size());
  destroy_world(w);
}

void BM_Hash(benchmark::State& state) {
  const WorldId w = make_pile();
  for (auto _ : state) benchmark::DoNotOptimize(world_state_hash(w));
  destroy_world(w);
}

void BM_Step(benchmark::State& state) {
  const WorldId w = make_pile();
  std::vector<uint8_t> snap;
  encode_world_state(w, &snap);
  int32_t n = 0;
  for (auto _ : state) {
    world_step(w, k_dt);
    if (++n == 8) {  // keep the scene near the measured state
      state.PauseTiming();
      world_restore(w, snap.data(), snap.size());
      n = 0;
      state.ResumeTiming();
    }
  }
  destroy_world(w);
}

/// Snapshot, then restore and resimulate 8 ticks: one rollback of a
/// rollback netcode session (snapshot of the confirmed tick + resim).
void BM_Rollback8(benchmark::State& state) {
  const WorldId w = make_pile();
  std::vector<uint8_t> snap(world_snapshot_size(w));
  size_t written = 0;
  world_snapshot(w, snap.data(), snap.size(), &written);
  for (auto _ : state) {
    world_snapshot(w, snap.data(), snap.size(), &written);
    world_restore(w, snap.data(), written);
    for (int32_t t = 0; t < 8; ++t) world_step(w, k_dt);
    state.PauseTiming();
    world_restore(w, snap.data(), written);  // the same 8 ticks every iteration
    state.ResumeTiming();
  }
  set_counters(state, written);
  destroy_world(w);
}

/// The compact form: a full image, then its delta against the image of
/// `range(0)` ticks earlier (counters: delta bytes per body).
void BM_DeltaSnapshot(benchmark::State& state) {
  const WorldId w = make_pile();
  std::vector<uint8_t> base;
  encode_world_state(w, &base);
  for (int64_t t = 0; t < state.range(0); ++t) world_step(w, k_dt);
  std::vector<uint8_t> image(world_snapshot_size(w));
  std::vector<uint8_t> delta;
  size_t written = 0;
  for (auto _ : state) {
    world_snapshot(w, image.data(), image.size(), &written);
    encode_state_delta(base.data(), base.size(), image.data(), written, &delta);
    benchmark::DoNotOptimize(delta.data());
  }
  set_counters(state, delta.size());
  state.counters["full_bytes_per_body"] = static_cast<double>(written) / k_bodies;
  destroy_world(w);
}

/// Rebuilding the image from base + delta and restoring it.
void BM_DeltaRestore(benchmark::State& state) {
  const WorldId w = make_pile();
  std::vector<uint8_t> base;
  encode_world_state(w, &base);
  for (int64_t t = 0; t < state.range(0); ++t) world_step(w, k_dt);
  std::vector<uint8_t> image;
  encode_world_state(w, &image);
  std::vector<uint8_t> delta;
  encode_state_delta(base.data(), base.size(), image.data(), image.size(), &delta);
  std::vector<uint8_t> rebuilt;
  for (auto _ : state) {
    apply_state_delta(base.data(), base.size(), delta.data(), delta.size(), &rebuilt);
    world_restore(w, rebuilt.data(), rebuilt.size());
  }
  set_counters(state, delta.size());
  destroy_world(w);
}

BENCHMARK(BM_Snapshot)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Restore)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Hash)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Step)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Rollback8)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DeltaSnapshot)->Arg(1)->Arg(8)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_DeltaRestore)->Arg(8)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
