// scenes.cpp — the benchmark scene generators (see scenes.h for the scenes
// and for why every value is built from integers).
#include "scenes.h"

#include "fixed/splitmix64.h"

#include <algorithm>
#include <cstdlib>
#include <utility>

#include "fixed/fixed_math.h"
#include "fixed/vec2.h"

namespace tandem::bench {
namespace {

/// splitmix64: a fixed, portable sequence (as scene.h).
struct SplitMix64 {
  uint64_t s;
  uint64_t next() {
    return splitmix64_next(&s);
  }
  /// Uniform in [a, b): a + (b − a)·u with u the top 32 bits of a draw as a
  /// Q32.32 fraction in [0, 1), one rounded Q32 product.
  Q32 uni(Q32 a, Q32 b) {
    const Q32 u = Q32::from_raw(static_cast<int64_t>(next() >> 32));
    return a + (b - a) * u;
  }
};

Q32 q_int(int64_t v) { return Q32::from_int(v); }
Q32 q_ratio(int64_t num, int64_t den) { return Q32::from_ratio(num, den); }

BodySpec static_box(Q32 cx, Q32 cy, Q32 hx, Q32 hy, Q32 friction, Q32 restitution) {
  BodySpec b;
  b.dynamic = false;
  b.shape = ShapeKind::box;
  b.x = cx;
  b.y = cy;
  b.half_width = hx;
  b.half_height = hy;
  b.friction = friction;
  b.restitution = restitution;
  b.density = Q32::one();
  return b;
}

}  // namespace

Q32 time_step() { return Q32::from_ratio(1, 60); }

SceneSpec make_circles(int32_t n, uint64_t seed) {
  SceneSpec s;
  s.name = "circles-" + std::to_string(n);
  s.family = "circles";
  s.size = n;
  s.warmup_steps = 60;
  s.timed_steps = 300;
  SplitMix64 rng{seed};
  // Box side L for 25 % coverage: n·E[πr²] / L² = 1/4 with E[r²] = 0.25 + 0.04/12
  // for r ~ U(0.4, 0.6), so L² = n·π·(1 + 1/75) = n·π·76/75.
  const Q32 side = sqrt(k_pi * q_ratio(76, 75) * q_int(n));
  const Q32 half = side / q_int(2);
  const Q32 cell = q_ratio(6, 5);
  const int64_t cells = (side / cell).floor_int();
  std::vector<int64_t> idx(static_cast<size_t>(cells * cells));
  for (size_t i = 0; i < idx.size(); ++i) idx[i] = static_cast<int64_t>(i);
  for (size_t i = idx.size() - 1; i > 0; --i) {  // Fisher-Yates, as scene.h
    const auto j = static_cast<size_t>(rng.next() % static_cast<uint64_t>(i + 1));
    std::swap(idx[i], idx[j]);
  }
  const Q32 wall = Q32::one();  // half thickness
  const Q32 zero{};
  const Q32 one = Q32::one();
  const Q32 long_half = half + q_int(2);
  s.bodies.push_back(static_box(zero, -half - wall, long_half, wall, zero, one));
  s.bodies.push_back(static_box(zero, half + wall, long_half, wall, zero, one));
  s.bodies.push_back(static_box(-half - wall, zero, wall, long_half, zero, one));
  s.bodies.push_back(static_box(half + wall, zero, wall, long_half, zero, one));
  const Q32 origin = -half + (side - q_int(cells) * cell) / q_int(2) + cell / q_int(2);
  for (int32_t k = 0; k < n; ++k) {
    const int64_t c = idx[static_cast<size_t>(k)];
    BodySpec b;
    b.dynamic = true;
    b.shape = ShapeKind::circle;
    b.x = origin + q_int(c % cells) * cell;
    b.y = origin + q_int(c / cells) * cell;
    b.radius = rng.uni(q_ratio(2, 5), q_ratio(3, 5));
    b.vx = rng.uni(q_int(-5), q_int(5));
    b.vy = rng.uni(q_int(-5), q_int(5));
    b.friction = zero;
    b.restitution = one;
    b.density = one;
    s.bodies.push_back(b);
  }
  s.dynamic_count = n;
  const double lim = to_double(half) + 0.01;
  s.container = {-lim, lim, -lim, lim};
  return s;
}

SceneSpec make_pyramid(int32_t base) {
  SceneSpec s;
  s.name = "pyramid-" + std::to_string(base);
  s.family = "pyramid";
  s.size = base;
  s.warmup_steps = 0;
  s.timed_steps = 500;
  s.gravity_y = q_int(-10);
  const Q32 a = Q32::half();
  const Q32 friction = q_ratio(3, 5);
  const Q32 ground_half = std::max(q_int(100), a * q_int(base) + q_int(10));
  s.bodies.push_back(static_box(Q32{}, q_int(-1), ground_half, Q32::one(), friction, Q32{}));
  for (int32_t i = 0; i < base; ++i) {
    const Q32 y = q_int(2 * i + 1) * a;
    for (int32_t j = i; j < base; ++j) {
      BodySpec b;
      b.dynamic = true;
      b.shape = ShapeKind::box;
      b.x = q_int(i + 1) * a + q_int(2 * (j - i)) * a - a * q_int(base);
      b.y = y;
      b.half_width = a;
      b.half_height = a;
      b.friction = friction;
      b.density = Q32::one();
      s.bodies.push_back(b);
      ++s.dynamic_count;
    }
  }
  s.track_index = static_cast<int32_t>(s.bodies.size()) - 1;  // the last one made is the top box
  s.container.min_y = -0.5;
  return s;
}

SceneSpec make_rain(int32_t n, uint64_t seed) {
  SceneSpec s;
  s.name = "rain-" + std::to_string(n);
  s.family = "rain";
  s.size = n;
  s.warmup_steps = 0;
  s.timed_steps = 600;
  s.gravity_y = q_int(-10);
  SplitMix64 rng{seed};
  const Q32 friction = q_ratio(3, 5);
  const Q32 zero{};
  s.bodies.push_back(static_box(zero, q_int(-1), q_int(42), Q32::one(), friction, zero));
  s.bodies.push_back(static_box(q_int(-41), q_int(74), Q32::one(), q_int(75), friction, zero));
  s.bodies.push_back(static_box(q_int(41), q_int(74), Q32::one(), q_int(75), friction, zero));
  constexpr int32_t cols = 50;
  const Q32 spacing = q_ratio(3, 2);
  const Q32 left = q_ratio(-49 * 3, 4);  // −(cols − 1)/2 · 1.5
  for (int32_t k = 0; k < n; ++k) {
    const int32_t row = k / cols, col = k % cols;
    BodySpec b;
    b.dynamic = true;
    b.x = left + q_int(col) * spacing + rng.uni(q_ratio(-1, 10), q_ratio(1, 10));
    b.y = q_int(5) + q_int(row) * spacing;
    switch (k % 3) {
      case 0:
        b.shape = ShapeKind::circle;
        b.radius = rng.uni(q_ratio(2, 5), q_ratio(3, 5));
        break;
      case 1:
        b.shape = ShapeKind::box;
        b.half_width = rng.uni(q_ratio(7, 20), q_ratio(1, 2));
        b.half_height = b.half_width;
        break;
      default:
        b.shape = ShapeKind::capsule;
        b.radius = rng.uni(q_ratio(1, 5), q_ratio(3, 10));
        b.half_width = rng.uni(q_ratio(1, 5), q_ratio(2, 5));
        break;
    }
    b.friction = friction;
    b.restitution = zero;
    b.density = Q32::one();
    s.bodies.push_back(b);
    ++s.dynamic_count;
  }
  s.container.min_x = -40.01;
  s.container.max_x = 40.01;
  s.container.min_y = -0.01;
  return s;
}

SceneSpec make_many_pyramids(int32_t rows, int32_t columns, int32_t base) {
  SceneSpec s;
  s.name = "many_pyramids";
  s.family = "many_pyramids";
  s.size = rows * columns;
  s.warmup_steps = 0;
  s.timed_steps = 200;
  s.gravity_y = q_int(-10);
  const Q32 a = Q32::half();  // box half extent
  const Q32 friction = q_ratio(3, 5);
  const Q32 ground_dy = q_int(2) * a * q_int(base + 1);                 // 11 m
  const Q32 ground_width = q_int(2) * a * q_int(columns) * q_int(base + 1);  // 220 m
  for (int32_t i = 0; i < rows; ++i) {
    BodySpec g;
    g.dynamic = false;
    g.shape = ShapeKind::segment;
    g.x = Q32{};
    g.y = q_int(i) * ground_dy;
    g.half_width = ground_width / q_int(2);
    g.friction = friction;
    g.density = Q32::one();
    s.bodies.push_back(g);
  }
  const Q32 base_width = q_int(2) * a * q_int(base);
  for (int32_t r = 0; r < rows; ++r) {
    const Q32 base_y = q_int(r) * ground_dy;
    for (int32_t c = 0; c < columns; ++c) {
      const Q32 center_x = -(ground_width / q_int(2)) + q_int(c) * (base_width + q_int(2) * a) + q_int(2) * a;
      for (int32_t i = 0; i < base; ++i) {
        const Q32 y = q_int(2 * i + 1) * a + base_y;
        for (int32_t j = i; j < base; ++j) {
          BodySpec b;
          b.dynamic = true;
          b.shape = ShapeKind::box;
          b.x = q_int(i + 1) * a + q_int(2 * (j - i)) * a + center_x - Q32::half();
          b.y = y;
          b.half_width = a;
          b.half_height = a;
          b.friction = friction;
          b.density = Q32::one();
          s.bodies.push_back(b);
          ++s.dynamic_count;
        }
      }
    }
  }
  s.container.min_x = -to_double(ground_width) / 2 - 0.01;
  s.container.max_x = to_double(ground_width) / 2 + 0.01;
  s.container.min_y = -0.01;
  return s;
}

SceneSpec make_smash(int32_t columns, int32_t rows) {
  SceneSpec s;
  s.name = "smash";
  s.family = "smash";
  s.size = columns * rows;
  s.warmup_steps = 0;
  s.timed_steps = 300;
  s.sleep = true;
  const Q32 friction = q_ratio(3, 5);
  BodySpec hammer;
  hammer.dynamic = true;
  hammer.shape = ShapeKind::box;
  hammer.x = q_int(-20);
  hammer.vx = q_int(40);
  hammer.half_width = q_int(4);
  hammer.half_height = q_int(4);
  hammer.friction = friction;
  hammer.density = q_int(8);
  s.bodies.push_back(hammer);
  s.dynamic_count = 1;
  const Q32 d = q_ratio(2, 5);
  for (int32_t i = 0; i < columns; ++i) {
    for (int32_t j = 0; j < rows; ++j) {
      BodySpec b;
      b.dynamic = true;
      b.awake = false;
      b.shape = ShapeKind::box;
      b.x = q_int(i) * d + q_int(30);
      b.y = q_int(2 * j - rows) * d / q_int(2);  // (j − rows/2)·d, exact for odd rows too
      b.half_width = d / q_int(2);
      b.half_height = d / q_int(2);
      b.friction = friction;
      b.density = Q32::one();
      s.bodies.push_back(b);
      ++s.dynamic_count;
    }
  }
  return s;
}

SceneSpec make_joint_grid(int32_t n) {
  SceneSpec s;
  s.name = n == 100 ? "joint_grid" : "joint_grid-" + std::to_string(n);
  s.family = "joint_grid";
  s.size = n;
  s.gravity_y = q_int(-10);
  s.warmup_steps = 0;
  s.timed_steps = 500;
  const Q32 half = q_ratio(1, 2);
  for (int32_t k = 0; k < n; ++k) {
    for (int32_t i = 0; i < n; ++i) {
      BodySpec b;
      b.dynamic = !(k >= n / 2 - 3 && k <= n / 2 + 3 && i == 0);
      b.shape = ShapeKind::circle;
      b.x = q_int(k);
      b.y = q_int(-i);
      b.radius = q_ratio(2, 5);
      b.friction = q_ratio(3, 5);
      b.density = Q32::one();
      b.self_collide = false;
      const int32_t index = static_cast<int32_t>(s.bodies.size());
      if (i > 0) s.joints.push_back(RevoluteSpec{index - 1, index, b.x, b.y + half, false, {}, {}});
      // v3 also joins the static anchors to each other (a joint that does
      // nothing); Tandem refuses a joint between two static bodies.
      const bool both_static = !b.dynamic && !s.bodies[static_cast<size_t>(index - n)].dynamic;
      if (k > 0 && !both_static) s.joints.push_back(RevoluteSpec{index - n, index, b.x - half, b.y, false, {}, {}});
      if (b.dynamic) ++s.dynamic_count;
      s.bodies.push_back(b);
    }
  }
  // The grid hangs and swings below its anchors; it never leaves this box.
  s.container.min_x = -2.0 * n;
  s.container.max_x = 3.0 * n;
  s.container.min_y = -2.5 * n;
  s.container.max_y = 1.0 * n;
  return s;
}

SceneSpec make_tumbler(int32_t grid) {
  SceneSpec s;
  s.name = grid == 45 ? "tumbler" : "tumbler-" + std::to_string(grid);
  s.family = "tumbler";
  s.size = grid;
  s.gravity_y = q_int(-10);
  s.warmup_steps = 0;
  s.timed_steps = 750;
  BodySpec ground;
  ground.shape = ShapeKind::none;
  s.bodies.push_back(ground);
  BodySpec drum;
  drum.dynamic = true;
  drum.shape = ShapeKind::none;
  drum.y = q_int(10);
  drum.friction = q_ratio(3, 5);
  drum.density = q_int(50);
  const Q32 half = q_ratio(1, 2);
  drum.boxes = {BoxPart{q_int(10), {}, half, q_int(10)}, BoxPart{q_int(-10), {}, half, q_int(10)},
                BoxPart{{}, q_int(10), q_int(10), half}, BoxPart{{}, q_int(-10), q_int(10), half}};
  s.bodies.push_back(drum);
  s.dynamic_count = 1;
  // 25°/s as v3 writes it: (π/180)·25 rad/s.
  s.joints.push_back(RevoluteSpec{0, 1, {}, q_int(10), true, k_pi * q_int(25) / q_int(180), q_int(100000000)});
  const Q32 step = q_ratio(2, 5);
  const Q32 start = q_int(-grid) * q_ratio(1, 5);
  for (int32_t i = 0; i < grid; ++i) {
    for (int32_t j = 0; j < grid; ++j) {
      BodySpec b;
      b.dynamic = true;
      b.shape = ShapeKind::box;
      b.x = start + q_int(j) * step;
      b.y = start + q_int(10) + q_int(i) * step;
      b.half_width = q_ratio(1, 8);
      b.half_height = q_ratio(1, 8);
      b.friction = q_ratio(3, 5);
      b.density = Q32::one();
      s.bodies.push_back(b);
      ++s.dynamic_count;
    }
  }
  // Inside the drum (its corners reach 10·√2 ≈ 14.2 m from (0, 10)).
  s.container.min_x = -15;
  s.container.max_x = 15;
  s.container.min_y = -5;
  s.container.max_y = 25;
  return s;
}

SceneSpec make_spinner(int32_t count) {
  SceneSpec s;
  s.name = count == 6076 ? "spinner" : "spinner-" + std::to_string(count);
  s.family = "spinner";
  s.size = count;
  s.gravity_y = q_int(-10);
  s.warmup_steps = 0;
  s.timed_steps = 500;
  constexpr int32_t k_points = 360;
  BodySpec ring;
  ring.shape = ShapeKind::none;
  ring.friction = q_ratio(1, 10);
  ring.density = Q32::one();
  std::vector<Vec2> points;
  for (int32_t i = 0; i < k_points; ++i) {
    const auto sc = sincos(-k_two_pi * q_int(i) / q_int(k_points));
    points.push_back(Vec2{q_int(40) * sc.cos, q_int(40) * sc.sin + q_int(32)});
  }
  for (int32_t i = 0; i < k_points; ++i) {
    const Vec2 a = points[static_cast<size_t>(i)], b = points[static_cast<size_t>((i + 1) % k_points)];
    ring.segments.push_back(SegmentPart{a.x, a.y, b.x, b.y});
  }
  s.bodies.push_back(ring);
  BodySpec bar;
  bar.dynamic = true;
  bar.shape = ShapeKind::box;
  bar.y = q_int(12);
  bar.half_width = q_ratio(2, 5);
  bar.half_height = q_int(20);
  bar.rounding = q_ratio(1, 5);
  bar.friction = Q32{};
  bar.density = Q32::one();
  s.bodies.push_back(bar);
  s.dynamic_count = 1;
  s.joints.push_back(RevoluteSpec{0, 1, {}, q_int(12), true, q_int(5), q_int(100000000)});
  Q32 x = q_int(-23), y = q_int(2);
  for (int32_t i = 0; i < count; ++i) {
    BodySpec b;
    b.dynamic = true;
    b.x = x;
    b.y = y;
    b.friction = q_ratio(1, 10);
    b.restitution = q_ratio(1, 10);
    b.density = q_ratio(1, 4);
    switch (i % 3) {
      case 0:
        b.shape = ShapeKind::capsule;
        b.half_width = q_ratio(1, 4);
        b.radius = q_ratio(1, 4);
        break;
      case 1:
        b.shape = ShapeKind::circle;
        b.radius = q_ratio(7, 20);
        break;
      default:
        b.shape = ShapeKind::box;
        b.half_width = q_ratio(7, 20);
        b.half_height = q_ratio(7, 20);
        break;
    }
    s.bodies.push_back(b);
    ++s.dynamic_count;
    x += q_ratio(1, 2);
    if (x >= q_int(23)) {
      x = q_int(-23);
      y += q_ratio(1, 2);
    }
  }
  s.container.min_x = -41;
  s.container.max_x = 41;
  s.container.min_y = -9;
  s.container.max_y = 73;
  return s;
}

bool make_scene(const std::string& name, SceneSpec* out, std::string* error) {
  if (name == "large_pyramid") {
    *out = make_pyramid(100);
    out->name = "large_pyramid";
    return true;
  }
  if (name == "many_pyramids") {
    *out = make_many_pyramids();
    return true;
  }
  if (name == "smash") {
    *out = make_smash();
    return true;
  }
  const size_t dash = name.find('-');
  const std::string family = name.substr(0, dash);
  int64_t size = family == "rain" ? 4000 : 0;
  if (dash != std::string::npos) {
    std::string digits = name.substr(dash + 1);
    int64_t scale = 1;
    if (!digits.empty() && (digits.back() == 'k' || digits.back() == 'K')) {
      scale = 1000;
      digits.pop_back();
    }
    if (digits.empty() || digits.size() > 6 ||
        !std::all_of(digits.begin(), digits.end(), [](char ch) { return ch >= '0' && ch <= '9'; })) {
      *error = "scene '" + name + "': expected <family>-<count>, e.g. circles-4000 or circles-4k";
      return false;
    }
    size = std::strtoll(digits.c_str(), nullptr, 10) * scale;
  }
  if (family == "circles" || family == "rain") {
    if (size < 1 || size > 100000) {
      *error = "scene '" + name + "': count must be 1…100000";
      return false;
    }
    *out = family == "circles" ? make_circles(static_cast<int32_t>(size)) : make_rain(static_cast<int32_t>(size));
    return true;
  }
  if (family == "joint_grid" || family == "tumbler" || family == "spinner") {
    const int64_t fallback = family == "joint_grid" ? 100 : family == "tumbler" ? 45 : 6076;
    const int64_t max = family == "spinner" ? 100000 : 300;
    if (dash == std::string::npos) size = fallback;
    if (size < 1 || size > max) {
      *error = "scene '" + name + "': " + family + " size must be 1…" + std::to_string(max);
      return false;
    }
    const auto n = static_cast<int32_t>(size);
    *out = family == "joint_grid" ? make_joint_grid(n) : family == "tumbler" ? make_tumbler(n) : make_spinner(n);
    return true;
  }
  if (family == "pyramid") {
    if (size < 1 || size > 200) {
      *error = "scene '" + name + "': pyramid base must be 1…200";
      return false;
    }
    *out = make_pyramid(static_cast<int32_t>(size));
    return true;
  }
  *error = "scene '" + name + "': unknown family '" + family +
           "' (circles-N, pyramid-B, rain-N, large_pyramid, many_pyramids, smash, joint_grid[-N], tumbler[-G], "
           "spinner[-N])";
  return false;
}

std::vector<std::string> default_scene_names() {
  return {"circles-1000", "circles-2000", "circles-4000", "circles-8000",  "circles-16000", "circles-32000",
          "pyramid-20",   "pyramid-100",  "rain-4000",    "many_pyramids", "smash",
          "joint_grid",   "tumbler"};
}

}  // namespace tandem::bench
