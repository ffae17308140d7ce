// test_hull.cpp — compute_hull, make_polygon, boxes and the shape validators.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "physics/collision.h"

using namespace tandem;

namespace {

#ifdef NDEBUG
constexpr int k_scale = 1;
#else
constexpr int k_scale = 8;  // debug and sanitizer builds run fewer random cases
#endif

constexpr long double k_two32 = 4294967296.0L;
long double ld(Q32 v) { return static_cast<long double>(v.raw) / k_two32; }

Vec2 v(const char* x, const char* y) { return {parse_q32(x).value, parse_q32(y).value}; }

/// A raw value uniformly in [−range, range] (raw units), drawn without std
/// distributions (their output differs across standard libraries).
int64_t draw(std::mt19937_64& rng, int64_t range) {
  const uint64_t span = static_cast<uint64_t>(range) * 2 + 1;
  return static_cast<int64_t>(rng() % span) - range;
}

/// Fisher–Yates with modulo draws (std::shuffle is library-specific).
template <typename T>
void shuffle(std::vector<T>* items, std::mt19937_64& rng) {
  for (size_t i = items->size(); i > 1; --i) std::swap((*items)[i - 1], (*items)[rng() % i]);
}

bool same_bits(const Polygon& a, const Polygon& b) {
  if (a.count != b.count || a.radius != b.radius || a.centroid != b.centroid) return false;
  for (int i = 0; i < a.count; ++i) {
    if (a.vertices[static_cast<size_t>(i)] != b.vertices[static_cast<size_t>(i)]) return false;
    if (a.normals[static_cast<size_t>(i)] != b.normals[static_cast<size_t>(i)]) return false;
  }
  return true;
}

/// Twice the signed area of (a, b, c), long double.
long double orient(Vec2 a, Vec2 b, Vec2 c) {
  return (ld(b.x) - ld(a.x)) * (ld(c.y) - ld(a.y)) - (ld(b.y) - ld(a.y)) * (ld(c.x) - ld(a.x));
}

}  // namespace

TEST_CASE("compute_hull: square with interior points", "[physics]") {
  const std::vector<Vec2> pts = {vec2(0, 0), v("0.5", "0.2"), vec2(1, 1), vec2(-1, 1), v("-0.3", "0.7"),
                                 vec2(1, -1), v("0.9", "-0.9"), vec2(-1, -1)};
  Hull hull;
  const Status s = compute_hull(pts.data(), static_cast<int32_t>(pts.size()), &hull);
  REQUIRE(s.ok());
  CHECK(s.message.empty());
  REQUIRE(hull.count == 4);
  CHECK(hull.points[0] == vec2(-1, -1));  // lowest, then leftmost
  CHECK(hull.points[1] == vec2(1, -1));
  CHECK(hull.points[2] == vec2(1, 1));
  CHECK(hull.points[3] == vec2(-1, 1));
}

TEST_CASE("compute_hull: points on edges and exact duplicates are dropped", "[physics]") {
  const std::vector<Vec2> pts = {vec2(0, 0), vec2(2, 0), vec2(4, 0), vec2(4, 2), vec2(4, 4), vec2(0, 4),
                                 vec2(0, 2), vec2(4, 4), vec2(0, 0), vec2(2, 4)};
  Hull hull;
  REQUIRE(compute_hull(pts.data(), static_cast<int32_t>(pts.size()), &hull).ok());
  REQUIRE(hull.count == 4);
  CHECK(hull.points[0] == vec2(0, 0));
  CHECK(hull.points[1] == vec2(4, 0));
  CHECK(hull.points[2] == vec2(4, 4));
  CHECK(hull.points[3] == vec2(0, 4));
}

TEST_CASE("compute_hull: points within the weld tolerance are welded", "[physics]") {
  // Each corner twice: the second copy 0.0001 m away (< 0.0005 m). The kept
  // point of a cluster is the smallest in (x, y) order.
  const std::vector<Vec2> pts = {vec2(1, 1),   v("1.0001", "0.9999"), vec2(-1, 1), v("-1.0001", "1"),
                                 vec2(-1, -1), v("-0.9999", "-1"),    vec2(1, -1), v("1", "-1.0001")};
  Hull hull;
  REQUIRE(compute_hull(pts.data(), static_cast<int32_t>(pts.size()), &hull).ok());
  REQUIRE(hull.count == 4);
  CHECK(hull.points[0] == v("1", "-1.0001"));  // the lowest point
  CHECK(hull.points[1] == vec2(1, 1));
  CHECK(hull.points[2] == v("-1.0001", "1"));
  CHECK(hull.points[3] == vec2(-1, -1));

  // All points in one weld cluster.
  const std::vector<Vec2> blob = {vec2(3, 3), v("3.0001", "3"), v("3", "3.0002"), v("2.9999", "2.9999")};
  const Status s = compute_hull(blob.data(), 4, &hull);
  CHECK_FALSE(s.ok());
  CHECK(s.message == "polygon: only 1 distinct points of 4 after welding points closer than 0.0005 m, need at least 3");
  CHECK(hull.count == 0);
}

TEST_CASE("compute_hull: degenerate input is rejected with a message", "[physics]") {
  Hull hull;
  SECTION("collinear") {
    const std::vector<Vec2> pts = {vec2(0, 0), vec2(1, 1), vec2(3, 3), vec2(-2, -2)};
    const Status s = compute_hull(pts.data(), 4, &hull);
    CHECK_FALSE(s.ok());
    CHECK(s.message == "polygon: all 4 points are collinear");
    CHECK(hull.count == 0);
  }
  SECTION("nearly collinear (within linear slop of a line)") {
    const std::vector<Vec2> pts = {vec2(0, 0), vec2(10, 0), v("5", "0.004")};
    const Status s = compute_hull(pts.data(), 3, &hull);
    CHECK_FALSE(s.ok());
    CHECK(s.message == "polygon: all 3 points lie within 0.005 m of a line");
  }
  SECTION("two points") {
    const std::vector<Vec2> pts = {vec2(0, 0), vec2(1, 0)};
    const Status s = compute_hull(pts.data(), 2, &hull);
    CHECK_FALSE(s.ok());
    CHECK(s.message == "polygon: 2 points given, need at least 3");
  }
  SECTION("null") {
    CHECK_FALSE(compute_hull(nullptr, 5, &hull).ok());
  }
  SECTION("more than 8 hull vertices") {
    // A regular 12-gon of radius 1 (from exact sines of multiples of 30°).
    const char* c[12][2] = {{"1", "0"},          {"0.8660254", "0.5"},  {"0.5", "0.8660254"},  {"0", "1"},
                            {"-0.5", "0.8660254"}, {"-0.8660254", "0.5"}, {"-1", "0"},          {"-0.8660254", "-0.5"},
                            {"-0.5", "-0.8660254"}, {"0", "-1"},        {"0.5", "-0.8660254"}, {"0.8660254", "-0.5"}};
    std::vector<Vec2> pts;
    for (auto& p : c) pts.push_back(v(p[0], p[1]));
    const Status s = compute_hull(pts.data(), 12, &hull);
    CHECK_FALSE(s.ok());
    CHECK(s.message == "polygon: the hull of the 12 points has 12 vertices, at most 8 are allowed");
  }
  SECTION("too many input points") {
    std::vector<Vec2> pts(static_cast<size_t>(k_max_hull_input_points + 1), vec2(0, 0));
    const Status s = compute_hull(pts.data(), static_cast<int32_t>(pts.size()), &hull);
    CHECK_FALSE(s.ok());
    CHECK(s.message == "polygon: 65 points given, at most 64 are accepted");
  }
  SECTION("out of range") {
    const std::vector<Vec2> pts = {vec2(0, 0), vec2(20000, 0), vec2(0, 1)};
    const Status s = compute_hull(pts.data(), 3, &hull);
    CHECK_FALSE(s.ok());
    CHECK(s.message == "polygon: point 1 (20000, 0) m is beyond ±10000 m");
  }
}

TEST_CASE("compute_hull: more than 8 input points are fine when the hull has at most 8", "[physics]") {
  // Octagon corners plus interior points: 8 hull vertices.
  const char* c[8][2] = {{"2", "0"},  {"1.4", "1.4"},  {"0", "2"},  {"-1.4", "1.4"},
                         {"-2", "0"}, {"-1.4", "-1.4"}, {"0", "-2"}, {"1.4", "-1.4"}};
  std::vector<Vec2> pts;
  for (auto& p : c) pts.push_back(v(p[0], p[1]));
  pts.push_back(vec2(0, 0));
  pts.push_back(v("0.3", "-0.7"));
  Hull hull;
  REQUIRE(compute_hull(pts.data(), static_cast<int32_t>(pts.size()), &hull).ok());
  REQUIRE(hull.count == 8);
  CHECK(hull.points[0] == vec2(0, -2));
  CHECK(hull.points[1] == v("1.4", "-1.4"));
}

TEST_CASE("compute_hull: a vertex within linear slop of its neighbours' line is dropped", "[physics]") {
  const std::vector<Vec2> pts = {vec2(0, 0), vec2(4, 0), vec2(0, 3), v("2", "-0.004")};
  Hull hull;
  REQUIRE(compute_hull(pts.data(), 4, &hull).ok());
  REQUIRE(hull.count == 3);
  CHECK(hull.points[0] == vec2(0, 0));
  CHECK(hull.points[1] == vec2(4, 0));
  CHECK(hull.points[2] == vec2(0, 3));
  // 0.006 m off the line: kept (and it is now the lowest point).
  const std::vector<Vec2> pts2 = {vec2(0, 0), vec2(4, 0), vec2(0, 3), v("2", "-0.006")};
  REQUIRE(compute_hull(pts2.data(), 4, &hull).ok());
  REQUIRE(hull.count == 4);
  CHECK(hull.points[0] == v("2", "-0.006"));
}

TEST_CASE("compute_hull: random clouds are order independent and convex", "[physics]") {
  std::mt19937_64 rng(0x48554c4cu);
  const int cases = 3000 / k_scale;
  int ok_count = 0;
  for (int c = 0; c < cases; ++c) {
    const int n = 3 + static_cast<int>(rng() % 14);
    std::vector<Vec2> pts;
    // Mostly 1–5 m clouds; some points snapped to a coarse grid so that
    // collinear and duplicate points occur.
    const int64_t range = (int64_t{1} << 32) * (1 + static_cast<int64_t>(rng() % 5));
    for (int i = 0; i < n; ++i) {
      Vec2 p{Q32::from_raw(draw(rng, range)), Q32::from_raw(draw(rng, range))};
      if (rng() % 3 == 0) p = {Q32::from_raw(p.x.raw & ~((int64_t{1} << 31) - 1)), Q32::from_raw(p.y.raw & ~((int64_t{1} << 31) - 1))};
      pts.push_back(p);
    }
    Polygon base;
    const Status s = make_polygon_from_points(pts.data(), n, Q32::zero(), &base);
    for (int k = 0; k < 3; ++k) {
      std::vector<Vec2> shuffled = pts;
      shuffle(&shuffled, rng);
      Polygon other;
      const Status s2 = make_polygon_from_points(shuffled.data(), n, Q32::zero(), &other);
      REQUIRE(s2.ok() == s.ok());
      REQUIRE(s2.message == s.message);
      REQUIRE(same_bits(base, other));
    }
    if (!s.ok()) continue;
    ++ok_count;
    REQUIRE(validate_polygon(base).ok());
    // Strictly convex, CCW, starting at the lowest-then-leftmost vertex.
    for (int i = 0; i < base.count; ++i) {
      const Vec2 a = base.vertices[static_cast<size_t>(i)];
      const Vec2 b = base.vertices[static_cast<size_t>((i + 1) % base.count)];
      const Vec2 cc = base.vertices[static_cast<size_t>((i + 2) % base.count)];
      REQUIRE(orient(a, b, cc) > 0);
      if (i > 0) {
        const bool lower = a.y > base.vertices[0].y || (a.y == base.vertices[0].y && a.x > base.vertices[0].x);
        REQUIRE(lower);
      }
    }
    // Every input point lies inside the hull, or within linear slop outside
    // it (a dropped near-collinear vertex).
    for (const Vec2 p : pts) {
      for (int i = 0; i < base.count; ++i) {
        const Vec2 a = base.vertices[static_cast<size_t>(i)];
        const Vec2 nrm = base.normals[static_cast<size_t>(i)];
        const long double sep = (ld(p.x) - ld(a.x)) * ld(nrm.x) + (ld(p.y) - ld(a.y)) * ld(nrm.y);
        REQUIRE(sep <= ld(k_linear_slop) + 1e-9L);
      }
    }
  }
  CHECK(ok_count > cases / 2);
}

TEST_CASE("make_polygon: normals and centroid", "[physics]") {
  Hull hull;
  hull.count = 3;
  hull.points = {vec2(0, 0), vec2(3, 0), vec2(0, 3)};
  Polygon p;
  REQUIRE(make_polygon(hull, Q32::zero(), &p).ok());
  CHECK(p.count == 3);
  CHECK(p.centroid == vec2(1, 1));  // exact: dyadic arithmetic throughout… except the /3
  CHECK(p.normals[0] == Vec2{Q32::zero(), -Q32::one()});
  CHECK(p.normals[2] == Vec2{-Q32::one(), Q32::zero()});
  // Normal 1 is (1, 1)/√2, correctly rounded per component.
  const long double inv_sqrt2 = 0.70710678118654752440L;
  CHECK(std::abs(static_cast<long double>(p.normals[1].x.raw) - inv_sqrt2 * k_two32) <= 1);
  CHECK(p.normals[1].x == p.normals[1].y);

  // A quadrilateral: centroid against the long double formula.
  hull.count = 4;
  hull.points = {v("0.1", "-0.3"), v("2.7", "0.2"), v("1.9", "1.8"), v("-0.4", "0.9")};
  REQUIRE(make_polygon(hull, v("0.05", "0").x, &p).ok());
  long double a2 = 0, cx = 0, cy = 0;
  for (int i = 0; i < 4; ++i) {
    const Vec2 a = hull.points[static_cast<size_t>(i)], b = hull.points[static_cast<size_t>((i + 1) % 4)];
    const long double d = ld(a.x) * ld(b.y) - ld(b.x) * ld(a.y);
    a2 += d;
    cx += d * (ld(a.x) + ld(b.x));
    cy += d * (ld(a.y) + ld(b.y));
  }
  CHECK(std::abs(ld(p.centroid.x) - cx / (3 * a2)) * k_two32 <= 1.5L);
  CHECK(std::abs(ld(p.centroid.y) - cy / (3 * a2)) * k_two32 <= 1.5L);
  CHECK(p.radius == v("0.05", "0").x);
  CHECK(validate_polygon(p).ok());
}

TEST_CASE("make_polygon: rejects bad hulls", "[physics]") {
  Polygon p;
  Hull hull;
  hull.count = 4;
  hull.points = {vec2(0, 0), vec2(0, 1), vec2(1, 1), vec2(1, 0)};  // clockwise
  Status s = make_polygon(hull, Q32::zero(), &p);
  CHECK_FALSE(s.ok());
  CHECK(s.message.find("strictly convex and counter-clockwise") != std::string::npos);
  CHECK(p.count == 0);
  hull.points = {vec2(0, 0), vec2(2, 0), vec2(1, 1), vec2(2, 2)};  // reflex vertex
  CHECK_FALSE(make_polygon(hull, Q32::zero(), &p).ok());
  hull.points = {vec2(0, 0), vec2(1, 0), vec2(1, 1), vec2(0, 1)};
  s = make_polygon(hull, -Q32::one(), &p);
  CHECK_FALSE(s.ok());
  CHECK(s.message == "polygon: radius -1 m is outside [0, 10000] m");
  hull.count = 3;
  hull.points = {vec2(0, 0), v("0.001", "0"), v("0", "0.001")};
  s = make_polygon(hull, Q32::zero(), &p);
  CHECK_FALSE(s.ok());
  CHECK(s.message == "polygon: area 0.0000005 m² is below the minimum 0.000001 m²");
  hull.count = 2;
  s = make_polygon(hull, Q32::zero(), &p);
  CHECK(s.message == "polygon: 2 vertices, need 3 to 8");
}

TEST_CASE("make_box and make_offset_box", "[physics]") {
  Polygon box;
  REQUIRE(make_box(v("0.5", "0").x, Q32::one(), &box).ok());
  CHECK(box.count == 4);
  CHECK(box.vertices[0] == v("-0.5", "-1"));
  CHECK(box.vertices[2] == v("0.5", "1"));
  CHECK(box.normals[1] == vec2(1, 0));
  CHECK(box.centroid == vec2(0, 0));
  CHECK(validate_polygon(box).ok());
  // The same box through the hull builder: identical bits.
  const Vec2 corners[4] = {v("0.5", "1"), v("-0.5", "-1"), v("-0.5", "1"), v("0.5", "-1")};
  Polygon hull_box;
  REQUIRE(make_polygon_from_points(corners, 4, Q32::zero(), &hull_box).ok());
  CHECK(same_bits(box, hull_box));

  Status s = make_box(Q32::zero(), Q32::one(), &box);
  CHECK(s.message == "box: half width 0 m is outside [0.005, 10000] m");
  CHECK(box.count == 0);

  Polygon ob;
  const Q32 angle = parse_q32("0.7").value;
  REQUIRE(make_offset_box(Q32::one(), v("0.25", "0").x, v("3", "-2"), angle, v("0.1", "0").x, &ob).ok());
  CHECK(validate_polygon(ob).ok());
  CHECK(ob.centroid == v("3", "-2"));
  CHECK(ob.radius == v("0.1", "0").x);
  const long double c = std::cos(0.7L), sn = std::sin(0.7L);
  const long double hx[4] = {-1, 1, 1, -1}, hy[4] = {-0.25L, -0.25L, 0.25L, 0.25L};
  for (int i = 0; i < 4; ++i) {
    const Vec2 q = ob.vertices[static_cast<size_t>(i)];
    CHECK(std::abs(ld(q.x) - (3 + c * hx[i] - sn * hy[i])) * k_two32 <= 4);
    CHECK(std::abs(ld(q.y) - (-2 + sn * hx[i] + c * hy[i])) * k_two32 <= 4);
  }
  s = make_offset_box(Q32::one(), Q32::one(), vec2(9999, 0), angle, Q32::zero(), &ob);
  CHECK_FALSE(s.ok());
  CHECK(s.message.rfind("box: centre (9999, 0) m", 0) == 0);
}

TEST_CASE("validate_polygon catches hand-made mistakes", "[physics]") {
  Polygon box;
  REQUIRE(make_box(Q32::one(), Q32::one(), &box).ok());
  Polygon p = box;
  p.normals[2] = vec2(1, 0);
  Status s = validate_polygon(p);
  CHECK_FALSE(s.ok());
  CHECK(s.message == "polygon: normal 2 (1, 0) is not the unit outward normal of edge 2 (0, 1)");
  p = box;
  p.normals[1] = {Q32::from_raw(Q32::one().raw + (int64_t{1} << 15)), Q32::zero()};  // not unit
  CHECK_FALSE(validate_polygon(p).ok());
  p = box;
  p.centroid = v("0.001", "0");
  s = validate_polygon(p);
  CHECK(s.message == "polygon: centroid (0.001, 0) m is not the vertices' centroid (0, 0) m");
  p = box;
  std::swap(p.vertices[1], p.vertices[3]);
  CHECK_FALSE(validate_polygon(p).ok());
  p = box;
  p.count = 9;
  CHECK(validate_polygon(p).message == "polygon: 9 vertices, need 3 to 8");
  p = box;
  p.radius = -Q32::epsilon();
  CHECK_FALSE(validate_polygon(p).ok());
}

TEST_CASE("validate_circle, validate_capsule, validate_segment", "[physics]") {
  CHECK(validate_circle({vec2(1, 2), v("0.5", "0").x}).ok());
  CHECK(validate_circle({vec2(0, 0), Q32::zero()}).message == "circle: radius 0 m is outside [0.005, 10000] m");
  CHECK(validate_circle({vec2(0, 0), v("0.001", "0").x}).message == "circle: radius 0.001 m is outside [0.005, 10000] m");
  CHECK(validate_circle({vec2(9999, 0), vec2(2, 0).x}).message ==
        "circle: centre (9999, 0) m plus radius 2 m reaches beyond ±10000 m");

  CHECK(validate_capsule({vec2(0, 0), vec2(1, 0), v("0.25", "0").x}).ok());
  CHECK(validate_capsule({vec2(0, 0), v("0.001", "0"), v("0.25", "0").x}).message ==
        "capsule: centres 0.001 m apart, need at least 0.005 m");
  CHECK(validate_capsule({vec2(0, 0), vec2(1, 0), -Q32::one()}).message ==
        "capsule: radius -1 m is outside [0.005, 10000] m");

  CHECK(validate_segment({vec2(0, 0), vec2(0, 1)}).ok());
  CHECK(validate_segment({vec2(0, 0), v("0", "0.004")}).message ==
        "segment: end points 0.004 m apart, need at least 0.005 m");
  CHECK(validate_segment({vec2(0, 0), vec2(0, -10001)}).message == "segment: end point (0, -10001) m is beyond ±10000 m");
}
