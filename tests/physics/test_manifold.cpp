// Tests for physics/manifold.cpp: contact manifolds for every shape pair.
//
// Known answers (numbers worked out by hand in the comments), speculative
// margins, symmetry through collide(), feature-id stability, full-turn
// rotation sweeps, chains with ghost vertices, and random pairs checked
// against an independent long double oracle (exact core distance of the
// convex point sets) and against GJK (shape_distance).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "fixed/vec2.h"
#include "physics/collision.h"
#include "physics/narrow_math.h"

using namespace tandem;

namespace {

// ---------------------------------------------------------------------------
// Helpers (doubles are fine here: they only build inputs and oracles)
// ---------------------------------------------------------------------------

constexpr double k_pi_d = 3.14159265358979323846;

Q32 q(double v) { return Q32::from_raw(static_cast<int64_t>(std::llround(std::ldexp(v, 32)))); }
double dbl(Q32 v) { return v.to_double(); }
Vec2 v2(double x, double y) { return {q(x), q(y)}; }

Rot rot_deg(double degrees) {
  if (degrees == 0.0) return rot_identity();
  return rot_from_angle(q(degrees * k_pi_d / 180.0));
}
Transform pose(double x, double y, double degrees = 0.0) { return {v2(x, y), rot_deg(degrees)}; }

/// A convex CCW polygon from points (normals from normalize(); the centroid
/// is the vertex average, which lies inside: only the chain code reads it).
Polygon polygon_from(const std::vector<Vec2>& pts, Q32 radius = Q32::zero()) {
  Polygon p;
  p.count = static_cast<int32_t>(pts.size());
  Vec2 sum;
  for (size_t i = 0; i < pts.size(); ++i) {
    p.vertices[i] = pts[i];
    p.normals[i] = normalize(right_perp(pts[(i + 1) % pts.size()] - pts[i]));
    sum += pts[i];
  }
  p.centroid = {sum.x / p.count, sum.y / p.count};
  p.radius = radius;
  return p;
}

/// A box centred on its origin, vertices (−hx,−hy), (hx,−hy), (hx,hy), (−hx,hy).
Polygon box(double hx, double hy, double radius = 0) {
  return polygon_from({v2(-hx, -hy), v2(hx, -hy), v2(hx, hy), v2(-hx, hy)}, q(radius));
}

ShapeGeometry geo(const Circle& c) { ShapeGeometry g; g.type = ShapeType::circle; g.circle = c; return g; }
ShapeGeometry geo(const Capsule& c) { ShapeGeometry g; g.type = ShapeType::capsule; g.capsule = c; return g; }
ShapeGeometry geo(const Segment& s) { ShapeGeometry g; g.type = ShapeType::segment; g.segment = s; return g; }
ShapeGeometry geo(const Polygon& p) { ShapeGeometry g; g.type = ShapeType::polygon; g.polygon = p; return g; }
ShapeGeometry geo(const ChainSegment& s) {
  ShapeGeometry g;
  g.type = ShapeType::chain_segment;
  g.chain_segment = s;
  return g;
}

/// An open chain like Box2D's: the first and last points are ghosts only.
std::vector<ChainSegment> make_chain(const std::vector<Vec2>& pts) {
  std::vector<ChainSegment> segs;
  for (size_t i = 1; i + 2 < pts.size(); ++i) {
    ChainSegment s;
    s.ghost1 = pts[i - 1];
    s.segment = {pts[i], pts[i + 1]};
    s.ghost2 = pts[i + 2];
    s.chain_id = 0;
    segs.push_back(s);
  }
  return segs;
}

Q32 min_separation(const Manifold& m) {
  Q32 s = Q32::max();
  for (int32_t i = 0; i < m.point_count; ++i) s = min(s, m.points[static_cast<size_t>(i)].separation);
  return s;
}

bool identical(const Manifold& a, const Manifold& b) {
  if (a.point_count != b.point_count) return false;
  if (a.point_count == 0) return true;
  if (!(a.normal == b.normal)) return false;
  for (int32_t i = 0; i < a.point_count; ++i) {
    const ManifoldPoint& p = a.points[static_cast<size_t>(i)];
    const ManifoldPoint& r = b.points[static_cast<size_t>(i)];
    if (!(p.point == r.point && p.anchor_a == r.anchor_a && p.anchor_b == r.anchor_b && p.separation == r.separation &&
          p.id == r.id))
      return false;
  }
  return true;
}

std::vector<uint16_t> sorted_ids(const Manifold& m) {
  std::vector<uint16_t> ids;
  for (int32_t i = 0; i < m.point_count; ++i) ids.push_back(m.points[static_cast<size_t>(i)].id);
  std::sort(ids.begin(), ids.end());
  return ids;
}

/// Every manifold invariant that holds for any input: count in range, unit
/// normal, anchors consistent with the point and the transforms, all
/// separations inside the margin.
void check_invariants(const Manifold& m, Transform xf_a, Transform xf_b) {
  REQUIRE(m.point_count >= 0);
  REQUIRE(m.point_count <= 2);
  if (m.point_count == 0) return;
  const double len = std::hypot(dbl(m.normal.x), dbl(m.normal.y));
  REQUIRE(std::fabs(len - 1.0) < 1e-8);
  for (int32_t i = 0; i < m.point_count; ++i) {
    const ManifoldPoint& p = m.points[static_cast<size_t>(i)];
    REQUIRE(p.separation < k_speculative_distance);
    REQUIRE(p.point == xf_a.p + p.anchor_a);
    REQUIRE(p.anchor_b == p.anchor_a + (xf_a.p - xf_b.p));
  }
}

std::string describe(const ShapeGeometry& g, Transform xf) {
  std::ostringstream o;
  o.precision(17);
  const auto pt = [&](Vec2 v) { o << "(" << dbl(v.x) << ", " << dbl(v.y) << ")"; };
  switch (g.type) {
    case ShapeType::circle: o << "circle c "; pt(g.circle.center); o << " r " << dbl(g.circle.radius); break;
    case ShapeType::capsule:
      o << "capsule "; pt(g.capsule.center1); pt(g.capsule.center2); o << " r " << dbl(g.capsule.radius);
      break;
    case ShapeType::segment: o << "segment "; pt(g.segment.point1); pt(g.segment.point2); break;
    case ShapeType::polygon:
      o << "polygon r " << dbl(g.polygon.radius) << ":";
      for (int32_t i = 0; i < g.polygon.count; ++i) pt(g.polygon.vertices[static_cast<size_t>(i)]);
      break;
    case ShapeType::chain_segment:
      o << "chain ghost1 "; pt(g.chain_segment.ghost1); o << " seg "; pt(g.chain_segment.segment.point1);
      pt(g.chain_segment.segment.point2); o << " ghost2 "; pt(g.chain_segment.ghost2);
      break;
    case ShapeType::count: break;
  }
  o << " at "; pt(xf.p); o << " rot (" << dbl(xf.q.c) << ", " << dbl(xf.q.s) << ")";
  return o.str();
}

std::string describe(const Manifold& m) {
  std::ostringstream o;
  o.precision(17);
  o << "manifold n (" << dbl(m.normal.x) << ", " << dbl(m.normal.y) << ") count " << m.point_count;
  for (int32_t i = 0; i < m.point_count; ++i) {
    const ManifoldPoint& p = m.points[static_cast<size_t>(i)];
    o << " [(" << dbl(p.point.x) << ", " << dbl(p.point.y) << ") sep " << dbl(p.separation) << " id " << p.id << "]";
  }
  return o.str();
}

bool near(Q32 a, double b, double tol) { return std::fabs(dbl(a) - b) <= tol; }
bool near(Vec2 a, double x, double y, double tol) { return near(a.x, x, tol) && near(a.y, y, tol); }

/// Raw-integer random numbers (never std distributions), turned into Q32
/// values with integer arithmetic only, so every platform (x87, big-endian,
/// no __int128) draws the same inputs. Draw one value per statement: the
/// order in which function arguments are evaluated is unspecified, and gcc
/// and clang differ.
struct Rng {
  std::mt19937_64 gen;
  explicit Rng(uint64_t seed) : gen(seed) {}
  /// lo + (hi − lo)·k/2^24 for a 24-bit draw k (k/2^24 is the Q32 raw k·2^8).
  Q32 uniform(Q32 lo, Q32 hi) {
    const int64_t k = static_cast<int64_t>(gen() >> 40);
    return lo + (hi - lo) * Q32::from_raw(k * 256);
  }
  Q32 uniform(double lo, double hi) { return uniform(q(lo), q(hi)); }
  /// An angle in [0, 2π) radians.
  Q32 angle() { return uniform(Q32::zero(), k_two_pi); }
  int range(int lo, int hi) { return lo + static_cast<int>(gen() % static_cast<uint64_t>(hi - lo + 1)); }
};

/// len·(cos a, sin a), fixed point.
Vec2 polar(Q32 len, Q32 a) {
  const Rot r = rot_from_angle(a);
  return {len * r.c, len * r.s};
}

// ---------------------------------------------------------------------------
// Long double oracle: exact distance between the convex cores
// ---------------------------------------------------------------------------

using LD = long double;
struct P2 {
  LD x, y;
};
P2 operator-(P2 a, P2 b) { return {a.x - b.x, a.y - b.y}; }
LD dotl(P2 a, P2 b) { return a.x * b.x + a.y * b.y; }
LD crossl(P2 a, P2 b) { return a.x * b.y - a.y * b.x; }
LD ld(Q32 v) { return static_cast<LD>(v.raw) / 4294967296.0L; }

P2 world(Vec2 v, Transform xf) {
  const LD c = ld(xf.q.c), s = ld(xf.q.s);
  return {c * ld(v.x) - s * ld(v.y) + ld(xf.p.x), s * ld(v.x) + c * ld(v.y) + ld(xf.p.y)};
}

/// A shape's core as a world point set (1: point, 2: segment, ≥3: CCW polygon).
struct OracleCore {
  std::vector<P2> pts;
  LD radius = 0;
};

OracleCore oracle_core(const ShapeGeometry& g, Transform xf) {
  OracleCore o;
  switch (g.type) {
    case ShapeType::circle: o.pts = {world(g.circle.center, xf)}; o.radius = ld(g.circle.radius); break;
    case ShapeType::capsule:
      o.pts = {world(g.capsule.center1, xf), world(g.capsule.center2, xf)};
      o.radius = ld(g.capsule.radius);
      break;
    case ShapeType::segment: o.pts = {world(g.segment.point1, xf), world(g.segment.point2, xf)}; break;
    case ShapeType::chain_segment:
      o.pts = {world(g.chain_segment.segment.point1, xf), world(g.chain_segment.segment.point2, xf)};
      break;
    case ShapeType::polygon:
      for (int32_t i = 0; i < g.polygon.count; ++i) o.pts.push_back(world(g.polygon.vertices[static_cast<size_t>(i)], xf));
      o.radius = ld(g.polygon.radius);
      break;
    case ShapeType::count: break;
  }
  return o;
}

LD point_segment(P2 p, P2 a, P2 b) {
  const P2 e = b - a;
  const LD ee = dotl(e, e);
  LD t = ee > 0 ? dotl(p - a, e) / ee : 0;
  t = std::clamp(t, LD(0), LD(1));
  const P2 c{a.x + t * e.x, a.y + t * e.y};
  return std::sqrt(dotl(p - c, p - c));
}

bool segments_cross(P2 a, P2 b, P2 c, P2 d) {
  const LD d1 = crossl(b - a, c - a), d2 = crossl(b - a, d - a);
  const LD d3 = crossl(d - c, a - c), d4 = crossl(d - c, b - c);
  return ((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0));
}

bool inside(P2 p, const std::vector<P2>& poly) {
  if (poly.size() < 3) return false;
  for (size_t i = 0; i < poly.size(); ++i) {
    if (crossl(poly[(i + 1) % poly.size()] - poly[i], p - poly[i]) < 0) return false;
  }
  return true;
}

/// Distance between the cores (0 when they overlap).
LD core_distance(const OracleCore& a, const OracleCore& b) {
  const auto edges = [](const std::vector<P2>& p) {
    std::vector<std::pair<P2, P2>> e;
    if (p.size() == 1) e.push_back({p[0], p[0]});
    else if (p.size() == 2) e.push_back({p[0], p[1]});
    else for (size_t i = 0; i < p.size(); ++i) e.push_back({p[i], p[(i + 1) % p.size()]});
    return e;
  };
  if (inside(b.pts[0], a.pts) || inside(a.pts[0], b.pts)) return 0;
  const auto ea = edges(a.pts), eb = edges(b.pts);
  LD best = 1e30L;
  for (const auto& x : ea) {
    for (const auto& y : eb) {
      if (segments_cross(x.first, x.second, y.first, y.second)) return 0;
      best = std::min({best, point_segment(x.first, y.first, y.second), point_segment(x.second, y.first, y.second),
                       point_segment(y.first, x.first, x.second), point_segment(y.second, x.first, x.second)});
    }
  }
  return best;
}

// ---------------------------------------------------------------------------
// Random shapes
// ---------------------------------------------------------------------------

Polygon random_polygon(Rng& rng) {
  const int n = rng.range(3, k_max_polygon_vertices);
  // Points on an ellipse; angle gaps within 1:3 of each other keep every
  // vertex clearly convex.
  std::vector<Q32> gaps(static_cast<size_t>(n));
  Q32 total;
  for (Q32& g : gaps) {
    g = rng.uniform(1.0, 3.0);
    total += g;
  }
  const Q32 r = rng.uniform(0.05, 1.5);
  const Q32 sx = rng.uniform(0.15, 1.0);  // squash: thin polygons too
  Q32 a = rng.angle();
  std::vector<Vec2> pts;
  for (int i = 0; i < n; ++i) {
    const Vec2 p = polar(r, a);
    pts.push_back({p.x * sx, p.y});
    a += gaps[static_cast<size_t>(i)] / total * k_two_pi;
  }
  const Q32 radius = rng.range(0, 3) == 0 ? rng.uniform(0.005, 0.2) : Q32::zero();
  return polygon_from(pts, radius);
}

ShapeGeometry random_shape(Rng& rng, int kind) {
  switch (kind) {
    case 0: {
      const Q32 cx = rng.uniform(-0.3, 0.3), cy = rng.uniform(-0.3, 0.3), r = rng.uniform(0.02, 1.0);
      return geo(Circle{{cx, cy}, r});
    }
    case 1: {
      const Q32 len = rng.uniform(0.01, 1.5), ang = rng.angle();
      const Q32 cx = rng.uniform(-0.3, 0.3), cy = rng.uniform(-0.3, 0.3), r = rng.uniform(0.02, 0.5);
      return geo(Capsule{{cx, cy}, Vec2{cx, cy} + polar(len, ang), r});
    }
    case 2: {
      const Q32 len = rng.uniform(0.01, 3.0), ang = rng.angle();
      return geo(Segment{{}, polar(len, ang)});
    }
    case 3: return geo(random_polygon(rng));
    default: {
      // A chain segment with ghosts turning by up to ±100°.
      const Q32 len = rng.uniform(0.05, 3.0), ang = rng.angle();
      const Q32 t0 = rng.uniform(-1.75, 1.75), t2 = rng.uniform(-1.75, 1.75);
      const Q32 l0 = rng.uniform(0.05, 2.0), l2 = rng.uniform(0.05, 2.0);
      ChainSegment s;
      s.segment = {{}, polar(len, ang)};
      s.ghost1 = -polar(l0, ang - t0);
      s.ghost2 = s.segment.point2 + polar(l2, ang + t2);
      s.chain_id = 1;
      return geo(s);
    }
  }
}

#ifdef NDEBUG
constexpr int k_random_pairs = 100000;
#else
constexpr int k_random_pairs = 5000;
#endif

}  // namespace

// ---------------------------------------------------------------------------
// Known answers
// ---------------------------------------------------------------------------

TEST_CASE("box resting on a box: two points, normal up, ids", "[physics][manifold]") {
  // Ground 10 × 1 at the origin (top face y = 0.5, edge 2: (5,0.5)→(−5,0.5));
  // a unit box at (0, 0.99) sinks 0.01 into it. The reference face is the
  // ground's top (edge 2), the incident edge the box's bottom (edge 0,
  // (−0.5,−0.5)→(0.5,−0.5)); the points sit midway, at y = 0.495.
  const Polygon ground = box(5, 0.5);
  const Polygon b = box(0.5, 0.5);
  const Transform xa = pose(0, 0), xb = pose(0, 0.99);
  const Manifold m = collide_polygons(ground, xa, b, xb);
  check_invariants(m, xa, xb);
  REQUIRE(m.point_count == 2);
  CHECK(m.normal == Vec2{Q32::zero(), Q32::one()});
  CHECK(near(m.points[0].point, 0.5, 0.495, 1e-9));
  CHECK(near(m.points[1].point, -0.5, 0.495, 1e-9));
  CHECK(near(m.points[0].separation, -0.01, 1e-9));
  CHECK(near(m.points[1].separation, -0.01, 1e-9));
  CHECK(m.points[0].id == make_feature_id(2, 1));  // ground vertex 2 (right end of its top), box vertex 1
  CHECK(m.points[1].id == make_feature_id(3, 0));
  CHECK(near(m.points[0].anchor_a, 0.5, 0.495, 1e-9));
  CHECK(near(m.points[0].anchor_b, 0.5, 0.495 - 0.99, 1e-9));

  // Far from the origin and rotated as a whole: the same manifold, turned.
  const Transform fa{v2(123456.25, -98765.5), rot_deg(30)};
  const Transform fb = mul_transforms(fa, xb);
  const Manifold f = collide_polygons(ground, fa, b, fb);
  REQUIRE(f.point_count == 2);
  CHECK(near(f.normal, -0.5, std::sqrt(3.0) / 2, 1e-8));
  for (int i = 0; i < 2; ++i) {
    CHECK(near(f.points[static_cast<size_t>(i)].separation, -0.01, 1e-8));
    CHECK(f.points[static_cast<size_t>(i)].id == m.points[static_cast<size_t>(i)].id);
    const Vec2 expect = rotate(fa.q, m.points[static_cast<size_t>(i)].anchor_a);
    CHECK(near(f.points[static_cast<size_t>(i)].anchor_a, dbl(expect.x), dbl(expect.y), 1e-8));
  }
}

TEST_CASE("tiny shapes far from the origin keep full precision", "[physics][manifold]") {
  // 5 mm boxes (the smallest shape size) 10⁶ m from the origin, the pair
  // turned by 30°: a 0.1 mm overlap and a 0.1 mm gap are both resolved to
  // ~1e-9 m, because everything is solved relative to A.
  const Polygon a = box(0.0025, 0.0025);
  const Polygon b = box(0.0025, 0.0025);
  const Transform xa{v2(999999.5, -999999.25), rot_deg(30)};
  for (const double gap : {-0.0001, 0.0001}) {
    const Transform xb = mul_transforms(xa, pose(0.001, 0.005 + gap));
    const Manifold m = collide_polygons(a, xa, b, xb);
    check_invariants(m, xa, xb);
    REQUIRE(m.point_count == 2);
    CHECK(near(m.normal, -0.5, std::sqrt(3.0) / 2, 1e-8));
    CHECK(near(m.points[0].separation, gap, 1e-9));
    CHECK(near(m.points[1].separation, gap, 1e-9));
    CHECK(sorted_ids(m) == std::vector<uint16_t>{make_feature_id(2, 1), make_feature_id(3, 0)});
  }
  // Circles of 5 mm radius 1e-7 m apart along (0.6, 0.8).
  const Circle c{v2(0, 0), q(0.005)};
  const Manifold m = collide_circles(c, pose(-999999.75, 5e5), c, pose(-999999.75 + 0.00600006, 5e5 + 0.00800008));
  REQUIRE(m.point_count == 1);
  CHECK(near(m.normal, 0.6, 0.8, 1e-7));
  CHECK(near(m.points[0].separation, 1e-7, 1e-9));
}

TEST_CASE("circles, and a circle on a segment's edge and vertex", "[physics][manifold]") {
  SECTION("circle on circle") {
    // Centres 1 apart along (0.6, 0.8), radii 0.3 + 0.71: separation −0.01.
    const Manifold m = collide_circles({v2(0, 0), q(0.3)}, pose(1, 2), {v2(0, 0), q(0.71)}, pose(1.6, 2.8));
    REQUIRE(m.point_count == 1);
    CHECK(near(m.normal, 0.6, 0.8, 1e-9));
    CHECK(near(m.points[0].separation, -0.01, 1e-9));
    // Surface points at 0.3 and 1 − 0.71 = 0.29 from A: midpoint 0.295 along the normal.
    CHECK(near(m.points[0].point, 1 + 0.295 * 0.6, 2 + 0.295 * 0.8, 1e-9));
    CHECK(m.points[0].id == 0);
  }
  SECTION("on the segment's edge") {
    // Segment (−1,0)→(1,0); circle r 0.5 at (0.3, 0.49): normal up (left of
    // the segment), separation −0.01, point midway at (0.3, −0.005).
    const Manifold m = collide_segment_and_circle({v2(-1, 0), v2(1, 0)}, pose(0, 0), {v2(0, 0), q(0.5)}, pose(0.3, 0.49));
    REQUIRE(m.point_count == 1);
    CHECK(m.normal == Vec2{Q32::zero(), Q32::one()});
    CHECK(near(m.points[0].separation, -0.01, 1e-9));
    CHECK(near(m.points[0].point, 0.3, -0.005, 1e-9));
    // Below the segment the normal points down (segments are two-sided).
    const Manifold below =
        collide_segment_and_circle({v2(-1, 0), v2(1, 0)}, pose(0, 0), {v2(0, 0), q(0.5)}, pose(0.3, -0.49));
    REQUIRE(below.point_count == 1);
    CHECK(below.normal == Vec2{Q32::zero(), -Q32::one()});
  }
  SECTION("on the segment's vertex") {
    // Circle r 0.51 at (1.3, 0.4): 0.5 from the end (1,0) along (0.6, 0.8);
    // separation −0.01; surface points (1,0) and (0.994, −0.008).
    const Manifold m = collide_segment_and_circle({v2(-1, 0), v2(1, 0)}, pose(0, 0), {v2(0, 0), q(0.51)}, pose(1.3, 0.4));
    REQUIRE(m.point_count == 1);
    CHECK(near(m.normal, 0.6, 0.8, 1e-9));
    CHECK(near(m.points[0].separation, -0.01, 1e-9));
    CHECK(near(m.points[0].point, 0.997, -0.004, 1e-9));
  }
  SECTION("polygon and circle: face, corner, centre inside") {
    const Polygon a = box(1, 0.5);
    Manifold m = collide_polygon_and_circle(a, pose(0, 0), {v2(0, 0), q(0.25)}, pose(0.2, 0.74));
    REQUIRE(m.point_count == 1);
    CHECK(m.normal == Vec2{Q32::zero(), Q32::one()});
    CHECK(near(m.points[0].separation, -0.01, 1e-9));
    CHECK(near(m.points[0].point, 0.2, 0.495, 1e-9));
    // Corner (1, 0.5); circle 0.24 away along (0.6, 0.8), radius 0.25.
    m = collide_polygon_and_circle(a, pose(0, 0), {v2(0, 0), q(0.25)}, pose(1.144, 0.692));
    REQUIRE(m.point_count == 1);
    CHECK(near(m.normal, 0.6, 0.8, 1e-9));
    CHECK(near(m.points[0].separation, -0.01, 1e-9));
    // Centre inside, nearest the top face (0.1 below it): normal up, separation −0.1 − 0.25.
    m = collide_polygon_and_circle(a, pose(0, 0), {v2(0, 0), q(0.25)}, pose(0.3, 0.4));
    REQUIRE(m.point_count == 1);
    CHECK(m.normal == Vec2{Q32::zero(), Q32::one()});
    CHECK(near(m.points[0].separation, -0.35, 1e-9));
  }
}

TEST_CASE("capsule against a polygon's edge and corner, and capsules", "[physics][manifold]") {
  const Polygon a = box(1, 0.5);
  const Capsule cap{v2(-0.5, 0), v2(0.5, 0), q(0.25)};
  SECTION("edge: two points") {
    // Capsule axis at y = 0.74, radius 0.25: bottom at 0.49, 0.01 deep.
    // Reference: the box's top (edge 2); incident: capsule edge 0
    // (centre1 → centre2, normal down). Points midway at y = 0.495.
    const Manifold m = collide_polygon_and_capsule(a, pose(0, 0), cap, pose(0, 0.74));
    REQUIRE(m.point_count == 2);
    CHECK(m.normal == Vec2{Q32::zero(), Q32::one()});
    CHECK(near(m.points[0].point, 0.5, 0.495, 1e-9));
    CHECK(near(m.points[1].point, -0.5, 0.495, 1e-9));
    CHECK(near(m.points[0].separation, -0.01, 1e-9));
    CHECK(near(m.points[1].separation, -0.01, 1e-9));
    CHECK(m.points[0].id == make_feature_id(2, 1));
    CHECK(m.points[1].id == make_feature_id(3, 0));
  }
  SECTION("corner: one point along the vertex pair") {
    // Centre1 0.24 from the corner (1, 0.5) along (0.6, 0.8); the capsule
    // points away (+x). Normal (0.6, 0.8), separation −0.01, point midway
    // between (1, 0.5) and (0.994, 0.492).
    const Manifold m = collide_polygon_and_capsule(a, pose(0, 0), {v2(0, 0), v2(1, 0), q(0.25)}, pose(1.144, 0.692));
    REQUIRE(m.point_count == 1);
    CHECK(near(m.normal, 0.6, 0.8, 1e-9));
    CHECK(near(m.points[0].separation, -0.01, 1e-9));
    CHECK(near(m.points[0].point, 0.997, 0.496, 1e-9));
    CHECK(m.points[0].id == make_feature_id(2, 0));
  }
  SECTION("capsule on capsule: parallel, crossed, end to end") {
    // Parallel, 0.49 apart with radii 0.25 + 0.25: two points, −0.01.
    Manifold m = collide_capsules(cap, pose(0, 0), cap, pose(0.3, 0.49));
    REQUIRE(m.point_count == 2);
    CHECK(m.normal == Vec2{Q32::zero(), Q32::one()});
    CHECK(near(min_separation(m), -0.01, 1e-9));
    CHECK(near(m.points[0].point, 0.5, 0.245, 1e-9));   // clipped at A's end
    CHECK(near(m.points[1].point, -0.2, 0.245, 1e-9));  // B's end
    // End on: B upright, its lower centre 0.45 above A's axis: one point, −0.05.
    m = collide_capsules(cap, pose(0, 0), cap, pose(0.1, 0.95, 90));
    REQUIRE(m.point_count == 1);
    CHECK(near(m.normal, 0, 1, 1e-9));
    CHECK(near(m.points[0].separation, -0.05, 1e-9));
    CHECK(near(m.points[0].point, 0.1, 0.225, 1e-9));
    // Crossed (cores intersect): still a contact, deeper than the radii.
    m = collide_capsules(cap, pose(0, 0), cap, pose(0.1, 0.1, 90));
    REQUIRE(m.point_count >= 1);
    CHECK(dbl(min_separation(m)) <= -0.5);
    // Collinear, end to end with a 0.01 gap between the caps: one point
    // along the axis (not a face contact: the SAT alone would say "touching").
    m = collide_capsules(cap, pose(0, 0), cap, pose(1.51, 0));
    REQUIRE(m.point_count == 1);
    CHECK(near(m.normal, 1, 0, 1e-9));
    CHECK(near(m.points[0].separation, 0.01, 1e-9));
    CHECK(m.points[0].id == make_feature_id(1, 0));
    // Collinear and far apart: nothing (the SAT over ±normals alone sees 0).
    CHECK(collide_capsules(cap, pose(0, 0), cap, pose(3, 0)).point_count == 0);
    CHECK(collide_segment_and_capsule({v2(-0.5, 0), v2(0.5, 0)}, pose(0, 0), cap, pose(3, 0)).point_count == 0);
  }
}

TEST_CASE("speculative points: inside the margin yes, beyond it no", "[physics][manifold]") {
  const Polygon ground = box(5, 0.5);
  const Polygon b = box(0.5, 0.5);
  SECTION("box on box") {
    Manifold m = collide_polygons(ground, pose(0, 0), b, pose(0.2, 1.01));  // gap 0.01 < 0.02
    REQUIRE(m.point_count == 2);
    CHECK(m.normal == Vec2{Q32::zero(), Q32::one()});
    CHECK(near(m.points[0].separation, 0.01, 1e-9));
    CHECK(near(m.points[1].separation, 0.01, 1e-9));
    CHECK(sorted_ids(m) == sorted_ids(collide_polygons(ground, pose(0, 0), b, pose(0.2, 0.99))));
    CHECK(collide_polygons(ground, pose(0, 0), b, pose(0.2, 1.03)).point_count == 0);  // gap 0.03
    CHECK(collide_polygons(ground, pose(0, 0), b, pose(0.2, 1.02)).point_count == 0);  // gap = margin
    // Tilted so one corner is 0.01 above and the other 0.1 above: one point.
    const double ang = std::asin(0.09);  // rises 0.09 over the unit width
    const double cy = 0.5 + 0.01 + 0.5 * std::cos(ang) + 0.5 * std::sin(ang);
    m = collide_polygons(ground, pose(0, 0), b, pose(0, cy, ang * 180 / k_pi_d));
    REQUIRE(m.point_count == 1);
    CHECK(near(m.points[0].separation, 0.01, 1e-6));
  }
  SECTION("circles and capsules") {
    const Circle c{v2(0, 0), q(0.5)};
    Manifold m = collide_circles(c, pose(0, 0), c, pose(1.01, 0));
    REQUIRE(m.point_count == 1);
    CHECK(near(m.points[0].separation, 0.01, 1e-9));
    CHECK(collide_circles(c, pose(0, 0), c, pose(1.03, 0)).point_count == 0);
    const Capsule cap{v2(-0.5, 0), v2(0.5, 0), q(0.25)};
    m = collide_capsules(cap, pose(0, 0), cap, pose(0.2, 0.51));
    REQUIRE(m.point_count == 2);
    CHECK(near(min_separation(m), 0.01, 1e-9));
    CHECK(collide_capsules(cap, pose(0, 0), cap, pose(0.2, 0.53)).point_count == 0);
    // Rounded polygons: the radius counts.
    const Polygon rb = box(0.4, 0.4, 0.1);
    m = collide_polygons(ground, pose(0, 0), rb, pose(0, 1.01));
    REQUIRE(m.point_count == 2);
    CHECK(near(min_separation(m), 0.01, 1e-9));
    CHECK(collide_polygons(ground, pose(0, 0), rb, pose(0, 1.03)).point_count == 0);
  }
  SECTION("rounded corner to corner") {
    // Two boxes rounded by 0.1, cores corner to corner along the diagonal,
    // core gap 0.21·√2: separation 0.21√2 − 0.2 ≈ 0.0970 (> margin: none)
    // and, closer, 0.15√2 − 0.2 ≈ 0.0121 (one point along the diagonal).
    const Polygon r = box(0.4, 0.4, 0.1);
    CHECK(collide_polygons(r, pose(0, 0), r, pose(1.01, 1.01)).point_count == 0);
    const Manifold m = collide_polygons(r, pose(0, 0), r, pose(0.95, 0.95));
    REQUIRE(m.point_count == 1);
    CHECK(near(m.normal, std::sqrt(0.5), std::sqrt(0.5), 1e-9));
    CHECK(near(m.points[0].separation, 0.15 * std::sqrt(2.0) - 0.2, 1e-9));
    CHECK(m.points[0].id == make_feature_id(2, 0));
  }
}

// ---------------------------------------------------------------------------
// Chains
// ---------------------------------------------------------------------------

namespace {

/// All manifolds of a shape against every segment of a chain at the origin.
std::vector<Manifold> collide_chain(const std::vector<ChainSegment>& chain, const ShapeGeometry& b, Transform xb) {
  std::vector<Manifold> out;
  for (const ChainSegment& s : chain) out.push_back(collide(geo(s), transform_identity(), b, xb));
  return out;
}

/// A flat chain on y = 0 from x = 4 to x = −4 (right to left, so the normal
/// right_perp(−1, 0) = (0, 1) points up), joints at x = 2, 0, −2.
std::vector<ChainSegment> flat_chain() {
  return make_chain({v2(6, 0), v2(4, 0), v2(2, 0), v2(0, 0), v2(-2, 0), v2(-4, 0), v2(-6, 0)});
}

}  // namespace

TEST_CASE("chain: box sliding across inner vertices never catches", "[physics][manifold]") {
  const auto chain = flat_chain();
  const Polygon b = box(0.5, 0.5);
  for (const double gap : {-0.01, 0.0003, 0.005}) {
    for (int step = -300; step <= 300; ++step) {
      const double x = step * 0.01;
      const Transform xb = pose(x, 0.5 + gap);
      const auto ms = collide_chain(chain, geo(b), xb);
      int points = 0;
      bool left_corner = false, right_corner = false;
      Q32 smin = Q32::max();
      for (size_t k = 0; k < ms.size(); ++k) {
        const Manifold& m = ms[k];
        check_invariants(m, transform_identity(), xb);
        if (m.point_count == 0) continue;
        INFO("gap " << gap << " x " << x << " segment " << k);
        REQUIRE(m.normal == Vec2{Q32::zero(), Q32::one()});
        const double hi = dbl(chain[k].segment.point1.x), lo = dbl(chain[k].segment.point2.x);
        for (int32_t i = 0; i < m.point_count; ++i) {
          const ManifoldPoint& p = m.points[static_cast<size_t>(i)];
          // No contact on the ghost side: every point over this segment.
          REQUIRE(dbl(p.point.x) >= lo - 1e-9);
          REQUIRE(dbl(p.point.x) <= hi + 1e-9);
          left_corner |= std::fabs(dbl(p.point.x) - (x - 0.5)) < 1e-9;
          right_corner |= std::fabs(dbl(p.point.x) - (x + 0.5)) < 1e-9;
          smin = min(smin, p.separation);
          ++points;
        }
      }
      INFO("gap " << gap << " x " << x);
      REQUIRE(points >= 2);
      CHECK(left_corner);
      CHECK(right_corner);
      CHECK(near(smin, gap, 1e-9));
    }
  }
}

TEST_CASE("chain: circle and capsule slide across a joint with the normal straight up", "[physics][manifold]") {
  const auto chain = flat_chain();
  const Circle c{v2(0, 0), q(0.5)};
  const Capsule cap{v2(-0.3, 0), v2(0.3, 0), q(0.2)};
  for (int step = -150; step <= 150; ++step) {
    const double x = step * 0.01 + 0.005;
    INFO("x " << x);
    int points = 0;
    for (const Manifold& m : collide_chain(chain, geo(c), pose(x, 0.49))) {
      if (m.point_count == 0) continue;
      REQUIRE(m.normal == Vec2{Q32::zero(), Q32::one()});
      CHECK(near(m.points[0].separation, -0.01, 1e-9));
      points += m.point_count;
    }
    CHECK(points == 1);
    points = 0;
    for (const Manifold& m : collide_chain(chain, geo(cap), pose(x, 0.195))) {
      if (m.point_count == 0) continue;
      REQUIRE(m.normal == Vec2{Q32::zero(), Q32::one()});
      CHECK(near(min_separation(m), -0.005, 1e-9));
      points += m.point_count;
    }
    CHECK(points >= 2);
  }
}

TEST_CASE("chain: one-sided, and ghost sides at convex and concave vertices", "[physics][manifold]") {
  const Polygon b = box(0.5, 0.5);
  SECTION("behind the chain: nothing") {
    const auto chain = flat_chain();
    for (const Manifold& m : collide_chain(chain, geo(b), pose(0.3, -0.49))) CHECK(m.point_count == 0);
    for (const Manifold& m : collide_chain(chain, geo(Circle{v2(0, 0), q(0.5)}), pose(0.3, -0.49)))
      CHECK(m.point_count == 0);
  }
  SECTION("convex vertex: a box on the downhill slope does not touch the flat part") {
    // Flat from x = 4 to 0, then down at 45° (a cliff edge at the origin).
    const auto chain = make_chain({v2(6, 0), v2(4, 0), v2(0, 0), v2(-4, -4), v2(-6, -6)});
    REQUIRE(chain.size() == 2);
    const double s = std::sqrt(0.5);
    // Box turned 45°, resting 0.01 deep on the slope at 1.5 m from the edge.
    const double cx = -1.5 * s - 0.49 * s, cy = -1.5 * s + 0.49 * s;
    const auto ms = collide_chain(chain, geo(b), pose(cx, cy, -45));
    CHECK(ms[0].point_count == 0);
    REQUIRE(ms[1].point_count == 2);
    CHECK(near(ms[1].normal, -s, s, 1e-9));
    CHECK(near(min_separation(ms[1]), -0.01, 1e-8));
    // Over the edge: a box whose corner hangs past the vertex keeps the
    // flat part's normal; the corner region gives normals between the two.
    for (int step = 0; step <= 40; ++step) {
      const double x = 0.5 - step * 0.02;  // box centre from 0.5 to −0.3
      for (const Manifold& m : collide_chain(chain, geo(b), pose(x, 0.49))) {
        if (m.point_count == 0) continue;
        INFO("x " << x);
        CHECK(dbl(m.normal.y) >= s - 1e-9);  // between up and the slope's normal
        CHECK(dbl(m.normal.x) <= 1e-9);
      }
    }
  }
  SECTION("concave vertex: a box in the corner gets both faces' normals only") {
    // Flat from x = 4 to 0, then up at 45° to the left (a valley at the origin).
    const auto chain = make_chain({v2(6, 0), v2(4, 0), v2(0, 0), v2(-4, 4), v2(-6, 6)});
    const double s = std::sqrt(0.5);
    for (int step = 0; step <= 40; ++step) {
      const double x = 1.0 - step * 0.02;
      for (const Manifold& m : collide_chain(chain, geo(b), pose(x, 0.49))) {
        if (m.point_count == 0) continue;
        INFO("x " << x);
        const bool up = m.normal == Vec2{Q32::zero(), Q32::one()};
        const bool slope = near(m.normal, s, s, 1e-9);
        CHECK((up || slope));
      }
    }
  }
}

// ---------------------------------------------------------------------------
// Symmetry, feature ids, rotation sweeps
// ---------------------------------------------------------------------------

TEST_CASE("collide(A, B) is flip(collide(B, A))", "[physics][manifold]") {
  const Polygon ground = box(5, 0.5);
  const Polygon b = box(0.5, 0.5);
  SECTION("same types: negated normal, same points") {
    const Manifold ab = collide(geo(ground), pose(0, 0), geo(b), pose(0.3, 0.99));
    const Manifold ba = collide(geo(b), pose(0.3, 0.99), geo(ground), pose(0, 0));
    REQUIRE(ab.point_count == 2);
    REQUIRE(ba.point_count == 2);
    CHECK(ab.normal == -ba.normal);
    for (const ManifoldPoint& p : ab.points) {
      const bool found = std::any_of(ba.points.begin(), ba.points.end(), [&](const ManifoldPoint& r) {
        return near(r.point, dbl(p.point.x), dbl(p.point.y), 1e-9) && r.separation == p.separation;
      });
      CHECK(found);
    }
    const Circle c{v2(0, 0), q(0.3)};
    const Manifold cc1 = collide(geo(c), pose(1, 1), geo(c), pose(1.3, 1.4));
    const Manifold cc2 = collide(geo(c), pose(1.3, 1.4), geo(c), pose(1, 1));
    REQUIRE(cc1.point_count == 1);
    CHECK(near(cc1.normal, -dbl(cc2.normal.x), -dbl(cc2.normal.y), 1e-9));
    CHECK(near(cc1.points[0].point, dbl(cc2.points[0].point.x), dbl(cc2.points[0].point.y), 1e-9));
  }
  SECTION("mixed types: bit for bit, random poses") {
    Rng rng(0x5eed0001);
    int compared = 0;
    for (int n = 0; n < 2000; ++n) {
      const int ka = rng.range(0, 4), kb = rng.range(0, 4);
      if (ka == kb) continue;
      const ShapeGeometry a = random_shape(rng, ka), bb = random_shape(rng, kb);
      const Q32 ax = rng.uniform(-50, 50), ay = rng.uniform(-50, 50), aa = rng.angle();
      const Q32 bx = rng.uniform(-2, 2), by = rng.uniform(-2, 2), bang = rng.angle();
      const Transform xa{{ax, ay}, rot_from_angle(aa)};
      const Transform xb{xa.p + Vec2{bx, by}, rot_from_angle(bang)};
      const Manifold ab = collide(a, xa, bb, xb);
      const Manifold ba = collide(bb, xb, a, xa);
      INFO("kinds " << ka << " " << kb);
      REQUIRE(identical(ab, flip_manifold(ba)));
      compared += ab.point_count > 0;
    }
    CHECK(compared > 200);
  }
}

TEST_CASE("feature ids are stable under small motions", "[physics][manifold]") {
  const Polygon ground = box(5, 0.5);
  const Polygon b = box(0.5, 0.5);
  const Capsule cap{v2(-0.5, 0), v2(0.5, 0), q(0.25)};
  const auto chain = flat_chain();
  struct Motion {
    double dx, dy, deg;
  };
  const std::vector<Motion> motions = {{0, 0, 0},       {0.003, 0, 0},       {-0.003, 0, 0},   {0, 0.002, 0},
                                       {0, -0.002, 0},  {0, 0, 0.1},         {0, 0, -0.1},     {0.004, 0.002, 0.1},
                                       {-0.004, -0.002, -0.1}, {0, 0.012, 0}};  // the last one: speculative
  for (const double base_y : {0.99, 1.005}) {
    const std::vector<uint16_t> box_ids = sorted_ids(collide_polygons(ground, pose(0, 0), b, pose(0.2, 0.99)));
    const std::vector<uint16_t> cap_ids = sorted_ids(collide_polygon_and_capsule(ground, pose(0, 0), cap, pose(0.2, 0.74)));
    REQUIRE(box_ids.size() == 2);
    REQUIRE(cap_ids.size() == 2);
    for (const Motion& mo : motions) {
      INFO("base " << base_y << " motion " << mo.dx << " " << mo.dy << " " << mo.deg);
      CHECK(sorted_ids(collide_polygons(ground, pose(0, 0), b, pose(0.2 + mo.dx, base_y + mo.dy, mo.deg))) == box_ids);
      CHECK(sorted_ids(collide_polygon_and_capsule(ground, pose(0, 0), cap,
                                                   pose(0.2 + mo.dx, base_y - 0.25 + mo.dy, mo.deg))) == cap_ids);
    }
  }
  // Box on the chain, over the middle of segment 1 (x from 2 to 0).
  const std::vector<uint16_t> chain_ids =
      sorted_ids(collide_chain_segment_and_polygon(chain[1], transform_identity(), b, pose(1.0, 0.49)));
  REQUIRE(chain_ids.size() == 2);
  for (const Motion& mo : motions) {
    INFO("chain motion " << mo.dx << " " << mo.dy << " " << mo.deg);
    CHECK(sorted_ids(collide_chain_segment_and_polygon(chain[1], transform_identity(), b,
                                                       pose(1.0 + mo.dx, 0.49 + mo.dy, mo.deg))) == chain_ids);
  }
}

TEST_CASE("persistent polygon pairs re-clip last step's edges, or fall back to the full search", "[physics][manifold]") {
  // collide_persistent() re-clips the two edges named by the previous
  // manifold's ids. Where the full search would pick the same edges (small
  // motions of a box resting on a wide ground, either shape the reference),
  // the result is the full search's, bit for bit; beyond the thresholds
  // (turned past atan 0.05, slid to a corner, previous manifold with one
  // point, not touching) it is collide() itself.
  const Polygon ground = box(5, 0.5);
  const Polygon b = box(0.5, 0.5);
  struct Motion {
    double dx, dy, deg;
  };
  const std::vector<Motion> small = {{0, 0, 0}, {0.003, 0, 0}, {-0.2, 0.004, 0}, {0, -0.003, 0.5},
                                     {0.1, 0.002, -1.0}, {0, 0.012, 0}, {0.3, -0.004, 1.5}};
  for (const bool box_is_a : {false, true}) {
    // Ground as A (its top face is the reference), or the box as A turned
    // by 0.5° so the ground's face is the better axis (B the reference).
    const ShapeGeometry ga = box_is_a ? geo(b) : geo(ground);
    const ShapeGeometry gb = box_is_a ? geo(ground) : geo(b);
    const double turn = box_is_a ? 0.5 : 0.0;
    const auto poses = [&](const Motion& mo, Transform* xa, Transform* xb) {
      const Transform ground_pose = pose(0, 0);
      const Transform box_pose = pose(0.2 + mo.dx, 0.99 + mo.dy, turn + mo.deg);
      *xa = box_is_a ? box_pose : ground_pose;
      *xb = box_is_a ? ground_pose : box_pose;
    };
    Transform xa, xb;
    poses({0, 0, 0}, &xa, &xb);
    const Manifold previous = collide(ga, xa, gb, xb);
    REQUIRE(previous.point_count == 2);
    for (const Motion& mo : small) {
      INFO("box is A " << box_is_a << " motion " << mo.dx << " " << mo.dy << " " << mo.deg);
      poses(mo, &xa, &xb);
      const Manifold full = collide(ga, xa, gb, xb);
      const Manifold again = collide_persistent(ga, xa, gb, xb, previous);
      REQUIRE(again.point_count == 2);
      CHECK(identical(again, full));
      CHECK(sorted_ids(again) == sorted_ids(previous));
      check_invariants(again, xa, xb);
    }
    // Beyond the thresholds: exactly collide().
    const std::vector<Motion> beyond = {{0, 0, 4.0}, {0, 0, -8.0}, {5.28, 0, 0}, {-5.69, 0, 0}, {0, 0.05, 0}};
    for (const Motion& mo : beyond) {
      INFO("beyond: box is A " << box_is_a << " motion " << mo.dx << " " << mo.dy << " " << mo.deg);
      poses(mo, &xa, &xb);
      CHECK(identical(collide_persistent(ga, xa, gb, xb, previous), collide(ga, xa, gb, xb)));
    }
    Manifold one = previous;
    one.point_count = 1;
    poses(small[2], &xa, &xb);
    CHECK(identical(collide_persistent(ga, xa, gb, xb, one), collide(ga, xa, gb, xb)));
  }
  // Other shape pairs always take collide().
  const Capsule cap{v2(-0.5, 0), v2(0.5, 0), q(0.25)};
  const Manifold cap_previous = collide(geo(ground), pose(0, 0), geo(cap), pose(0.2, 0.74));
  REQUIRE(cap_previous.point_count == 2);
  CHECK(identical(collide_persistent(geo(ground), pose(0, 0), geo(cap), pose(0.21, 0.745), cap_previous),
                  collide(geo(ground), pose(0, 0), geo(cap), pose(0.21, 0.745))));
}

TEST_CASE("rotation sweeps: no missing contacts, no flipped normals", "[physics][manifold]") {
  const Polygon ground = box(5, 0.5);
  const Polygon b = box(0.5, 0.3);
  const Polygon rb = box(0.4, 0.2, 0.1);
  const Capsule cap{v2(-0.4, 0), v2(0.4, 0), q(0.2)};
  const auto chain = flat_chain();
  // The lowest point of each shape turned by q, relative to its origin.
  const auto lowest = [](const Polygon& p, Rot r) {
    Q32 low = Q32::max();
    for (int32_t i = 0; i < p.count; ++i) low = min(low, rotate(r, p.vertices[static_cast<size_t>(i)]).y);
    return low - p.radius;
  };
  for (int deg = 0; deg < 360; ++deg) {
    const Rot r = rot_deg(deg);
    for (const double gap : {-0.005, 0.01}) {
      INFO("angle " << deg << " gap " << gap);
      // Box on box (sharp and rounded).
      for (const Polygon* p : {&b, &rb}) {
        const Transform xb{{q(0.3), q(0.5 + gap) - lowest(*p, r)}, r};
        const Manifold m = collide_polygons(ground, pose(0, 0), *p, xb);
        check_invariants(m, pose(0, 0), xb);
        REQUIRE(m.point_count >= 1);
        CHECK(m.normal == Vec2{Q32::zero(), Q32::one()});
        CHECK(near(min_separation(m), gap, 1e-8));
      }
      // Capsule on box.
      {
        const Q32 low = min(rotate(r, cap.center1).y, rotate(r, cap.center2).y) - cap.radius;
        const Transform xb{{q(-0.7), q(0.5 + gap) - low}, r};
        const Manifold m = collide_polygon_and_capsule(ground, pose(0, 0), cap, xb);
        check_invariants(m, pose(0, 0), xb);
        REQUIRE(m.point_count >= 1);
        CHECK(m.normal == Vec2{Q32::zero(), Q32::one()});
        CHECK(near(min_separation(m), gap, 1e-8));
      }
      // Box on the flat chain, over the joint at x = 0.
      for (const double x : {0.0, 0.37}) {
        const Transform xb{{q(x), q(gap) - lowest(b, r)}, r};
        Q32 smin = Q32::max();
        int points = 0;
        for (const Manifold& m : collide_chain(chain, geo(b), xb)) {
          check_invariants(m, transform_identity(), xb);
          if (m.point_count == 0) continue;
          CHECK(m.normal == Vec2{Q32::zero(), Q32::one()});
          smin = min(smin, min_separation(m));
          points += m.point_count;
        }
        REQUIRE(points >= 1);
        CHECK(near(smin, gap, 1e-8));
      }
    }
  }
}

// ---------------------------------------------------------------------------
// Random pairs against the oracle and against GJK
// ---------------------------------------------------------------------------

namespace {

/// Oracle separation of the rounded shapes (core distance − radii; for
/// overlapping cores −radii).
LD oracle_separation(const ShapeGeometry& a, Transform xa, const ShapeGeometry& b, Transform xb, LD* out_core) {
  const OracleCore oa = oracle_core(a, xa), ob = oracle_core(b, xb);
  const LD core = core_distance(oa, ob);
  if (out_core) *out_core = core;
  return core - (oa.radius + ob.radius);
}

/// Penetration depth of overlapping cores: the smallest overlap over the
/// edge normals of both (the Minkowski difference's normals; for a 2-gon its
/// ±normal). Needs at least one core with two or more points.
LD oracle_depth(const ShapeGeometry& a, Transform xa, const ShapeGeometry& b, Transform xb) {
  const OracleCore oa = oracle_core(a, xa), ob = oracle_core(b, xb);
  std::vector<P2> axes;
  for (const OracleCore* o : {&oa, &ob}) {
    const size_t n = o->pts.size();
    if (n < 2) continue;
    for (size_t i = 0; i < (n == 2 ? 1 : n); ++i) {
      const P2 e = o->pts[(i + 1) % n] - o->pts[i];
      const LD len = std::sqrt(dotl(e, e));
      axes.push_back({e.y / len, -e.x / len});
      axes.push_back({-e.y / len, e.x / len});
    }
  }
  if (axes.empty()) return 0;  // two points
  LD best = 1e30L;
  for (const P2& u : axes) {
    LD amax = -1e30L, bmin = 1e30L;
    for (const P2& p : oa.pts) amax = std::max(amax, dotl(u, p));
    for (const P2& p : ob.pts) bmin = std::min(bmin, dotl(u, p));
    best = std::min(best, amax - bmin);
  }
  return best;
}

struct RandomPair {
  ShapeGeometry a, b;
  Transform xa, xb;
  int ka = 0, kb = 0;
};

/// A random pair; three times in four B is slid towards A until the oracle
/// separation is a random target in [−0.03, 0.03] m (bisection on doubles),
/// so most pairs land near contact. A lies anywhere within ±10⁵ m.
RandomPair random_pair(Rng& rng) {
  RandomPair r;
  r.ka = rng.range(0, 4);
  r.kb = rng.range(0, 4);
  if ((r.ka == 2 || r.ka == 4) && (r.kb == 2 || r.kb == 4)) r.kb = rng.range(0, 1) == 0 ? 0 : 3;
  r.a = random_shape(rng, r.ka);
  r.b = random_shape(rng, r.kb);
  const Q32 ax = rng.uniform(-1e5, 1e5), ay = rng.uniform(-1e5, 1e5), aa = rng.angle();
  r.xa = {{ax, ay}, rot_from_angle(aa)};
  const Q32 ox = rng.uniform(-2.5, 2.5), oy = rng.uniform(-2.5, 2.5), ba = rng.angle();
  const Rot qb = rot_from_angle(ba);
  const Q32 target = rng.range(0, 2) == 0 ? rng.uniform(-0.1, 0.0) : rng.uniform(-0.03, 0.03);
  // B's origin at A's plus (ox, oy)·(1 − t), t in [0, 1] (Q32).
  const auto place = [&](Q32 t) {
    return Transform{r.xa.p + Vec2{ox * (Q32::one() - t), oy * (Q32::one() - t)}, qb};
  };
  r.xb = place(Q32::zero());
  if (rng.range(0, 3) != 0) {
    // Signed separation: core distance, or minus the penetration depth.
    const auto f = [&](Q32 t) {
      LD core = 0;
      const LD sep = oracle_separation(r.a, r.xa, r.b, place(t), &core);
      return (core > 0 ? sep : sep - oracle_depth(r.a, r.xa, r.b, place(t))) - ld(target);
    };
    if (f(Q32::zero()) > 0 && f(Q32::one()) < 0) {
      Q32 lo = Q32::zero(), hi = Q32::one();
      for (int i = 0; i < 36; ++i) {  // 2^-36 of the path: ~5e-11 m
        const Q32 mid = Q32::from_raw((lo.raw + hi.raw) / 2);
        (f(mid) > 0 ? lo : hi) = mid;
      }
      r.xb = place(lo);
    }
  }
  return r;
}

ShapeProxy proxy_of(const ShapeGeometry& g) {
  switch (g.type) {
    case ShapeType::circle: return make_proxy(g.circle);
    case ShapeType::capsule: return make_proxy(g.capsule);
    case ShapeType::segment: return make_proxy(g.segment);
    case ShapeType::polygon: return make_proxy(g.polygon);
    case ShapeType::chain_segment: return make_proxy(g.chain_segment.segment);
    case ShapeType::count: break;
  }
  return {};
}

}  // namespace

TEST_CASE("random pairs: separation agrees with the exact core distance", "[physics][manifold]") {
  // Disjoint cores: the manifold's smallest separation must equal the exact
  // core distance minus the radii whenever that is inside the margin —
  // vertex–vertex and face contacts to rounding, except where A is kept as
  // the reference face within the flip tolerance (then at most that much
  // larger, never smaller). Beyond the margin: no points. Overlapping cores:
  // at least one point, at least as deep as the radii; the depth is compared
  // with the exact penetration depth (measured, asserted for shallow ones).
  const double k_face_tolerance = dbl(k_linear_slop) / 10 + 1e-8;
  const double margin = dbl(k_speculative_distance);
  Rng rng(0x6d616e69666f6c64);
  double worst_disjoint = 0, worst_shallow = 0;
  int disjoint_checked = 0, inexact = 0, overlap_checked = 0, shallow_checked = 0, empty_checked = 0;
  int chain_front = 0;
  for (int n = 0; n < k_random_pairs; ++n) {
    const RandomPair r = random_pair(rng);
    const Manifold m = collide(r.a, r.xa, r.b, r.xb);
    INFO("pair " << n << " kinds " << r.ka << " " << r.kb << "\n A " << describe(r.a, r.xa) << "\n B "
                 << describe(r.b, r.xb) << "\n " << describe(m));
    check_invariants(m, r.xa, r.xb);
    LD core_ld = 0;
    const double sep = static_cast<double>(oracle_separation(r.a, r.xa, r.b, r.xb, &core_ld));
    const double core = static_cast<double>(core_ld);
    if (r.ka == 4 || r.kb == 4) {
      // One-sided: the separation is the signed depth along the chain's
      // normal, so a body partly on the solid side may be reported deeper
      // than its core distance. A body wholly in front of the segment's line
      // never is.
      const bool a_chain = r.ka == 4;
      const ChainSegment& cs = a_chain ? r.a.chain_segment : r.b.chain_segment;
      const Transform xc = a_chain ? r.xa : r.xb;
      const OracleCore other = a_chain ? oracle_core(r.b, r.xb) : oracle_core(r.a, r.xa);
      const P2 p1 = world(cs.segment.point1, xc), p2 = world(cs.segment.point2, xc);
      const P2 e = p2 - p1;
      const LD len = std::sqrt(dotl(e, e));
      const P2 nrm{e.y / len, -e.x / len};
      bool in_front = true, front = true;
      for (const P2& p : other.pts) {
        const LD t = dotl(p - p1, e) / (len * len);
        in_front = in_front && dotl(p - p1, nrm) > 0;
        front = front && t > 0.01L && t < 0.99L && dotl(p - p1, nrm) > 0;
      }
      if (m.point_count > 0 && in_front) CHECK(dbl(min_separation(m)) >= sep - 1e-7);
      // Wholly in front of the segment's interior: a plain face contact.
      if (front && sep < margin - 1e-6) {
        ++chain_front;
        REQUIRE(m.point_count >= 1);
        const Manifold mc = a_chain ? m : flip_manifold(m);
        CHECK(std::fabs(dbl(mc.normal.x) - static_cast<double>(nrm.x)) < 1e-8);
        CHECK(std::fabs(dbl(mc.normal.y) - static_cast<double>(nrm.y)) < 1e-8);
        CHECK(std::fabs(dbl(min_separation(m)) - sep) < 1e-7);
      }
      continue;
    }
    if (core > 0) {
      if (sep < margin - k_face_tolerance) {
        REQUIRE(m.point_count >= 1);
        const double err = dbl(min_separation(m)) - sep;
        worst_disjoint = std::max(worst_disjoint, std::fabs(err));
        inexact += err > 1e-7;
        CHECK(err >= -1e-7);  // never more overlap than the shapes have
        CHECK(err <= k_face_tolerance);
        ++disjoint_checked;
      } else if (sep > margin + 1e-7) {
        CHECK(m.point_count == 0);
        ++empty_checked;
      }
    } else {
      REQUIRE(m.point_count >= 1);
      const double radii = sep;  // −(rA + rB)
      CHECK(dbl(min_separation(m)) <= radii + 1e-7);
      ++overlap_checked;
      if (r.ka != 0 && r.kb != 0) {
        const double depth = static_cast<double>(oracle_depth(r.a, r.xa, r.b, r.xb));
        const double err = dbl(min_separation(m)) - (radii - depth);
        if (depth < 0.05) {
          // Shallow: the SAT face is the minimum-depth axis (A kept within
          // the flip tolerance), and its deepest vertex is clipped in.
          worst_shallow = std::max(worst_shallow, std::fabs(err));
          CHECK(err >= -k_face_tolerance);
          CHECK(err <= 1e-7);
          ++shallow_checked;
        }
      }
    }
  }
  WARN("random pairs " << k_random_pairs << ": disjoint in margin " << disjoint_checked << " (worst |error| "
                       << worst_disjoint << " m, " << inexact << " above 1e-7 m); beyond margin " << empty_checked
                       << "; overlapping " << overlap_checked << " (shallow " << shallow_checked << ", worst |error| "
                       << worst_shallow << " m); chain wholly in front " << chain_front);
  CHECK(disjoint_checked > k_random_pairs / 5);
  CHECK(overlap_checked > k_random_pairs / 20);
  CHECK(shallow_checked > k_random_pairs / 50);
  CHECK(empty_checked > k_random_pairs / 10);
  CHECK(chain_front > k_random_pairs / 200);
}

TEST_CASE("random pairs: separation agrees with GJK distance", "[physics][manifold]") {
  // shape_distance on the cores (use_radii = false) against the manifold's
  // smallest separation plus the radii, whenever the cores are apart and the
  // rounded shapes within the margin (chain segments, one-sided, are left to
  // the oracle test).
  const double k_tolerance = dbl(k_linear_slop) / 10 + 1e-7;
  const double margin = dbl(k_speculative_distance);
  Rng rng(0x676a6b);
  double worst = 0;
  int checked = 0;
  for (int n = 0; n < k_random_pairs / 4; ++n) {
    const RandomPair r = random_pair(rng);
    const Manifold m = collide(r.a, r.xa, r.b, r.xb);
    DistanceInput in;
    in.proxy_a = proxy_of(r.a);
    in.proxy_b = proxy_of(r.b);
    in.transform_a = r.xa;
    in.transform_b = r.xb;
    in.use_radii = false;
    const DistanceOutput d = shape_distance(in);
    const double radii = dbl(in.proxy_a.radius + in.proxy_b.radius);
    const double sep = dbl(d.distance) - radii;
    INFO("pair " << n << " kinds " << r.ka << " " << r.kb << "\n A " << describe(r.a, r.xa) << "\n B "
                 << describe(r.b, r.xb) << "\n " << describe(m) << "\n gjk distance " << dbl(d.distance));
    if (d.distance <= k_geometry_epsilon || sep >= margin - k_tolerance) continue;
    if (r.ka == 4 || r.kb == 4) continue;  // one-sided: covered by the oracle test
    REQUIRE(m.point_count >= 1);
    const double err = dbl(min_separation(m)) - sep;
    worst = std::max(worst, std::fabs(err));
    CHECK(std::fabs(err) <= k_tolerance);
    ++checked;
  }
  WARN("GJK comparisons " << checked << ", worst |manifold − GJK| " << worst << " m");
  CHECK(checked > k_random_pairs / 40);
}

TEST_CASE("flip_manifold negates the normal and swaps anchors and feature-id halves", "[physics][manifold]") {
  using namespace tandem::literals;
  Manifold m;
  m.normal = {0_q32, 1_q32};
  m.point_count = 1;
  m.points[0].anchor_a = {1_q32, 2_q32};
  m.points[0].anchor_b = {3_q32, 4_q32};
  m.points[0].point = {5_q32, 6_q32};
  m.points[0].separation = -0.25_q32;
  m.points[0].id = make_feature_id(1, 2);
  const Manifold f = flip_manifold(m);
  CHECK(f.normal == Vec2{0_q32, -1_q32});
  CHECK(f.point_count == 1);
  CHECK(f.points[0].anchor_a == Vec2{3_q32, 4_q32});
  CHECK(f.points[0].anchor_b == Vec2{1_q32, 2_q32});
  CHECK(f.points[0].point == m.points[0].point);
  CHECK(f.points[0].separation == m.points[0].separation);
  CHECK(f.points[0].id == make_feature_id(2, 1));
  const Manifold back = flip_manifold(f);
  CHECK(back.normal == m.normal);
  CHECK(back.points[0].anchor_a == m.points[0].anchor_a);
  CHECK(back.points[0].id == m.points[0].id);
}

TEST_CASE("narrow_math: native and portable definitions agree", "[physics][manifold]") {
  // narrow_math.h defines its sums of products and clipping fractions once
  // (wide.h limbs, long division); the native paths (__int128, divq) must
  // give those bits, in range and, wrapping, out of it. In range the product
  // sums also match the checked operators except at exact negative ties.
  std::mt19937_64 rng(20);
  const auto draw = [&rng](int bits) {
    const uint64_t r = rng();
    const int64_t v = static_cast<int64_t>(r >> (64 - bits));
    return (r & 1) != 0 ? -v : v;
  };
  int ties = 0;
  for (int i = 0; i < 200000; ++i) {
    const int64_t a = draw(53), b = draw(33), c = draw(53), d = draw(33);
    const int64_t got = narrow_math::sum_products(a, b, c, d);
    REQUIRE(got == narrow_math::sum_products_portable(a, b, c, d));
    const Q32 checked = Q32::from_raw(a) * Q32::from_raw(b) + Q32::from_raw(c) * Q32::from_raw(d);
    // Two roundings in the checked sum: within one raw unit of the one rounding.
    CHECK(std::llabs(got - checked.raw) <= 1);
    const Q32 once = dot(Vec2{Q32::from_raw(a), Q32::from_raw(c)}, Vec2{Q32::from_raw(b), Q32::from_raw(d)});
    if (got != once.raw) {
      ++ties;
      CHECK(got == once.raw + 1);  // only a negative exact tie: rounded up instead of away from zero
    }
    // Out of range: both wrap the same way.
    const int64_t wa = draw(63), wb = draw(63), wc = draw(63), wd = draw(63);
    REQUIRE(narrow_math::sum_products(wa, wb, wc, wd) == narrow_math::sum_products_portable(wa, wb, wc, wd));
    // Clipping fractions 0 ≤ n ≤ d: exact quotient and the Q32 division's bits.
    const int64_t den = std::max<int64_t>(1, std::llabs(draw(54)));
    const int64_t num = static_cast<int64_t>(rng() % (static_cast<uint64_t>(den) + 1));
    uint64_t r_native = 0, r_portable = 0;
    const uint64_t q_native = narrow_math::fraction_quotient(static_cast<uint64_t>(num), static_cast<uint64_t>(den), &r_native);
    const uint64_t q_portable =
        narrow_math::fraction_quotient_portable(static_cast<uint64_t>(num), static_cast<uint64_t>(den), &r_portable);
    REQUIRE(q_native == q_portable);
    REQUIRE(r_native == r_portable);
    REQUIRE(narrow_math::fraction(Q32::from_raw(num), Q32::from_raw(den)) == Q32::from_raw(num) / Q32::from_raw(den));
    // Halving: Q32's a / 2 for every raw value.
    const Q32 h = Q32::from_raw(static_cast<int64_t>(rng()));
    REQUIRE(narrow_math::half(h) == h / 2);
  }
  for (const int64_t raw : {INT64_MIN, INT64_MIN + 1, int64_t{-3}, int64_t{-2}, int64_t{-1}, int64_t{0}, int64_t{1},
                            int64_t{2}, int64_t{3}, INT64_MAX - 1, INT64_MAX}) {
    CHECK(narrow_math::half(Q32::from_raw(raw)) == Q32::from_raw(raw) / 2);
  }
  CHECK(ties < 100);
}
