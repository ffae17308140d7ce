// Tests for physics/broad_phase*.cpp: every broad phase (naive, sweep and
// prune, grid, tree) must give exactly the naive pair list, step after step,
// in random scenes (sizes 0…400, static and moving, rotating boxes, sensors,
// filters, kinematic and disabled bodies, a huge ground, shapes created,
// destroyed and teleported mid-run) and in crafted edge cases (boxes touching
// exactly at the fattened boundary, one raw unit apart, negative coordinates,
// grid cell boundaries, the world's corners); switching kinds mid-run gives a
// bit-identical simulation; settings, stats, the custom filter, the tree's
// structure and the buffers' stability after warm-up.
//
// Allocation: test_world.cpp owns this binary's counting operator new (its
// counters are private to that file), so here "no allocation per step" is
// checked as "no broad-phase buffer changes its data pointer or capacity
// over warmed-up steps", for each kind; test_world.cpp's counting test covers
// the whole step for the default kind.
#include <catch2/catch.hpp>

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "physics/broad_phase.h"
#include "physics/tandem.h"
#include "physics/world.h"
#include "physics_test_support.h"

using namespace tandem;
using namespace tandem::literals;
using namespace tandem::test_support;

namespace {

constexpr BroadPhaseKind k_kinds[4] = {BroadPhaseKind::naive, BroadPhaseKind::sweep_and_prune, BroadPhaseKind::grid,
                                       BroadPhaseKind::tree};

const char* kind_name(BroadPhaseKind k) {
  switch (k) {
    case BroadPhaseKind::naive: return "naive";
    case BroadPhaseKind::sweep_and_prune: return "sweep_and_prune";
    case BroadPhaseKind::grid: return "grid";
    case BroadPhaseKind::tree: return "tree";
  }
  return "?";
}

/// A raw Q32 in [lo, hi] metres from the generator (integers only).
Q32 random_q32(std::mt19937_64& rng, int64_t lo_m, int64_t hi_m) {
  const uint64_t span = static_cast<uint64_t>(hi_m - lo_m) << 32;
  const uint64_t r = rng() % (span + 1);
  return Q32::from_raw((lo_m * (int64_t{1} << 32)) + static_cast<int64_t>(r));
}

WorldDef world_def_with(BroadPhaseKind kind, bool gravity = true) {
  WorldDef def = default_world_def();
  def.broad_phase = kind;
  if (!gravity) def.gravity = {};
  return def;
}

std::vector<uint64_t> pair_keys(WorldId id) {
  std::vector<uint64_t> keys;
  for (const ShapePair& p : find_world(id)->broad_phase.pairs) keys.push_back(shape_pair_key(p.shape_a, p.shape_b));
  return keys;
}

/// Checks a pair list is strictly ascending (sorted, no duplicates) with
/// lower < higher.
void check_sorted_unique(const std::vector<ShapePair>& pairs) {
  for (size_t i = 0; i < pairs.size(); ++i) {
    REQUIRE(pairs[i].shape_a < pairs[i].shape_b);
    if (i > 0) {
      REQUIRE(shape_pair_key(pairs[i - 1].shape_a, pairs[i - 1].shape_b) <
              shape_pair_key(pairs[i].shape_a, pairs[i].shape_b));
    }
  }
}

/// Adds one random body with one or two random shapes; the same generator
/// state gives the same calls in every world.
void add_random_body(WorldId id, std::mt19937_64& rng, int64_t half_extent_m) {
  BodyDef def = default_body_def();
  const uint64_t type_roll = rng() % 10;
  def.type = type_roll < 7 ? BodyType::dynamic_body
                           : (type_roll < 9 ? BodyType::static_body : BodyType::kinematic_body);
  def.position = {random_q32(rng, -half_extent_m, half_extent_m), random_q32(rng, -half_extent_m, half_extent_m)};
  def.rotation = rot_from_angle(random_q32(rng, -3, 3));
  if (def.type != BodyType::static_body) {
    def.linear_velocity = {random_q32(rng, -3, 3), random_q32(rng, -3, 3)};
    def.angular_velocity = random_q32(rng, -4, 4);  // rotating boxes change their AABB size
  }
  def.is_enabled = rng() % 20 != 0;
  Result<BodyId> body = create_body(id, def);
  REQUIRE(body.ok());
  const int shapes = 1 + static_cast<int>(rng() % 2);
  for (int k = 0; k < shapes; ++k) {
    ShapeDef sd = default_shape_def();
    sd.is_sensor = rng() % 12 == 0;
    if (rng() % 6 == 0) {
      sd.filter.category_bits = uint64_t{1} << (rng() % 3);
      sd.filter.mask_bits = rng() % 2 == 0 ? UINT64_MAX : (uint64_t{1} << (rng() % 3));
      sd.filter.group_index = static_cast<int32_t>(rng() % 5) - 2;
    }
    const Vec2 offset = {random_q32(rng, -1, 1), random_q32(rng, -1, 1)};
    const uint64_t geometry = rng() % 10;
    Result<ShapeId> r;
    if (geometry < 4) {
      Circle c{offset, Q32::from_raw(static_cast<int64_t>((rng() % (uint64_t{3} << 31)) + (uint64_t{1} << 29)))};
      r = create_circle_shape(body.value, sd, c);
    } else if (geometry < 8) {
      Polygon box;
      REQUIRE(make_offset_box(random_q32(rng, 0, 1) + 0.1_q32, random_q32(rng, 0, 1) + 0.1_q32, offset,
                              random_q32(rng, -3, 3), Q32::zero(), &box)
                  .ok());
      r = create_polygon_shape(body.value, sd, box);
    } else if (geometry < 9) {
      Capsule cap{offset, offset + Vec2{random_q32(rng, 0, 1) + 0.1_q32, random_q32(rng, -1, 1)}, 0.2_q32};
      r = create_capsule_shape(body.value, sd, cap);
    } else {
      Segment seg{offset, offset + Vec2{random_q32(rng, 1, 3), random_q32(rng, -1, 1)}};
      r = create_segment_shape(body.value, sd, seg);
    }
    REQUIRE(r.ok());
  }
}

/// A random scene: a huge static ground (an outlier for the grid), then n
/// random bodies.
void build_random_scene(WorldId id, std::mt19937_64& rng, int n, int64_t half_extent_m) {
  BodyDef gd = default_body_def();
  gd.position = {0_q32, Q32::from_int(-half_extent_m - 2)};
  Result<BodyId> g = create_body(id, gd);
  REQUIRE(g.ok());
  Polygon ground;
  REQUIRE(make_box(Q32::from_int(half_extent_m * 4 + 50), 1_q32, &ground).ok());
  REQUIRE(create_polygon_shape(g.value, default_shape_def(), ground).ok());
  for (int i = 0; i < n; ++i) add_random_body(id, rng, half_extent_m);
}

/// Random mid-run changes: destroy a body or a shape, add a body, teleport a
/// body, flip enabled state. Same generator state → same calls everywhere.
void random_edit(WorldId id, std::mt19937_64& rng, int64_t half_extent_m) {
  std::vector<BodyId> bodies(static_cast<size_t>(world_bodies(id, nullptr, 0)));
  world_bodies(id, bodies.data(), static_cast<int32_t>(bodies.size()));
  const uint64_t what = rng() % 6;
  const uint64_t pick = rng();
  if (bodies.size() <= 1 || what == 0) {
    add_random_body(id, rng, half_extent_m);
    return;
  }
  const BodyId b = bodies[1 + pick % (bodies.size() - 1)];  // never the ground (index 0)
  switch (what) {
    case 1: REQUIRE(destroy_body(b).ok()); break;
    case 2: {
      ShapeId shapes[4];
      const int32_t count = body_shapes(b, shapes, 4);
      if (count > 0) REQUIRE(destroy_shape(shapes[0]).ok());
      break;
    }
    case 3:
      REQUIRE(body_set_transform(b, {random_q32(rng, -half_extent_m, half_extent_m),
                                     random_q32(rng, -half_extent_m, half_extent_m)},
                                 rot_from_angle(random_q32(rng, -3, 3)))
                  .ok());
      break;
    case 4:
      if (body_is_enabled(b)) {
        REQUIRE(body_set_enabled(b, false).ok());
      } else {
        REQUIRE(body_set_enabled(b, true).ok());
      }
      break;
    default: add_random_body(id, rng, half_extent_m); break;
  }
}

/// Bit-level state of every live body (transform and velocities), in body
/// order.
std::vector<int64_t> body_bits(WorldId id) {
  std::vector<BodyId> bodies(static_cast<size_t>(world_bodies(id, nullptr, 0)));
  world_bodies(id, bodies.data(), static_cast<int32_t>(bodies.size()));
  std::vector<int64_t> bits;
  for (const BodyId b : bodies) {
    const Transform xf = body_transform(b);
    const Vec2 v = body_linear_velocity(b);
    bits.insert(bits.end(), {xf.p.x.raw, xf.p.y.raw, xf.q.c.raw, xf.q.s.raw, v.x.raw, v.y.raw,
                             body_angular_velocity(b).raw});
  }
  return bits;
}

/// Contact keys and impulses, in contact order.
std::vector<int64_t> contact_bits(WorldId id) {
  std::vector<int64_t> bits;
  for (const Contact& c : find_world(id)->contacts) {
    bits.push_back(static_cast<int64_t>(contact_key(c)));
    bits.push_back(c.manifold.point_count);
    for (int32_t i = 0; i < c.manifold.point_count; ++i) {
      bits.push_back(c.normal_impulse[static_cast<size_t>(i)].raw);
      bits.push_back(c.tangent_impulse[static_cast<size_t>(i)].raw);
    }
  }
  return bits;
}

}  // namespace

TEST_CASE("every broad phase gives the naive pair list in random scenes with edits", "[physics][broad_phase]") {
  const int sizes[] = {0, 1, 2, 5, 20, 80, 250};
  for (const int n : sizes) {
    for (uint64_t seed = 1; seed <= 2; ++seed) {
      const int64_t half_extent = 3 + n / 12;  // crowded: many overlaps
      INFO("n = " << n << ", seed = " << seed);
      std::vector<ScopedWorld*> worlds;
      ScopedWorld w0(world_def_with(k_kinds[0])), w1(world_def_with(k_kinds[1])), w2(world_def_with(k_kinds[2])),
          w3(world_def_with(k_kinds[3]));
      ScopedWorld* all[4] = {&w0, &w1, &w2, &w3};
      for (ScopedWorld* w : all) {
        std::mt19937_64 rng(seed * 7919 + static_cast<uint64_t>(n));
        build_random_scene(w->id, rng, n, half_extent);
      }
      std::mt19937_64 edits[4] = {std::mt19937_64(seed), std::mt19937_64(seed), std::mt19937_64(seed),
                                  std::mt19937_64(seed)};
      for (int step = 0; step < 40; ++step) {
        INFO("step " << step);
        for (ScopedWorld* w : all) REQUIRE(world_step(w->id, k_dt).ok());
        const std::vector<uint64_t> reference = pair_keys(w0.id);
        check_sorted_unique(find_world(w0.id)->broad_phase.pairs);
        for (int k = 1; k < 4; ++k) {
          INFO(kind_name(k_kinds[k]));
          CHECK(pair_keys(all[k]->id) == reference);
          const BroadPhaseStats stats = world_broad_phase_stats(all[k]->id);
          CHECK(stats.pairs == static_cast<int32_t>(reference.size()));
          // Pairs carried over between unchanged proxies were not tested again.
          CHECK(stats.pairs - stats.pairs_carried <= stats.candidate_pairs);
        }
        if (step % 3 == 1) {
          for (int k = 0; k < 4; ++k) random_edit(all[k]->id, edits[k], half_extent);
        }
        if (step % 10 == 9) REQUIRE(tree_validate(find_world(w3.id)->broad_phase.tree) >= 0);
      }
    }
  }
}

TEST_CASE("switching broad phase every few steps is bit-identical to naive only", "[physics][broad_phase]") {
  ScopedWorld reference(world_def_with(BroadPhaseKind::naive));
  ScopedWorld switching(world_def_with(BroadPhaseKind::naive));
  for (ScopedWorld* w : {&reference, &switching}) {
    std::mt19937_64 rng(42);
    build_random_scene(w->id, rng, 120, 8);
  }
  std::mt19937_64 edit_a(5), edit_b(5);
  for (int step = 0; step < 120; ++step) {
    INFO("step " << step);
    if (step % 7 == 0) REQUIRE(world_set_broad_phase(switching.id, k_kinds[(step / 7) % 4]).ok());
    REQUIRE(world_step(reference.id, k_dt).ok());
    REQUIRE(world_step(switching.id, k_dt).ok());
    REQUIRE(body_bits(switching.id) == body_bits(reference.id));
    REQUIRE(contact_bits(switching.id) == contact_bits(reference.id));
    if (step % 11 == 5) {
      random_edit(reference.id, edit_a, 8);
      random_edit(switching.id, edit_b, 8);
    }
  }
  CHECK(find_world(reference.id)->contacts.size() > 10u);
}

TEST_CASE("broad phases find pairs touching exactly at the fattened boundary", "[physics][broad_phase]") {
  // Two circles whose fattened boxes touch exactly (gap 2·k_speculative_distance)
  // form a pair; one raw unit farther they do not. Placed at many random
  // offsets (negative, positive, straddling grid cells) with random radii,
  // plus filler circles so the grid's cell size is not set by the pair alone.
  std::mt19937_64 rng(99);
  for (int trial = 0; trial < 60; ++trial) {
    const Q32 r1 = Q32::from_raw(static_cast<int64_t>(rng() % (uint64_t{1} << 32)) + (int64_t{1} << 29));
    const Q32 r2 = Q32::from_raw(static_cast<int64_t>(rng() % (uint64_t{1} << 32)) + (int64_t{1} << 29));
    const Vec2 p1 = {random_q32(rng, -50, 50), random_q32(rng, -50, 50)};
    const bool vertical = rng() % 2 == 0;
    const int64_t extra = trial % 2;  // 0: touching, 1: one raw unit apart
    const Q32 gap = r1 + r2 + k_speculative_distance * 2 + Q32::from_raw(extra);
    const Vec2 p2 = vertical ? Vec2{p1.x + random_q32(rng, -1, 1) / 4, p1.y - gap}
                             : Vec2{p1.x - gap, p1.y + random_q32(rng, -1, 1) / 4};
    for (const BroadPhaseKind kind : k_kinds) {
      INFO("trial " << trial << " " << kind_name(kind));
      ScopedWorld w(world_def_with(kind, false));
      const auto add = [&](Vec2 p, Q32 r, BodyType type) {
        BodyDef bd = default_body_def();
        bd.type = type;
        bd.position = p;
        Result<BodyId> b = create_body(w.id, bd);
        REQUIRE(b.ok());
        REQUIRE(create_circle_shape(b.value, default_shape_def(), Circle{{}, r}).ok());
      };
      add(p1, r1, BodyType::dynamic_body);
      add(p2, r2, trial % 3 == 0 ? BodyType::static_body : BodyType::dynamic_body);
      for (int k = 0; k < 12; ++k) add({Q32::from_int(200 + 3 * k), Q32::from_int(200)}, 0.3_q32, BodyType::dynamic_body);
      broad_phase_update_pairs(find_world(w.id));
      const std::vector<uint64_t> keys = pair_keys(w.id);
      const bool found = !keys.empty() && keys[0] == shape_pair_key(0, 1);
      CHECK(found == (extra == 0));
      CHECK(keys.size() == (extra == 0 ? 1u : 0u));
    }
  }
}

TEST_CASE("broad phases agree on crowded grids and at the world's corners", "[physics][broad_phase]") {
  // Equal circles on a lattice whose spacing equals the touching distance:
  // every neighbour pair sits exactly on the fattened boundary, and lattice
  // points fall on grid cell edges. Then the same at the world's corners
  // (±1e6 m), with shapes reaching past the bounds.
  struct Layout {
    Vec2 origin;
    Q32 spacing_extra;
  };
  const Layout layouts[] = {{{-3_q32, -3_q32}, Q32::zero()},
                            {{-999990_q32, -999990_q32}, Q32::zero()},
                            {{999980_q32, 999980_q32}, Q32::from_raw(1)},
                            {{-999990_q32, 999980_q32}, Q32::from_raw(-1)}};
  for (const Layout& layout : layouts) {
    std::vector<uint64_t> reference;
    for (const BroadPhaseKind kind : k_kinds) {
      INFO(kind_name(kind) << " at " << to_string(layout.origin.x));
      ScopedWorld w(world_def_with(kind, false));
      const Q32 r = 0.5_q32;
      const Q32 spacing = r * 2 + k_speculative_distance * 2 + layout.spacing_extra;
      for (int i = 0; i < 8; ++i) {
        for (int j = 0; j < 8; ++j) {
          BodyDef bd = default_body_def();
          bd.type = (i + j) % 4 == 0 ? BodyType::static_body : BodyType::dynamic_body;
          bd.position = layout.origin + Vec2{spacing * i, spacing * j};
          Result<BodyId> b = create_body(w.id, bd);
          REQUIRE(b.ok());
          REQUIRE(create_circle_shape(b.value, default_shape_def(), Circle{{}, r}).ok());
        }
      }
      // A big static box reaching past the world bounds near the lattice.
      BodyDef gd = default_body_def();
      gd.position = layout.origin - Vec2{2_q32, 2_q32};
      Result<BodyId> g = create_body(w.id, gd);
      REQUIRE(g.ok());
      Polygon box;
      REQUIRE(make_box(40_q32, 1.5_q32, &box).ok());
      REQUIRE(create_polygon_shape(g.value, default_shape_def(), box).ok());
      broad_phase_update_pairs(find_world(w.id));
      const std::vector<uint64_t> keys = pair_keys(w.id);
      if (kind == BroadPhaseKind::naive) {
        reference = keys;
        // Touching lattice: 2·8·7 neighbour pairs (minus static–static ones).
        if (layout.spacing_extra <= Q32::zero()) CHECK(keys.size() >= 100u);
        if (layout.spacing_extra > Q32::zero()) CHECK(keys.size() < 20u);
      } else {
        CHECK(keys == reference);
      }
    }
  }
}

TEST_CASE("broad phases handle empty and single-body worlds", "[physics][broad_phase]") {
  for (const BroadPhaseKind kind : k_kinds) {
    INFO(kind_name(kind));
    ScopedWorld empty(world_def_with(kind));
    for (int k = 0; k < 3; ++k) REQUIRE(world_step(empty.id, k_dt).ok());
    CHECK(world_broad_phase_stats(empty.id).proxies == 0);
    CHECK(world_broad_phase_stats(empty.id).pairs == 0);

    ScopedWorld one(world_def_with(kind));
    BodyDef bd = default_body_def();
    bd.type = BodyType::dynamic_body;
    Result<BodyId> b = create_body(one.id, bd);
    REQUIRE(b.ok());
    REQUIRE(create_circle_shape(b.value, default_shape_def(), Circle{{}, 0.5_q32}).ok());
    for (int k = 0; k < 3; ++k) REQUIRE(world_step(one.id, k_dt).ok());
    CHECK(world_broad_phase_stats(one.id).proxies == 1);
    CHECK(world_broad_phase_stats(one.id).pairs == 0);
    REQUIRE(destroy_body(b.value).ok());
    REQUIRE(world_step(one.id, k_dt).ok());
    CHECK(world_broad_phase_stats(one.id).proxies == 0);
  }
}

TEST_CASE("broad-phase selection: settings, refusals and reset", "[physics][broad_phase]") {
  ScopedWorld w;
  CHECK(world_broad_phase(w.id) == BroadPhaseKind::naive);
  for (const BroadPhaseKind kind : k_kinds) {
    REQUIRE(world_set_broad_phase(w.id, kind).ok());
    CHECK(world_broad_phase(w.id) == kind);
    CHECK(world_def(w.id).broad_phase == kind);
  }
  const Status bad = world_set_broad_phase(w.id, static_cast<BroadPhaseKind>(9));
  CHECK(bad.code == StatusCode::invalid_argument);
  CHECK(bad.message.find("world_set_broad_phase") != std::string::npos);
  CHECK(world_broad_phase(w.id) == BroadPhaseKind::tree);
  WorldDef def = default_world_def();
  def.broad_phase = static_cast<BroadPhaseKind>(-1);
  const Result<WorldId> refused = create_world(def);
  CHECK(refused.status.code == StatusCode::invalid_argument);
  CHECK(refused.status.message.find("broad_phase") != std::string::npos);
  CHECK(world_set_broad_phase(WorldId{}, BroadPhaseKind::grid).code == StatusCode::null_handle);
  CHECK(world_broad_phase(WorldId{}) == BroadPhaseKind::naive);
  CHECK(world_broad_phase_stats(WorldId{}).proxies == 0);

  // broad_phase_reset drops persistent state; the next update rebuilds it
  // and gives the same pairs.
  std::mt19937_64 rng(3);
  build_random_scene(w.id, rng, 60, 6);
  for (const BroadPhaseKind kind : {BroadPhaseKind::sweep_and_prune, BroadPhaseKind::tree}) {
    REQUIRE(world_set_broad_phase(w.id, kind).ok());
    REQUIRE(world_step(w.id, k_dt).ok());
    World* world = find_world(w.id);
    broad_phase_update_pairs(world);
    const std::vector<uint64_t> before = pair_keys(w.id);
    broad_phase_reset(world);
    CHECK(world->broad_phase.sap.endpoints.empty());
    CHECK(world->broad_phase.tree.root == -1);
    broad_phase_update_pairs(world);
    CHECK(pair_keys(w.id) == before);
  }
}

namespace {

struct LockProbe {
  WorldId world;
  int calls = 0;
  StatusCode set_result = StatusCode::ok;
};

/// Rejects pairs whose index sum is a multiple of 3 (a pure function of the
/// handles), and records what a change of broad phase from inside the step
/// returns.
bool sum_filter(ShapeId a, ShapeId b, void* context) {
  auto* probe = static_cast<LockProbe*>(context);
  ++probe->calls;
  probe->set_result = world_set_broad_phase(probe->world, BroadPhaseKind::grid).code;
  return (a.index1 + b.index1) % 3 != 0;
}

}  // namespace

TEST_CASE("custom filter: deterministic, after the category test, same for every kind", "[physics][broad_phase]") {
  std::vector<uint64_t> reference;
  for (const BroadPhaseKind kind : k_kinds) {
    INFO(kind_name(kind));
    ScopedWorld w(world_def_with(kind));
    std::mt19937_64 rng(11);
    build_random_scene(w.id, rng, 150, 7);
    LockProbe probe{w.id};
    REQUIRE(world_set_custom_filter(w.id, sum_filter, &probe).ok());
    REQUIRE(world_step(w.id, k_dt).ok());
    CHECK(probe.calls > 0);
    CHECK(probe.set_result == StatusCode::world_locked);  // refused while locked
    CHECK(world_broad_phase(w.id) == kind);
    const std::vector<uint64_t> keys = pair_keys(w.id);
    for (const uint64_t key : keys) {
      const uint64_t a = (key >> 32) + 1, b = (key & 0xFFFFFFFFu) + 1;  // index1 = index + 1
      CHECK((a + b) % 3 != 0);
    }
    if (kind == BroadPhaseKind::naive) {
      reference = keys;
    } else {
      CHECK(keys == reference);
    }
    REQUIRE(world_set_custom_filter(w.id, nullptr, nullptr).ok());
    REQUIRE(world_step(w.id, k_dt).ok());
    CHECK(world_broad_phase_stats(w.id).pairs > static_cast<int32_t>(keys.size()));
  }
}

TEST_CASE("broad-phase stats are consistent", "[physics][broad_phase]") {
  for (const BroadPhaseKind kind : k_kinds) {
    INFO(kind_name(kind));
    ScopedWorld w(world_def_with(kind));
    std::mt19937_64 rng(17);
    build_random_scene(w.id, rng, 100, 6);
    for (int k = 0; k < 30; ++k) REQUIRE(world_step(w.id, k_dt).ok());
    const BroadPhaseStats s = world_broad_phase_stats(w.id);
    const World* world = find_world(w.id);
    int32_t expected_proxies = 0;
    for (int32_t i = 0; i < id_pool_capacity(world->shape_pool); ++i) {
      if (world->broad_phase.shape_kind[static_cast<size_t>(i)] != k_proxy_none) ++expected_proxies;
    }
    CHECK(s.proxies == expected_proxies);
    CHECK(s.pairs == static_cast<int32_t>(world->broad_phase.pairs.size()));
    CHECK(s.pairs > 0);
    CHECK(s.pairs <= s.candidate_pairs);
    CHECK(s.touching_pairs > 0);
    CHECK(s.touching_pairs <= s.pairs);
    CHECK(s.update_nanoseconds > 0);
    if (kind == BroadPhaseKind::naive) {
      CHECK(s.candidate_pairs <= s.proxies * (s.proxies - 1) / 2);
    }
  }
}

TEST_CASE("broad-phase buffers are stable once warmed up, for every kind", "[physics][broad_phase]") {
  for (const BroadPhaseKind kind : k_kinds) {
    INFO(kind_name(kind));
    ScopedWorld w(world_def_with(kind));
    std::mt19937_64 rng(23);
    build_random_scene(w.id, rng, 120, 6);
    for (int k = 0; k < 120; ++k) REQUIRE(world_step(w.id, k_dt).ok());
    const BroadPhase& bp = find_world(w.id)->broad_phase;
    const auto snapshot = [&bp]() {
      return std::vector<const void*>{bp.pairs.data(),         bp.unsorted.data(),
                                      bp.proxies.data(),       bp.fat_bounds.data(),
                                      bp.shape_fat.data(),     bp.counts.data(),
                                      bp.sap.endpoints.data(), bp.sap.merged.data(),
                                      bp.sap.active_dynamic.data(), bp.sap.active_other.data(),
                                      bp.grid.entries.data(),  bp.grid.bucket_start.data(),
                                      bp.grid.proxy_cell.data(), bp.grid.outliers.data(),
                                      bp.tree.nodes.data(),    bp.tree.stack.data()};
    };
    const std::vector<const void*> before = snapshot();
    for (int k = 0; k < 90; ++k) REQUIRE(world_step(w.id, k_dt).ok());
    CHECK(snapshot() == before);
  }
}

TEST_CASE("the tree stays valid and shallow under churn", "[physics][broad_phase]") {
  ScopedWorld w(world_def_with(BroadPhaseKind::tree));
  std::mt19937_64 rng(31);
  build_random_scene(w.id, rng, 300, 20);
  std::mt19937_64 edits(8);
  for (int step = 0; step < 60; ++step) {
    REQUIRE(world_step(w.id, k_dt).ok());
    for (int k = 0; k < 4; ++k) random_edit(w.id, edits, 20);
    const DynamicTree& tree = find_world(w.id)->broad_phase.tree;
    const int32_t leaves = tree_validate(tree);
    REQUIRE(leaves == world_broad_phase_stats(w.id).proxies);
    // A balanced binary tree of n leaves has height ≈ log2 n; allow 3×.
    int32_t log2n = 0;
    while ((int32_t{1} << log2n) < leaves) ++log2n;
    if (tree.root != -1) CHECK(tree.nodes[static_cast<size_t>(tree.root)].height <= 3 * log2n + 2);
  }
}

TEST_CASE("shapes enter the broad phase only inside the checked limits", "[physics][broad_phase]") {
  // The broad phase never sees an empty, inverted or unbounded box: bodies
  // must start inside the world bounds, shapes reach at most
  // k_max_shape_size from their body and have at least k_min_shape_size,
  // and a body that leaves the bounds is disabled (k_step_flag_body_left_bounds).
  ScopedWorld w;
  BodyDef bd = default_body_def();
  bd.type = BodyType::dynamic_body;
  bd.position = {k_max_world_coordinate + 1_q32, 0_q32};
  CHECK(create_body(w.id, bd).status.code == StatusCode::invalid_argument);
  bd.position = {};
  Result<BodyId> b = create_body(w.id, bd);
  REQUIRE(b.ok());
  CHECK(!create_circle_shape(b.value, default_shape_def(), Circle{{}, Q32::zero()}).ok());
  CHECK(!create_circle_shape(b.value, default_shape_def(), Circle{{}, -1_q32}).ok());
  CHECK(!create_circle_shape(b.value, default_shape_def(), Circle{{k_max_shape_size, 0_q32}, 1_q32}).ok());
  Segment degenerate{{1_q32, 1_q32}, {1_q32, 1_q32}};
  CHECK(!create_segment_shape(b.value, default_shape_def(), degenerate).ok());
  CHECK(world_broad_phase_stats(w.id).proxies == 0);
}

TEST_CASE("the grid's dense and hashed layouts both match naive", "[physics][broad_phase]") {
  // Crowded clusters far apart make the occupied cell range sparse (hashed
  // buckets); one cluster alone is dense. Both must equal naive, step after
  // step.
  for (const int clusters : {1, 5}) {
    INFO("clusters " << clusters);
    ScopedWorld naive(world_def_with(BroadPhaseKind::naive, false));
    ScopedWorld grid(world_def_with(BroadPhaseKind::grid, false));
    for (ScopedWorld* w : {&naive, &grid}) {
      std::mt19937_64 rng(77);
      for (int c = 0; c < clusters; ++c) {
        const Vec2 centre = {Q32::from_int(-2000 + 997 * c), Q32::from_int(1500 - 731 * c)};
        for (int i = 0; i < 60; ++i) {
          BodyDef bd = default_body_def();
          bd.type = i % 7 == 0 ? BodyType::static_body : BodyType::dynamic_body;
          bd.position = centre + Vec2{random_q32(rng, -4, 4), random_q32(rng, -4, 4)};
          if (bd.type == BodyType::dynamic_body) bd.linear_velocity = {random_q32(rng, -2, 2), random_q32(rng, -2, 2)};
          Result<BodyId> b = create_body(w->id, bd);
          REQUIRE(b.ok());
          const Q32 r = Q32::from_raw(static_cast<int64_t>(rng() % (uint64_t{1} << 31)) + (int64_t{1} << 30));
          REQUIRE(create_circle_shape(b.value, default_shape_def(), Circle{{}, r}).ok());
        }
      }
    }
    for (int step = 0; step < 20; ++step) {
      REQUIRE(world_step(naive.id, k_dt).ok());
      REQUIRE(world_step(grid.id, k_dt).ok());
      REQUIRE(pair_keys(grid.id) == pair_keys(naive.id));
    }
    CHECK(!pair_keys(naive.id).empty());
    const bool hashed = find_world(grid.id)->broad_phase.grid.bucket_bits != 0;
    CHECK(hashed == (clusters > 1));
  }
}
