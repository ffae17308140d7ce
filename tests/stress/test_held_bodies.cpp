// Failures of the random-world stress runs of 2026-11-28 (issue 14),
// rebuilt as small worlds so that each tests its cause, not one seed's
// history: a thin spinning body that continuous collision held at a wall
// while it kept its speed (stress seed 1104), and a light body between a
// heavy falling body and the floor (stress seed 6298). Each test failed
// before its fix (checked by reverting it) and asserts no fixed-point fault.

#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdio>

#include "fixed/fault.h"
#include "physics/tandem.h"
#include "edge_support.h"

namespace {

using namespace tandem;
using namespace tandem::literals;
using namespace tandem::stress_edges;

const Q32 k_dt = Q32::from_ratio(1, 60);

/// A dynamic body (a bullet or not) whose only shape is `segment`: no area,
/// so the default 1 kg and no rotational inertia, as in the stress seeds
/// below.
BodyId segment_body(WorldId w, Vec2 position, Rot rotation, bool bullet, Vec2 velocity, Q32 spin,
                    const Segment& segment) {
  BodyDef bd = default_body_def();
  bd.type = BodyType::dynamic_body;
  bd.position = position;
  bd.rotation = rotation;
  bd.is_bullet = bullet;
  bd.linear_velocity = velocity;
  bd.angular_velocity = spin;
  Result<BodyId> b = create_body(w, bd);
  REQUIRE(b.ok());
  REQUIRE(create_segment_shape(b.value, default_shape_def(), segment).ok());
  REQUIRE(body_rotational_inertia(b.value) == 0_q32);
  return b.value;
}

}  // namespace

// Stress seed 1104: a 1 kg bullet whose only solid shape is a 2 m segment
// (no area, so no rotational inertia: contacts cannot change its spin)
// spinning at 59 rad/s reached a box wall at ~155 m/s. The contact solver
// read the contact point as separating (the spin carries it away from the
// wall at that instant), and continuous collision, finding the segment
// touching the wall at the start of each step, held it halfway to the wall
// without touching its velocity: 28 steps in place at 155 m/s, then through
// the wall once the centroid was too close to hold. continuous.cpp's hold
// now also takes away the velocity towards the obstacle.
TEST_CASE("stress: a thin spinning body held at a wall by continuous collision does not keep its speed into it",
          "[stress][continuous]") {
  FaultCount faults;
  for (const bool bullet : {true, false}) {
    TestWorld w;
    // Wall: its face at x = 0, 3 m thick (middle at x = -1.5).
    static_box(w.id, Vec2{-1.5_q32, 0_q32}, 1.5_q32, 60_q32);
    // Seed 1104's body when the hold began (tick 428, the pose relative to
    // the wall's face): its 3.3 m segment nearly parallel to the wall, one
    // end 0.02 m into it, the other 0.03 m from it (outside the contact's
    // speculative distance), moving into the wall at 116 m/s while the spin
    // carries the touching end away from it.
    const Segment segment{Vec2{1.94591_q32, 0.39351_q32}, Vec2{-1.27520_q32, -0.21637_q32}};
    const BodyId body = segment_body(w.id, Vec2{0.03546_q32, 0_q32}, Rot{0.170895_q32, 0.985289_q32}, bullet,
                                     Vec2{-115.61_q32, 106.45_q32}, -58.9049_q32, segment);
    REQUIRE(body_mass(body) == 1_q32);
    const Vec2 middle = (segment.point1 + segment.point2) * 0.5_q32;
    long double leftmost = 1e9L;
    int held = 0;
    for (int t = 0; t < 60; ++t) {
      REQUIRE(world_step(w.id, k_dt).ok());
      const Vec2 mid = body_world_point(body, middle);
      leftmost = std::min(leftmost, static_cast<long double>(mid.x.to_double()));
      if (mid.x < 2_q32 && body_linear_velocity(body).x < -50_q32) ++held;
    }
    std::printf("held at a wall (bullet %d): leftmost segment middle x = %.4Lf m (wall face 0, middle -1.5); steps "
                "within 2 m of the wall still moving into it faster than 50 m/s: %d\n",
                bullet ? 1 : 0, leftmost, held);
    INFO("bullet " << bullet);
    CHECK(leftmost > -1.5L);  // never past the wall's middle
    CHECK(held == 0);         // its speed into the wall is gone after the first step
  }
  CHECK(faults.count() == 0);
}

// Stress seed 6298: a 3,150 kg body fell at ~13 m/s onto a 0.04 kg circle
// (1.45 m radius) lying on the floor. Their contact alternated between
// resting (the mass-ratio cap on: the light body takes impulses as a
// 31.5 kg one) and closing (true masses), and when it closed, the impulse
// stored under the cap warm-started the contact against the circle's true
// mass: kicked down at 35 m/s, it went 3 m into the floor and out of it.
// Such a contact now warm-starts with at most the impulse that changes the
// light body's velocity by the restitution threshold (contact_prepare.cpp).
TEST_CASE("stress: a light circle under a heavy falling box stays above the floor",
          "[stress][limits]") {
  FaultCount faults;
  for (const Q32 speed : {0_q32, 5_q32, 13_q32}) {
    TestWorld w;
    static_box(w.id, Vec2{0_q32, -1.5_q32}, 30_q32, 1.5_q32);  // top face at y = 0
    BodyDef bd = default_body_def();
    bd.type = BodyType::dynamic_body;
    bd.position = Vec2{0_q32, 1.45_q32};
    Result<BodyId> light = create_body(w.id, bd);
    REQUIRE(light.ok());
    ShapeDef sd = default_shape_def();
    sd.density = 0.0061_q32;  // 0.04 kg
    REQUIRE(create_circle_shape(light.value, sd, Circle{Vec2{}, 1.45_q32}).ok());
    bd.position = Vec2{0.4_q32, 4.5_q32};
    bd.linear_velocity = Vec2{-2_q32, -speed};
    Result<BodyId> heavy = create_body(w.id, bd);
    REQUIRE(heavy.ok());
    Polygon box;
    REQUIRE(make_box(1.5_q32, 1.5_q32, &box).ok());
    sd.density = 350_q32;  // 3,150 kg
    REQUIRE(create_polygon_shape(heavy.value, sd, box).ok());
    long double lowest = 1e9L;
    for (int t = 0; t < 240; ++t) {
      REQUIRE(world_step(w.id, k_dt).ok());
      lowest = std::min(lowest, static_cast<long double>(body_world_center(light.value).y.to_double()));
    }
    std::printf("light circle under a heavy box at %g m/s: mass %.4f kg under %.1f kg, lowest centre %.4Lf m "
                "(rest 1.45), final %.4f m\n",
                speed.to_double(), body_mass(light.value).to_double(), body_mass(heavy.value).to_double(), lowest,
                body_world_center(light.value).y.to_double());
    INFO("heavy box at " << speed.to_double() << " m/s");
    CHECK(lowest > 0.0L);  // its centre never below the floor's face
  }
  CHECK(faults.count() == 0);
}

// Stress seed 8724 (the 10,000-world run's one failure): a 1 kg body whose
// only solid shape is a 4.1 m segment (no rotational inertia), spinning at
// 59 rad/s and sliding down a wall at 234 m/s with the segment along the
// wall's face and its centre of mass 0.44 m inside the wall. Each step the
// spin swung the segment into the wall; continuous collision held its
// middle halfway to the face, step after step, with the body frozen in
// place at 229 m/s (the hold took only the velocity into the wall), until
// the middle was too close to the face to halve the distance again
// (26 steps); then it was let go and swung through the wall's middle. Now a
// hold within half the slop of the wall also takes the body's spin, and the
// body slides down along the wall.
TEST_CASE("stress: a thin spinning body sliding along a wall is never let go through it by continuous collision",
          "[stress][continuous]") {
  FaultCount faults;
  for (const bool bullet : {false, true}) {
    TestWorld w;
    // Wall: its face at x = 0, 3 m thick (middle at x = -1.5), 400 m tall.
    static_box(w.id, Vec2{-1.5_q32, 0_q32}, 1.5_q32, 200_q32);
    // Seed 8724's body one step before the hold began (tick 284, relative to
    // the wall's face).
    const Segment segment{Vec2{0.161927_q32, -0.531205_q32}, Vec2{3.763054_q32, 1.658798_q32}};
    const BodyId body = segment_body(w.id, Vec2{-0.443749_q32, 150_q32}, Rot{0.796806_q32, 0.604235_q32}, bullet,
                                     Vec2{-19.1991_q32, -233.7205_q32}, 58.9049_q32, segment);
    const Vec2 middle = (segment.point1 + segment.point2) * 0.5_q32;
    long double leftmost = 1e9L;
    int frozen = 0;
    Vec2 last = body_world_center(body);
    for (int t = 0; t < 60; ++t) {
      REQUIRE(world_step(w.id, k_dt).ok());
      const Vec2 mid = body_world_point(body, middle);
      leftmost = std::min(leftmost, static_cast<long double>(mid.x.to_double()));
      // In place while its velocity says it slides at over 50 m/s.
      const Vec2 now = body_world_center(body);
      if (length(now - last) < 0.01_q32 && length(body_linear_velocity(body)) > 50_q32) ++frozen;
      last = now;
    }
    std::printf("sliding along a wall (bullet %d): leftmost segment middle x = %.4Lf m (wall face 0, middle -1.5); "
                "steps frozen in place while moving faster than 50 m/s: %d\n",
                bullet ? 1 : 0, leftmost, frozen);
    INFO("bullet " << bullet);
    CHECK(leftmost > -1.5L);  // never past the wall's middle
    // A held body does not keep a speed it does not move at for more than
    // the holds that halve its distance from the slop (where a hold starts)
    // to half of it, where the hold takes its spin: three steps.
    CHECK(frozen <= 3);
  }
  CHECK(faults.count() == 0);
}

// Stress seeds 3769 and 6309 (the 10,000-world release run after the
// seed-8724 fix): a segment body resting on the floor sinks by up to the
// slop, so its middle starts the step inside the floor's box. An input then
// flings it at 400-1,000 m/s into the floor or along it. The centroid core
// had no distance to the floor, so no hold normal, and continuous collision
// let the body go through (3769) or past the floor's corner (6309). Now the
// middle is held where it would sink half the slop deeper behind the face
// it rests on.
TEST_CASE("stress: a segment resting inside the floor's face and flung into it stays above the floor's middle",
          "[stress][continuous]") {
  FaultCount faults;
  struct Throw {
    Segment segment;  // body frame (the origin is the centre of mass), m
    Rot rotation;
    Vec2 velocity;    // m/s
    Q32 spin;         // rad/s
  };
  const Rot level{1_q32, 0_q32};
  const Rot tilted{0.996195_q32, 0.087156_q32};  // 5 degrees
  const Segment two_metres{Vec2{-1_q32, 0_q32}, Vec2{1_q32, 0_q32}};
  // Seed 3769's body at tick 514: a 0.38 m segment below its origin, turned
  // by -25.7 degrees (one end deep in the floor: contacts cannot turn it).
  const Segment seed_3769{Vec2{-0.1771_q32, -0.0333_q32}, Vec2{0.2059_q32, -0.0333_q32}};
  const Rot seed_3769_rotation{0.901049_q32, -0.433718_q32};
  const Throw throws[] = {
      {two_metres, level, Vec2{0_q32, -1000_q32}, 0_q32},
      {two_metres, tilted, Vec2{0_q32, -400_q32}, 0_q32},
      {two_metres, level, Vec2{300_q32, -700_q32}, 0_q32},
      {two_metres, tilted, Vec2{-600_q32, -500_q32}, 20_q32},
      {two_metres, level, Vec2{990_q32, -40_q32}, 0_q32},
      {seed_3769, seed_3769_rotation, Vec2{-1000_q32, 0_q32}, 0_q32},
      {seed_3769, seed_3769_rotation, Vec2{0_q32, -1000_q32}, 0_q32},
      {seed_3769, seed_3769_rotation, Vec2{1000_q32, 0_q32}, 0_q32},
  };
  for (const bool bullet : {false, true}) {
    for (const Throw& th : throws) {
      WorldDef def = default_world_def();
      def.max_linear_speed = k_max_linear_speed;  // 1,000 m/s, as in the stress seeds' fast worlds
      TestWorld w(def);
      // Floor: its face at y = 0, 3 m thick (middle at y = -1.5), 2,400 m
      // wide (a body sliding at 1,000 m/s stays over it for the 60 steps).
      static_box(w.id, Vec2{0_q32, -1.5_q32}, 1200_q32, 1.5_q32);
      // The segment's middle 3 mm inside the floor's face, as a resting
      // segment sinks.
      const Vec2 middle = (th.segment.point1 + th.segment.point2) * 0.5_q32;
      const Vec2 origin = Vec2{0_q32, -0.003_q32} - rotate(th.rotation, middle);
      const BodyId body = segment_body(w.id, origin, th.rotation, bullet, th.velocity, th.spin, th.segment);
      long double lowest = 1e9L;
      for (int t = 0; t < 60; ++t) {
        REQUIRE(world_step(w.id, k_dt).ok());
        lowest = std::min(lowest, static_cast<long double>(body_world_point(body, middle).y.to_double()));
      }
      const Vec2 end = body_world_point(body, middle);
      std::printf("%.3f m segment resting inside the floor's face (bullet %d), thrown at (%g, %g) m/s, %g rad/s: "
                  "lowest middle %.4Lf m (face 0, floor middle -1.5), final (%.3f, %.4f)\n",
                  length(th.segment.point2 - th.segment.point1).to_double(), bullet ? 1 : 0,
                  th.velocity.x.to_double(), th.velocity.y.to_double(), th.spin.to_double(), lowest, end.x.to_double(),
                  end.y.to_double());
      INFO("bullet " << bullet << ", velocity (" << th.velocity.x.to_double() << ", " << th.velocity.y.to_double()
                     << ")");
      // Never deeper than the slop below its start (3 mm in + 5 mm).
      CHECK(lowest > -0.008L);
    }
  }
  CHECK(faults.count() == 0);
}
