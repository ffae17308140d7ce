// manifold.cpp — the narrow phase: contact manifolds for every shape pair
// (dispatch, round shapes, local → world; manifold_internal.h lists the
// other files).
//
// Design notes
//
// * Frame. Every pair is solved in shape A's local frame: B is brought over
//   with inv_mul_transforms(xf_a, xf_b), whose translation is the (small)
//   difference of the two body positions rotated once, so bodies far from the
//   world origin lose nothing and no dot product ever sees a large absolute
//   coordinate. The result is rotated into world axes only at the end
//   (to_world): normal = q_a·n, anchor_a = q_a·p, anchor_b = anchor_a +
//   (p_a − p_b), point = p_a + anchor_a.
//
// * One algorithm for everything with edges: SAT, not GJK. Polygons,
//   capsules and segments are all "cores" (a convex point set with outward
//   edge normals and a rounding radius; a capsule or segment is a 2-gon with
//   normals ±n). collide_cores() handles every pair of them:
//     1. Separating axis test over both cores' edge normals (lowest index wins
//        ties). A 2-gon has no end-cap normals, so two 2-gons also test the
//        segment directions (otherwise collinear capsules end to end would
//        look touching). The best axis is a lower bound of the core distance:
//        if it already exceeds radius + margin there is no contact.
//     2. Cores overlap (best axis ≤ 0): reference face = the SAT face; A keeps
//        the reference unless B's face is better by more than
//        k_flip_tolerance (0.1 × linear slop, Box2D's flip tolerance), so a
//        resting stack does not alternate. Incident edge = the other core's
//        edge most anti-parallel to the reference normal (lowest index on
//        ties). Clip the incident edge to the reference edge's side planes.
//     3. Cores disjoint: the exact closest features by brute force over all
//        vertex–vertex and vertex–edge pairs (≤ 2·8·8 exact 128-bit tests;
//        closest pairs of disjoint convex polygons always involve a vertex).
//        A vertex–vertex pair gives one point with the normal along the
//        pair (rounded corners); a vertex–edge pair makes that edge the
//        reference face (A preferred within the flip tolerance) and the
//        incident edge is chosen among the two edges at that vertex, so the
//        closest vertex is always one of the clipped points.
//   Clipping: an incident edge lying wholly outside the reference edge's
//   side planes gives one point at its nearest end (cores that overlap must
//   touch somewhere) — except against chain segments, where it gives nothing
//   (that region belongs to the neighbouring segment).
//   Box2D v3 uses the same SAT + clipping for polygons, but decides "disjoint"
//   by SAT separation > 0.1 slop and then only looks at the reference and
//   incident edges. The SAT value can be far below the true distance (two
//   thin wedges tip to tip: 0.0004 by SAT, 0.4 m apart), which would make a
//   ghost contact; the brute-force distance costs little and is exact.
//   GJK (distance.cpp) is not used here, so the manifolds depend on nothing
//   but this file and vec2.h.
//
// * Circles are points with a radius: circle–circle, capsule/segment–circle
//   (closest point on the segment), polygon–circle (SAT over the polygon's
//   normals, then the reference edge's vertex regions — exact for a point
//   against a convex polygon).
//
// * Chain segments (one-sided, normal = right_perp(point2 − point1), contact
//   only on that side) follow Box2D v3's smooth collision ("ghost
//   collisions", box2d.org 2020): the ghost vertices tell whether each end
//   vertex is convex (the chain turns left there by more than sin⁻¹ 0.01);
//   a candidate normal is admitted only inside the segment's own normal cone
//   (between the neighbour's normal and ours at a convex end), snapped to the
//   segment normal at a flat or concave end, and skipped outside, so a body
//   sliding across an inner vertex never catches on it. The closest features
//   come from the same brute-force query as above instead of GJK's simplex.
//   Which side the other shape is on: Box2D's test of its centroid, and, when
//   the cores overlap, also the part of it over the segment (clipped to the
//   segment's span): if that part reaches farther behind the line than in
//   front, no contact. The centroid alone fails for a shape much larger than
//   the segment (a wall box beside a body carrying chain segments), which was
//   then pushed out through the segment's front by its depth behind it; a
//   polygon vertex over the segment's back is likewise not a contact.
//
// * Margin. A point is reported while its separation < k_speculative_distance
//   (each clipped point is filtered on its own, so a tilted box can report
//   one point).
//
// * Shortcuts that change no bit: the SAT stops an edge's minimum once it
//   falls to the best edge so far (that edge cannot win: max_separation);
//   two round points farther apart than their radii plus the margin are
//   rejected on the exact squared distance before the root (collide_points).
//
// * Feature ids. make_feature_id(feature on A, feature on B) with vertex
//   indices: a clipped point gets (reference vertex, incident vertex) with the
//   reference edge's start vertex for the point clipped at its start side, so
//   the ids depend only on which edges touch, not on the exact pose. Circle
//   contacts use id 0 (one point). collide() flips ids with the shapes.
//
// * Determinism and safety. Integer only; ties broken by index; every
//   division is guarded (lengths against zero, clipping spans against
//   k_clip_span_epsilon); normalize() is scale-free, so tiny vectors give
//   accurate unit directions and only the exactly zero vector needs a
//   fallback normal, chosen by a fixed rule per pair.
//
// * Accuracy (tests/physics/test_manifold.cpp, 100,000 random pairs against
//   an exact extended-precision oracle and against GJK): for disjoint cores the
//   smallest separation matches the exact one to ~1e-9 m, except where A's
//   face is kept within the flip tolerance (then up to 5e-4 m larger, never
//   smaller); shallow overlaps match the exact penetration depth likewise.
//
// * Reuse across steps (collide_persistent, manifold_cores.cpp). A polygon
//   pair that touched last step with two clipped points re-clips the same
//   two edges — decoded from the previous manifold's feature ids: (r, i+1),
//   (r+1, i) with A as reference, (i+1, r), (i, r+1) with B, patterns that
//   exclude each other for polygons of 3+ vertices — instead of running the
//   SAT, as long as:
//     - the incident edge still runs against the reference edge and turns
//       from it by at most atan(k_reclip_sin) = atan 0.05 ≈ 2.9° (|h1 − h2|
//       ≤ 0.05·span, h the heights of its ends over the reference line, span
//       its extent along it: no normal is rotated for the test);
//     - it overlaps the reference edge along the tangent by more than
//       k_reclip_min_overlap (2 linear slops) + 4 × the penetration, so the
//       pair is a face contact, not a corner about to slide off;
//     - both clipped points are inside the margin.
//   Otherwise (and for every other pair kind) the full search runs. For
//   small relative motions the full search picks the same two edges, and
//   then the re-clip's result is its result bit for bit (the same transforms
//   and the same clipping code); the tests check that, and that it falls back
//   beyond each threshold. No state is added: the decision reads the previous
//   manifold's point count and ids, which are in the canonical state
//   (replay/state.cpp), so a world restored from a snapshot re-clips exactly
//   when the original does. Stacking quality is unchanged (pyramid-100 top
//   sag 0.734 m after 500 steps, 0.735 m before; docs/benchmarks.md).
//
// * Arithmetic. Dot products, rotations, transforms, sums and differences
//   go through narrow_math.h: one exact 128-bit sum of products rounded once,
//   half up, and plain 64-bit adds, with no saturation test, where
//   manifold_internal.h's range argument shows nothing can overflow (every
//   coordinate in A's frame is below 2^21 m, every direction unit); outside
//   the limits they wrap identically in every build. Clipping fractions use
//   one 128÷64 division (their quotient is in [0, 1]). Squared distances stay
//   exact 128-bit squares. Error: each projection is one rounded Q32.32 value
//   (error ≤ ½ raw unit ≈ 1.2e-10 m; only exact negative ties round
//   differently from the checked operators, toward +∞); a clipped point
//   carries one rounded quotient t (the span is ≥ k_clip_span_epsilon =
//   2^-20 m, so t's error moves the point by ≤ |edge|·2^-33) and one rounded
//   product per component; the oracle tests (tests/physics/test_manifold.cpp)
//   keep their tolerances and pass. The change from fast_math.h (checked
//   bits, saturation and ties-away rounding) to these operations halved the
//   re-clip's instruction count (docs/benchmarks.md) and changed results in
//   the last bits (golden chains regenerated once).
//
// * Symmetry. collide() swaps and flips pairs stored the other way round, so
//   collide(A, B) is bit-for-bit flip_manifold(collide(B, A)) for pairs of different
//   types. For two shapes of the same type the function itself runs with A
//   as reference first, so the two orders agree up to rounding and the
//   choice of reference face within the flip tolerance.
#include <algorithm>
#include <utility>

#include "fixed/vec2.h"
#include "physics/collision.h"
#include "physics/manifold_internal.h"

namespace tandem {
namespace manifold_detail {

/// Local manifold → world manifold.
Manifold to_world(const LocalManifold& lm, Transform xf_a, Transform xf_b) {
  Manifold m;
  if (lm.count == 0) return m;
  to_world(lm, xf_a, xf_b, &m);
  return m;
}

// ---------------------------------------------------------------------------
// Round points and segments against round points
// ---------------------------------------------------------------------------

/// Two rounded points: core points pa (radius ra) and pb (radius rb) in A's
/// frame. `fallback` is the normal used when the core points coincide.
void collide_points(Vec2 pa, Q32 ra, Vec2 pb, Q32 rb, Vec2 fallback, LocalManifold* m) {
  const Vec2 d = pb - pa;
  // Far apart: no point, decided without the root. length(d) is the
  // isqrt_round of the exact |d|² (vec2.cpp), monotone and exact on squares,
  // so |d|² ≥ reach² with reach = ra + rb + margin (a Q32 value, radii
  // ≤ 1e4 m: no overflow) gives length(d) ≥ reach, i.e. separation ≥ margin
  // below: the same return, bit for bit. Squares are exact 128-bit values.
  const Q32 reach = nm::add(nm::add(ra, rb), k_margin);
  if (reach.raw > 0 && !wide::less_u(wide::add(square(d.x), square(d.y)), square(reach))) return;
  const Q32 separation = length(d) - ra - rb;
  if (separation >= k_margin) return;
  Vec2 n;
  if (!unit_vector(d, &n)) n = fallback;
  const Vec2 ca = nm::mul_add(pa, ra, n);
  const Vec2 cb = nm::mul_sub(pb, rb, n);
  m->normal = n;
  add_point(m, midpoint(ca, cb), separation, 0);
}

/// A rounded segment p1–p2 (radius ra) against a rounded point c (radius rb).
/// `fallback` is the normal used when c lies on the segment's core.
void collide_segment_point(Vec2 p1, Vec2 p2, Q32 ra, Vec2 c, Q32 rb, Vec2 fallback, LocalManifold* m) {
  Q32 len;
  const Vec2 u = length_and_normalize(p2 - p1, &len);
  if (len.raw == 0) {
    collide_points(p1, ra, c, rb, fallback, m);
    return;
  }
  const Vec2 w = nm::sub(c, p1);
  const Q32 s = nm::dot(w, u);
  if (s <= Q32::zero()) {
    collide_points(p1, ra, c, rb, fallback, m);
    return;
  }
  if (s >= len) {
    collide_points(p2, ra, c, rb, fallback, m);
    return;
  }
  const Q32 h = nm::cross(u, w);  // > 0: c left of p1→p2
  const Vec2 n = h.raw > 0 ? left_perp(u) : (h.raw < 0 ? right_perp(u) : fallback);
  const Q32 separation = abs(h) - ra - rb;
  if (separation >= k_margin) return;
  const Vec2 pa = nm::mul_add(p1, s, u);
  m->normal = n;
  add_point(m, midpoint(nm::mul_add(pa, ra, n), nm::mul_sub(c, rb, n)), separation, 0);
}

}  // namespace manifold_detail

using namespace manifold_detail;

Manifold flip_manifold(const Manifold& m) {
  Manifold f = m;
  f.normal = -m.normal;
  for (int32_t i = 0; i < m.point_count; ++i) {
    ManifoldPoint& p = f.points[static_cast<size_t>(i)];
    std::swap(p.anchor_a, p.anchor_b);
    p.id = static_cast<uint16_t>(((p.id & 0xFFu) << 8) | (p.id >> 8));
  }
  return f;
}


// ---------------------------------------------------------------------------
// Public manifold functions
// ---------------------------------------------------------------------------

Manifold collide_circles(const Circle& a, Transform xf_a, const Circle& b, Transform xf_b) {
  const Vec2 pb = nm::transform_point(nm::inv_mul_transforms(xf_a, xf_b), b.center);
  LocalManifold lm;
  collide_points(a.center, a.radius, pb, b.radius, {Q32::zero(), Q32::one()}, &lm);
  return to_world(lm, xf_a, xf_b);
}

Manifold collide_capsule_and_circle(const Capsule& a, Transform xf_a, const Circle& b, Transform xf_b) {
  const Vec2 pb = nm::transform_point(nm::inv_mul_transforms(xf_a, xf_b), b.center);
  Vec2 u;
  if (!unit_vector(a.center2 - a.center1, &u)) u = {Q32::one(), Q32::zero()};
  LocalManifold lm;
  collide_segment_point(a.center1, a.center2, a.radius, pb, b.radius, left_perp(u), &lm);
  return to_world(lm, xf_a, xf_b);
}

Manifold collide_segment_and_circle(const Segment& a, Transform xf_a, const Circle& b, Transform xf_b) {
  return collide_capsule_and_circle({a.point1, a.point2, Q32::zero()}, xf_a, b, xf_b);
}

Manifold collide_polygon_and_circle(const Polygon& a, Transform xf_a, const Circle& b, Transform xf_b) {
  const Vec2 c = nm::transform_point(nm::inv_mul_transforms(xf_a, xf_b), b.center);
  const int32_t count = std::clamp(a.count, int32_t{0}, int32_t{k_max_polygon_vertices});
  LocalManifold lm;
  if (count == 0) return {};

  Q32 separation = Q32::min();
  int32_t edge = 0;
  for (int32_t i = 0; i < count; ++i) {
    const Q32 s = nm::dot(a.normals[sz(i)], nm::sub(c, a.vertices[sz(i)]));
    if (s > separation) {
      separation = s;
      edge = i;
    }
  }
  const Q32 radius = a.radius + b.radius;
  if (separation >= radius + k_margin) return {};

  const Vec2 n = a.normals[sz(edge)];
  const Vec2 v1 = a.vertices[sz(edge)];
  const Vec2 v2 = a.vertices[sz(next_index(edge, count))];
  if (separation > Q32::zero()) {
    // Outside the core: the reference edge or one of its vertices is closest.
    if (nm::dot(nm::sub(c, v1), nm::sub(v2, v1)) < Q32::zero()) {
      collide_points(v1, a.radius, c, b.radius, n, &lm);
      return to_world(lm, xf_a, xf_b);
    }
    if (nm::dot(nm::sub(c, v2), nm::sub(v1, v2)) < Q32::zero()) {
      collide_points(v2, a.radius, c, b.radius, n, &lm);
      return to_world(lm, xf_a, xf_b);
    }
  }
  // Over the face (or inside the core): the face normal.
  const Vec2 ca = nm::mul_add(c, nm::sub(a.radius, separation), n);
  const Vec2 cb = nm::mul_sub(c, b.radius, n);
  lm.normal = n;
  add_point(&lm, midpoint(ca, cb), separation - radius, 0);
  return to_world(lm, xf_a, xf_b);
}

// ---------------------------------------------------------------------------
// Dispatch
// ---------------------------------------------------------------------------

Manifold collide(const ShapeGeometry& a, Transform xf_a, const ShapeGeometry& b, Transform xf_b) {
  using T = ShapeType;
  switch (a.type) {
    case T::circle:
      switch (b.type) {
        case T::circle: return collide_circles(a.circle, xf_a, b.circle, xf_b);
        case T::capsule: return flip_manifold(collide_capsule_and_circle(b.capsule, xf_b, a.circle, xf_a));
        case T::segment: return flip_manifold(collide_segment_and_circle(b.segment, xf_b, a.circle, xf_a));
        case T::polygon: return flip_manifold(collide_polygon_and_circle(b.polygon, xf_b, a.circle, xf_a));
        case T::chain_segment: return flip_manifold(collide_chain_segment_and_circle(b.chain_segment, xf_b, a.circle, xf_a));
        case T::count: break;
      }
      break;
    case T::capsule:
      switch (b.type) {
        case T::circle: return collide_capsule_and_circle(a.capsule, xf_a, b.circle, xf_b);
        case T::capsule: return collide_capsules(a.capsule, xf_a, b.capsule, xf_b);
        case T::segment: return flip_manifold(collide_segment_and_capsule(b.segment, xf_b, a.capsule, xf_a));
        case T::polygon: return flip_manifold(collide_polygon_and_capsule(b.polygon, xf_b, a.capsule, xf_a));
        case T::chain_segment: return flip_manifold(collide_chain_segment_and_capsule(b.chain_segment, xf_b, a.capsule, xf_a));
        case T::count: break;
      }
      break;
    case T::segment:
      switch (b.type) {
        case T::circle: return collide_segment_and_circle(a.segment, xf_a, b.circle, xf_b);
        case T::capsule: return collide_segment_and_capsule(a.segment, xf_a, b.capsule, xf_b);
        case T::polygon: return collide_segment_and_polygon(a.segment, xf_a, b.polygon, xf_b);
        case T::segment:
        case T::chain_segment:
        case T::count: break;
      }
      break;
    case T::polygon:
      switch (b.type) {
        case T::circle: return collide_polygon_and_circle(a.polygon, xf_a, b.circle, xf_b);
        case T::capsule: return collide_polygon_and_capsule(a.polygon, xf_a, b.capsule, xf_b);
        case T::segment: return flip_manifold(collide_segment_and_polygon(b.segment, xf_b, a.polygon, xf_a));
        case T::polygon: return collide_polygons(a.polygon, xf_a, b.polygon, xf_b);
        case T::chain_segment: return flip_manifold(collide_chain_segment_and_polygon(b.chain_segment, xf_b, a.polygon, xf_a));
        case T::count: break;
      }
      break;
    case T::chain_segment:
      switch (b.type) {
        case T::circle: return collide_chain_segment_and_circle(a.chain_segment, xf_a, b.circle, xf_b);
        case T::capsule: return collide_chain_segment_and_capsule(a.chain_segment, xf_a, b.capsule, xf_b);
        case T::polygon: return collide_chain_segment_and_polygon(a.chain_segment, xf_a, b.polygon, xf_b);
        case T::segment:
        case T::chain_segment:
        case T::count: break;
      }
      break;
    case T::count: break;
  }
  return {};
}

void collide_persistent(const ShapeGeometry& a, Transform xf_a, const ShapeGeometry& b, Transform xf_b,
                        const Manifold& previous, Manifold* out) {
  if (a.type == ShapeType::polygon && b.type == ShapeType::polygon && previous.point_count == 2 &&
      reclip_polygons(a.polygon, xf_a, b.polygon, xf_b, previous, out)) {
    return;
  }
  *out = collide(a, xf_a, b, xf_b);
}

Manifold collide_persistent(const ShapeGeometry& a, Transform xf_a, const ShapeGeometry& b, Transform xf_b,
                            const Manifold& previous) {
  Manifold m;
  collide_persistent(a, xf_a, b, xf_b, previous, &m);
  return m;
}

}  // namespace tandem
