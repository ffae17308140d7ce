// state_image.h — what state_access.cpp and state_check.cpp share (internal
// to physics): the StateImage behind state_access.h's opaque handle and the
// conversions between a World and its opaque WorldState.
#pragma once

#include "physics/state_access.h"
#include "physics/world.h"

namespace tandem::state_access {

/// A decoded image: a World that is never registered or stepped, so the
/// functions that derive cached values (shape bounds, body mass, extents)
/// run on the image itself for the consistency checks.
struct StateImage {
  World world;
};

// WorldState is an incomplete type standing for a World: a pointer is
// converted to it and back, never dereferenced as a WorldState.
inline WorldState* as_state(World* w) { return reinterpret_cast<WorldState*>(w); }
inline World& as_world(WorldState& s) { return *reinterpret_cast<World*>(&s); }
inline const World& as_world(const WorldState& s) { return *reinterpret_cast<const World*>(&s); }

/// What every restore does after replacing a world's records: clears the
/// per-step buffers, points pending joint events at this world, rebuilds
/// the joint filter and the broad phase, reserves step headroom.
void rebuild_after_restore(World* w);

}  // namespace tandem::state_access
