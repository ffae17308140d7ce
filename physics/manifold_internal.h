// manifold_internal.h — what the narrow-phase files share (internal):
// local manifolds in shape A's frame, cores (polygons, capsules and segments
// as convex point sets with normals), clipping and the core collider.
//
// Files (manifold.cpp has the design notes):
//   manifold.cpp        dispatch, round shapes (circles, capsule/segment–circle,
//                       polygon–circle), local → world
//   manifold_cores.cpp  cores: SAT, clipping, closest features, polygon and
//                       capsule pairs, and the re-clip of a persistent contact
//   manifold_chain.cpp  chain segments (one-sided, smooth collision)
//
// Range (why narrow_math.h's wrapping, unsaturated operations are exact
// here). Every body-local coordinate of a shape, radius included, lies
// within ±k_max_shape_size = 1e4 m (hull.cpp checks it), and body positions
// within ±k_max_world_coordinate = 1e6 m. In A's frame every point of either
// shape is therefore within 2·1e6 + 2·1e4 < 2^21 m of the origin: raw values
// below 2^53. Every product formed here is a coordinate (< 2^53 raw) times a
// unit or near-unit direction or rotation component (< 2^33 raw), or two
// unit components: below 2^86, so the 128-bit sum of two never wraps, and
// every rounded result is a coordinate or a projection on a unit axis, below
// 2^21·√2 m — inside Q32.32's ±2^31; a sum or difference of two coordinates
// is below 2^22 m. Nothing overflows, so the 64-bit adds need no saturation
// test and the products no range test (outside the limits they wrap, the same
// way in every build: narrow_math.h). Clipping fractions n/d have 0 ≤ n ≤ d,
// so their quotient fits 33 bits and one 128÷64 division does it
// (narrow_math::fraction). Squared distances are the one exception: they use
// wide.h's exact 128-bit squares, as before.
#pragma once

#include <array>
#include <cstdint>

#include "fixed/vec2.h"
#include "fixed/wide.h"
#include "physics/collision.h"
#include "physics/narrow_math.h"

namespace tandem::manifold_detail {

namespace nm = narrow_math;

/// Points are reported while separation < this (m).
inline constexpr Q32 k_margin = k_speculative_distance;
/// B's face must beat A's by more than this to become the reference (m).
inline constexpr Q32 k_flip_tolerance = Q32::from_raw(k_linear_slop.raw / 10);
/// Incident edges whose extent along the reference tangent is below this are
/// not clipped (m, 2^-20 ≈ 9.5e-7): the division would amplify rounding.
inline constexpr Q32 k_clip_span_epsilon = Q32::from_raw(int64_t{1} << 12);
/// Vertex–vertex pairs closer than this are handled by face clipping (m).
inline constexpr Q32 k_vertex_pair_epsilon = Q32::from_raw(int64_t{1} << 12);

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
inline void add_point(LocalManifold* m, Vec2 point, Q32 separation, uint16_t id) {
  if (separation >= k_margin || m->count >= 2) return;
  m->points[static_cast<size_t>(m->count)] = {point, separation, id};
  ++m->count;
}

/// (a + b)/2 without overflow of the sum; each component rounded once.
inline Vec2 midpoint(Vec2 a, Vec2 b) { return {a.x + nm::half(b.x - a.x), a.y + nm::half(b.y - a.y)}; }

/// v/|v|; false for the zero vector (normalize is scale-free, so any other
/// vector gives a direction accurate to about a raw unit).
inline bool unit_vector(Vec2 v, Vec2* out) {
  if (v.x.raw == 0 && v.y.raw == 0) return false;
  *out = normalize(v);
  return true;
}

/// Local manifold → world manifold (manifold.cpp).
Manifold to_world(const LocalManifold& lm, Transform xf_a, Transform xf_b);

/// The same into *out: the normal, the count and points [0, count) only
/// (the caller's slot keeps its other bytes). Needs lm.count > 0.
inline void to_world(const LocalManifold& lm, Transform xf_a, Transform xf_b, Manifold* out) {
  out->normal = nm::rotate(xf_a.q, lm.normal);
  const Vec2 pab = nm::sub(xf_a.p, xf_b.p);
  for (int32_t i = 0; i < lm.count; ++i) {
    const LocalPoint& lp = lm.points[static_cast<size_t>(i)];
    ManifoldPoint& mp = out->points[static_cast<size_t>(i)];
    mp.anchor_a = nm::rotate(xf_a.q, lp.point);
    mp.anchor_b = nm::add(mp.anchor_a, pab);
    mp.point = nm::add(xf_a.p, mp.anchor_a);
    mp.separation = lp.separation;
    mp.id = lp.id;
  }
  out->point_count = lm.count;
}

/// Two rounded points (manifold.cpp).
void collide_points(Vec2 pa, Q32 ra, Vec2 pb, Q32 rb, Vec2 fallback, LocalManifold* m);
/// A rounded segment against a rounded point (manifold.cpp).
void collide_segment_point(Vec2 p1, Vec2 p2, Q32 ra, Vec2 c, Q32 rb, Vec2 fallback, LocalManifold* m);

// ---------------------------------------------------------------------------
// Cores (manifold_cores.cpp)
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

Core core_from_polygon(const Polygon& p);
/// A segment or capsule as a 2-gon: edge 0 is p1→p2 with normal
/// right_perp(p2 − p1), edge 1 the way back.
Core core_from_segment(Vec2 p1, Vec2 p2, Q32 radius);
/// The core moved by xf (B's frame → A's frame).
Core transform_core(const Core& c, Transform xf);
/// The same, moving *c itself.
void transform_core_in_place(Core* c, Transform xf);
/// Smallest signed distance of `other`'s vertices along `axis` from `origin`;
/// stops at the first vertex that brings it to `stop_at` or below (the
/// result is then ≤ stop_at, not the minimum). The differences are exact
/// narrow_math subtractions (coordinates below 2^53 raw, see above). Inline:
/// the SAT calls it once per edge.
inline Q32 min_along(Vec2 axis, Vec2 origin, const Core& other, Q32 stop_at = Q32::min()) {
  Q32 s = Q32::max();
  for (int32_t j = 0; j < other.count; ++j) {
    s = min(s, nm::dot(axis, nm::sub(other.vertices[sz(j)], origin)));
    if (s <= stop_at) break;
  }
  return s;
}
/// The SAT over c1's edge normals (lowest index wins ties).
Q32 max_separation(const Core& c1, const Core& c2, int32_t* out_edge);
/// For a 2-gon: the separation along its own direction (the end caps).
Q32 cap_separation(const Core& seg, const Core& other);
/// Of the two edges of `inc` meeting at `vertex`, the one more anti-parallel
/// to `normal` (the one starting at the vertex on ties).
int32_t incident_edge_at_vertex(const Core& inc, int32_t vertex, Vec2 normal);

/// What clip() does when the incident edge lies wholly outside the reference
/// edge's side planes.
enum class Outside {
  nearest_end,  // one point at the incident edge's nearest end (overlapping cores)
  nothing,      // no points (chain segments: that region belongs to a neighbour)
};

/// A reference edge r1→r2 (vertex indices r, r2i; outward unit normal) and
/// an incident edge i1→i2 (indices i, i2i), all in A's frame, with the two
/// cores' rounding radii.
struct ClipEdges {
  Vec2 normal;
  Vec2 r1, r2, i1, i2;
  Q32 ref_radius, inc_radius;
  int32_t r = 0, r2i = 0, i = 0, i2i = 0;
};
/// Clips the incident edge against the reference edge's side planes and adds
/// the points (see clip).
void clip_edges(const ClipEdges& e, bool ref_is_b, Outside outside, LocalManifold* m);

/// Clips incident edge `i` of `inc` against the side planes of reference edge
/// `r` of `ref` (both cores in A's frame) and adds the points. `ref_is_b`:
/// the reference belongs to shape B (normal and ids are flipped to A→B).
void clip(const Core& ref, int32_t r, const Core& inc, int32_t i, bool ref_is_b, Outside outside, LocalManifold* m);

/// Re-clip of a persistent polygon pair (the reuse across steps): the
/// largest |tan| of the angle between the reference edge and the reversed
/// incident edge (dimensionless; atan 0.05 ≈ 2.9°), and the smallest
/// overlap of the two edges along the reference edge (m), to which four
/// times the deepest penetration is added.
inline constexpr Q32 k_reclip_sin = 0.05_q32;
inline constexpr Q32 k_reclip_min_overlap = Q32::from_raw(k_linear_slop.raw * 2);

/// Two polygons that touched last step with `previous` (their manifold then):
/// when its two points came from clipping one reference edge against one
/// incident edge (decoded from the feature ids) and those edges still face
/// each other (within atan k_reclip_sin of anti-parallel), still overlap along the
/// reference edge (by more than k_reclip_min_overlap plus four times the
/// penetration) and still give two points inside the margin, writes the
/// re-clipped manifold to *out and returns true; otherwise false (the caller
/// runs the full SAT). Uses only the previous manifold's point count and ids
/// and the current poses, so a world restored from a snapshot decides the
/// same way.
bool reclip_polygons(const Polygon& a, const Transform& xf_a, const Polygon& b, const Transform& xf_b, const Manifold& previous,
                     Manifold* out);

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
ClosestFeatures find_closest_features(const Core& a, const Core& b);
/// Squared Q32 distance in 2^-64 m² units (exact).
wide::U128 square(Q32 d);

}  // namespace tandem::manifold_detail
