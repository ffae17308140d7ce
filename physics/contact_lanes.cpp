// contact_lanes.cpp — the lane path of the contact solver (contact_lanes.h):
// packing each colour's constraints into blocks of k_contact_lanes after
// prepare, and the lane kernels that contact_solver.cpp's passes call per
// block. Same bits as the scalar path by construction (docs/determinism.md,
// "The contact solver's two paths").
#include "physics/contact_lanes.h"

#include "physics/contact_solver.h"
#include "physics/contact_solver_internal.h"

namespace tandem {

using namespace contact_internal;

void pack_contact_lanes(World* world, StepContext* context) {
  context->lanes = nullptr;
  for (int32_t& offset : context->lane_offsets) offset = 0;
  if (contact_solver_path() != ContactSolverPath::lanes) return;
  const int32_t* offsets = context->colour_offsets;
  int32_t blocks = 0;
  for (int32_t k = 0; k < k_contact_colour_count; ++k) {
    context->lane_offsets[k] = blocks;
    blocks += (offsets[k + 1] - offsets[k] + k_contact_lanes - 1) / k_contact_lanes;
  }
  context->lane_offsets[k_contact_colour_count] = blocks;
  ContactLanes* lanes = arena_allocate_array<ContactLanes>(&world->arena, blocks, "contact_lanes");
  for (int32_t b = 0; b < blocks; ++b) {
    ContactLanes& cl = lanes[b];
    cl = ContactLanes{};
    for (int32_t l = 0; l < k_contact_lanes; ++l) {
      cl.solver_a[l] = k_null_index;
      cl.solver_b[l] = k_null_index;
      cl.contact_index[l] = -1;
      for (ContactLanePoint& p : cl.points) {
        p.bounce_sub_step[l] = -1;
        p.active_sub_step[l] = -1;
      }
    }
  }
  for (int32_t k = 0; k < k_contact_colour_count; ++k) {
    for (int32_t i = offsets[k]; i < offsets[k + 1]; ++i) {
      const ContactConstraint& cc = context->constraints[i];
      ContactLanes& cl = lanes[context->lane_offsets[k] + (i - offsets[k]) / k_contact_lanes];
      const int32_t l = (i - offsets[k]) % k_contact_lanes;
      cl.solver_a[l] = cc.solver_a;
      cl.solver_b[l] = cc.solver_b;
      cl.contact_index[l] = cc.contact_index;
      cl.movable_a[l] = cc.inv_mass_a != Q32::zero() || cc.inv_inertia_a != Q32::zero() ? 1 : 0;
      cl.movable_b[l] = cc.inv_mass_b != Q32::zero() || cc.inv_inertia_b != Q32::zero() ? 1 : 0;
      cl.normal_x[l] = cc.normal.x;
      cl.normal_y[l] = cc.normal.y;
      cl.inv_mass_a[l] = cc.inv_mass_a;
      cl.inv_mass_b[l] = cc.inv_mass_b;
      cl.friction[l] = cc.friction;
      cl.restitution[l] = cc.restitution;
      cl.kick[l] = cc.kick;
      cl.bias_rate[l] = cc.softness.bias_rate;
      cl.impulse_scale[l] = cc.softness.impulse_scale;
      for (int32_t j = 0; j < cc.point_count; ++j) {
        const ContactConstraintPoint& cp = cc.points[j];
        ContactLanePoint& p = cl.points[j];
        p.rn_a[l] = cp.rn_a;
        p.rn_b[l] = cp.rn_b;
        p.rt_a[l] = cp.rt_a;
        p.rt_b[l] = cp.rt_b;
        p.angular_n_a[l] = cp.angular_n_a;
        p.angular_n_b[l] = cp.angular_n_b;
        p.angular_t_a[l] = cp.angular_t_a;
        p.angular_t_b[l] = cp.angular_t_b;
        p.local_a_x[l] = cp.local_a.x;
        p.local_a_y[l] = cp.local_a.y;
        p.local_b_x[l] = cp.local_b.x;
        p.local_b_y[l] = cp.local_b.y;
        p.adjusted_separation[l] = cp.adjusted_separation;
        p.normal_impulse[l] = cp.normal_impulse;
        p.tangent_impulse[l] = cp.tangent_impulse;
        p.normal_mass[l] = cp.normal_mass;
        p.soft_normal_mass[l] = cp.soft_normal_mass;
        p.tangent_mass[l] = cp.tangent_mass;
        p.approach_velocity[l] = cp.approach_velocity;
        p.bounce_velocity[l] = cp.bounce_velocity;
        p.bounce_sub_step[l] = cp.bounce_sub_step;
        p.active_sub_step[l] = cp.active_sub_step;
        p.present[l] = 1;
      }
    }
  }
  context->lanes = lanes;
}

namespace contact_internal {

// ---- Lane kernels (contact_lanes.h). Each is the scalar function of the
// same name below (…_constraint) with the constraint index turned into a
// lane index: the same in_range operations on the same operands in the same
// order for every lane, and the scalar path's branches turned into per-lane
// selects. A lane whose point is missing, empty or skipped computes its
// values anyway and keeps its old state (the select), so no lane ever
// changes what the scalar path would leave alone.

/// The velocities of a block's bodies, gathered before and scattered after
/// a kernel (a missing body reads a zero-velocity dummy and is never
/// written).
struct LaneVelocities {
  Vec2 va[k_contact_lanes];
  Q32 wa[k_contact_lanes];
  Vec2 vb[k_contact_lanes];
  Q32 wb[k_contact_lanes];
};

inline const BodyState& lane_body(const BodyState* states, int32_t index, const BodyState& dummy) {
  return index >= 0 ? states[index] : dummy;
}

inline void gather_velocities(const ContactLanes& cl, const BodyState* states, LaneVelocities* out) {
  const BodyState dummy{};
  for (int32_t l = 0; l < k_contact_lanes; ++l) {
    const BodyState& a = lane_body(states, cl.solver_a[l], dummy);
    const BodyState& b = lane_body(states, cl.solver_b[l], dummy);
    out->va[l] = a.linear_velocity;
    out->wa[l] = a.angular_velocity;
    out->vb[l] = b.linear_velocity;
    out->wb[l] = b.angular_velocity;
  }
}

/// Writes back the movable bodies (store_velocity's rule).
inline void scatter_velocities(const ContactLanes& cl, BodyState* states, const LaneVelocities& v) {
  for (int32_t l = 0; l < k_contact_lanes; ++l) {
    if (cl.solver_a[l] >= 0 && cl.movable_a[l] != 0) {
      states[cl.solver_a[l]].linear_velocity = v.va[l];
      states[cl.solver_a[l]].angular_velocity = v.wa[l];
    }
    if (cl.solver_b[l] >= 0 && cl.movable_b[l] != 0) {
      states[cl.solver_b[l]].linear_velocity = v.vb[l];
      states[cl.solver_b[l]].angular_velocity = v.wb[l];
    }
  }
}

/// cond ? if_true : if_false, a per-lane select (compilers emit cmov/blend).
template <typename T>
inline T pick(bool cond, T if_true, T if_false) {
  return cond ? if_true : if_false;
}

/// Applies impulse along d in lane l, or keeps the lane's velocities when
/// `skip` (apply_impulse's operations).
inline void apply_lane_impulse(LaneVelocities* v, int32_t l, bool skip, Q32 impulse, Vec2 d, Q32 inv_mass_a,
                               Q32 angular_a, Q32 inv_mass_b, Q32 angular_b) {
  Vec2 va = v->va[l], vb = v->vb[l];
  Q32 wa = v->wa[l], wb = v->wb[l];
  apply_impulse(impulse, d, inv_mass_a, angular_a, inv_mass_b, angular_b, &va, &wa, &vb, &wb);
  v->va[l] = {pick(skip, v->va[l].x, va.x), pick(skip, v->va[l].y, va.y)};
  v->wa[l] = pick(skip, v->wa[l], wa);
  v->vb[l] = {pick(skip, v->vb[l].x, vb.x), pick(skip, v->vb[l].y, vb.y)};
  v->wb[l] = pick(skip, v->wb[l], wb);
}

void record_approach_lanes(ContactLanes& cl, BodyState* states) {
  const BodyState dummy{};
  for (int32_t l = 0; l < k_contact_lanes; ++l) {
    const BodyState& a = lane_body(states, cl.solver_a[l], dummy);
    const BodyState& b = lane_body(states, cl.solver_b[l], dummy);
    const Vec2 n{cl.normal_x[l], cl.normal_y[l]};
    for (ContactLanePoint& p : cl.points) {
      p.approach_velocity[l] = relative_velocity(b.linear_velocity - a.linear_velocity, n, b.angular_velocity,
                                                 p.rn_b[l], a.angular_velocity, p.rn_a[l]);
    }
  }
}

void warm_start_lanes(ContactLanes& cl, BodyState* states, int32_t previous) {
  using namespace in_range;
  LaneVelocities v;
  gather_velocities(cl, states, &v);
  for (ContactLanePoint& p : cl.points) {
    int32_t any = 0;
    for (int32_t l = 0; l < k_contact_lanes; ++l) any |= p.present[l];
    if (any == 0) continue;  // no lane has this point
    for (int32_t l = 0; l < k_contact_lanes; ++l) {
      const bool skip = p.present[l] == 0;
      const Vec2 n{cl.normal_x[l], cl.normal_y[l]}, t = right_perp(n);
      const bool restart = p.bounce_sub_step[l] >= 0 && p.bounce_sub_step[l] == previous;
      const Q32 ni = pick(restart, Q32::zero(), p.normal_impulse[l]);
      const Q32 ti = p.tangent_impulse[l];
      p.normal_impulse[l] = pick(skip, p.normal_impulse[l], ni);
      const Vec2 impulse{sum2(ni, n.x, ti, t.x), sum2(ni, n.y, ti, t.y)};
      const Q32 spin_a = sum2(ni, p.angular_n_a[l], ti, p.angular_t_a[l]);
      const Q32 spin_b = sum2(ni, p.angular_n_b[l], ti, p.angular_t_b[l]);
      const Q32 ma = cl.inv_mass_a[l], mb = cl.inv_mass_b[l];
      const Vec2 va{sub(v.va[l].x, mul(ma, impulse.x)), sub(v.va[l].y, mul(ma, impulse.y))};
      const Q32 wa = sub(v.wa[l], spin_a);
      const Vec2 vb{add(v.vb[l].x, mul(mb, impulse.x)), add(v.vb[l].y, mul(mb, impulse.y))};
      const Q32 wb = add(v.wb[l], spin_b);
      v.va[l] = {pick(skip, v.va[l].x, va.x), pick(skip, v.va[l].y, va.y)};
      v.wa[l] = pick(skip, v.wa[l], wa);
      v.vb[l] = {pick(skip, v.vb[l].x, vb.x), pick(skip, v.vb[l].y, vb.y)};
      v.wb[l] = pick(skip, v.wb[l], wb);
    }
  }
  scatter_velocities(cl, states, v);
}

/// solve_constraint over the lanes of a block. enabled (may be null: all
/// lanes): per lane, 0 leaves the lane's constraint untouched (the bounce
/// relax passes solve only the constraints of marked bodies).
template <bool use_bias>
void solve_lanes(ContactLanes& cl, StepContext* context, const int32_t* enabled) {
  using namespace in_range;
  BodyState* states = context->states;
  const int32_t k = context->sub_step_index;
  const Q32 h = context->h;
  const Q32 inv_h = context->inv_h;
  const Q32 min_push_bias = -context->max_push_speed;
  const Q32 min_approach = -context->restitution_threshold;
  LaneVelocities v;
  Vec2 dc[k_contact_lanes];
  Rot rot_a[k_contact_lanes], rot_b[k_contact_lanes];
  {
    const BodyState dummy{};
    for (int32_t l = 0; l < k_contact_lanes; ++l) {
      const BodyState& a = lane_body(states, cl.solver_a[l], dummy);
      const BodyState& b = lane_body(states, cl.solver_b[l], dummy);
      v.va[l] = a.linear_velocity;
      v.wa[l] = a.angular_velocity;
      v.vb[l] = b.linear_velocity;
      v.wb[l] = b.angular_velocity;
      dc[l] = sub(b.center, a.center);
      rot_a[l] = a.rotation;
      rot_b[l] = b.rotation;
    }
  }
  bool skip[2][k_contact_lanes];

  for (int32_t j = 0; j < 2; ++j) {
    ContactLanePoint& p = cl.points[j];
    bool live[k_contact_lanes];
    bool any_live = false;
    for (int32_t l = 0; l < k_contact_lanes; ++l) {
      live[l] = p.present[l] != 0 && (enabled == nullptr || enabled[l] != 0);
      any_live |= live[l];
      skip[j][l] = true;
    }
    if (!any_live) continue;  // what the scalar loop never visits (no point, or not enabled)
    for (int32_t l = 0; l < k_contact_lanes; ++l) {
      const Vec2 n{cl.normal_x[l], cl.normal_y[l]};
      const Vec2 d = add(dc[l], sub(in_range::rotate(rot_b[l], Vec2{p.local_b_x[l], p.local_b_y[l]}),
                                    in_range::rotate(rot_a[l], Vec2{p.local_a_x[l], p.local_a_y[l]})));
      const Q32 s = add(in_range::dot(d, n), p.adjusted_separation[l]);
      const bool touching = s <= Q32::zero();
      bool active = touching;
      if constexpr (use_bias) {
        // The relax pass never reads `active`; the scalar path computes it
        // there but has no use for it.
        active = touching || add(s, mul(h, add(p.approach_velocity[l], cl.kick[l]))) < Q32::zero();
        const bool act = live[l] && active;
        p.active_sub_step[l] = pick(act, k, p.active_sub_step[l]);
        const bool latch = act && cl.restitution[l] > Q32::zero() && p.approach_velocity[l] < min_approach &&
                           p.bounce_sub_step[l] != k;
        if (latch) [[unlikely]] {
          p.bounce_sub_step[l] = k;
          p.bounce_velocity[l] = -(cl.restitution[l] * p.approach_velocity[l]);
          if (cl.solver_a[l] >= 0) mark_bounce(&context->bounce_marks[cl.solver_a[l]], k);
          if (cl.solver_b[l] >= 0) mark_bounce(&context->bounce_marks[cl.solver_b[l]], k);
          atomic_store_relaxed(&context->bounced_this_sub_step, true);
        }
      }
      const bool bouncing = p.bounce_sub_step[l] == k;
      const bool skipped =
          !live[l] || (!use_bias && !bouncing &&
                       (!touching || (p.active_sub_step[l] != k && p.normal_impulse[l] == Q32::zero())));
      skip[j][l] = skipped;
      // The scalar chain: bouncing → rigid, target speed; speculative →
      // rigid, bias s·(1/h); touching in the biased solve → soft, bias
      // max(rate·s, −push); touching in relax → rigid, no bias. Both
      // products are one Q32 multiplication by s, so one multiplication
      // with the factor selected gives the same bits.
      const Q32 vn = relative_velocity(sub(v.vb[l], v.va[l]), n, v.wb[l], p.rn_b[l], v.wa[l], p.rn_a[l]);
      Q32 impulse;
      if constexpr (use_bias) {
        const bool soft = touching && !bouncing;
        const Q32 scaled = (touching ? cl.bias_rate[l] : inv_h) * s;
        const Q32 bias = bouncing ? -p.bounce_velocity[l] : (touching ? max(scaled, min_push_bias) : scaled);
        const Q32 mass = soft ? p.soft_normal_mass[l] : p.normal_mass[l];
        const Q32 impulse_scale = soft ? cl.impulse_scale[l] : Q32::zero();
        impulse = sub(neg(mul(mass, add(vn, bias))), mul(impulse_scale, p.normal_impulse[l]));
        const bool gate = !bouncing && !touching && !active;
        impulse = pick(gate, min(impulse, Q32::zero()), impulse);
      } else {
        // Relax: impulse scale 0, so the scalar path's "− 0·λ" is exact
        // (neg never returns the one value, INT64_MIN, that "− 0" changes);
        // speculative points are skipped, so the bias is the bounce
        // target or 0.
        const Q32 bias = bouncing ? -p.bounce_velocity[l] : Q32::zero();
        impulse = neg(mul(p.normal_mass[l], add(vn, bias)));
      }
      const Q32 accumulated = max(add(p.normal_impulse[l], impulse), Q32::zero());
      impulse = sub(accumulated, p.normal_impulse[l]);
      p.normal_impulse[l] = pick(skipped, p.normal_impulse[l], accumulated);
      apply_lane_impulse(&v, l, skipped, impulse, n, cl.inv_mass_a[l], p.angular_n_a[l], cl.inv_mass_b[l],
                         p.angular_n_b[l]);
    }
  }

  for (int32_t j = 0; j < 2; ++j) {
    ContactLanePoint& p = cl.points[j];
    bool any = false;
    for (int32_t l = 0; l < k_contact_lanes; ++l) any |= !skip[j][l];
    if (!any) continue;
    for (int32_t l = 0; l < k_contact_lanes; ++l) {
      const Vec2 n{cl.normal_x[l], cl.normal_y[l]}, t = right_perp(n);
      const bool skipped = skip[j][l];
      const Q32 vt = relative_velocity(sub(v.vb[l], v.va[l]), t, v.wb[l], p.rt_b[l], v.wa[l], p.rt_a[l]);
      const Q32 max_friction = mul(cl.friction[l], p.normal_impulse[l]);
      const Q32 accumulated = clamp(sub(p.tangent_impulse[l], mul(p.tangent_mass[l], vt)), neg(max_friction),
                                    max_friction);
      const Q32 impulse = sub(accumulated, p.tangent_impulse[l]);
      p.tangent_impulse[l] = pick(skipped, p.tangent_impulse[l], accumulated);
      apply_lane_impulse(&v, l, skipped, impulse, t, cl.inv_mass_a[l], p.angular_t_a[l], cl.inv_mass_b[l],
                         p.angular_t_b[l]);
    }
  }

  scatter_velocities(cl, states, v);
}

template void solve_lanes<true>(ContactLanes& cl, StepContext* context, const int32_t* enabled);
template void solve_lanes<false>(ContactLanes& cl, StepContext* context, const int32_t* enabled);

}  // namespace contact_internal

}  // namespace tandem
