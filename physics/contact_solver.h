// contact_solver.h — contact constraints of one step (internal): the
// per-step solver records built from touching contacts, and the stages that
// prepare, warm start, solve, relax and store them (contact_solver.cpp
// explains the formulation).
//
// Layout for batching: the constraints of a step are one contiguous arena
// array in contact order; each refers to its two bodies only by SOLVER index
// (k_null_index for a body that is not simulated: static, sleeping, disabled)
// and carries copies of their inverse masses, so the inner loops read
// BodyState and the constraint and nothing else. The array is ordered by
// graph colour (prepare_contact_constraints): the constraints of one colour
// touch disjoint movable bodies, so a wide solver can transpose a colour into
// lanes without changing these records.
#pragma once

#include <cstdint>

#include "fixed/fixed.h"
#include "fixed/vec2.h"

namespace tandem {

struct World;
struct StepContext;
struct ContactLanes;

/// Which code solves the constraints of the graph colours (warm start,
/// solve, relax, approach, store): the scalar reference, one constraint at a
/// time, or the lanes (contact_lanes.h), k_contact_lanes constraints side by
/// side. Both compute the same bits. Not state: the build picks the default
/// (CMake TANDEM_CONTACT_LANES), tests and benchmarks may switch it between
/// steps (never during one).
enum class ContactSolverPath : int32_t { scalar = 0, lanes = 1 };

/// The path the next prepare_contact_constraints selects.
ContactSolverPath contact_solver_path();
/// Selects the path for the steps that follow (process-wide; call between
/// steps only).
void set_contact_solver_path(ContactSolverPath path);

/// Graph colours for contact constraints; constraints that find none of
/// them free are solved last, in an overflow group.
inline constexpr int32_t k_contact_colour_count = 24;

/// Soft constraint coefficients for one stiffness at one sub-step (Box2D v3's
/// "soft step"): with ω = 2π·hertz, a1 = 2ζ + hω, a2 = hω·a1, a3 = 1/(1 + a2):
/// bias_rate = ω/a1 (1/s), mass_scale = a2·a3, impulse_scale = a3
/// (dimensionless). Each is one rounded Q32 operation on the previous ones.
struct Softness {
  Q32 bias_rate;      ///< 1/s
  Q32 mass_scale;     ///< dimensionless, in (0, 1)
  Q32 impulse_scale;  ///< dimensionless, in (0, 1)
};

/// The softness of a spring of `hertz` (Hz, > 0) and damping ratio `zeta`
/// (≥ 0) over a sub-step of h seconds (> 0); see Softness. Rounded to nearest
/// at each operation; no saturation for hertz, zeta ≤ 1e4 and h ≤ 1 s.
Softness make_softness(Q32 hertz, Q32 zeta, Q32 h);

/// One point of a contact constraint.
struct ContactConstraintPoint {
  Q32 rn_a;                   ///< r_A × n: A's anchor (from its centre of mass, fixed for the step) across the normal, m
  Q32 rn_b;                   ///< r_B × n, m
  Q32 rt_a;                   ///< r_A × t (t = right_perp(n)), m
  Q32 rt_b;                   ///< r_B × t, m
  Q32 angular_n_a;            ///< I_A⁻¹ · (r_A × n): A's spin per unit normal impulse, 1/(kg·m)
  Q32 angular_n_b;            ///< I_B⁻¹ · (r_B × n)
  Q32 angular_t_a;            ///< I_A⁻¹ · (r_A × t)
  Q32 angular_t_b;            ///< I_B⁻¹ · (r_B × t)
  Vec2 local_a;               ///< anchor in A's body frame (or the world point when A is not simulated), m
  Vec2 local_b;               ///< the same for B, m
  Q32 adjusted_separation;    ///< the manifold separation (the anchors close exactly at the start of the step), m
  Q32 normal_impulse;         ///< accumulated this sub-step, N·s
  Q32 tangent_impulse;        ///< accumulated this sub-step, N·s
  Q32 normal_mass;            ///< 1/k_normal, kg (0 when k is 0)
  Q32 soft_normal_mass;       ///< normal_mass · mass_scale of the constraint's softness, kg
  Q32 tangent_mass;           ///< 1/k_tangent, kg
  Q32 approach_velocity;      ///< relative normal velocity before this sub-step's gravity, m/s (< 0: closing)
  Q32 bounce_velocity;        ///< target separating speed of a latched bounce, m/s
  Q32 separation;             ///< current separation at the last relax pass (the poses the next solve sees), m
  int32_t bounce_sub_step = -1;  ///< sub-step in which the bounce latched, or −1
  int32_t active_sub_step = -1;  ///< last sub-step whose biased solve found the point touching or about to
};

/// A contact constraint for one step, in the arena.
struct ContactConstraint {
  int32_t solver_a = -1;       ///< solver index of body A or k_null_index
  int32_t solver_b = -1;       ///< solver index of body B or k_null_index
  int32_t contact_index = 0;   ///< into World::contacts
  int32_t point_count = 0;     ///< 1 or 2
  Vec2 normal;                 ///< unit, from A to B
  Q32 inv_mass_a;              ///< 1/kg (0 when not simulated)
  Q32 inv_inertia_a;           ///< 1/(kg·m²)
  Q32 inv_mass_b;
  Q32 inv_inertia_b;
  Q32 friction;                ///< mixed, dimensionless
  Q32 restitution;             ///< mixed, dimensionless
  Q32 kick;                    ///< normal part of the per-sub-step velocity change from gravity/forces, m/s
  Softness softness;           ///< contact or static softness
  ContactConstraintPoint points[2];
};

/// Builds the step's constraints (arena) from touching contacts with at least
/// one simulated body, in contact order, and the per-step constants; on the
/// lanes path also their lane blocks (pack_contact_lanes).
void prepare_contact_constraints(World* world, StepContext* context);
/// Transposes the constraints of the graph colours into lane blocks (arena,
/// after the constraints; freed by store_contact_impulses), or sets
/// context->lanes to null on the scalar path.
void pack_contact_lanes(World* world, StepContext* context);
/// Records each point's relative normal velocity (the bounce reference) at
/// the start of a sub-step, before gravity and forces are integrated.
void record_contact_approach(StepContext* context);
/// Applies the accumulated impulses (a point that bounced in the previous
/// sub-step starts from zero instead).
void warm_start_contacts(StepContext* context);
/// One Gauss-Seidel pass with position bias and bounce latching.
void solve_contacts(StepContext* context);
/// The relax pass without bias; two more passes over the constraints of
/// bodies that bounced in this sub-step.
void relax_contacts(StepContext* context);
/// Writes impulses back to the contacts for the next step's warm start and
/// frees the constraint arrays.
void store_contact_impulses(World* world, StepContext* context);

}  // namespace tandem
