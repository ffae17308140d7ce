// manifold_cores.cpp — polygons, capsules and segments as cores: the SAT,
// clipping, exact closest features for disjoint cores, and the core pair
// manifolds (design notes in manifold.cpp).
#include <algorithm>
#include <array>

#include "fixed/vec2.h"
#include "fixed/wide.h"
#include "physics/collision.h"
#include "physics/manifold_internal.h"

namespace tandem {
namespace manifold_detail {

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

/// Moves *c by xf (B's frame → A's frame), in place.
void transform_core_in_place(Core* c, Transform xf) {
  for (int32_t i = 0; i < c->count; ++i) {
    c->vertices[sz(i)] = nm::transform_point(xf, c->vertices[sz(i)]);
    c->normals[sz(i)] = nm::rotate(xf.q, c->normals[sz(i)]);
  }
  c->centroid = nm::transform_point(xf, c->centroid);
}

/// The core moved by xf (B's frame → A's frame).
Core transform_core(const Core& c, Transform xf) {
  Core t = c;
  transform_core_in_place(&t, xf);
  return t;
}

/// The SAT over c1's edge normals: the largest, over edges, of the smallest
/// signed distance of c2's vertices to the edge's line. Lowest index wins ties.
Q32 max_separation(const Core& c1, const Core& c2, int32_t* out_edge) {
  Q32 best = Q32::min();
  int32_t best_edge = 0;
  for (int32_t i = 0; i < c1.count; ++i) {
    // An edge whose running minimum falls to `best` cannot win (s > best is
    // needed), so min_along may stop there: the same edge and value as the
    // full minima.
    const Q32 s = min_along(c1.normals[sz(i)], c1.vertices[sz(i)], c2, best);
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
namespace {
int32_t find_incident_edge(const Core& inc, Vec2 normal) {
  int32_t best = 0;
  Q32 best_dot = Q32::max();
  for (int32_t i = 0; i < inc.count; ++i) {
    const Q32 d = nm::dot(normal, inc.normals[sz(i)]);
    if (d < best_dot) {
      best_dot = d;
      best = i;
    }
  }
  return best;
}

}  // namespace

/// Of the two edges of `inc` meeting at `vertex`, the one more anti-parallel
/// to `normal` (the one starting at the vertex on ties).
int32_t incident_edge_at_vertex(const Core& inc, int32_t vertex, Vec2 normal) {
  const int32_t prev = prev_index(vertex, inc.count);
  return nm::dot(normal, inc.normals[sz(prev)]) < nm::dot(normal, inc.normals[sz(vertex)]) ? prev : vertex;
}


namespace {

/// Coordinates of the incident ends from r1, along the reference edge's
/// tangent t = left_perp(n) and its normal n: the reference edge ends at
/// upper1, the incident ends are at s1 (i1) and s2 (i2) along t and at
/// heights h1, h2 along n; the incident edge runs the other way (i1 upper,
/// i2 lower) when the edges face each other.
struct Projected {
  Q32 upper1, s1, s2, h1, h2;
};

Projected project(const ClipEdges& e) {
  const Vec2 t = nm::left_perp(e.normal);
  const Vec2 d1 = nm::sub(e.i1, e.r1), d2 = nm::sub(e.i2, e.r1);
  return {nm::dot(nm::sub(e.r2, e.r1), t), nm::dot(d1, t), nm::dot(d2, t), nm::dot(d1, e.normal),
          nm::dot(d2, e.normal)};
}

inline void clip_projected(const ClipEdges& e, const Projected& pr, bool ref_is_b, Outside outside, LocalManifold* m) {
  const Vec2 n = e.normal;
  const Vec2 r1 = e.r1;
  const Vec2 i1 = e.i1;
  const Vec2 i2 = e.i2;
  const Q32 upper1 = pr.upper1, s1 = pr.s1, s2 = pr.s2;
  const Q32 span = nm::sub(s1, s2);

  // Each point with its core separation along the reference normal: an
  // unclipped end's is its height h (the same dot product as for a clipped
  // point: (p − r1)·n).
  struct Clipped {
    Vec2 p;
    Q32 s;
    int32_t ref_vertex;
    int32_t inc_vertex;
  };
  std::array<Clipped, 2> pts{};
  int32_t count = 0;
  if (outside == Outside::nothing && (max(s1, s2) < Q32::zero() || min(s1, s2) > upper1)) return;
  if (span > k_clip_span_epsilon && s1 <= Q32::zero()) {
    pts[0] = {i1, pr.h1, e.r, e.i};  // incident edge wholly before r1 (or ending on it): its nearest end
    count = 1;
  } else if (span > k_clip_span_epsilon && s2 >= upper1) {
    pts[0] = {i2, pr.h2, e.r2i, e.i2i};  // wholly past r2
    count = 1;
  } else {
    Clipped lower{i2, pr.h2, e.r, e.i2i};
    Clipped upper{i1, pr.h1, e.r2i, e.i};
    if (span > k_clip_span_epsilon) {
      if (s2 < Q32::zero()) {
        lower.p = nm::lerp(i2, i1, nm::fraction(nm::sub(Q32::zero(), s2), span));
        lower.s = nm::dot(nm::sub(lower.p, r1), n);
      }
      if (s1 > upper1) {
        upper.p = nm::lerp(i2, i1, nm::fraction(nm::sub(upper1, s2), span));
        upper.s = nm::dot(nm::sub(upper.p, r1), n);
      }
    }
    pts[0] = lower;
    pts[1] = upper;
    count = 2;
  }

  const Q32 radius = nm::add(e.ref_radius, e.inc_radius);
  m->normal = ref_is_b ? -n : n;
  for (int32_t k = 0; k < count; ++k) {
    const Clipped& c = pts[sz(k)];
    const Q32 s = c.s;
    const Vec2 mid = nm::mul_add(c.p, nm::half(nm::sub(nm::sub(e.ref_radius, e.inc_radius), s)), n);
    const uint16_t id = ref_is_b ? make_feature_id(c.inc_vertex, c.ref_vertex) : make_feature_id(c.ref_vertex, c.inc_vertex);
    add_point(m, mid, nm::sub(s, radius), id);
  }
}

}  // namespace

void clip_edges(const ClipEdges& e, bool ref_is_b, Outside outside, LocalManifold* m) {
  clip_projected(e, project(e), ref_is_b, outside, m);
}

void clip(const Core& ref, int32_t r, const Core& inc, int32_t i, bool ref_is_b, Outside outside,
          LocalManifold* m) {
  ClipEdges e;
  e.r = r;
  e.r2i = next_index(r, ref.count);
  e.i = i;
  e.i2i = next_index(i, inc.count);
  e.normal = ref.normals[sz(r)];
  e.r1 = ref.vertices[sz(e.r)];
  e.r2 = ref.vertices[sz(e.r2i)];
  e.i1 = inc.vertices[sz(e.i)];
  e.i2 = inc.vertices[sz(e.i2i)];
  e.ref_radius = ref.radius;
  e.inc_radius = inc.radius;
  clip_edges(e, ref_is_b, outside, m);
}

namespace {

/// |v|² exactly, in 2^-64 m² units (fits: components are Q32 raw values).
wide::U128 exact_length_squared(Vec2 v) {
  const uint64_t ax = detail::magnitude(v.x.raw), ay = detail::magnitude(v.y.raw);
  return wide::add(wide::mul_u64(ax, ax), wide::mul_u64(ay, ay));
}


/// Vertices of `pts` over the interior of an edge of `edges`, outside it:
/// the nearest such pair (lowest edge, then vertex, on ties).
void find_face_pair(const Core& edges, const Core& pts, bool* out_has, Q32* out_distance, int32_t* out_edge,
                    int32_t* out_vertex) {
  *out_has = false;
  for (int32_t e = 0; e < edges.count; ++e) {
    const Vec2 n = edges.normals[sz(e)];
    const Vec2 dir = left_perp(n);
    const Vec2 v1 = edges.vertices[sz(e)];
    const Q32 len = nm::dot(edges.vertices[sz(next_index(e, edges.count))] - v1, dir);
    for (int32_t j = 0; j < pts.count; ++j) {
      const Vec2 w = pts.vertices[sz(j)] - v1;
      const Q32 s = nm::dot(w, dir);
      if (s <= Q32::zero() || s >= len) continue;
      const Q32 h = nm::dot(w, n);
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

}  // namespace

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
  if (sep_a >= max_distance) return;  // early out: a separating axis of A already
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
        add_point(m, midpoint(nm::mul_add(va, a.radius, n), mul_sub(vb, b.radius, n)), distance - radius,
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

}  // namespace manifold_detail

using namespace manifold_detail;

namespace {

/// `b` by value: the callers' fresh cores are built in place and moved to
/// A's frame there (no second copy).
Manifold collide_core_pair(const Core& a, Transform xf_a, Core b, Transform xf_b) {
  transform_core_in_place(&b, nm::inv_mul_transforms(xf_a, xf_b));
  LocalManifold lm;
  collide_cores(a, b, &lm);
  return to_world(lm, xf_a, xf_b);
}

}  // namespace

// ---------------------------------------------------------------------------
// Persistent polygon pairs: re-clip last step's features
// ---------------------------------------------------------------------------

namespace manifold_detail {

bool reclip_polygons(const Polygon& a, const Transform& xf_a, const Polygon& b, const Transform& xf_b, const Manifold& previous,
                     Manifold* out) {
  // Which edges clipped last step, from the two feature ids alone (clip()
  // writes (r, i+1) and (r+1, i) with A as reference, (i+1, r) and (i, r+1)
  // with B; for polygons of 3 or more vertices the two patterns exclude each
  // other).
  if (previous.point_count != 2) return false;
  const int32_t count_a = a.count, count_b = b.count;
  if (count_a < 3 || count_b < 3 || count_a > k_max_polygon_vertices || count_b > k_max_polygon_vertices) return false;
  const int32_t a0 = previous.points[0].id >> 8, b0 = previous.points[0].id & 0xFF;
  const int32_t a1 = previous.points[1].id >> 8, b1 = previous.points[1].id & 0xFF;
  if (a0 >= count_a || a1 >= count_a || b0 >= count_b || b1 >= count_b) return false;
  bool ref_is_b;
  if (a1 == next_index(a0, count_a) && b0 == next_index(b1, count_b)) {
    ref_is_b = false;
  } else if (b1 == next_index(b0, count_b) && a0 == next_index(a1, count_a)) {
    ref_is_b = true;
  } else {
    return false;
  }

  const Transform rel = nm::inv_mul_transforms(xf_a, xf_b);  // B's frame → A's frame
  ClipEdges e;
  if (!ref_is_b) {
    e.r = a0;
    e.r2i = a1;
    e.i = b1;
    e.i2i = b0;
    e.normal = a.normals[sz(e.r)];
    e.r1 = a.vertices[sz(e.r)];
    e.r2 = a.vertices[sz(e.r2i)];
    e.i1 = nm::transform_point(rel, b.vertices[sz(e.i)]);
    e.i2 = nm::transform_point(rel, b.vertices[sz(e.i2i)]);
    e.ref_radius = a.radius;
    e.inc_radius = b.radius;
  } else {
    e.r = b0;
    e.r2i = b1;
    e.i = a1;
    e.i2i = a0;
    e.normal = nm::rotate(rel.q, b.normals[sz(e.r)]);
    e.r1 = nm::transform_point(rel, b.vertices[sz(e.r)]);
    e.r2 = nm::transform_point(rel, b.vertices[sz(e.r2i)]);
    e.i1 = a.vertices[sz(e.i)];
    e.i2 = a.vertices[sz(e.i2i)];
    e.ref_radius = b.radius;
    e.inc_radius = a.radius;
  }

  // Still facing each other: the incident edge runs against the reference
  // edge (span > 0) and turns from it by at most atan(k_reclip_sin):
  // |h1 − h2| ≤ k_reclip_sin · span, h the heights over the reference line.
  const Projected pr = project(e);
  const Q32 span = nm::sub(pr.s1, pr.s2);
  if (span <= k_clip_span_epsilon) return false;
  const Q32 h1 = pr.h1, h2 = pr.h2;
  if (abs(nm::sub(h1, h2)) > nm::mul(k_reclip_sin, span)) return false;

  // Still overlapping along the reference edge by a clear margin (not a
  // corner contact), and both clipped points inside the margin.
  LocalManifold lm;
  clip_projected(e, pr, ref_is_b, Outside::nearest_end, &lm);
  if (lm.count != 2) return false;
  const Q32 overlap = nm::sub(min(pr.s1, pr.upper1), max(pr.s2, Q32::zero()));
  const Q32 deepest = min(min(h1, h2), Q32::zero());
  if (overlap <= nm::sub(k_reclip_min_overlap, deepest * 4)) return false;
  to_world(lm, xf_a, xf_b, out);
  return true;
}

}  // namespace manifold_detail

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

}  // namespace tandem
