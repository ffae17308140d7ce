// UniqueWorld: the public owning wrapper (physics/tandem.h).
#include <catch2/catch.hpp>

#include <cstdint>
#include <utility>

#include "physics/tandem.h"

using namespace tandem;

TEST_CASE("UniqueWorld destroys its world at scope end, moves and releases", "[physics][world]") {
  WorldId seen{};
  {
    Result<UniqueWorld> made = make_unique_world(default_world_def());
    REQUIRE(made.ok());
    seen = made.value.id;
    CHECK(world_is_valid(seen));
    UniqueWorld moved = std::move(made.value);
    CHECK(is_null(made.value.id));  // the moved-from wrapper owns nothing
    CHECK(moved.id == seen);
    CHECK(world_is_valid(seen));
  }
  CHECK_FALSE(world_is_valid(seen));  // destroyed with `moved`

  UniqueWorld a = make_unique_world(default_world_def()).value;
  UniqueWorld b = make_unique_world(default_world_def()).value;
  const WorldId first = a.id, second = b.id;
  a = std::move(b);  // destroys a's world, takes b's
  CHECK_FALSE(world_is_valid(first));
  CHECK(a.id == second);
  const WorldId released = a.release();
  CHECK(is_null(a.id));
  CHECK(world_is_valid(released));  // released: still alive
  a.reset(released);                // owned again
  CHECK(destroy_world(a.id).ok());  // destroyed by hand: the wrapper's handle is stale...
  a.reset();                        // ...and resetting it is harmless
  CHECK(is_null(a.id));
}

TEST_CASE("make_unique_world refuses a bad definition with the create_world message", "[physics][world]") {
  WorldDef def = default_world_def();
  def.sub_step_count = 0;
  const Result<WorldId> plain = create_world(def);
  const Result<UniqueWorld> wrapped = make_unique_world(def);
  CHECK_FALSE(wrapped.ok());
  CHECK(is_null(wrapped.value.id));
  CHECK(wrapped.status.message == plain.status.message);
  CHECK(wrapped.status.code == plain.status.code);
}

namespace {
struct Seen {
  int64_t y_raw = 0;
  BodyId body;
};
Seen readme_owning_example() {
  // --- README owning example begins ---
  Result<UniqueWorld> made = make_unique_world(default_world_def());
  if (!made.ok()) return {};                    // made.status.message says why
  UniqueWorld world = std::move(made.value);    // destroyed at scope end, even on early returns
  BodyDef def = default_body_def();
  def.type = BodyType::dynamic_body;
  BodyId body = create_body(world.id, def).value;
  (void)world_step(world.id, Q32::from_ratio(1, 60));
  // --- README owning example ends ---
  return {body_position(body).y.raw, body};
}
}  // namespace

TEST_CASE("README owning example: the body falls and the world is gone afterwards", "[physics][world][readme]") {
  const Seen seen = readme_owning_example();
  CHECK(seen.y_raw < 0);                  // one tick of gravity from y = 0
  CHECK_FALSE(is_null(seen.body));
  CHECK_FALSE(body_is_valid(seen.body));  // its world was destroyed with `world`
}
