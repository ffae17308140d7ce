// Command application allocates nothing when it succeeds: apply_command of
// apply_force, apply_linear_impulse and set_linear_velocity on a live body
// builds no message text (the handle check and the limit checks build it
// only on a refusal), so a rollback session re-simulating many ticks per
// frame does not touch the heap for its commands.
//
// tests/counting_allocator.h (included here, once in the replay test binary)
// counts operator new calls while g_count_allocations is set, only around
// the apply_command calls under test. The same counter shows that a warm
// compact rollback save and restore (replay/rollback.h) allocate nothing.
#include <catch2/catch.hpp>

#include "../counting_allocator.h"  // this binary's counting operator new/delete

#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <new>
#include <string>

#include "physics/tandem.h"
#include "replay/commands.h"
#include "replay/rollback.h"
#include "replay_test_scenes.h"

using namespace tandem;

namespace {

/// Allocations made by apply_command(world, command); the status is checked.
int64_t allocations_of(WorldId world, const Command& command, bool expect_ok) {
  g_allocation_count = 0;
  g_count_allocations = true;
  const Status s = apply_command(world, command);
  g_count_allocations = false;
  CHECK(s.ok() == expect_ok);
  return g_allocation_count.load();
}

}  // namespace

TEST_CASE("apply_command of force, impulse and velocity on a live body allocates nothing", "[replay][commands]") {
  TANDEM_REQUIRE_ALLOCATION_COUNTING();
  UniqueWorld world = make_unique_world(default_world_def()).value;
  BodyDef def = default_body_def();
  def.type = BodyType::dynamic_body;
  const BodyId body = create_body(world.id, def).value;
  REQUIRE(create_circle_shape(body, default_shape_def(), Circle{vec2(0, 0), Q32::from_int(1)}).ok());
  const BodyRef ref = body_ref(body);

  const Command force = make_apply_force(ref, vec2(3, -2), vec2(1, 0));
  const Command force_center = make_apply_force_to_center(ref, vec2(-1, 4));
  const Command impulse = make_apply_linear_impulse(ref, vec2(1, 1), vec2(0, 1));
  const Command impulse_center = make_apply_linear_impulse_to_center(ref, vec2(0, -1));
  const Command velocity = make_set_linear_velocity(ref, vec2(2, 5));

  // The counter sees allocations made inside apply_command: a refused
  // command (a stale handle) builds its message.
  const Command stale = make_set_linear_velocity(BodyRef{ref.index, ref.generation + 1}, vec2(1, 1));
  CHECK(allocations_of(world.id, stale, false) > 0);

  int64_t total = 0;
  for (int k = 0; k < 10; ++k) {
    total += allocations_of(world.id, force, true);
    total += allocations_of(world.id, force_center, true);
    total += allocations_of(world.id, impulse, true);
    total += allocations_of(world.id, impulse_center, true);
    total += allocations_of(world.id, velocity, true);
    REQUIRE(world_step(world.id, Q32::from_ratio(1, 60)).ok());
  }
  CHECK(total == 0);
  // The commands took effect (the last one set the velocity before the step).
  CHECK(body_linear_velocity(body) != Vec2{});
}

TEST_CASE("warm rollback_save and rollback_restore allocate nothing", "[replay][rollback]") {
  TANDEM_REQUIRE_ALLOCATION_COUNTING();
  using namespace tandem::replay_test;
  const WorldId w = make_scene_world(Scene::pile);
  for (int64_t t = 0; t < 40; ++t) step_scene(Scene::pile, w, t);
  RollbackBuffer buffer;
  REQUIRE(rollback_save(w, &buffer).ok());  // sizes the buffer and the scratch
  REQUIRE(rollback_restore(w, buffer).ok());
  g_allocation_count = 0;
  g_count_allocations = true;
  const bool saved = rollback_save(w, &buffer).ok();
  const bool restored = rollback_restore(w, buffer).ok();
  g_count_allocations = false;
  CHECK(saved);
  CHECK(restored);
  CHECK(g_allocation_count.load() == 0);
  (void)destroy_world(w);
}
