// Tests for make_chain_segments and a box sliding along a built chain.
#include <catch2/catch.hpp>

#include <array>

#include "physics/collision.h"

using namespace tandem;
using namespace tandem::literals;

TEST_CASE("open chains: first and last points are ghosts", "[physics][chain]") {
  const std::array<Vec2, 5> pts{{{Q32(-3), 1_q32}, {Q32(-2), 0_q32}, {0_q32, 0_q32}, {2_q32, 0_q32}, {3_q32, 1_q32}}};
  std::array<ChainSegment, 8> segs{};
  int32_t n = 0;
  const Status s = make_chain_segments(pts.data(), 5, false, 7, segs.data(), 8, &n);
  REQUIRE(s.ok());
  REQUIRE(n == 2);
  CHECK(segs[0].ghost1 == pts[0]);
  CHECK(segs[0].segment.point1 == pts[1]);
  CHECK(segs[0].segment.point2 == pts[2]);
  CHECK(segs[0].ghost2 == pts[3]);
  CHECK(segs[1].ghost1 == pts[1]);
  CHECK(segs[1].segment.point2 == pts[3]);
  CHECK(segs[1].ghost2 == pts[4]);
  CHECK(segs[1].chain_id == 7);
}

TEST_CASE("loops wrap their ghosts", "[physics][chain]") {
  const std::array<Vec2, 4> square{{{0_q32, 0_q32}, {1_q32, 0_q32}, {1_q32, 1_q32}, {0_q32, 1_q32}}};
  std::array<ChainSegment, 4> segs{};
  int32_t n = 0;
  REQUIRE(make_chain_segments(square.data(), 4, true, 0, segs.data(), 4, &n).ok());
  REQUIRE(n == 4);
  CHECK(segs[0].ghost1 == square[3]);
  CHECK(segs[3].segment.point1 == square[3]);
  CHECK(segs[3].segment.point2 == square[0]);
  CHECK(segs[3].ghost2 == square[1]);
}

TEST_CASE("bad chains are rejected with a message", "[physics][chain]") {
  std::array<ChainSegment, 8> segs{};
  int32_t n = -1;
  const std::array<Vec2, 3> three{{{0_q32, 0_q32}, {1_q32, 0_q32}, {2_q32, 0_q32}}};
  Status s = make_chain_segments(three.data(), 3, false, 0, segs.data(), 8, &n);
  CHECK_FALSE(s.ok());
  CHECK(n == 0);
  CHECK(s.message == "chain: an open chain needs at least 4 points, got 3 (the first and last points are ghost vertices only)");
  const std::array<Vec2, 4> dup{{{0_q32, 0_q32}, {1_q32, 0_q32}, {1.001_q32, 0_q32}, {2_q32, 0_q32}}};
  s = make_chain_segments(dup.data(), 4, false, 0, segs.data(), 8, &n);
  CHECK_FALSE(s.ok());
  CHECK(s.message.rfind("chain: points 1 and 2 are 0.00099", 0) == 0);
  const std::array<Vec2, 4> square{{{0_q32, 0_q32}, {1_q32, 0_q32}, {1_q32, 1_q32}, {0_q32, 1_q32}}};
  s = make_chain_segments(square.data(), 4, true, 0, segs.data(), 2, &n);
  CHECK_FALSE(s.ok());
  CHECK(s.message == "chain: 4 segments do not fit the output capacity of 2");
}

TEST_CASE("a box sliding along a flat built chain never catches an inner vertex", "[physics][chain]") {
  // Flat ground from x = -4 to 4 made of 1 m segments; solid below (points
  // run right to left, so the right of each segment's direction is up).
  std::array<Vec2, 11> pts{};
  for (int i = 0; i < 11; ++i) pts[static_cast<size_t>(i)] = Vec2{Q32(5 - i), 0_q32};
  std::array<ChainSegment, 16> segs{};
  int32_t n = 0;
  REQUIRE(make_chain_segments(pts.data(), 11, false, 0, segs.data(), 16, &n).ok());
  REQUIRE(n == 8);
  Polygon box;
  REQUIRE(make_box(0.5_q32, 0.5_q32, &box).ok());
  ShapeGeometry ground;
  ground.type = ShapeType::chain_segment;
  ShapeGeometry body;
  body.type = ShapeType::polygon;
  body.polygon = box;
  // Slide in 1 cm steps, resting 1 mm into the ground.
  for (int step = 0; step <= 700; ++step) {
    const Transform xf{Vec2{Q32(-3) + Q32::from_ratio(step, 100), 0.499_q32}, Rot{}};
    int touching = 0;
    for (int32_t k = 0; k < n; ++k) {
      ground.chain_segment = segs[static_cast<size_t>(k)];
      const Manifold m = collide(ground, Transform{}, body, xf);
      for (int32_t p = 0; p < m.point_count; ++p) {
        INFO("step " << step << " segment " << k);
        // Every point pushes straight up: no normal from an inner vertex.
        REQUIRE(m.normal.x == 0_q32);
        REQUIRE(m.normal.y == 1_q32);
        REQUIRE(m.points[static_cast<size_t>(p)].separation <= 0_q32);
        ++touching;
      }
    }
    REQUIRE(touching >= 2);
  }
}
