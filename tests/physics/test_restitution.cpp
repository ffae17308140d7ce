// Tests restitution in a many-body scene through the public API: the
// "circles" scene of shared/reference/peer-bench/scene.h (N circles, radius
// 0.4-0.6 m, velocity components in [-5, 5] m/s, drawn from the same
// splitmix64 sequence and seed 12345, placed on a random subset of a 1.2 m
// lattice; a closed square box of 4 static walls sized for 25 % area
// coverage; no gravity, restitution 1, friction 0, sleep off), stepped at
// 60 Hz with 4 sub-steps. Every collision is elastic, so the total kinetic
// energy should stay where it started; the sub-step bounce of
// contact_solver.cpp measured −0.5 % to −2.2 % in the reference study
// (shared/reference/restitution/README.md) over 360 steps.
//
// The scene values are computed in double (tests may use doubles) and
// rounded once to Q32.32, so the scene matches scene.h to ~1e-10 m.
// Full size (N = 1000, 360 steps) in Release; Debug and sanitizer builds use
// N = 100 and 120 steps. Measured values are printed with WARN.
#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <vector>

#include "physics/tandem.h"
#include "fixed/splitmix64.h"
#include "physics_test_support.h"
#include "tests/readme_quote.h"

using namespace tandem;
using namespace tandem::test_support;

namespace {

/// splitmix64, as in scene.h: a fixed, portable sequence.
struct SplitMix64 {
  uint64_t s;
  uint64_t next() {
    return splitmix64_next(&s);
  }
  /// Uniform in [a, b), from the top 53 bits.
  double uni(double a, double b) {
    return a + (b - a) * (static_cast<double>(next() >> 11) * (1.0 / 9007199254740992.0));
  }
};

/// A double rounded to the nearest Q32.32 (test-side conversion).
Q32 q(double v) { return Q32::from_raw(std::llround(std::ldexp(v, 32))); }

struct CirclesScene {
  std::vector<BodyId> circles;
  double half = 0;  ///< interior half side L/2, m
};

/// Builds scene.h's makeCircles(n, 12345) in world w.
CirclesScene make_circles(WorldId w, int n) {
  SplitMix64 rng{12345};
  const double pi = 3.14159265358979323846;
  const double mean_area = pi * (0.25 + 0.04 / 12.0);  // E[πr²], r ~ U(0.4, 0.6)
  const double side = std::sqrt(n * mean_area / 0.25);
  const double cell = 1.2;
  const int cells = static_cast<int>(std::floor(side / cell));
  std::vector<int> idx(static_cast<size_t>(cells * cells));
  for (int i = 0; i < cells * cells; ++i) idx[static_cast<size_t>(i)] = i;
  for (int i = cells * cells - 1; i > 0; --i) {  // Fisher-Yates
    const int j = static_cast<int>(rng.next() % static_cast<uint64_t>(i + 1));
    std::swap(idx[static_cast<size_t>(i)], idx[static_cast<size_t>(j)]);
  }
  ShapeDef sd = default_shape_def();
  sd.friction = 0_q32;
  sd.restitution = 1_q32;
  sd.density = 1_q32;
  const double wall = 1.0;  // half thickness
  const auto add_wall = [&](double cx, double cy, double hx, double hy) {
    BodyDef def = default_body_def();
    def.position = {q(cx), q(cy)};
    Result<BodyId> b = create_body(w, def);
    REQUIRE(b.ok());
    Polygon box;
    REQUIRE(make_box(q(hx), q(hy), &box).ok());
    REQUIRE(create_polygon_shape(b.value, sd, box).ok());
  };
  add_wall(0, -side / 2 - wall, side / 2 + 2 * wall, wall);
  add_wall(0, side / 2 + wall, side / 2 + 2 * wall, wall);
  add_wall(-side / 2 - wall, 0, wall, side / 2 + 2 * wall);
  add_wall(side / 2 + wall, 0, wall, side / 2 + 2 * wall);
  const double origin = -side / 2 + (side - cells * cell) / 2 + cell / 2;
  CirclesScene scene;
  scene.half = side / 2;
  for (int k = 0; k < n; ++k) {
    const int c = idx[static_cast<size_t>(k)];
    BodyDef def = default_body_def();
    def.type = BodyType::dynamic_body;
    def.enable_sleep = false;
    def.position = {q(origin + (c % cells) * cell), q(origin + (c / cells) * cell)};
    const double r = rng.uni(0.4, 0.6);
    const double vx = rng.uni(-5, 5), vy = rng.uni(-5, 5);
    def.linear_velocity = {q(vx), q(vy)};
    Result<BodyId> b = create_body(w, def);
    REQUIRE(b.ok());
    REQUIRE(create_circle_shape(b.value, sd, Circle{{}, q(r)}).ok());
    scene.circles.push_back(b.value);
  }
  return scene;
}

long double total_kinetic_energy(const std::vector<BodyId>& bodies) {
  long double ke = 0;
  for (const BodyId b : bodies) {
    const Vec2 v = body_linear_velocity(b);
    const long double om = ld(body_angular_velocity(b));
    ke += 0.5L * ld(body_mass(b)) * (ld(v.x) * ld(v.x) + ld(v.y) * ld(v.y)) +
          0.5L * ld(body_rotational_inertia(b)) * om * om;
  }
  return ke;
}

/// Deepest overlap between two circles (O(n²), called once), m.
long double max_overlap(const std::vector<BodyId>& bodies, const std::vector<long double>& radii) {
  long double worst = 0;
  for (size_t i = 0; i < bodies.size(); ++i) {
    const Vec2 a = body_world_center(bodies[i]);
    for (size_t j = i + 1; j < bodies.size(); ++j) {
      const Vec2 b = body_world_center(bodies[j]);
      const long double dx = ld(a.x) - ld(b.x), dy = ld(a.y) - ld(b.y);
      const long double reach = radii[i] + radii[j];
      if (std::fabs(dx) >= reach || std::fabs(dy) >= reach) continue;
      worst = std::max(worst, reach - std::sqrt(dx * dx + dy * dy));
    }
  }
  return worst;
}

}  // namespace

TEST_CASE("elastic circles in a closed box keep their kinetic energy", "[physics][restitution]") {
#ifdef NDEBUG
  const int n = 1000, steps = 360;
#else
  const int n = 100, steps = 120;  // Debug / sanitizers: smaller and shorter
#endif
  WorldDef def = default_world_def();
  def.gravity = {0_q32, 0_q32};
  def.sub_step_count = 4;
  def.enable_sleep = false;
  ScopedWorld w(def);
  const CirclesScene scene = make_circles(w.id, n);
  REQUIRE(scene.circles.size() == static_cast<size_t>(n));
  std::vector<long double> radii;
  for (const BodyId b : scene.circles) {
    // mass = density·π·r² with density 1 → r = √(m/π)
    radii.push_back(std::sqrt(ld(body_mass(b)) / 3.14159265358979323846L));
  }

  const long double ke0 = total_kinetic_energy(scene.circles);
  REQUIRE(ke0 > 0);
  long double highest = ke0, lowest = ke0;
  int outside_steps = 0;  // circle-steps with the centre beyond an inner wall face
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < steps; ++i) {
    REQUIRE(world_step(w.id, k_dt).ok());
    const long double ke = total_kinetic_energy(scene.circles);
    highest = std::max(highest, ke);
    lowest = std::min(lowest, ke);
    for (const BodyId b : scene.circles) {
      const Vec2 c = body_world_center(b);
      if (std::max(std::fabs(ld(c.x)), std::fabs(ld(c.y))) > static_cast<long double>(scene.half)) ++outside_steps;
    }
  }
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count() / steps;
  const long double ke1 = total_kinetic_energy(scene.circles);
  const long double change = ke1 / ke0 - 1;
  const long double overlap = max_overlap(scene.circles, radii);
  WARN("elastic circles N = " << n << ", " << steps << " steps: dKE = " << change * 100 << " % (min "
                              << (lowest / ke0 - 1) * 100 << " %, max " << (highest / ke0 - 1) * 100
                              << " %), circle-steps outside the box " << outside_steps << ", max overlap at end "
                              << overlap * 1000 << " mm, " << ms << " ms/step (incl. KE bookkeeping)");
  // The bound: the reference study measured −0.5 % (N = 4000) to −2.2 % (N = 1000)
  // in Q32.32 with this formulation; 3 % leaves room for the scene differences
  // (polygon walls, our manifolds) without hiding a regression to v3's −20 %.
  // Not ±1 % (the bound for the dropped ball): the loss here is mostly
  // the restitution threshold (approaches below 1 m/s are inelastic, and a
  // closed gas develops a slow tail), which this scene cannot avoid at the
  // default threshold; lowering it trades the loss for a small energy gain.
  CHECK(std::fabs(change) <= 0.03L);
  // No energy gain: an elastic scene must never get more than +1 % above its start.
  CHECK(highest <= ke0 * 1.01L);
  CHECK(outside_steps == 0);
#ifdef NDEBUG
  // The README quotes the full-size loss to 2 decimals, and the same scene
  // with a 0.5 m/s restitution threshold (most of the loss is the default
  // 1 m/s threshold).
  const auto percent = [](long double c) {
    return (c < 0 ? "−" : "+") + readme::fixed(std::fabs(c) * 100, 2) + " %";
  };
  WorldDef def_half = def;
  def_half.restitution_threshold = 0.5_q32;
  ScopedWorld w_half(def_half);
  const CirclesScene half = make_circles(w_half.id, n);
  const long double ke0_half = total_kinetic_energy(half.circles);
  for (int i = 0; i < steps; ++i) REQUIRE(world_step(w_half.id, k_dt).ok());
  const long double change_half = total_kinetic_energy(half.circles) / ke0_half - 1;
  WARN("elastic circles with a 0.5 m/s restitution threshold: dKE = " << change_half * 100 << " %");
  REQUIRE(change < 0);
  readme::check_quotes("1000 elastic circles in a closed box (the report's scene) lose " +
                       readme::fixed(-change * 100, 2) + " % of their kinetic energy over 360 steps");
  readme::check_quotes("(0.5 m/s gives " + percent(change_half) + ")");
#endif
}
