/* c_consumer.c — a C11 program using an installed libtandem.so through
 * tandem_c.h, linked once through find_package(Tandem) (Tandem::c) and once
 * through `pkg-config tandem-c`. Exit status 0 when the checks hold. */
#include <stdio.h>
#include <string.h>

#include "tandem_c.h"

int main(void) {
  tandem_world_def def = tandem_default_world_def();
  tandem_world_id world;
  tandem_q32 dt;
  char text[64];
  size_t length = 0;
  if (tandem_abi_version() != TANDEM_C_ABI_VERSION) return 1;
  if (tandem_create_world(&def, &world) != TANDEM_OK) return 2;
  if (tandem_q32_from_ratio(1, 60, &dt) != TANDEM_OK || tandem_world_step(world, dt, NULL) != TANDEM_OK) return 3;
  if (tandem_q32_from_ratio(-3, 2, &dt) != TANDEM_OK) return 4;
  if (tandem_q32_to_text(dt, text, sizeof text, &length) != TANDEM_OK) return 4;
  if (strcmp(text, "-1.5") != 0) return 5;
  if (tandem_world_check((tandem_world_id){0, 0}) != TANDEM_ERROR_NULL_HANDLE) return 6;
  if (tandem_destroy_world(world) != TANDEM_OK) return 7;
  printf("c consumer: libtandem %s ok\n", tandem_version_string());
  return 0;
}
