/* rope.c — the README's grappling hook (a rope: a distance joint with a
 * spring of 0 Hz and a maximum length) through the C API, printing the same
 * "rope tick N hash 0x..." lines as the C++ version (capi/tests/rope_native.cpp;
 * ctest capi/example_rope compares them). Compiled as C11 with -Wall -Wextra
 * -pedantic -Werror. */
#include <inttypes.h>
#include <stdio.h>

#include "tandem_c.h"

#define CHECK(call)                                                           \
  do {                                                                        \
    if ((call) != TANDEM_OK) {                                                \
      fprintf(stderr, "%s failed: %s\n", #call, tandem_last_error_message()); \
      return 1;                                                               \
    }                                                                         \
  } while (0)

int main(void) {
  tandem_world_def world_def = tandem_default_world_def();
  tandem_world_id world;
  tandem_body_def ceiling_def = tandem_default_body_def();
  tandem_body_def player_def = tandem_default_body_def();
  tandem_body_id ceiling, player;
  tandem_shape_def shape_def = tandem_default_shape_def();
  tandem_circle ball = {{0, 0}, 0};
  tandem_shape_id shape;
  tandem_joint_id hook = {0, 0, {0, 0}}; /* null: not attached */
  tandem_q32 rope = 0, step, dt, one = tandem_q32_from_int(1), twenty = tandem_q32_from_int(20);
  int tick;
  CHECK(tandem_create_world(&world_def, &world));
  ceiling_def.position.y = tandem_q32_from_int(10);
  CHECK(tandem_create_body(world, &ceiling_def, &ceiling));
  player_def.type = TANDEM_BODY_DYNAMIC;
  player_def.position.x = tandem_q32_from_int(-4);
  player_def.position.y = tandem_q32_from_int(3);
  CHECK(tandem_create_body(world, &player_def, &player));
  CHECK(tandem_q32_from_text("0.4", &ball.radius));
  CHECK(tandem_create_circle_shape(player, &shape_def, &ball, &shape));
  CHECK(tandem_q32_from_ratio(-5, 100, &step)); /* reel in 5 cm a tick */
  CHECK(tandem_q32_from_ratio(1, 60, &dt));

  for (tick = 0; tick < 420; ++tick) {
    tandem_vec2 aim;
    aim.x = 0;
    aim.y = tandem_q32_from_int(10);
    if (tick == 5 && hook.index1 == 0) { /* fire: attach at the current distance */
      tandem_distance_joint_def def = tandem_default_distance_joint_def();
      def.base.body_a = ceiling;
      def.base.body_b = player;
      def.base.local_anchor_a = tandem_body_local_point(ceiling, aim);
      rope = tandem_vec2_distance(aim, tandem_body_position(player));
      if (rope < one) rope = one;
      def.length = rope;
      def.enable_spring = true; /* hertz 0: no spring force, a free rope... */
      def.enable_limit = true;  /* ...that never gets longer than max_length */
      def.max_length = rope;
      CHECK(tandem_create_distance_joint(world, &def, &hook));
    }
    if (hook.index1 != 0 && tick >= 120 && tick < 200) { /* reel in, between 1 m and 20 m */
      rope += step; /* raw Q32.32 addition: exact (no overflow at these lengths) */
      if (rope < one) rope = one;
      if (rope > twenty) rope = twenty;
      CHECK(tandem_joint_set_limits(hook, 0, rope));
    }
    if (tick == 300 && hook.index1 != 0) { /* release */
      tandem_joint_id none = {0, 0, {0, 0}};
      CHECK(tandem_destroy_joint(hook));
      hook = none;
    }
    CHECK(tandem_world_step(world, dt, NULL));
    if ((tick + 1) % 60 == 0) printf("rope tick %d hash 0x%016" PRIx64 "\n", tick + 1, tandem_world_state_hash(world));
  }
  CHECK(tandem_destroy_world(world));
  return 0;
}
