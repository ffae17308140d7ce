// events.cpp — builds the event lists of a step (see events.h for the
// definitions and orders).
//
// Two hooks in world_step: events_after_contacts (after the contact update,
// before any body moves) copies every body's transform and notes contacts
// that approach faster than the hit threshold, from the start-of-step
// velocities and whose gap closes within the step; events_after_step
// (after finalize) diffs the touching-pair and
// sensor-overlap sets against the last step's (both sorted by the unique
// (index, index) key, merged in one forward pass), emits the hits, and
// compares transforms for move events. (The solver's stored impulses cannot
// say whether a point pushed during the step: a bounce latched in the last
// sub-step stores zero, so the hit test is kinematic.)
// The vectors only grow; events_reserve_headroom keeps spare capacity.
#include "physics/event_state.h"

#include <utility>

#include "physics/broad_phase.h"
#include "physics/query.h"
#include "physics/world.h"

namespace tandem {

namespace {

ShapeId shape_handle(const World& w, int32_t index, uint32_t generation) {
  return ShapeId{static_cast<uint32_t>(index + 1), generation, w.id};
}

uint64_t record_key(const PairRecord& r) { return shape_pair_key(r.shape_a, r.shape_b); }

bool same_generations(const PairRecord& a, const PairRecord& b) {
  return a.generation_a == b.generation_a && a.generation_b == b.generation_b;
}

/// Merges the sorted old and new sets: on_begin(new record) for records only
/// in `next` (or with other generations), on_end(old record) for records only
/// in `old`.
template <typename Begin, typename End>
void diff_sets(const std::vector<PairRecord>& old, const std::vector<PairRecord>& next, Begin on_begin, End on_end) {
  size_t i = 0;
  size_t j = 0;
  while (i < old.size() || j < next.size()) {
    if (j == next.size() || (i < old.size() && record_key(old[i]) < record_key(next[j]))) {
      on_end(old[i++]);
    } else if (i == old.size() || record_key(next[j]) < record_key(old[i])) {
      on_begin(next[j++]);
    } else {
      if (!same_generations(old[i], next[j])) {
        on_end(old[i]);
        on_begin(next[j]);
      }
      ++i;
      ++j;
    }
  }
}

/// Relative normal velocity (B relative to A along the normal) at a world
/// point, from the body sims' current velocities, m/s.
Q32 normal_velocity(const World& w, const Contact& c, Vec2 point, Vec2 normal) {
  const BodySim& a = w.body_sims[static_cast<size_t>(c.body_a)];
  const BodySim& b = w.body_sims[static_cast<size_t>(c.body_b)];
  const Vec2 va = a.linear_velocity + cross(a.angular_velocity, point - a.center);
  const Vec2 vb = b.linear_velocity + cross(b.angular_velocity, point - b.center);
  return dot(vb - va, normal);
}

void build_sensor_overlaps(const World& w, std::vector<PairRecord>* out) {
  out->clear();
  const int32_t n = id_pool_capacity(w.shape_pool);
  for (int32_t s = 0; s < n; ++s) {
    if (!id_pool_is_alive(w.shape_pool, s)) continue;
    const Shape& sensor = w.shapes[static_cast<size_t>(s)];
    if (!sensor.is_sensor) continue;
    const Body& sensor_body = w.bodies[static_cast<size_t>(sensor.body_index)];
    if (!sensor_body.enabled) continue;
    const Transform xf_s = w.body_sims[static_cast<size_t>(sensor.body_index)].transform;
    const ShapeProxy proxy_s = make_shape_proxy(w.shape_geometries[static_cast<size_t>(s)]);
    for (int32_t v = 0; v < n; ++v) {
      if (v == s || !id_pool_is_alive(w.shape_pool, v)) continue;
      const Shape& visitor = w.shapes[static_cast<size_t>(v)];
      if (visitor.is_sensor || visitor.body_index == sensor.body_index) continue;
      const Body& visitor_body = w.bodies[static_cast<size_t>(visitor.body_index)];
      if (!visitor_body.enabled) continue;
      if (sensor_body.type == BodyType::static_body && visitor_body.type == BodyType::static_body) continue;
      if (!filters_should_collide(sensor.filter, visitor.filter)) continue;
      if (!aabb_overlaps(sensor.aabb, visitor.aabb)) continue;
      DistanceInput input;
      input.proxy_a = proxy_s;
      input.proxy_b = make_shape_proxy(w.shape_geometries[static_cast<size_t>(v)]);
      input.transform_a = xf_s;
      input.transform_b = w.body_sims[static_cast<size_t>(visitor.body_index)].transform;
      input.use_radii = true;
      if (shape_distance(input).distance != Q32::zero()) continue;
      out->push_back(PairRecord{s, v, id_pool_generation(w.shape_pool, s), id_pool_generation(w.shape_pool, v)});
    }
  }
}

template <typename T>
void reserve_for(std::vector<T>* v, size_t use) {
  if (4 * use + 4 <= 3 * v->capacity()) return;
  v->reserve(2 * use + 64);
}

}  // namespace

void events_after_contacts(World* w) {
  EventState& e = w->events;
  e.hit_candidates.clear();
  // Hits need a shape with hit events (off by default): one pass over the
  // shapes is cheaper than a pass over the contacts, which outnumber them.
  bool any_hit_shape = false;
  const int32_t shapes = id_pool_capacity(w->shape_pool);
  for (int32_t s = 0; s < shapes && !any_hit_shape; ++s) {
    any_hit_shape = id_pool_is_alive(w->shape_pool, s) && w->shapes[static_cast<size_t>(s)].enable_hit_events;
  }
  if (!any_hit_shape) return;
  const Q32 threshold = w->def.hit_event_threshold;
  const Q32 dt = w->context.dt;
  const int32_t count = static_cast<int32_t>(w->contacts.size());
  w->contacts_read_after_update += count;
  for (int32_t ci = 0; ci < count; ++ci) {
    const Contact& c = w->contacts[static_cast<size_t>(ci)];
    if ((c.flags & k_contact_touching) == 0) continue;
    if (!w->shapes[static_cast<size_t>(c.shape_a)].enable_hit_events &&
        !w->shapes[static_cast<size_t>(c.shape_b)].enable_hit_events) {
      continue;
    }
    HitCandidate best;
    best.point_index = -1;
    for (int32_t p = 0; p < c.manifold.point_count; ++p) {
      const ManifoldPoint& mp = c.manifold.points[static_cast<size_t>(p)];
      const Q32 approach = -normal_velocity(*w, c, mp.point, c.manifold.normal);
      // Only a point that closes its gap within this step hits now (a
      // speculative point further away hits at a later step).
      if (approach <= threshold || !(mp.separation < approach * dt)) continue;
      if (best.point_index < 0 || approach > best.approach_speed) {
        best.contact_index = ci;
        best.point_index = p;
        best.approach_speed = approach;
      }
    }
    if (best.point_index >= 0) e.hit_candidates.push_back(best);
  }
}

namespace {
void emit_hits_and_rest(World* w);
}  // namespace

void events_clear_reported(EventState* e) {
  e->contact_begin.clear();
  e->contact_end.clear();
  e->contact_hit.clear();
  e->sensor_begin.clear();
  e->sensor_end.clear();
  e->body_move.clear();
}

void events_after_step(World* w) {
  EventState& e = w->events;
  events_clear_reported(&e);

  // Contacts: the touching set now (contacts are sorted by key). When this
  // step's contact update kept every contact with its touching flag (every
  // step of a world at rest or asleep whose pairs did not change) and
  // `touching` is the set of the list it started from, the set is the same
  // and nothing begins or ends: the pass over the contacts is skipped.
  if (w->contact_set_unchanged && e.touching_in_sync) {
    emit_hits_and_rest(w);
    return;
  }
  e.touching_next.clear();
  w->contacts_read_after_update += static_cast<int64_t>(w->contacts.size());
  for (const Contact& c : w->contacts) {
    if ((c.flags & k_contact_touching) == 0) continue;
    e.touching_next.push_back(PairRecord{c.shape_a, c.shape_b, c.generation_a, c.generation_b});
  }
  size_t cursor = 0;  // the contact of each begin record, found by a forward scan
  diff_sets(
      e.touching, e.touching_next,
      [&](const PairRecord& r) {
        while (contact_key(w->contacts[cursor]) != record_key(r)) ++cursor;
        e.contact_begin.push_back(ContactBeginEvent{shape_handle(*w, r.shape_a, r.generation_a),
                                                    shape_handle(*w, r.shape_b, r.generation_b),
                                                    w->contacts[cursor].manifold});
      },
      [&](const PairRecord& r) {
        e.contact_end.push_back(
            ContactEndEvent{shape_handle(*w, r.shape_a, r.generation_a), shape_handle(*w, r.shape_b, r.generation_b)});
      });
  std::swap(e.touching, e.touching_next);
  e.touching_in_sync = true;
  emit_hits_and_rest(w);
}

namespace {

/// The part of events_after_step after the touching-set diff: hits, sensors,
/// moves.
void emit_hits_and_rest(World* w) {
  EventState& e = w->events;
  // Hits: the candidates, in contact order.
  for (const HitCandidate& h : e.hit_candidates) {
    const Contact& c = w->contacts[static_cast<size_t>(h.contact_index)];
    ContactHitEvent hit;
    hit.shape_a = shape_handle(*w, c.shape_a, c.generation_a);
    hit.shape_b = shape_handle(*w, c.shape_b, c.generation_b);
    hit.point = c.manifold.points[static_cast<size_t>(h.point_index)].point;
    hit.normal = c.manifold.normal;
    hit.approach_speed = h.approach_speed;
    e.contact_hit.push_back(hit);
  }

  // Sensors: the overlap set at the end-of-step poses.
  build_sensor_overlaps(*w, &e.sensor_next);
  diff_sets(
      e.sensor_overlaps, e.sensor_next,
      [&](const PairRecord& r) {
        e.sensor_begin.push_back(
            SensorEvent{shape_handle(*w, r.shape_a, r.generation_a), shape_handle(*w, r.shape_b, r.generation_b)});
      },
      [&](const PairRecord& r) {
        e.sensor_end.push_back(
            SensorEvent{shape_handle(*w, r.shape_a, r.generation_a), shape_handle(*w, r.shape_b, r.generation_b)});
      });
  std::swap(e.sensor_overlaps, e.sensor_next);

  // Moves, in body index order: the bodies finalize saw move (only
  // simulated bodies move in a step, so the sleeping ones cost nothing).
  for (const int32_t i : e.moved_bodies) {
    const size_t bi = static_cast<size_t>(i);
    e.body_move.push_back(BodyMoveEvent{make_body_id(*w, i), w->body_sims[bi].transform, !w->bodies[bi].awake});
  }
}

}  // namespace

void events_reserve_headroom(World* w) {
  EventState& e = w->events;
  reserve_for(&e.touching, e.touching.size());
  reserve_for(&e.touching_next, e.touching.size());
  reserve_for(&e.sensor_overlaps, e.sensor_overlaps.size());
  reserve_for(&e.sensor_next, e.sensor_overlaps.size());
  reserve_for(&e.hit_candidates, e.hit_candidates.size());
  reserve_for(&e.contact_begin, e.contact_begin.size());
  reserve_for(&e.contact_end, e.contact_end.size());
  reserve_for(&e.contact_hit, e.contact_hit.size());
  reserve_for(&e.sensor_begin, e.sensor_begin.size());
  reserve_for(&e.sensor_end, e.sensor_end.size());
  reserve_for(&e.body_move, e.body_move.size());
  reserve_for(&e.moved_bodies, static_cast<size_t>(id_pool_capacity(w->body_pool)));
}

Result<ContactEvents> world_contact_events(WorldId id) {
  Result<ContactEvents> result;
  World* w = nullptr;
  result.status = resolve_world(id, "world_contact_events", false, &w);
  if (!result.ok()) return result;
  result.value.begin = w->events.contact_begin;
  result.value.end = w->events.contact_end;
  result.value.hit = w->events.contact_hit;
  return result;
}

Result<SensorEvents> world_sensor_events(WorldId id) {
  Result<SensorEvents> result;
  World* w = nullptr;
  result.status = resolve_world(id, "world_sensor_events", false, &w);
  if (!result.ok()) return result;
  result.value.begin = w->events.sensor_begin;
  result.value.end = w->events.sensor_end;
  return result;
}

Result<BodyEvents> world_body_events(WorldId id) {
  Result<BodyEvents> result;
  World* w = nullptr;
  result.status = resolve_world(id, "world_body_events", false, &w);
  if (!result.ok()) return result;
  result.value.move = w->events.body_move;
  return result;
}

}  // namespace tandem
