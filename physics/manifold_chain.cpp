// manifold_chain.cpp — chain segments (one-sided, smooth collision) against
// cores and circles (design notes in manifold.cpp).
#include <algorithm>

#include "fixed/vec2.h"
#include "fixed/wide.h"
#include "physics/collision.h"
#include "physics/manifold_internal.h"

namespace tandem {

using namespace manifold_detail;

namespace {

/// A chain vertex is convex when sin(turn angle) ≥ this; a normal more than
/// asin(this) outside the segment's cone is skipped (dimensionless).
constexpr Q32 k_chain_sin_tolerance = 0.01_q32;
/// Chain features closer than this use the SAT path (m), as in Box2D.
constexpr Q32 k_chain_distance_tolerance = Q32::from_raw(k_linear_slop.raw / 10);

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
  if (nm::dot(normal, c.edge1) <= Q32::zero()) {
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
  const Q32 d1 = nm::dot(n, c.p1 - b1);
  const Q32 d2 = nm::dot(n, c.p2 - b1);
  const Q32 own = nm::dot(c.normal1, n);
  if (d1 < d2) {
    if (nm::dot(n0, n) < own) return;
  } else {
    if (nm::dot(n2, n) < own) return;
  }
  clip(poly, ref, seg, 0, true, Outside::nothing, m);
}

/// True when core b, where it lies over the segment (clipped to the slab of
/// points whose projection on edge1 falls within [p1, p2]), reaches farther
/// behind the segment's line than in front of it: b is on the back side
/// where the two meet (ties: the front). False when no part of b lies over
/// the segment.
bool overlap_is_behind(const ChainParams& c, const Core& b) {
  const Q32 length_along = nm::dot(c.edge1, c.p2 - c.p1);
  Q32 t[k_max_polygon_vertices], d[k_max_polygon_vertices];
  for (int32_t j = 0; j < b.count; ++j) {
    const Vec2 r = b.vertices[sz(j)] - c.p1;
    t[j] = nm::dot(c.edge1, r);
    d[j] = nm::dot(c.normal1, r);
  }
  bool any = false;
  Q32 lo = Q32::max(), hi = Q32::min();
  const auto take = [&](Q32 value) {
    lo = min(lo, value);
    hi = max(hi, value);
    any = true;
  };
  for (int32_t j = 0; j < b.count; ++j) {
    if (t[j] >= Q32::zero() && t[j] <= length_along) take(d[j]);
    // Where edge j → j+1 crosses either end of the slab.
    const int32_t k = next_index(j, b.count);
    for (const Q32 end : {Q32::zero(), length_along}) {
      if ((t[j] < end && t[k] > end) || (t[j] > end && t[k] < end)) {
        const Q32 f = (end - t[j]) / (t[k] - t[j]);  // in (0, 1)
        take(d[j] + (d[k] - d[j]) * f);
      }
    }
  }
  return any && lo + hi < Q32::zero();
}

void collide_chain_core(const ChainSegment& chain, const Core& b, LocalManifold* m) {
  const ChainParams c = make_chain_params(chain);
  const Core seg = core_from_segment(c.p1, c.p2, Q32::zero());  // edge 0 normal = normal1

  // One-sided: nothing when B's centroid is behind this segment and behind
  // the convex neighbours.
  const bool behind1 = nm::dot(c.normal1, b.centroid - c.p1) < Q32::zero();
  const bool behind0 = !c.convex1 || nm::dot(c.normal0, b.centroid - c.p1) < Q32::zero();
  const bool behind2 = !c.convex2 || nm::dot(c.normal2, b.centroid - c.p2) < Q32::zero();
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
        // A polygon vertex over the segment: only from the front (a vertex
        // over the back is one of a large B whose centroid is in front).
        if (nm::dot(c.normal1, b.vertices[sz(f.a_face_vertex)] - c.p1) < Q32::zero()) return;
        incident_vertex = f.a_face_vertex;
      }
    }
  }

  if (use_sat) {
    // One-sided, judged where B overlaps the segment rather than by B's
    // centroid: when the part of B over the segment lies mostly behind it,
    // this segment does not push B. The centroid test above is not enough
    // for a B much larger than the segment (a wall box beside a small body
    // carrying chain segments: its centroid projects in front of a tilted
    // segment while the part the segment touches is behind it), and the
    // normal1 axis then pushed B out through the segment's front by B's
    // whole depth behind the line: the chain's body sank through the box
    // (stress seeds 6, 19, 22, 44; about 20 % of stress worlds).
    if (overlap_is_behind(c, b)) return;
    // Segment normal (and convex neighbours' normals) against polygon normals.
    Q32 edge_separation = Q32::max();
    for (int32_t j = 0; j < b.count; ++j) {
      const Q32 s = nm::dot(c.normal1, b.vertices[sz(j)] - c.p1);
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
      const Q32 s = min(nm::dot(n, c.p1 - v), nm::dot(n, c.p2 - v));
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

  // The segment is the reference face. Off the SAT path (B a little apart,
  // its normal snapped to the segment's at a flat or concave end, or a
  // vertex of B over the segment), B may still lie mostly behind the
  // segment where it is over it: a wall box much larger than the segment,
  // beside a small body carrying chain segments, whose top edge runs nearly
  // along the segment's normal. Clipping that edge to the segment's slab
  // gave points hundreds of metres behind the segment (stress seed 776:
  // separations of −260 m and −760 m; the solve spun the 1 cm body to 6·10^8
  // rad/s and overflowed). As in the SAT path, such a segment does not push B.
  if (!use_sat && overlap_is_behind(c, b)) return;
  const int32_t inc = incident_edge >= 0 ? incident_edge : incident_edge_at_vertex(b, incident_vertex, c.normal1);
  clip(seg, 0, b, inc, false, Outside::nothing, m);
}

Manifold collide_chain_segment_and_core(const ChainSegment& a, Transform xf_a, const Core& b_local, Transform xf_b) {
  const Core b = transform_core(b_local, nm::inv_mul_transforms(xf_a, xf_b));
  LocalManifold lm;
  collide_chain_core(a, b, &lm);
  return to_world(lm, xf_a, xf_b);
}

}  // namespace

Manifold collide_chain_segment_and_circle(const ChainSegment& a, Transform xf_a, const Circle& b, Transform xf_b) {
  const Vec2 c = nm::transform_point(nm::inv_mul_transforms(xf_a, xf_b), b.center);
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

}  // namespace tandem
