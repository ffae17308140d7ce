// scenes.h — the benchmark scenes, described once for every engine (tools only).
//
// One generator builds each scene as a list of BodySpec records; the Tandem
// harness and the peer harnesses (Box2D 2.4, Chipmunk2D) all build their
// worlds from that same list, in list order, so every engine simulates the
// same bodies.
//
// Exactness: every value in a spec is a Q32.32 made from integers — ratios
// (Q32::from_ratio), integer arithmetic on raw splitmix64 draws and Q32
// products, never a binary floating-point value — so nothing computed in
// floating point flows into Tandem's state. The peers get
// to_double(value) = raw / 2^32, which is exact in binary64 for every value
// here (|raw| < 2^53), so the bodies match to the last bit a double can
// show (Box2D 2.4 then rounds to binary32 itself).
//
// Scenes (same layout and seeds as shared/reference/peer-bench/scene.h; the
// random draws use the top 32 bits of each splitmix64 output as a fraction
// in [0, 1) instead of the top 53, so values differ from scene.h by < 2^-32
// of their range):
//   circles-N    N circles, r ∈ [0.4, 0.6) m, velocity components ∈ [−5, 5)
//                m/s, on a random subset of a 1.2 m lattice inside a closed
//                square box of four static walls sized for ~25 % area
//                coverage; no gravity, restitution 1, friction 0. Warm-up
//                60 steps, timed 300.
//   pyramid-B    B(B+1)/2 boxes of half extent 0.5 m, exactly touching, on a
//                static ground; gravity −10, friction 0.6. Timed 500 steps.
//                The tracked body is the top box.
//   rain-N       N bodies cycling circle (r ∈ [0.4, 0.6)), box (half extent
//                ∈ [0.35, 0.5)) and capsule (radius ∈ [0.2, 0.3), segment
//                half length ∈ [0.2, 0.4), horizontal), released at rest
//                from a 50-column lattice (1.5 m spacing, x jitter ±0.1 m)
//                above an 80 m wide open-top container; gravity −10,
//                friction 0.6, restitution 0. Timed 600 steps.
// Box2D v3's joint-free benchmark scenes (benchmark/main.c and
// shared/benchmarks.c of its repository, rebuilt here from their layout):
//   large_pyramid  = pyramid-100 (the same layout: 5,050 boxes on a 100 m
//                  half-width ground at y = −1), timed 500 steps.
//   many_pyramids  20 × 20 pyramids of base 10 (55 boxes of half extent
//                  0.5 m each, 22,000 boxes) on 20 static ground segments
//                  11 m apart vertically, 220 m wide; gravity −10,
//                  friction 0.6. Timed 200 steps.
//   smash          no gravity; a 8 × 8 m box of density 8 at (−20, 0) moving
//                  at 40 m/s into a 120 × 80 block of 0.4 m boxes (9,600,
//                  created asleep, starting at x = 30, centred on y = 0);
//                  sleeping on. Timed 300 steps.
// Box2D v3's joint benchmark scenes (the same files), rebuilt from their
// layout with revolute joints (SceneSpec::joints):
//   joint_grid-N   N × N circles (r 0.4 m, density 1) at (k, −i), 1 m apart,
//                  each joined by revolute joints to its upper and left
//                  neighbours at the midpoints; the 7 top bodies of the
//                  middle columns are static; the circles do not collide
//                  with each other (v3's category/mask bits). Gravity −10.
//                  The 6 joints between two static anchors, which v3 makes
//                  and which do nothing, are left out (Tandem refuses them).
//                  joint_grid = joint_grid-100 (10,000 bodies, 19,794 joints),
//                  timed 500 steps.
//   tumbler-G      a 20 m square drum of four walls (density 50) on a
//                  revolute motor (25°/s, max torque 1e8 N·m) about
//                  (0, 10) on a shapeless ground, tumbling G × G boxes of
//                  half extent 0.125 m on a 0.4 m lattice. tumbler =
//                  tumbler-45 (2,025 boxes), timed 750 steps.
//   spinner-N      a static ring of 360 two-sided segments (radius 40 m about
//                  (0, 32), v3: a loop chain) around a 0.8 × 40 m bar
//                  rounded by 0.2 m on a revolute motor (5 rad/s; max
//                  torque 1e8 N·m, v3: FLT_MAX) stirring N capsules,
//                  circles and squares (density 0.25, friction 0.1,
//                  restitution 0.1). spinner = spinner-6076 (v3's count),
//                  timed 500 steps.
// Every other body has sleeping off (the harnesses disable it unless the
// scene has `sleep`).
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "fixed/fixed.h"

namespace tandem::bench {

/// The shape of one body.
enum class ShapeKind : int32_t {
  circle = 0,   ///< radius
  box = 1,      ///< half_width × half_height, axis-aligned, centred on the body
  capsule = 2,  ///< segment (−half_width, 0)…(+half_width, 0) swept by radius
  segment = 3,  ///< two-sided segment (−half_width, 0)…(+half_width, 0); static bodies only
  none = 4,     ///< no shape of its own (only `boxes` / `segments`, or a bare joint anchor)
};

/// An axis-aligned box part centred at (cx, cy) in the body frame, m.
struct BoxPart {
  Q32 cx, cy, half_width, half_height;
};

/// A two-sided segment part from (x1, y1) to (x2, y2) in the body frame, m
/// (static bodies only).
struct SegmentPart {
  Q32 x1, y1, x2, y2;
};

/// One body with one shape, in Q32.32 SI units (m, m/s, kg/m²).
struct BodySpec {
  bool dynamic = false;
  bool awake = true;            ///< false: created asleep (scenes with sleep on only)
  ShapeKind shape = ShapeKind::box;
  Q32 x, y;                     ///< position of the body origin (= centre of mass), m
  Q32 vx, vy;                   ///< initial linear velocity, m/s
  Q32 radius;                   ///< circle / capsule radius, m
  Q32 half_width, half_height;  ///< box half extents; capsule: half_width = half segment length, m
  Q32 friction, restitution, density;
  Q32 rounding;                 ///< box corner radius, m (Box2D 2.4 has none: plain box)
  bool self_collide = true;     ///< false: never collides with another body whose flag is false
  std::vector<BoxPart> boxes;   ///< extra box parts (the tumbler's drum walls)
  std::vector<SegmentPart> segments;  ///< extra segment parts (the spinner's ring)
};

/// A revolute joint between two bodies of SceneSpec::bodies (indices) at a
/// world point (the bodies at their initial poses), optionally motorised.
struct RevoluteSpec {
  int32_t a = 0, b = 0;
  Q32 x, y;                     ///< anchor, m
  bool motor = false;
  Q32 motor_speed;              ///< rad/s
  Q32 max_motor_torque;         ///< N·m
};

/// Where the dynamic bodies belong: a body whose centre lies outside these
/// bounds (m) at the end of a run counts as escaped.
struct Container {
  double min_x = -std::numeric_limits<double>::infinity();
  double max_x = std::numeric_limits<double>::infinity();
  double min_y = -std::numeric_limits<double>::infinity();
  double max_y = std::numeric_limits<double>::infinity();
};

/// A whole scene.
struct SceneSpec {
  std::string name;    ///< e.g. "circles-4000"
  std::string family;  ///< "circles", "pyramid", "rain", "many_pyramids", "smash", "joint_grid", "tumbler", "spinner"
  int32_t size = 0;    ///< N (circles, rain) or base B (pyramid)
  Q32 gravity_x, gravity_y;     ///< m/s²
  std::vector<BodySpec> bodies;  ///< build in this order
  std::vector<RevoluteSpec> joints;  ///< built after every body, in this order
  int32_t warmup_steps = 0;      ///< default steps before timing
  int32_t timed_steps = 0;       ///< default timed steps
  int32_t track_index = -1;      ///< body whose height is reported (pyramid top), −1 none
  int32_t dynamic_count = 0;
  bool sleep = false;            ///< sleeping on (smash); every other scene runs with it off
  Container container;
};

/// The time step every engine uses: the Q32.32 nearest 1/60 s.
Q32 time_step();

/// A Q32.32 value as a binary64 double (exact for |raw| < 2^53). Display and
/// peer input only.
inline double to_double(Q32 v) { return static_cast<double>(v.raw) / 4294967296.0; }

/// circles-N (seed 12345 as scene.h).
SceneSpec make_circles(int32_t n, uint64_t seed = 12345);
/// pyramid-B: B(B+1)/2 boxes.
SceneSpec make_pyramid(int32_t base);
/// rain-N (seed 777 as scene.h).
SceneSpec make_rain(int32_t n, uint64_t seed = 777);

/// many_pyramids: rows × columns pyramids of the given base (v3: 20, 20, 10).
SceneSpec make_many_pyramids(int32_t rows = 20, int32_t columns = 20, int32_t base = 10);
/// smash: a heavy box into columns × rows sleeping boxes (v3: 120, 80).
SceneSpec make_smash(int32_t columns = 120, int32_t rows = 80);

/// joint_grid-N: N × N jointed circles (v3: N = 100).
SceneSpec make_joint_grid(int32_t n = 100);
/// tumbler-G: a motorised drum tumbling G × G small boxes (v3: G = 45).
SceneSpec make_tumbler(int32_t grid = 45);
/// spinner-N: a motorised bar stirring N bodies in a ring (v3: N = 6076).
SceneSpec make_spinner(int32_t count = 6076);

/// Parses a scene name — "circles-4000", "circles-4k", "pyramid-100",
/// "rain-4000", "rain" (= rain-4000), "large_pyramid", "many_pyramids",
/// "smash", "joint_grid[-N]", "tumbler[-G]", "spinner[-N]" — and builds it. On an unknown family
/// or a size out of range (circles/rain 1…100000, pyramid 1…200) returns
/// false and writes why to *error.
bool make_scene(const std::string& name, SceneSpec* out, std::string* error);

/// The default suite: circles-1k…32k, pyramid-20, pyramid-100 (=
/// large_pyramid), rain-4000, many_pyramids, smash, joint_grid, tumbler
/// (spinner by name only: Box2D 2.4's time-of-impact sub-steps take about
/// half a second a step on spinner-500 already).
std::vector<std::string> default_scene_names();

}  // namespace tandem::bench
