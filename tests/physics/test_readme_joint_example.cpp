// The README's grappling-hook example (joints), compiled and run, so the
// README cannot drift from the API. Keep the block between the markers
// identical to the README's "Joints" example.
#include <catch2/catch.hpp>

#include <vector>

#include "physics/tandem.h"

using namespace tandem;
using namespace tandem::literals;

namespace {

/// One tick of the game's (deterministic) input.
struct PlayerInput {
  bool fire = false;     // shoot the hook at `aim`
  Vec2 aim;              // where it hits the ceiling, m
  int reel = 0;          // −1 reel in, +1 pay out, 0 hold
  bool release = false;  // let go
};

struct Outcome {
  Q32 shortest_rope;      // m
  Q32 height_when_reeled; // player y after reeling in, m
  bool hook_gone = false;
  Q32 fall_speed;         // m/s after the release
};

Outcome grappling_hook(WorldId world, BodyId ceiling, BodyId player, const std::vector<PlayerInput>& inputs) {
  Outcome out;
  out.shortest_rope = 1000_q32;
  // --- README joint example begins ---
  JointId hook{};                                   // null: not attached
  Q32 rope;                                         // current rope length, m
  for (const PlayerInput& in : inputs) {
    if (in.fire && is_null(hook)) {                 // attach at the current distance
      DistanceJointDef def = default_distance_joint_def();
      def.base.body_a = ceiling;
      def.base.body_b = player;
      def.base.local_anchor_a = body_local_point(ceiling, in.aim);
      rope = max(distance(in.aim, body_position(player)), 1_q32);
      def.length = rope;
      def.enable_spring = true;                     // hertz 0: no spring force, a free rope...
      def.enable_limit = true;                      // ...that never gets longer than max_length
      def.max_length = rope;
      hook = create_distance_joint(world, def).value;
    }
    if (!is_null(hook) && in.reel != 0) {           // reel by 5 cm a tick, between 1 m and 20 m
      rope = clamp(rope + Q32::from_ratio(in.reel * 5, 100), 1_q32, 20_q32);
      Status s = joint_set_limits(hook, 0_q32, rope);
      if (!s.ok()) std::printf("%s\n", s.message.c_str());  // names the joint, field and range
    }
    if (in.release && !is_null(hook)) {
      (void)destroy_joint(hook);                    // refused only for a stale handle
      hook = JointId{};
    }
    world_step(world, Q32::from_ratio(1, 60));
    // --- README joint example ends ---
    if (!is_null(hook)) out.shortest_rope = min(out.shortest_rope, rope);
    if (in.release) out.hook_gone = !joint_is_valid(hook) && world_counters(world).joint_count == 0;
    if (!is_null(hook) && in.reel < 0) out.height_when_reeled = body_position(player).y;
  }
  out.fall_speed = -body_linear_velocity(player).y;
  return out;
}

}  // namespace

TEST_CASE("README joint example: a grappling hook attaches, reels in and releases", "[physics][joint][readme]") {
  WorldId world = create_world(default_world_def()).value;
  BodyDef cd = default_body_def();
  cd.position = {0_q32, 10_q32};
  BodyId ceiling = create_body(world, cd).value;
  BodyDef pd = default_body_def();
  pd.type = BodyType::dynamic_body;
  pd.position = {-4_q32, 3_q32};
  BodyId player = create_body(world, pd).value;
  REQUIRE(create_circle_shape(player, default_shape_def(), Circle{Vec2{}, 0.4_q32}).ok());

  std::vector<PlayerInput> inputs(420);
  inputs[5].fire = true;
  inputs[5].aim = {0_q32, 10_q32};
  for (int t = 120; t < 200; ++t) inputs[static_cast<size_t>(t)].reel = -1;  // 80 ticks × 5 cm = 4 m shorter
  inputs[300].release = true;
  const Q32 start_rope = distance(Vec2{0_q32, 10_q32}, Vec2{-4_q32, 3_q32} + Vec2{0_q32, Q32::from_ratio(-5, 60 * 60)});
  const Outcome o = grappling_hook(world, ceiling, player, inputs);
  // The rope started at the distance when fired (about 8 m: the player fell a
  // few cm first) and was reeled in by 4 m.
  CHECK(o.shortest_rope > start_rope - 4_q32 - 0.2_q32);
  CHECK(o.shortest_rope < start_rope - 4_q32 + 0.2_q32);
  CHECK(o.height_when_reeled > 4_q32);  // pulled up towards the ceiling (it hung at y < 2.1 m on the full rope)
  CHECK(o.hook_gone);
  CHECK(o.fall_speed > 5_q32);          // falling freely for 2 s after the release
  (void)destroy_world(world);
}
