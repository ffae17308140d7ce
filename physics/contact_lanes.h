// contact_lanes.h — the contact constraints of one graph colour in lanes
// (internal): structure-of-arrays blocks of k_contact_lanes constraints,
// transposed from the step's ContactConstraint array after prepare
// (contact_lanes.cpp, pack_contact_lanes) and solved lane by lane.
//
// Why lanes: the constraints of one colour touch disjoint movable bodies, so
// the k_contact_lanes constraints of a block can be gathered, solved side by
// side and scattered with the same result as solving them one after another.
// Each field is a short array over the lanes, so the kernels in
// contact_lanes.cpp are loops `for lane in 0…k_contact_lanes−1` over plain
// Q32.32 values with the control flow of the scalar solver turned into
// per-lane selects (touching, active, bouncing, skipped). The arithmetic of
// a lane is the scalar path's own in_range helpers, in the same order, so a
// lane computes the scalar path's bits by construction, whatever the
// compiler does with the loop (tests/physics/test_contact_lanes.cpp runs
// both paths side by side and compares every step).
//
// Padding: the last block of a colour is filled with empty lanes (no bodies,
// zero data, no points present); an empty lane changes nothing. The overflow
// colour, whose constraints may share bodies, stays in the scalar array and
// is solved serially after the lanes.
//
// Status: correct (same bits, tested) but NOT faster. No compiler vectorises
// a 64×64→128 product with rounding, so each lane still runs scalar
// multiplies; the lane form adds the selects and keeps the block's
// velocities in memory instead of registers. callgrind counts ~14 % more
// instructions for solve + relax on pyramid-100 and the wall clock is slower
// (docs/benchmarks.md, "Wide contact solver"), so the build's default path
// is the scalar one (CMake TANDEM_CONTACT_LANES=OFF). The blocks are the
// layout an explicit vector kernel would consume.
//
// Rejected (for now): blocks of 8 (no 8-wide 64-bit integer multiply on the
// targets we build; 4 fills an AVX2 register of 64-bit values); an explicit
// intrinsic path: a 64×64→128 product with rounding and exact saturation
// has no vector instruction (four 32×32 partial products, carries, then the
// rounding and the saturation test per lane), and
// shared/reference/wide-products measured even a 4-lane AVX2 64×32 product
// at only ~1.4× a branch-free scalar one.
#pragma once

#include <cstdint>

#include "fixed/fixed.h"

namespace tandem {

/// Constraints per block of the lane solver.
inline constexpr int32_t k_contact_lanes = 4;

/// One contact point of the k_contact_lanes constraints of a block, one array
/// element per lane (units and meaning as ContactConstraintPoint).
struct ContactLanePoint {
  Q32 rn_a[k_contact_lanes];                ///< r_A × n, m
  Q32 rn_b[k_contact_lanes];                ///< r_B × n, m
  Q32 rt_a[k_contact_lanes];                ///< r_A × t, m
  Q32 rt_b[k_contact_lanes];                ///< r_B × t, m
  Q32 angular_n_a[k_contact_lanes];         ///< I_A⁻¹ · (r_A × n), 1/(kg·m)
  Q32 angular_n_b[k_contact_lanes];
  Q32 angular_t_a[k_contact_lanes];
  Q32 angular_t_b[k_contact_lanes];
  Q32 local_a_x[k_contact_lanes];           ///< anchor in A's body frame (world point for a missing A), m
  Q32 local_a_y[k_contact_lanes];
  Q32 local_b_x[k_contact_lanes];
  Q32 local_b_y[k_contact_lanes];
  Q32 adjusted_separation[k_contact_lanes];  ///< m
  Q32 normal_impulse[k_contact_lanes];      ///< N·s
  Q32 tangent_impulse[k_contact_lanes];     ///< N·s
  Q32 normal_mass[k_contact_lanes];         ///< kg
  Q32 soft_normal_mass[k_contact_lanes];    ///< kg
  Q32 tangent_mass[k_contact_lanes];        ///< kg
  Q32 approach_velocity[k_contact_lanes];   ///< m/s
  Q32 bounce_velocity[k_contact_lanes];     ///< m/s
  int32_t bounce_sub_step[k_contact_lanes];  ///< or −1
  int32_t active_sub_step[k_contact_lanes];  ///< or −1
  int32_t present[k_contact_lanes];          ///< 1 when the lane's constraint has this point, else 0
};

/// k_contact_lanes constraints of one colour (units as ContactConstraint).
struct ContactLanes {
  int32_t solver_a[k_contact_lanes];        ///< solver index of A, or k_null_index (also for an empty lane)
  int32_t solver_b[k_contact_lanes];
  int32_t contact_index[k_contact_lanes];   ///< into World::contacts, or −1 for an empty lane
  int32_t movable_a[k_contact_lanes];       ///< 1 when A is written back (nonzero inverse mass or inertia)
  int32_t movable_b[k_contact_lanes];
  Q32 normal_x[k_contact_lanes];            ///< unit normal from A to B
  Q32 normal_y[k_contact_lanes];
  Q32 inv_mass_a[k_contact_lanes];          ///< 1/kg
  Q32 inv_mass_b[k_contact_lanes];
  Q32 friction[k_contact_lanes];            ///< dimensionless
  Q32 restitution[k_contact_lanes];         ///< dimensionless
  Q32 kick[k_contact_lanes];                ///< m/s
  Q32 bias_rate[k_contact_lanes];           ///< the constraint's Softness, 1/s
  Q32 impulse_scale[k_contact_lanes];       ///< dimensionless
  ContactLanePoint points[2];
};

}  // namespace tandem
