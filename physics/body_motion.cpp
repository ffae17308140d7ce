// body_motion.cpp — forces and impulses on bodies: body_apply_force,
// body_apply_torque, body_apply_linear_impulse and their variants (the rest of
// the body API is in body.cpp).
//
// Like every mutating body function, each resolves the handle, checks the
// result of the change with quiet (non-faulting) arithmetic against the
// documented limits (accumulated force and torque, the accelerations they
// give, the velocities an impulse gives) and only then writes, so a refused
// call leaves the world unchanged. A call that succeeds builds no text.
#include "physics/body.h"
#include "physics/body_checks.h"
#include "physics/island.h"
#include "physics/world.h"

namespace tandem {

using namespace body_checks;

namespace {

/// The shared path of the force functions. `at_point` false: at the centre.
Status apply_force_impl(BodyId id, const char* function, Vec2 force, Vec2 point, bool at_point, bool wake_body) {
  World* w = nullptr;
  int32_t i = 0;
  Status s = resolve_body(id, function, true, WorldId{}, &w, &i);
  if (!s.ok()) return s;
  Body& body = body_at(w, i);
  BodySim& sim = sim_at(w, i);
  if (body.type != BodyType::dynamic_body || !body.enabled || (!body.awake && !wake_body)) return s;
  if (at_point && !check_in_bounds(*w, function, "point", point, &s)) return s;
  const Vec2 f{add_quiet(sim.force.x, force.x), add_quiet(sim.force.y, force.y)};
  if (!check_closed(function, [&] { return describe(id) + " accumulated force x"; },
                    f.x, -k_max_force, k_max_force, "N", &s) ||
      !check_closed(function, [&] { return describe(id) + " accumulated force y"; },
                    f.y, -k_max_force, k_max_force, "N", &s)) {
    return s;
  }
  Q32 torque = sim.torque;
  if (at_point) {
    const Vec2 r{point.x - sim.center.x, point.y - sim.center.y};  // both inside ±1e6 m: no saturation
    torque = add_quiet(torque, cross_quiet(r, force));
    if (!check_closed(function, [&] { return describe(id) + " accumulated torque"; },
                    torque, -k_max_torque, k_max_torque, "N·m",
                      &s)) {
      return s;
    }
  }
  const Q32 ax = mul_quiet(sim.inv_mass, f.x), ay = mul_quiet(sim.inv_mass, f.y);
  if (!check_closed(function, [&] { return describe(id) + " acceleration x"; },
                    ax, -k_max_linear_acceleration,
                    k_max_linear_acceleration, "m/s²", &s) ||
      !check_closed(function, [&] { return describe(id) + " acceleration y"; },
                    ay, -k_max_linear_acceleration,
                    k_max_linear_acceleration, "m/s²", &s)) {
    return s;
  }
  const Q32 alpha = mul_quiet(sim.inv_inertia, torque);
  if (!check_closed(function, [&] { return describe(id) + " angular acceleration"; },
                    alpha, -k_max_angular_acceleration,
                    k_max_angular_acceleration, "rad/s²", &s)) {
    return s;
  }
  sim.force = f;
  sim.torque = torque;
  wake_body_island(w, i);
  return s;
}

/// The shared path of the impulse functions.
Status apply_impulse_impl(BodyId id, const char* function, Vec2 impulse, Q32 angular_impulse, Vec2 point,
                          bool at_point, bool wake_body) {
  World* w = nullptr;
  int32_t i = 0;
  Status s = resolve_body(id, function, true, WorldId{}, &w, &i);
  if (!s.ok()) return s;
  Body& body = body_at(w, i);
  BodySim& sim = sim_at(w, i);
  if (body.type != BodyType::dynamic_body || !body.enabled || (!body.awake && !wake_body)) return s;
  if (at_point && !check_in_bounds(*w, function, "point", point, &s)) return s;
  const Vec2 v{add_quiet(sim.linear_velocity.x, mul_quiet(sim.inv_mass, impulse.x)),
               add_quiet(sim.linear_velocity.y, mul_quiet(sim.inv_mass, impulse.y))};
  if (!check_speed(*w, function, [&] { return "the velocity this impulse gives " + describe(id); }, v, &s)) {
    return s;
  }
  Q32 angular = angular_impulse;
  if (at_point) {
    const Vec2 r{point.x - sim.center.x, point.y - sim.center.y};
    angular = cross_quiet(r, impulse);
  }
  const Q32 omega = add_quiet(sim.angular_velocity, mul_quiet(sim.inv_inertia, angular));
  if (!check_angular_speed(
          function, [&] { return "the angular velocity this impulse gives " + describe(id); }, omega, &s)) {
    return s;
  }
  sim.linear_velocity = v;
  sim.angular_velocity = omega;
  wake_body_island(w, i);
  return s;
}

}  // namespace

// ---------------------------------------------------------------------------
// Forces and impulses
// ---------------------------------------------------------------------------

Status body_apply_force(BodyId id, Vec2 force, Vec2 world_point, bool wake_body) {
  return apply_force_impl(id, "body_apply_force", force, world_point, true, wake_body);
}

Status body_apply_force_to_center(BodyId id, Vec2 force, bool wake_body) {
  return apply_force_impl(id, "body_apply_force_to_center", force, Vec2{}, false, wake_body);
}

Status body_apply_torque(BodyId id, Q32 torque, bool wake_body) {
  const char* fn = "body_apply_torque";
  World* w = nullptr;
  int32_t i = 0;
  Status s = resolve_body(id, fn, true, WorldId{}, &w, &i);
  if (!s.ok()) return s;
  Body& body = body_at(w, i);
  BodySim& sim = sim_at(w, i);
  if (body.type != BodyType::dynamic_body || !body.enabled || (!body.awake && !wake_body)) return s;
  const Q32 t = add_quiet(sim.torque, torque);
  if (!check_closed(fn, [&] { return describe(id) + " accumulated torque"; },
                    t, -k_max_torque, k_max_torque, "N·m", &s)) return s;
  const Q32 alpha = mul_quiet(sim.inv_inertia, t);
  if (!check_closed(fn, [&] { return describe(id) + " angular acceleration"; },
                    alpha, -k_max_angular_acceleration,
                    k_max_angular_acceleration, "rad/s²", &s)) {
    return s;
  }
  sim.torque = t;
  wake_body_island(w, i);
  return s;
}

Status body_apply_linear_impulse(BodyId id, Vec2 impulse, Vec2 world_point, bool wake_body) {
  return apply_impulse_impl(id, "body_apply_linear_impulse", impulse, Q32::zero(), world_point, true, wake_body);
}

Status body_apply_linear_impulse_to_center(BodyId id, Vec2 impulse, bool wake_body) {
  return apply_impulse_impl(id, "body_apply_linear_impulse_to_center", impulse, Q32::zero(), Vec2{}, false,
                            wake_body);
}

Status body_apply_angular_impulse(BodyId id, Q32 impulse, bool wake_body) {
  return apply_impulse_impl(id, "body_apply_angular_impulse", Vec2{}, impulse, Vec2{}, false, wake_body);
}

}  // namespace tandem
