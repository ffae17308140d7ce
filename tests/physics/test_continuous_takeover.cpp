// Tests for physics/continuous.cpp's rule that continuous collision stops a
// fast body only where the contact solver can take over: two segment kinds
// (segments, chain segments) have no contact manifold, and a one-sided chain
// segment makes none with a shape whose centroid starts behind it. Stopping
// a body there held it in the air, step after step, while gravity added to
// its velocity, until it slipped past and fell at that speed (random-world
// stress seed 572: a segment held on a chain segment reached 13 m/s and went
// into the floor). Each test fails without the rule (the body is held).
#include <catch2/catch.hpp>

#include <vector>

#include "physics/tandem.h"
#include "physics_test_support.h"

using namespace tandem;
using namespace tandem::test_support;

namespace {

/// A static body at the origin carrying one plain segment (chain = false) or
/// an open chain (chain = true; four points: p1, p2 and the two points one
/// segment length beyond each end, on the same line) from `p1` to `p2`.
void add_static_line(WorldId w, Vec2 p1, Vec2 p2, bool chain) {
  const Result<BodyId> b = create_body(w, default_body_def());
  REQUIRE(b.ok());
  if (chain) {
    const Vec2 points[4] = {p1 - (p2 - p1), p1, p2, p2 + (p2 - p1)};
    REQUIRE(create_chain_shapes(b.value, default_shape_def(), points, 4, false, nullptr).ok());
  } else {
    REQUIRE(create_segment_shape(b.value, default_shape_def(), Segment{p1, p2}).ok());
  }
}

/// A static ground box whose top face is at y = -2.
void add_ground(WorldId w) { add_box_body(w, body_def_at({0_q32, -3_q32}, BodyType::static_body), 10_q32, 1_q32); }

/// A dynamic body at (0, 0.5) falling at 20 m/s (1/3 m per step: fast for
/// continuous collision) carrying a 1 m horizontal segment (segment = true;
/// its mass is the default 1 kg) or a 0.5 m box.
BodyId add_falling_body(WorldId w, bool segment) {
  BodyDef bd = body_def_at({0_q32, 0.5_q32});
  bd.linear_velocity = {0_q32, -20_q32};
  if (!segment) return add_box_body(w, bd, 0.25_q32, 0.25_q32);
  const Result<BodyId> b = create_body(w, bd);
  REQUIRE(b.ok());
  REQUIRE(create_segment_shape(b.value, default_shape_def(), Segment{{-0.5_q32, 0_q32}, {0.5_q32, 0_q32}}).ok());
  return b.value;
}

void step(WorldId w, int ticks) {
  for (int i = 0; i < ticks; ++i) REQUIRE(world_step(w, k_dt).ok());
}

}  // namespace

TEST_CASE("continuous: a fast segment is not stopped at a static segment or chain segment (no contact between them)",
          "[continuous]") {
  for (const bool chain : {false, true}) {
    INFO((chain ? "chain segment" : "segment"));
    ScopedWorld w;
    // Front side (chain) facing up: right_perp of (2,0) → (−2,0) is +y.
    add_static_line(w.id, {2_q32, 0_q32}, {-2_q32, 0_q32}, chain);
    add_ground(w.id);
    const BodyId body = add_falling_body(w.id, true);
    // Without contact between the two, it falls past the line within two
    // steps (0.5 m at 20 m/s), as with continuous collision off.
    step(w.id, 2);
    CHECK(ld(body_world_center(body).y) < 0.0L);
    // ...and comes to rest on the ground (top face at y = -2).
    step(w.id, 120);
    CHECK(ld(body_world_center(body).y) == Approx(-2.0L).margin(0.01L));
  }
}

TEST_CASE("continuous: a fast box is not stopped behind a one-sided chain segment, but is in front of it",
          "[continuous]") {
  for (const bool from_front : {false, true}) {
    INFO((from_front ? "from the front" : "from behind"));
    ScopedWorld w;
    // right_perp(p2 − p1) is the chain's front: +y for (2,0) → (−2,0), −y
    // for (−2,0) → (2,0). The box comes from above.
    if (from_front) {
      add_static_line(w.id, {2_q32, 0_q32}, {-2_q32, 0_q32}, true);
    } else {
      add_static_line(w.id, {-2_q32, 0_q32}, {2_q32, 0_q32}, true);
    }
    add_ground(w.id);
    const BodyId body = add_falling_body(w.id, false);
    step(w.id, 2);
    if (from_front) {
      // Stopped on the chain, then resting on it (half height 0.25 m).
      CHECK(ld(body_world_center(body).y) > 0.2L);
      step(w.id, 120);
      CHECK(ld(body_world_center(body).y) == Approx(0.25L).margin(0.01L));
    } else {
      // The chain makes no contact from behind: the box passes within two
      // steps and rests on the ground.
      CHECK(ld(body_world_center(body).y) < 0.0L);
      step(w.id, 120);
      CHECK(ld(body_world_center(body).y) == Approx(-1.75L).margin(0.01L));
    }
  }
}
