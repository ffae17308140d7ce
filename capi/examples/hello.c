/* hello.c — Tandem from C: a ground box, a stack of boxes and a ball, stepped
 * for two seconds; prints the world hash every second. The C# example
 * (bindings/csharp/Hello.cs) builds the same world and must print the same
 * hashes. The README's "From other languages" section shows this file. */
#include <inttypes.h>
#include <stdio.h>

#include "tandem_c.h"

#define CHECK(call)                                                                 \
  do {                                                                              \
    if ((call) != TANDEM_OK) {                                                      \
      fprintf(stderr, "%s failed: %s\n", #call, tandem_last_error_message());       \
      return 1;                                                                     \
    }                                                                               \
  } while (0)

int main(void) {
  tandem_world_def world_def = tandem_default_world_def();
  tandem_world_id world;
  CHECK(tandem_create_world(&world_def, &world));

  tandem_body_def ground_def = tandem_default_body_def();
  tandem_body_id ground;
  tandem_polygon ground_box;
  tandem_shape_def shape_def = tandem_default_shape_def();
  tandem_shape_id shape;
  CHECK(tandem_create_body(world, &ground_def, &ground));
  CHECK(tandem_make_box(tandem_q32_from_int(20), tandem_q32_from_int(1), &ground_box));
  CHECK(tandem_create_polygon_shape(ground, &shape_def, &ground_box, &shape));

  tandem_polygon box;
  tandem_q32 half;
  CHECK(tandem_q32_from_text("0.5", &half));
  CHECK(tandem_make_box(half, half, &box));
  for (int i = 0; i < 5; ++i) {
    tandem_body_def def = tandem_default_body_def();
    tandem_body_id body;
    def.type = TANDEM_BODY_DYNAMIC;
    def.position.y = tandem_q32_from_int(2 + i);  /* metres, raw Q32.32 */
    CHECK(tandem_create_body(world, &def, &body));
    CHECK(tandem_create_polygon_shape(body, &shape_def, &box, &shape));
  }
  tandem_body_def ball_def = tandem_default_body_def();
  tandem_body_id ball;
  tandem_circle circle = {{0, 0}, half};
  ball_def.type = TANDEM_BODY_DYNAMIC;
  ball_def.position.x = tandem_q32_from_int(-6);
  ball_def.position.y = tandem_q32_from_int(3);
  ball_def.linear_velocity.x = tandem_q32_from_int(8);  /* m/s, towards the stack */
  CHECK(tandem_create_body(world, &ball_def, &ball));
  CHECK(tandem_create_circle_shape(ball, &shape_def, &circle, &shape));

  tandem_q32 dt;
  CHECK(tandem_q32_from_ratio(1, 60, &dt));
  for (int tick = 1; tick <= 120; ++tick) {
    CHECK(tandem_world_step(world, dt, NULL));
    if (tick % 60 == 0) {
      tandem_vec2 p = tandem_body_position(ball);
      printf("tick %d hash 0x%016" PRIx64 " ball x %.3f m\n", tick, tandem_world_state_hash(world),
             tandem_q32_to_double(p.x)); /* double: display only */
    }
  }
  CHECK(tandem_destroy_world(world));
  return 0;
}
