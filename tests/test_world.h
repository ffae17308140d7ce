// test_world.h — worlds for tests, owned by the public UniqueWorld.
#pragma once

#include <catch2/catch.hpp>

#include "physics/tandem.h"

namespace tandem::test_world {

/// A world created from `def`, owned by the returned UniqueWorld; the test
/// case fails (REQUIRE) when creation is refused.
inline UniqueWorld require_world(const WorldDef& def = default_world_def()) {
  Result<UniqueWorld> created = make_unique_world(def);
  INFO(created.status.message);
  REQUIRE(created.ok());
  return std::move(created.value);
}

}  // namespace tandem::test_world
