// profile_stages.cpp — steps one benchmark scene for an instruction-count
// profile (tools only; driven by callgrind_stages.sh).
//
// Usage: tandem_profile_stages SCENE [--warmup W] [--ticks N] [--broadphase NAME]
//                              [--sleep on|off|scene]
//
// Builds SCENE (scenes.h: circles-N, pyramid-B, rain-N, smash, ...) the way
// the bench harness does (default_world_def(), the scene's gravity; sleeping
// as --sleep says: `scene` (the default) follows the scene as the harness does
// — on for smash, whose block is created asleep, off for every other scene —,
// `off` forces it off everywhere with every body created awake (the tool's
// behaviour before the option), `on` turns it on for every body),
// steps it W times, then N times inside tandem_profile_timed_steps(), the one
// function callgrind_stages.sh collects (--toggle-collect), and prints the
// mean broad-phase pairs and touching pairs per timed step, which the script
// divides the stage counts by. Doubles never reach the world.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "physics/tandem.h"
#include "scenes.h"

using namespace tandem;

/// Per-step figures summed over the timed steps.
struct ProfileTotals {
  int64_t pairs = 0;
  int64_t touching_pairs = 0;
  int32_t failed_step = -1;
};

/// The collected region: `ticks` steps of `world`. Not inlined, so callgrind
/// can toggle collection on its name.
extern "C" __attribute__((noinline)) void tandem_profile_timed_steps(WorldId world, int32_t ticks, Q32 dt,
                                                                      ProfileTotals* out) {
  for (int32_t i = 0; i < ticks; ++i) {
    const StepResult r = world_step(world, dt);
    if (!r.ok()) {
      out->failed_step = i;
      return;
    }
    const BroadPhaseStats s = world_broad_phase_stats(world);
    out->pairs += s.pairs;
    out->touching_pairs += s.touching_pairs;
  }
}

namespace {

int usage(const char* why) {
  std::fprintf(stderr, "tandem_profile_stages: %s\nusage: tandem_profile_stages SCENE [--warmup W] [--ticks N] "
                       "[--broadphase naive|sap|grid|tree] [--sleep on|off|scene]\n", why);
  return 2;
}

bool parse_count(const char* text, int32_t lo, int32_t hi, int32_t* out) {
  char* end = nullptr;
  const long v = std::strtol(text, &end, 10);
  if (end == text || *end != '\0' || v < lo || v > hi) return false;
  *out = static_cast<int32_t>(v);
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  std::string scene_name;
  int32_t warmup = 0, ticks = 30;
  BroadPhaseKind kind = BroadPhaseKind::grid;
  enum class SleepMode { scene, on, off } sleep_mode = SleepMode::scene;
  for (int i = 1; i < argc; ++i) {
    const char* a = argv[i];
    if (std::strcmp(a, "--warmup") == 0 && i + 1 < argc) {
      if (!parse_count(argv[++i], 0, 1000000, &warmup)) return usage("--warmup: expected an integer in [0, 1000000]");
    } else if (std::strcmp(a, "--ticks") == 0 && i + 1 < argc) {
      if (!parse_count(argv[++i], 1, 1000000, &ticks)) return usage("--ticks: expected an integer in [1, 1000000]");
    } else if (std::strcmp(a, "--broadphase") == 0 && i + 1 < argc) {
      const std::string b = argv[++i];
      if (b == "naive") kind = BroadPhaseKind::naive;
      else if (b == "sap") kind = BroadPhaseKind::sweep_and_prune;
      else if (b == "grid") kind = BroadPhaseKind::grid;
      else if (b == "tree") kind = BroadPhaseKind::tree;
      else return usage("--broadphase: expected naive, sap, grid or tree");
    } else if (std::strcmp(a, "--sleep") == 0 && i + 1 < argc) {
      const std::string m = argv[++i];
      if (m == "scene") sleep_mode = SleepMode::scene;
      else if (m == "on") sleep_mode = SleepMode::on;
      else if (m == "off") sleep_mode = SleepMode::off;
      else return usage("--sleep: expected on, off or scene");
    } else if (a[0] != '-' && scene_name.empty()) {
      scene_name = a;
    } else {
      return usage((std::string("unexpected argument '") + a + "'").c_str());
    }
  }
  if (scene_name.empty()) return usage("no scene given");
  bench::SceneSpec scene;
  std::string error;
  if (!bench::make_scene(scene_name, &scene, &error)) return usage(error.c_str());

  const bool sleep = sleep_mode == SleepMode::on || (sleep_mode == SleepMode::scene && scene.sleep);
  WorldDef wd = default_world_def();
  wd.gravity = {scene.gravity_x, scene.gravity_y};
  wd.enable_sleep = sleep;
  wd.broad_phase = kind;
  const Result<WorldId> w = create_world(wd);
  if (!w.ok()) return usage(w.status.message.c_str());
  if (!scene.joints.empty()) return usage("the joint scenes (joint_grid, tumbler, spinner) are not profiled here");
  for (size_t i = 0; i < scene.bodies.size(); ++i) {
    const bench::BodySpec& s = scene.bodies[i];
    BodyDef bd = default_body_def();
    bd.type = s.dynamic ? BodyType::dynamic_body : BodyType::static_body;
    bd.position = {s.x, s.y};
    bd.linear_velocity = {s.vx, s.vy};
    bd.enable_sleep = sleep;
    bd.is_awake = sleep ? s.awake : true;  // a scene's sleeping bodies start awake with sleep off
    const Result<BodyId> b = create_body(w.value, bd);
    if (!b.ok()) return usage(b.status.message.c_str());
    ShapeDef sd = default_shape_def();
    sd.friction = s.friction;
    sd.restitution = s.restitution;
    sd.density = s.density;
    Result<ShapeId> sh;
    switch (s.shape) {
      case bench::ShapeKind::circle: sh = create_circle_shape(b.value, sd, Circle{{}, s.radius}); break;
      case bench::ShapeKind::capsule:
        sh = create_capsule_shape(b.value, sd, Capsule{{-s.half_width, Q32{}}, {s.half_width, Q32{}}, s.radius});
        break;
      case bench::ShapeKind::box: {
        Polygon box;
        if (!make_box(s.half_width, s.half_height, &box).ok()) return usage("make_box refused a box");
        sh = create_polygon_shape(b.value, sd, box);
        break;
      }
      case bench::ShapeKind::segment:
        sh = create_segment_shape(b.value, sd, Segment{{-s.half_width, Q32{}}, {s.half_width, Q32{}}});
        break;
      case bench::ShapeKind::none:  // joint scenes only, refused above
        break;
    }
    if (!sh.ok()) return usage(sh.status.message.c_str());
  }
  const Q32 dt = bench::time_step();
  for (int32_t i = 0; i < warmup; ++i) {
    if (!world_step(w.value, dt).ok()) return usage("a warm-up step failed");
  }
  ProfileTotals totals;
  tandem_profile_timed_steps(w.value, ticks, dt, &totals);
  if (totals.failed_step >= 0) return usage("a timed step failed");
  std::printf("scene %s sleep %s bodies %zu warmup %d ticks %d pairs_per_step %.1f touching_pairs_per_step %.1f\n",
              scene_name.c_str(), sleep ? "on" : "off", scene.bodies.size(), warmup, ticks, static_cast<double>(totals.pairs) / ticks,
              static_cast<double>(totals.touching_pairs) / ticks);
  (void)destroy_world(w.value);
  return 0;
}
