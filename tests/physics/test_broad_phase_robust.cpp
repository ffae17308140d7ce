// test_broad_phase_robust.cpp — every broad phase takes any AABB it is given
// (broad_phase.h: broad_phase_sanitize_box): inverted on one or both axes,
// at the limits of Q32.32, huge, empty. No out-of-bounds access (run under
// ASan + UBSan in clang-sanitize), no hang, and all four kinds still report
// the naive pair list, update after update (SAP's end points and the tree
// persist between updates), and step the same bits.
#include <catch2/catch.hpp>

#include <cstdint>
#include <random>
#include <vector>

#include "physics/broad_phase.h"
#include "physics/tandem.h"
#include "physics/world.h"
#include "physics_test_support.h"

using namespace tandem;
using namespace tandem::literals;
using namespace tandem::test_support;

namespace {

constexpr BroadPhaseKind k_all_kinds[4] = {BroadPhaseKind::naive, BroadPhaseKind::sweep_and_prune,
                                           BroadPhaseKind::grid, BroadPhaseKind::tree};

constexpr int64_t k_raw_max = INT64_MAX;
constexpr int64_t k_raw_min = INT64_MIN + 1;  // Q32's most negative value (INT64_MIN is never produced)

/// Adversarial boxes: each a function of a shape's true box.
AABB adversarial_box(int32_t variant, const AABB& b, std::mt19937_64& rng) {
  const auto raw = [](int64_t v) { return Q32::from_raw(v); };
  switch (variant % 12) {
    case 0: return {{b.upper.x, b.lower.y}, {b.lower.x, b.upper.y}};                     // inverted on x
    case 1: return {{b.lower.x, b.upper.y}, {b.upper.x, b.lower.y}};                     // inverted on y
    case 2: return {b.upper, b.lower};                                                    // inverted on both
    case 3: return {{raw(k_raw_min), raw(k_raw_min)}, {raw(k_raw_max), raw(k_raw_max)}};  // everything
    case 4: return {{raw(k_raw_max), raw(k_raw_max)}, {raw(k_raw_min), raw(k_raw_min)}};  // everything, inverted
    case 5: return {{raw(k_raw_max), raw(k_raw_max)}, {raw(k_raw_max), raw(k_raw_max)}};  // a point at +max
    case 6: return {{raw(k_raw_min), raw(k_raw_min)}, {raw(k_raw_min), raw(k_raw_min)}};  // a point at −max
    case 7: return {{b.lower.x, raw(k_raw_min)}, {b.upper.x, raw(k_raw_max)}};           // infinitely tall
    case 8: return {{raw(int64_t{1} << 62), b.lower.y}, {raw(-(int64_t{1} << 62)), b.upper.y}};  // huge, inverted
    case 9: return {b.lower, b.lower};                                                    // empty
    case 10: {  // a random box anywhere in Q32, either orientation
      const auto any = [&] { return raw(static_cast<int64_t>(rng() >> 1) - static_cast<int64_t>(rng() >> 1)); };
      return {{any(), any()}, {any(), any()}};
    }
    default: return b;  // untouched
  }
}

/// A digest of every body's pose and velocity and the contact list (the
/// physics tests do not link replay/'s state hash).
uint64_t world_digest(WorldId id) {
  const World* w = find_world(id);
  uint64_t h = 1469598103934665603ull;
  const auto mix = [&](int64_t v) { h = (h ^ static_cast<uint64_t>(v)) * 1099511628211ull; };
  for (const BodySim& s : w->body_sims) {
    mix(s.transform.p.x.raw);
    mix(s.transform.p.y.raw);
    mix(s.transform.q.s.raw);
    mix(s.linear_velocity.x.raw);
    mix(s.linear_velocity.y.raw);
    mix(s.angular_velocity.raw);
  }
  for (const Contact& c : w->contacts) {
    mix(c.shape_a);
    mix(c.shape_b);
    mix(c.normal_impulse[0].raw);
  }
  return h;
}

struct Scene {
  ScopedWorld world;
  explicit Scene(BroadPhaseKind kind) : world([&] {
      WorldDef def = default_world_def();
      def.broad_phase = kind;
      return def;
    }()) {
    std::mt19937_64 rng(7);
    for (int32_t i = 0; i < 48; ++i) {
      BodyDef bd = default_body_def();
      bd.type = i % 3 == 0 ? BodyType::static_body : BodyType::dynamic_body;
      bd.position = {Q32::from_int(static_cast<int32_t>(rng() % 40) - 20), Q32::from_int(static_cast<int32_t>(rng() % 40))};
      Result<BodyId> b = create_body(world.id, bd);
      REQUIRE(b.ok());
      REQUIRE(create_circle_shape(b.value, default_shape_def(), Circle{{}, 0.5_q32 + Q32::from_ratio(i % 5, 4)}).ok());
    }
  }
  /// Overwrites shape boxes (round r): every shape gets variant (i + r).
  void corrupt(int32_t round) {
    World* w = find_world(world.id);
    std::mt19937_64 rng(static_cast<uint64_t>(round) * 977u + 1u);
    for (size_t i = 0; i < w->shapes.size(); ++i) {
      w->shapes[i].aabb = adversarial_box(static_cast<int32_t>(i) + round, w->shapes[i].aabb, rng);
    }
  }
  std::vector<uint64_t> pairs() {
    std::vector<uint64_t> keys;
    for (const ShapePair& p : find_world(world.id)->broad_phase.pairs) keys.push_back(shape_pair_key(p.shape_a, p.shape_b));
    return keys;
  }
};

}  // namespace

TEST_CASE("broad_phase_sanitize_box is the identity on ordered in-range boxes and orders any other",
          "[physics][broad_phase]") {
  std::mt19937_64 rng(11);
  for (int32_t i = 0; i < 2000; ++i) {
    const AABB b{{Q32::from_raw(static_cast<int64_t>(rng() >> 1) - static_cast<int64_t>(rng() >> 1)),
                  Q32::from_raw(static_cast<int64_t>(rng() >> 1) - static_cast<int64_t>(rng() >> 1))},
                 {Q32::from_raw(static_cast<int64_t>(rng() >> 1) - static_cast<int64_t>(rng() >> 1)),
                  Q32::from_raw(static_cast<int64_t>(rng() >> 1) - static_cast<int64_t>(rng() >> 1))}};
    const AABB s = broad_phase_sanitize_box(b);
    CHECK(s.lower.x <= s.upper.x);
    CHECK(s.lower.y <= s.upper.y);
    CHECK(s.lower.x.raw >= -k_broad_phase_coordinate_limit);
    CHECK(s.upper.y.raw <= k_broad_phase_coordinate_limit);
    const AABB fat = aabb_fatten(s, k_speculative_distance);  // never saturates
    CHECK(fat.lower.x < s.lower.x);
    CHECK(fat.upper.y > s.upper.y);
    // A world's boxes (within ±2^53 raw, ordered) are unchanged.
    const int64_t lim = int64_t{1} << 53;
    const auto in = [&](int64_t v) { return Q32::from_raw(v % lim); };
    const AABB small{{in(b.lower.x.raw), in(b.lower.y.raw)}, {in(b.lower.x.raw), in(b.lower.y.raw)}};
    const AABB ordered{small.lower, {small.lower.x + Q32::from_raw(static_cast<int64_t>(rng() % lim)),
                                     small.lower.y + Q32::from_raw(static_cast<int64_t>(rng() % lim))}};
    CHECK(broad_phase_sanitize_box(ordered) == ordered);
  }
}

TEST_CASE("every broad phase is safe with inverted and extreme AABBs and agrees with naive",
          "[physics][broad_phase]") {
  Scene reference(BroadPhaseKind::naive);
  Scene sap(BroadPhaseKind::sweep_and_prune);
  Scene grid(BroadPhaseKind::grid);
  Scene tree(BroadPhaseKind::tree);
  Scene* scenes[4] = {&reference, &sap, &grid, &tree};
  // Rounds alternate corrupt boxes with true ones, so the persistent
  // structures (SAP end points, tree leaves) move between both.
  for (int32_t round = 0; round < 24; ++round) {
    INFO("round " << round);
    for (Scene* s : scenes) {
      if (round % 3 != 2) s->corrupt(round);
      broad_phase_update_pairs(find_world(s->world.id));
    }
    const std::vector<uint64_t> expected = reference.pairs();
    for (int32_t k = 1; k < 4; ++k) {
      INFO("kind " << static_cast<int32_t>(k_all_kinds[k]));
      CHECK(scenes[k]->pairs() == expected);
    }
    CHECK(tree_validate(find_world(tree.world.id)->broad_phase.tree) >= 0);
    // Restore true boxes before the next round's corruption (by stepping:
    // finalize recomputes dynamic bodies' boxes; static ones keep theirs).
    for (Scene* s : scenes) REQUIRE(world_step(s->world.id, Q32::from_ratio(1, 60)).ok());
    CHECK(world_digest(sap.world.id) == world_digest(reference.world.id));
    CHECK(world_digest(grid.world.id) == world_digest(reference.world.id));
    CHECK(world_digest(tree.world.id) == world_digest(reference.world.id));
  }
}

TEST_CASE("30 steps with corrupt static boxes are safe and identical with every broad phase",
          "[physics][broad_phase]") {
  // Static shapes' boxes are not recomputed by the step, so a corrupt box
  // stays in every update for the whole run.
  uint64_t hashes[4] = {};
  for (int32_t k = 0; k < 4; ++k) {
    Scene s(k_all_kinds[k]);
    World* w = find_world(s.world.id);
    std::mt19937_64 rng(5);
    for (size_t i = 0; i < w->shapes.size(); ++i) {
      if (w->bodies[static_cast<size_t>(w->shapes[i].body_index)].type != BodyType::static_body) continue;
      w->shapes[i].aabb = adversarial_box(static_cast<int32_t>(i), w->shapes[i].aabb, rng);
    }
    for (int32_t t = 0; t < 30; ++t) REQUIRE(world_step(s.world.id, Q32::from_ratio(1, 60)).ok());
    hashes[k] = world_digest(s.world.id);
  }
  CHECK(hashes[1] == hashes[0]);
  CHECK(hashes[2] == hashes[0]);
  CHECK(hashes[3] == hashes[0]);
}
