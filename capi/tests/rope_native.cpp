// rope_native.cpp — the README's grappling hook (the C++ "Joints" example)
// in the C++ API, printing "rope tick N hash 0x..." every 60 ticks: the
// native reference that capi/examples/rope.c, bindings/csharp/Rope.cs and the
// Python rope test must reproduce bit for bit (ctest capi/example_rope,
// capi/csharp, capi/python). The scene and inputs are those of
// tests/physics/test_readme_joint_example.cpp: ceiling at (0, 10), a 0.4 m
// ball at (−4, 3); fire at tick 5 aiming at (0, 10), reel in for ticks
// 120…199, release at tick 300, 420 ticks.
#include <cinttypes>
#include <cstdio>

#include "physics/tandem.h"
#include "replay/state.h"

using namespace tandem;
using namespace tandem::literals;

int main() {
  const WorldId world = create_world(default_world_def()).value;
  BodyDef cd = default_body_def();
  cd.position = {0_q32, 10_q32};
  const BodyId ceiling = create_body(world, cd).value;
  BodyDef pd = default_body_def();
  pd.type = BodyType::dynamic_body;
  pd.position = {-4_q32, 3_q32};
  const BodyId player = create_body(world, pd).value;
  if (!create_circle_shape(player, default_shape_def(), Circle{Vec2{}, 0.4_q32}).ok()) return 1;
  JointId hook{};
  Q32 rope;
  for (int tick = 0; tick < 420; ++tick) {
    const bool fire = tick == 5, release = tick == 300;
    const int reel = tick >= 120 && tick < 200 ? -1 : 0;
    const Vec2 aim{0_q32, 10_q32};
    if (fire && is_null(hook)) {
      DistanceJointDef def = default_distance_joint_def();
      def.base.body_a = ceiling;
      def.base.body_b = player;
      def.base.local_anchor_a = body_local_point(ceiling, aim);
      rope = max(distance(aim, body_position(player)), 1_q32);
      def.length = rope;
      def.enable_spring = true;
      def.enable_limit = true;
      def.max_length = rope;
      hook = create_distance_joint(world, def).value;
    }
    if (!is_null(hook) && reel != 0) {
      rope = clamp(rope + Q32::from_ratio(reel * 5, 100), 1_q32, 20_q32);
      if (!joint_set_limits(hook, 0_q32, rope).ok()) return 1;
    }
    if (release && !is_null(hook)) {
      if (!destroy_joint(hook).ok()) return 1;
      hook = JointId{};
    }
    if (!world_step(world, Q32::from_ratio(1, 60)).ok()) return 1;
    if ((tick + 1) % 60 == 0) std::printf("rope tick %d hash 0x%016" PRIx64 "\n", tick + 1, world_state_hash(world));
  }
  return destroy_world(world).ok() ? 0 : 1;
}
