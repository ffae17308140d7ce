// test_state_fields.cpp — a guard for the canonical state's field lists: the
// sizes of the records the state encodes (64-bit hosts with 8-byte aligned
// int64, where the sizes below hold). When one fails, a field was added to
// (or removed from) a physics record: add it to its visit_* function in
// physics/state_fields.h (portable image, hash, decode, diff; bump the
// format version if the bytes change) and to the compact rollback image
// (physics/state_compact.cpp, state_compact_restore.cpp: packed, carried
// beside the image or recomputed) — or, for per-step scratch that is not
// state, say so next to the field — then update the size here.
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

// ---------------------------------------------------------------------------
// The two writers of a world image (physics' direct writer on the hash and
// snapshot path, replay's WriteVisitor one call per field) write the same
// bytes, for every scene and format version.
// ---------------------------------------------------------------------------

#include "replay/state_internal.h"
#include "replay_test_scenes.h"

namespace {

using namespace tandem;
using namespace tandem::replay_test;
using namespace tandem::literals;

/// Both encodings of `world` (broad phase as is, and as naive); CHECKs them equal.
void check_writers_agree(WorldId world) {
  using namespace state_detail;
  WorldState* ws = find_world_state(world, true);
  REQUIRE(ws != nullptr);
  const StateCensus census_now = census(*ws);
  const size_t n = encoded_size(census_now);
  for (const bool naive : {false, true}) {
    std::vector<uint8_t> direct(n), per_field(n);
    CHECK(encode_into(*ws, census_now, direct.data(), n, naive, false) == n);
    CHECK(encode_into(*ws, census_now, per_field.data(), n, naive, true) == n);
    CHECK(direct == per_field);
  }
}

TEST_CASE("state fields: physics' direct writer and the per-field WriteVisitor write the same image",
          "[replay][state]") {
  for (int32_t s = 0; s < static_cast<int32_t>(Scene::count); ++s) {
    const Scene scene = static_cast<Scene>(s);
    INFO(scene_name(scene));
    const WorldId w = make_scene_world(scene);
    for (int64_t t = 0; t < 40; ++t) step_scene(scene, w, t);
    check_writers_agree(w);
    REQUIRE(destroy_world(w).ok());
  }
  // Joints (format 2), then a pending joint event (format 3).
  WorldDef def = default_world_def();
  const WorldId w = create_world(def).value;
  const BodyId a = add_body(w, BodyType::dynamic_body, Vec2{0_q32, 2_q32});
  const BodyId b = add_body(w, BodyType::dynamic_body, Vec2{1_q32, 2_q32});
  (void)add_box(a, 0.5_q32, 0.5_q32);
  (void)add_box(b, 0.5_q32, 0.5_q32);
  RevoluteJointDef rd = default_revolute_joint_def();
  rd.base.body_a = a;
  rd.base.body_b = b;
  REQUIRE(create_revolute_joint(w, rd).ok());
  for (int32_t t = 0; t < 10; ++t) REQUIRE(world_step(w, k_dt).ok());
  check_writers_agree(w);
  REQUIRE(destroy_body(b).ok());
  check_writers_agree(w);
  REQUIRE(destroy_world(w).ok());
}

}  // namespace
