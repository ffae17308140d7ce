// contact_prepare.cpp — the per-step half of the contact solver: one
// constraint per touching contact with a simulated body (normal, inverse
// masses, friction, restitution, soft coefficients) and per point the
// anchors, lever-arm products, effective masses and warm-start impulses that
// the sub-step passes of contact_solver.cpp read. The arithmetic and range
// argument ("PER STEP", "Range of the preparation") is in contact_solver.cpp's
// opening comment and docs/determinism.md, "Range of the contact
// preparation". Split out of contact_solver.cpp (code moved, not changed).
//
// Cost (issue 20): ~1,000 instructions per touching contact on pyramid-100
// (998; x86-64 g++, callgrind; docs/benchmarks.md), of which ~320 per point (a
// box contact has two) go to its 17 rounded 128-bit products, 2 reciprocals
// and 22 stores. What the
// per-contact part avoids: reading four per-body arrays (SolverBodyParams,
// BodyState, BodySim, Body) per side and contact — a PrepBody record per
// solver body that some constraint reads is gathered once per step —
// and walking the awake index a third time: the colouring pass hands over
// each constraint's contact and solver indices (ConstraintJob).
//
// Workers: the counting pass, the colouring (which gives each constraint its
// slot: its colour's offset plus its rank in the colour) and one short pass
// that lists the bodies to gather run on the stepping thread in contact
// order; gathering the records and building the constraints run in blocks
// (task.h), each item writing only its own record or constraint, so the bits
// do not depend on the worker count. Making them parallel cost ~30
// instructions per contact on one thread (969 → 998: the listing pass, the
// slot lookup).
// Rejected: gathering every solver body's record up front (a scene of many
// bodies and few contacts, circles-16k: 16,000 bodies, 875 contacts, would
// pay for all of them); dropping the counting pass (the constraint array,
// allocated before the colouring's arena arrays and outliving them, needs
// the count first; the pass costs ~10 instructions per contact).
#include <bit>

#include "physics/contact_colour.h"
#include "physics/contact_lanes.h"
#include "physics/contact_solver.h"
#include "physics/contact_solver_internal.h"
#include "physics/fast_math.h"
#include "physics/world.h"

namespace tandem {

using namespace contact_internal;

namespace {

/// The largest angular term I⁻¹·r² of a contact's effective-mass denominator,
/// 1/kg: 64 times the largest inverse mass of a body (1/k_min_body_mass). See
/// "Range of the preparation" in contact_solver.cpp and docs/determinism.md.
constexpr int64_t k_max_contact_angular_inv_mass = 64000;

/// d², saturated at Q32::max() (an extent of at most 2·k_max_shape_size
/// squares to ≤ 4e8 m², far inside the range).
inline Q32 square_extent(Q32 d) { return fast::mul(d, d); }

/// The inverse inertia a contact constraint uses for a body whose contact
/// points lie within reach_sq (m²) of its centre of mass: I⁻¹ itself while
/// I⁻¹·reach² ≤ k_max_contact_angular_inv_mass, otherwise
/// k_max_contact_angular_inv_mass / reach² (< I⁻¹). The test is exact (a
/// 128-bit product), so a body under the bound keeps every bit of I⁻¹.
/// Whether contact_inv_inertia keeps I⁻¹ for this reach².
inline bool keeps_inv_inertia(Q32 inv_inertia, Q32 reach_sq) {
  if (inv_inertia <= Q32::zero() || reach_sq <= Q32::zero()) return true;
  // I⁻¹.raw · reach².raw > K · 2^64 ⇔ I⁻¹ · reach² > K (both factors ≥ 0).
  const wide::U128 p = wide::mul_s64(inv_inertia.raw, reach_sq.raw);
  const uint64_t k = static_cast<uint64_t>(k_max_contact_angular_inv_mass);
  return p.hi < k || (p.hi == k && p.lo == 0);
}

inline Q32 contact_inv_inertia(Q32 inv_inertia, Q32 reach_sq) {
  if (keeps_inv_inertia(inv_inertia, reach_sq)) return inv_inertia;
  return Q32::from_int(k_max_contact_angular_inv_mass) / reach_sq;
}

/// A per-body shortcut for contact_inv_inertia, computed once per step: a
/// bound c (raw Q32, a power of two, or 0 for none) such that every anchor r
/// with |r.x|, |r.y| < c leaves the body's I⁻¹ unchanged, so its contacts
/// skip the reach² dot products and the 128-bit test. Why that is exact:
/// with v = I⁻¹.raw > 0 and w = bit_width(v), I⁻¹ < 2^(w−32); c = 2^e m
/// with 2e + 1 + (w − 32) ≤ 15 (2^15 ≤ K = 64 000) gives I⁻¹·2c² < K, and
/// e ≤ 14 as well. An anchor inside the box has exact |r|² < 2c² = 2^(2e+1)
/// ≤ 2^29, a power of two that Q32 holds exactly, so its rounded dot product
/// (rounding is monotonic, nothing saturates) is ≤ 2c² too; if also I⁻¹·max_extent² ≤ K (the same exact test, done here
/// once), the reach² contact_inv_inertia would see is ≤ max(max_extent², 2c²)
/// and its test passes: it would return I⁻¹, bit for bit. Anything else (a
/// point outside the box, a body over the bound) takes the full path. I⁻¹ ≤ 0
/// is returned unchanged by contact_inv_inertia, so every anchor passes.
inline uint64_t contact_reach_box(Q32 inv_inertia, Q32 max_extent) {
  if (inv_inertia <= Q32::zero()) return ~uint64_t{0};
  if (!keeps_inv_inertia(inv_inertia, square_extent(max_extent))) return 0;
  const int32_t w = static_cast<int32_t>(std::bit_width(static_cast<uint64_t>(inv_inertia.raw)));  // 1 … 63
  const int32_t e2 = 46 - w;  // 2e ≤ 15 − 1 + 32 − w
  if (e2 < -64) return 0;
  const int32_t e = e2 >= 0 ? e2 / 2 : -((1 - e2) / 2);  // floor(e2 / 2)
  const int32_t shift = 32 + e;                          // c.raw = 2^(32 + e)
  if (shift <= 0) return 0;
  // At most 2^14 m (anchors lie within 2^15 m of the centre of mass): then
  // 2c² ≤ 2^29 m², so the dot products it stands for never saturate.
  return uint64_t{1} << (shift < 46 ? shift : 46);
}

/// The largest ratio of the two inverse masses a contact constraint sees
/// (issue 14): a body more than this many times lighter than the other body
/// of a contact responds in that contact as if it were 1/k_max_contact_mass_ratio
/// of the heavier one's mass (see cap_mass_ratio).
constexpr int64_t k_max_contact_mass_ratio = 100;

/// The per-contact mass-ratio cap (issue 14; PhysX's per-contact inverse mass
/// scales, Havok's mass-ratio clamping): when both bodies are dynamic and
/// m_light⁻¹ > R·m_heavy⁻¹ (R = k_max_contact_mass_ratio), the light side's
/// inverse mass becomes R·m_heavy⁻¹ and its inverse inertia is scaled by the
/// same factor s = R·m_heavy⁻¹ / m_light⁻¹ ∈ (0, 1): in this contact the light
/// body is a copy of itself R times lighter than the heavy one. Why: the soft
/// contact is as stiff as the lighter body (its effective mass), so a light
/// body under a heavy one cannot carry more than ~R times its own weight; the
/// ground under it then takes the load at the light body's stiffness
/// (1:1,000 sank 0.85 m, 1:10,000 tunnelled). With the cap every heavy-on-light
/// stack moves, per unit of velocity, as a 1:R stack does. The cost: the
/// contact gives the light body less velocity than its true mass would take
/// (momentum is not conserved in that contact), visible only at ratios over R.
/// Equal or near masses (every golden scene but the mass-ratio ones) keep
/// every bit. Range: R·m⁻¹ ≤ 100 · 1000 kg⁻¹; s·I⁻¹ < I⁻¹.
inline void cap_mass_ratio(Q32* inv_mass_light, Q32* inv_inertia_light, Q32 inv_mass_heavy) {
  if (inv_mass_heavy <= Q32::zero()) return;  // static or kinematic: no ratio
  const Q32 capped = Q32::from_raw(inv_mass_heavy.raw * k_max_contact_mass_ratio);
  if (*inv_mass_light <= capped) return;
  *inv_inertia_light = fast::mul(*inv_inertia_light, capped / *inv_mass_light);
  *inv_mass_light = capped;
}

// Unsaturated arithmetic of the per-point preparation. Every value it forms
// is far inside the Q32.32 range in every state the API and restore accept
// (the argument below), so the checked operators would neither saturate nor
// report a fault there, and the exact result wrapped through unsigned (add,
// sub) or rounded to the value fast::round_shift_words gives (to nearest,
// ties away from zero; no saturation test) is their result, bit for bit. Debug and
// sanitizer builds (and targets without __int128) use the checked operators
// instead, which would report a fault — and give other bits, caught by the
// golden chains of those builds — should the argument ever fail.
// The bounds (limits.h; "Range of the preparation" in contact_solver.cpp):
//   com offset c − p: the centre of mass lies within its body's shapes,
//     |c − p| ≤ max_extent ≤ 2·k_max_shape_size < 2^15 m;
//   anchors r = anchor − (c − p): a manifold point lies within the
//     speculative distance of both shapes (narrow phase, this step), so
//     |r| < 2^16 m, and so are both terms;
//   R⁻¹·r (rotation entries ≤ 1 + 2^-30), r × n, r × t (n unit): < 2^17 m;
//   I⁻¹_c·(r × n) < 2^24 and I⁻¹_c·(r × n)² ≤ 64 000 (the inverse-inertia
//     bound), m⁻¹ ≤ 1000 kg⁻¹: k < 2^17, every partial sum too;
//   normal_mass · mass_scale ≤ normal_mass (mass_scale ∈ (0, 1)).
// Each 128-bit sum of products is then below 2^82 in magnitude, far from
// round_shift's saturation threshold 2^95 − 2^31, and every add/sub result
// is below 2^49 raw. A static side's world anchor (c + r) keeps fast::add:
// a body that is not simulated may lie anywhere in range.
namespace unsat {
#if TANDEM_FAST_MATH_UNCHECKED
inline Q32 add(Q32 a, Q32 b) {
  return Q32::from_raw(static_cast<int64_t>(static_cast<uint64_t>(a.raw) + static_cast<uint64_t>(b.raw)));
}
inline Q32 sub(Q32 a, Q32 b) {
  return Q32::from_raw(static_cast<int64_t>(static_cast<uint64_t>(a.raw) - static_cast<uint64_t>(b.raw)));
}
/// fast::round_shift_words(lo, hi) of p: bits 32…95 of p + h with
/// h = 2^31 − [p < 0] < 2^32, formed as (p >> 32) + ((p mod 2^32 + h) >> 32)
/// (the low 32 bits of p plus h carry at most 1 into bit 32), the same value
/// modulo 2^64, which g++ compiles to shrd and three short 64-bit steps
/// instead of a 128-bit add, two shifts and an or.
inline Q32 round(fast::u128 p) {
  const uint64_t half = (uint64_t{1} << 31) - (static_cast<uint64_t>(p >> 64) >> 63);
  const uint64_t carry = (static_cast<uint64_t>(static_cast<uint32_t>(p)) + half) >> 32;
  return Q32::from_raw(static_cast<int64_t>(static_cast<uint64_t>(p >> 32) + carry));
}
inline Q32 mul(Q32 a, Q32 b) { return round(fast::product(a.raw, b.raw)); }
inline Q32 sum2(Q32 a, Q32 b, Q32 c, Q32 d) { return round(fast::product(a.raw, b.raw) + fast::product(c.raw, d.raw)); }
inline Q32 diff2(Q32 a, Q32 b, Q32 c, Q32 d) { return round(fast::product(a.raw, b.raw) - fast::product(c.raw, d.raw)); }
/// mul(a, b) for a·b ≥ 0 (the caller's sign argument): the exact product is
/// then below 2^126 and non-negative, its high word's sign bit is clear, and
/// round_shift_words' half is the constant 2^31: the same bits, two
/// instructions fewer.
inline Q32 mul_nonneg(Q32 a, Q32 b) {
  const fast::u128 p = fast::product(a.raw, b.raw) + (fast::u128{1} << 31);
  return Q32::from_raw(static_cast<int64_t>(static_cast<uint64_t>(p >> 32)));
}
#else
inline Q32 add(Q32 a, Q32 b) { return fast::add(a, b); }
inline Q32 sub(Q32 a, Q32 b) { return fast::sub(a, b); }
inline Q32 mul(Q32 a, Q32 b) { return fast::mul(a, b); }
inline Q32 sum2(Q32 a, Q32 b, Q32 c, Q32 d) { return fast::sum2(a, b, c, d); }
inline Q32 diff2(Q32 a, Q32 b, Q32 c, Q32 d) { return fast::diff2(a, b, c, d); }
inline Q32 mul_nonneg(Q32 a, Q32 b) { return fast::mul(a, b); }
#endif
inline Vec2 sub(Vec2 a, Vec2 b) { return {sub(a.x, b.x), sub(a.y, b.y)}; }
/// fast::cross(a, b).
inline Q32 cross(Vec2 a, Vec2 b) { return diff2(a.x, b.y, a.y, b.x); }
/// fast::inv_rotate(q, v).
inline Vec2 inv_rotate(Rot q, Vec2 v) { return {sum2(q.c, v.x, q.s, v.y), diff2(q.c, v.y, q.s, v.x)}; }
}  // namespace unsat

/// What the preparation reads of one side of a contact constraint, gathered
/// once per solver body and step (at the body's first constraint) instead of
/// from four arrays per contact (SolverBodyParams, BodyState, BodySim, Body).
/// A side that is not simulated gets a record built on the spot
/// (static_side): no mass, the identity rotation, its own centre offset.
struct PrepBody {
  Q32 inv_mass;         ///< SolverBodyParams::inv_mass, 1/kg (0: not simulated)
  Q32 inv_inertia;      ///< SolverBodyParams::inv_inertia, 1/(kg·m²) (0: not simulated)
  Rot rotation;         ///< BodyState::rotation (identity: not simulated)
  Vec2 com_offset;      ///< centre of mass − origin (BodySim center − transform.p), m
  Vec2 delta_velocity;  ///< SolverBodyParams::delta_linear_velocity, m/s (0: not simulated)
  /// The reach box (contact_reach_box, c raw) as an interval test: an anchor
  /// r is inside when has_box and r.x + box_offset, r.y + box_offset (raw,
  /// unsigned, wrapping) are both ≤ box_limit. c in 1 … 2^46: offset c − 1,
  /// limit 2c − 2 (−c < x < c ⇔ 0 ≤ x + c − 1 ≤ 2c − 2, and x + c − 1
  /// wraps to ≥ 2^64 − 2^46 for x ≤ −c, x + c − 1 ≥ 2c − 1 for x ≥ c, as
  /// every raw x is below 2^63 in magnitude); c all ones (any anchor):
  /// offset 0, limit all ones; c = 0 (none): has_box 0.
  uint64_t box_offset;
  uint64_t box_limit;
  int32_t has_box;  ///< 1, 0 (c = 0), or k_prep_body_unset (not yet gathered)
};

/// PrepBody::has_box of a record not yet gathered this step.
constexpr int32_t k_prep_body_unset = -1;

/// Items per block of the parallel loops (fixed, task.h): solver bodies
/// gathered, constraints built.
constexpr int32_t k_prep_body_block = 128;
constexpr int32_t k_prep_contact_block = 64;

/// Gathers solver body `solver_index`'s record (see PrepBody).
inline void gather_prep_body(const World& world, const StepContext& context, int32_t solver_index, PrepBody* out) {
  const int32_t body_index = context.solver_to_body[solver_index];
  const SolverBodyParams& p = context.params[solver_index];
  const BodySim& sim = world.body_sims[static_cast<size_t>(body_index)];
  out->inv_mass = p.inv_mass;
  out->inv_inertia = p.inv_inertia;
  out->rotation = context.states[solver_index].rotation;
  out->com_offset = unsat::sub(sim.center, sim.transform.p);
  out->delta_velocity = p.delta_linear_velocity;
  const uint64_t c = contact_reach_box(p.inv_inertia, world.bodies[static_cast<size_t>(body_index)].max_extent);
  out->has_box = c != 0 ? 1 : 0;
  out->box_offset = c == ~uint64_t{0} ? 0 : c - 1;
  out->box_limit = c == ~uint64_t{0} ? ~uint64_t{0} : 2 * c - 2;
}

/// The record of a side that is not simulated (I⁻¹ = 0 there, so any anchor
/// is inside its box).
inline PrepBody static_side(const BodySim& sim) {
  PrepBody r;
  r.inv_mass = Q32::zero();
  r.inv_inertia = Q32::zero();
  r.rotation = Rot{};
  r.com_offset = unsat::sub(sim.center, sim.transform.p);
  r.delta_velocity = Vec2{};
  r.box_offset = 0;
  r.box_limit = ~uint64_t{0};
  r.has_box = 1;
  return r;
}

/// Whether anchor v lies inside side b's reach box (PrepBody's interval test).
inline bool inside_reach_box(Vec2 v, const PrepBody& b) {
  return (static_cast<uint64_t>(v.x.raw) + b.box_offset <= b.box_limit) &
         (static_cast<uint64_t>(v.y.raw) + b.box_offset <= b.box_limit);
}

/// Builds the constraints of jobs [begin, end) (prepare_contact_constraints;
/// every argument a local, so nothing the stores below write can make the
/// compiler reload them).
void build_constraints(World* world, StepContext* context, const PrepBody* prep_bodies, const Contact* contacts,
                       const ConstraintJob* jobs, int32_t begin, int32_t end) {
  for (int32_t n = begin; n < end; ++n) {
    const ConstraintJob& job = jobs[n];
    const int32_t ci = job.contact, ia = job.solver_a, ib = job.solver_b;
    const Contact& c = contacts[static_cast<size_t>(ci)];
    PrepBody static_a, static_b;  // a side that is not simulated
    const PrepBody* side_a;
    const PrepBody* side_b;
    if (ia >= 0) {
      side_a = &prep_bodies[ia];
    } else {
      static_a = static_side(world->body_sims[static_cast<size_t>(c.body_a)]);
      side_a = &static_a;
    }
    if (ib >= 0) {
      side_b = &prep_bodies[ib];
    } else {
      static_b = static_side(world->body_sims[static_cast<size_t>(c.body_b)]);
      side_b = &static_b;
    }
    ContactConstraint& cc = context->constraints[context->colour_offsets[job.colour] + job.rank];
    // Every field is written below (the array is unwritten storage,
    // arena_allocate_array_for_overwrite): the header here, each used point in the loop, an
    // unused second point zeroed as a whole. A field added to either struct
    // must be written here too: the sizes are asserted so that a merge that
    // adds one stops at this line.
    // (Sizes of 64-bit targets; i686 packs 64-bit members at 4 bytes.)
    static_assert(sizeof(void*) != 8 || (sizeof(ContactConstraintPoint) == 176 &&
                                         sizeof(ContactConstraint) == 464),
                  "prepare_contact_constraints writes every field of ContactConstraint: add the new field there");
    cc.solver_a = ia;
    cc.solver_b = ib;
    cc.contact_index = ci;
    cc.point_count = c.manifold.point_count;
    cc.normal = c.manifold.normal;
    cc.friction = c.friction;
    cc.restitution = c.restitution;
    cc.inv_mass_a = side_a->inv_mass;
    cc.inv_inertia_a = side_a->inv_inertia;
    cc.inv_mass_b = side_b->inv_mass;
    cc.inv_inertia_b = side_b->inv_inertia;
    // Equal velocity changes (both bodies under gravity alone, the common
    // case) give fast::sub = 0 exactly and a dot product of 0: the same bits
    // without the checked arithmetic.
    const Vec2 dv_a = side_a->delta_velocity, dv_b = side_b->delta_velocity;
    cc.kick = dv_a.x == dv_b.x && dv_a.y == dv_b.y ? Q32::zero() : fast::dot(fast::sub(dv_b, dv_a), cc.normal);
    // The mass-ratio cap, for resting contacts only: both sides dynamic
    // (then both are simulated), one over R times lighter, and the centres
    // closing or parting slower than the restitution threshold along the
    // normal. An impact keeps the true masses, so momentum is exchanged as
    // it should be where it shows (see cap_mass_ratio). Such an uncapped
    // contact warm-starts with at most the impulse that changes the light
    // body's velocity by the restitution threshold: its stored impulse may
    // come from a step where the cap was on (up to R·m_heavy⁻¹/m_light⁻¹
    // times what the light body can take), and applied to the true mass it
    // threw the light body through the floor (stress seed 6298: a 0.04 kg
    // circle under a 3,150 kg body, kicked down at 35 m/s).
    Q32 warm_limit = Q32::max();
    if (cc.inv_mass_a > Q32::zero() && cc.inv_mass_b > Q32::zero() &&
        (cc.inv_mass_a > Q32::from_raw(cc.inv_mass_b.raw * k_max_contact_mass_ratio) ||
         cc.inv_mass_b > Q32::from_raw(cc.inv_mass_a.raw * k_max_contact_mass_ratio))) {
      const Q32 vn = fast::dot(fast::sub(context->states[ib].linear_velocity, context->states[ia].linear_velocity), cc.normal);
      if (abs(vn) < context->restitution_threshold) {
        cap_mass_ratio(&cc.inv_mass_a, &cc.inv_inertia_a, cc.inv_mass_b);
        cap_mass_ratio(&cc.inv_mass_b, &cc.inv_inertia_b, cc.inv_mass_a);
      } else {
        warm_limit = context->restitution_threshold / max(cc.inv_mass_a, cc.inv_mass_b);
      }
    }
    const bool rigid_side = cc.inv_mass_a == Q32::zero() || cc.inv_mass_b == Q32::zero();
    cc.softness = rigid_side ? context->static_softness : context->contact_softness;

    const Rot rotation_a = side_a->rotation;
    const Rot rotation_b = side_b->rotation;
    const Vec2 n_vec = cc.normal;
    const Vec2 t_vec = right_perp(n_vec);
    const Vec2 com_offset_a = side_a->com_offset;
    const Vec2 com_offset_b = side_b->com_offset;
    const Q32 inv_mass_sum = unsat::add(cc.inv_mass_a, cc.inv_mass_b);
    // Geometry (anchors, crosses) and the mass terms use the unsaturated
    // helpers above (their range argument: same bits as the checked
    // operators); the inverse inertia is first bounded by
    // contact_inv_inertia ("Range of the preparation" in contact_solver.cpp).
    Vec2 anchors_a[2], anchors_b[2];
    bool inside_a = side_a->has_box != 0, inside_b = side_b->has_box != 0;
    for (int32_t j = 0; j < cc.point_count; ++j) {
      const ManifoldPoint& mp = c.manifold.points[static_cast<size_t>(j)];
      anchors_a[j] = unsat::sub(mp.anchor_a, com_offset_a);
      anchors_b[j] = unsat::sub(mp.anchor_b, com_offset_b);
      inside_a = inside_a & inside_reach_box(anchors_a[j], *side_a);
      inside_b = inside_b & inside_reach_box(anchors_b[j], *side_b);
    }
    // Outside the box: the full bound (reach² from max_extent and the
    // anchors; the same values contact_reach_box's shortcut stands for).
    if (!inside_a) {
      Q32 reach_sq = square_extent(world->bodies[static_cast<size_t>(c.body_a)].max_extent);
      for (int32_t j = 0; j < cc.point_count; ++j) reach_sq = max(reach_sq, fast::dot(anchors_a[j], anchors_a[j]));
      cc.inv_inertia_a = contact_inv_inertia(cc.inv_inertia_a, reach_sq);
    }
    if (!inside_b) {
      Q32 reach_sq = square_extent(world->bodies[static_cast<size_t>(c.body_b)].max_extent);
      for (int32_t j = 0; j < cc.point_count; ++j) reach_sq = max(reach_sq, fast::dot(anchors_b[j], anchors_b[j]));
      cc.inv_inertia_b = contact_inv_inertia(cc.inv_inertia_b, reach_sq);
    }
    for (int32_t j = 0; j < cc.point_count; ++j) {
      const ManifoldPoint& mp = c.manifold.points[static_cast<size_t>(j)];
      ContactConstraintPoint& cp = cc.points[j];
      const Vec2 anchor_a = anchors_a[j];
      const Vec2 anchor_b = anchors_b[j];
      cp.local_a = ia >= 0 ? unsat::inv_rotate(rotation_a, anchor_a)
                           : fast::add(world->body_sims[static_cast<size_t>(c.body_a)].center, anchor_a);
      cp.local_b = ib >= 0 ? unsat::inv_rotate(rotation_b, anchor_b)
                           : fast::add(world->body_sims[static_cast<size_t>(c.body_b)].center, anchor_b);
      // The solver's current separation is (c_B + R_B·l_B − c_A − R_A·l_A)·n
      // plus this. At the start of the step the anchors close exactly
      // (anchor_b = anchor_a + p_A − p_B, collision.h), so the gap is only
      // the rounding of R·(Rᵀ·anchor), a few raw units: the manifold's
      // separation is taken as it is instead of paying four rotations to
      // cancel that rounding.
      cp.adjusted_separation = mp.separation;
      const Q32 rn_a = unsat::cross(anchor_a, n_vec), rn_b = unsat::cross(anchor_b, n_vec);
      const Q32 rt_a = unsat::cross(anchor_a, t_vec), rt_b = unsat::cross(anchor_b, t_vec);
      cp.angular_n_a = unsat::mul(cc.inv_inertia_a, rn_a);
      cp.angular_n_b = unsat::mul(cc.inv_inertia_b, rn_b);
      cp.angular_t_a = unsat::mul(cc.inv_inertia_a, rt_a);
      cp.angular_t_b = unsat::mul(cc.inv_inertia_b, rt_b);
      // The products below are ≥ 0 (unsat::mul_nonneg): I⁻¹ ≥ 0 (body.cpp's
      // mass data, checked again on restore; the caps scale it by factors
      // in (0, 1] or replace it by K/reach² > 0), and round(I⁻¹·r) has r's
      // sign or is 0 (rounding is monotonic and keeps 0), so
      // round(I⁻¹·r)·r ≥ 0; normal_mass ≥ 0 (1/k for k > 0, else 0) and
      // mass_scale = a2·a3 ≥ 0 (hertz > 0, damping ratio ≥ 0, h > 0: the
      // world's checks).
      const Q32 k_normal = unsat::add(unsat::add(inv_mass_sum, unsat::mul_nonneg(cp.angular_n_a, rn_a)),
                                      unsat::mul_nonneg(cp.angular_n_b, rn_b));
      cp.normal_mass = k_normal > Q32::zero() ? fast::reciprocal(k_normal) : Q32::zero();
      cp.soft_normal_mass = unsat::mul_nonneg(cp.normal_mass, cc.softness.mass_scale);
      const Q32 k_tangent = unsat::add(unsat::add(inv_mass_sum, unsat::mul_nonneg(cp.angular_t_a, rt_a)),
                                       unsat::mul_nonneg(cp.angular_t_b, rt_b));
      cp.tangent_mass = k_tangent > Q32::zero() ? fast::reciprocal(k_tangent) : Q32::zero();
      cp.rn_a = rn_a;
      cp.rn_b = rn_b;
      cp.rt_a = rt_a;
      cp.rt_b = rt_b;
      cp.normal_impulse = min(c.normal_impulse[static_cast<size_t>(j)], warm_limit);
      cp.tangent_impulse = clamp(c.tangent_impulse[static_cast<size_t>(j)], -warm_limit, warm_limit);
      cp.approach_velocity = Q32::zero();
      cp.bounce_velocity = Q32::zero();
      cp.bounce_sub_step = -1;
      cp.active_sub_step = -1;
      cp.separation = Q32::zero();  // written by the first relax pass before any solve reads it
    }
    if (cc.point_count < 2) cc.points[1] = ContactConstraintPoint{};
  }
}

}  // namespace

Softness make_softness(Q32 hertz, Q32 zeta, Q32 h) {
  const Q32 omega = k_two_pi * hertz;
  const Q32 a1 = zeta * 2 + h * omega;
  const Q32 a2 = h * omega * a1;
  const Q32 a3 = Q32::one() / (Q32::one() + a2);
  Softness s;
  s.bias_rate = a1 > Q32::zero() ? omega / a1 : Q32::zero();
  s.mass_scale = a2 * a3;
  s.impulse_scale = a3;
  return s;
}

void prepare_contact_constraints(World* world, StepContext* context) {
  const Q32 h = context->h;
  context->inv_h = Q32::one() / h;
  context->max_push_speed = world->def.max_contact_push_speed;
  context->restitution_threshold = world->def.restitution_threshold;
  // Stiffness capped at a quarter of the sub-step rate (stability).
  const Q32 hertz = min(world->def.contact_hertz, context->inv_h / 4);
  context->contact_softness = make_softness(hertz, world->def.contact_damping_ratio, h);
  context->static_softness = make_softness(hertz * 2, world->def.contact_damping_ratio, h);

  // Contacts of sleeping islands are not read: only the awake index
  // (for_each_awake_contact, world.h), in contact order.
  const std::vector<Contact>& contacts = world->contacts;
  int32_t count = 0;
  for_each_awake_contact(*world, [&](int32_t ci) {
    const Contact& c = contacts[static_cast<size_t>(ci)];
    if ((c.flags & k_contact_touching) == 0) return;
    if (context->body_to_solver[static_cast<size_t>(c.body_a)] == k_null_index &&
        context->body_to_solver[static_cast<size_t>(c.body_b)] == k_null_index) {
      return;
    }
    ++count;
  });
  Arena* arena = &world->arena;
  // Unwritten: every field of each record is stored below (no zeroing
  // pass over the 464-byte records first).
  context->constraints = arena_allocate_array_for_overwrite<ContactConstraint>(arena, count, "contact_constraints");
  context->bounce_marks = arena_allocate_array<int32_t>(arena, context->solver_body_count, "bounce_marks");
  context->constraint_count = count;
  // Per solver body: the record of what the preparation reads of it
  // (PrepBody), gathered only for the bodies some constraint reads
  // (k_prep_body_unset for the others: a scene of many bodies and few
  // contacts pays nothing for them).
  PrepBody* prep_bodies =
      arena_allocate_array_for_overwrite<PrepBody>(arena, context->solver_body_count, "prep_bodies");
  for (int32_t i = 0; i < context->solver_body_count; ++i) {
    context->bounce_marks[i] = -1;
    prep_bodies[i].has_box = k_prep_body_unset;
  }
  // Graph colours (contact_colour.cpp): constraints are stored colour by
  // colour, in contact order within a colour. The colouring pass hands over
  // the constraints' contacts and solver indices (jobs, in contact order).
  ConstraintJob* jobs = colour_contact_constraints(world, context, count);
  world->contacts_read_after_update += count;

  // Serial, in contact order: the solver bodies whose PrepBody records the
  // constraints read (each once).
  int32_t* gather = arena_allocate_array<int32_t>(arena, context->solver_body_count, "prep_gather");
  int32_t gather_count = 0;
  const auto list = [prep_bodies, gather, &gather_count](int32_t i) {
    if (i < 0 || prep_bodies[i].has_box != k_prep_body_unset) return;
    prep_bodies[i].has_box = 0;  // listed; gather_prep_body writes it
    gather[gather_count++] = i;
  };
  for (int32_t n = 0; n < count; ++n) {
    list(jobs[n].solver_a);
    list(jobs[n].solver_b);
  }
  // In blocks on the workers (task.h): each record and each constraint is
  // written by one item only and depends on nothing another item writes.
  parallel_for(context->tasks, "prepare_contact_bodies", gather_count, k_prep_body_block,
               [=](int32_t begin, int32_t end) {
                 for (int32_t g = begin; g < end; ++g) gather_prep_body(*world, *context, gather[g], &prep_bodies[gather[g]]);
               });
  parallel_for(context->tasks, "prepare_contacts", count, k_prep_contact_block,
               [world, context, prep_bodies, jobs](int32_t begin, int32_t end) {
                 build_constraints(world, context, prep_bodies, world->contacts.data(), jobs, begin, end);
               });
  arena_free(arena, gather);
  arena_free(arena, jobs);
  arena_free(arena, prep_bodies);
  pack_contact_lanes(world, context);
}

}  // namespace tandem
