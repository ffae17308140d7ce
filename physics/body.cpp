// body.cpp — bodies: creation, destruction, the body API, and mass data
// (forces and impulses: body_motion.cpp; shared checks: body_checks.h).
//
// Every mutating function follows one pattern: resolve the handle (which
// refuses null, stale, foreign and locked), check every argument with quiet
// (non-faulting) arithmetic, and only then write. So a refused call leaves
// the world exactly as it was, and nothing a caller passes can make a later
// step saturate.
//
// Mass data. A dynamic body's mass is the sum of its shapes' masses (exact:
// Q32 addition is integer addition); its centre of mass is Σ mᵢ·cᵢ / m with
// the numerator summed exactly in 128 bits and rounded once; its rotational
// inertia about that centre is Σ (Iᵢ + mᵢ·|cᵢ − c|²), each term rounded once
// and summed exactly. Every sum is exact, so the result does not depend on
// the order of the shapes. A dynamic body with no massive shape gets 1 kg and
// no rotational inertia (as Box2D). Static and kinematic bodies have zero
// mass and inverse mass.
#include "physics/body.h"

#include <string>
#include <vector>

#include "physics/body_checks.h"
#include "physics/island.h"
#include "physics/world.h"

namespace tandem {

using namespace body_checks;

namespace {

bool valid_type(BodyType type) {
  return type == BodyType::static_body || type == BodyType::kinematic_body || type == BodyType::dynamic_body;
}

const char* type_name(BodyType type) {
  switch (type) {
    case BodyType::static_body: return "static";
    case BodyType::kinematic_body: return "kinematic";
    case BodyType::dynamic_body: return "dynamic";
  }
  return "unknown";
}

/// A velocity clamped to the world's maximum speed (after a centre shift).
Vec2 clamp_speed(Vec2 v, Q32 max_speed) {
  if (!length_exceeds(v, max_speed)) return v;
  return v * (max_speed / length(v));
}

/// Shared path of the simple setters: resolve (mutating), then run `set`.
template <typename Set>
Status set_body(BodyId id, const char* function, Set set) {
  return set_resolved(id, function, resolve_body, set);
}

/// Shared path of the getters: `fallback` for an invalid handle.
template <typename T, typename Get>
T get_body(BodyId id, T fallback, Get get) {
  return get_found(id, fallback, find_body, get);
}

/// The body's mass for its (possibly new) type and flags, without changing it.
Status compute_body_mass(const World& w, int32_t index, BodyType type, bool fixed_rotation, int32_t replace_shape,
                         Q32 replace_density, const MassData* extra, const std::string& what, BodyMass* out) {
  std::vector<MassData> items;
  if (type == BodyType::dynamic_body) {
    Status s = gather_shape_masses(w, index, replace_shape, replace_density, what, &items);
    if (!s.ok()) return s;
    if (extra != nullptr) items.push_back(*extra);
  }
  return combine_masses(items.data(), static_cast<int32_t>(items.size()), type, fixed_rotation, what, out);
}

}  // namespace

// ---------------------------------------------------------------------------
// Internal helpers (body.h)
// ---------------------------------------------------------------------------

bool find_body(BodyId id, World** out_world, int32_t* out_index) {
  return find_handle(id.index1, id.generation, id.world, &World::body_pool, out_world, out_index);
}

Status resolve_body(BodyId id, const char* function, bool mutating, WorldId expected_world, World** out_world,
                    int32_t* out_index) {
  return resolve_handle(function, "body", id.index1, id.generation, id.world, expected_world, mutating,
                        &World::body_pool, out_world, out_index);
}

BodyId make_body_id(const World& world, int32_t index) {
  BodyId id;
  id.index1 = static_cast<uint32_t>(index) + 1u;
  id.generation = id_pool_generation(world.body_pool, index);
  id.world = world.id;
  return id;
}

Status gather_shape_masses(const World& w, int32_t body_index, int32_t replace_shape, Q32 replace_density,
                           const std::string& what, std::vector<MassData>* out) {
  for (int32_t s = body_at(&w, body_index).head_shape; s != k_null_index;
       s = w.shapes[static_cast<size_t>(s)].next_shape) {
    const Shape& shape = w.shapes[static_cast<size_t>(s)];
    const Q32 density = s == replace_shape ? replace_density : shape.density;
    MassData md{};
    Status st = shape_mass_for_body(w.shape_geometries[static_cast<size_t>(s)], density,
                                    what + " " + describe(make_shape_id(w, s)), &md);
    if (!st.ok()) return st;
    if (md.mass > Q32::zero()) out->push_back(md);
  }
  return Status{};
}

Status combine_masses(const MassData* items, int32_t count, BodyType type, bool fixed_rotation,
                      const std::string& what, BodyMass* out_mass) {
  BodyMass m{};
  if (type != BodyType::dynamic_body) {
    *out_mass = m;
    return Status{};
  }
  // Total mass, exact; quiet saturation only ever exceeds the limit.
  Q32 total;
  for (int32_t k = 0; k < count; ++k) total = add_quiet(total, items[k].mass);
  if (total == Q32::zero()) {
    m.mass = Q32::one();
    m.inv_mass = Q32::one();
    *out_mass = m;
    return Status{};
  }
  if (total < k_min_body_mass || total > k_max_body_mass) {
    return make_status(StatusCode::invalid_argument, what + ": the mass " + q32_text(total) +
                                                         " kg would be outside [" + q32_text(k_min_body_mass) + ", " +
                                                         q32_text(k_max_body_mass) + "] kg");
  }
  // Centre: Σ m·c exactly in 128 bits (Q64.64), one rounded division by m.
  wide::U128 sx{}, sy{};
  for (int32_t k = 0; k < count; ++k) {
    sx = wide::add(sx, wide::mul_s64(items[k].mass.raw, items[k].center.x.raw));
    sy = wide::add(sy, wide::mul_s64(items[k].mass.raw, items[k].center.y.raw));
  }
  const auto divide = [&](wide::U128 n) {
    const bool negative = wide::is_negative(n);
    const wide::U128 mag = wide::abs_u(n);
    const uint64_t d = static_cast<uint64_t>(total.raw);
    // A weighted mean of centres within ±k_max_shape_size: the quotient fits.
    TANDEM_ASSERT(mag.hi < d);
    uint64_t rem = 0;
    uint64_t q = wide::div_u128_u64(mag, d, &rem);
    if (rem >= d - rem) ++q;
    const int64_t r = static_cast<int64_t>(q);
    return Q32::from_raw(negative ? -r : r);
  };
  m.local_center = {divide(sx), divide(sy)};
  // Inertia about the centre: Σ (Iᵢ + mᵢ·|cᵢ − c|²), quiet, then checked.
  Q32 inertia;
  for (int32_t k = 0; k < count; ++k) {
    const Vec2 d{items[k].center.x - m.local_center.x, items[k].center.y - m.local_center.y};
    bool overflow = false;
    const Q32 dd = Q32::from_raw(wide::round_shift_saturate(
        wide::add(wide::mul_s64(d.x.raw, d.x.raw), wide::mul_s64(d.y.raw, d.y.raw)), 32, &overflow));
    inertia = add_quiet(inertia, add_quiet(items[k].rotational_inertia, mul_quiet(items[k].mass, dd)));
  }
  if (inertia > k_max_rotational_inertia) {
    return make_status(StatusCode::invalid_argument, what + ": the rotational inertia " + q32_text(inertia) +
                                                         " kg·m² would exceed " + q32_text(k_max_rotational_inertia) +
                                                         " kg·m²");
  }
  m.mass = total;
  m.rotational_inertia = inertia;
  m.inv_mass = Q32::one() / total;  // total ≥ k_min_body_mass: ≤ 1000, no saturation
  // An inertia of 1 or 2 raw units has no representable inverse; it counts as none.
  m.inv_inertia = (!fixed_rotation && inertia.raw > 2) ? Q32::one() / inertia : Q32::zero();
  *out_mass = m;
  return Status{};
}

void apply_body_mass(World* w, int32_t index, const BodyMass& m) {
  Body& body = body_at(w, index);
  BodySim& sim = sim_at(w, index);
  body.mass = m.mass;
  body.rotational_inertia = m.rotational_inertia;
  sim.inv_mass = m.inv_mass;
  sim.inv_inertia = m.inv_inertia;
  const Vec2 old_center = sim.center;
  sim.local_center = m.local_center;
  sim.center = transform_point(sim.transform, sim.local_center);
  if (body.type != BodyType::static_body) {
    // The body's motion is unchanged: the new centre moves with v + ω × Δc.
    const Vec2 dc = sim.center - old_center;
    const Vec2 dv{mul_quiet(-sim.angular_velocity, dc.y), mul_quiet(sim.angular_velocity, dc.x)};
    sim.linear_velocity = clamp_speed(
        Vec2{add_quiet(sim.linear_velocity.x, dv.x), add_quiet(sim.linear_velocity.y, dv.y)}, w->def.max_linear_speed);
  }
  if (body.fixed_rotation) sim.angular_velocity = Q32::zero();
  compute_body_extents(*w, index, sim.local_center, &body.min_extent, &body.max_extent);
}

Status update_body_mass(World* w, int32_t index, const char* function) {
  const Body& body = body_at(w, index);
  BodyMass m{};
  Status s = compute_body_mass(*w, index, body.type, body.fixed_rotation, k_null_index, Q32::zero(), nullptr,
                               std::string(function) + ": " + describe(make_body_id(*w, index)), &m);
  if (s.ok()) {
    apply_body_mass(w, index, m);
    // Shapes added, removed or re-massed: wake the body and what touches it
    // (a lone sleeper stays asleep, so scenes can be built asleep; island.h).
    wake_body_and_touching(w, index, false);
  }
  return s;
}

Status check_body_mass_with(const World& w, int32_t body_index, int32_t replace_shape, Q32 replace_density,
                            const MassData* extra, const std::string& what) {
  const Body& body = body_at(&w, body_index);
  BodyMass m{};
  return compute_body_mass(w, body_index, body.type, body.fixed_rotation, replace_shape, replace_density, extra, what,
                           &m);
}

void update_body_shape_bounds(World* w, int32_t body_index) {
  broad_phase_mark_stale(w);  // queries re-sync (broad_phase.h)
  compute_body_shape_bounds(w, body_index);
}

void compute_body_shape_bounds(World* w, int32_t body_index) {
  const Transform xf = sim_at(w, body_index).transform;
  for (int32_t s = body_at(w, body_index).head_shape; s != k_null_index;
       s = w->shapes[static_cast<size_t>(s)].next_shape) {
    w->shapes[static_cast<size_t>(s)].aabb = compute_shape_aabb(w->shape_geometries[static_cast<size_t>(s)], xf);
  }
}

// ---------------------------------------------------------------------------
// Creation and destruction
// ---------------------------------------------------------------------------

Result<BodyId> create_body(WorldId world_id, const BodyDef& def) {
  const char* fn = "create_body";
  Result<BodyId> result;
  World* w = nullptr;
  Status& s = result.status;
  s = resolve_world(world_id, fn, true, &w);
  if (!s.ok()) return result;
  if (def.internal_cookie != k_def_cookie) {
    s = make_status(StatusCode::invalid_definition, "create_body: the BodyDef was not made by default_body_def()");
    return result;
  }
  if (!valid_type(def.type)) {
    s = invalid_argument(fn, "type", std::to_string(static_cast<int32_t>(def.type)) + " is not a body type");
    return result;
  }
  if (!check_in_bounds(*w, fn, "position", def.position, &s)) return result;
  if (def.rotation.c == Q32::zero() && def.rotation.s == Q32::zero()) {
    s = invalid_argument(fn, "rotation", "(0, 0) is not a rotation");
    return result;
  }
  const bool is_static = def.type == BodyType::static_body;
  if (is_static && (def.linear_velocity != Vec2{} || def.angular_velocity != Q32::zero())) {
    s = invalid_argument(fn, "velocity", "must be zero for a static body");
    return result;
  }
  if (def.fixed_rotation && def.angular_velocity != Q32::zero()) {
    s = invalid_argument(fn, "angular_velocity", "must be zero for a body with fixed rotation");
    return result;
  }
  if (!check_speed(
          *w, fn, [&] { return "linear_velocity " + format_vec2(def.linear_velocity) + " m/s"; }, def.linear_velocity,
          &s) ||
      !check_angular_speed(fn, "angular_velocity", def.angular_velocity, &s) ||
      !check_closed(fn, "linear_damping", def.linear_damping, Q32::zero(), k_max_damping, "1/s", &s) ||
      !check_closed(fn, "angular_damping", def.angular_damping, Q32::zero(), k_max_damping, "1/s", &s) ||
      !check_closed(fn, "gravity_scale", def.gravity_scale, -k_max_gravity_scale, k_max_gravity_scale, "", &s)) {
    return result;
  }
  if (w->body_pool.alive_count >= k_max_bodies) {
    s = make_status(StatusCode::capacity_exceeded,
                    "create_body: " + describe(world_id) + " already has " + std::to_string(k_max_bodies) + " bodies");
    return result;
  }

  const int32_t index = id_pool_allocate(&w->body_pool);
  if (static_cast<size_t>(index) >= w->bodies.size()) {
    w->bodies.resize(static_cast<size_t>(index) + 1);
    w->body_sims.resize(static_cast<size_t>(index) + 1);
  }
  Body& body = body_at(w, index);
  body = Body{};
  body.type = def.type;
  body.user_data = def.user_data;
  body.enable_sleep = def.enable_sleep;
  body.awake = def.is_awake;
  body.enabled = def.is_enabled;
  body.fixed_rotation = def.fixed_rotation;
  body.bullet = def.is_bullet;
  BodySim& sim = sim_at(w, index);
  sim = BodySim{};
  sim.transform = {def.position, rot_normalize(def.rotation)};
  sim.center = def.position;
  sim.linear_velocity = def.linear_velocity;
  sim.angular_velocity = def.angular_velocity;
  sim.linear_damping = def.linear_damping;
  sim.angular_damping = def.angular_damping;
  sim.gravity_scale = def.gravity_scale;
  if (!body.awake) {
    sim.linear_velocity = {};
    sim.angular_velocity = Q32::zero();
  }
  const Status mass = update_body_mass(w, index, fn);  // no shapes yet: cannot fail
  TANDEM_ASSERT(mass.ok());
  if (!body.awake && body.type != BodyType::static_body) put_body_to_sleep(w, index);
  result.value = make_body_id(*w, index);
  return result;
}

Status destroy_body(BodyId id) {
  World* w = nullptr;
  int32_t i = 0;
  Status s = resolve_body(id, "destroy_body", true, WorldId{}, &w, &i);
  if (!s.ok()) return s;
  // Whatever touched it (and its own island) wakes: its support is gone.
  wake_body_and_touching(w, i, true);
  destroy_body_joints(w, i);  // its joints go with it, reported at the next step (joint.cpp)
  // Shapes go first, in ascending shape index.
  while (body_at(w, i).head_shape != k_null_index) remove_shape(w, body_at(w, i).head_shape);
  body_at(w, i) = Body{};
  sim_at(w, i) = BodySim{};
  id_pool_free(&w->body_pool, i);
  return s;
}

bool body_is_valid(BodyId id) {
  World* w = nullptr;
  int32_t i = 0;
  return find_body(id, &w, &i);
}

Status body_check(BodyId id, WorldId expected_world) {
  World* w = nullptr;
  int32_t i = 0;
  return resolve_body(id, "body_check", false, expected_world, &w, &i);
}

WorldId body_world(BodyId id) { return id.world; }

// ---------------------------------------------------------------------------
// Type, pose, velocity
// ---------------------------------------------------------------------------

BodyType body_type(BodyId id) {
  return get_body(id, BodyType::static_body, [](const World& w, int32_t i) { return body_at(&w, i).type; });
}

Status body_set_type(BodyId id, BodyType type) {
  const char* fn = "body_set_type";
  return set_body(id, fn, [&](World* w, int32_t i) {
    if (!valid_type(type)) {
      return invalid_argument(fn, "type", std::to_string(static_cast<int32_t>(type)) + " is not a body type");
    }
    Body& body = body_at(w, i);
    if (body.type == type) return Status{};
    BodyMass m{};
    Status s = compute_body_mass(*w, i, type, body.fixed_rotation, k_null_index, Q32::zero(), nullptr,
                                 std::string(fn) + ": " + describe(id) + " as " + type_name(type), &m);
    if (!s.ok()) return s;
    BodySim& sim = sim_at(w, i);
    wake_body_and_touching(w, i, true);  // its island and what touches it, under the old type
    body.type = type;
    sim.force = {};
    sim.torque = Q32::zero();
    if (type == BodyType::static_body) {
      sim.linear_velocity = {};
      sim.angular_velocity = Q32::zero();
    }
    apply_body_mass(w, i, m);
    wake_body_island(w, i);
    return s;
  });
}

Vec2 body_position(BodyId id) {
  return get_body(id, Vec2{}, [](const World& w, int32_t i) { return sim_at(&w, i).transform.p; });
}

Rot body_rotation(BodyId id) {
  return get_body(id, Rot{}, [](const World& w, int32_t i) { return sim_at(&w, i).transform.q; });
}

Q32 body_angle(BodyId id) {
  return get_body(id, Q32{}, [](const World& w, int32_t i) { return rot_angle(sim_at(&w, i).transform.q); });
}

Transform body_transform(BodyId id) {
  return get_body(id, Transform{}, [](const World& w, int32_t i) { return sim_at(&w, i).transform; });
}

Status body_set_transform(BodyId id, Vec2 position, Rot rotation) {
  const char* fn = "body_set_transform";
  return set_body(id, fn, [&](World* w, int32_t i) {
    Status s;
    if (!check_in_bounds(*w, fn, "position", position, &s)) return s;
    if (rotation.c == Q32::zero() && rotation.s == Q32::zero()) {
      return invalid_argument(fn, "rotation", "(0, 0) is not a rotation");
    }
    BodySim& sim = sim_at(w, i);
    sim.transform = {position, rot_normalize(rotation)};
    sim.center = transform_point(sim.transform, sim.local_center);
    update_body_shape_bounds(w, i);
    wake_body_and_touching(w, i, true);
    wake_overlapping_sleepers(w, i);
    return s;
  });
}

Vec2 body_world_center(BodyId id) {
  return get_body(id, Vec2{}, [](const World& w, int32_t i) { return sim_at(&w, i).center; });
}

Vec2 body_local_center(BodyId id) {
  return get_body(id, Vec2{}, [](const World& w, int32_t i) { return sim_at(&w, i).local_center; });
}

Vec2 body_linear_velocity(BodyId id) {
  return get_body(id, Vec2{}, [](const World& w, int32_t i) { return sim_at(&w, i).linear_velocity; });
}

Status body_set_linear_velocity(BodyId id, Vec2 velocity) {
  const char* fn = "body_set_linear_velocity";
  return set_body(id, fn, [&](World* w, int32_t i) {
    Status s;
    Body& body = body_at(w, i);
    if (velocity == Vec2{}) {
      if (body.type != BodyType::static_body) sim_at(w, i).linear_velocity = velocity;
      return s;
    }
    if (body.type == BodyType::static_body) {
      return invalid_argument(fn, describe(id), "is static; a static body cannot move");
    }
    if (!check_speed(*w, fn, [&] { return "velocity " + format_vec2(velocity) + " m/s"; }, velocity, &s)) return s;
    sim_at(w, i).linear_velocity = velocity;
    wake_body_island(w, i);
    return s;
  });
}

Q32 body_angular_velocity(BodyId id) {
  return get_body(id, Q32{}, [](const World& w, int32_t i) { return sim_at(&w, i).angular_velocity; });
}

Status body_set_angular_velocity(BodyId id, Q32 angular_velocity) {
  const char* fn = "body_set_angular_velocity";
  return set_body(id, fn, [&](World* w, int32_t i) {
    Status s;
    Body& body = body_at(w, i);
    if (angular_velocity == Q32::zero()) {
      if (body.type != BodyType::static_body) sim_at(w, i).angular_velocity = angular_velocity;
      return s;
    }
    if (body.type == BodyType::static_body) {
      return invalid_argument(fn, describe(id), "is static; a static body cannot move");
    }
    if (body.fixed_rotation) return invalid_argument(fn, describe(id), "has fixed rotation");
    if (!check_angular_speed(fn, "angular velocity", angular_velocity, &s)) return s;
    sim_at(w, i).angular_velocity = angular_velocity;
    wake_body_island(w, i);
    return s;
  });
}

Vec2 body_point_velocity(BodyId id, Vec2 world_point) {
  return get_body(id, Vec2{}, [&](const World& w, int32_t i) {
    const BodySim& sim = sim_at(&w, i);
    const Vec2 r{add_quiet(world_point.x, -sim.center.x), add_quiet(world_point.y, -sim.center.y)};
    return Vec2{add_quiet(sim.linear_velocity.x, mul_quiet(-sim.angular_velocity, r.y)),
                add_quiet(sim.linear_velocity.y, mul_quiet(sim.angular_velocity, r.x))};
  });
}

// ---------------------------------------------------------------------------
// Mass
// ---------------------------------------------------------------------------

Q32 body_mass(BodyId id) {
  return get_body(id, Q32{}, [](const World& w, int32_t i) { return body_at(&w, i).mass; });
}

Q32 body_rotational_inertia(BodyId id) {
  return get_body(id, Q32{}, [](const World& w, int32_t i) { return body_at(&w, i).rotational_inertia; });
}

MassData body_mass_data(BodyId id) {
  return get_body(id, MassData{}, [](const World& w, int32_t i) {
    MassData md{};
    md.mass = body_at(&w, i).mass;
    md.center = sim_at(&w, i).local_center;
    md.rotational_inertia = body_at(&w, i).rotational_inertia;
    return md;
  });
}

// ---------------------------------------------------------------------------
// Damping, gravity scale, flags
// ---------------------------------------------------------------------------

Q32 body_linear_damping(BodyId id) {
  return get_body(id, Q32{}, [](const World& w, int32_t i) { return sim_at(&w, i).linear_damping; });
}

Status body_set_linear_damping(BodyId id, Q32 damping) {
  const char* fn = "body_set_linear_damping";
  return set_body(id, fn, [&](World* w, int32_t i) {
    Status s;
    if (check_closed(fn, "linear damping", damping, Q32::zero(), k_max_damping, "1/s", &s)) {
      sim_at(w, i).linear_damping = damping;
    }
    return s;
  });
}

Q32 body_angular_damping(BodyId id) {
  return get_body(id, Q32{}, [](const World& w, int32_t i) { return sim_at(&w, i).angular_damping; });
}

Status body_set_angular_damping(BodyId id, Q32 damping) {
  const char* fn = "body_set_angular_damping";
  return set_body(id, fn, [&](World* w, int32_t i) {
    Status s;
    if (check_closed(fn, "angular damping", damping, Q32::zero(), k_max_damping, "1/s", &s)) {
      sim_at(w, i).angular_damping = damping;
    }
    return s;
  });
}

Q32 body_gravity_scale(BodyId id) {
  return get_body(id, Q32{}, [](const World& w, int32_t i) { return sim_at(&w, i).gravity_scale; });
}

Status body_set_gravity_scale(BodyId id, Q32 scale) {
  const char* fn = "body_set_gravity_scale";
  return set_body(id, fn, [&](World* w, int32_t i) {
    Status s;
    if (check_closed(fn, "gravity scale", scale, -k_max_gravity_scale, k_max_gravity_scale, "", &s)) {
      sim_at(w, i).gravity_scale = scale;
    }
    return s;
  });
}

bool body_is_fixed_rotation(BodyId id) {
  return get_body(id, false, [](const World& w, int32_t i) { return body_at(&w, i).fixed_rotation; });
}

Status body_set_fixed_rotation(BodyId id, bool fixed) {
  const char* fn = "body_set_fixed_rotation";
  return set_body(id, fn, [&](World* w, int32_t i) {
    Body& body = body_at(w, i);
    if (body.fixed_rotation == fixed) return Status{};
    BodyMass m{};
    Status s = compute_body_mass(*w, i, body.type, fixed, k_null_index, Q32::zero(), nullptr,
                                 std::string(fn) + ": " + describe(id), &m);
    if (!s.ok()) return s;
    body.fixed_rotation = fixed;
    if (fixed) sim_at(w, i).angular_velocity = Q32::zero();
    apply_body_mass(w, i, m);
    return s;
  });
}

bool body_is_bullet(BodyId id) {
  return get_body(id, false, [](const World& w, int32_t i) { return body_at(&w, i).bullet; });
}

Status body_set_bullet(BodyId id, bool bullet) {
  return set_body(id, "body_set_bullet", [&](World* w, int32_t i) {
    body_at(w, i).bullet = bullet;
    return Status{};
  });
}

bool body_is_enabled(BodyId id) {
  return get_body(id, false, [](const World& w, int32_t i) { return body_at(&w, i).enabled; });
}

Status body_set_enabled(BodyId id, bool enabled) {
  return set_body(id, "body_set_enabled", [&](World* w, int32_t i) {
    Body& body = body_at(w, i);
    if (enabled) {
      if (!body.enabled) {
        body.enabled = true;
        update_body_shape_bounds(w, i);
        wake_body_island(w, i);
      }
      return Status{};
    }
    if (body.enabled) wake_body_and_touching(w, i, true);
    body_at(w, i).enabled = false;
    broad_phase_mark_stale(w);  // queries re-sync (broad_phase.h)
    sim_at(w, i).force = {};
    sim_at(w, i).torque = Q32::zero();
    return Status{};
  });
}

bool body_is_awake(BodyId id) {
  return get_body(id, false, [](const World& w, int32_t i) {
    const Body& b = body_at(&w, i);
    return b.type != BodyType::static_body && b.awake;
  });
}

Status body_set_awake(BodyId id, bool awake) {
  return set_body(id, "body_set_awake", [&](World* w, int32_t i) {
    Body& body = body_at(w, i);
    if (body.type == BodyType::static_body) return Status{};
    if (awake) {
      wake_body_island(w, i);
    } else {
      put_body_to_sleep(w, i);  // an island of its own (island.h)
    }
    return Status{};
  });
}

bool body_is_sleep_enabled(BodyId id) {
  return get_body(id, false, [](const World& w, int32_t i) { return body_at(&w, i).enable_sleep; });
}

Status body_enable_sleep(BodyId id, bool enable) {
  return set_body(id, "body_enable_sleep", [&](World* w, int32_t i) {
    Body& body = body_at(w, i);
    body.enable_sleep = enable;
    if (!enable) wake_body_island(w, i);
    return Status{};
  });
}

uint64_t body_user_data(BodyId id) {
  return get_body(id, uint64_t{0}, [](const World& w, int32_t i) { return body_at(&w, i).user_data; });
}

Status body_set_user_data(BodyId id, uint64_t user_data) {
  return set_body(id, "body_set_user_data", [&](World* w, int32_t i) {
    body_at(w, i).user_data = user_data;
    return Status{};
  });
}

// ---------------------------------------------------------------------------
// Frames and shapes
// ---------------------------------------------------------------------------

Vec2 body_world_point(BodyId id, Vec2 local_point) {
  return get_body(id, Vec2{},
                  [&](const World& w, int32_t i) { return transform_point(sim_at(&w, i).transform, local_point); });
}

Vec2 body_local_point(BodyId id, Vec2 world_point) {
  return get_body(id, Vec2{},
                  [&](const World& w, int32_t i) { return inv_transform_point(sim_at(&w, i).transform, world_point); });
}

Vec2 body_world_vector(BodyId id, Vec2 local_vector) {
  return get_body(id, Vec2{}, [&](const World& w, int32_t i) { return rotate(sim_at(&w, i).transform.q, local_vector); });
}

Vec2 body_local_vector(BodyId id, Vec2 world_vector) {
  return get_body(id, Vec2{},
                  [&](const World& w, int32_t i) { return inv_rotate(sim_at(&w, i).transform.q, world_vector); });
}

int32_t body_shape_count(BodyId id) {
  return get_body(id, int32_t{0}, [](const World& w, int32_t i) { return body_at(&w, i).shape_count; });
}

int32_t body_shapes(BodyId id, ShapeId* out_ids, int32_t capacity) {
  return get_body(id, int32_t{0}, [&](const World& w, int32_t i) {
    int32_t n = 0;
    for (int32_t s = body_at(&w, i).head_shape; s != k_null_index; s = w.shapes[static_cast<size_t>(s)].next_shape) {
      if (n < capacity && out_ids != nullptr) out_ids[n] = make_shape_id(w, s);
      ++n;
    }
    return n;
  });
}

}  // namespace tandem
