// broad_phase.cpp — the naive broad phase (see broad_phase.h for the
// contract every broad phase keeps).
//
// Proxies are gathered in ascending shape index (live, non-sensor shapes on
// enabled bodies), each with its AABB fattened by k_speculative_distance
// (exact additions). Then for i < j over the proxy list, a pair is emitted
// when the fat boxes overlap and shapes_should_collide agrees; the nested
// loop visits (i, j) in ascending key order, so no sort is needed.
#include "physics/broad_phase.h"

#include "physics/world.h"

namespace tandem {

bool filters_should_collide(const Filter& a, const Filter& b) {
  if (a.group_index == b.group_index && a.group_index != 0) return a.group_index > 0;
  return (a.category_bits & b.mask_bits) != 0 && (b.category_bits & a.mask_bits) != 0;
}

bool shapes_should_collide(const World& world, int32_t shape_a, int32_t shape_b) {
  const Shape& a = world.shapes[static_cast<size_t>(shape_a)];
  const Shape& b = world.shapes[static_cast<size_t>(shape_b)];
  if (a.body_index == b.body_index || a.is_sensor || b.is_sensor) return false;
  const Body& ba = world.bodies[static_cast<size_t>(a.body_index)];
  const Body& bb = world.bodies[static_cast<size_t>(b.body_index)];
  if (!ba.enabled || !bb.enabled) return false;
  if (ba.type != BodyType::dynamic_body && bb.type != BodyType::dynamic_body) return false;
  return filters_should_collide(a.filter, b.filter);
}

void broad_phase_update_pairs(World* world) {
  BroadPhase& bp = world->broad_phase;
  bp.pairs.clear();
  bp.proxies.clear();
  bp.fat_bounds.clear();
  const int32_t capacity = id_pool_capacity(world->shape_pool);
  for (int32_t s = 0; s < capacity; ++s) {
    if (!id_pool_is_alive(world->shape_pool, s)) continue;
    const Shape& shape = world->shapes[static_cast<size_t>(s)];
    if (shape.is_sensor || !world->bodies[static_cast<size_t>(shape.body_index)].enabled) continue;
    bp.proxies.push_back(s);
    bp.fat_bounds.push_back(aabb_fatten(shape.aabb, k_speculative_distance));
  }
  switch (world->def.broad_phase) {
    case BroadPhaseKind::naive:
    default: {
      const size_t n = bp.proxies.size();
      for (size_t i = 0; i < n; ++i) {
        const AABB box = bp.fat_bounds[i];
        const int32_t a = bp.proxies[i];
        const bool a_dynamic =
            world->bodies[static_cast<size_t>(world->shapes[static_cast<size_t>(a)].body_index)].type ==
            BodyType::dynamic_body;
        for (size_t j = i + 1; j < n; ++j) {
          if (!aabb_overlaps(box, bp.fat_bounds[j])) continue;
          const int32_t b = bp.proxies[j];
          if (!a_dynamic &&
              world->bodies[static_cast<size_t>(world->shapes[static_cast<size_t>(b)].body_index)].type !=
                  BodyType::dynamic_body) {
            continue;  // static/kinematic against static/kinematic
          }
          if (!shapes_should_collide(*world, a, b)) continue;
          bp.pairs.push_back(ShapePair{a, b});
        }
      }
      break;
    }
  }
}

}  // namespace tandem
