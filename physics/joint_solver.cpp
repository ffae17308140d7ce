// joint_solver.cpp — joints in the sub-stepped soft solver (see joint.h).
//
// Formulation (our own write-up of the soft-step scheme contact_solver.cpp
// uses): each scalar or 2D constraint has a position error C, a velocity
// Jacobian J (Cdot = J·v) and an effective mass M = (J M⁻¹ Jᵀ)⁻¹. One pass
// applies
//     λ = −s_m · M · (Cdot + b) − s_i · λ_acc,     λ_acc += λ
// where, in the biased solve, (b, s_m, s_i) = (rate·C, mass_scale,
// impulse_scale) of the joint's softness (Softness, contact_solver.h), and in
// the relax pass (0, 1, 0): the relax pass removes the velocity the position
// correction injected, so a pendulum keeps its energy. Springs (revolute,
// prismatic, wheel, distance springs; soft weld parts; the mouse joint) use
// their own softness in both passes. Limits are one-sided: when the limit is
// not reached (C > 0) the bias is C/h (speculative: only stop it being
// crossed within the sub-step), and the accumulated impulse stays ≥ 0.
// Motors drive Cdot to the motor speed with |λ_acc| ≤ h · max force/torque.
//
// Anchors are taken from each body's centre of mass and rotated with the
// body's current sub-step rotation; the position error is computed from the
// current absolute poses (BodyState holds absolute centres and rotations). A
// body that is not simulated (static, asleep) keeps the pose it had at
// prepare and zero velocity and inverse mass; a kinematic body has zero
// inverse mass, so the joint never changes it.
//
// Rigid position pass (revolute joints): the soft point constraint stretches
// under load (about a/(2π·joint_hertz)² under an acceleration a), so a light
// limb hit by a heavy body opens its joint by centimetres for a few steps, and
// continuous collision stops a fast body at its time of impact without moving
// its joint partners. Once per step, after continuous collision
// (stage_project_joints), the part of each revolute joint's anchor gap beyond
// k_joint_slop is removed by moving the two poses directly: a non-linear
// Gauss-Seidel position projection with the point-constraint mass,
// c_A −= m_A⁻¹·P, q_A turned by −i_A⁻¹·(r_A × P), B the other way, with
// P = K⁻¹·(gap − slop·n), scaled down when a side would turn by more than
// k_max_projection_turn (1 rad), a turn above 1/16 rad taken exactly, in joint
// index order, up to k_joint_project_passes passes (a pass that moves nothing
// ends them). Velocities are not touched,
// so no energy is injected (the pendulum's 60 s energy figure is unchanged)
// and joints within the slop see no change at all. Measured
// (tests/physics/test_joint.cpp ragdolls in a box,
// tests/tools/test_scene_joints.cpp ragdolls down stairs): worst separation at
// impact 61 mm → 3.3 mm and 110 mm → 7.3 mm, at rest 8.3 mm → 3.0 mm. Long
// chains under heavy loads (the 30-plank bridge, the 50-link chain, a hanging
// joint_grid) still stretch by about 3 cm: a few passes do not carry a
// correction along 30 links, and there the pass costs time on every step
// (about a fifth of joint_grid's step, docs/benchmarks.md). Also tried:
// projecting after every sub-step as well (4.9 mm on the stairs, twice the
// cost), two joint iterations per sub-step (37 mm), stiffer joint softness
// (120 Hz: 22 mm, but the bridge fails), a rigid (non-soft) biased solve (the
// bridge fails).
//
// Order: joints in ascending joint index, before the contacts, in every stage.
// Arithmetic: Q32.32 with the checked operators (rounded to nearest, ties away
// from zero); 2×2 systems by vec2.h's exact Cramer solve.
#include <algorithm>

#include "physics/island.h"
#include "physics/state_fields.h"
#include "physics/world.h"

namespace tandem {

namespace {

/// Revolute anchor gap the rigid position pass leaves alone, m (3 mm).
constexpr Q32 k_joint_slop = Q32::from_ratio(3, 1000);
/// k_joint_slop/√2 rounded down: a gap with both components within it is
/// within the slop.
constexpr Q32 k_joint_slop_inner = Q32::from_ratio(2121, 1000000);
/// Projection passes after continuous collision (at most; a pass that moves
/// nothing ends them).
constexpr int32_t k_joint_project_passes = 4;
/// Largest turn one projection gives a body, rad (1). The correction is
/// linearised: a body of small inertia whose anchor lies near its centre of
/// mass would be asked to turn by radians to move that anchor by centimetres
/// (a 30 kg body with a 7 mm radius of gyration, its anchor 1 cm from its
/// centre: tens of radians for a 2 m gap), which is meaningless past a
/// fraction of a radian; integrate_rotation's first-order turn even
/// diverged past about √2 rad, and the rotation grew every sub-step until it
/// overflowed (random-world stress with joint inputs, seed 32; a fixed-point
/// fault, which aborts a release build by default). A larger correction is
/// scaled down as a whole (translation and turn alike) to this turn; the
/// next passes and steps remove the rest.
constexpr Q32 k_max_projection_turn = Q32::from_raw(int64_t{1} << 32);
/// Largest turn taken by integrate_rotation's first-order form (1/16 rad, as
/// solver.cpp's polynomial path): its length error, about 0.42·δ⁸, is below
/// a raw unit there. A larger turn is exact, rot_normalize(rot_from_angle(δ)
/// · q), so no step ends with a rotation off unit length (a first-order turn
/// of 0.35 rad leaves |q| about 5·10⁻⁵ from 1, beyond the 2^-16 ≈ 1.5·10⁻⁵
/// that world_restore accepts: the snapshot of that step was refused;
/// random-world stress with joint inputs, 10 of seeds 1-1,000). Changed the golden chains
/// joints_ragdolls and joints_bridge_chain (2026-11-29), whose projections
/// turn limbs and planks by more than 1/16 rad.
constexpr Q32 k_small_projection_turn = Q32::from_raw(int64_t{1} << 28);

/// One side of a joint during a pass: its state (a copy), written back only
/// when the body is simulated.
struct Side {
  Vec2 v;
  Q32 w;
  Vec2 c;
  Rot q;
};

struct Pair {
  Side a, b;
  Q32 ma, ia, mb, ib;
};

Pair load(const Joint& j, const StepContext* ctx) {
  Pair p;
  if (j.step_solver_a >= 0) {
    const BodyState& s = ctx->states[j.step_solver_a];
    p.a = {s.linear_velocity, s.angular_velocity, s.center, s.rotation};
  } else {
    p.a = {Vec2{}, Q32::zero(), j.step_center_a, j.step_rotation_a};
  }
  if (j.step_solver_b >= 0) {
    const BodyState& s = ctx->states[j.step_solver_b];
    p.b = {s.linear_velocity, s.angular_velocity, s.center, s.rotation};
  } else {
    p.b = {Vec2{}, Q32::zero(), j.step_center_b, j.step_rotation_b};
  }
  p.ma = j.step_inv_mass_a;
  p.ia = j.step_inv_inertia_a;
  p.mb = j.step_inv_mass_b;
  p.ib = j.step_inv_inertia_b;
  return p;
}

void store(const Joint& j, const Pair& p, StepContext* ctx) {
  if (j.step_solver_a >= 0) {
    BodyState& s = ctx->states[j.step_solver_a];
    s.linear_velocity = p.a.v;
    s.angular_velocity = p.a.w;
  }
  if (j.step_solver_b >= 0) {
    BodyState& s = ctx->states[j.step_solver_b];
    s.linear_velocity = p.b.v;
    s.angular_velocity = p.b.w;
  }
}

/// Applies a linear impulse P at arms (arm_a, arm_b) plus an angular impulse
/// L: A gets −P, −(arm_a×P + L); B gets +P, +(arm_b×P + L).
void apply(Pair* p, Vec2 impulse, Q32 angular_a, Q32 angular_b) {
  p->a.v = p->a.v - p->ma * impulse;
  p->a.w = p->a.w - p->ia * angular_a;
  p->b.v = p->b.v + p->mb * impulse;
  p->b.w = p->b.w + p->ib * angular_b;
}

Q32 inverse_or_zero(Q32 k) { return k > Q32::zero() ? Q32::one() / k : Q32::zero(); }

/// Relative angle of B to A minus the reference, wrapped into [−π, π].
Q32 joint_angle_of(const Pair& p, Q32 reference) {
  Q32 a = relative_angle(p.a.q, p.b.q) - reference;
  if (a > k_pi) a = a - k_two_pi;
  if (a < -k_pi) a = a + k_two_pi;
  return a;
}

/// The relative velocity of the anchor points, (v_B + ω_B × r_B) − (v_A + ω_A × r_A).
Vec2 point_velocity(const Pair& p, Vec2 ra, Vec2 rb) {
  return (p.b.v + cross(p.b.w, rb)) - (p.a.v + cross(p.a.w, ra));
}

/// The point-constraint mass matrix K = (m_A + m_B)·I + i_A·[r_A]ₓ² + i_B·[r_B]ₓ².
Mat22 point_mass(const Pair& p, Vec2 ra, Vec2 rb) {
  const Q32 m = p.ma + p.mb;
  const Q32 k11 = m + p.ia * ra.y * ra.y + p.ib * rb.y * rb.y;
  const Q32 k12 = -(p.ia * ra.x * ra.y) - p.ib * rb.x * rb.y;
  const Q32 k22 = m + p.ia * ra.x * ra.x + p.ib * rb.x * rb.x;
  return Mat22{{k11, k12}, {k12, k22}};
}

/// The coefficients of one pass: bias, mass scale, impulse scale.
struct Coeffs {
  Q32 bias;
  Q32 mass_scale = Q32::one();
  Q32 impulse_scale;
};

/// Rigid part: soft with bias in the solve pass, plain in the relax pass.
Coeffs rigid(const Softness& soft, Q32 c, bool use_bias) {
  Coeffs k;
  if (use_bias) {
    k.bias = soft.bias_rate * c;
    k.mass_scale = soft.mass_scale;
    k.impulse_scale = soft.impulse_scale;
  }
  return k;
}

/// One-sided limit with error c (≥ 0 allowed): speculative above 0.
Coeffs limit(const Softness& soft, Q32 c, Q32 inv_h, bool use_bias) {
  Coeffs k;
  if (c > Q32::zero()) {
    k.bias = c * inv_h;
  } else if (use_bias) {
    k.bias = soft.bias_rate * c;
    k.mass_scale = soft.mass_scale;
    k.impulse_scale = soft.impulse_scale;
  }
  return k;
}

/// λ = −s_m·M·(cdot + b) − s_i·acc.
Q32 soft_impulse(Q32 mass, Q32 cdot, const Coeffs& k, Q32 acc) {
  return -(k.mass_scale * (mass * (cdot + k.bias))) - k.impulse_scale * acc;
}

/// Clamps the accumulated impulse *acc + λ to [lo, hi]; returns the applied change.
Q32 accumulate(Q32* acc, Q32 impulse, Q32 lo, Q32 hi) {
  const Q32 old = *acc;
  *acc = clamp(old + impulse, lo, hi);
  return *acc - old;
}

/// Spring + motor + limits on a scalar axis whose velocity is `cdot_of()` and
/// whose impulse is applied by `apply_axial(λ)`; the shared part of
/// revolute, prismatic, wheel and distance joints. `position` is the joint
/// coordinate (angle, translation, length).
template <typename CdotOf, typename ApplyAxial>
void solve_axis(Joint& j, Q32 mass, Q32 position, Q32 spring_target, bool spring_on, bool motor_on, bool limit_on,
                bool use_bias, const StepContext* ctx, CdotOf cdot_of, ApplyAxial apply_axial) {
  if (mass == Q32::zero()) return;
  if (spring_on && j.hertz > Q32::zero()) {
    Coeffs k;
    k.bias = j.step_spring.bias_rate * (position - spring_target);
    k.mass_scale = j.step_spring.mass_scale;
    k.impulse_scale = j.step_spring.impulse_scale;
    const Q32 impulse = soft_impulse(mass, cdot_of(), k, j.spring_impulse);
    j.spring_impulse = j.spring_impulse + impulse;
    apply_axial(impulse);
  }
  if (motor_on) {
    const Q32 max_impulse = ctx->h * j.max_motor_force;
    const Q32 impulse = -(mass * (cdot_of() - j.motor_speed));
    apply_axial(accumulate(&j.motor_impulse, impulse, -max_impulse, max_impulse));
  }
  if (limit_on) {
    {
      const Coeffs k = limit(j.step_soft, position - j.lower, ctx->inv_h, use_bias);
      const Q32 impulse = soft_impulse(mass, cdot_of(), k, j.lower_impulse);
      apply_axial(accumulate(&j.lower_impulse, impulse, Q32::zero(), Q32::max()));
    }
    {
      const Coeffs k = limit(j.step_soft, j.upper - position, ctx->inv_h, use_bias);
      const Q32 impulse = soft_impulse(mass, -cdot_of(), k, j.upper_impulse);
      apply_axial(-accumulate(&j.upper_impulse, impulse, Q32::zero(), Q32::max()));
    }
  }
}

/// The 2D point constraint between anchors ra and rb with position error c
/// (pb − pa): soft (rate, mass scale, impulse scale) or plain; accumulates
/// into *acc and applies. Returns the applied impulse.
Vec2 solve_point(Pair* p, Vec2 ra, Vec2 rb, Vec2 c, const Softness* soft, Vec2* acc) {
  const Vec2 cdot = point_velocity(*p, ra, rb);
  Vec2 bias{};
  Q32 mass_scale = Q32::one(), impulse_scale = Q32::zero();
  if (soft != nullptr) {
    bias = soft->bias_rate * c;
    mass_scale = soft->mass_scale;
    impulse_scale = soft->impulse_scale;
  }
  const Vec2 x = solve(point_mass(*p, ra, rb), cdot + bias);
  const Vec2 impulse = -(mass_scale * x) - impulse_scale * *acc;
  *acc = *acc + impulse;
  apply(p, impulse, cross(ra, impulse), cross(rb, impulse));
  return impulse;
}

// --- per kind ----------------------------------------------------------------

struct Anchors {
  Vec2 ra, rb, d;  ///< anchors from the centres (world frame) and pb − pa, m
};

Anchors anchors(const Joint& j, const Pair& p) {
  Anchors a;
  a.ra = rotate(p.a.q, j.step_local_a);
  a.rb = rotate(p.b.q, j.step_local_b);
  a.d = (p.b.c + a.rb) - (p.a.c + a.ra);
  return a;
}

void solve_revolute(Joint& j, Pair* p, const StepContext* ctx, bool use_bias) {
  const Q32 axial_mass = inverse_or_zero(p->ia + p->ib);
  const Q32 angle = joint_angle_of(*p, j.reference_angle);
  solve_axis(j, axial_mass, angle, Q32::zero(), j.enable_spring, j.enable_motor, j.enable_limit, use_bias, ctx,
             [&] { return p->b.w - p->a.w; }, [&](Q32 impulse) { apply(p, Vec2{}, impulse, impulse); });
  const Anchors an = anchors(j, *p);
  solve_point(p, an.ra, an.rb, an.d, use_bias ? &j.step_soft : nullptr, &j.linear_impulse);
}

void solve_weld(Joint& j, Pair* p, bool use_bias) {
  const Q32 axial_mass = inverse_or_zero(p->ia + p->ib);
  if (axial_mass > Q32::zero()) {
    const bool spring = j.angular_hertz > Q32::zero();
    Coeffs k;
    if (spring || use_bias) {
      const Softness& soft = spring ? j.step_angular_spring : j.step_soft;
      k = rigid(soft, joint_angle_of(*p, j.reference_angle), true);
    }
    const Q32 impulse = soft_impulse(axial_mass, p->b.w - p->a.w, k, j.angular_impulse);
    j.angular_impulse = j.angular_impulse + impulse;
    apply(p, Vec2{}, impulse, impulse);
  }
  const bool spring = j.hertz > Q32::zero();
  const Anchors an = anchors(j, *p);
  const Softness* soft = spring ? &j.step_spring : (use_bias ? &j.step_soft : nullptr);
  solve_point(p, an.ra, an.rb, an.d, soft, &j.linear_impulse);
}

void solve_distance(Joint& j, Pair* p, const StepContext* ctx, bool use_bias) {
  const Anchors an = anchors(j, *p);
  Q32 len;
  Vec2 axis = length_and_normalize(an.d, &len);
  if (len == Q32::zero()) axis = {Q32::one(), Q32::zero()};
  const Q32 cra = cross(an.ra, axis), crb = cross(an.rb, axis);
  const Q32 mass = inverse_or_zero(p->ma + p->mb + p->ia * cra * cra + p->ib * crb * crb);
  if (mass == Q32::zero()) return;
  const auto cdot_of = [&] { return dot(point_velocity(*p, an.ra, an.rb), axis); };
  const auto apply_axial = [&](Q32 impulse) {
    const Vec2 pv = impulse * axis;
    apply(p, pv, cross(an.ra, pv), cross(an.rb, pv));
  };
  if (!j.enable_spring) {
    const Coeffs k = rigid(j.step_soft, len - j.length, use_bias);
    const Q32 impulse = soft_impulse(mass, cdot_of(), k, j.axial_impulse);
    j.axial_impulse = j.axial_impulse + impulse;
    apply_axial(impulse);
  }
  solve_axis(j, mass, len, j.length, j.enable_spring, j.enable_motor, j.enable_spring && j.enable_limit, use_bias,
             ctx, cdot_of, apply_axial);
}

/// Prismatic and wheel joints: the axis frame at the current poses.
struct AxisFrame {
  Anchors an;
  Vec2 axis, perp;
  Q32 a1, a2, s1, s2;  ///< (d + r_A) × axis, r_B × axis, (d + r_A) × perp, r_B × perp
  Q32 translation;
};

AxisFrame axis_frame(const Joint& j, const Pair& p) {
  AxisFrame f;
  f.an = anchors(j, p);
  f.axis = rotate(p.a.q, j.local_axis_a);
  f.perp = left_perp(f.axis);
  const Vec2 arm_a = f.an.d + f.an.ra;
  f.a1 = cross(arm_a, f.axis);
  f.a2 = cross(f.an.rb, f.axis);
  f.s1 = cross(arm_a, f.perp);
  f.s2 = cross(f.an.rb, f.perp);
  f.translation = dot(f.axis, f.an.d);
  return f;
}

void solve_slider(Joint& j, Pair* p, const StepContext* ctx, bool use_bias) {
  const bool wheel = j.type == JointType::wheel;
  const AxisFrame f = axis_frame(j, *p);
  const Q32 axial_mass = inverse_or_zero(p->ma + p->mb + p->ia * f.a1 * f.a1 + p->ib * f.a2 * f.a2);
  const auto cdot_of = [&] { return dot(f.axis, p->b.v - p->a.v) + f.a2 * p->b.w - f.a1 * p->a.w; };
  const auto apply_axial = [&](Q32 impulse) { apply(p, impulse * f.axis, impulse * f.a1, impulse * f.a2); };
  if (wheel) {
    // Spring and limits along the axis; the motor turns B relative to A.
    solve_axis(j, axial_mass, f.translation, Q32::zero(), j.enable_spring, false, j.enable_limit, use_bias, ctx,
               cdot_of, apply_axial);
    if (j.enable_motor) {
      const Q32 angular_mass = inverse_or_zero(p->ia + p->ib);
      const Q32 max_impulse = ctx->h * j.max_motor_force;
      const Q32 impulse = -(angular_mass * ((p->b.w - p->a.w) - j.motor_speed));
      const Q32 applied = accumulate(&j.motor_impulse, impulse, -max_impulse, max_impulse);
      apply(p, Vec2{}, applied, applied);
    }
    // Perpendicular: a scalar point-on-line constraint.
    const Q32 perp_mass = inverse_or_zero(p->ma + p->mb + p->ia * f.s1 * f.s1 + p->ib * f.s2 * f.s2);
    const Q32 cdot = dot(f.perp, p->b.v - p->a.v) + f.s2 * p->b.w - f.s1 * p->a.w;
    const Coeffs k = rigid(j.step_soft, dot(f.perp, f.an.d), use_bias);
    const Q32 impulse = soft_impulse(perp_mass, cdot, k, j.linear_impulse.x);
    j.linear_impulse.x = j.linear_impulse.x + impulse;
    apply(p, impulse * f.perp, impulse * f.s1, impulse * f.s2);
    return;
  }
  solve_axis(j, axial_mass, f.translation, Q32::zero(), j.enable_spring, j.enable_motor, j.enable_limit, use_bias, ctx,
             cdot_of, apply_axial);
  // Perpendicular and angular together: a 2×2 block.
  const Q32 k11 = p->ma + p->mb + p->ia * f.s1 * f.s1 + p->ib * f.s2 * f.s2;
  const Q32 k12 = p->ia * f.s1 + p->ib * f.s2;
  Q32 k22 = p->ia + p->ib;
  if (k22 == Q32::zero()) k22 = Q32::one();  // no rotation on either side: the angular row is idle
  const Vec2 cdot{dot(f.perp, p->b.v - p->a.v) + f.s2 * p->b.w - f.s1 * p->a.w, p->b.w - p->a.w};
  Vec2 bias{};
  Q32 mass_scale = Q32::one(), impulse_scale = Q32::zero();
  if (use_bias) {
    const Vec2 c{dot(f.perp, f.an.d), joint_angle_of(*p, j.reference_angle)};
    bias = j.step_soft.bias_rate * c;
    mass_scale = j.step_soft.mass_scale;
    impulse_scale = j.step_soft.impulse_scale;
  }
  const Vec2 acc{j.linear_impulse.x, j.angular_impulse};
  const Vec2 x = solve(Mat22{{k11, k12}, {k12, k22}}, cdot + bias);
  const Vec2 impulse = -(mass_scale * x) - impulse_scale * acc;
  j.linear_impulse.x = j.linear_impulse.x + impulse.x;
  j.angular_impulse = j.angular_impulse + impulse.y;
  apply(p, impulse.x * f.perp, impulse.x * f.s1 + impulse.y, impulse.x * f.s2 + impulse.y);
}

void solve_mouse(Joint& j, Pair* p, const StepContext* ctx) {
  if (p->mb == Q32::zero() && p->ib == Q32::zero()) return;
  const Vec2 rb = rotate(p->b.q, j.step_local_b);
  const Vec2 c = (p->b.c + rb) - j.target;
  const Vec2 cdot = p->b.v + cross(p->b.w, rb);
  const Q32 k11 = p->mb + p->ib * rb.y * rb.y;
  const Q32 k12 = -(p->ib * rb.x * rb.y);
  const Q32 k22 = p->mb + p->ib * rb.x * rb.x;
  const Vec2 x = solve(Mat22{{k11, k12}, {k12, k22}}, cdot + j.step_spring.bias_rate * c);
  Vec2 impulse = -(j.step_spring.mass_scale * x) - j.step_spring.impulse_scale * j.linear_impulse;
  const Vec2 old = j.linear_impulse;
  Vec2 acc = old + impulse;
  const Q32 max_impulse = ctx->h * j.max_force;
  if (length_exceeds(acc, max_impulse)) acc = normalize(acc) * max_impulse;
  j.linear_impulse = acc;
  impulse = acc - old;
  p->b.v = p->b.v + p->mb * impulse;
  p->b.w = p->b.w + p->ib * cross(rb, impulse);
}

void solve_motor(Joint& j, Pair* p, const StepContext* ctx, bool use_bias) {
  const Q32 correction = use_bias ? j.correction_factor * ctx->inv_h : Q32::zero();
  const Q32 axial_mass = inverse_or_zero(p->ia + p->ib);
  if (axial_mass > Q32::zero()) {
    const Q32 c = joint_angle_of(*p, j.angular_offset);
    const Q32 max_impulse = ctx->h * j.max_torque;
    const Q32 impulse = -(axial_mass * ((p->b.w - p->a.w) + correction * c));
    const Q32 applied = accumulate(&j.angular_impulse, impulse, -max_impulse, max_impulse);
    apply(p, Vec2{}, applied, applied);
  }
  const Anchors an = anchors(j, *p);
  const Vec2 c = an.d - rotate(p->a.q, j.target);
  const Vec2 cdot = point_velocity(*p, an.ra, an.rb);
  const Vec2 x = solve(point_mass(*p, an.ra, an.rb), cdot + correction * c);
  const Vec2 old = j.linear_impulse;
  Vec2 acc = old - x;
  const Q32 max_impulse = ctx->h * j.max_force;
  if (length_exceeds(acc, max_impulse)) acc = normalize(acc) * max_impulse;
  j.linear_impulse = acc;
  const Vec2 impulse = acc - old;
  apply(p, impulse, cross(an.ra, impulse), cross(an.rb, impulse));
}

void solve_one(Joint& j, StepContext* ctx, bool use_bias) {
  Pair p = load(j, ctx);
  switch (j.type) {
    case JointType::revolute: solve_revolute(j, &p, ctx, use_bias); break;
    case JointType::distance: solve_distance(j, &p, ctx, use_bias); break;
    case JointType::weld: solve_weld(j, &p, use_bias); break;
    case JointType::prismatic:
    case JointType::wheel: solve_slider(j, &p, ctx, use_bias); break;
    case JointType::mouse: solve_mouse(j, &p, ctx); break;
    case JointType::motor: solve_motor(j, &p, ctx, use_bias); break;
  }
  store(j, p, ctx);
}

/// The total impulse a joint applies to B (linear, and angular about B's
/// centre excluding the lever of the linear part), at the current poses.
void total_impulse(const Joint& j, const Pair& p, Vec2* out_linear, Q32* out_angular) {
  const Q32 axial = j.spring_impulse + j.motor_impulse + j.lower_impulse - j.upper_impulse;
  switch (j.type) {
    case JointType::revolute:
      *out_linear = j.linear_impulse;
      *out_angular = axial;
      return;
    case JointType::distance: {
      const Anchors an = anchors(j, p);
      Vec2 axis = normalize(an.d);
      if (axis == Vec2{}) axis = {Q32::one(), Q32::zero()};
      *out_linear = (j.axial_impulse + axial) * axis;
      *out_angular = Q32::zero();
      return;
    }
    case JointType::weld:
    case JointType::motor:
      *out_linear = j.linear_impulse;
      *out_angular = j.angular_impulse;
      return;
    case JointType::prismatic: {
      const AxisFrame f = axis_frame(j, p);
      *out_linear = axial * f.axis + j.linear_impulse.x * f.perp;
      *out_angular = j.angular_impulse;
      return;
    }
    case JointType::wheel: {
      const AxisFrame f = axis_frame(j, p);
      const Q32 along = j.spring_impulse + j.lower_impulse - j.upper_impulse;
      *out_linear = along * f.axis + j.linear_impulse.x * f.perp;
      *out_angular = j.motor_impulse;
      return;
    }
    case JointType::mouse:
      *out_linear = j.linear_impulse;
      *out_angular = Q32::zero();
      return;
  }
}

void warm_start_one(Joint& j, StepContext* ctx) {
  Pair p = load(j, ctx);
  Vec2 linear;
  Q32 angular;
  total_impulse(j, p, &linear, &angular);
  if (j.type == JointType::mouse) {
    const Vec2 rb = rotate(p.b.q, j.step_local_b);
    p.b.v = p.b.v + p.mb * linear;
    p.b.w = p.b.w + p.ib * cross(rb, linear);
  } else if (j.type == JointType::prismatic || j.type == JointType::wheel) {
    const AxisFrame f = axis_frame(j, p);
    const Q32 along = j.type == JointType::wheel ? j.spring_impulse + j.lower_impulse - j.upper_impulse
                                                 : j.spring_impulse + j.motor_impulse + j.lower_impulse - j.upper_impulse;
    const Q32 la = along * f.a1 + j.linear_impulse.x * f.s1 + angular;
    const Q32 lb = along * f.a2 + j.linear_impulse.x * f.s2 + angular;
    apply(&p, linear, la, lb);
  } else {
    const Anchors an = anchors(j, p);
    apply(&p, linear, cross(an.ra, linear) + angular, cross(an.rb, linear) + angular);
  }
  store(j, p, ctx);
}

/// The rigid position pass of one revolute joint (file comment): removes the
/// anchor gap beyond k_joint_slop by moving the simulated sides' poses.
bool project_revolute(const Joint& j, StepContext* ctx) {
  if (j.type != JointType::revolute) return false;
  const Pair p = load(j, ctx);
  const Anchors an = anchors(j, p);
  // Inside the square of half side slop/√2 the gap is within the slop: no root.
  if (abs(an.d.x) <= k_joint_slop_inner && abs(an.d.y) <= k_joint_slop_inner) return false;
  Q32 gap;
  const Vec2 n = length_and_normalize(an.d, &gap);
  if (gap <= k_joint_slop) return false;
  Vec2 impulse = -solve(point_mass(p, an.ra, an.rb), (gap - k_joint_slop) * n);
  // The turns, i⁻¹·(r × P) (zero for a side that is not simulated: i⁻¹ = 0).
  Q32 turn_a = p.ia * cross(an.ra, impulse), turn_b = p.ib * cross(an.rb, impulse);
  const Q32 largest = max(abs(turn_a), abs(turn_b));
  if (largest > k_max_projection_turn) {
    // Scale the whole correction down to the largest turn (see its comment).
    impulse = impulse * (k_max_projection_turn / largest);
    turn_a = p.ia * cross(an.ra, impulse);
    turn_b = p.ib * cross(an.rb, impulse);
  }
  // q turned by `angle`: first-order when small, else exactly (see
  // k_small_projection_turn).
  const auto turn = [](Rot q, Q32 angle) {
    if (abs(angle) <= k_small_projection_turn) return integrate_rotation(q, angle);
    return rot_normalize(mul_rot(rot_from_angle(angle), q));
  };
  if (j.step_solver_a >= 0) {
    BodyState& s = ctx->states[j.step_solver_a];
    s.center = s.center - p.ma * impulse;
    s.rotation = turn(s.rotation, -turn_a);
  }
  if (j.step_solver_b >= 0) {
    BodyState& s = ctx->states[j.step_solver_b];
    s.center = s.center + p.mb * impulse;
    s.rotation = turn(s.rotation, turn_b);
  }
  return true;
}

bool is_sleeping(const Body& b) { return b.type != BodyType::static_body && b.enabled && !b.awake; }

bool wakes_others(const Body& b) {
  if (!body_is_simulated(b)) return false;
  return b.type == BodyType::dynamic_body || b.sleep_time == Q32::zero();
}

template <typename F>
void for_active_joints(World* world, F f) {
  const int32_t end = id_pool_capacity(world->joint_pool);
  for (int32_t i = 0; i < end; ++i) {
    if (!id_pool_is_alive(world->joint_pool, i)) continue;
    Joint& j = world->joints.joints[static_cast<size_t>(i)];
    if (j.step_active) f(j);
  }
}

}  // namespace

void stage_wake_joined(World* world, StepContext* context) {
  (void)context;
  if (world->joint_pool.alive_count == 0) return;
  const int32_t end = id_pool_capacity(world->joint_pool);
  for (int32_t i = 0; i < end; ++i) {
    if (!id_pool_is_alive(world->joint_pool, i)) continue;
    const Joint& j = world->joints.joints[static_cast<size_t>(i)];
    const Body& a = world->bodies[static_cast<size_t>(j.body_a)];
    const Body& b = world->bodies[static_cast<size_t>(j.body_b)];
    if (is_sleeping(a) && wakes_others(b)) wake_body_island(world, j.body_a);
    if (is_sleeping(b) && wakes_others(a)) wake_body_island(world, j.body_b);
  }
}

void stage_prepare_joints(World* world, StepContext* context) {
  if (world->joint_pool.alive_count == 0) return;
  const Q32 h = context->h;
  context->inv_h = Q32::one() / h;  // as prepare_contact_constraints (same value)
  const Softness joint_soft = make_softness(world->def.joint_hertz, world->def.joint_damping_ratio, h);
  const int32_t end = id_pool_capacity(world->joint_pool);
  for (int32_t i = 0; i < end; ++i) {
    if (!id_pool_is_alive(world->joint_pool, i)) continue;
    Joint& j = world->joints.joints[static_cast<size_t>(i)];
    const size_t a = static_cast<size_t>(j.body_a), b = static_cast<size_t>(j.body_b);
    j.step_solver_a = context->body_to_solver[a];
    j.step_solver_b = context->body_to_solver[b];
    j.step_broken = false;
    j.step_active = world->bodies[a].enabled && world->bodies[b].enabled &&
                    (j.step_solver_a != k_null_index || j.step_solver_b != k_null_index);
    if (!j.step_active) continue;
    const BodySim& sa = world->body_sims[a];
    const BodySim& sb = world->body_sims[b];
    j.step_inv_mass_a = j.step_solver_a >= 0 ? context->params[j.step_solver_a].inv_mass : Q32::zero();
    j.step_inv_inertia_a = j.step_solver_a >= 0 ? context->params[j.step_solver_a].inv_inertia : Q32::zero();
    j.step_inv_mass_b = j.step_solver_b >= 0 ? context->params[j.step_solver_b].inv_mass : Q32::zero();
    j.step_inv_inertia_b = j.step_solver_b >= 0 ? context->params[j.step_solver_b].inv_inertia : Q32::zero();
    j.step_center_a = sa.center;
    j.step_rotation_a = sa.transform.q;
    j.step_center_b = sb.center;
    j.step_rotation_b = sb.transform.q;
    j.step_local_a = j.local_anchor_a - sa.local_center;
    j.step_local_b = j.local_anchor_b - sb.local_center;
    j.step_soft = joint_soft;
    j.step_spring = j.hertz > Q32::zero() ? make_softness(j.hertz, j.damping_ratio, h) : Softness{};
    j.step_angular_spring =
        j.angular_hertz > Q32::zero() ? make_softness(j.angular_hertz, j.angular_damping_ratio, h) : Softness{};
  }
}

void stage_warm_start_joints(World* world, StepContext* context) {
  if (world->joint_pool.alive_count == 0) return;
  for_active_joints(world, [&](Joint& j) { warm_start_one(j, context); });
}

void stage_solve_joints(World* world, StepContext* context) {
  if (world->joint_pool.alive_count == 0) return;
  for_active_joints(world, [&](Joint& j) { solve_one(j, context, true); });
}

void stage_relax_joints(World* world, StepContext* context) {
  if (world->joint_pool.alive_count == 0) return;
  for_active_joints(world, [&](Joint& j) { solve_one(j, context, false); });
}

void stage_project_joints(World* world, StepContext* context) {
  if (world->joint_pool.alive_count == 0) return;
  for (int32_t pass = 0; pass < k_joint_project_passes; ++pass) {
    bool moved = false;  // a pass that moved nothing ends the projection
    for_active_joints(world, [&](Joint& j) { moved = project_revolute(j, context) || moved; });
    if (!moved) break;
  }
}

namespace {

/// Holds a joint's accumulated impulses to ±k_max_restored_joint_impulse
/// (4·10⁸ N·s: the momentum of the heaviest body at four times the top
/// speed), the range world_restore accepts, so a step never stores a joint
/// its own snapshot cannot restore. Only a joint fighting another
/// constraint gets there (random-world stress with joint inputs: 10 of seeds
/// 1-1,000), and its warm start would only feed the fight.
void hold_impulses(Joint* j) {
  const Q32 m = state_fields::k_max_restored_joint_impulse;
  j->linear_impulse = {clamp(j->linear_impulse.x, -m, m), clamp(j->linear_impulse.y, -m, m)};
  j->angular_impulse = clamp(j->angular_impulse, -m, m);
  j->axial_impulse = clamp(j->axial_impulse, -m, m);
  j->spring_impulse = clamp(j->spring_impulse, -m, m);
  j->motor_impulse = clamp(j->motor_impulse, -m, m);
  j->lower_impulse = clamp(j->lower_impulse, -m, m);
  j->upper_impulse = clamp(j->upper_impulse, -m, m);
}

}  // namespace

void stage_store_joints(World* world, StepContext* context) {
  JointWorld& jw = world->joints;
  if (world->joint_pool.alive_count == 0 && jw.pending.empty() && jw.events.empty()) return;
  jw.events.clear();
  for (const JointEvent& e : jw.pending) jw.events.push_back(e);
  jw.pending.clear();
  const Q32 inv_h = context->inv_h;
  bool any_broken = false;
  const int32_t end = id_pool_capacity(world->joint_pool);
  for (int32_t i = 0; i < end; ++i) {
    if (!id_pool_is_alive(world->joint_pool, i)) continue;
    Joint& j = jw.joints[static_cast<size_t>(i)];
    if (!j.step_active) {
      j.reaction_force = {};
      j.reaction_torque = Q32::zero();
      continue;
    }
    hold_impulses(&j);
    const Pair p = load(j, context);
    Vec2 linear;
    Q32 angular;
    total_impulse(j, p, &linear, &angular);
    j.reaction_force = inv_h * linear;
    j.reaction_torque = inv_h * angular;
    const bool force_breaks = j.break_force > Q32::zero() && length_exceeds(j.reaction_force, j.break_force);
    const bool torque_breaks = j.break_torque > Q32::zero() && abs(j.reaction_torque) > j.break_torque;
    if (!force_breaks && !torque_breaks) continue;
    JointEvent e;
    e.joint = make_joint_id(*world, i);
    e.body_a = make_body_id(*world, j.body_a);
    e.body_b = make_body_id(*world, j.body_b);
    e.kind = JointEventKind::broke;
    e.force = j.reaction_force;
    e.torque = j.reaction_torque;
    e.user_data = j.user_data;
    jw.events.push_back(e);
    free_joint(world, i);
    any_broken = true;
  }
  if (any_broken) rebuild_joint_filter(world);
}

}  // namespace tandem
