// test_limits_edges.cpp — limits at the edges (issue 14): worlds placed at
// ±999,000 m, bodies at the mass, inertia, speed and size limits of
// physics/limits.h, extreme mass ratios (1:100,000) stacked. Every test counts
// fixed-point faults (reported in builds with fault checks: debug and
// sanitizer builds) and asserts none; the figures asserted here are the ones
// quoted in the README's "Range and limits" table, at the precision asserted.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "fixed/fault.h"
#include "physics/tandem.h"
#include "edge_support.h"

namespace {

using namespace tandem;
using namespace tandem::literals;
using namespace tandem::stress_edges;

constexpr long double k_two32 = 4294967296.0L;
long double ld(Q32 v) { return static_cast<long double>(v.raw) / k_two32; }
const Q32 k_dt = Q32::from_ratio(1, 60);


BodyId dynamic_box(WorldId w, Vec2 position, Q32 hw, Q32 hh, Q32 density) {
  BodyDef bd = default_body_def();
  bd.type = BodyType::dynamic_body;
  bd.position = position;
  Result<BodyId> b = create_body(w, bd);
  REQUIRE(b.ok());
  Polygon box;
  REQUIRE(make_box(hw, hh, &box).ok());
  ShapeDef sd = default_shape_def();
  sd.density = density;
  Result<ShapeId> s = create_polygon_shape(b.value, sd, box);
  INFO(s.status.message);
  REQUIRE(s.ok());
  return b.value;
}

void step(WorldId w, int ticks) {
  for (int i = 0; i < ticks; ++i) REQUIRE(world_step(w, k_dt).ok());
}

/// A stack of five 1 m boxes on a ground box whose top face is at `origin`;
/// returns each box's centre relative to `origin` after `ticks` steps.
std::vector<Vec2> stack_at(Vec2 origin, int ticks) {
  TestWorld w;
  static_box(w.id, origin + Vec2{0_q32, -1_q32}, 20_q32, 1_q32);
  std::vector<BodyId> boxes;
  for (int i = 0; i < 5; ++i)
    boxes.push_back(dynamic_box(w.id, origin + Vec2{Q32::from_ratio(i, 20), Q32::from_ratio(1, 2) + Q32(i)},
                                Q32::from_ratio(1, 2), Q32::from_ratio(1, 2), 1_q32));
  step(w.id, ticks);
  std::vector<Vec2> out;
  for (BodyId b : boxes) out.push_back(body_world_center(b) - origin);
  return out;
}

}  // namespace

TEST_CASE("limits: a stack at ±999,000 m settles as at the origin, no fault", "[stress][limits]") {
  FaultCount faults;
  const std::vector<Vec2> home = stack_at(Vec2{}, 300);
  const Vec2 corners[4] = {{999000_q32, 999000_q32}, {-999000_q32, 999000_q32},
                           {999000_q32, -999000_q32}, {-999000_q32, -999000_q32}};
  long double worst = 0;
  for (const Vec2& corner : corners) {
    const std::vector<Vec2> far = stack_at(corner, 300);
    for (size_t i = 0; i < far.size(); ++i) {
      const long double dx = ld(far[i].x - home[i].x), dy = ld(far[i].y - home[i].y);
      worst = std::max({worst, dx < 0 ? -dx : dx, dy < 0 ? -dy : dy});
    }
    // The top box rests 4.5 m above the ground (±1 cm: resting overlap).
    CHECK(ld(far[4].y) > 4.49L);
    CHECK(ld(far[4].y) < 4.51L);
  }
  UNSCOPED_INFO("largest difference from the origin stack after 5 s: " << static_cast<double>(worst) << " m");
  std::printf("limits: stack at ±999,000 m: largest difference from the origin run %.3Le m\n", worst);
  // Q32.32 has the same resolution everywhere, so a translated stack follows
  // the origin one to within a few raw units.
  CHECK(worst <= 1e-6L);
  CHECK(faults.count() == 0);
}

TEST_CASE("limits: mass ratios 1:10 to 1:100,000 stacked, either way up", "[stress][limits]") {
  FaultCount faults;
  // Two 1 m boxes (density = mass) stacked on a 2 m thick static ground (top
  // face at y = 0) for 10 s: the upper one starts resting on the lower one.
  struct Case { Q32 lower; Q32 upper; };
  const Case cases[] = {
      // heavy on light
      {1_q32, 10_q32}, {1_q32, 100_q32}, {1_q32, 1000_q32}, {1_q32, 10000_q32}, {1_q32, 100000_q32},
      {0.001_q32, 100_q32},
      // light on heavy
      {1000_q32, 1_q32}, {10000_q32, 1_q32}, {100000_q32, 1_q32}, {100_q32, 0.001_q32}};
  for (const Case& c : cases) {
    TestWorld w;
    static_box(w.id, Vec2{0_q32, -1_q32}, 20_q32, 1_q32);
    const BodyId lower = dynamic_box(w.id, Vec2{0_q32, 0.5_q32}, 0.5_q32, 0.5_q32, c.lower);
    const BodyId upper = dynamic_box(w.id, Vec2{0_q32, 1.5_q32}, 0.5_q32, 0.5_q32, c.upper);
    const long double m_lower = ld(body_mass(lower)), m_upper = ld(body_mass(upper));
    long double lowest_lower = 1e9L, lowest_upper = 1e9L, lowest_gap = 1e9L, widest_x = 0;
    for (int t = 0; t < 600; ++t) {
      REQUIRE(world_step(w.id, k_dt).ok());
      const Vec2 pl = body_world_center(lower), pu = body_world_center(upper);
      lowest_lower = std::min(lowest_lower, ld(pl.y));
      lowest_upper = std::min(lowest_upper, ld(pu.y));
      lowest_gap = std::min(lowest_gap, ld(pu.y) - ld(pl.y));
      widest_x = std::max({widest_x, ld(abs(pl.x)), ld(abs(pu.x))});
    }
    const long double gap = ld(body_world_center(upper).y) - ld(body_world_center(lower).y);
    const long double final_lower = ld(body_world_center(lower).y), final_upper = ld(body_world_center(upper).y);
    std::printf("limits: %g kg on %g kg: lower centre lowest %.4Lf (rest 0.5), upper lowest %.4Lf (rest 1.5); upper above "
                "lower: lowest %.4Lf, final %.4Lf (rest 1.0); final lower %.4Lf upper %.4Lf; |x| up to %.4Lf\n",
                static_cast<double>(m_upper), static_cast<double>(m_lower), lowest_lower, lowest_upper, lowest_gap, gap,
                final_lower, final_upper, widest_x);
    const long double ratio = m_upper / m_lower;
    INFO(static_cast<double>(m_upper) << " kg on " << static_cast<double>(m_lower) << " kg");
    if (ratio < 1) {
      // Light on heavy, 1:1,000 to 1:100,000: holds as equal masses do, the
      // boxes 1.000 ± 0.001 m apart, the lower one 0.001 m from its rest.
      CHECK(lowest_gap == Approx(1.0L).margin(0.001L));
      CHECK(gap == Approx(1.0L).margin(0.001L));
      CHECK(lowest_lower > 0.499L);
      CHECK(widest_x < 0.001L);
    } else if (ratio <= 10.5L) {
      // 1:10 holds: the heavy box rests on the light one within 1 cm.
      CHECK(gap == Approx(1.0L).margin(0.01L));
      CHECK(lowest_lower > 0.49L);
    } else {
      // 1:100 to 1:100,000 (also 100 kg on 0.001 kg) hold alike: the
      // contact's mass-ratio cap (contact_prepare.cpp, issue 14) makes a body
      // more than 100 times lighter respond in a resting contact as one 100
      // times lighter, so every heavy-on-light stack moves as the 1:100 one:
      // the boxes overlap by 0.036 m (0.964 ± 0.002 m apart, lowest and
      // final), the lower one pressed under 0.01 m into the ground, no
      // sideways motion (< 0.01 m). (Before the cap 1:1,000 sank 0.85 m and
      // 1:10,000 and 1:100,000 tunnelled.)
      CHECK(lowest_gap == Approx(0.964L).margin(0.002L));
      CHECK(gap == Approx(0.964L).margin(0.002L));
      CHECK(lowest_lower > 0.49L);
      CHECK(widest_x < 0.01L);
    }
    // Nothing goes through the ground: the lower box's centre stays above
    // 0.39 m (pressed at most 0.11 m into the ground), the upper one's above
    // 0.48 m.
    CHECK(lowest_lower > 0.39L);
    CHECK(lowest_upper > 0.48L);
  }
  CHECK(faults.count() == 0);
}

TEST_CASE("limits: 1:100,000 impacts at 10 and 100 m/s: both end side by side, nothing goes through the ground, no fault",
          "[stress][limits]") {
  FaultCount faults;
  // A 1 m heavy box thrown down at 10 or 100 m/s onto a 1 m light box resting
  // on a 2 m thick static ground (top face at y = 0), 100,000 kg on 1 kg and
  // 100 kg on 0.001 kg. An impact keeps the true masses (the mass-ratio cap
  // is for resting contacts only, contact_prepare.cpp), and such a contact
  // warm-starts with at most the impulse that changes the light body's
  // velocity by the restitution threshold (a stored impulse may come from a
  // capped step: stress seed 6298). The heavy box passes into the light one,
  // pressing it into the ground (measured: lowest light centre -0.260 m at
  // 10 m/s, 0.120 m at 100 m/s; the ground's bottom is at -2 m); then the
  // two are pushed apart and both end side by side on the ground (0.5 m).
  // Neither goes through the ground.
  struct Case { Q32 light; Q32 heavy; Q32 speed; };
  const Case cases[] = {{1_q32, 100000_q32, 10_q32}, {1_q32, 100000_q32, 100_q32},
                        {0.001_q32, 100_q32, 10_q32}, {0.001_q32, 100_q32, 100_q32}};
  for (const Case& c : cases) {
    TestWorld w;
    static_box(w.id, Vec2{0_q32, -1_q32}, 20_q32, 1_q32);
    const BodyId light = dynamic_box(w.id, Vec2{0_q32, 0.5_q32}, 0.5_q32, 0.5_q32, c.light);
    const BodyId heavy = dynamic_box(w.id, Vec2{0_q32, 3_q32}, 0.5_q32, 0.5_q32, c.heavy);
    REQUIRE(body_set_linear_velocity(heavy, Vec2{0_q32, -c.speed}).ok());
    long double lowest_light = 1e9L, lowest_heavy = 1e9L;
    for (int t = 0; t < 300; ++t) {
      REQUIRE(world_step(w.id, k_dt).ok());
      lowest_light = std::min(lowest_light, ld(body_world_center(light).y));
      lowest_heavy = std::min(lowest_heavy, ld(body_world_center(heavy).y));
    }
    std::printf("limits: %g kg at %g m/s onto %g kg: lowest centres light %.4Lf m, heavy %.4Lf m; final light %.4Lf, "
                "heavy %.4Lf (ground top at 0)\n",
                body_mass(heavy).to_double(), c.speed.to_double(), body_mass(light).to_double(), lowest_light,
                lowest_heavy, ld(body_world_center(light).y), ld(body_world_center(heavy).y));
    INFO(body_mass(heavy).to_double() << " kg at " << c.speed.to_double() << " m/s onto " << body_mass(light).to_double()
                                      << " kg");
    CHECK(lowest_light > -0.3L);
    CHECK(lowest_heavy > 0.35L);
    // At rest after 5 s, within the linear slop, side by side on the ground.
    CHECK(ld(body_world_center(light).y) == Approx(0.5L).margin(0.005L));
    CHECK(ld(body_world_center(heavy).y) == Approx(0.5L).margin(0.005L));
    CHECK(std::fabs(ld(body_world_center(light).x - body_world_center(heavy).x)) > 0.99L);
  }
  CHECK(faults.count() == 0);
}

// One heavy-on-light impact: a 1 m box of `heavy` kg thrown down at `speed`
// m/s from 3 m onto a 1 m box of `light` kg resting on a 40 m wide, 2 m thick
// static ground (top face at y = 0); 600 steps. What the range table quotes.
struct ImpactRun {
  long double lowest_light = 1e9L, highest = 0, widest = 0;  // centres, m
  long double final_light = 0, final_heavy = 0, final_speed = 0;
};
ImpactRun impact(Q32 heavy_kg, Q32 light_kg, Q32 speed) {
  TestWorld w;
  static_box(w.id, Vec2{0_q32, -1_q32}, 20_q32, 1_q32);
  const BodyId light = dynamic_box(w.id, Vec2{0_q32, 0.5_q32}, 0.5_q32, 0.5_q32, light_kg);
  const BodyId heavy = dynamic_box(w.id, Vec2{0_q32, 3_q32}, 0.5_q32, 0.5_q32, heavy_kg);
  REQUIRE(body_set_linear_velocity(heavy, Vec2{0_q32, -speed}).ok());
  ImpactRun r;
  for (int t = 0; t < 600; ++t) {
    REQUIRE(world_step(w.id, k_dt).ok());
    const Vec2 pl = body_world_center(light), ph = body_world_center(heavy);
    r.lowest_light = std::min(r.lowest_light, ld(pl.y));
    r.highest = std::max({r.highest, ld(pl.y), ld(ph.y)});
    r.widest = std::max({r.widest, ld(abs(pl.x)), ld(abs(ph.x))});
  }
  r.final_light = ld(body_world_center(light).y);
  r.final_heavy = ld(body_world_center(heavy).y);
  for (BodyId b : {light, heavy})
    r.final_speed = std::max({r.final_speed, ld(abs(body_linear_velocity(b).x)), ld(abs(body_linear_velocity(b).y))});
  return r;
}

TEST_CASE("limits: heavy-on-light impacts at 5 to 40 m/s, mass ratios 1:1 to 1:100,000: the pair stays on the ground and "
          "comes to rest on it, no fault",
          "[stress][limits]") {
  FaultCount faults;
  // Dynamic against dynamic there is no continuous collision (non-bullets):
  // at these speeds the heavy box moves 0.08-0.67 m a step and may start a
  // step deep inside the light one. The soft contact then separates them
  // faster than max_contact_push_speed (the warm-started impulse of the
  // impact, solved against the ground: measured 47 m/s at 1:10, 100 m/s), so
  // the pair can be thrown up; what is asserted is that it stays over the
  // ground, is not pushed through it and ends at rest on it. Measured
  // 2026-11-28: lowest light centre -0.295 m (1:100,000 at 15 m/s), highest
  // centre 21.14 m (1:10 at 40 m/s), widest 15.18 m (1:10 at 40 m/s).
  const Q32 ratios[] = {1_q32, 10_q32, 100_q32, 1000_q32, 100000_q32};
  for (const Q32 heavy : ratios) {
    for (int v = 5; v <= 40; v += 5) {
      const ImpactRun r = impact(heavy, 1_q32, Q32::from_int(v));
      INFO(heavy.to_double() << " kg onto 1 kg at " << v << " m/s: lowest light " << static_cast<double>(r.lowest_light)
                             << ", highest " << static_cast<double>(r.highest) << ", widest "
                             << static_cast<double>(r.widest) << ", final light " << static_cast<double>(r.final_light)
                             << ", heavy " << static_cast<double>(r.final_heavy));
      CHECK(r.lowest_light > -0.35L);  // pressed at most 0.85 m into the 2 m ground
      CHECK(r.highest < 22.0L);
      CHECK(r.widest < 16.0L);  // over the ground (half width 20 m) all the time
      // At rest on the ground: the light box within 0.01 m of 0.5; the heavy
      // one beside it (0.5) or on it (1.5; above 1:100 the mass-ratio cap
      // leaves the pair overlapping by 0.034-0.043 m: 1.457 here).
      CHECK(r.final_speed < 0.01L);
      CHECK(r.final_light == Approx(0.5L).margin(0.01L));
      const bool beside = std::fabs(r.final_heavy - 0.5L) < 0.01L;
      const bool on_top = r.final_heavy > 1.45L && r.final_heavy < 1.51L;
      CHECK((beside || on_top));
    }
  }
  CHECK(faults.count() == 0);
}

// Known issue (2026-11-28, README range table): from 45 m/s some impacts
// throw the pair sideways off the 40 m ground and it falls past its edge
// (measured in 300 steps: 1:100 at 45, 50, 55, 90 and 100 m/s, 1:10 at 45 and
// 50 m/s). Hidden: it passes while the issue stands and fails once the pair
// stays on the ground.
TEST_CASE("known issue 6: a 100 kg box at 100 m/s onto a 1 kg box throws both off a 40 m ground", "[.][known-issue][stress]") {
  const ImpactRun r = impact(100_q32, 1_q32, 100_q32);
  std::printf("known issue 6: widest %.2Lf m, final light %.3Lf m, heavy %.3Lf m\n", r.widest, r.final_light,
              r.final_heavy);
  CHECK(r.widest > 20.0L);
  CHECK(r.final_light < -1.0L);
}

TEST_CASE("limits: bodies at the mass, inertia and size limits, no fault", "[stress][limits]") {
  FaultCount faults;
  TestWorld w;
  // A 20,000 m ground: one box of half width 9,999 m (shape extent ≤ 10,000 m).
  static_box(w.id, Vec2{0_q32, -1_q32}, 9999_q32, 1_q32);
  // The lightest and the heaviest body the API accepts.
  const BodyId light = dynamic_box(w.id, Vec2{-9990_q32, 0.5_q32}, 0.5_q32, 0.5_q32, k_min_body_mass);
  const BodyId heavy = dynamic_box(w.id, Vec2{9990_q32, 1_q32}, 1_q32, 1_q32, k_max_body_mass / 4);
  CHECK(body_mass(light) == k_min_body_mass);
  CHECK(body_mass(heavy) == k_max_body_mass);
  // The smallest shapes: a 0.005 m circle and a 0.005 m box far out on the ground.
  BodyDef bd = default_body_def();
  bd.type = BodyType::dynamic_body;
  bd.position = Vec2{5000_q32, 0.005_q32};
  const BodyId tiny_circle = create_body(w.id, bd).value;
  ShapeDef dense = default_shape_def();
  dense.density = 100_q32;  // 0.0079 kg: at density 1 a 0.005 m circle is below the 0.001 kg mass limit
  REQUIRE(create_circle_shape(tiny_circle, dense, Circle{Vec2{}, k_min_shape_size}).ok());
  const BodyId tiny_box = dynamic_box(w.id, Vec2{-5000_q32, 0.005_q32}, k_min_shape_size, k_min_shape_size, 100_q32);
  // A plank at the inertia limit: 100 m × 0.2 m, 1,190 kg, I ≈ 991,670 kg·m²,
  // dropped turning slowly. (Spun at the largest angular speed the API
  // accepts, its tips move at ~2,300 m/s and the impact throws it kilometres
  // up: physical, not a fault, but no resting height to assert.)
  const BodyId plank = dynamic_box(w.id, Vec2{0_q32, 60_q32}, 50_q32, 0.1_q32, 59.5_q32);
  CHECK(body_rotational_inertia(plank) <= k_max_rotational_inertia);
  CHECK(ld(body_rotational_inertia(plank)) > 990000.0L);
  REQUIRE(body_set_angular_velocity(plank, 0.2_q32).ok());
  // A light 200 m box (the largest dynamic box under the inertia limit at its density).
  const BodyId big = dynamic_box(w.id, Vec2{3000_q32, 100_q32}, 100_q32, 100_q32, 0.000001_q32);
  CHECK(body_rotational_inertia(big) <= k_max_rotational_inertia);
  step(w.id, 900);
  std::printf("limits: rest heights: 0.001 kg box %.5Lf (0.5), 100,000 kg box %.5Lf (1.0), 0.005 m circle %.6Lf (0.005), "
              "0.005 m box %.6Lf (0.005), plank %.4Lf (0.1), 200 m box %.4Lf (100)\n",
              ld(body_world_center(light).y), ld(body_world_center(heavy).y), ld(body_world_center(tiny_circle).y),
              ld(body_world_center(tiny_box).y), ld(body_world_center(plank).y), ld(body_world_center(big).y));
  // Each rests on the ground within the linear slop (0.005 m).
  CHECK(ld(body_world_center(light).y) == Approx(0.5L).margin(0.005L));
  CHECK(ld(body_world_center(heavy).y) == Approx(1.0L).margin(0.005L));
  CHECK(ld(body_world_center(tiny_circle).y) == Approx(0.005L).margin(0.005L));
  CHECK(ld(body_world_center(tiny_box).y) == Approx(0.005L).margin(0.005L));
  CHECK(ld(body_world_center(plank).y) == Approx(0.1L).margin(0.005L));
  CHECK(ld(body_world_center(big).y) == Approx(100.0L).margin(0.005L));
  CHECK(faults.count() == 0);
}

namespace {

/// Fires a projectile at `speed` m/s (direction (cos, sin) of `angle_deg` from
/// +x, towards a static wall whose near face is at x = 1 m) and returns the
/// largest x its centre reached (the wall's far face is at 1 + thickness).
long double fire(int kind, Q32 size, Q32 speed, Q32 thickness, int angle_deg, Q32 spin, bool* out_through) {
  WorldDef def = default_world_def();
  def.max_linear_speed = k_max_linear_speed;
  def.gravity = Vec2{};
  TestWorld w(def);
  BodyDef wd = default_body_def();
  wd.position = Vec2{1_q32 + thickness / 2, 0_q32};
  const BodyId wall = create_body(w.id, wd).value;
  Polygon box;
  REQUIRE(make_box(thickness / 2, 50_q32, &box).ok());
  REQUIRE(create_polygon_shape(wall, default_shape_def(), box).ok());
  BodyDef bd = default_body_def();
  bd.type = BodyType::dynamic_body;
  bd.position = Vec2{-3_q32, 0_q32};
  const Rot dir = rot_from_angle(Q32(angle_deg) * k_pi / 180);
  const Q32 v = speed - 0.0001_q32;  // |(c, s)| may round a raw unit above 1
  bd.linear_velocity = Vec2{dir.c * v, dir.s * v};
  bd.angular_velocity = spin;
  Result<BodyId> b = create_body(w.id, bd);
  REQUIRE(b.ok());
  ShapeDef sd = default_shape_def();
  sd.density = 1000_q32;  // the 0.005 m shapes stay above the 0.001 kg mass limit
  Result<ShapeId> s;
  if (kind == 0) s = create_circle_shape(b.value, sd, Circle{Vec2{}, size});
  if (kind == 1) {
    Polygon p;
    REQUIRE(make_box(size, size, &p).ok());
    s = create_polygon_shape(b.value, sd, p);
  }
  if (kind == 2) s = create_capsule_shape(b.value, sd, Capsule{Vec2{-size * 4, 0_q32}, Vec2{size * 4, 0_q32}, size});
  REQUIRE(s.ok());
  long double far = -1e9L;
  for (int t = 0; t < 60; ++t) {
    REQUIRE(world_step(w.id, k_dt).ok());
    far = std::max(far, ld(body_world_center(b.value).x));
  }
  *out_through = ld(body_world_center(b.value).x) > ld(1_q32 + thickness / 2);
  return far;
}

/// The shots of the tunnelling grid: 3 shapes × 3 sizes × 4 speeds × 3 wall
/// thicknesses × 3 angles × 2 spins = 648. Returns how many went through;
/// `only_tiny_circles` counts only the 0.005 m circles, otherwise only the rest.
int tunnelling_grid(bool tiny_circles) {
  const Q32 speeds[] = {10_q32, 100_q32, 400_q32, k_max_linear_speed};
  const Q32 sizes[] = {k_min_shape_size, 0.05_q32, 0.5_q32};
  const Q32 walls[] = {k_min_shape_size * 2, 0.1_q32, 1_q32};
  const int angles[] = {0, 30, 60};
  int shots = 0, through = 0;
  for (int kind = 0; kind < 3; ++kind)
    for (Q32 size : sizes)
      for (Q32 speed : speeds)
        for (Q32 wall : walls)
          for (int angle : angles)
            for (Q32 spin : {0_q32, 40_q32}) {
              const bool tiny_circle = kind == 0 && size == k_min_shape_size;
              if (tiny_circle != tiny_circles) continue;
              bool passed = false;
              (void)fire(kind, size, speed, wall, angle, spin, &passed);
              ++shots;
              if (passed) {
                ++through;
                std::printf("through: kind %d size %g speed %g wall %g angle %d spin %g\n", kind, size.to_double(),
                            speed.to_double(), wall.to_double(), angle, spin.to_double());
              }
            }
  std::printf("limits: %d shots at static walls (%s), %d went through\n", shots,
              tiny_circles ? "0.005 m circles" : "circles >= 0.05 m, boxes and capsules >= 0.005 m", through);
  return through;
}

}  // namespace

// Circles, boxes and capsules of 0.005–0.5 m fired at 10–1000 m/s, straight
// and at 30° and 60°, spinning or not, at static walls 0.01, 0.1 and 1 m
// thick: none goes through. The 0.005 m circles run as a test of their own.
TEST_CASE("limits: no tunnelling through static walls >= 0.01 m up to 1000 m/s (isolated body), no fault",
          "[stress][limits]") {
  FaultCount faults;
  CHECK(tunnelling_grid(false) == 0);
  CHECK(faults.count() == 0);
}

// Formerly KNOWN ISSUE 3: a 0.005 m circle went through a 0.01 m static wall
// at 100 m/s (30°) and 400 m/s (60°), and at 1000 m/s through 0.01 m and
// 0.1 m walls head on — 8 of its 72 shots. Continuous collision stopped the
// circle touching the wall (cores at total radius − k_linear_slop); the next
// step's contact started touching, hence soft, and let ~2 % of the speed
// through in its first sub-step, and continuous collision, sweeping only a
// core at the centroid of a shape that starts a step touching, could not
// stop it: the circle's centre already lay within the core's default
// stopping distance of the wall (k_linear_slop), so the sweep reported a hit
// at t = 0, which is ignored. The core now stops halfway to the obstacle in
// that case (continuous.cpp, time_of_impact_to): none of the 72 goes
// through. (Backing the first stop off by 2·k_linear_slop also fixed the
// shots but changed every golden scene; this fix changes only the chains
// scene.)
TEST_CASE("limits: the smallest circles (0.005 m) do not tunnel through static walls >= 0.01 m up to 1000 m/s",
          "[stress][limits]") {
  FaultCount faults;
  CHECK(tunnelling_grid(true) == 0);
  CHECK(faults.count() == 0);
}
