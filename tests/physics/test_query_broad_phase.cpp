// Tests for queries through the broad phase (physics/query.cpp,
// physics/broad_phase_query.cpp): on seeded random worlds — every shape kind,
// static, kinematic, dynamic, sleeping and disabled bodies, sensors, filter
// layers — every query under every broad phase must give exactly the results,
// in the same order, of the reference path that visits every shape
// (BroadPhase::query_brute_force), after steps and after changes made between
// steps (teleports, creation, destruction, enable/disable, a change of broad
// phase) with no step in between. A twin world that is never queried must
// stay bit-identical to the queried one.
#include <catch2/catch.hpp>

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "physics/tandem.h"
#include "physics/world.h"
#include "tests/test_world.h"

using namespace tandem;

namespace {

using Rng = std::mt19937;

const Q32 k_dt = Q32::from_ratio(1, 60);  // s

uint64_t draw64(Rng* rng) { return (static_cast<uint64_t>((*rng)()) << 32) | (*rng)(); }

/// Uniform-ish integer in [lo, hi] (modulo of a fully specified generator).
int64_t draw(Rng* rng, int64_t lo, int64_t hi) {
  return lo + static_cast<int64_t>(draw64(rng) % static_cast<uint64_t>(hi - lo + 1));
}

/// Metres in [lo_mm, hi_mm] millimetres, at raw resolution.
Q32 metres(Rng* rng, int64_t lo_mm, int64_t hi_mm) {
  const int64_t per_mm = (int64_t{1} << 32) / 1000;
  return Q32::from_raw(draw(rng, lo_mm * per_mm, hi_mm * per_mm));
}

Vec2 point_in(Rng* rng, int64_t half_mm) { return {metres(rng, -half_mm, half_mm), metres(rng, -half_mm, half_mm)}; }

Rot random_rot(Rng* rng) { return rot_from_angle(metres(rng, -3142, 3142)); }

/// A random shape on body b (segments and chains only on static bodies).
void add_random_shape(BodyId b, bool is_static, Rng* rng, std::vector<ShapeId>* shapes) {
  ShapeDef sd = default_shape_def();
  sd.filter.category_bits = static_cast<uint64_t>(draw(rng, 1, 3));
  sd.is_sensor = draw(rng, 0, 9) == 0;
  const int64_t kind = draw(rng, 0, is_static ? 5 : 3);
  Result<ShapeId> made;
  if (kind == 0) {
    made = create_circle_shape(b, sd, Circle{point_in(rng, 300), metres(rng, 100, 900)});
  } else if (kind == 1) {
    const Vec2 c = point_in(rng, 200);
    made = create_capsule_shape(b, sd, Capsule{c, c + Vec2{metres(rng, 200, 1200), metres(rng, -600, 600)},
                                                metres(rng, 80, 500)});
  } else if (kind == 2 || kind == 3) {
    Polygon box;
    REQUIRE(make_offset_box(metres(rng, 100, 1000), metres(rng, 100, 1000), point_in(rng, 300), metres(rng, -3000, 3000),
                            kind == 3 ? metres(rng, 0, 200) : Q32::zero(), &box)
                .ok());
    made = create_polygon_shape(b, sd, box);
  } else if (kind == 4) {
    const Vec2 a = point_in(rng, 3000);
    made = create_segment_shape(b, sd, Segment{a, a + Vec2{metres(rng, 500, 4000), metres(rng, -2000, 2000)}});
  } else {
    std::vector<Vec2> points;
    Vec2 p = point_in(rng, 3000);
    for (int i = 0; i < 5; ++i) {
      points.push_back(p);
      p = p + Vec2{metres(rng, 800, 2000), metres(rng, -600, 600)};
    }
    std::vector<ShapeId> chain;
    sd.is_sensor = false;
    REQUIRE(create_chain_shapes(b, sd, points.data(), static_cast<int32_t>(points.size()), false, &chain).ok());
    shapes->insert(shapes->end(), chain.begin(), chain.end());
    return;
  }
  INFO(made.status.message);
  REQUIRE(made.ok());
  shapes->push_back(made.value);
}

struct Sim {
  UniqueWorld world;
  std::vector<BodyId> bodies;
  std::vector<ShapeId> shapes;
};

void add_random_body(Sim* sim, Rng* rng) {
  BodyDef bd = default_body_def();
  const int64_t type = draw(rng, 0, 9);
  bd.type = type < 2 ? BodyType::static_body : (type < 3 ? BodyType::kinematic_body : BodyType::dynamic_body);
  bd.position = {metres(rng, -25000, 25000), metres(rng, -15000, 25000)};
  bd.rotation = random_rot(rng);
  if (bd.type == BodyType::kinematic_body) bd.angular_velocity = metres(rng, -1000, 1000);
  bd.is_enabled = draw(rng, 0, 19) != 0;
  Result<BodyId> b = create_body(sim->world.id, bd);
  REQUIRE(b.ok());
  sim->bodies.push_back(b.value);
  const int64_t count = draw(rng, 1, 2);
  for (int64_t i = 0; i < count; ++i) add_random_shape(b.value, bd.type == BodyType::static_body, rng, &sim->shapes);
}

void build(Sim* sim, BroadPhaseKind kind, uint64_t seed) {
  WorldDef def = default_world_def();
  def.broad_phase = kind;
  sim->world = test_world::require_world(def);
  Rng rng(static_cast<uint32_t>(seed));
  // A container: ground and two walls.
  BodyDef ground = default_body_def();
  ground.position = {0_q32, Q32(-20)};
  Result<BodyId> g = create_body(sim->world.id, ground);
  REQUIRE(g.ok());
  Polygon slab;
  REQUIRE(make_box(Q32(40), 1_q32, &slab).ok());
  REQUIRE(create_polygon_shape(g.value, default_shape_def(), slab).ok());
  Polygon wall;
  REQUIRE(make_offset_box(1_q32, Q32(30), {Q32(-40), Q32(30)}, Q32::zero(), Q32::zero(), &wall).ok());
  REQUIRE(create_polygon_shape(g.value, default_shape_def(), wall).ok());
  REQUIRE(make_offset_box(1_q32, Q32(30), {Q32(40), Q32(30)}, Q32::zero(), Q32::zero(), &wall).ok());
  REQUIRE(create_polygon_shape(g.value, default_shape_def(), wall).ok());
  sim->bodies.push_back(g.value);
  for (int i = 0; i < 90; ++i) add_random_body(sim, &rng);
}

/// One change between steps, the same for every Sim given equal generators.
void mutate(Sim* sim, Rng* rng) {
  const int64_t what = draw(rng, 0, 7);
  const BodyId b = sim->bodies[static_cast<size_t>(draw(rng, 1, static_cast<int64_t>(sim->bodies.size()) - 1))];
  switch (what) {
    case 0:
    case 1:
      if (body_is_valid(b)) (void)body_set_transform(b, point_in(rng, 25000), random_rot(rng));
      break;
    case 2: add_random_body(sim, rng); break;
    case 3:
      if (body_is_valid(b)) REQUIRE(destroy_body(b).ok());
      break;
    case 4: {
      const ShapeId s = sim->shapes[static_cast<size_t>(draw(rng, 0, static_cast<int64_t>(sim->shapes.size()) - 1))];
      if (shape_is_valid(s)) (void)destroy_shape(s);  // may be refused (chain rules); either way consistent
      break;
    }
    case 5:
      if (body_is_valid(b)) REQUIRE(body_set_enabled(b, !body_is_enabled(b)).ok());
      break;
    case 6:
      if (body_is_valid(b)) (void)body_set_awake(b, false);
      break;
    default: {
      const auto kind = static_cast<BroadPhaseKind>(draw(rng, 0, 3));
      REQUIRE(world_set_broad_phase(sim->world.id, kind).ok());
      break;
    }
  }
}

/// Mostly where bodies pile up (x within ±40 m, y from −22 to 5 m), sometimes
/// anywhere within ±45 m.
Vec2 near_pile(Rng* rng) {
  if (draw(rng, 0, 7) == 0) return point_in(rng, 45000);
  return {metres(rng, -40000, 40000), metres(rng, -22000, 5000)};
}

QueryFilter random_filter(Rng* rng) {
  QueryFilter f;
  f.category_bits = static_cast<uint64_t>(draw(rng, 1, 3));
  const int64_t m = draw(rng, 0, 3);
  f.mask_bits = m == 0 ? UINT64_MAX : static_cast<uint64_t>(m);
  f.include_sensors = draw(rng, 0, 1) != 0;
  return f;
}

bool same_hit(const RayHit& a, const RayHit& b) {
  return a.hit == b.hit && a.shape == b.shape && a.point.x == b.point.x && a.point.y == b.point.y &&
         a.normal.x == b.normal.x && a.normal.y == b.normal.y && a.fraction == b.fraction;
}

std::string describe(const std::vector<ShapeId>& ids) {
  std::string s;
  for (const ShapeId& id : ids) s += std::to_string(id.index1) + " ";
  return s;
}

struct Totals {
  int64_t queries = 0;
  int64_t results = 0;  ///< shapes or hits reported (both paths agree)
  int64_t closest_hits = 0;
};

/// Runs `count` random queries through the broad phase and the reference
/// path and requires identical answers.
void compare_queries(WorldId w, Rng* rng, int count, Totals* totals) {
  World* world = find_world(w);
  REQUIRE(world != nullptr);
  const auto both = [&](auto&& run) {
    world->broad_phase.query_brute_force = false;
    auto fast = run();
    world->broad_phase.query_brute_force = true;
    auto slow = run();
    world->broad_phase.query_brute_force = false;
    return std::make_pair(fast, slow);
  };
  std::vector<RayHit> hits;
  std::vector<ShapeId> ids;
  for (int q = 0; q < count; ++q) {
    const QueryFilter filter = random_filter(rng);
    const Vec2 origin = near_pile(rng);
    Vec2 translation = point_in(rng, draw(rng, 0, 3) == 0 ? 80000 : 8000);
    if (draw(rng, 0, 9) == 0) translation = {Q32::zero(), translation.y};  // vertical
    if (draw(rng, 0, 19) == 0) translation = {};                           // a point ray
    ++totals->queries;
    INFO("query " << q << " origin " << origin.x.raw << "," << origin.y.raw << " translation " << translation.x.raw
                  << "," << translation.y.raw);

    const auto closest = both([&] { return world_cast_ray_closest(w, origin, translation, filter); });
    REQUIRE(closest.first.ok());
    REQUIRE(closest.second.ok());
    CHECK(same_hit(closest.first.value, closest.second.value));
    if (closest.second.value.hit) ++totals->closest_hits;

    const auto all = both([&] {
      REQUIRE(world_cast_ray_all(w, origin, translation, filter, &hits).ok());
      return hits;
    });
    REQUIRE(all.first.size() == all.second.size());
    for (size_t i = 0; i < all.first.size(); ++i) CHECK(same_hit(all.first[i], all.second[i]));
    totals->results += static_cast<int64_t>(all.second.size());

    const Vec2 c = near_pile(rng);
    const Vec2 h{metres(rng, 0, 6000), metres(rng, 0, 6000)};
    const AABB box{c - h, c + h};
    const auto boxes = both([&] {
      REQUIRE(world_overlap_aabb(w, box, filter, &ids).ok());
      return ids;
    });
    CHECK(describe(boxes.first) == describe(boxes.second));
    totals->results += static_cast<int64_t>(boxes.second.size());

    const auto points = both([&] {
      REQUIRE(world_overlap_point(w, c, filter, &ids).ok());
      return ids;
    });
    CHECK(describe(points.first) == describe(points.second));
    totals->results += static_cast<int64_t>(points.second.size());

    const Transform xf{c, random_rot(rng)};
    const Circle circle{point_in(rng, 500), metres(rng, 100, 3000)};
    const auto circles = both([&] {
      REQUIRE(world_overlap_circle(w, circle, xf, filter, &ids).ok());
      return ids;
    });
    CHECK(describe(circles.first) == describe(circles.second));
    const Capsule capsule{{Q32(-2), 0_q32}, {Q32(2), metres(rng, -1000, 1000)}, metres(rng, 100, 1500)};
    const auto capsules = both([&] {
      REQUIRE(world_overlap_capsule(w, capsule, xf, filter, &ids).ok());
      return ids;
    });
    CHECK(describe(capsules.first) == describe(capsules.second));
    Polygon polygon;
    REQUIRE(make_offset_box(metres(rng, 100, 4000), metres(rng, 100, 4000), point_in(rng, 500), metres(rng, -3000, 3000),
                            metres(rng, 0, 300), &polygon)
                .ok());
    const auto polygons = both([&] {
      REQUIRE(world_overlap_polygon(w, polygon, xf, filter, &ids).ok());
      return ids;
    });
    CHECK(describe(polygons.first) == describe(polygons.second));
    totals->results += static_cast<int64_t>(circles.second.size() + capsules.second.size() + polygons.second.size());
  }
}

/// Every body's pose and velocity, raw, to compare twins.
std::vector<int64_t> body_bits(const Sim& sim) {
  std::vector<int64_t> bits;
  for (const BodyId b : sim.bodies) {
    if (!body_is_valid(b)) {
      bits.push_back(-1);
      continue;
    }
    const Transform xf = body_transform(b);
    const Vec2 v = body_linear_velocity(b);
    bits.insert(bits.end(), {xf.p.x.raw, xf.p.y.raw, xf.q.c.raw, xf.q.s.raw, v.x.raw, v.y.raw,
                             body_is_awake(b) ? 1 : 0, body_is_enabled(b) ? 1 : 0});
  }
  return bits;
}

int32_t sleeping_bodies(const Sim& sim) {
  int32_t n = 0;
  for (const BodyId b : sim.bodies) n += body_is_valid(b) && body_is_enabled(b) && !body_is_awake(b) ? 1 : 0;
  return n;
}

}  // namespace

TEST_CASE("queries through every broad phase equal the brute-force path on random worlds", "[physics][query]") {
  const BroadPhaseKind kinds[] = {BroadPhaseKind::naive, BroadPhaseKind::sweep_and_prune, BroadPhaseKind::grid,
                                  BroadPhaseKind::tree};
  for (const uint64_t seed : {11u, 12u, 13u}) {
    for (const BroadPhaseKind kind : kinds) {
      INFO("seed " << seed << " broad phase " << static_cast<int>(kind));
      Sim queried, twin;
      build(&queried, kind, seed);
      build(&twin, kind, seed);
      Rng query_rng(static_cast<uint32_t>(seed * 7 + 1));
      Rng mutate_rng(static_cast<uint32_t>(seed * 13 + 5));
      Totals totals;
      int32_t most_asleep = 0;
      compare_queries(queried.world.id, &query_rng, 8, &totals);  // before any step
      for (int step = 0; step < 150; ++step) {
        if (step % 10 == 9) {
          // Changes with no step in between: queries before and after each.
          for (int m = 0; m < 3; ++m) {
            Rng copy = mutate_rng;
            mutate(&queried, &mutate_rng);
            mutate(&twin, &copy);
            compare_queries(queried.world.id, &query_rng, 3, &totals);
          }
        }
        (void)world_step(queried.world.id, k_dt);
        (void)world_step(twin.world.id, k_dt);
        if (step % 5 == 4) compare_queries(queried.world.id, &query_rng, 4, &totals);
        REQUIRE(body_bits(queried) == body_bits(twin));
        const int32_t asleep = sleeping_bodies(queried);
        most_asleep = asleep > most_asleep ? asleep : most_asleep;
      }
      // The worlds exercised what they should: many hits and overlaps, and
      // sleeping bodies at some point.
      CHECK(totals.queries > 200);
      CHECK(totals.closest_hits > totals.queries / 4);
      CHECK(totals.results > 4 * totals.queries);
      CHECK(most_asleep > 0);
    }
  }
}

TEST_CASE("a query sees a teleport, a creation and a destruction made after the step", "[physics][query]") {
  for (const BroadPhaseKind kind : {BroadPhaseKind::naive, BroadPhaseKind::sweep_and_prune, BroadPhaseKind::grid,
                                    BroadPhaseKind::tree}) {
    INFO("broad phase " << static_cast<int>(kind));
    WorldDef def = default_world_def();
    def.broad_phase = kind;
    UniqueWorld world = test_world::require_world(def);
    BodyDef bd = default_body_def();
    bd.type = BodyType::dynamic_body;
    Result<BodyId> ball = create_body(world.id, bd);
    REQUIRE(ball.ok());
    REQUIRE(create_circle_shape(ball.value, default_shape_def(), Circle{{}, 1_q32}).ok());
    (void)world_step(world.id, k_dt);
    const Vec2 down{0_q32, Q32(-20)};
    Result<RayHit> hit = world_cast_ray_closest(world.id, {0_q32, Q32(10)}, down);
    REQUIRE(hit.value.hit);
    // Teleported 50 m away: the old place is empty, the new one hit.
    REQUIRE(body_set_transform(ball.value, {Q32(50), 0_q32}, rot_identity()).ok());
    CHECK_FALSE(world_cast_ray_closest(world.id, {0_q32, Q32(10)}, down).value.hit);
    hit = world_cast_ray_closest(world.id, {Q32(50), Q32(10)}, down);
    CHECK(hit.value.hit);
    CHECK(hit.value.shape.index1 != 0);
    // A new static box far away is found at once; destroyed, it is gone.
    Result<BodyId> box = create_body(world.id, default_body_def());
    REQUIRE(box.ok());
    Polygon square;
    REQUIRE(make_box(1_q32, 1_q32, &square).ok());
    REQUIRE(body_set_transform(box.value, {Q32(-300), Q32(-300)}, rot_identity()).ok());
    Result<ShapeId> made = create_polygon_shape(box.value, default_shape_def(), square);
    REQUIRE(made.ok());
    std::vector<ShapeId> found;
    REQUIRE(world_overlap_point(world.id, {Q32(-300), Q32(-300)}, QueryFilter{}, &found).ok());
    REQUIRE(found.size() == 1);
    CHECK(found[0] == made.value);
    REQUIRE(body_set_enabled(box.value, false).ok());
    REQUIRE(world_overlap_point(world.id, {Q32(-300), Q32(-300)}, QueryFilter{}, &found).ok());
    CHECK(found.empty());
    REQUIRE(body_set_enabled(box.value, true).ok());
    REQUIRE(world_overlap_point(world.id, {Q32(-300), Q32(-300)}, QueryFilter{}, &found).ok());
    CHECK(found.size() == 1);
    REQUIRE(destroy_body(box.value).ok());
    REQUIRE(world_overlap_point(world.id, {Q32(-300), Q32(-300)}, QueryFilter{}, &found).ok());
    CHECK(found.empty());
  }
}

TEST_CASE("segment_overlaps_box is exact at touching and missing boxes", "[physics][query]") {
  const AABB box{{0_q32, 0_q32}, {1_q32, 1_q32}};
  // Through, touching a corner, touching an edge, just missing a corner.
  CHECK(segment_overlaps_box({Q32(-1), 0.5_q32}, {Q32(2), 0.5_q32}, box));
  CHECK(segment_overlaps_box({Q32(-1), 0_q32}, {1_q32, Q32(2)}, box));   // through the corner (0, 1)
  CHECK(segment_overlaps_box({Q32(-1), 1_q32}, {Q32(2), 1_q32}, box));   // along the top edge
  const Q32 ulp = Q32::from_raw(1);
  CHECK_FALSE(segment_overlaps_box({Q32(-1), ulp}, {1_q32, Q32(2) + ulp}, box));
  // Diagonal past the corner (1, 1): inside the segment's bounds, outside the box.
  CHECK_FALSE(segment_overlaps_box({0.5_q32, 1.5_q32 + ulp}, {1.5_q32 + ulp, 0.5_q32}, box));
  CHECK(segment_overlaps_box({0.5_q32, 1.5_q32}, {1.5_q32, 0.5_q32}, box));  // touches (1, 1)
  // A point.
  CHECK(segment_overlaps_box({1_q32, 0.5_q32}, {1_q32, 0.5_q32}, box));
  CHECK_FALSE(segment_overlaps_box({1_q32 + ulp, 0.5_q32}, {1_q32 + ulp, 0.5_q32}, box));
}
