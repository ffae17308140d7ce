// test_distance.cpp — GJK distance, shape cast, sweeps and time of impact.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
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
Q32 q(long double x) { return Q32::from_raw(std::llround(x * k_two32)); }
Vec2 v(long double x, long double y) { return {q(x), q(y)}; }
long double raw_diff(Q32 a, long double b) { return std::abs(ld(a) - b) * k_two32; }
bool near(Vec2 a, long double x, long double y, long double tol_raw) {
  return raw_diff(a.x, x) <= tol_raw && raw_diff(a.y, y) <= tol_raw;
}

int64_t draw(std::mt19937_64& rng, int64_t lo, int64_t hi) {
  return lo + static_cast<int64_t>(rng() % static_cast<uint64_t>(hi - lo + 1));
}
Q32 draw_q(std::mt19937_64& rng, long double lo, long double hi) {
  return Q32::from_raw(draw(rng, q(lo).raw, q(hi).raw));
}
Vec2 draw_v(std::mt19937_64& rng, long double lo, long double hi) { return {draw_q(rng, lo, hi), draw_q(rng, lo, hi)}; }

Transform xf_at(long double x, long double y, long double angle = 0) { return {v(x, y), rot_from_angle(q(angle))}; }

/// A random proxy: a circle, capsule, segment or (rounded) polygon, 0.1–3 m.
ShapeProxy random_proxy(std::mt19937_64& rng) {
  const int kind = static_cast<int>(rng() % 4);
  const long double size = 0.1L + static_cast<long double>(rng() % 30) / 10;
  if (kind == 0) return make_proxy(Circle{draw_v(rng, -0.5L, 0.5L), draw_q(rng, 0.05L, size)});
  if (kind == 1) {
    const Vec2 a = draw_v(rng, -size, size);
    return make_proxy(Capsule{a, a + draw_v(rng, -size, size) + v(0.01L, 0), draw_q(rng, 0.05L, size / 2)});
  }
  for (;;) {
    const int n = 3 + static_cast<int>(rng() % 8);
    std::vector<Vec2> pts;
    for (int i = 0; i < n; ++i) pts.push_back(draw_v(rng, -size, size));
    Polygon p;
    const Q32 r = kind == 3 ? draw_q(rng, 0.005L, size / 3) : Q32::zero();
    if (make_polygon_from_points(pts.data(), n, r, &p).ok()) return make_proxy(p);
  }
}

struct P {
  long double x, y;
};
P world(const ShapeProxy& proxy, Transform xf, int i) {
  const Vec2 w = transform_point(xf, proxy.points[static_cast<size_t>(i)]);
  return {ld(w.x), ld(w.y)};
}
long double cross3(P a, P b, P c) { return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x); }
long double point_segment(P p, P a, P b) {
  const long double ex = b.x - a.x, ey = b.y - a.y, ll = ex * ex + ey * ey;
  long double t = ll > 0 ? ((p.x - a.x) * ex + (p.y - a.y) * ey) / ll : 0;
  t = std::clamp(t, 0.0L, 1.0L);
  const long double dx = p.x - a.x - t * ex, dy = p.y - a.y - t * ey;
  return std::sqrt(dx * dx + dy * dy);
}
bool segments_cross(P a, P b, P c, P d) {
  const long double d1 = cross3(c, d, a), d2 = cross3(c, d, b), d3 = cross3(a, b, c), d4 = cross3(a, b, d);
  return ((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0));
}
bool inside_convex(P p, const std::vector<P>& poly) {
  if (poly.size() < 3) return false;
  for (size_t i = 0; i < poly.size(); ++i) {
    if (cross3(poly[i], poly[(i + 1) % poly.size()], p) < 0) return false;
  }
  return true;
}

/// Brute-force core distance between two convex point sets (long double).
long double oracle_core_distance(const ShapeProxy& a, Transform xa, const ShapeProxy& b, Transform xb) {
  std::vector<P> pa, pb;
  for (int i = 0; i < a.count; ++i) pa.push_back(world(a, xa, i));
  for (int i = 0; i < b.count; ++i) pb.push_back(world(b, xb, i));
  for (const P& p : pa) if (inside_convex(p, pb)) return 0;
  for (const P& p : pb) if (inside_convex(p, pa)) return 0;
  long double best = 1e30L;
  for (size_t i = 0; i < pa.size(); ++i) {
    const P a1 = pa[i], a2 = pa[(i + 1) % pa.size()];
    for (size_t j = 0; j < pb.size(); ++j) {
      const P b1 = pb[j], b2 = pb[(j + 1) % pb.size()];
      if (segments_cross(a1, a2, b1, b2)) return 0;
      best = std::min({best, point_segment(a1, b1, b2), point_segment(b1, a1, a2)});
    }
  }
  return best;
}

DistanceOutput dist(const ShapeProxy& a, Transform xa, const ShapeProxy& b, Transform xb, bool radii = true) {
  DistanceInput in;
  in.proxy_a = a;
  in.proxy_b = b;
  in.transform_a = xa;
  in.transform_b = xb;
  in.use_radii = radii;
  return shape_distance(in);
}

Polygon box(long double hw, long double hh) {
  Polygon p;
  REQUIRE(make_box(q(hw), q(hh), &p).ok());
  return p;
}

}  // namespace

// ---------------------------------------------------------------------------
// GJK
// ---------------------------------------------------------------------------

TEST_CASE("shape_distance: two circles", "[physics]") {
  const ShapeProxy a = make_proxy(Circle{vec2(0, 0), Q32::one()});
  const ShapeProxy b = make_proxy(Circle{vec2(0, 0), q(0.5L)});
  DistanceOutput o = dist(a, transform_identity(), b, xf_at(3, 4));
  CHECK(raw_diff(o.distance, 3.5L) <= 2);
  CHECK(near(o.normal, 0.6L, 0.8L, 2));
  CHECK(near(o.point_a, 0.6L, 0.8L, 4));
  CHECK(near(o.point_b, 2.7L, 3.6L, 4));
  o = dist(a, transform_identity(), b, xf_at(3, 4), false);
  CHECK(raw_diff(o.distance, 5) <= 2);
  CHECK(o.point_b == vec2(3, 4));
  // Overlapping discs, separate centres: distance 0, points on the surfaces.
  o = dist(a, transform_identity(), b, xf_at(1, 0));
  CHECK(o.distance == Q32::zero());
  CHECK(near(o.point_a, 1, 0, 2));
  CHECK(near(o.point_b, 0.5L, 0, 2));
  // Concentric: the normal is zero and both points are the centre.
  o = dist(a, transform_identity(), b, transform_identity());
  CHECK(o.distance == Q32::zero());
  CHECK(o.normal == Vec2{});
  CHECK(o.point_a == o.point_b);
  // A rotated frame: A's centre at local (1, 0) turned 90° → world (0, 1).
  const ShapeProxy a2 = make_proxy(Circle{vec2(1, 0), Q32::one()});
  o = dist(a2, {vec2(0, 0), Rot{Q32::zero(), Q32::one()}}, b, xf_at(0, 4));
  CHECK(raw_diff(o.distance, 1.5L) <= 2);
  CHECK(near(o.normal, 0, 1, 1));
}

TEST_CASE("shape_distance: boxes and points", "[physics]") {
  const ShapeProxy unit = make_proxy(box(0.5L, 0.5L));
  DistanceOutput o = dist(unit, transform_identity(), unit, xf_at(3, 0));
  CHECK(o.distance == vec2(2, 0).x);  // exact
  CHECK(o.normal == vec2(1, 0));
  CHECK(o.point_a.x == q(0.5L));
  CHECK(o.point_b.x == q(2.5L));
  // B turned 45°: its corner reaches x = 3 − √2/2.
  o = dist(unit, transform_identity(), unit, xf_at(3, 0, 0.78539816339744830962L));
  CHECK(raw_diff(o.distance, 2.5L - std::sqrt(0.5L)) <= 8);
  CHECK(near(o.normal, 1, 0, 4));
  CHECK(near(o.point_b, 3 - std::sqrt(0.5L), 0, 8));
  // Diagonal: corner to corner.
  o = dist(unit, transform_identity(), unit, xf_at(2, 2));
  CHECK(raw_diff(o.distance, std::sqrt(2.0L)) <= 4);
  CHECK(near(o.point_a, 0.5L, 0.5L, 2));
  CHECK(near(o.point_b, 1.5L, 1.5L, 2));
  // Overlap.
  o = dist(unit, transform_identity(), unit, xf_at(0.7L, 0.2L));
  CHECK(o.distance == Q32::zero());
  CHECK(o.simplex_count == 3);

  // A point inside a polygon, on its edge, and outside.
  const ShapeProxy tri = make_proxy(
      [] {
        Polygon p;
        const Vec2 pts[3] = {vec2(0, 0), vec2(4, 0), vec2(0, 3)};
        REQUIRE(make_polygon_from_points(pts, 3, Q32::zero(), &p).ok());
        return p;
      }());
  const Vec2 origin{};
  const ShapeProxy point = make_proxy(&origin, 1, Q32::zero());
  CHECK(dist(tri, transform_identity(), point, xf_at(1, 1)).distance == Q32::zero());
  CHECK(dist(tri, transform_identity(), point, xf_at(2, 0)).distance == Q32::zero());
  o = dist(tri, transform_identity(), point, xf_at(4, 3));
  CHECK(raw_diff(o.distance, 2.4L) <= 2);  // to the hypotenuse 3x + 4y = 12
  CHECK(near(o.normal, 0.6L, 0.8L, 2));
  CHECK(near(o.point_a, 4 - 1.44L, 3 - 1.92L, 4));
}

TEST_CASE("shape_distance: random shapes against a brute-force oracle, both orders", "[physics]") {
  std::mt19937_64 rng(0x474a4b21u);
  const int cases = 6000 / k_scale;
  long double worst = 0, worst_sym = 0, worst_witness = 0;
  int separated = 0, overlapping = 0, max_iterations = 0;
  for (int c = 0; c < cases; ++c) {
    const ShapeProxy a = random_proxy(rng), b = random_proxy(rng);
    const Transform xa{draw_v(rng, -3, 3), rot_from_angle(draw_q(rng, -4, 4))};
    const Transform xb{draw_v(rng, -3, 3), rot_from_angle(draw_q(rng, -4, 4))};
    const DistanceOutput ab = dist(a, xa, b, xb), ba = dist(b, xb, a, xa);
    const DistanceOutput core = dist(a, xa, b, xb, false);
    max_iterations = std::max({max_iterations, ab.iterations, ba.iterations});
    const long double oc = oracle_core_distance(a, xa, b, xb);
    const long double expected = std::max(0.0L, oc - ld(a.radius) - ld(b.radius));
    worst = std::max({worst, std::abs(ld(core.distance) - oc), std::abs(ld(ab.distance) - expected)});
    worst_sym = std::max(worst_sym, std::abs(ld(ab.distance) - ld(ba.distance)));
    REQUIRE(ab.distance >= Q32::zero());
    if (oc > 1e-6L) {
      ++separated;
      // Witness points: their distance is the core distance, the normal is
      // their direction, and B, A gives the mirror image.
      const long double dx = ld(core.point_b.x) - ld(core.point_a.x), dy = ld(core.point_b.y) - ld(core.point_a.y);
      worst_witness = std::max(worst_witness, std::abs(std::sqrt(dx * dx + dy * dy) - oc));
      worst_witness = std::max(worst_witness, std::abs(dx - oc * ld(core.normal.x)) + std::abs(dy - oc * ld(core.normal.y)));
      REQUIRE(raw_diff(length(core.normal), 1) <= 4);
      const DistanceOutput core_ba = dist(b, xb, a, xa, false);
      REQUIRE(std::abs(core_ba.normal.x.raw + core.normal.x.raw) <= 64);
      REQUIRE(std::abs(core_ba.normal.y.raw + core.normal.y.raw) <= 64);
    } else {
      ++overlapping;
    }
  }
  INFO("worst distance error " << static_cast<double>(worst) << " m, symmetry " << static_cast<double>(worst_sym)
                               << " m, witness " << static_cast<double>(worst_witness) << " m; separated "
                               << separated << ", overlapping " << overlapping << ", max iterations " << max_iterations);
  CHECK(worst <= 1e-8L);
  CHECK(worst_sym <= 1e-8L);
  CHECK(worst_witness <= 1e-7L);
  CHECK(separated > cases / 4);
  CHECK(overlapping > cases / 20);
  CHECK(max_iterations < k_max_gjk_iterations);
}

TEST_CASE("shape_distance is deterministic and independent of earlier calls", "[physics]") {
  const ShapeProxy a = make_proxy(box(1, 0.25L));
  const ShapeProxy b = make_proxy(Capsule{vec2(0, 0), vec2(1, 1), q(0.1L)});
  const DistanceOutput first = dist(a, xf_at(0.1L, 0.2L, 0.3L), b, xf_at(2, 1.5L, -1));
  (void)dist(b, xf_at(5, 5), a, xf_at(-2, 1));  // an unrelated query in between
  const DistanceOutput second = dist(a, xf_at(0.1L, 0.2L, 0.3L), b, xf_at(2, 1.5L, -1));
  CHECK(first.distance == second.distance);
  CHECK(first.point_a == second.point_a);
  CHECK(first.point_b == second.point_b);
  CHECK(first.normal == second.normal);
  CHECK(first.iterations == second.iterations);
}

// ---------------------------------------------------------------------------
// Shape cast
// ---------------------------------------------------------------------------

TEST_CASE("shape_cast: known answers", "[physics]") {
  const ShapeProxy wall = make_proxy(box(1, 1));
  const ShapeProxy ball = make_proxy(Circle{vec2(0, 0), q(0.5L)});
  ShapeCastInput in;
  in.proxy_a = wall;
  in.proxy_b = ball;
  in.transform_b = xf_at(-5, 0);
  in.translation_b = vec2(10, 0);
  const Q32 slop = k_linear_slop;
  SECTION("a ball hits the box: the core stops within slop/4 of radius − slop") {
    const CastOutput o = shape_cast(in);
    REQUIRE(o.hit);
    // Core distance 4 − 10f must end in [target, target + slop/4], target = 0.5 − slop.
    const long double target = 0.5L - ld(slop);
    CHECK(ld(o.fraction) >= (4 - target - ld(slop) / 4) / 10 - 1e-9L);
    CHECK(ld(o.fraction) <= (4 - target) / 10 + 1e-9L);
    CHECK(near(o.normal, -1, 0, 2));
    CHECK(near(o.point, -1, 0, 4));
    CHECK(o.iterations <= 3);
  }
  SECTION("box against box: polygons stop a slop apart") {
    in.proxy_b = make_proxy(box(1, 1));
    in.transform_b = xf_at(-5, 0.3L);
    const CastOutput o = shape_cast(in);
    REQUIRE(o.hit);
    CHECK(ld(o.fraction) >= (3 - ld(slop) * 1.25L) / 10 - 1e-9L);
    CHECK(ld(o.fraction) <= (3 - ld(slop)) / 10 + 1e-9L);
    CHECK(near(o.normal, -1, 0, 2));
  }
  SECTION("misses") {
    in.translation_b = vec2(-10, 0);  // moving away
    CHECK_FALSE(shape_cast(in).hit);
    in.translation_b = vec2(0, 10);  // passing by
    CHECK_FALSE(shape_cast(in).hit);
    in.translation_b = vec2(10, 0);
    in.max_fraction = q(0.3L);  // stops short
    CHECK_FALSE(shape_cast(in).hit);
  }
  SECTION("initial overlap and encroaching") {
    in.transform_b = xf_at(-1.2L, 0);
    CastOutput o = shape_cast(in);
    CHECK(o.hit);
    CHECK(o.fraction == Q32::zero());
    // Two discs overlapping by 0.01 m, approaching: a hit at 0, unless they
    // may encroach — then they advance until one more slop closer.
    ShapeCastInput c;
    c.proxy_a = make_proxy(Circle{vec2(0, 0), Q32::one()});
    c.proxy_b = make_proxy(Circle{vec2(0, 0), Q32::one()});
    c.transform_b = xf_at(1.99L, 0);
    c.translation_b = vec2(-1, 0);
    o = shape_cast(c);
    CHECK(o.hit);
    CHECK(o.fraction == Q32::zero());
    c.can_encroach = true;
    o = shape_cast(c);
    REQUIRE(o.hit);
    CHECK(ld(o.fraction) >= ld(slop) * 0.75L - 1e-9L);
    CHECK(ld(o.fraction) <= ld(slop) + 1e-9L);
  }
}

TEST_CASE("shape_cast: random casts never pass through", "[physics]") {
  std::mt19937_64 rng(0x43415354u);
  const int cases = 2000 / k_scale;
  int hits = 0;
  for (int c = 0; c < cases; ++c) {
    ShapeCastInput in;
    in.proxy_a = random_proxy(rng);
    in.proxy_b = random_proxy(rng);
    in.transform_a = {draw_v(rng, -1, 1), rot_from_angle(draw_q(rng, -4, 4))};
    in.transform_b = {draw_v(rng, -8, 8), rot_from_angle(draw_q(rng, -4, 4))};
    // One draw per statement: the order of evaluation of operands is unspecified.
    const Vec2 aim = in.transform_a.p - in.transform_b.p + draw_v(rng, -2, 2);
    in.translation_b = aim * draw_q(rng, 0.5L, 2);
    const CastOutput o = shape_cast(in);
    const long double target = std::max(ld(k_linear_slop), ld(in.proxy_a.radius) + ld(in.proxy_b.radius) - ld(k_linear_slop));
    const Q32 end = o.hit ? o.fraction : Q32::one();
    // Up to the reported fraction the cores stay at least `target` apart
    // (sampled), and at a hit they are within slop/4 above it.
    for (int s = 0; s <= 16; ++s) {
      Transform xb = in.transform_b;
      xb.p = mul_add(in.transform_b.p, end * Q32::from_ratio(s, 16), in.translation_b);
      const DistanceOutput d = dist(in.proxy_a, in.transform_a, in.proxy_b, xb, false);
      if (o.hit && o.fraction == Q32::zero()) break;
      REQUIRE(ld(d.distance) >= target - 1e-7L);
      if (s == 16 && o.hit) {
        ++hits;
        REQUIRE(ld(d.distance) < target + ld(k_linear_slop) / 4 + 1e-7L);
      }
    }
  }
  CHECK(hits > cases / 5);
}

// ---------------------------------------------------------------------------
// Sweeps and time of impact
// ---------------------------------------------------------------------------

TEST_CASE("sweep_transform interpolates position and rotation", "[physics]") {
  Sweep s;
  s.local_center = vec2(1, 0);
  s.c1 = vec2(0, 0);
  s.c2 = vec2(4, 2);
  s.q1 = rot_identity();
  s.q2 = Rot{Q32::zero(), Q32::one()};
  Transform t = sweep_transform(s, Q32::zero());
  CHECK(t.q == rot_identity());
  CHECK(t.p == vec2(-1, 0));  // origin = centre − q·local_center
  t = sweep_transform(s, Q32::one());
  CHECK(t.q == s.q2);
  CHECK(t.p == vec2(4, 1));
  t = sweep_transform(s, Q32::half());
  CHECK(raw_diff(t.q.c, std::sqrt(0.5L)) <= 1);
  CHECK(raw_diff(t.q.s, std::sqrt(0.5L)) <= 1);
  CHECK(raw_diff(t.p.x, 2 - std::sqrt(0.5L)) <= 2);
  CHECK(raw_diff(t.p.y, 1 - std::sqrt(0.5L)) <= 2);
}

namespace {

Sweep still(Vec2 c) {
  Sweep s;
  s.c1 = c;
  s.c2 = c;
  return s;
}

ToiInput toi_input(const ShapeProxy& a, const Sweep& sa, const ShapeProxy& b, const Sweep& sb) {
  ToiInput in;
  in.proxy_a = a;
  in.proxy_b = b;
  in.sweep_a = sa;
  in.sweep_b = sb;
  return in;
}

}  // namespace

TEST_CASE("time_of_impact: a fast circle hits a thin wall", "[physics]") {
  const ShapeProxy wall = make_proxy(box(0.1L, 5));
  const ShapeProxy ball = make_proxy(Circle{vec2(0, 0), q(0.25L)});
  Sweep sb = still(vec2(-10, 0));
  sb.c2 = vec2(10, 0);  // 20 m in one step: far more than the wall's 0.2 m
  ToiOutput o = time_of_impact(toi_input(wall, still(vec2(0, 0)), ball, sb));
  REQUIRE(o.state == ToiState::hit);
  // Core distance 9.9 − 20t reaches target 0.25 − slop (within slop/4).
  const long double target = 0.25L - ld(k_linear_slop);
  CHECK(ld(o.fraction) >= (9.9L - target - ld(k_linear_slop) / 4) / 20 - 1e-9L);
  CHECK(ld(o.fraction) <= (9.9L - target) / 20 + 1e-9L);
  // Too slow to arrive.
  sb.c2 = vec2(-5, 0);
  o = time_of_impact(toi_input(wall, still(vec2(0, 0)), ball, sb));
  CHECK(o.state == ToiState::separated);
  CHECK(o.fraction == Q32::one());
  // Moving away.
  sb.c2 = vec2(-20, 3);
  CHECK(time_of_impact(toi_input(wall, still(vec2(0, 0)), ball, sb)).state == ToiState::separated);
  // Starting inside.
  sb.c1 = vec2(0, 1);
  o = time_of_impact(toi_input(wall, still(vec2(0, 0)), ball, sb));
  CHECK(o.state == ToiState::overlapped);
  CHECK(o.fraction == Q32::zero());
}

namespace {

/// The plank's largest x over the sweep's nlerp rotation at time t (long
/// double), for corners (±hx, ±hy) around its centre.
long double plank_max_x(const Sweep& s, long double hx, long double hy, long double t) {
  const long double c = (1 - t) * ld(s.q1.c) + t * ld(s.q2.c), sn = (1 - t) * ld(s.q1.s) + t * ld(s.q2.s);
  const long double len = std::sqrt(c * c + sn * sn);
  const long double cx = (1 - t) * ld(s.c1.x) + t * ld(s.c2.x);
  long double best = -1e30L;
  for (const long double x : {-hx, hx}) {
    for (const long double y : {-hy, hy}) best = std::max(best, cx + (c * x - sn * y) / len);
  }
  return best;
}

/// First t in [0, 1] with plank_max_x ≥ face − gap (bisection; max_x rises
/// monotonically over these sweeps).
long double first_reach(const Sweep& s, long double hx, long double hy, long double face, long double gap) {
  long double lo = 0, hi = 1;
  for (int i = 0; i < 200; ++i) {
    const long double mid = (lo + hi) / 2;
    (plank_max_x(s, hx, hy, mid) >= face - gap ? hi : lo) = mid;
  }
  return lo;
}

}  // namespace

TEST_CASE("time_of_impact: a spinning plank reaches a wall", "[physics]") {
  // Plank 2 × 0.1 m, centred at the origin, turning from vertical towards the
  // wall face at x = 0.7 (wall 0.1 m thick, 10 m tall).
  const ShapeProxy wall = make_proxy(box(0.05L, 5));
  const ShapeProxy plank = make_proxy(box(1, 0.05L));
  const long double slop = ld(k_linear_slop);
  for (const long double shift : {0.0L, 0.3L}) {
    Sweep sb = still(vec2(0, 0));
    sb.q1 = rot_from_angle(q(1.57079632679489661923L));
    sb.q2 = rot_from_angle(q(1.57079632679489661923L - 1.2L));
    sb.c2 = v(shift, 0);
    const ToiOutput o = time_of_impact(toi_input(wall, still(v(0.75L, 0)), plank, sb));
    REQUIRE(o.state == ToiState::hit);
    const long double t_hi = first_reach(sb, 1, 0.05L, 0.7L, slop);
    const long double t_lo = first_reach(sb, 1, 0.05L, 0.7L, slop * 1.25L);
    INFO("shift " << static_cast<double>(shift) << ": toi " << static_cast<double>(ld(o.fraction)) << " in ["
                  << static_cast<double>(t_lo) << ", " << static_cast<double>(t_hi) << "] after " << o.iterations
                  << " iterations");
    CHECK(ld(o.fraction) >= t_lo - 1e-7L);
    CHECK(ld(o.fraction) <= t_hi + 1e-7L);
    CHECK(o.iterations < k_max_toi_iterations);
  }
}

TEST_CASE("time_of_impact: random sweeps never tunnel", "[physics]") {
  std::mt19937_64 rng(0x544f4921u);
  const int cases = 1500 / k_scale;
  int hits = 0, separated = 0, failed = 0, worst_iterations = 0;
  for (int c = 0; c < cases; ++c) {
    const ShapeProxy a = random_proxy(rng), b = random_proxy(rng);
    Sweep sa = still(draw_v(rng, -1, 1));
    sa.c2 = sa.c1 + draw_v(rng, -1, 1);
    sa.local_center = draw_v(rng, -0.3L, 0.3L);
    sa.q1 = rot_from_angle(draw_q(rng, -3, 3));
    sa.q2 = mul_rot(sa.q1, rot_from_angle(draw_q(rng, -1, 1)));
    Sweep sb = still(draw_v(rng, -6, 6));
    sb.c2 = draw_v(rng, -6, 6);
    sb.local_center = draw_v(rng, -0.3L, 0.3L);
    sb.q1 = rot_from_angle(draw_q(rng, -3, 3));
    sb.q2 = mul_rot(sb.q1, rot_from_angle(draw_q(rng, -1.5L, 1.5L)));
    const ToiOutput o = time_of_impact(toi_input(a, sa, b, sb));
    worst_iterations = std::max(worst_iterations, o.iterations);
    if (o.state == ToiState::overlapped) continue;
    const long double target = std::max(ld(k_linear_slop), ld(a.radius) + ld(b.radius) - ld(k_linear_slop));
    hits += o.state == ToiState::hit;
    separated += o.state == ToiState::separated;
    failed += o.state == ToiState::failed;
    const Q32 end = o.fraction;
    if (o.state == ToiState::hit && end == Q32::zero()) {
      // Already within the target at the start (rounded shapes overlapping).
      REQUIRE(ld(dist(a, sweep_transform(sa, end), b, sweep_transform(sb, end), false).distance) <
              target + ld(k_linear_slop) / 4);
      continue;
    }
    for (int s = 0; s <= 32; ++s) {
      const Q32 t = end * Q32::from_ratio(s, 32);
      const DistanceOutput d = dist(a, sweep_transform(sa, t), b, sweep_transform(sb, t), false);
      REQUIRE(ld(d.distance) >= target - 1e-7L);
      if (s == 32 && o.state == ToiState::hit) REQUIRE(ld(d.distance) < target + ld(k_linear_slop) / 4 + 1e-7L);
    }
  }
  INFO("hit " << hits << ", separated " << separated << ", failed " << failed << ", most iterations "
                << worst_iterations);
  CHECK(hits > cases / 10);
  CHECK(separated > cases / 10);
  CHECK(failed <= cases / 50);
}

TEST_CASE("make_proxy: counts are clamped and shapes map to their cores", "[physics]") {
  const ShapeProxy empty = make_proxy(nullptr, 0, q(0.5L));
  CHECK(empty.count == 1);
  CHECK(empty.points[0] == Vec2{});
  CHECK(empty.radius == q(0.5L));
  std::vector<Vec2> many;
  for (int i = 0; i < 12; ++i) many.push_back(vec2(i, -i));
  const ShapeProxy clamped = make_proxy(many.data(), 12, Q32::zero());
  CHECK(clamped.count == k_max_polygon_vertices);
  CHECK(clamped.points[7] == vec2(7, -7));
  const ShapeProxy cap = make_proxy(Capsule{vec2(1, 2), vec2(3, 4), q(0.25L)});
  CHECK(cap.count == 2);
  CHECK(cap.points[1] == vec2(3, 4));
  CHECK(cap.radius == q(0.25L));
  const ShapeProxy seg = make_proxy(Segment{vec2(1, 2), vec2(3, 4)});
  CHECK(seg.count == 2);
  CHECK(seg.radius == Q32::zero());
  const Polygon b = box(1, 2);
  const ShapeProxy poly = make_proxy(b);
  CHECK(poly.count == 4);
  CHECK(poly.points[2] == vec2(1, 2));
}
