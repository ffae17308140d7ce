// test_state_fields.cpp — a guard for the canonical state's field lists: the
// sizes of the records the state encodes (64-bit hosts with 8-byte aligned
// int64, where the sizes below hold). When one fails, a field was added to
// (or removed from) a physics record: add it to its visit_* function in
// physics/state_fields.h (portable image, hash, decode, diff; bump the
// format version if the bytes change) and to the compact rollback image
// (replay/rollback.cpp, rollback_restore.cpp) — or, for per-step scratch
// that is not state, say so next to the field — then update the size here.
#include <catch2/catch.hpp>

#include <cstdint>

#include "physics/body.h"
#include "physics/contact.h"
#include "physics/joint_state.h"
#include "physics/shape.h"
#include "physics/world.h"

namespace {

using namespace tandem;

TEST_CASE("state fields: the encoded physics records have the sizes their visitors were written for",
          "[replay][state]") {
  if constexpr (sizeof(void*) != 8 || alignof(int64_t) != 8) {
    SUCCEED("sizes are checked on 64-bit hosts only");
    return;
  }
  // visit_world_def; the last 32 bytes (worker_count and the task callbacks)
  // are deliberately not state: results are the same for every worker count.
  CHECK(sizeof(WorldDef) == 176);
  CHECK(sizeof(Body) == 80);           // visit_body (with BodySim)
  CHECK(sizeof(BodySim) == 152);       // visit_body
  CHECK(sizeof(Shape) == 112);         // visit_shape
  CHECK(sizeof(ShapeGeometry) == 464); // visit_shape (active variant only)
  CHECK(sizeof(Contact) == 232);       // visit_contact
  CHECK(sizeof(PairRecord) == 16);     // visit_pair
  CHECK(sizeof(Joint) == 528);         // visit_joint (the step_* scratch is not state)
  CHECK(sizeof(JointEvent) == 72);     // visit_joint_event
}

}  // namespace
