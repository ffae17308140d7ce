// continuous.cpp — continuous collision (internal): fast bodies are stopped
// at their time of impact instead of tunnelling through thin geometry.
//
// WHEN. After the sub-steps (stage_continuous, between store_impulses and
// finalize_bodies), each simulated dynamic body with shapes compares how far
// it moved this step with its size:
//     moved = |c2 − c1| + max_extent · |Δθ|,   Δθ ≈ |ω| · dt (end-of-step ω)
// and counts as FAST when moved > min_extent / 2 (Box2D v3's rule and safety
// factor). min_extent is the body's thinnest shape (circle or capsule radius,
// polygon inradius plus rounding, k_linear_slop for segments); max_extent the
// farthest shape point from the centre of mass (both cached in Body by
// apply_body_mass).
//
// WHAT. A fast body sweeps its shapes from the start-of-step pose (c1, q1;
// still in BodySim) to the solver's end pose (c2, q2) against:
//   - every shape of a static or kinematic body (at its end-of-step pose), and
//   - for a BULLET body, also every shape of a non-bullet dynamic body, at
//     that body's final pose (non-bullets are finished first, so bullets see
//     them where they end the step).
// Pairs are filtered as contacts are (filters_should_collide, custom filter,
// no sensors, not the same body). time_of_impact gives the first fraction t
// of contact. A pair already touching at t = 0 is not stopped there (the
// contact solver owns it; stopping would freeze the body): instead a small
// circle at the shape's centroid (a quarter of its thinnest extent) is swept,
// so a fast spin cannot carry the shape's centre through the obstacle (the
// fallback Box2D v3 uses too). Where the centroid already lies within that
// core's stopping distance (max(linear slop, radii − slop)) of the obstacle —
// a shape no thicker than about the slop, such as a 5 mm circle or a
// segment, resting on it — the core stops halfway to the obstacle instead
// (time_of_impact_to), otherwise its sweep would report a hit at t = 0 and
// stop nothing (formerly stress known issues 1 and 3); one held within
// k_hold_floor (half the slop) of the obstacle also loses its spin relative
// to it (stress seed 8724: a spinning segment body with no rotational
// inertia, halved nearer a wall every step, reached its face in 26 steps,
// where it could no longer be held, and the next step swung it through the
// wall). A centroid that starts inside a polygon obstacle (a segment resting
// on a floor sinks by up to the slop) has no distance to halve: it is held
// where it would sink k_hold_floor deeper behind the face it is least deep
// behind (inside_hold; stress seeds 3769, 6309). The body's end
// pose becomes the sweep at the smallest t found (if < 1); its velocity is
// kept, so the next step's speculative contact makes the collision response.
//
// LIMITS. Only the first impact of a step is found, and a shape that starts a
// step touching an obstacle is left to the contact solver (only its centroid
// core is swept); a centroid that starts inside an obstacle that is not a
// polygon (on a circle's centre, a capsule's or a segment's line) is not
// held at all. A thin body that hits at hundreds of m/s while spinning can
// be turned by a one-point contact so fast that its far end swings through a
// thin obstacle within the next step (measured: a 1 m × 4 cm stick falling at
// 200 m/s with 5–30 rad/s of spin through a 10 cm floor). Box2D 2.4 solves
// such cases with time-of-impact sub-steps; not done here.
//
// ORDER. Non-bullets in ascending body index, then bullets in ascending body
// index; candidates in ascending shape index; ties in t keep the first. Each
// non-bullet depends only on its own sweep and on static/kinematic bodies, so
// the result does not depend on the order of non-bullets among themselves.
// Likewise a bullet depends only on its own sweep and on bodies that are not
// bullets (final after the non-bullet pass).
//
// WORKERS (task.h). So each pass is split in two: the first-impact searches
// of its fast bodies run in fixed blocks of k_sweep_block bodies on any
// thread in any order, each writing only its own fraction slot; the stepping
// thread then moves the bodies that hit, in list order. No search reads a
// pose its own pass moves, so the result is the serial one for every worker
// count. The fast-body test is per body (blocks of k_fast_test_block) into a
// per-body mark; the lists are built from the marks serially.
//
// COST. Candidate static/kinematic shapes are gathered once per step (only
// when some body is fast) and each fast body tests those whose AABB meets its
// swept AABB: O(fast bodies × static shapes). Bullets scan every shape.
// Rejected for now: querying the broad phase's structure (the broad phases
// differ; this brute-force list gives the same answer for every one of them).
#include <algorithm>

#include "physics/fast_math.h"
#include "physics/world.h"

namespace tandem {

namespace {

/// The farthest point of `geometry` from `center` (m) and its thinnest
/// dimension (m).
void shape_extents(const ShapeGeometry& geometry, Vec2 center, Q32* out_min, Q32* out_max) {
  Q32 min_extent, max_extent;
  switch (geometry.type) {
    case ShapeType::circle:
      min_extent = geometry.circle.radius;
      max_extent = length(geometry.circle.center - center) + geometry.circle.radius;
      break;
    case ShapeType::capsule:
      min_extent = geometry.capsule.radius;
      max_extent = max(length(geometry.capsule.center1 - center), length(geometry.capsule.center2 - center)) +
                   geometry.capsule.radius;
      break;
    case ShapeType::polygon: {
      const Polygon& p = geometry.polygon;
      Q32 inradius = Q32::max();
      Q32 far = Q32::zero();
      for (int32_t i = 0; i < p.count; ++i) {
        const size_t k = static_cast<size_t>(i);
        inradius = min(inradius, dot(p.normals[k], p.vertices[k] - p.centroid));
        far = max(far, length(p.vertices[k] - center));
      }
      min_extent = max(inradius, Q32::zero()) + p.radius;
      max_extent = far + p.radius;
      break;
    }
    case ShapeType::segment:
      min_extent = k_linear_slop;
      max_extent = max(length(geometry.segment.point1 - center), length(geometry.segment.point2 - center));
      break;
    case ShapeType::chain_segment:
    default: {
      const Segment& s = geometry.chain_segment.segment;
      min_extent = k_linear_slop;
      max_extent = max(length(s.point1 - center), length(s.point2 - center));
      break;
    }
  }
  *out_min = max(min_extent, k_linear_slop);
  *out_max = max_extent;
}

/// A shape's centre in its body frame, m: circle centre, capsule or segment
/// midpoint, polygon centroid.
Vec2 shape_centroid(const ShapeGeometry& geometry) {
  switch (geometry.type) {
    case ShapeType::circle: return geometry.circle.center;
    case ShapeType::capsule: return lerp(geometry.capsule.center1, geometry.capsule.center2, Q32::half());
    case ShapeType::polygon: return geometry.polygon.centroid;
    case ShapeType::segment: return lerp(geometry.segment.point1, geometry.segment.point2, Q32::half());
    case ShapeType::chain_segment:
    default:
      return lerp(geometry.chain_segment.segment.point1, geometry.chain_segment.segment.point2, Q32::half());
  }
}

/// The body's sweep over this step: start pose from BodySim, end from the
/// solver state.
Sweep body_sweep(const BodySim& sim, const BodyState& end) {
  Sweep s;
  s.local_center = sim.local_center;
  s.c1 = sim.center;
  s.q1 = sim.transform.q;
  s.c2 = end.center;
  s.q2 = end.rotation;
  return s;
}

/// A sweep that stays at one pose (transform xf, centre of mass offset lc).
Sweep still_sweep(Transform xf, Vec2 local_center) {
  Sweep s;
  s.local_center = local_center;
  s.c1 = s.c2 = transform_point(xf, local_center);
  s.q1 = s.q2 = xf.q;
  return s;
}

/// An obstacle's pose at the end of the step, held still for the sweep: the
/// solver state of a simulated body (kinematic, or dynamic after its own
/// sweep), else its BodySim (static, or asleep: it does not move).
Sweep end_pose(const World& world, const StepContext& context, int32_t shape) {
  const int32_t ob = world.shapes[static_cast<size_t>(shape)].body_index;
  const BodySim& sim = world.body_sims[static_cast<size_t>(ob)];
  const int32_t si = context.body_to_solver[static_cast<size_t>(ob)];
  if (si == k_null_index) return still_sweep(sim.transform, sim.local_center);
  const BodyState& st = context.states[si];
  return still_sweep({st.center - rotate(st.rotation, sim.local_center), st.rotation}, sim.local_center);
}

/// True when the shapes may collide by filter (contacts' rule, without the
/// body-type tests).
bool may_collide(const World& world, int32_t shape_a, int32_t shape_b) {
  const Shape& a = world.shapes[static_cast<size_t>(shape_a)];
  const Shape& b = world.shapes[static_cast<size_t>(shape_b)];
  if (a.is_sensor || b.is_sensor || a.body_index == b.body_index) return false;
  if (!world.bodies[static_cast<size_t>(b.body_index)].enabled) return false;
  return shapes_should_collide(world, std::min(shape_a, shape_b), std::max(shape_a, shape_b));
}

/// True for the shape kinds without area (segments and chain segments): no
/// contact manifold exists between two of them (manifold.cpp's dispatch, as
/// in Box2D), so neither may stop the other here.
bool is_segment_kind(ShapeType type) { return type == ShapeType::segment || type == ShapeType::chain_segment; }

/// True when `point` (world) lies behind the one-sided chain segment `chain`
/// placed at `xf`: on the side right_perp(point2 − point1) points away from,
/// where the chain manifold makes no contact (Box2D v3's continuous rule:
/// a shape that starts behind a chain segment is not stopped by it).
bool behind_chain_segment(const ChainSegment& chain, Transform xf, Vec2 point) {
  const Vec2 p1 = transform_point(xf, chain.segment.point1);
  const Vec2 p2 = transform_point(xf, chain.segment.point2);
  return dot(right_perp(p2 - p1), point - p1) < Q32::zero();
}

/// True when the continuous search may stop `geometry` (of the fast body,
/// at its start pose `start`) at `other` (held at `other_xf`): only pairs the
/// contact solver can take over. Two segment kinds have no manifold, and a
/// one-sided chain segment makes no contact with a shape whose centroid is
/// behind it; stopping the body there left it held in place by this search
/// alone, each step, while gravity added to its velocity with no contact to
/// take it away, until it slipped past the end and fell at that speed (stress
/// seed 572: a segment held on a chain segment reached 13 m/s and went into
/// the floor).
bool contact_can_take_over(const ShapeGeometry& geometry, Transform start, const ShapeGeometry& other,
                           Transform other_xf) {
  if (is_segment_kind(geometry.type) && is_segment_kind(other.type)) return false;
  if (other.type == ShapeType::chain_segment &&
      behind_chain_segment(other.chain_segment, other_xf, transform_point(start, shape_centroid(geometry)))) {
    return false;
  }
  if (geometry.type == ShapeType::chain_segment &&
      behind_chain_segment(geometry.chain_segment, start, transform_point(other_xf, shape_centroid(other)))) {
    return false;
  }
  return true;
}

/// A hold of a centroid nearer its obstacle than this, m, also takes the
/// body's spin relative to the obstacle (first_impact, move_to_impact).
constexpr Q32 k_hold_floor = k_linear_slop / 2;

/// Bisection steps of inside_hold: the fraction to 1/65,536 of the sweep.
constexpr int32_t k_inside_hold_steps = 16;

/// A centroid `local` (body frame of `sweep`) that starts the step inside
/// `polygon` (held at `xf`) has no distance, so no hold normal: take the face
/// it is least deep behind (the first of equals) as the floor it rests on.
/// Returns true, with the last fraction of the sweep at which the centroid
/// is at most k_hold_floor deeper behind that face than at the start and the
/// face's inward normal (body towards obstacle), when the sweep's end would
/// be deeper than that (stress seeds 3769, 6309: a segment resting on the
/// floor sinks by up to the slop, its middle inside the floor's face, and was
/// flung through it at 400-1,000 m/s). The sweep turns the body, so the depth
/// is not linear in the fraction: bisection, k_inside_hold_steps steps.
bool inside_hold(const Sweep& sweep, Vec2 local, const Polygon& polygon, Transform xf, Q32* fraction,
                 Vec2* normal) {
  const Vec2 start = transform_point(sweep_transform(sweep, Q32::zero()), local);
  const Vec2 p = inv_transform_point(xf, start);
  int32_t face = 0;
  Q32 depth = Q32::min();  // separation behind the face, m (≤ 0 inside)
  for (int32_t k = 0; k < polygon.count; ++k) {
    const Q32 separation = dot(polygon.normals[static_cast<size_t>(k)], p - polygon.vertices[static_cast<size_t>(k)]);
    if (separation > depth) {
      depth = separation;
      face = k;
    }
  }
  const Vec2 n = rotate(xf.q, polygon.normals[static_cast<size_t>(face)]);
  const Vec2 v = transform_point(xf, polygon.vertices[static_cast<size_t>(face)]);
  const Q32 floor = depth - k_hold_floor;
  const auto separation_at = [&](Q32 t) { return dot(n, transform_point(sweep_transform(sweep, t), local) - v); };
  if (separation_at(Q32::one()) >= floor) return false;
  Q32 lo = Q32::zero(), hi = Q32::one();  // separation_at(lo) ≥ floor > separation_at(hi)
  for (int32_t step = 0; step < k_inside_hold_steps; ++step) {
    const Q32 mid = (lo + hi) * Q32::half();
    if (separation_at(mid) >= floor) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  *fraction = lo;
  *normal = -n;
  return true;
}

/// A body's first impact in its sweep.
struct Impact {
  Q32 fraction = Q32::one();  ///< of the sweep, (0, 1]; 1: no impact
  /// Unit, from the body towards the obstacle, when the impact is a hold
  /// (below); zero otherwise.
  Vec2 hold_normal;
  /// The obstacle's body (hold only), for its velocity.
  int32_t hold_body = k_null_index;
  /// A hold of a centroid within k_hold_floor of the obstacle.
  bool at_floor = false;
};

/// Sweeps the body of solver index i against `candidates` (each held at its
/// end_pose) and returns its first impact (fraction 1 when none).
/// Reads only: the search runs on any thread, move_to_impact applies it.
Impact first_impact(const World* world, const StepContext* context, int32_t i, const int32_t* candidates,
                    int32_t candidate_count) {
  const int32_t b = context->solver_to_body[i];
  const Body& body = world->bodies[static_cast<size_t>(b)];
  const BodySim& sim = world->body_sims[static_cast<size_t>(b)];
  const BodyState& state = context->states[i];
  const Sweep sweep = body_sweep(sim, state);
  const Transform end{state.center - rotate(state.rotation, sim.local_center), state.rotation};

  Impact best;
  for (int32_t s = body.head_shape; s != k_null_index; s = world->shapes[static_cast<size_t>(s)].next_shape) {
    const Shape& shape = world->shapes[static_cast<size_t>(s)];
    if (shape.is_sensor) continue;
    const ShapeGeometry& geometry = world->shape_geometries[static_cast<size_t>(s)];
    const AABB swept = aabb_union(shape.aabb, compute_shape_aabb(geometry, end));
    const ShapeProxy proxy = make_shape_proxy(geometry);
    ShapeProxy core;  // the centroid core (below), made when first needed
    bool have_core = false;
    for (int32_t k = 0; k < candidate_count; ++k) {
      const int32_t o = candidates[k];
      const Shape& other = world->shapes[static_cast<size_t>(o)];
      if (other.body_index == b || !aabb_overlaps(swept, other.aabb)) continue;
      if (!may_collide(*world, s, o)) continue;
      const ShapeGeometry& other_geometry = world->shape_geometries[static_cast<size_t>(o)];
      const Sweep other_sweep = end_pose(*world, *context, o);
      if (!contact_can_take_over(geometry, sim.transform, other_geometry, sweep_transform(other_sweep, Q32::zero()))) {
        continue;
      }
      ToiInput input;
      input.proxy_a = proxy;
      input.proxy_b = make_shape_proxy(other_geometry);
      input.sweep_a = sweep;
      input.sweep_b = other_sweep;
      input.max_fraction = best.fraction;
      ToiOutput out = time_of_impact(input);
      Vec2 hold_normal;
      bool at_floor = false;
      if (out.fraction == Q32::zero() || out.state == ToiState::overlapped) {
        // Touching at the start (typically: stopped here by the previous
        // step's sweep). The contact solver owns that contact, but a fast
        // spin can still carry the rest of the shape through: sweep a small
        // core (a circle of a quarter of the thinnest extent at the shape's
        // centroid) so that at least the centroid cannot tunnel.
        if (!have_core) {
          const Vec2 centroid = shape_centroid(geometry);
          Q32 thinnest, farthest;
          shape_extents(geometry, centroid, &thinnest, &farthest);
          core = make_proxy(&centroid, 1, thinnest / 4);
          have_core = true;
        }
        input.proxy_a = core;
        out = time_of_impact(input);
        if (out.fraction == Q32::zero() || out.state == ToiState::overlapped) {
          // The core already lies within the default target (max(linear
          // slop, radii − slop)) of the obstacle: a shape whose thinnest
          // extent is near the slop (a 5 mm circle, a segment) resting on
          // it. Stop the centroid halfway to the obstacle instead, so it
          // still cannot pass through (formerly stress known issue 1).
          DistanceInput din;
          din.proxy_a = core;
          din.proxy_b = input.proxy_b;
          din.transform_a = sweep_transform(input.sweep_a, Q32::zero());
          din.transform_b = sweep_transform(input.sweep_b, Q32::zero());
          din.use_radii = false;
          const DistanceOutput held = shape_distance(din);
          if (held.distance > Q32::zero()) {
            out = time_of_impact_to(input, held.distance / 2);
            hold_normal = held.normal;
            // Near the obstacle: a hold here also takes the body's spin
            // (move_to_impact), or halving step after step brings the
            // centroid onto the obstacle, where it can no longer be held
            // (stress seed 8724).
            at_floor = held.distance <= k_hold_floor;
          } else if (other_geometry.type == ShapeType::polygon &&
                     inside_hold(input.sweep_a, core.points[0], other_geometry.polygon, din.transform_b,
                                 &out.fraction, &hold_normal)) {
            // The centroid starts inside the obstacle: held where it would
            // sink deeper than k_hold_floor below its start (inside_hold).
            out.state = ToiState::hit;
            at_floor = true;
          }
        }
      }
      const bool hold = hold_normal != Vec2{};
      if ((out.state == ToiState::hit || out.state == ToiState::failed) && (out.fraction > Q32::zero() || hold) &&
          out.fraction < best.fraction) {
        best.fraction = out.fraction;
        best.hold_normal = hold_normal;
        best.hold_body = other.body_index;
        best.at_floor = at_floor;
      }
    }
  }
  return best;
}

/// Moves the end pose of the body of solver index i to the fraction of its
/// sweep where `impact` stops it (< 1). A hold (a thin shape that started
/// the step touching the obstacle, stopped halfway to it) also takes away
/// the body's velocity towards the obstacle, relative to the obstacle's
/// body, along the normal between them, as a perfectly inelastic hit: the
/// contact solver had that contact this step and still left the body
/// moving into it (a spin the linearised contact reads as separating: stress
/// seed 1104, a 1 kg segment body with no rotational inertia spinning at
/// 59 rad/s, held at a wall for 28 steps while keeping 155 m/s, then
/// through it once its centroid was too close to be held halfway). A hold
/// at the floor also takes away the body's spin relative to the obstacle
/// (below).
void move_to_impact(World* world, StepContext* context, int32_t i, const Impact& impact) {
  const BodySim& sim = world->body_sims[static_cast<size_t>(context->solver_to_body[i])];
  BodyState& state = context->states[i];
  const Transform xf = sweep_transform(body_sweep(sim, state), impact.fraction);
  state.rotation = xf.q;
  state.center = transform_point(xf, sim.local_center);
  context->continuous_hits += 1;
  if (impact.hold_normal == Vec2{}) return;
  const int32_t other = context->body_to_solver[static_cast<size_t>(impact.hold_body)];
  const Vec2 other_velocity = other >= 0 ? context->states[other].linear_velocity : Vec2{};
  const Vec2 relative = state.linear_velocity - other_velocity;
  const Q32 towards = dot(relative, impact.hold_normal);
  if (towards > Q32::zero()) state.linear_velocity = state.linear_velocity - impact.hold_normal * towards;
  if (!impact.at_floor) return;
  // Held at the floor: the turn that keeps bringing the centroid back to the
  // obstacle goes too (the body takes the obstacle's angular velocity), so
  // the next step's sweep is the body's translation, which a body leaving
  // the obstacle or sliding along it makes freely. Without it, a spinning
  // body with no rotational inertia (whose spin no contact changes, and
  // which holds no energy) stayed held in place step after step while its
  // velocity said it was leaving (stress seed 8724).
  state.angular_velocity = other >= 0 ? context->states[other].angular_velocity : Q32::zero();
}

/// Fast bodies per block of the parallel sweeps (a sweep is a handful of
/// time-of-impact searches: small blocks balance the workers).
constexpr int32_t k_sweep_block = 4;
/// Solver bodies per block of the parallel fast-body test.
constexpr int32_t k_fast_test_block = 64;

/// Finds the first impact of each body in `list` (solver indices, ascending)
/// against `candidates`, in parallel blocks of k_sweep_block into
/// fractions[k], then moves the bodies that hit, in list order. The searches
/// only read (poses of static and kinematic bodies, and of non-bullets when
/// bullets sweep, none of which a search of the same pass moves), so the
/// result does not depend on the worker count or the order the blocks run.
/// A custom filter is called from the stepping thread only (it need not be
/// thread-safe), so with one installed the blocks run there in order.
void sweep_and_move(World* world, StepContext* context, const char* stage, const int32_t* list, int32_t list_count,
                    const int32_t* candidates, int32_t candidate_count, Impact* impacts) {
  const World* w = world;
  const StepContext* c = context;
  const auto search = [=](int32_t begin, int32_t end) {
    for (int32_t k = begin; k < end; ++k) impacts[k] = first_impact(w, c, list[k], candidates, candidate_count);
  };
  if (world->broad_phase.custom_filter != nullptr) {
    search(0, list_count);
  } else {
    parallel_for(context->tasks, stage, list_count, k_sweep_block, search);
  }
  for (int32_t k = 0; k < list_count; ++k) {
    if (impacts[k].fraction < Q32::one()) move_to_impact(world, context, list[k], impacts[k]);
  }
}

}  // namespace

void compute_body_extents(const World& world, int32_t body_index, Vec2 local_center, Q32* out_min, Q32* out_max) {
  Q32 min_extent = Q32::max(), max_extent = Q32::zero();
  bool any = false;
  for (int32_t s = world.bodies[static_cast<size_t>(body_index)].head_shape; s != k_null_index;
       s = world.shapes[static_cast<size_t>(s)].next_shape) {
    Q32 lo, hi;
    shape_extents(world.shape_geometries[static_cast<size_t>(s)], local_center, &lo, &hi);
    min_extent = min(min_extent, lo);
    max_extent = max(max_extent, hi);
    any = true;
  }
  *out_min = any ? min_extent : Q32::zero();
  *out_max = max_extent;
}

/// (|d.x| + |d.y| + turn)·2 ≤ min_extent with fixed.h's saturating + and ·2
/// (turn ≥ 0, min_extent ≥ 0), decided on exact integers: the saturating
/// sums of non-negative terms are min(exact, max), so for min_extent < max
/// "saturated sum ≤ min_extent" is "exact sum ≤ min_extent" (and for
/// min_extent = max the saturated sum always passes), and 2·x ≤ m is
/// x ≤ ⌊m/2⌋. Each term is first tested against ⌊m/2⌋ (< 2^62), so the sum
/// of three stays below 2^64. A negative turn or min_extent (impossible:
/// both are lengths) answers false, which leaves the decision to the exact
/// test after it, as the saturating form did.
bool continuous_surely_slow(Vec2 d, Q32 turn, Q32 min_extent) {
  if (min_extent.raw < 0 || turn.raw < 0) return false;
  if (min_extent.raw == INT64_MAX) return true;
  const uint64_t half = static_cast<uint64_t>(min_extent.raw) / 2;
  const uint64_t ux = detail::magnitude(d.x.raw), uy = detail::magnitude(d.y.raw);
  const uint64_t ut = static_cast<uint64_t>(turn.raw);
  return ux <= half && uy <= half && ut <= half && ux + uy + ut <= half;
}

void stage_continuous(World* world, StepContext* context) {
  context->continuous_hits = 0;
  context->fast_body_count = 0;
  if (!world->def.enable_continuous) return;
  const int32_t count = context->solver_body_count;
  if (count == 0) return;
  Arena* arena = &world->arena;
  // Fast bodies, marked per solver index (0: slow, 1: fast, 2: fast bullet),
  // each block of bodies on any thread (a body writes only its own mark).
  uint8_t* fast = arena_allocate_array<uint8_t>(arena, count, "fast_bodies");
  {
    const World* w = world;
    const StepContext* c = context;
    parallel_for(context->tasks, "continuous_fast_test", count, k_fast_test_block, [=](int32_t begin, int32_t end) {
      for (int32_t i = begin; i < end; ++i) {
        fast[i] = 0;
        const int32_t b = c->solver_to_body[i];
        const Body& body = w->bodies[static_cast<size_t>(b)];
        if (body.type != BodyType::dynamic_body || body.shape_count == 0) continue;
        const BodySim& sim = w->body_sims[static_cast<size_t>(b)];
        const BodyState& state = c->states[i];
        // |Δc| ≤ |Δx| + |Δy|: the square root only where that bound says "maybe fast".
        const Vec2 d = fast::sub(state.center, sim.center);
        const Q32 turn = fast::mul(fast::mul(body.max_extent, abs(state.angular_velocity)), c->dt);
        if (continuous_surely_slow(d, turn, body.min_extent)) continue;
        if ((length(d) + turn) * 2 > body.min_extent) fast[i] = body.bullet ? 2 : 1;
      }
    });
  }
  // The fast bodies in ascending solver index (= ascending body index), non-
  // bullets first in the list, bullets after them.
  int32_t* list = arena_allocate_array<int32_t>(arena, count, "ccd_fast_list");
  int32_t fast_count = 0, bullet_count = 0;
  for (int32_t i = 0; i < count; ++i) {
    if (fast[i] == 1) list[fast_count++] = i;
  }
  for (int32_t i = 0; i < count; ++i) {
    if (fast[i] == 2) list[fast_count + bullet_count++] = i;
  }
  const int32_t non_bullet_count = fast_count;
  fast_count += bullet_count;
  context->fast_body_count = fast_count;
  if (fast_count == 0) {
    arena_free(arena, list);
    arena_free(arena, fast);
    return;
  }
  Impact* impacts = arena_allocate_array<Impact>(arena, fast_count, "ccd_impacts");
  // Static and kinematic shapes (the obstacles of every fast body).
  const int32_t shape_capacity = static_cast<int32_t>(world->shapes.size());
  int32_t* obstacles = arena_allocate_array<int32_t>(arena, shape_capacity, "ccd_obstacles");
  int32_t obstacle_count = 0;
  for (int32_t s = 0; s < shape_capacity; ++s) {
    if (!id_pool_is_alive(world->shape_pool, s)) continue;
    const Shape& shape = world->shapes[static_cast<size_t>(s)];
    const Body& owner = world->bodies[static_cast<size_t>(shape.body_index)];
    if (owner.type != BodyType::dynamic_body && !shape.is_sensor) obstacles[obstacle_count++] = s;
  }
  sweep_and_move(world, context, "continuous_sweep", list, non_bullet_count, obstacles, obstacle_count, impacts);
  // Bullets: also against non-bullet dynamic bodies at their final pose.
  if (bullet_count > 0) {
    int32_t* targets = arena_allocate_array<int32_t>(arena, shape_capacity, "ccd_bullet_targets");
    int32_t target_count = 0;
    for (int32_t s = 0; s < shape_capacity; ++s) {
      if (!id_pool_is_alive(world->shape_pool, s)) continue;
      const Shape& shape = world->shapes[static_cast<size_t>(s)];
      if (shape.is_sensor) continue;
      const Body& owner = world->bodies[static_cast<size_t>(shape.body_index)];
      if (owner.type != BodyType::dynamic_body || !owner.bullet) targets[target_count++] = s;
    }
    sweep_and_move(world, context, "continuous_bullet_sweep", list + non_bullet_count, bullet_count, targets,
                   target_count, impacts + non_bullet_count);
    arena_free(arena, targets);
  }
  arena_free(arena, obstacles);
  arena_free(arena, impacts);
  arena_free(arena, list);
  arena_free(arena, fast);
}

}  // namespace tandem
