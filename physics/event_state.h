// event_state.h — internal: the world's event buffers (world.h holds one
// EventState) and the step hooks that fill them (events.cpp). Not installed;
// the public event types and getters are in events.h.
#pragma once

#include <cstdint>
#include <vector>

#include "physics/events.h"

namespace tandem {

struct World;

/// A touching pair or sensor overlap: shape indices and their generations.
struct PairRecord {
  int32_t shape_a = 0;
  int32_t shape_b = 0;
  uint32_t generation_a = 0;
  uint32_t generation_b = 0;
};

/// A contact that approached faster than the threshold at the step start.
struct HitCandidate {
  int32_t contact_index = 0;  ///< into World::contacts (unchanged during the step)
  int32_t point_index = 0;
  Q32 approach_speed;
};

/// Per-world event state and output.
struct EventState {
  std::vector<PairRecord> touching;         ///< touching pairs at the last step, sorted
  std::vector<PairRecord> touching_next;    ///< scratch, swapped
  std::vector<PairRecord> sensor_overlaps;  ///< sensor overlaps at the last step, sorted
  std::vector<PairRecord> sensor_next;      ///< scratch, swapped
  std::vector<HitCandidate> hit_candidates;
  /// Body indices, ascending, of the bodies this step moved (their transform
  /// differs from the step's start): written by stage_finalize_bodies, which
  /// sees every simulated body — the only ones a step moves — and compares
  /// the pose it writes with the one it replaces.
  std::vector<int32_t> moved_bodies;
  std::vector<ContactBeginEvent> contact_begin;
  std::vector<ContactEndEvent> contact_end;
  std::vector<ContactHitEvent> contact_hit;
  std::vector<SensorEvent> sensor_begin;
  std::vector<SensorEvent> sensor_end;
  std::vector<BodyMoveEvent> body_move;
  /// `touching` is the touching set of World::contacts as they are now: set
  /// by events_after_step once it has built the set, cleared by a restore
  /// (which replaces both). Not state: with it false the next step only takes
  /// the full diff instead of skipping it (World::contact_set_unchanged).
  bool touching_in_sync = false;
};

/// Called by world_step right after the contact update: records hit
/// candidates.
void events_after_contacts(World* world);
/// Empties the six reported lists (contact begin/end/hit, sensor begin/end,
/// body move), keeping their capacity: the start of events_after_step, and a
/// snapshot restore (whose world has reported nothing yet).
void events_clear_reported(EventState* events);
/// Called by world_step after finalize: builds every event list.
void events_after_step(World* world);
/// Called at the end of world_step: grows buffers with headroom.
void events_reserve_headroom(World* world);

}  // namespace tandem
