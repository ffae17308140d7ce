// edge_support.h — set-up shared by the stress edge tests
// (test_limits_edges.cpp, test_held_bodies.cpp): a fault counter, a world
// destroyed with the test, a static box.
#pragma once

#include <catch2/catch.hpp>

#include <atomic>
#include <cstdint>

#include "fixed/fault.h"
#include "physics/tandem.h"
#include "../test_world.h"

namespace tandem::stress_edges {

inline std::atomic<int64_t> g_faults{0};
inline void count_fault(FixedFault, const char*) { g_faults.fetch_add(1); }

/// Counts fixed-point faults while alive (only builds with fault checks report any).
struct FaultCount {
  FixedFaultHandler previous;
  FaultCount() : previous(set_fixed_fault_handler(&count_fault)) { g_faults.store(0); }
  ~FaultCount() { set_fixed_fault_handler(previous); }
  int64_t count() const { return g_faults.load(); }
};

/// A world destroyed when the test ends.
struct TestWorld : UniqueWorld {
  explicit TestWorld(const WorldDef& def = default_world_def()) : UniqueWorld(test_world::require_world(def).release()) {}
};

/// A static box body of half size (hw, hh) m at `position`.
inline BodyId static_box(WorldId w, Vec2 position, Q32 hw, Q32 hh) {
  BodyDef bd = default_body_def();
  bd.position = position;
  Result<BodyId> b = create_body(w, bd);
  REQUIRE(b.ok());
  Polygon box;
  REQUIRE(make_box(hw, hh, &box).ok());
  REQUIRE(create_polygon_shape(b.value, default_shape_def(), box).ok());
  return b.value;
}

}  // namespace tandem::stress_edges
