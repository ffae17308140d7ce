// test_capi_geometry.cpp — single-shape geometry through the C API
// (tandem_c_geometry.h): every result equals the C++ function's (the pure
// functions of this executable's static copy), bit for bit; bad input gives a
// status and a message.
#include "capi_test_util.h"

namespace {

tandem_shape_geometry geometry(int32_t type) {
  tandem_shape_geometry g;
  std::memset(&g, 0, sizeof g);
  g.type = type;
  g.circle = {{qt("0.25"), 0}, qt("0.5")};
  g.capsule = {{qi(-1), 0}, {qi(1), 0}, qt("0.25")};
  g.segment = {{qi(-2), 0}, {qi(2), qt("0.5")}};
  REQUIRE(tandem_make_offset_box(qt("0.75"), qt("0.5"), {0, qt("0.1")}, qt("0.2"), 0, &g.polygon) == TANDEM_OK);
  g.chain_segment = {{qi(-3), 0}, {{qi(-2), 0}, {qi(2), 0}}, {qi(3), 0}, 0};
  return g;
}

tandem::Vec2 cpp(tandem_vec2 v) { return {tandem::Q32::from_raw(v.x), tandem::Q32::from_raw(v.y)}; }

}  // namespace

TEST_CASE("geometry: validation, mass, bounds, point tests, ray casts and manifolds equal C++", "[capi][geometry]") {
  using namespace tandem;
  const tandem_shape_geometry circle = geometry(TANDEM_SHAPE_CIRCLE);
  const tandem_shape_geometry capsule = geometry(TANDEM_SHAPE_CAPSULE);
  const tandem_shape_geometry segment = geometry(TANDEM_SHAPE_SEGMENT);
  const tandem_shape_geometry polygon = geometry(TANDEM_SHAPE_POLYGON);
  const tandem_shape_geometry chain = geometry(TANDEM_SHAPE_CHAIN_SEGMENT);
  const Circle cc{cpp(circle.circle.center), Q32::from_raw(circle.circle.radius)};
  const Capsule ccap{cpp(capsule.capsule.center1), cpp(capsule.capsule.center2), Q32::from_raw(capsule.capsule.radius)};
  Polygon cpoly;
  REQUIRE(make_offset_box(Q32::from_ratio(3, 4), Q32::from_ratio(1, 2), Vec2{Q32{}, parse_q32("0.1").value},
                          parse_q32("0.2").value, Q32{}, &cpoly)
              .ok());

  // Validation.
  CHECK(tandem_validate_circle(&circle.circle) == TANDEM_OK);
  CHECK(tandem_validate_capsule(&capsule.capsule) == TANDEM_OK);
  CHECK(tandem_validate_segment(&segment.segment) == TANDEM_OK);
  CHECK(tandem_validate_polygon(&polygon.polygon) == TANDEM_OK);
  tandem_circle bad = circle.circle;
  bad.radius = 0;
  require_error(tandem_validate_circle(&bad), TANDEM_ERROR_INVALID_ARGUMENT, "radius");
  tandem_segment dot = {{0, 0}, {0, 0}};
  CHECK(tandem_validate_segment(&dot) == TANDEM_ERROR_INVALID_ARGUMENT);
  tandem_capsule thin = capsule.capsule;
  thin.radius = -1;
  CHECK(tandem_validate_capsule(&thin) == TANDEM_ERROR_INVALID_ARGUMENT);
  tandem_polygon empty = polygon.polygon;
  empty.count = 0;
  CHECK(tandem_validate_polygon(&empty) == TANDEM_ERROR_INVALID_ARGUMENT);
  require_error(tandem_validate_polygon(nullptr), TANDEM_ERROR_NULL_POINTER, "shape");

  // Mass.
  tandem_mass_data m{};
  REQUIRE(tandem_compute_circle_mass(&circle.circle, qi(2), &m) == TANDEM_OK);
  CHECK(m.mass == compute_circle_mass(cc, Q32::from_int(2)).mass.raw);
  REQUIRE(tandem_compute_capsule_mass(&capsule.capsule, qi(2), &m) == TANDEM_OK);
  CHECK(m.rotational_inertia == compute_capsule_mass(ccap, Q32::from_int(2)).rotational_inertia.raw);
  REQUIRE(tandem_compute_polygon_mass(&polygon.polygon, qi(2), &m) == TANDEM_OK);
  CHECK(m.center.y == compute_polygon_mass(cpoly, Q32::from_int(2)).center.y.raw);
  require_error(tandem_compute_polygon_mass(&polygon.polygon, qi(2), nullptr), TANDEM_ERROR_NULL_POINTER, "out_mass");
  require_error(tandem_compute_circle_mass(nullptr, qi(2), &m), TANDEM_ERROR_NULL_POINTER, "shape");
  require_error(tandem_compute_capsule_mass(nullptr, qi(2), &m), TANDEM_ERROR_NULL_POINTER, "shape");

  // Bounds of every kind under a rotation and translation.
  const tandem_transform xf = {{qi(1), qi(2)}, tandem_rot_from_angle(qt("0.3"))};
  const Transform cxf{cpp(xf.p), Rot{Q32::from_raw(xf.q.c), Q32::from_raw(xf.q.s)}};
  tandem_aabb box{};
  REQUIRE(tandem_compute_shape_aabb(&circle, xf, &box) == TANDEM_OK);
  CHECK(box.upper.x == compute_circle_aabb(cc, cxf).upper.x.raw);
  REQUIRE(tandem_compute_shape_aabb(&capsule, xf, &box) == TANDEM_OK);
  CHECK(box.lower.y == compute_capsule_aabb(ccap, cxf).lower.y.raw);
  REQUIRE(tandem_compute_shape_aabb(&polygon, xf, &box) == TANDEM_OK);
  CHECK(box.upper.y == compute_polygon_aabb(cpoly, cxf).upper.y.raw);
  REQUIRE(tandem_compute_shape_aabb(&segment, xf, &box) == TANDEM_OK);
  CHECK(box.upper.x > box.lower.x);
  REQUIRE(tandem_compute_shape_aabb(&chain, xf, &box) == TANDEM_OK);
  CHECK(box.upper.x > box.lower.x);
  tandem_shape_geometry unknown = circle;
  unknown.type = 9;
  require_error(tandem_compute_shape_aabb(&unknown, xf, &box), TANDEM_ERROR_INVALID_ARGUMENT, "shape.type 9");
  require_error(tandem_compute_shape_aabb(&circle, xf, nullptr), TANDEM_ERROR_NULL_POINTER, "out_aabb");

  // Point tests.
  bool inside = false;
  REQUIRE(tandem_point_in_shape(&circle, {qt("0.5"), 0}, &inside) == TANDEM_OK);
  CHECK(inside);
  REQUIRE(tandem_point_in_shape(&capsule, {0, qi(1)}, &inside) == TANDEM_OK);
  CHECK_FALSE(inside);
  REQUIRE(tandem_point_in_shape(&polygon, {0, 0}, &inside) == TANDEM_OK);
  CHECK(inside == point_in_polygon(Vec2{}, cpoly));
  REQUIRE(tandem_point_in_shape(&segment, {0, 0}, &inside) == TANDEM_OK);
  CHECK_FALSE(inside);
  require_error(tandem_point_in_shape(&circle, {0, 0}, nullptr), TANDEM_ERROR_NULL_POINTER, "out_inside");

  // Ray casts: down through every kind from above.
  const tandem_ray_cast_input ray = {{0, qi(3)}, {0, qi(-6)}, qi(1)};
  const RayCastInput cray{vec2(0, 3), vec2(0, -6), Q32::one()};
  tandem_cast_output hit{};
  REQUIRE(tandem_ray_cast_shape(&circle, &ray, &hit) == TANDEM_OK);
  CHECK(hit.hit);
  CHECK(hit.fraction == ray_cast_circle(cray, cc).fraction.raw);
  REQUIRE(tandem_ray_cast_shape(&capsule, &ray, &hit) == TANDEM_OK);
  CHECK(hit.point.y == ray_cast_capsule(cray, ccap).point.y.raw);
  REQUIRE(tandem_ray_cast_shape(&polygon, &ray, &hit) == TANDEM_OK);
  CHECK(hit.normal.y == ray_cast_polygon(cray, cpoly).normal.y.raw);
  REQUIRE(tandem_ray_cast_shape(&segment, &ray, &hit) == TANDEM_OK);
  CHECK(hit.hit);
  REQUIRE(tandem_ray_cast_shape(&chain, &ray, &hit) == TANDEM_OK);  // one-sided: hit from the solid side only
  const bool from_above = hit.hit;
  const tandem_ray_cast_input up = {{0, qi(-3)}, {0, qi(6)}, qi(1)};
  REQUIRE(tandem_ray_cast_shape(&chain, &up, &hit) == TANDEM_OK);
  CHECK(from_above != hit.hit);
  require_error(tandem_ray_cast_shape(&circle, nullptr, &hit), TANDEM_ERROR_NULL_POINTER, "input");
  require_error(tandem_ray_cast_shape(&circle, &ray, nullptr), TANDEM_ERROR_NULL_POINTER, "out");
  require_error(tandem_ray_cast_shape(nullptr, &ray, &hit), TANDEM_ERROR_NULL_POINTER, "shape");

  // Manifolds: a box resting on a segment, either order; a circle far away.
  const tandem_transform on = {{0, qt("0.55")}, tandem_rot_identity()};
  const tandem_transform at0 = {{0, 0}, tandem_rot_identity()};
  tandem_manifold mf{};
  REQUIRE(tandem_collide(&polygon, on, &segment, at0, &mf) == TANDEM_OK);
  CHECK(mf.point_count > 0);
  tandem_manifold flipped{};
  REQUIRE(tandem_collide(&segment, at0, &polygon, on, &flipped) == TANDEM_OK);
  CHECK(flipped.point_count == mf.point_count);
  CHECK(flipped.normal.y == -mf.normal.y);
  const tandem_transform far = {{qi(50), 0}, tandem_rot_identity()};
  REQUIRE(tandem_collide(&circle, far, &polygon, at0, &mf) == TANDEM_OK);
  CHECK(mf.point_count == 0);
  require_error(tandem_collide(&circle, far, &unknown, at0, &mf), TANDEM_ERROR_INVALID_ARGUMENT, "b.type");
  require_error(tandem_collide(&circle, far, &polygon, at0, nullptr), TANDEM_ERROR_NULL_POINTER, "out_manifold");
}

TEST_CASE("geometry: distance, shape cast, sweeps and time of impact equal C++", "[capi][geometry]") {
  using namespace tandem;
  const tandem_shape_geometry circle = geometry(TANDEM_SHAPE_CIRCLE);
  const tandem_shape_geometry polygon = geometry(TANDEM_SHAPE_POLYGON);
  tandem_shape_proxy pa{}, pb{};
  REQUIRE(tandem_make_shape_proxy(&polygon, &pa) == TANDEM_OK);
  REQUIRE(tandem_make_shape_proxy(&circle, &pb) == TANDEM_OK);
  CHECK(pa.count == polygon.polygon.count);
  CHECK(pb.count == 1);
  CHECK(pb.radius == circle.circle.radius);
  tandem_shape_proxy seg{}, cap{};
  const tandem_shape_geometry segment = geometry(TANDEM_SHAPE_SEGMENT);
  const tandem_shape_geometry capsule = geometry(TANDEM_SHAPE_CAPSULE);
  REQUIRE(tandem_make_shape_proxy(&segment, &seg) == TANDEM_OK);
  REQUIRE(tandem_make_shape_proxy(&capsule, &cap) == TANDEM_OK);
  CHECK(seg.count == 2);
  CHECK(cap.radius == capsule.capsule.radius);
  const tandem_shape_geometry chain = geometry(TANDEM_SHAPE_CHAIN_SEGMENT);
  require_error(tandem_make_shape_proxy(&chain, &pa), TANDEM_ERROR_INVALID_ARGUMENT, "chain segment");
  REQUIRE(tandem_make_shape_proxy(&polygon, &pa) == TANDEM_OK);
  const tandem_vec2 pts[2] = {v2(0, 0), v2(1, 0)};
  tandem_shape_proxy line{};
  REQUIRE(tandem_make_proxy(pts, 2, qt("0.1"), &line) == TANDEM_OK);
  CHECK(line.count == 2);
  CHECK(line.points[1].x == qi(1));
  require_error(tandem_make_proxy(nullptr, 2, 0, &line), TANDEM_ERROR_NULL_POINTER, "points");
  require_error(tandem_make_proxy(pts, 2, 0, nullptr), TANDEM_ERROR_NULL_POINTER, "out_proxy");

  // The C++ proxies of the same shapes.
  Polygon cpoly;
  REQUIRE(make_offset_box(Q32::from_ratio(3, 4), Q32::from_ratio(1, 2), Vec2{Q32{}, parse_q32("0.1").value},
                          parse_q32("0.2").value, Q32{}, &cpoly)
              .ok());
  const ShapeProxy cpa = make_proxy(cpoly);
  const ShapeProxy cpb = make_proxy(Circle{cpp(circle.circle.center), Q32::from_raw(circle.circle.radius)});
  const tandem_transform at0 = {{0, 0}, tandem_rot_identity()};
  const tandem_transform right = {{qi(4), qi(1)}, tandem_rot_from_angle(qt("0.4"))};
  const Transform c0{}, cright{vec2(4, 1), rot_from_angle(parse_q32("0.4").value)};

  tandem_distance_input din;
  std::memset(&din, 0, sizeof din);
  din.proxy_a = pa, din.proxy_b = pb, din.transform_a = at0, din.transform_b = right, din.use_radii = true;
  tandem_distance_output dout{};
  REQUIRE(tandem_shape_distance(&din, &dout) == TANDEM_OK);
  const DistanceOutput cd = shape_distance(DistanceInput{cpa, cpb, c0, cright, true});
  CHECK(dout.distance == cd.distance.raw);
  CHECK(dout.point_b.x == cd.point_b.x.raw);
  CHECK(dout.iterations == cd.iterations);
  CHECK(dout.distance > qi(2));
  require_error(tandem_shape_distance(nullptr, &dout), TANDEM_ERROR_NULL_POINTER, "input");
  require_error(tandem_shape_distance(&din, nullptr), TANDEM_ERROR_NULL_POINTER, "out");
  din.proxy_b.count = 9;
  require_error(tandem_shape_distance(&din, &dout), TANDEM_ERROR_INVALID_ARGUMENT, "proxy_b.count 9");

  tandem_shape_cast_input cin;
  std::memset(&cin, 0, sizeof cin);
  cin.proxy_a = pa, cin.proxy_b = pb, cin.transform_a = at0, cin.transform_b = right;
  cin.translation_b = v2(-8, -2), cin.max_fraction = qi(1);
  tandem_cast_output cout{};
  REQUIRE(tandem_shape_cast(&cin, &cout) == TANDEM_OK);
  const CastOutput cc = shape_cast(ShapeCastInput{cpa, cpb, c0, cright, vec2(-8, -2), Q32::one(), false});
  CHECK(cout.hit);
  CHECK(cout.fraction == cc.fraction.raw);
  CHECK(cout.normal.x == cc.normal.x.raw);
  cin.proxy_a.count = 0;
  require_error(tandem_shape_cast(&cin, &cout), TANDEM_ERROR_INVALID_ARGUMENT, "proxy_a.count 0");
  require_error(tandem_shape_cast(nullptr, &cout), TANDEM_ERROR_NULL_POINTER, "input");

  // Sweeps and time of impact: the circle flies through the box in one step.
  tandem_sweep sa, sb;
  std::memset(&sa, 0, sizeof sa);
  std::memset(&sb, 0, sizeof sb);
  sa.q1 = sa.q2 = tandem_rot_identity();
  sb.c1 = v2(-5, 0), sb.c2 = v2(5, 0), sb.q1 = tandem_rot_identity(), sb.q2 = tandem_rot_from_angle(qi(1));
  tandem_transform mid{};
  REQUIRE(tandem_sweep_transform(&sb, qt("0.5"), &mid) == TANDEM_OK);
  const Sweep csb{Vec2{}, vec2(-5, 0), vec2(5, 0), rot_identity(), rot_from_angle(Q32::one())};
  const Transform cmid = sweep_transform(csb, Q32::from_ratio(1, 2));
  CHECK(mid.p.x == cmid.p.x.raw);
  CHECK(mid.q.s == cmid.q.s.raw);
  require_error(tandem_sweep_transform(nullptr, 0, &mid), TANDEM_ERROR_NULL_POINTER, "sweep");
  require_error(tandem_sweep_transform(&sb, 0, nullptr), TANDEM_ERROR_NULL_POINTER, "out_transform");
  tandem_toi_input tin;
  std::memset(&tin, 0, sizeof tin);
  tin.proxy_a = pa, tin.proxy_b = pb, tin.sweep_a = sa, tin.sweep_b = sb, tin.max_fraction = qi(1);
  tandem_toi_output tout{};
  REQUIRE(tandem_time_of_impact(&tin, &tout) == TANDEM_OK);
  const Sweep csa{Vec2{}, Vec2{}, Vec2{}, rot_identity(), rot_identity()};
  const ToiOutput ct = time_of_impact(ToiInput{cpa, cpb, csa, csb, Q32::one()});
  CHECK(tout.state == TANDEM_TOI_HIT);
  CHECK(tout.state == static_cast<int32_t>(ct.state));
  CHECK(tout.fraction == ct.fraction.raw);
  CHECK(tout.fraction > 0);
  CHECK(tout.fraction < qt("0.5"));
  require_error(tandem_time_of_impact(&tin, nullptr), TANDEM_ERROR_NULL_POINTER, "out");
  tin.proxy_a.count = -1;
  require_error(tandem_time_of_impact(&tin, &tout), TANDEM_ERROR_INVALID_ARGUMENT, "proxy_a.count");
}
