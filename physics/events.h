// events.h — what happened during the last world_step(): contact begin and
// end, hit events, sensor begin and end, and body moves. Public API (included
// by tandem.h); the world's internal event buffers are in event_state.h.
//
// LIFETIME. Each accepted non-empty world_step() replaces all event lists at
// its end; the spans returned by world_contact_events() and friends stay
// valid until the next world_step(), destroy_world() or any call that may
// create or destroy something in that world — copy what you keep. A step of
// time 0 changes nothing, events included.
//
// DEFINITIONS.
//   * Touching: a contact is touching when its manifold has at least one point
//     (speculative points, up to k_speculative_distance apart, included — the
//     same flag the solver uses; contact.h). Contact begin: a pair touches at
//     this step and did not at the last one; end: it touched at the last step
//     and no longer does, including because a shape or body was destroyed or
//     disabled, or its filter changed. DESTROYED SHAPES: the end event is
//     reported at the next step (not inside destroy_shape/destroy_body), with
//     the (now stale) handles the shapes had. A shape slot reused by a new
//     shape is a different shape (end for the old pair, begin for the new).
//   * Hit: a contact where at least one shape has ShapeDef::enable_hit_events,
//     whose approach speed (−relative normal velocity at a manifold point,
//     from the velocities at the start of the step, i.e. before this step's
//     gravity) exceeds WorldDef::hit_event_threshold at a manifold point
//     whose gap closes within the step (separation < approach speed × dt).
//     One event per contact and step: the qualifying point with the highest
//     approach speed (the first point on a tie).
//   * Sensor: a sensor shape overlaps a visitor — a live non-sensor shape of
//     another body, both bodies enabled, not both static, filters agreeing
//     (filters_should_collide) — when their current AABBs overlap and the
//     GJK distance of the shapes at the end-of-step poses is 0 (touching
//     counts). Begin/end are the changes of that set from the last step;
//     destroyed shapes end at the next step, as for contacts. Sensors are
//     not visitors of other sensors.
//   * Move: a non-static live body whose transform after the step differs
//     (any raw bit) from before it. fell_asleep is true for a body that moved in
//     this step and ended it asleep (its island fell asleep).
//
// ORDER. Every list is sorted by a unique data key: contact begin, end and
// hit events by (lower shape index, higher shape index) — shape_a is always
// the lower index and the manifold normal points from shape_a to shape_b;
// sensor events by (sensor shape index, visitor shape index); move events by
// body index. Nothing depends on addresses.
//
// MEMORY. The buffers are vectors owned by the world; they grow at the end of
// a step (like the contact buffers) with headroom, so a warmed-up scene does
// not allocate.
#pragma once

#include <cstdint>
#include <span>

#include "physics/tandem.h"

namespace tandem {

/// Two shapes began touching this step.
struct ContactBeginEvent {
  ShapeId shape_a;    ///< the lower shape index
  ShapeId shape_b;    ///< the higher shape index
  Manifold manifold;  ///< at the start of the step; normal from shape_a to shape_b
};

/// Two shapes stopped touching this step (or one of them is gone).
struct ContactEndEvent {
  ShapeId shape_a;  ///< the lower shape index (may be stale)
  ShapeId shape_b;  ///< the higher shape index (may be stale)
};

/// Two shapes hit faster than the world's hit_event_threshold.
struct ContactHitEvent {
  ShapeId shape_a;     ///< the lower shape index
  ShapeId shape_b;     ///< the higher shape index
  Vec2 point;          ///< world manifold point of the fastest approach, m
  Vec2 normal;         ///< unit, world, from shape_a to shape_b
  Q32 approach_speed;  ///< m/s, > threshold
};

/// A shape began or stopped overlapping a sensor.
struct SensorEvent {
  ShapeId sensor;   ///< the sensor shape (may be stale in an end event)
  ShapeId visitor;  ///< the overlapping shape (may be stale in an end event)
};

/// A body moved during the step.
struct BodyMoveEvent {
  BodyId body;
  Transform transform;      ///< the pose after the step
  bool fell_asleep = false; ///< the body moved this step and is now asleep
};

/// The contact events of the last step.
struct ContactEvents {
  std::span<const ContactBeginEvent> begin;  ///< by (shape_a, shape_b) index
  std::span<const ContactEndEvent> end;      ///< by (shape_a, shape_b) index
  std::span<const ContactHitEvent> hit;      ///< by (shape_a, shape_b) index
};

/// The sensor events of the last step.
struct SensorEvents {
  std::span<const SensorEvent> begin;  ///< by (sensor, visitor) index
  std::span<const SensorEvent> end;    ///< by (sensor, visitor) index
};

/// The body events of the last step.
struct BodyEvents {
  std::span<const BodyMoveEvent> move;  ///< by body index
};

/// Contact begin, end and hit events of the last step (see the lifetime
/// rule above). An error Status and empty spans for an invalid world handle.
Result<ContactEvents> world_contact_events(WorldId world);
/// Sensor begin and end events of the last step; as world_contact_events.
Result<SensorEvents> world_sensor_events(WorldId world);
/// Body move events of the last step; as world_contact_events.
Result<BodyEvents> world_body_events(WorldId world);
/// Sets the hit event threshold, m/s, [0, max linear speed].
Status world_set_hit_event_threshold(WorldId world, Q32 threshold);

}  // namespace tandem
