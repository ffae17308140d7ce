// contact_solver.cpp — the sub-stepped soft contact solver (our own take on
// the structure of Box2D v3's soft step), with restitution solved inside the
// sub-steps ("sub-step bounce", shared/reference/restitution/README.md).
//
// PER STEP (prepare_contact_constraints): for every touching contact with a
// simulated body, in contact order, one constraint with the normal, copies of
// both inverse masses (0 for a body that is not simulated), the mixed
// friction and restitution, and per point: anchors from each centre of mass
// (fixed for the step), normal and tangent effective masses 1/k (the only
// divisions; the inner loops multiply), the anchor in each body frame for
// tracking the separation, and the warm-start impulses. The soft coefficients
// are computed once per step: contact_hertz is capped at a quarter of the
// sub-step rate, and a contact with an immovable side uses twice that
// stiffness (as Box2D v3 does).
//
// PER SUB-STEP:
//   record_approach   vn0 = relative normal velocity at each point, before
//                     gravity and forces are integrated (the bounce
//                     reference; a body resting on the ground has vn0 ≈ 0).
//   warm start        apply the accumulated impulses (a point that bounced
//                     in the previous sub-step restarts from zero).
//   solve (bias)      current separation s = (c_B + R_B·l_B − c_A − R_A·l_A)·n
//                     + adjusted separation. A point is "active" when it
//                     touches (s ≤ 0) or would within this sub-step
//                     (s + h·(vn0 + kick) < 0). An active point closing faster
//                     than the restitution threshold with restitution > 0
//                     LATCHES a bounce for this sub-step: it becomes a rigid
//                     constraint (mass scale 1, impulse scale 0, no soft push)
//                     with target vn ≥ −e·vn0, in this sub-step's solve and
//                     relax passes only. Other points: speculative (s > 0):
//                     bias s/h, rigid; touching: soft, bias max(rate·s,
//                     −push speed). Gate: a speculative point that is not
//                     about to touch may only reduce its impulse, so a
//                     secondary collision caused by another bounce in this
//                     sub-step is bounced in the next one instead of being
//                     caught inelastically.
//   integrate positions
//   relax (no bias)   rigid, bias 0 for touching points, skipping speculative
//                     points and points that were not active in this sub-step
//                     and carry no impulse. When some point latched a bounce in
//                     this sub-step, two more relax passes run over the
//                     constraints of bodies involved in a bounce (so a bounce
//                     inside a touching group settles to the elastic answer).
//                     Each point's separation computed here is stored: the
//                     poses do not change again before the next sub-step's
//                     solve, which (with the bounce relax passes) reads it
//                     instead of recomputing it (see solve_constraint_with).
// AFTER THE SUB-STEPS: no restitution pass (Box2D v3's end-of-step pass uses
// the velocity at prepare and loses a third of a dropped ball's energy); a
// point that bounced in the last sub-step stores a zero normal impulse.
//
// Friction: Coulomb, |λ_t| ≤ μ·λ_n per point, solved after the normal
// impulses of the constraint in the same pass (bias-free).
//
// Arithmetic: every product is one Q32 multiplication (nearest, ties away
// from zero); dot and cross are exact 128-bit sums rounded once. Q32.32 holds
// magnitudes below 2^31 ≈ 2.1e9.
//
// Range of the preparation (limits.h; docs/determinism.md, "Range of the
// contact preparation"). Per body side of a constraint:
//   m⁻¹ ≤ 1/k_min_body_mass = 1000 kg⁻¹ (< 2^10).
//   I⁻¹ < 2^31: body.cpp inverts any inertia of more than 2 raw units, and
//     nothing bounds I from below (a 1 g circle of 5 mm radius has I⁻¹ ≈
//     8e7; a mass-free segment adds reach but no inertia).
//   r, the anchor from the centre of mass: shapes lie within
//     k_max_shape_size = 1e4 m of the body origin and so does the centre of
//     mass, so |r| ≤ 2e4 m (< 2^15) plus the speculative margin; r×n, r×t
//     and |r|² ≈ 4e8 m² (< 2^29) are in range.
//   Unbounded: I⁻¹·(r×n) ≤ 2^46 and I⁻¹·(r×n)² ≤ 2^61 — the overflow of
//     stress seeds 55, 9, 94 (formerly known issue 4), which then spun bodies
//     to 1e7 rad/s.
// The bound: each side uses I⁻¹_c = min(I⁻¹, K/ρ²), where ρ² is the largest
// of the body's max_extent² and |r|² of the constraint's points and K =
// k_max_contact_angular_inv_mass = 64 000 kg⁻¹ (64 × the largest m⁻¹). Then
//   I⁻¹_c·(r×n)² ≤ I⁻¹_c·ρ² ≤ K = 64 000,
//   I⁻¹_c·|r×n| ≤ min(I⁻¹·ρ, K/ρ) ≤ √(I⁻¹·K) < √(2^31·2^16) < 2^24,
//   k = m⁻¹_A + m⁻¹_B + Σ I⁻¹_c·(r×n)² ≤ 2·(1000 + 64 000) < 2^17,
// and the effective mass 1/k ≥ 7.7e-6 kg keeps ≥ 15 significant bits.
// Physical meaning: a contact point never responds as lighter than 1/(m⁻¹ +
// K) ≈ 1/64 of the lightest allowed body; equivalently, for its contacts a
// body's inertia is taken as at least ρ²/K (its radius of gyration at least
// ρ/253 for a 1 kg body). A body of one solid shape never reaches the bound
// (its radius of gyration is at least 0.4 of its reach, so I⁻¹ρ² ≤ 6.25/m ≤
// 6 250 kg⁻¹ within the mass limit); a body does only when massless segments
// or chain segments, or a much lighter shape, lie far from where its mass is,
// and there the exact answer (an effective mass of I/ρ², below the Q32
// resolution of the impulses that would act on it) is not representable
// anyway. A body under
// the bound keeps every bit of I⁻¹ (the test is an exact 128-bit product),
// so ordinary scenes (the golden chains) are unchanged.
// In the sub-steps: impulses are at most (effective mass) × (relative
// speed) ≤ 1e5 kg × 2e3 m/s plus the rotational part, and a spin change per
// impulse is λ·I⁻¹_c·(r×n) ≤ |v_rel|·I⁻¹_c|r×n|/(I⁻¹_c(r×n)²) = |v_rel|/|r×n|
// for the rotation-dominated case. The in_range helpers below still saturate
// (the same bits in every build) should a crafted state go further.
//
// Workers (task.h): the loops run colour by colour, each colour in blocks of
// k_constraint_block constraints on any thread in any order, with a barrier
// between colours (run_blocks returns when the colour is done); the overflow
// colour, whose constraints may share bodies, runs serially last, as before.
// Within a colour the constraints touch disjoint movable bodies; a body that
// is not movable (kinematic: zero inverse mass and inertia) may be shared,
// but a constraint never changes it, so its write-back is skipped (the value
// it would store is the one already there). A bounce mark is an idempotent
// store of the sub-step index (a relaxed atomic store), so every order
// leaves the same marks. record_approach and store_impulses write only their
// own constraint or contact and run over all constraints at once.
//
// Lanes (contact_lanes.h): on ContactSolverPath::lanes the colours are
// transposed into blocks of k_contact_lanes constraints after prepare and
// warm start, solve, relax, record_approach and store run over the blocks
// (…_lanes kernels below: the scalar functions with the constraint index
// turned into a lane index and branches into selects); the overflow colour
// stays on the scalar functions. Same bits by construction
// (docs/determinism.md, "The contact solver's two paths").
//
// Rejected: Box2D v3's end-of-step restitution (energy loss above); holding
// a bounce target for the rest of the step (fights gravity, gains energy);
// re-normalising rotations here (solver.cpp's integrate_rotation does it
// cheaply); storing deltas from the start of the step in BodyState (it holds
// absolute poses; l_A/l_B rotate with the body instead, 4 products per side).
#include "physics/contact_solver.h"

#include <bit>

#include "physics/contact_colour.h"
#include "physics/contact_lanes.h"
#include "physics/contact_solver_internal.h"
#include "physics/fast_math.h"
#include "physics/world.h"

#ifndef TANDEM_CONTACT_LANES
#define TANDEM_CONTACT_LANES 0  // CMake sets it (option TANDEM_CONTACT_LANES)
#endif

namespace tandem {

using namespace contact_internal;

namespace {

/// The process-wide path (ContactSolverPath), read once per step by prepare.
int32_t g_contact_solver_path = TANDEM_CONTACT_LANES ? 1 : 0;

/// Calls per_constraint(cc) for every constraint, colour by colour (each
/// colour's blocks in parallel, a barrier between colours), then the
/// overflow colour serially in order (see "Workers" above). On the lanes
/// path the colours run as per_block(lanes) over their lane blocks instead
/// (k_constraint_block / k_contact_lanes blocks per task: the same block
/// boundaries for every worker count).
template <typename PerBlock, typename PerConstraint>
void for_each_by_colour(StepContext* context, const char* stage, PerBlock&& per_block, PerConstraint&& per_constraint) {
  ContactConstraint* constraints = context->constraints;
  const int32_t* offsets = context->colour_offsets;
  if (context->lanes != nullptr) {
    const int32_t* lane_offsets = context->lane_offsets;
    for (int32_t k = 0; k < k_contact_colour_count; ++k) {
      ContactLanes* first = context->lanes + lane_offsets[k];
      parallel_for(context->tasks, stage, lane_offsets[k + 1] - lane_offsets[k], k_constraint_block / k_contact_lanes,
                   [first, &per_block](int32_t begin, int32_t end) {
                     for (int32_t i = begin; i < end; ++i) per_block(first[i]);
                   });
    }
  } else {
    for (int32_t k = 0; k < k_contact_colour_count; ++k) {
      ContactConstraint* first = constraints + offsets[k];
      parallel_for(context->tasks, stage, offsets[k + 1] - offsets[k], k_constraint_block,
                   [first, &per_constraint](int32_t begin, int32_t end) {
                     for (int32_t i = begin; i < end; ++i) per_constraint(first[i]);
                   });
    }
  }
  for (int32_t i = offsets[k_contact_colour_count]; i < offsets[k_contact_colour_count + 1]; ++i) {
    per_constraint(constraints[i]);
  }
}

}  // namespace

ContactSolverPath contact_solver_path() {
  return __atomic_load_n(&g_contact_solver_path, __ATOMIC_RELAXED) != 0 ? ContactSolverPath::lanes
                                                                         : ContactSolverPath::scalar;
}

void set_contact_solver_path(ContactSolverPath path) {
  __atomic_store_n(&g_contact_solver_path, path == ContactSolverPath::lanes ? 1 : 0, __ATOMIC_RELAXED);
}


namespace {

/// The body a constraint side reads when it has no solver body: zero
/// velocity at the origin, the identity rotation. Never written (such a
/// side has zero inverse mass and inertia, so store_velocity skips it).
constexpr BodyState k_no_body{};

/// Each point's relative normal velocity at the start of a sub-step, where
/// the solve pass will read it. The solve reads it for a point that is not
/// touching (the "about to touch" test) or may bounce (restitution > 0);
/// a touching point without restitution only vets it (WrappingOps), and a
/// stale value there changes no result (at worst the witness falls back to
/// the saturating pass, which gives the same bits). From sub-step 1 on, the
/// separation the solve will read is the one the last relax pass stored
/// (cp.separation, solve_constraint_with), so such points are skipped:
/// on a resting pile, most of them (issue 15, "work not done").
/// separations_known: false in sub-step 0 (the solve computes s afresh).
void record_approach_constraint(ContactConstraint& cc, const BodyState* states, bool separations_known) {
  const bool every_point = !separations_known || cc.restitution > Q32::zero();
  bool need[2] = {true, true};
  if (!every_point) {
    need[0] = cc.points[0].separation > Q32::zero();
    need[1] = cc.point_count > 1 && cc.points[1].separation > Q32::zero();
    if (!need[0] && !need[1]) return;
  }
  const BodyState& a = cc.solver_a >= 0 ? states[cc.solver_a] : k_no_body;
  const BodyState& b = cc.solver_b >= 0 ? states[cc.solver_b] : k_no_body;
  const Vec2 dv = b.linear_velocity - a.linear_velocity;
  for (int32_t j = 0; j < cc.point_count; ++j) {
    if (!need[j]) continue;
    ContactConstraintPoint& cp = cc.points[j];
    cp.approach_velocity = relative_velocity(dv, cc.normal, b.angular_velocity, cp.rn_b, a.angular_velocity, cp.rn_a);
  }
}

}  // namespace

void record_contact_approach(StepContext* context) {
  BodyState* states = context->states;
  if (context->lanes != nullptr) {
    parallel_for(context->tasks, "record_approach", context->lane_offsets[k_contact_colour_count],
                 k_constraint_block / k_contact_lanes, [context, states](int32_t begin, int32_t end) {
                   for (int32_t i = begin; i < end; ++i) record_approach_lanes(context->lanes[i], states);
                 });
  }
  const int32_t first = context->lanes != nullptr ? context->colour_offsets[k_contact_colour_count] : 0;
  ContactConstraint* constraints = context->constraints + first;
  const bool separations_known = context->sub_step_index > 0;
  parallel_for(context->tasks, "record_approach", context->constraint_count - first, k_constraint_block,
               [constraints, states, separations_known](int32_t begin, int32_t end) {
                 for (int32_t i = begin; i < end; ++i) {
                   record_approach_constraint(constraints[i], states, separations_known);
                 }
               });
}

namespace {

/// Warm start of one constraint with the arithmetic of Ops: the bodies are
/// written only if ops.clean() holds at the end; returns whether they were.
/// (Zeroing a bounced point's impulse does not depend on the arithmetic.)
template <typename Ops>
bool warm_start_constraint_with(ContactConstraint& cc, BodyState* states, int32_t previous, Ops& o) {
  const BodyState& a = cc.solver_a >= 0 ? states[cc.solver_a] : k_no_body;
  const BodyState& b = cc.solver_b >= 0 ? states[cc.solver_b] : k_no_body;
  const Vec2 n = cc.normal, t = right_perp(n);
  Vec2 va = a.linear_velocity, vb = b.linear_velocity;
  Q32 wa = a.angular_velocity, wb = b.angular_velocity;
  o.vet(va.x);
  o.vet(va.y);
  o.vet(vb.x);
  o.vet(vb.y);
  o.vet(wa);
  o.vet(wb);
  const bool same_mass = cc.inv_mass_a == cc.inv_mass_b;  // m_B⁻¹·p = m_A⁻¹·p: computed once
  for (int32_t j = 0; j < cc.point_count; ++j) {
    ContactConstraintPoint& cp = cc.points[j];
    if (cp.bounce_sub_step >= 0 && cp.bounce_sub_step == previous) cp.normal_impulse = Q32::zero();
    const Vec2 p{o.sum2(cp.normal_impulse, n.x, cp.tangent_impulse, t.x),
                 o.sum2(cp.normal_impulse, n.y, cp.tangent_impulse, t.y)};
    const Q32 spin_a = o.sum2(cp.normal_impulse, cp.angular_n_a, cp.tangent_impulse, cp.angular_t_a);
    const Q32 spin_b = o.sum2(cp.normal_impulse, cp.angular_n_b, cp.tangent_impulse, cp.angular_t_b);
    const Vec2 pa = {o.mul(cc.inv_mass_a, p.x), o.mul(cc.inv_mass_a, p.y)};
    const Vec2 pb = same_mass ? pa : Vec2{o.mul(cc.inv_mass_b, p.x), o.mul(cc.inv_mass_b, p.y)};
    va = {o.sub(va.x, pa.x), o.sub(va.y, pa.y)};
    wa = o.sub(wa, spin_a);
    vb = {o.add(vb.x, pb.x), o.add(vb.y, pb.y)};
    wb = o.add(wb, spin_b);
  }
  if (!o.clean()) return false;
  if (cc.solver_a >= 0) store_velocity(&states[cc.solver_a], va, wa, cc.inv_mass_a, cc.inv_inertia_a);
  if (cc.solver_b >= 0) store_velocity(&states[cc.solver_b], vb, wb, cc.inv_mass_b, cc.inv_inertia_b);
  return true;
}

}  // namespace

void warm_start_contacts(StepContext* context) {
  BodyState* states = context->states;
  const int32_t previous = context->sub_step_index - 1;
  for_each_by_colour(
      context, "warm_start", [states, previous](ContactLanes& cl) { warm_start_lanes(cl, states, previous); },
      [states, previous](ContactConstraint& cc) {
#if TANDEM_CONTACT_WRAP_FIRST
        WrappingOps wrapping;
        if (warm_start_constraint_with(cc, states, previous, wrapping)) return;
#endif
        SaturatingOps saturating;
        warm_start_constraint_with(cc, states, previous, saturating);
      });
}

namespace {

/// Which pass solve_constraint_with runs: the biased solve (latches
/// bounces, soft push), the relax pass, or one of the bounce relax passes.
enum class Pass { solve, relax, relax_bounce };

/// The current separation of a point, (c_B + R_B·l_B − c_A − R_A·l_A)·n +
/// adjusted separation, each rotation component and the dot rounded once.
/// neg_sa, neg_sb: 0 − sin of each rotation, computed once per constraint.
template <typename Ops>
inline Q32 current_separation(const ContactConstraintPoint& cp, const BodyState& a, const BodyState& b, Vec2 dc,
                              Q32 neg_sa, Q32 neg_sb, Vec2 n, Ops& o) {
  const auto rotate = [&o](Rot q, Q32 neg_s, Vec2 v) { return Vec2{o.sum2(q.c, v.x, neg_s, v.y), o.sum2(q.s, v.x, q.c, v.y)}; };
  o.vet(cp.adjusted_separation);
  const Vec2 rb = rotate(b.rotation, neg_sb, cp.local_b), ra = rotate(a.rotation, neg_sa, cp.local_a);
  const Vec2 d = {o.add(dc.x, o.sub(rb.x, ra.x)), o.add(dc.y, o.sub(rb.y, ra.y))};
  return o.add(o.sum2(d.x, n.x, d.y, n.y), cp.adjusted_separation);
}

/// One pass over one constraint with the arithmetic of Ops.
/// Nothing is written (constraint points, bodies, bounce marks) unless
/// ops.clean() holds at the end; returns whether it wrote.
///
/// The separation s of a point depends only on the poses (centres and
/// rotations), and only stage_integrate_positions changes them inside the
/// sub-steps (between the solve and the relax of a sub-step; world.cpp's
/// stage list). So the s a relax pass computes is bit for bit the s of the
/// bounce relax passes of the same sub-step and of the next sub-step's
/// solve: the relax stores it (cp.separation) and those passes read it
/// instead of paying two rotations and a dot per point again (debug builds
/// recompute it and assert the equality). Only sub-step 0's solve and the
/// relax compute it.
///
/// Identities used (exact in both arithmetics, so the same bits as the
/// general formula impulse = −m·(vn + bias) − scale·λ): where the impulse
/// scale is 0 (a bounce, a speculative point, every relax pass) the term
/// "− 0·λ" is dropped (0·λ = 0 exactly, and x − 0 = x because no operation
/// here returns the raw minimum, the one value "− 0" would change: the
/// roundings and subtractions saturate to ±(2^63 − 1), and under a clean
/// witness |x| < 2^62); a touching point in a relax pass has bias 0 and
/// vn + 0 = vn (vn is a rounding, never the raw minimum). An operation whose
/// result is not used (the "about to touch" test in a relax pass) is not
/// computed: the witness only has to cover the operations that reach a
/// stored value.
template <Pass pass, typename Ops>
bool solve_constraint_with(ContactConstraint& cc, StepContext* context, Ops& o) {
  constexpr bool use_bias = pass == Pass::solve;
  const int32_t count = cc.point_count;
  const int32_t k = context->sub_step_index;
  const bool fresh_separation = pass == Pass::relax || (pass == Pass::solve && k == 0);
  BodyState* states = context->states;
  const BodyState& a = cc.solver_a >= 0 ? states[cc.solver_a] : k_no_body;
  const BodyState& b = cc.solver_b >= 0 ? states[cc.solver_b] : k_no_body;
  const Vec2 n = cc.normal, t = right_perp(n);
  const Q32 ma = cc.inv_mass_a, mb = cc.inv_mass_b;
  Vec2 va = a.linear_velocity, vb = b.linear_velocity;
  Q32 wa = a.angular_velocity, wb = b.angular_velocity;
  o.vet(va.x);
  o.vet(va.y);
  o.vet(vb.x);
  o.vet(vb.y);
  o.vet(wa);
  o.vet(wb);
  Vec2 dc{};
  Q32 neg_sa{}, neg_sb{};
  if (fresh_separation) {
    o.vet(a.center.x);
    o.vet(a.center.y);
    o.vet(b.center.x);
    o.vet(b.center.y);
    dc = {o.sub(b.center.x, a.center.x), o.sub(b.center.y, a.center.y)};
    neg_sa = o.sub(Q32::zero(), a.rotation.s);
    neg_sb = o.sub(Q32::zero(), b.rotation.s);
  }
  if constexpr (use_bias) o.vet(cc.kick);
  // Equal inverse masses (a pile of equal bodies): m_B⁻¹λ = m_A⁻¹λ and its
  // products with d are the same values, computed once (the witness ORs the
  // same contributions either way).
  const bool same_mass = ma == mb;
  const auto apply = [&](Q32 impulse, Vec2 d, Q32 angular_a, Q32 angular_b) {
    const Q32 ka = o.mul(ma, impulse);
    const Vec2 pa = {o.mul(ka, d.x), o.mul(ka, d.y)};
    Vec2 pb = pa;
    if (!same_mass) {
      const Q32 kb = o.mul(mb, impulse);
      pb = {o.mul(kb, d.x), o.mul(kb, d.y)};
    }
    va = {o.sub(va.x, pa.x), o.sub(va.y, pa.y)};
    wa = o.sub(wa, o.mul(impulse, angular_a));
    vb = {o.add(vb.x, pb.x), o.add(vb.y, pb.y)};
    wb = o.add(wb, o.mul(impulse, angular_b));
  };
  // relative_velocity's formula: sum4 of dv·d and ω_B (r_B × d) − ω_A (r_A × d).
  const auto relative = [&](Vec2 d, Q32 rd_b, Q32 rd_a) {
    return o.sum4(o.sub(vb.x, va.x), d.x, o.sub(vb.y, va.y), d.y, wb, rd_b, o.sub(Q32::zero(), wa), rd_a);
  };
  // The points' mutable state, written back only at the end.
  struct PointState {
    Q32 normal_impulse, tangent_impulse, bounce_velocity, separation;
    int32_t active_sub_step, bounce_sub_step;
  };
  PointState ps[2];
  bool skip[2] = {false, false};
  bool bounced = false;

  for (int32_t j = 0; j < count; ++j) {
    const ContactConstraintPoint& cp = cc.points[j];
    PointState& p = ps[j];
    p = {cp.normal_impulse, cp.tangent_impulse, cp.bounce_velocity, cp.separation, cp.active_sub_step,
         cp.bounce_sub_step};
    Q32 s;
    if (fresh_separation) {
      s = current_separation(cp, a, b, dc, neg_sa, neg_sb, n, o);
      p.separation = s;
    } else {
      s = p.separation;
#ifndef NDEBUG
      {
        SaturatingOps check;
        const Vec2 check_dc = {check.sub(b.center.x, a.center.x), check.sub(b.center.y, a.center.y)};
        const Q32 check_sa = check.sub(Q32::zero(), a.rotation.s), check_sb = check.sub(Q32::zero(), b.rotation.s);
        TANDEM_ASSERT(current_separation(cp, a, b, check_dc, check_sa, check_sb, n, check) == s);
      }
#endif
      if constexpr (use_bias) o.vet(s);  // an add operand below (relax passes only compare it)
    }
    const bool touching = s <= Q32::zero();
    bool active = touching;
    if constexpr (use_bias) {
      o.vet(cp.approach_velocity);
      active = touching || o.add(s, o.mul(context->h, o.add(cp.approach_velocity, cc.kick))) < Q32::zero();
      if (active) {
        p.active_sub_step = k;
        if (cc.restitution > Q32::zero() && cp.approach_velocity < -context->restitution_threshold &&
            p.bounce_sub_step != k) {
          p.bounce_sub_step = k;
          p.bounce_velocity = -(cc.restitution * cp.approach_velocity);
          bounced = true;
        }
      }
    }
    const bool bouncing = p.bounce_sub_step == k;
    if (!use_bias && !bouncing && (!touching || (p.active_sub_step != k && p.normal_impulse == Q32::zero()))) {
      skip[j] = true;  // relax gate: speculative, or idle this sub-step
      continue;
    }
    o.vet(p.normal_impulse);
    o.vet(p.tangent_impulse);
    const Q32 vn = relative(n, cp.rn_b, cp.rn_a);
    Q32 impulse;
    if (bouncing || !touching) {
      // Rigid, impulse scale 0. Speculative (only in the solve pass): only
      // stop it reaching the surface.
      const Q32 bias = bouncing ? -p.bounce_velocity : o.mul(s, context->inv_h);
      o.vet(bias);
      impulse = o.sub(Q32::zero(), o.mul(cp.normal_mass, o.add(vn, bias)));
      if (use_bias && !bouncing && !active) impulse = min(impulse, Q32::zero());
    } else if constexpr (use_bias) {
      // o.mul is fixed.h's product (the same rounding and saturation) under
      // the witness.
      const Q32 bias = max(o.mul(cc.softness.bias_rate, s), -context->max_push_speed);
      o.vet(bias);
      impulse = o.sub(o.sub(Q32::zero(), o.mul(cp.soft_normal_mass, o.add(vn, bias))),
                      o.mul(cc.softness.impulse_scale, p.normal_impulse));
    } else {
      impulse = o.sub(Q32::zero(), o.mul(cp.normal_mass, vn));
    }
    const Q32 accumulated = max(o.add(p.normal_impulse, impulse), Q32::zero());
    impulse = o.sub(accumulated, p.normal_impulse);
    p.normal_impulse = accumulated;
    apply(impulse, n, cp.angular_n_a, cp.angular_n_b);
  }

  for (int32_t j = 0; j < count; ++j) {
    if (skip[j]) continue;
    const ContactConstraintPoint& cp = cc.points[j];
    PointState& p = ps[j];
    const Q32 vt = relative(t, cp.rt_b, cp.rt_a);
    const Q32 max_friction = o.mul(cc.friction, p.normal_impulse);
    const Q32 accumulated = clamp(o.sub(p.tangent_impulse, o.mul(cp.tangent_mass, vt)),
                                  o.sub(Q32::zero(), max_friction), max_friction);
    const Q32 impulse = o.sub(accumulated, p.tangent_impulse);
    p.tangent_impulse = accumulated;
    apply(impulse, t, cp.angular_t_a, cp.angular_t_b);
  }

  if (!o.clean()) return false;
  for (int32_t j = 0; j < count; ++j) {
    ContactConstraintPoint& cp = cc.points[j];
    const PointState& p = ps[j];
    cp.normal_impulse = p.normal_impulse;
    cp.tangent_impulse = p.tangent_impulse;
    if constexpr (use_bias) {
      cp.bounce_velocity = p.bounce_velocity;
      cp.active_sub_step = p.active_sub_step;
      cp.bounce_sub_step = p.bounce_sub_step;
    }
    if (fresh_separation) cp.separation = p.separation;
  }
  if (bounced) {
    if (cc.solver_a >= 0) mark_bounce(&context->bounce_marks[cc.solver_a], k);
    if (cc.solver_b >= 0) mark_bounce(&context->bounce_marks[cc.solver_b], k);
    atomic_store_relaxed(&context->bounced_this_sub_step, true);
  }
  if (cc.solver_a >= 0) store_velocity(&states[cc.solver_a], va, wa, ma, cc.inv_inertia_a);
  if (cc.solver_b >= 0) store_velocity(&states[cc.solver_b], vb, wb, mb, cc.inv_inertia_b);
  return true;
}

/// One pass over one constraint (see solve_constraint_with). Release builds
/// with a native 128-bit type first run the wrapping arithmetic and keep its
/// result when its witness shows that nothing came near saturation (every
/// ordinary contact); otherwise, and in every other build, the saturating
/// arithmetic. Same bits either way.
template <Pass pass>
void solve_constraint(ContactConstraint& cc, StepContext* context) {
#if TANDEM_CONTACT_WRAP_FIRST
  WrappingOps wrapping;
  if (solve_constraint_with<pass>(cc, context, wrapping)) return;
#endif
  SaturatingOps saturating;
  solve_constraint_with<pass>(cc, context, saturating);
}

}  // namespace

void solve_contacts(StepContext* context) {
  context->bounced_this_sub_step = false;
  for_each_by_colour(
      context, "solve", [context](ContactLanes& cl) { solve_lanes<true>(cl, context, nullptr); },
      [context](ContactConstraint& cc) { solve_constraint<Pass::solve>(cc, context); });
}

void relax_contacts(StepContext* context) {
  for_each_by_colour(
      context, "relax", [context](ContactLanes& cl) { solve_lanes<false>(cl, context, nullptr); },
      [context](ContactConstraint& cc) { solve_constraint<Pass::relax>(cc, context); });
  if (!context->bounced_this_sub_step) return;
  const int32_t k = context->sub_step_index;
  const int32_t* marks = context->bounce_marks;
  for (int32_t pass = 0; pass < 2; ++pass) {
    for_each_by_colour(
        context, "relax_bounce",
        [context, marks, k](ContactLanes& cl) {
          int32_t enabled[k_contact_lanes];
          int32_t any = 0;
          for (int32_t l = 0; l < k_contact_lanes; ++l) {
            enabled[l] = (cl.solver_a[l] >= 0 && marks[cl.solver_a[l]] == k) ||
                                 (cl.solver_b[l] >= 0 && marks[cl.solver_b[l]] == k)
                             ? 1
                             : 0;
            any |= enabled[l];
          }
          if (any != 0) solve_lanes<false>(cl, context, enabled);
        },
        [context, marks, k](ContactConstraint& cc) {
          const bool marked =
              (cc.solver_a >= 0 && marks[cc.solver_a] == k) || (cc.solver_b >= 0 && marks[cc.solver_b] == k);
          if (marked) solve_constraint<Pass::relax_bounce>(cc, context);
        });
  }
}

void store_contact_impulses(World* world, StepContext* context) {
  const int32_t last = context->sub_step_count - 1;
  Contact* contacts = world->contacts.data();
  ContactLanes* lanes = context->lanes;
  if (lanes != nullptr) {
    parallel_for(context->tasks, "store_impulses", context->lane_offsets[k_contact_colour_count],
                 k_constraint_block / k_contact_lanes, [lanes, contacts, last](int32_t begin, int32_t end) {
                   for (int32_t i = begin; i < end; ++i) {
                     const ContactLanes& cl = lanes[i];
                     for (int32_t l = 0; l < k_contact_lanes; ++l) {
                       if (cl.contact_index[l] < 0) continue;
                       Contact& c = contacts[cl.contact_index[l]];
                       for (int32_t j = 0; j < 2; ++j) {
                         const ContactLanePoint& p = cl.points[j];
                         if (p.present[l] == 0) continue;
                         c.normal_impulse[static_cast<size_t>(j)] =
                             p.bounce_sub_step[l] == last ? Q32::zero() : p.normal_impulse[l];
                         c.tangent_impulse[static_cast<size_t>(j)] = p.tangent_impulse[l];
                       }
                     }
                   }
                 });
  }
  const int32_t first = lanes != nullptr ? context->colour_offsets[k_contact_colour_count] : 0;
  ContactConstraint* constraints = context->constraints + first;
  parallel_for(context->tasks, "store_impulses", context->constraint_count - first, k_constraint_block,
               [constraints, contacts, last](int32_t begin, int32_t end) {
                 for (int32_t i = begin; i < end; ++i) {
                   const ContactConstraint& cc = constraints[i];
                   Contact& c = contacts[cc.contact_index];
                   for (int32_t j = 0; j < cc.point_count; ++j) {
                     const ContactConstraintPoint& cp = cc.points[j];
                     c.normal_impulse[static_cast<size_t>(j)] = cp.bounce_sub_step == last ? Q32::zero() : cp.normal_impulse;
                     c.tangent_impulse[static_cast<size_t>(j)] = cp.tangent_impulse;
                   }
                 }
               });
  Arena* arena = &world->arena;
  if (lanes != nullptr) arena_free(arena, lanes);
  context->lanes = nullptr;
  arena_free(arena, context->bounce_marks);
  arena_free(arena, context->constraints);
  context->bounce_marks = nullptr;
  context->constraints = nullptr;
  context->constraint_count = 0;
}

}  // namespace tandem
