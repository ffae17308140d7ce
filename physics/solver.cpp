// solver.cpp — the body stages of the step: prepare, integrate velocities,
// integrate positions, finalize; the contact stages forward to contact.cpp
// and contact_solver.cpp.
//
// Integration is symplectic Euler per sub-step of h = dt/n seconds:
//
//   v ← v·fᵥ + Δv      fᵥ = 1/(1 + h·c_linear),  Δv = h·(s·g + F·(1/m))
//   ω ← ω·f_ω + Δω     f_ω = 1/(1 + h·c_angular), Δω = h·(τ·(1/I))
//   clamp |v| ≤ max linear speed, |ω| ≤ max angular speed (StepContext)
//   (contact and joint solves)
//   clamp again        (integrate positions: nothing moves faster)
//   c ← c + h·v        (the centre of mass)
//   q ← integrate_rotation(q, h·ω)   (skipped when ω = 0, so a body at rest
//                                     keeps its rotation bit for bit)
//
// Rotation: integrate_rotation (fixed/vec2.h) turns q by atan(h·ω) and
// leaves a length error of about 0.42·(h·ω)⁸, which does not accumulate. Up
// to |h·ω| = 1/16 rad per sub-step (15 rad/s at 60 Hz and 4 sub-steps) that
// is below one raw unit and the angle is 0.13 % short at most — the same
// first-order update floating-point engines use. Faster spins (up to the clamp of
// k_max_rotation_per_sub_step = π/16) take the exact path instead:
// rot_normalize(rot_from_angle(h·ω)·q), a sine, a cosine, a root and two
// divides, paid only by bodies spinning that fast.
//
// Exact formulation (what tests reproduce bit for bit): each named product
// is one Q32 multiplication (rounded to nearest, ties away from zero), each
// quotient one Q32 division, sums are exact. fᵥ, f_ω, Δv and Δω are computed
// once per step in prepare_bodies (forces, gravity and damping are constant
// over the step); a damping of 0 gives a factor of exactly 1, and
// multiplying by 1 is exact. Only dynamic bodies take gravity, forces and
// damping; a kinematic body keeps its velocity (up to the speed clamps).
// Damping is the implicit 1/(1 + h·c) form: unconditionally stable and never
// reverses a velocity, for any h·c ≥ 0.
//
// F·(1/m) and τ·(1/I) are computed with quiet saturation and clamped to
// k_max_linear_acceleration / k_max_angular_acceleration: the API refuses
// larger forces, but a body's mass may have changed since the force was
// applied. Every other product here is bounded by the limits (|s·g| ≤ 1e6,
// |Δv| ≤ 2e6 m/s, |v| before the clamp ≤ 2.1e6 m/s), so nothing saturates.
//
// The speed clamp decides |v| > max exactly on 128-bit squares and then
// scales v by max/|v| (one rounded division, two rounded products), so the
// clamped speed is within a few raw units of the maximum. It runs where
// velocities are integrated, again before positions are integrated and when
// finalize stores the velocities (there a pre-test on the raw magnitudes and
// an out-of-line clamp: callgrind, circles-16k 43.56 → 45.22 M instructions
// per step, pyramid-100 231.27 → 231.82 M): the contact and joint solves run
// after the first clamp and nothing else bounds what they add. Without the
// later clamps, joints fighting each other or a contact drove bodies to
// 10^4-10^8 m/s, moved them that fast and stored it, beyond the 4 × limits
// world_restore accepts, so a rollback could not restore that step
// (random-world stress with joint inputs, known issue 8: 51 → 17 of seeds
// 1-1,000 together with the joints' impulse bound). Changed the golden
// chains random_mix, joints_ragdolls and joints_bridge_chain (2026-11-29),
// where a solve leaves a limb or a small body above 100 rad/s.
//
// Workers (task.h): integration and finalize are per body, each body's work
// reads and writes only its own records (finalize: its sim, its body's
// enabled flag, its own shapes' bounds), so they run in blocks of
// k_body_block solver bodies on any thread in any order. The only shared
// effect, the left-bounds step flag, is gathered per block and OR-ed in block
// order.
#include "physics/fast_math.h"
#include "physics/world.h"

namespace tandem {

namespace {

/// Solver bodies per block of the parallel body stages (fixed: block
/// boundaries never depend on the worker count).
constexpr int32_t k_body_block = 64;

/// Largest per-sub-step turn taken by the polynomial path, radians (1/16).
constexpr Q32 k_small_rotation = Q32::from_raw(int64_t{1} << 28);

/// vec2.h's integrate_rotation (the first-order turn and two
/// rot_normalize_fast steps) written with fast_math.h's operations: the same
/// rounding and the same saturation as the checked operators for every
/// input (fast_math.h), minus the fault report, so the same bits in every
/// build (debug, sanitizer and portable builds use the checked operators).
inline Rot integrate_rotation_fast(Rot q, Q32 delta_angle) {
  const auto normalize = [](Rot r) {
    const Q32 m = fast::sum2(r.c, r.c, r.s, r.s);
    const Q32 k = fast::sub(Q32::from_int(3), m) / 2;
    return Rot{fast::mul(r.c, k), fast::mul(r.s, k)};
  };
  const Rot r{fast::sub(q.c, fast::mul(delta_angle, q.s)), fast::add(q.s, fast::mul(delta_angle, q.c))};
  return normalize(normalize(r));
}

/// v scaled down to at most max_speed (see the file comment).
inline Vec2 clamp_linear_speed(Vec2 v, Q32 max_speed) {
  if (!length_exceeds(v, max_speed)) return v;
  return v * (max_speed / length(v));
}

/// Whether a body's speeds may exceed the limits after the solves:
/// |v.x| + |v.y| > max_v (the same decision as abs(v.x) + abs(v.y) > max_v,
/// on unsigned raw magnitudes: that sum saturates only far above any limit)
/// or |ω| > max_w. The cheap pre-test of the clamps after the solves.
inline bool speeds_exceeded(const BodyState& s, Q32 max_v, Q32 max_w) {
  const uint64_t x = detail::magnitude(s.linear_velocity.x.raw), y = detail::magnitude(s.linear_velocity.y.raw);
  const uint64_t m = static_cast<uint64_t>(max_v.raw);
  return x > m || y > m - x || detail::magnitude(s.angular_velocity.raw) > static_cast<uint64_t>(max_w.raw);
}

/// The speed clamps (file comment), out of line: rarely taken.
[[gnu::cold, gnu::noinline]] void clamp_speeds(BodyState* s, Q32 max_v, Q32 max_w) {
  if (abs(s->linear_velocity.x) + abs(s->linear_velocity.y) > max_v) {
    s->linear_velocity = clamp_linear_speed(s->linear_velocity, max_v);
  }
  s->angular_velocity = clamp(s->angular_velocity, -max_w, max_w);
}

/// 1/(1 + h·c), exactly 1 when c is 0.
inline Q32 damping_factor(Q32 h, Q32 c) {
  if (c == Q32::zero()) return Q32::one();
  return Q32::one() / (Q32::one() + h * c);  // h ≤ 1 s, c ≤ 1e4 /s: no saturation
}

}  // namespace

void stage_update_contacts(World* world, StepContext* context) {
  (void)context;
  update_contacts(world);
}

void stage_prepare_bodies(World* world, StepContext* context) {
  Arena* arena = &world->arena;
  const int32_t body_capacity = id_pool_capacity(world->body_pool);
  // Freed in reverse order by stage_finalize_bodies. solver_to_body has room
  // for every body, so one serial pass numbers the simulated ones.
  context->body_to_solver = arena_allocate_array<int32_t>(arena, body_capacity, "body_to_solver");
  context->solver_to_body = arena_allocate_array<int32_t>(arena, body_capacity, "solver_to_body");
  // Serial: the solver indices, in body order.
  int32_t n = 0;
  for (int32_t b = 0; b < body_capacity; ++b) {
    const size_t bi = static_cast<size_t>(b);
    if (!id_pool_is_alive(world->body_pool, b) || !body_is_simulated(world->bodies[bi])) {
      context->body_to_solver[bi] = k_null_index;
      continue;
    }
    context->body_to_solver[bi] = n;
    context->solver_to_body[n] = b;
    ++n;
  }
  const int32_t count = n;
  // Unwritten (arena_allocate_array_for_overwrite): the blocks below write
  // every field of both records.
  context->states = arena_allocate_array_for_overwrite<BodyState>(arena, count, "body_states");
  context->params = arena_allocate_array_for_overwrite<SolverBodyParams>(arena, count, "solver_body_params");
  context->solver_body_count = count;
  // In blocks on the workers: each solver body's state and parameters.
  const Q32 h = context->h;
  const Vec2 gravity = world->def.gravity;
  const Body* bodies = world->bodies.data();
  const BodySim* sims = world->body_sims.data();
  const int32_t* solver_to_body = context->solver_to_body;
  BodyState* states = context->states;
  SolverBodyParams* params = context->params;
  // h·(s·g + F/m) and h·τ/I of a dynamic body, each acceleration capped
  // (limits.h).
  const auto velocity_changes = [h, gravity](Q32 gravity_scale, Q32 inv_mass, Vec2 force, Q32 inv_inertia, Q32 torque,
                                             Vec2* dv, Q32* dw) {
    const Q32 max_a = k_max_linear_acceleration, max_alpha = k_max_angular_acceleration;
    const Vec2 a{gravity_scale * gravity.x + clamp(mul_quiet(inv_mass, force.x), -max_a, max_a),
                 gravity_scale * gravity.y + clamp(mul_quiet(inv_mass, force.y), -max_a, max_a)};
    *dv = h * a;
    *dw = h * clamp(mul_quiet(inv_inertia, torque), -max_alpha, max_alpha);
  };
  // Most dynamic bodies have gravity scale 1 and no force or torque: their
  // changes, computed once. They do not depend on m⁻¹ or I⁻¹ there
  // (mul_quiet(x, 0) = 0 for every x).
  Vec2 plain_dv;
  Q32 plain_dw;
  velocity_changes(Q32::one(), Q32::zero(), Vec2{}, Q32::zero(), Q32::zero(), &plain_dv, &plain_dw);
  parallel_for(context->tasks, "prepare_bodies", count, k_body_block, [=](int32_t begin, int32_t end) {
    for (int32_t i = begin; i < end; ++i) {
      const size_t bi = static_cast<size_t>(solver_to_body[i]);
      const Body& body = bodies[bi];
      const BodySim& sim = sims[bi];
      BodyState& state = states[i];
      state.linear_velocity = sim.linear_velocity;
      state.angular_velocity = sim.angular_velocity;
      state.center = sim.center;
      state.rotation = sim.transform.q;
      SolverBodyParams& p = params[i];
      p = SolverBodyParams{};
      p.inv_mass = sim.inv_mass;
      p.inv_inertia = sim.inv_inertia;
      p.linear_damping_factor = Q32::one();
      p.angular_damping_factor = Q32::one();
      if (body.type == BodyType::dynamic_body) {
        if (sim.gravity_scale == Q32::one() && sim.force == Vec2{} && sim.torque == Q32::zero()) {
          p.delta_linear_velocity = plain_dv;
          p.delta_angular_velocity = plain_dw;
        } else {
          velocity_changes(sim.gravity_scale, sim.inv_mass, sim.force, sim.inv_inertia, sim.torque,
                           &p.delta_linear_velocity, &p.delta_angular_velocity);
        }
        p.linear_damping_factor = damping_factor(h, sim.linear_damping);
        p.angular_damping_factor = damping_factor(h, sim.angular_damping);
      }
    }
  });
}

void stage_prepare_contacts(World* world, StepContext* context) {
  prepare_contact_constraints(world, context);
}

void stage_record_approach(World* world, StepContext* context) {
  (void)world;
  record_contact_approach(context);
}

void stage_integrate_velocities(World* world, StepContext* context) {
  (void)world;
  const int32_t count = context->solver_body_count;
  const Q32 max_v = context->max_linear_speed;
  const Q32 max_w = context->max_angular_speed;
  BodyState* states = context->states;
  const SolverBodyParams* params = context->params;
  parallel_for(context->tasks, "integrate_velocities", count, k_body_block, [=](int32_t begin, int32_t end) {
    for (int32_t i = begin; i < end; ++i) {
      BodyState& s = states[i];
      const SolverBodyParams& p = params[i];
      // Without damping the factor is exactly 1 and x·1 = x exactly, so
      // skipping the product changes no bit.
      Vec2 v = s.linear_velocity;
      if (p.linear_damping_factor != Q32::one()) v = {v.x * p.linear_damping_factor, v.y * p.linear_damping_factor};
      v = v + p.delta_linear_velocity;
      Q32 w = s.angular_velocity;
      if (p.angular_damping_factor != Q32::one()) w = w * p.angular_damping_factor;
      w = w + p.delta_angular_velocity;
      // |v| ≤ |v.x| + |v.y|: the 128-bit length test only where that bound
      // exceeds the limit.
      if (abs(v.x) + abs(v.y) > max_v) v = clamp_linear_speed(v, max_v);
      s.linear_velocity = v;
      s.angular_velocity = clamp(w, -max_w, max_w);
    }
  });
}

void stage_warm_start(World* world, StepContext* context) {
  (void)world;
  warm_start_contacts(context);
}

void stage_solve(World* world, StepContext* context) {
  (void)world;
  solve_contacts(context);
}

void stage_integrate_positions(World* world, StepContext* context) {
  (void)world;
  const int32_t count = context->solver_body_count;
  const Q32 h = context->h;
  const Q32 max_v = context->max_linear_speed;
  const Q32 max_w = context->max_angular_speed;
  BodyState* states = context->states;
  parallel_for(context->tasks, "integrate_positions", count, k_body_block, [=](int32_t begin, int32_t end) {
    for (int32_t i = begin; i < end; ++i) {
      BodyState& s = states[i];
      // The solves may have gone past the limits (file comment).
      if (speeds_exceeded(s, max_v, max_w)) [[unlikely]] clamp_speeds(&s, max_v, max_w);
      // fast::: the checked operators' bits (integrate_rotation_fast).
      s.center = fast::mul_add(s.center, h, s.linear_velocity);
      if (s.angular_velocity == Q32::zero()) continue;
      const Q32 delta = fast::mul(h, s.angular_velocity);
      if (abs(delta) <= k_small_rotation) {
        s.rotation = integrate_rotation_fast(s.rotation, delta);
      } else {
        // Fast spin (rare): the exact turn, then exact normalisation.
        s.rotation = rot_normalize(mul_rot(rot_from_angle(delta), s.rotation));
      }
    }
  });
}

void stage_relax(World* world, StepContext* context) {
  (void)world;
  relax_contacts(context);
}

void stage_restitution(World* world, StepContext* context) {
  // Bounces are solved inside the sub-steps (contact_solver.cpp); nothing
  // is left to do after them.
  (void)world;
  (void)context;
}

void stage_store_impulses(World* world, StepContext* context) {
  store_contact_impulses(world, context);
}

void stage_finalize_bodies(World* world, StepContext* context) {
  const int32_t count = context->solver_body_count;
  const AABB bounds = world->def.bounds;
  Arena* arena = &world->arena;
  // Per block: 1 when one of its bodies left the bounds (combined below, in
  // block order).
  const int32_t blocks = block_count_of(count, k_body_block);
  uint8_t* left_bounds = arena_allocate_array<uint8_t>(arena, blocks, "left_bounds_per_block");
  for (int32_t k = 0; k < blocks; ++k) left_bounds[k] = 0;
  // 1 per solver body whose pose changed (the move events, events.cpp).
  uint8_t* moved = arena_allocate_array<uint8_t>(arena, count, "moved_per_body");
  // Once, here: the blocks below write only their own bodies and shapes
  // (every block marking the shared flag was a data race, if a benign one).
  if (count > 0) broad_phase_mark_stale(world);
  const Q32 max_v = context->max_linear_speed;
  const Q32 max_w = context->max_angular_speed;
  parallel_for(context->tasks, "finalize_bodies", count, k_body_block, [=](int32_t begin, int32_t end) {
    for (int32_t i = begin; i < end; ++i) {
      const int32_t b = context->solver_to_body[i];
      const size_t bi = static_cast<size_t>(b);
      const BodyState& s = context->states[i];
      BodySim& sim = world->body_sims[bi];
      const Transform before = sim.transform;
      // The last relax pass may have gone past the limits (file comment).
      sim.linear_velocity = s.linear_velocity;
      sim.angular_velocity = s.angular_velocity;
      if (speeds_exceeded(s, max_v, max_w)) [[unlikely]] {
        BodyState held = s;
        clamp_speeds(&held, max_v, max_w);
        sim.linear_velocity = held.linear_velocity;
        sim.angular_velocity = held.angular_velocity;
      }
      sim.center = s.center;
      sim.transform.q = s.rotation;
      // fast::: the checked operators' bits. A centre of mass at the body
      // origin (circles, boxes) needs no rotation: rotating (0, 0) gives (0, 0).
      const Vec2 offset = sim.local_center == Vec2{} ? Vec2{} : fast::rotate(s.rotation, sim.local_center);
      sim.transform.p = fast::sub(s.center, offset);
      sim.force = {};
      sim.torque = Q32::zero();
      moved[i] = sim.transform == before ? 0 : 1;
      if (!aabb_contains_point(bounds, sim.transform.p)) {
        // Out of the world: stop simulating it before it can run out of range.
        world->bodies[bi].enabled = false;
        left_bounds[begin / k_body_block] = 1;
      }
      compute_body_shape_bounds(world, b);
    }
  });
  for (int32_t k = 0; k < blocks; ++k) {
    if (left_bounds[k] != 0) context->flags |= k_step_flag_body_left_bounds;
  }
  // Solver order is ascending body index, so the list is too.
  std::vector<int32_t>& moved_bodies = world->events.moved_bodies;
  moved_bodies.clear();
  for (int32_t i = 0; i < count; ++i) {
    if (moved[i] != 0) moved_bodies.push_back(context->solver_to_body[i]);
  }
  arena_free(arena, moved);
  arena_free(arena, left_bounds);
  arena_free(arena, context->params);
  arena_free(arena, context->states);
  arena_free(arena, context->solver_to_body);
  arena_free(arena, context->body_to_solver);
  context->params = nullptr;
  context->states = nullptr;
  context->solver_to_body = nullptr;
  context->body_to_solver = nullptr;
}

}  // namespace tandem
