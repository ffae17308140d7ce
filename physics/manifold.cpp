// manifold.cpp — the narrow phase: contact manifolds for every shape pair.
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
//
// * Margin. A point is reported while its separation < k_speculative_distance
//   (each clipped point is filtered on its own, so a tilted box can report
//   one point).
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
// * Symmetry. collide() swaps and flips pairs stored the other way round, so
//   collide(A, B) is bit-for-bit flip_manifold(collide(B, A)) for pairs of different
//   types. For two shapes of the same type the function itself runs with A
//   as reference first, so the two orders agree up to rounding and the
//   choice of reference face within the flip tolerance.
#include <algorithm>
#include <array>
#include <utility>

#include "fixed/vec2.h"
#include "fixed/wide.h"
#include "physics/collision.h"

namespace tandem {
namespace {

/// Points are reported while separation < this (m).
constexpr Q32 k_margin = k_speculative_distance;
/// B's face must beat A's by more than this to become the reference (m).
constexpr Q32 k_flip_tolerance = Q32::from_raw(k_linear_slop.raw / 10);
/// A chain vertex is convex when sin(turn angle) ≥ this; a normal more than
/// asin(this) outside the segment's cone is skipped (dimensionless).
constexpr Q32 k_chain_sin_tolerance = 0.01_q32;
/// Chain features closer than this use the SAT path (m), as in Box2D.
constexpr Q32 k_chain_distance_tolerance = Q32::from_raw(k_linear_slop.raw / 10);
/// Incident edges whose extent along the reference tangent is below this are
/// not clipped (m, 2^-20 ≈ 9.5e-7): the division would amplify rounding.
constexpr Q32 k_clip_span_epsilon = Q32::from_raw(int64_t{1} << 12);
/// Vertex–vertex pairs closer than this are handled by face clipping (m).
constexpr Q32 k_vertex_pair_epsilon = Q32::from_raw(int64_t{1} << 12);

// ---------------------------------------------------------------------------
// Local manifolds (A's frame)
// ---------------------------------------------------------------------------

struct LocalPoint {
  Vec2 point;      // midway between the surfaces, A's frame, m
  Q32 separation;  // m
  uint16_t id = 0;
};

struct LocalManifold {
  Vec2 normal;  // unit, A's frame, from A to B
  std::array<LocalPoint, 2> points{};
  int32_t count = 0;
};

/// Appends a point if its separation is inside the margin.
void add_point(LocalManifold* m, Vec2 point, Q32 separation, uint16_t id) {
  if (separation >= k_margin || m->count >= 2) return;
  m->points[static_cast<size_t>(m->count)] = {point, separation, id};
  ++m->count;
}

/// (a + b)/2 without overflow of the sum; each component rounded once.
Vec2 midpoint(Vec2 a, Vec2 b) { return {a.x + (b.x - a.x) / 2, a.y + (b.y - a.y) / 2}; }

/// v/|v|; false for the zero vector (normalize is scale-free, so any other
/// vector gives a direction accurate to about a raw unit).
bool unit_vector(Vec2 v, Vec2* out) {
  if (v.x.raw == 0 && v.y.raw == 0) return false;
  *out = normalize(v);
  return true;
}

/// Local manifold → world manifold.
Manifold to_world(const LocalManifold& lm, Transform xf_a, Transform xf_b) {
  Manifold m;
  if (lm.count == 0) return m;
  m.normal = rotate(xf_a.q, lm.normal);
  const Vec2 pab = xf_a.p - xf_b.p;
  for (int32_t i = 0; i < lm.count; ++i) {
    const LocalPoint& lp = lm.points[static_cast<size_t>(i)];
    ManifoldPoint& mp = m.points[static_cast<size_t>(i)];
    mp.anchor_a = rotate(xf_a.q, lp.point);
    mp.anchor_b = mp.anchor_a + pab;
    mp.point = xf_a.p + mp.anchor_a;
    mp.separation = lp.separation;
    mp.id = lp.id;
  }
  m.point_count = lm.count;
  return m;
}

// ---------------------------------------------------------------------------
// Round points and segments against round points
// ---------------------------------------------------------------------------

/// Two rounded points: core points pa (radius ra) and pb (radius rb) in A's
/// frame. `fallback` is the normal used when the core points coincide.
void collide_points(Vec2 pa, Q32 ra, Vec2 pb, Q32 rb, Vec2 fallback, LocalManifold* m) {
  const Vec2 d = pb - pa;
  const Q32 separation = length(d) - ra - rb;
  if (separation >= k_margin) return;
  Vec2 n;
  if (!unit_vector(d, &n)) n = fallback;
  const Vec2 ca = mul_add(pa, ra, n);
  const Vec2 cb = mul_sub(pb, rb, n);
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
  const Vec2 w = c - p1;
  const Q32 s = dot(w, u);
  if (s <= Q32::zero()) {
    collide_points(p1, ra, c, rb, fallback, m);
    return;
  }
  if (s >= len) {
    collide_points(p2, ra, c, rb, fallback, m);
    return;
  }
  const Q32 h = cross(u, w);  // > 0: c left of p1→p2
  const Vec2 n = h.raw > 0 ? left_perp(u) : (h.raw < 0 ? right_perp(u) : fallback);
  const Q32 separation = abs(h) - ra - rb;
  if (separation >= k_margin) return;
  const Vec2 pa = mul_add(p1, s, u);
  m->normal = n;
  add_point(m, midpoint(mul_add(pa, ra, n), mul_sub(c, rb, n)), separation, 0);
}

// ---------------------------------------------------------------------------
// Cores: polygons, capsules and segments as convex point sets with normals
// ---------------------------------------------------------------------------

struct Core {
  std::array<Vec2, k_max_polygon_vertices> vertices{};  // CCW, m
  std::array<Vec2, k_max_polygon_vertices> normals{};   // unit, normal i: edge i → i+1
  Vec2 centroid;                                        // m
  Q32 radius;                                           // m
  int32_t count = 0;                                    // 2 … k_max_polygon_vertices
};

constexpr size_t sz(int32_t i) { return static_cast<size_t>(i); }
constexpr int32_t next_index(int32_t i, int32_t count) { return i + 1 < count ? i + 1 : 0; }
constexpr int32_t prev_index(int32_t i, int32_t count) { return i > 0 ? i - 1 : count - 1; }

Core core_from_polygon(const Polygon& p) {
  Core c;
  c.vertices = p.vertices;
  c.normals = p.normals;
  c.centroid = p.centroid;
  c.radius = p.radius;
  c.count = std::clamp(p.count, int32_t{0}, int32_t{k_max_polygon_vertices});
  return c;
}

/// A segment or capsule as a 2-gon: edge 0 is p1→p2 with normal
/// right_perp(p2 − p1), edge 1 the way back.
Core core_from_segment(Vec2 p1, Vec2 p2, Q32 radius) {
  Core c;
  Vec2 u;
  if (!unit_vector(p2 - p1, &u)) u = {Q32::one(), Q32::zero()};
  c.vertices[0] = p1;
  c.vertices[1] = p2;
  c.normals[0] = right_perp(u);
  c.normals[1] = left_perp(u);
  c.centroid = midpoint(p1, p2);
  c.radius = radius;
  c.count = 2;
  return c;
}

/// The core moved by xf (B's frame → A's frame).
Core transform_core(const Core& c, Transform xf) {
  Core t = c;
  for (int32_t i = 0; i < c.count; ++i) {
    t.vertices[sz(i)] = transform_point(xf, c.vertices[sz(i)]);
    t.normals[sz(i)] = rotate(xf.q, c.normals[sz(i)]);
  }
  t.centroid = transform_point(xf, c.centroid);
  return t;
}

/// Smallest signed distance of `other`'s vertices along `axis` from `origin`.
Q32 min_along(Vec2 axis, Vec2 origin, const Core& other) {
  Q32 s = Q32::max();
  for (int32_t j = 0; j < other.count; ++j) s = min(s, dot(axis, other.vertices[sz(j)] - origin));
  return s;
}

/// The SAT over c1's edge normals: the largest, over edges, of the smallest
/// signed distance of c2's vertices to the edge's line. Lowest index wins ties.
Q32 max_separation(const Core& c1, const Core& c2, int32_t* out_edge) {
  Q32 best = Q32::min();
  int32_t best_edge = 0;
  for (int32_t i = 0; i < c1.count; ++i) {
    const Q32 s = min_along(c1.normals[sz(i)], c1.vertices[sz(i)], c2);
    if (s > best) {
      best = s;
      best_edge = i;
    }
  }
  *out_edge = best_edge;
  return best;
}

/// For a 2-gon: the separation along its own direction (the end caps).
Q32 cap_separation(const Core& seg, const Core& other) {
  const Vec2 u = left_perp(seg.normals[0]);  // direction v0 → v1
  return max(min_along(u, seg.vertices[1], other), min_along(-u, seg.vertices[0], other));
}

/// The edge of `inc` most anti-parallel to `normal` (lowest index on ties).
int32_t find_incident_edge(const Core& inc, Vec2 normal) {
  int32_t best = 0;
  Q32 best_dot = Q32::max();
  for (int32_t i = 0; i < inc.count; ++i) {
    const Q32 d = dot(normal, inc.normals[sz(i)]);
    if (d < best_dot) {
      best_dot = d;
      best = i;
    }
  }
  return best;
}

/// Of the two edges of `inc` meeting at `vertex`, the one more anti-parallel
/// to `normal` (the one starting at the vertex on ties).
int32_t incident_edge_at_vertex(const Core& inc, int32_t vertex, Vec2 normal) {
  const int32_t prev = prev_index(vertex, inc.count);
  return dot(normal, inc.normals[sz(prev)]) < dot(normal, inc.normals[sz(vertex)]) ? prev : vertex;
}

/// What clip() does when the incident edge lies wholly outside the reference
/// edge's side planes.
enum class Outside {
  nearest_end,  // one point at the incident edge's nearest end (overlapping cores)
  nothing,      // no points (chain segments: that region belongs to a neighbour)
};

/// Clips incident edge `i` of `inc` against the side planes of reference edge
/// `r` of `ref` (both cores in A's frame) and adds the points. `ref_is_b`:
/// the reference belongs to shape B (normal and ids are flipped to A→B).
void clip(const Core& ref, int32_t r, const Core& inc, int32_t i, bool ref_is_b, Outside outside,
          LocalManifold* m) {
  const int32_t r2i = next_index(r, ref.count);
  const int32_t i2i = next_index(i, inc.count);
  const Vec2 n = ref.normals[sz(r)];
  const Vec2 r1 = ref.vertices[sz(r)];
  const Vec2 r2 = ref.vertices[sz(r2i)];
  const Vec2 i1 = inc.vertices[sz(i)];
  const Vec2 i2 = inc.vertices[sz(i2i)];

  // Tangent coordinates from r1 along the reference edge; the incident edge
  // runs the other way (i1 upper, i2 lower) when the edges face each other.
  const Vec2 t = left_perp(n);
  const Q32 upper1 = dot(r2 - r1, t);
  const Q32 s1 = dot(i1 - r1, t);
  const Q32 s2 = dot(i2 - r1, t);
  const Q32 span = s1 - s2;

  struct Clipped {
    Vec2 p;
    int32_t ref_vertex;
    int32_t inc_vertex;
  };
  std::array<Clipped, 2> pts{};
  int32_t count = 0;
  if (outside == Outside::nothing && (max(s1, s2) < Q32::zero() || min(s1, s2) > upper1)) return;
  if (span > k_clip_span_epsilon && s1 <= Q32::zero()) {
    pts[0] = {i1, r, i};  // incident edge wholly before r1 (or ending on it): its nearest end
    count = 1;
  } else if (span > k_clip_span_epsilon && s2 >= upper1) {
    pts[0] = {i2, r2i, i2i};  // wholly past r2
    count = 1;
  } else {
    Vec2 lower = i2;
    Vec2 upper = i1;
    if (span > k_clip_span_epsilon) {
      if (s2 < Q32::zero()) lower = lerp(i2, i1, (Q32::zero() - s2) / span);
      if (s1 > upper1) upper = lerp(i2, i1, (upper1 - s2) / span);
    }
    pts[0] = {lower, r, i2i};
    pts[1] = {upper, r2i, i};
    count = 2;
  }

  const Q32 radius = ref.radius + inc.radius;
  m->normal = ref_is_b ? -n : n;
  for (int32_t k = 0; k < count; ++k) {
    const Clipped& c = pts[sz(k)];
    const Q32 s = dot(c.p - r1, n);  // core separation along the reference normal
    const Vec2 mid = mul_add(c.p, (ref.radius - inc.radius - s) / 2, n);
    const uint16_t id = ref_is_b ? make_feature_id(c.inc_vertex, c.ref_vertex) : make_feature_id(c.ref_vertex, c.inc_vertex);
    add_point(m, mid, s - radius, id);
  }
}

/// |v|² exactly, in 2^-64 m² units (fits: components are Q32 raw values).
wide::U128 exact_length_squared(Vec2 v) {
  const uint64_t ax = detail::magnitude(v.x.raw), ay = detail::magnitude(v.y.raw);
  return wide::add(wide::mul_u64(ax, ax), wide::mul_u64(ay, ay));
}

/// The closest features of two disjoint cores.
struct ClosestFeatures {
  wide::U128 vv_d2;  // smallest vertex–vertex squared distance
  int32_t vv_a = 0, vv_b = 0;
  bool has_a_face = false;  // a vertex of B over the interior of an edge of A
  Q32 a_face_distance;
  int32_t a_face_edge = 0, a_face_vertex = 0;
  bool has_b_face = false;  // a vertex of A over the interior of an edge of B
  Q32 b_face_distance;
  int32_t b_face_edge = 0, b_face_vertex = 0;
};

/// Vertices of `pts` over the interior of an edge of `edges`, outside it:
/// the nearest such pair (lowest edge, then vertex, on ties).
void find_face_pair(const Core& edges, const Core& pts, bool* out_has, Q32* out_distance, int32_t* out_edge,
                    int32_t* out_vertex) {
  *out_has = false;
  for (int32_t e = 0; e < edges.count; ++e) {
    const Vec2 n = edges.normals[sz(e)];
    const Vec2 dir = left_perp(n);
    const Vec2 v1 = edges.vertices[sz(e)];
    const Q32 len = dot(edges.vertices[sz(next_index(e, edges.count))] - v1, dir);
    for (int32_t j = 0; j < pts.count; ++j) {
      const Vec2 w = pts.vertices[sz(j)] - v1;
      const Q32 s = dot(w, dir);
      if (s <= Q32::zero() || s >= len) continue;
      const Q32 h = dot(w, n);
      if (h <= Q32::zero()) continue;
      if (!*out_has || h < *out_distance) {
        *out_has = true;
        *out_distance = h;
        *out_edge = e;
        *out_vertex = j;
      }
    }
  }
}

ClosestFeatures find_closest_features(const Core& a, const Core& b) {
  ClosestFeatures f;
  bool first = true;
  for (int32_t i = 0; i < a.count; ++i) {
    for (int32_t j = 0; j < b.count; ++j) {
      const wide::U128 d2 = exact_length_squared(b.vertices[sz(j)] - a.vertices[sz(i)]);
      if (first || wide::less_u(d2, f.vv_d2)) {
        first = false;
        f.vv_d2 = d2;
        f.vv_a = i;
        f.vv_b = j;
      }
    }
  }
  find_face_pair(a, b, &f.has_a_face, &f.a_face_distance, &f.a_face_edge, &f.a_face_vertex);
  find_face_pair(b, a, &f.has_b_face, &f.b_face_distance, &f.b_face_edge, &f.b_face_vertex);
  return f;
}

/// Squared Q32 distance in the units of exact_length_squared.
wide::U128 square(Q32 d) {
  const uint64_t m = detail::magnitude(d.raw);
  return wide::mul_u64(m, m);
}

/// The manifold of two cores in A's frame (see the design notes).
void collide_cores(const Core& a, const Core& b, LocalManifold* m) {
  const Q32 radius = a.radius + b.radius;
  const Q32 max_distance = radius + k_margin;

  int32_t edge_a = 0, edge_b = 0;
  const Q32 sep_a = max_separation(a, b, &edge_a);
  const Q32 sep_b = max_separation(b, a, &edge_b);
  Q32 sep = max(sep_a, sep_b);
  if (a.count == 2 && b.count == 2) sep = max(sep, max(cap_separation(a, b), cap_separation(b, a)));
  if (sep >= max_distance) return;

  if (sep > Q32::zero()) {
    const ClosestFeatures f = find_closest_features(a, b);
    wide::U128 face_d2{~uint64_t{0}, ~uint64_t{0}};
    if (f.has_a_face) face_d2 = square(f.a_face_distance);
    if (f.has_b_face && wide::less_u(square(f.b_face_distance), face_d2)) face_d2 = square(f.b_face_distance);

    if (wide::less_u(f.vv_d2, face_d2)) {
      // Vertex–vertex: one point along the pair.
      const Vec2 va = a.vertices[sz(f.vv_a)];
      const Vec2 vb = b.vertices[sz(f.vv_b)];
      Q32 distance;
      const Vec2 n = length_and_normalize(vb - va, &distance);
      if (distance >= max_distance) return;
      if (distance > k_vertex_pair_epsilon) {
        m->normal = n;
        add_point(m, midpoint(mul_add(va, a.radius, n), mul_sub(vb, b.radius, n)), distance - radius,
                  make_feature_id(f.vv_a, f.vv_b));
        return;
      }
      // Too close to trust the direction: fall through to face clipping.
    } else {
      const Q32 closest = f.has_a_face && (!f.has_b_face || f.a_face_distance <= f.b_face_distance)
                              ? f.a_face_distance
                              : f.b_face_distance;
      if (closest >= max_distance) return;
      if (f.has_a_face && (!f.has_b_face || f.a_face_distance <= f.b_face_distance + k_flip_tolerance)) {
        const int32_t inc = incident_edge_at_vertex(b, f.a_face_vertex, a.normals[sz(f.a_face_edge)]);
        clip(a, f.a_face_edge, b, inc, false, Outside::nearest_end, m);
      } else {
        const int32_t inc = incident_edge_at_vertex(a, f.b_face_vertex, b.normals[sz(f.b_face_edge)]);
        clip(b, f.b_face_edge, a, inc, true, Outside::nearest_end, m);
      }
      return;
    }
  }

  // Overlapping (or touching) cores: SAT reference face, A preferred.
  if (sep_b > sep_a + k_flip_tolerance) {
    clip(b, edge_b, a, find_incident_edge(a, b.normals[sz(edge_b)]), true, Outside::nearest_end, m);
  } else {
    clip(a, edge_a, b, find_incident_edge(b, a.normals[sz(edge_a)]), false, Outside::nearest_end, m);
  }
}

Manifold collide_core_pair(const Core& a, Transform xf_a, const Core& b_local, Transform xf_b) {
  const Core b = transform_core(b_local, inv_mul_transforms(xf_a, xf_b));
  LocalManifold lm;
  collide_cores(a, b, &lm);
  return to_world(lm, xf_a, xf_b);
}

// ---------------------------------------------------------------------------
// Chain segments against cores (smooth collision)
// ---------------------------------------------------------------------------

enum class NormalType { skip, admit, snap };

struct ChainParams {
  Vec2 p1, p2;
  Vec2 edge1;    // unit p1 → p2
  Vec2 normal0;  // previous segment's normal
  Vec2 normal1;  // this segment's normal, right_perp(edge1)
  Vec2 normal2;  // next segment's normal
  bool convex1 = false;
  bool convex2 = false;
};

ChainParams make_chain_params(const ChainSegment& s) {
  ChainParams c;
  c.p1 = s.segment.point1;
  c.p2 = s.segment.point2;
  if (!unit_vector(c.p2 - c.p1, &c.edge1)) c.edge1 = {Q32::one(), Q32::zero()};
  Vec2 edge0, edge2;
  if (!unit_vector(c.p1 - s.ghost1, &edge0)) edge0 = c.edge1;
  if (!unit_vector(s.ghost2 - c.p2, &edge2)) edge2 = c.edge1;
  c.normal0 = right_perp(edge0);
  c.normal1 = right_perp(c.edge1);
  c.normal2 = right_perp(edge2);
  c.convex1 = cross(edge0, c.edge1) >= k_chain_sin_tolerance;
  c.convex2 = cross(c.edge1, edge2) >= k_chain_sin_tolerance;
  return c;
}

/// Where a candidate normal (A's frame, from the chain to B) falls in the
/// segment's Gauss map: inside the convex end's cone (admit), outside it
/// (skip: the neighbour segment owns it), or at a flat/concave end (snap to
/// the segment normal).
NormalType classify_normal(const ChainParams& c, Vec2 normal) {
  if (dot(normal, c.edge1) <= Q32::zero()) {
    if (!c.convex1) return NormalType::snap;
    return cross(normal, c.normal0) > k_chain_sin_tolerance ? NormalType::skip : NormalType::admit;
  }
  if (!c.convex2) return NormalType::snap;
  return cross(c.normal2, normal) > k_chain_sin_tolerance ? NormalType::skip : NormalType::admit;
}

/// Polygon edge `ref` (normal n, of B) as the reference against the chain
/// segment: refuses when the segment end that would be incident has a
/// neighbour facing n better than this segment (the neighbour owns it).
void chain_polygon_reference(const ChainParams& c, const Core& seg, const Core& poly, int32_t ref,
                             LocalManifold* m) {
  const Vec2 n = poly.normals[sz(ref)];
  const Vec2 b1 = poly.vertices[sz(ref)];
  const Vec2 n0 = c.convex1 ? c.normal0 : c.normal1;
  const Vec2 n2 = c.convex2 ? c.normal2 : c.normal1;
  const Q32 d1 = dot(n, c.p1 - b1);
  const Q32 d2 = dot(n, c.p2 - b1);
  const Q32 own = dot(c.normal1, n);
  if (d1 < d2) {
    if (dot(n0, n) < own) return;
  } else {
    if (dot(n2, n) < own) return;
  }
  clip(poly, ref, seg, 0, true, Outside::nothing, m);
}

void collide_chain_core(const ChainSegment& chain, const Core& b, LocalManifold* m) {
  const ChainParams c = make_chain_params(chain);
  const Core seg = core_from_segment(c.p1, c.p2, Q32::zero());  // edge 0 normal = normal1

  // One-sided: nothing when B's centroid is behind this segment and behind
  // the convex neighbours.
  const bool behind1 = dot(c.normal1, b.centroid - c.p1) < Q32::zero();
  const bool behind0 = !c.convex1 || dot(c.normal0, b.centroid - c.p1) < Q32::zero();
  const bool behind2 = !c.convex2 || dot(c.normal2, b.centroid - c.p2) < Q32::zero();
  if (behind1 && behind0 && behind2) return;

  const Q32 max_distance = b.radius + k_margin;

  // Core distance: SAT (complete with the segment's end caps), then exact
  // closest features when disjoint.
  int32_t edge_unused = 0;
  const Q32 sep = max(max(max_separation(seg, b, &edge_unused), max_separation(b, seg, &edge_unused)),
                      cap_separation(seg, b));
  if (sep >= max_distance) return;

  int32_t incident_vertex = -1;
  int32_t incident_edge = -1;
  bool use_sat = true;
  if (sep > Q32::zero()) {
    const ClosestFeatures f = find_closest_features(seg, b);
    wide::U128 face_d2{~uint64_t{0}, ~uint64_t{0}};
    if (f.has_a_face) face_d2 = square(f.a_face_distance);
    if (f.has_b_face && wide::less_u(square(f.b_face_distance), face_d2)) face_d2 = square(f.b_face_distance);
    const bool vertex_pair = wide::less_u(f.vv_d2, face_d2);
    Q32 distance;
    if (vertex_pair) {
      distance = length(b.vertices[sz(f.vv_b)] - seg.vertices[sz(f.vv_a)]);
    } else {
      distance = f.has_a_face && (!f.has_b_face || f.a_face_distance <= f.b_face_distance) ? f.a_face_distance
                                                                                           : f.b_face_distance;
    }
    if (distance >= max_distance) return;

    if (!behind1 && distance > k_chain_distance_tolerance) {
      use_sat = false;
      if (vertex_pair) {
        const Vec2 pa = seg.vertices[sz(f.vv_a)];
        const Vec2 pb = b.vertices[sz(f.vv_b)];
        const Vec2 n = normalize(pb - pa);
        const NormalType type = classify_normal(c, n);
        if (type == NormalType::skip) return;
        if (type == NormalType::admit) {
          m->normal = n;
          add_point(m, midpoint(pa, mul_sub(pb, b.radius, n)), distance - b.radius, make_feature_id(f.vv_a, f.vv_b));
          return;
        }
        incident_vertex = f.vv_b;  // snap
      } else if (f.has_b_face && (!f.has_a_face || f.b_face_distance < f.a_face_distance)) {
        // A segment end over a polygon edge.
        const Vec2 nb = b.normals[sz(f.b_face_edge)];
        const NormalType type = classify_normal(c, -nb);
        if (type == NormalType::skip) return;
        if (type == NormalType::admit) {
          chain_polygon_reference(c, seg, b, f.b_face_edge, m);
          return;
        }
        incident_edge = f.b_face_edge;  // snap
      } else {
        // A polygon vertex over the segment.
        incident_vertex = f.a_face_vertex;
      }
    }
  }

  if (use_sat) {
    // Segment normal (and convex neighbours' normals) against polygon normals.
    Q32 edge_separation = Q32::max();
    for (int32_t j = 0; j < b.count; ++j) {
      const Q32 s = dot(c.normal1, b.vertices[sz(j)] - c.p1);
      if (s < edge_separation) {
        edge_separation = s;
        incident_vertex = j;
      }
    }
    if (c.convex1) {
      const Q32 s0 = min_along(c.normal0, c.p1, b);
      if (s0 > edge_separation) {
        edge_separation = s0;
        incident_vertex = -1;  // the previous segment owns this axis
      }
    }
    if (c.convex2) {
      const Q32 s2 = min_along(c.normal2, c.p2, b);
      if (s2 > edge_separation) {
        edge_separation = s2;
        incident_vertex = -1;  // the next segment owns this axis
      }
    }

    Q32 polygon_separation = Q32::min();
    int32_t reference = -1;
    for (int32_t i = 0; i < b.count; ++i) {
      const Vec2 n = b.normals[sz(i)];
      if (classify_normal(c, -n) != NormalType::admit) continue;
      const Vec2 v = b.vertices[sz(i)];
      const Q32 s = min(dot(n, c.p1 - v), dot(n, c.p2 - v));
      if (s > polygon_separation) {
        polygon_separation = s;
        reference = i;
      }
    }
    if (reference >= 0 && polygon_separation > edge_separation) {
      chain_polygon_reference(c, seg, b, reference, m);
      return;
    }
    if (incident_vertex < 0) return;
  }

  // The segment is the reference face.
  const int32_t inc = incident_edge >= 0 ? incident_edge : incident_edge_at_vertex(b, incident_vertex, c.normal1);
  clip(seg, 0, b, inc, false, Outside::nothing, m);
}

Manifold collide_chain_segment_and_core(const ChainSegment& a, Transform xf_a, const Core& b_local, Transform xf_b) {
  const Core b = transform_core(b_local, inv_mul_transforms(xf_a, xf_b));
  LocalManifold lm;
  collide_chain_core(a, b, &lm);
  return to_world(lm, xf_a, xf_b);
}

}  // namespace

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
  const Vec2 pb = transform_point(inv_mul_transforms(xf_a, xf_b), b.center);
  LocalManifold lm;
  collide_points(a.center, a.radius, pb, b.radius, {Q32::zero(), Q32::one()}, &lm);
  return to_world(lm, xf_a, xf_b);
}

Manifold collide_capsule_and_circle(const Capsule& a, Transform xf_a, const Circle& b, Transform xf_b) {
  const Vec2 pb = transform_point(inv_mul_transforms(xf_a, xf_b), b.center);
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
  const Vec2 c = transform_point(inv_mul_transforms(xf_a, xf_b), b.center);
  const int32_t count = std::clamp(a.count, int32_t{0}, int32_t{k_max_polygon_vertices});
  LocalManifold lm;
  if (count == 0) return {};

  Q32 separation = Q32::min();
  int32_t edge = 0;
  for (int32_t i = 0; i < count; ++i) {
    const Q32 s = dot(a.normals[sz(i)], c - a.vertices[sz(i)]);
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
    if (dot(c - v1, v2 - v1) < Q32::zero()) {
      collide_points(v1, a.radius, c, b.radius, n, &lm);
      return to_world(lm, xf_a, xf_b);
    }
    if (dot(c - v2, v1 - v2) < Q32::zero()) {
      collide_points(v2, a.radius, c, b.radius, n, &lm);
      return to_world(lm, xf_a, xf_b);
    }
  }
  // Over the face (or inside the core): the face normal.
  const Vec2 ca = mul_add(c, a.radius - separation, n);
  const Vec2 cb = mul_sub(c, b.radius, n);
  lm.normal = n;
  add_point(&lm, midpoint(ca, cb), separation - radius, 0);
  return to_world(lm, xf_a, xf_b);
}

Manifold collide_capsules(const Capsule& a, Transform xf_a, const Capsule& b, Transform xf_b) {
  return collide_core_pair(core_from_segment(a.center1, a.center2, a.radius), xf_a,
                           core_from_segment(b.center1, b.center2, b.radius), xf_b);
}

Manifold collide_polygon_and_capsule(const Polygon& a, Transform xf_a, const Capsule& b, Transform xf_b) {
  return collide_core_pair(core_from_polygon(a), xf_a, core_from_segment(b.center1, b.center2, b.radius), xf_b);
}

Manifold collide_polygons(const Polygon& a, Transform xf_a, const Polygon& b, Transform xf_b) {
  return collide_core_pair(core_from_polygon(a), xf_a, core_from_polygon(b), xf_b);
}

Manifold collide_segment_and_capsule(const Segment& a, Transform xf_a, const Capsule& b, Transform xf_b) {
  return collide_core_pair(core_from_segment(a.point1, a.point2, Q32::zero()), xf_a,
                           core_from_segment(b.center1, b.center2, b.radius), xf_b);
}

Manifold collide_segment_and_polygon(const Segment& a, Transform xf_a, const Polygon& b, Transform xf_b) {
  return collide_core_pair(core_from_segment(a.point1, a.point2, Q32::zero()), xf_a, core_from_polygon(b), xf_b);
}

Manifold collide_chain_segment_and_circle(const ChainSegment& a, Transform xf_a, const Circle& b, Transform xf_b) {
  const Vec2 c = transform_point(inv_mul_transforms(xf_a, xf_b), b.center);
  const Vec2 p1 = a.segment.point1;
  const Vec2 p2 = a.segment.point2;
  const Vec2 e = p2 - p1;
  LocalManifold lm;

  // One-sided: the circle's centre must be on the normal's side.
  if (cross(e, c - p1) > Q32::zero()) return {};  // left of p1→p2

  Vec2 u;
  if (!unit_vector(e, &u)) return {};
  const Vec2 normal1 = right_perp(u);
  if (dot(e, c - p1) <= Q32::zero()) {
    // Before p1: the previous segment owns the region past its own end.
    if (dot(p1 - a.ghost1, c - p1) <= Q32::zero()) return {};
    collide_points(p1, Q32::zero(), c, b.radius, normal1, &lm);
  } else if (dot(e, p2 - c) <= Q32::zero()) {
    // Past p2: the next segment owns the region over itself.
    if (dot(a.ghost2 - p2, c - p2) > Q32::zero()) return {};
    collide_points(p2, Q32::zero(), c, b.radius, normal1, &lm);
  } else {
    collide_segment_point(p1, p2, Q32::zero(), c, b.radius, normal1, &lm);
  }
  return to_world(lm, xf_a, xf_b);
}

Manifold collide_chain_segment_and_capsule(const ChainSegment& a, Transform xf_a, const Capsule& b, Transform xf_b) {
  return collide_chain_segment_and_core(a, xf_a, core_from_segment(b.center1, b.center2, b.radius), xf_b);
}

Manifold collide_chain_segment_and_polygon(const ChainSegment& a, Transform xf_a, const Polygon& b, Transform xf_b) {
  return collide_chain_segment_and_core(a, xf_a, core_from_polygon(b), xf_b);
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

}  // namespace tandem
