// Tests for physics/contact.cpp and physics/broad_phase.cpp: contact
// lifetime keyed by shape ids, sorted order, filtering (category, mask,
// group, sensors, same body, static pairs), warm-start impulses carried by
// feature id, material mixing, and the record sizes the issue asks for.
#include <catch2/catch.hpp>

#include <cstdint>
#include <vector>

#include "physics/broad_phase.h"
#include "physics/contact.h"
#include "physics/contact_solver.h"
#include "physics/tandem.h"
#include "physics/world.h"
#include "../test_world.h"

using namespace tandem;

namespace {

const Q32 k_dt = Q32::from_ratio(1, 60);

/// A world and its internals (this test reads contacts directly).
struct ScopedWorld : UniqueWorld {
  World* world = nullptr;
  explicit ScopedWorld(const WorldDef& def = default_world_def())
      : UniqueWorld(test_world::require_world(def).release()), world(find_world(id)) {}
};

BodyId make_body(WorldId w, BodyType type, Vec2 p) {
  BodyDef def = default_body_def();
  def.type = type;
  def.position = p;
  Result<BodyId> r = create_body(w, def);
  REQUIRE(r.ok());
  return r.value;
}

ShapeId box_shape(BodyId b, Q32 hw, Q32 hh, ShapeDef sd = default_shape_def()) {
  Polygon box;
  REQUIRE(make_box(hw, hh, &box).ok());
  Result<ShapeId> r = create_polygon_shape(b, sd, box);
  REQUIRE(r.ok());
  return r.value;
}

ShapeId circle_shape(BodyId b, Q32 r, ShapeDef sd = default_shape_def()) {
  Result<ShapeId> s = create_circle_shape(b, sd, Circle{{}, r});
  REQUIRE(s.ok());
  return s.value;
}

}  // namespace

TEST_CASE("contact record sizes", "[physics][contact]") {
  WARN("bytes: Contact " << sizeof(Contact) << ", ContactConstraint " << sizeof(ContactConstraint)
                         << " (per touching contact per step), ContactConstraintPoint "
                         << sizeof(ContactConstraintPoint) << ", ShapePair " << sizeof(ShapePair));
  CHECK(sizeof(Contact) <= 256);
  // 464: each point keeps r×n, r×t and I⁻¹·(r×n), I⁻¹·(r×t) per body so the
  // inner loops need no cross products (about 18 % fewer instructions a step),
  // and its separation at the last relax pass, which the next sub-step's solve
  // reads instead of rotating both anchors again (solve+relax 186.7 M →
  // 152.3 M instructions per pyramid-100 step with the other solver changes).
  CHECK(sizeof(ContactConstraint) <= 464);
}

TEST_CASE("filters follow category, mask and group", "[physics][contact]") {
  Filter a, b;
  CHECK(filters_should_collide(a, b));
  a.category_bits = 2;
  b.mask_bits = 1;
  CHECK_FALSE(filters_should_collide(a, b));
  b.mask_bits = 3;
  CHECK(filters_should_collide(a, b));
  a.mask_bits = 4;  // b (category 1) is not in a's mask
  CHECK_FALSE(filters_should_collide(a, b));
  a.group_index = b.group_index = 5;  // positive shared group: always
  CHECK(filters_should_collide(a, b));
  a.group_index = b.group_index = -5;  // negative shared group: never
  a.mask_bits = b.mask_bits = UINT64_MAX;
  CHECK_FALSE(filters_should_collide(a, b));
  b.group_index = -4;  // different groups: categories decide
  CHECK(filters_should_collide(a, b));
}

TEST_CASE("contacts are created, kept sorted by shape ids and destroyed", "[physics][contact]") {
  WorldDef def = default_world_def();
  def.gravity = {};
  ScopedWorld w(def);
  const BodyId ground = make_body(w.id, BodyType::static_body, {0_q32, -1_q32});
  box_shape(ground, 50_q32, 1_q32);
  const BodyId other_static = make_body(w.id, BodyType::static_body, {0_q32, -1.5_q32});
  box_shape(other_static, 1_q32, 1_q32);  // overlaps the ground: static pair, no contact
  const BodyId a = make_body(w.id, BodyType::dynamic_body, {0_q32, 0.5_q32});
  box_shape(a, 0.5_q32, 0.5_q32);
  const BodyId b = make_body(w.id, BodyType::dynamic_body, {0.9_q32, 0.5_q32});
  box_shape(b, 0.5_q32, 0.5_q32);
  circle_shape(b, 0.3_q32);  // second shape of b (same body pair: no contact)
  ShapeDef sensor = default_shape_def();
  sensor.is_sensor = true;
  const BodyId s = make_body(w.id, BodyType::dynamic_body, {0_q32, 0.5_q32});
  circle_shape(s, 0.5_q32, sensor);  // sensors never form contacts
  ShapeDef masked = default_shape_def();
  masked.filter.category_bits = 2;
  masked.filter.mask_bits = 2;
  const BodyId m = make_body(w.id, BodyType::dynamic_body, {0_q32, 0.5_q32});
  circle_shape(m, 0.5_q32, masked);  // filtered out against everything

  REQUIRE(world_step(w.id, k_dt).ok());
  const std::vector<Contact>& cs = w.world->contacts;
  // Expected: ground–a, ground–b's box, a–b's box. b's circle (r 0.3 at
  // (0.9, 0.5)) is 0.2 m above the ground and 0.1 m from a: beyond the fat
  // AABB margins (2 × 0.02 m).
  for (size_t k = 1; k < cs.size(); ++k) CHECK(contact_key(cs[k - 1]) < contact_key(cs[k]));
  for (const Contact& c : cs) {
    CHECK(c.shape_a < c.shape_b);
    CHECK(c.body_a != c.body_b);
    CHECK(!(c.body_a == 0 && c.body_b == 1));  // no static pair
    CHECK(c.body_a != 4);                       // no sensor
    CHECK(c.body_b != 4);
    CHECK(c.body_a != 5);                       // filtered
    CHECK(c.body_b != 5);
  }
  REQUIRE(cs.size() == 3u);

  // Move b far away: its contacts are destroyed.
  REQUIRE(body_set_transform(b, {30_q32, 5_q32}, Rot{}).ok());
  REQUIRE(world_step(w.id, k_dt).ok());
  REQUIRE(w.world->contacts.size() == 1u);
  CHECK(w.world->contacts[0].body_b == 2);
}

TEST_CASE("warm-start impulses carry over by feature id", "[physics][contact]") {
  ScopedWorld w;
  const BodyId ground = make_body(w.id, BodyType::static_body, {0_q32, -1_q32});
  box_shape(ground, 50_q32, 1_q32);
  const BodyId box = make_body(w.id, BodyType::dynamic_body, {0_q32, 0.5_q32});
  box_shape(box, 0.5_q32, 0.5_q32);
  for (int i = 0; i < 60; ++i) REQUIRE(world_step(w.id, k_dt).ok());
  REQUIRE(w.world->contacts.size() == 1u);
  const Contact& c = w.world->contacts[0];
  REQUIRE(c.manifold.point_count == 2);
  // At rest the two points carry the weight: Σλ ≈ m·g·h per sub-step.
  const Q32 h = k_dt / 4;
  const long double expected = static_cast<long double>((body_mass(box) * 10_q32 * h).raw);
  const long double total = static_cast<long double>((c.normal_impulse[0] + c.normal_impulse[1]).raw);
  CHECK(total == Approx(expected).epsilon(0.01));
  CHECK(c.normal_impulse[0] > 0_q32);
  CHECK(c.normal_impulse[1] > 0_q32);
  // Mixing: friction sqrt(0.6·0.6) = 0.6 (within a few raw units), restitution max(0, 0).
  CHECK(std::abs(c.friction.raw - (0.6_q32).raw) <= 2);
  CHECK(c.restitution == 0_q32);
}

TEST_CASE("material mixing rules", "[physics][contact]") {
  CHECK(mix_friction(0.64_q32, 0.25_q32).raw - (0.4_q32).raw <= 2);
  CHECK(mix_friction(0_q32, 0.9_q32) == 0_q32);
  CHECK(mix_restitution(0.2_q32, 0.7_q32) == 0.7_q32);
}
