// Helpers shared by the physics tests: a world that is destroyed at the end
// of a test case, the usual tick, and a Q32 → long double conversion for
// oracles and messages (tests only).
#pragma once

#include <catch2/catch.hpp>

#include "physics/tandem.h"
#include "../test_world.h"

namespace tandem::test_support {

/// 2^32 as a long double.
inline constexpr long double k_two32 = 4294967296.0L;
/// A Q32.32 value as a long double (exact: 64-bit mantissa on x86).
inline long double ld(Q32 v) { return static_cast<long double>(v.raw) / k_two32; }
/// The tick used by the tests: the raw value nearest 1/60 s.
inline const Q32 k_dt = Q32::from_ratio(1, 60);

/// A world created from `def` and destroyed when the test case ends.
struct ScopedWorld : UniqueWorld {
  explicit ScopedWorld(const WorldDef& def = default_world_def()) : UniqueWorld(test_world::require_world(def).release()) {}
};

/// A body definition of `type` at `position`, otherwise default.
inline BodyDef body_def_at(Vec2 position, BodyType type = BodyType::dynamic_body) {
  BodyDef def = default_body_def();
  def.type = type;
  def.position = position;
  return def;
}

/// A body made from `def` carrying one box of half-extents `hx` × `hy`, m
/// (default shape def); the test fails where either is refused.
inline BodyId add_box_body(WorldId world, const BodyDef& def, Q32 hx, Q32 hy) {
  const Result<BodyId> body = create_body(world, def);
  REQUIRE(body.ok());
  Polygon box;
  REQUIRE(make_box(hx, hy, &box).ok());
  REQUIRE(create_polygon_shape(body.value, default_shape_def(), box).ok());
  return body.value;
}

/// A body made from `def` carrying one circle of `radius`, m, at its origin
/// (default shape def with `density`, kg/m²); the test fails where either is
/// refused.
inline BodyId add_ball_body(WorldId world, const BodyDef& def, Q32 radius, Q32 density = default_shape_def().density) {
  const Result<BodyId> body = create_body(world, def);
  REQUIRE(body.ok());
  ShapeDef sd = default_shape_def();
  sd.density = density;
  REQUIRE(create_circle_shape(body.value, sd, Circle{{}, radius}).ok());
  return body.value;
}

/// A single-threaded task system that runs each task's items one at a time
/// from the last to the first (WorldDef::enqueue_task / finish_task with
/// user_task_context = &a ReversingTasks).
struct ReversingTasks {
  TaskFunction task = nullptr;
  int32_t item_count = 0;
  void* task_context = nullptr;
};

inline void* reversing_enqueue(TaskFunction task, int32_t item_count, int32_t, void* task_context, void* user_context) {
  auto* r = static_cast<ReversingTasks*>(user_context);
  r->task = task;
  r->item_count = item_count;
  r->task_context = task_context;
  return r;
}

inline void reversing_finish(void*, void* user_context) {
  auto* r = static_cast<ReversingTasks*>(user_context);
  for (int32_t i = r->item_count - 1; i >= 0; --i) r->task(i, i + 1, r->task_context);
}

}  // namespace tandem::test_support
