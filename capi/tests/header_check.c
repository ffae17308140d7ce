/* header_check.c — tandem_c.h compiles alone as strict C11 (-pedantic -Werror). */
#include "tandem_c.h"

/* Every handle is a small POD that C can copy and compare field by field. */
int tandem_header_check_c(void);
int tandem_header_check_c(void) {
  tandem_body_id a = {0, 0, {0, 0}};
  tandem_body_id b = a;
  return (int)(sizeof(tandem_world_id) + sizeof(tandem_body_id) + sizeof(tandem_shape_id)) + (int)(a.index1 == b.index1);
}
