// header_check.cpp — tandem_c.h compiles as C++ too (extern "C", no C-only syntax).
#include "tandem_c.h"

static_assert(sizeof(tandem_world_id) == 4 && sizeof(tandem_body_id) == 12 && sizeof(tandem_shape_id) == 12 &&
                  sizeof(tandem_joint_id) == 12,
              "handles have no padding");
static_assert(sizeof(tandem_vec2) == 16, "a vec2 is two raw Q32.32 values");
