// collision.h — collision geometry: shapes, mass, bounds, ray and shape
// casts, distance, and contact manifolds. Integer (Q32.32) arithmetic only.
//
// Conventions (the same as Box2D v3's, which the solver design follows):
//   * Shapes are stored in their body's local frame (metres). Functions that
//     involve a pose take a Transform.
//   * A manifold's normal points from shape A to shape B, in world frame.
//   * Separation is negative when the shapes overlap (metres).
//   * Manifold points are returned with the world point midway between the
//     surfaces, and anchors relative to each body's origin (world-aligned), so
//     the solver never needs the transforms again.
//   * Feature ids identify which vertex/edge of A and of B produced a point:
//     make_feature_id(feature on A, feature on B). They stay equal from tick to
//     tick while the same features touch; the solver warm-starts on them.
//   * A speculative margin (k_speculative_distance) makes manifolds report
//     points that are about to touch (positive separation up to the margin).
//
// Degenerate input is rejected when a shape is made (make_polygon,
// compute_hull, validate_*), never inside a step.
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "fixed/fixed.h"
#include "fixed/vec2.h"
#include "physics/status.h"

namespace tandem {

using namespace tandem::literals;

// ---------------------------------------------------------------------------
// Tolerances (metres). Chosen for a world in metres with objects 0.1–10 m.
// ---------------------------------------------------------------------------

/// The collision and constraint tolerance: 0.005 m.
inline constexpr Q32 k_linear_slop = 0.005_q32;
/// Contacts are created this far before shapes touch: 4 × slop = 0.02 m.
inline constexpr Q32 k_speculative_distance = 0.02_q32;
/// Skin used by polygon radius and GJK termination: 0.0001 m.
inline constexpr Q32 k_geometry_epsilon = 0.0001_q32;
/// Most vertices in a convex polygon.
inline constexpr int k_max_polygon_vertices = 8;
/// Smallest polygon area accepted by the builders (m²).
inline constexpr Q32 k_min_polygon_area = 0.000001_q32;
/// Points closer than this are welded by compute_hull (metres).
inline constexpr Q32 k_weld_tolerance = 0.0005_q32;
/// Most input points compute_hull accepts (interior and duplicate points
/// included); the hull itself may have at most k_max_polygon_vertices.
inline constexpr int k_max_hull_input_points = 64;
/// validate_polygon: largest accepted difference of each normal component
/// from the exact unit normal of its edge (2^-18 ≈ 3.8e-6, dimensionless).
inline constexpr Q32 k_polygon_normal_tolerance = Q32::from_raw(int64_t{1} << 14);
/// validate_polygon: largest accepted difference of each centroid coordinate
/// from the vertices' centroid (2^-20 m ≈ 9.5e-7 m).
inline constexpr Q32 k_polygon_centroid_tolerance = Q32::from_raw(int64_t{1} << 12);
/// Support-point steps of one shape_distance (GJK) call.
inline constexpr int32_t k_max_gjk_iterations = 20;
/// Conservative-advancement steps of one shape_cast call.
inline constexpr int32_t k_max_cast_iterations = 20;
/// Conservative-advancement steps of one time_of_impact call.
inline constexpr int32_t k_max_toi_iterations = 50;
/// time_of_impact's cap on the angular-speed bound of a sweep's rotation
/// (rad per sweep); reached only for turns above ~175° per sweep.
inline constexpr Q32 k_max_nlerp_rate = 50_q32;

// ---------------------------------------------------------------------------
// Shapes
// ---------------------------------------------------------------------------

/// A solid circle.
struct Circle {
  Vec2 center;  ///< local position, m
  Q32 radius;   ///< m, > 0
};

/// A solid capsule: the segment center1–center2 swept by a radius.
struct Capsule {
  Vec2 center1;  ///< local, m
  Vec2 center2;  ///< local, m; distinct from center1
  Q32 radius;    ///< m, > 0
};

/// A solid convex polygon, counter-clockwise, optionally rounded by `radius`.
/// Made only by make_polygon / make_box* (which check it).
struct Polygon {
  std::array<Vec2, k_max_polygon_vertices> vertices{};  ///< local, m, CCW
  std::array<Vec2, k_max_polygon_vertices> normals{};   ///< unit outward edge normals; normal i is edge i→i+1
  Vec2 centroid;                                        ///< local, m
  Q32 radius;                                           ///< rounding radius, m, ≥ 0
  int32_t count = 0;                                    ///< 3…k_max_polygon_vertices
};

/// A line segment, two-sided, no thickness (usually static geometry).
struct Segment {
  Vec2 point1;  ///< local, m
  Vec2 point2;  ///< local, m
};

/// One segment of a chain: one-sided, with the outward normal
/// right_perp(point2 − point1) (as in Box2D: the solid is on the LEFT of
/// point1→point2, collision on the right), with the neighbouring vertices
/// (ghosts) so that a body sliding across an inner vertex does not catch.
struct ChainSegment {
  Vec2 ghost1;      ///< the previous chain vertex, local, m
  Segment segment;  ///< this edge
  Vec2 ghost2;      ///< the next chain vertex, local, m
  int32_t chain_id = -1;
};

/// The kinds of shape, in the order used by the manifold dispatch table.
enum class ShapeType : int32_t { circle = 0, capsule, segment, polygon, chain_segment, count };

/// Deprecated alias, kept for one release: geometry builders return the
/// API's one error type, Status (StatusCode::invalid_argument when refused).
using GeometryStatus [[deprecated("use Status")]] = Status;

// ---------------------------------------------------------------------------
// Builders (reject degenerate input with a message)
// ---------------------------------------------------------------------------

/// A convex hull of up to k_max_polygon_vertices points, CCW.
struct Hull {
  std::array<Vec2, k_max_polygon_vertices> points{};
  int32_t count = 0;
};

/// Computes the convex hull of a point cloud (3 … k_max_hull_input_points
/// points, coordinates within ±k_max_shape_size): welds points closer than
/// k_weld_tolerance, drops (near-)collinear points — those within
/// k_linear_slop of the line through their hull neighbours — and rejects
/// degenerate input — too few distinct points, all collinear, too small an
/// area, more than k_max_polygon_vertices hull vertices — with a message.
/// Deterministic: the same points in any order give the same hull bits,
/// counter-clockwise from the lowest-then-leftmost point. On error *out_hull
/// is empty (count 0).
Status compute_hull(const Vec2* points, int32_t count, Hull* out_hull);

/// Builds the one-sided segments of a chain from its vertices (local, m).
/// Open chain (loop = false): points[0] and points[count−1] are ghost
/// vertices only, so count ≥ 4 gives count − 3 segments (as Box2D v3); a body
/// sliding off either end meets no invisible wall. Loop: count ≥ 3 gives
/// count segments, the last joining points[count−1] to points[0]. Solid side:
/// for a counter-clockwise loop, the inside; collisions happen on the right of
/// each segment's direction. Rejects (with a message naming the vertex)
/// too few points, and consecutive vertices closer than k_linear_slop.
/// Writes at most `capacity` segments to out_segments and the count to
/// *out_count; the chain_id of each segment is set to `chain_id`.
Status make_chain_segments(const Vec2* points, int32_t count, bool loop, int32_t chain_id,
                                   ChainSegment* out_segments, int32_t capacity, int32_t* out_count);

/// Makes a polygon from a hull with an optional rounding radius (≥ 0):
/// checks the hull (3…8 vertices, strictly convex, CCW, in range, area) and
/// computes the unit normals and the area centroid (within 1 raw unit). On
/// error *out_polygon is empty (count 0).
Status make_polygon(const Hull& hull, Q32 radius, Polygon* out_polygon);

/// Makes a polygon from a point cloud: compute_hull then make_polygon.
Status make_polygon_from_points(const Vec2* points, int32_t count, Q32 radius, Polygon* out_polygon);

/// An axis-aligned box centred on the origin (half widths within
/// [k_min_shape_size, k_max_shape_size], m). Exact: vertices ±half extents
/// CCW from (−hw, −hh), axis normals, centroid 0.
Status make_box(Q32 half_width, Q32 half_height, Polygon* out_polygon);
/// A box centred at `center`, rotated by `angle` radians, with a rounding
/// radius (≥ 0).
Status make_offset_box(Q32 half_width, Q32 half_height, Vec2 center, Q32 angle, Q32 radius,
                               Polygon* out_polygon);

/// Checks a circle (radius within [k_min_shape_size, k_max_shape_size],
/// centre ± radius within ±k_max_shape_size).
Status validate_circle(const Circle& circle);
/// Checks a capsule (radius as for a circle, centres in range and at least
/// k_linear_slop apart).
Status validate_capsule(const Capsule& capsule);
/// Checks a segment (end points at least k_linear_slop apart).
Status validate_segment(const Segment& segment);
/// Checks a polygon made by hand: count in range, strictly convex, CCW,
/// coordinates in range, area ≥ k_min_polygon_area, radius in [0,
/// k_max_shape_size], each normal within k_polygon_normal_tolerance of its
/// edge's unit outward normal, centroid within k_polygon_centroid_tolerance.
Status validate_polygon(const Polygon& polygon);

// ---------------------------------------------------------------------------
// Mass and bounds
// ---------------------------------------------------------------------------

/// Mass properties of a solid shape.
struct MassData {
  Q32 mass;                ///< kg
  Vec2 center;             ///< centre of mass, local, m
  Q32 rotational_inertia;  ///< about the centre of mass, kg·m²
};

/// Mass data of one body as a compact rollback buffer carries it beside its
/// image (replay/rollback.h; not hashed): fixed between shape changes.
struct RollbackBodyMass {
  Q32 mass;                ///< kg
  Q32 rotational_inertia;  ///< kg·m²
  Q32 inv_mass;            ///< 1/kg (0 for static and kinematic bodies)
  Q32 inv_inertia;         ///< 1/(kg·m²)
  Vec2 local_center;       ///< centre of mass, local, m
  Q32 min_extent;          ///< m
  Q32 max_extent;          ///< m
};

/// Mass of a circle with density in kg/m²: m = ρπr², I = m·r²/2 (a few raw
/// units of rounding). Saturates (fault) when ρπr⁴/2 leaves the range.
MassData compute_circle_mass(const Circle& circle, Q32 density);
/// Mass of a capsule with density in kg/m²: exact closed form (rectangle
/// plus two half discs), inertia about the centre of mass.
MassData compute_capsule_mass(const Capsule& capsule, Q32 density);
/// Mass of a (rounded) polygon with density in kg/m²: exact, the rounded
/// polygon being the core plus edge rectangles plus vertex sectors (not
/// Box2D's pushed-out-vertices approximation). Inertia about the centre of
/// mass; saturates (fault) around ρ·s⁴ ≈ 2.5·10^10 for diameter s.
MassData compute_polygon_mass(const Polygon& polygon, Q32 density);

/// World bounds of each shape under a transform.
AABB compute_circle_aabb(const Circle& circle, Transform xf);
AABB compute_capsule_aabb(const Capsule& capsule, Transform xf);
AABB compute_polygon_aabb(const Polygon& polygon, Transform xf);
AABB compute_segment_aabb(const Segment& segment, Transform xf);
AABB compute_chain_segment_aabb(const ChainSegment& segment, Transform xf);

// ---------------------------------------------------------------------------
// Single-shape queries (shape's local frame)
// ---------------------------------------------------------------------------

/// A ray from origin along translation, hitting at most at max_fraction (in
/// [0, 1]) of the translation.
struct RayCastInput {
  Vec2 origin;        ///< m
  Vec2 translation;   ///< m
  Q32 max_fraction = Q32::one();
};

/// The result of a ray or shape cast.
struct CastOutput {
  Vec2 normal;        ///< unit surface normal at the hit
  Vec2 point;         ///< hit point, m
  Q32 fraction;       ///< of the translation, in [0, max_fraction]
  int32_t iterations = 0;
  bool hit = false;
};

/// True when the local point lies inside or on the shape.
bool point_in_circle(Vec2 point, const Circle& circle);
bool point_in_capsule(Vec2 point, const Capsule& capsule);
bool point_in_polygon(Vec2 point, const Polygon& polygon);

/// Ray casts in the shape's local frame. A ray starting inside or on a solid
/// shape does not hit it (as in Box2D). max_fraction is clamped to [0, 1].
/// Segments are two-sided; chain segments (one_sided) are hit only by rays
/// starting on the right of point1→point2 (the side their normal
/// right_perp(point2 − point1) points to). Exact for rounded polygons.
CastOutput ray_cast_circle(const RayCastInput& input, const Circle& circle);
CastOutput ray_cast_capsule(const RayCastInput& input, const Capsule& capsule);
CastOutput ray_cast_polygon(const RayCastInput& input, const Polygon& polygon);
CastOutput ray_cast_segment(const RayCastInput& input, const Segment& segment, bool one_sided);

// ---------------------------------------------------------------------------
// Distance (GJK) and shape cast (time of impact)
// ---------------------------------------------------------------------------

/// A convex point set with a radius: the common form every shape reduces to
/// for GJK (circle: 1 point; capsule and segment: 2; polygon: its vertices).
struct ShapeProxy {
  std::array<Vec2, k_max_polygon_vertices> points{};
  int32_t count = 0;
  Q32 radius;
};

/// Makes a proxy from points and a radius. count is clamped to
/// k_max_polygon_vertices; a null or empty list gives one point at the origin.
ShapeProxy make_proxy(const Vec2* points, int32_t count, Q32 radius);
ShapeProxy make_proxy(const Circle& circle);
ShapeProxy make_proxy(const Capsule& capsule);
ShapeProxy make_proxy(const Polygon& polygon);
ShapeProxy make_proxy(const Segment& segment);

/// Input to shape_distance: two proxies in their own frames with transforms.
struct DistanceInput {
  ShapeProxy proxy_a;
  ShapeProxy proxy_b;
  Transform transform_a;
  Transform transform_b;
  bool use_radii = true;  ///< subtract the radii from the core distance
};

/// Closest points and distance (0 when overlapping).
struct DistanceOutput {
  Vec2 point_a;     ///< closest point on A, world, m
  Vec2 point_b;     ///< closest point on B, world, m
  Vec2 normal;      ///< unit, from A to B (zero if overlapping cores)
  Q32 distance;     ///< m, ≥ 0
  int32_t iterations = 0;
  int32_t simplex_count = 0;
};

/// GJK distance between two convex shapes, with witness points. Starts from
/// an empty simplex every call (no cache), so results depend only on input;
/// at most k_max_gjk_iterations support steps (the result is then the
/// closest point of the last simplex, an upper bound). Works in A's frame;
/// the shapes' extents plus separation must stay below ~30,000 m.
/// With use_radii and overlapping rounded surfaces (but separate cores) the
/// distance is 0 and the points stay on the two surfaces; with touching
/// cores both points are the midpoint and the normal is zero.
DistanceOutput shape_distance(const DistanceInput& input);

/// Input to shape_cast: proxy B moves by translation_b relative to fixed A
/// (both in world frame via their transforms).
struct ShapeCastInput {
  ShapeProxy proxy_a;
  ShapeProxy proxy_b;
  Transform transform_a;
  Transform transform_b;
  Vec2 translation_b;             ///< m
  Q32 max_fraction = Q32::one();
  bool can_encroach = false;      ///< allow the shapes to end closer than linear slop
};

/// Linear shape cast: the first fraction of translation_b at which B touches
/// A (conservative advancement on GJK, ≤ k_max_cast_iterations). "Touches"
/// means the core distance reaches max(linear slop, rA + rB − linear slop)
/// within slop/4 (Box2D's target). normal is the unit normal from A to B,
/// point lies on A's surface. Starting that close gives a hit at fraction 0
/// (unless can_encroach). No hit when moving apart, beyond max_fraction, or
/// when the iterations run out.
CastOutput shape_cast(const ShapeCastInput& input);

/// A body's motion over a step for time of impact: the centre of mass moves
/// linearly from c1 to c2 and the angle from a1 to a2 (radians).
struct Sweep {
  Vec2 local_center;  ///< centre of mass in the body frame, m
  Vec2 c1, c2;        ///< world centre of mass at t = 0 and t = 1, m
  Rot q1, q2;         ///< rotation at t = 0 and t = 1
};

/// The transform of a sweep at time t in [0, 1] (rotation interpolated and
/// normalised).
Transform sweep_transform(const Sweep& sweep, Q32 t);

/// Result of time_of_impact.
enum class ToiState : int32_t { unknown, failed, overlapped, hit, separated };

/// Input to time_of_impact.
struct ToiInput {
  ShapeProxy proxy_a;
  ShapeProxy proxy_b;
  Sweep sweep_a;
  Sweep sweep_b;
  Q32 max_fraction = Q32::one();  ///< of the sweep interval
};

/// Output of time_of_impact.
struct ToiOutput {
  ToiState state = ToiState::unknown;
  Q32 fraction;  ///< in [0, max_fraction]
  int32_t iterations = 0;  ///< conservative-advancement steps taken (GJK calls)
};

/// Time of impact of two moving (translating and rotating) convex shapes:
/// the first time the core distance comes within slop/4 of max(linear slop,
/// rA + rB − linear slop), by conservative advancement (≤
/// k_max_toi_iterations). hit: fraction is that time; overlapped: the cores
/// overlap at fraction; separated: no contact before max_fraction (fraction =
/// max_fraction); failed: iterations ran out, fraction is a time before the
/// contact.
ToiOutput time_of_impact(const ToiInput& input);

/// time_of_impact stopping at a given core distance `target` (m, > 0)
/// instead of max(linear slop, rA + rB − linear slop), with a tolerance of
/// min(linear slop, target)/4. continuous.cpp uses it to stop a shape's
/// centroid core halfway to an obstacle it already lies within the default
/// target of.
ToiOutput time_of_impact_to(const ToiInput& input, Q32 target);

// ---------------------------------------------------------------------------
// Contact manifolds
// ---------------------------------------------------------------------------

/// Packs two feature indices (each 0…255) into one feature id.
constexpr uint16_t make_feature_id(int a, int b) {
  return static_cast<uint16_t>(((static_cast<unsigned>(a) & 0xFFu) << 8) | (static_cast<unsigned>(b) & 0xFFu));
}

/// One contact point.
struct ManifoldPoint {
  Vec2 point;        ///< world, midway between the surfaces, m
  Vec2 anchor_a;     ///< point relative to body A's origin, world-aligned, m
  Vec2 anchor_b;     ///< point relative to body B's origin, world-aligned, m
  Q32 separation;    ///< m; negative when overlapping
  uint16_t id = 0;   ///< feature id, stable while the same features touch
};

/// Up to two contact points sharing one normal.
struct Manifold {
  Vec2 normal;                           ///< unit, world, from A to B
  std::array<ManifoldPoint, 2> points{};
  int32_t point_count = 0;
};

/// Manifold functions: shape A with transform xf_a against shape B with xf_b.
/// Points are reported while separation < k_speculative_distance.
Manifold collide_circles(const Circle& a, Transform xf_a, const Circle& b, Transform xf_b);
Manifold collide_capsule_and_circle(const Capsule& a, Transform xf_a, const Circle& b, Transform xf_b);
Manifold collide_capsules(const Capsule& a, Transform xf_a, const Capsule& b, Transform xf_b);
Manifold collide_polygon_and_circle(const Polygon& a, Transform xf_a, const Circle& b, Transform xf_b);
Manifold collide_polygon_and_capsule(const Polygon& a, Transform xf_a, const Capsule& b, Transform xf_b);
Manifold collide_polygons(const Polygon& a, Transform xf_a, const Polygon& b, Transform xf_b);
Manifold collide_segment_and_circle(const Segment& a, Transform xf_a, const Circle& b, Transform xf_b);
Manifold collide_segment_and_capsule(const Segment& a, Transform xf_a, const Capsule& b, Transform xf_b);
Manifold collide_segment_and_polygon(const Segment& a, Transform xf_a, const Polygon& b, Transform xf_b);
Manifold collide_chain_segment_and_circle(const ChainSegment& a, Transform xf_a, const Circle& b, Transform xf_b);
Manifold collide_chain_segment_and_capsule(const ChainSegment& a, Transform xf_a, const Capsule& b, Transform xf_b);
Manifold collide_chain_segment_and_polygon(const ChainSegment& a, Transform xf_a, const Polygon& b, Transform xf_b);

/// Any shape, as a tagged value, for dispatch and tests.
struct ShapeGeometry {
  ShapeType type = ShapeType::circle;
  Circle circle;
  Capsule capsule;
  Segment segment;
  Polygon polygon;
  ChainSegment chain_segment;
};

/// The manifold seen from the other shape: normal negated, anchors swapped,
/// and the two halves of each feature id swapped. Exact; flipping twice gives
/// the manifold back.
Manifold flip_manifold(const Manifold& m);

/// Dispatches to the manifold function for the pair. When the pair's table
/// entry is stored the other way round (e.g. circle vs polygon), the shapes
/// are swapped, collided, and the result flipped (normal negated, anchors and
/// feature ids swapped), so collide(A, B) and collide(B, A) agree. Segment
/// and chain segments against each other give an empty manifold (static
/// geometry does not collide with static geometry).
Manifold collide(const ShapeGeometry& a, Transform xf_a, const ShapeGeometry& b, Transform xf_b);

/// As collide(), for a pair that already touched with manifold `previous`
/// (the contact's manifold from the last update, in the canonical state):
/// two polygons whose previous manifold clipped one edge against another
/// re-clip those two edges at the new poses while they still face each other
/// (manifold_internal.h states the thresholds), skipping the separating-axis
/// search; anything else is collide(). Depends only on `previous`'s point
/// count and feature ids and the current poses, so a restored world decides
/// the same way.
Manifold collide_persistent(const ShapeGeometry& a, Transform xf_a, const ShapeGeometry& b, Transform xf_b,
                            const Manifold& previous);
/// The same, written to *out (which must not alias `previous`): the normal,
/// the point count and the points in use; points past the count keep what
/// *out held (update_contacts passes a zeroed slot, so the bits equal the
/// by-value form's).
void collide_persistent(const ShapeGeometry& a, Transform xf_a, const ShapeGeometry& b, Transform xf_b,
                        const Manifold& previous, Manifold* out);

}  // namespace tandem
