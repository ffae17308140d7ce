// harness_tandem.cpp — runs a benchmark scene in Tandem with one broad phase.
//
// The world: default_world_def() (4 sub-steps, contact 30 Hz / damping 10,
// restitution threshold 1 m/s) with the scene's gravity, sleeping off (on for
// a scene with `sleep`: smash, whose bodies may start asleep) and the
// chosen WorldDef::broad_phase. Bodies and shapes are made from the spec's
// Q32 values as they are; joints (revolute) after every body, anchored at
// the spec's world point. Doubles appear only in the probes (harness.h).
#include <chrono>
#include <cmath>

#include "harness.h"
#include "physics/tandem.h"

namespace tandem::bench {
namespace {

struct NamedKind {
  const char* name;
  BroadPhaseKind kind;
};
constexpr NamedKind k_kinds[] = {
    {"naive", BroadPhaseKind::naive},
    {"sap", BroadPhaseKind::sweep_and_prune},
    {"grid", BroadPhaseKind::grid},
    {"tree", BroadPhaseKind::tree},
};

struct Fnv {
  uint64_t h = 1469598103934665603ull;
  void add(int64_t raw) {
    const auto u = static_cast<uint64_t>(raw);
    for (int i = 0; i < 8; ++i) {
      h ^= (u >> (8 * i)) & 0xFFu;
      h *= 1099511628211ull;
    }
  }
};

double ke_of(BodyId b) {
  const Vec2 v = body_linear_velocity(b);
  const double vx = to_double(v.x), vy = to_double(v.y), w = to_double(body_angular_velocity(b));
  return 0.5 * to_double(body_mass(b)) * (vx * vx + vy * vy) + 0.5 * to_double(body_rotational_inertia(b)) * w * w;
}

void probe(const SceneSpec& scene, const std::vector<BodyId>& bodies, bool end, Quality* q) {
  double ke = 0;
  for (size_t i = 0; i < bodies.size(); ++i) {
    if (!scene.bodies[i].dynamic) continue;
    ke += ke_of(bodies[i]);
  }
  const double track_y =
      scene.track_index >= 0 ? to_double(body_position(bodies[static_cast<size_t>(scene.track_index)]).y) : 0.0;
  if (!end) {
    q->ke_start = ke;
    q->track_y_start = track_y;
    return;
  }
  q->ke_end = ke;
  q->track_y_end = track_y;
  Fnv fp;
  for (size_t i = 0; i < bodies.size(); ++i) {
    const BodyId b = bodies[i];
    const Vec2 p = body_position(b);
    const Rot r = body_rotation(b);
    const Vec2 v = body_linear_velocity(b);
    fp.add(p.x.raw);
    fp.add(p.y.raw);
    fp.add(r.c.raw);
    fp.add(r.s.raw);
    fp.add(v.x.raw);
    fp.add(v.y.raw);
    fp.add(body_angular_velocity(b).raw);
    if (!scene.bodies[i].dynamic) continue;
    const double x = to_double(p.x), y = to_double(p.y);
    const double speed = std::hypot(to_double(v.x), to_double(v.y));
    if (speed > q->max_speed) q->max_speed = speed;
    const Container& c = scene.container;
    if (x < c.min_x || x > c.max_x || y < c.min_y || y > c.max_y) ++q->escaped;
    if (std::fabs(x - to_double(scene.bodies[i].x)) > 0.25) ++q->moved;
  }
  q->has_fingerprint = true;
  q->fingerprint = fp.h;
}

/// Builds the scene in a new world with broad phase `kind`; on refusal false,
/// the reason in *error and no world left behind.
bool build_tandem(BroadPhaseKind kind, int32_t workers, const SceneSpec& scene, WorldId* out_world,
                  std::vector<BodyId>* out_bodies, std::string* error) {
  WorldDef wd = default_world_def();
  wd.worker_count = workers;
  wd.gravity = {scene.gravity_x, scene.gravity_y};
  wd.enable_sleep = scene.sleep;
  wd.broad_phase = kind;
  const Result<WorldId> w = create_world(wd);
  if (!w.ok()) {
    *error = "create_world: " + w.status.message;
    return false;
  }
  std::vector<BodyId>& bodies = *out_bodies;
  bodies.clear();
  bodies.reserve(scene.bodies.size());
  const auto fail = [&](const std::string& what, const Status& st, size_t i) {
    *error = what + " (body " + std::to_string(i) + "): " + st.message;
    (void)destroy_world(w.value);
    return false;
  };
  for (size_t i = 0; i < scene.bodies.size(); ++i) {
    const BodySpec& s = scene.bodies[i];
    BodyDef bd = default_body_def();
    bd.type = s.dynamic ? BodyType::dynamic_body : BodyType::static_body;
    bd.position = {s.x, s.y};
    bd.linear_velocity = {s.vx, s.vy};
    bd.enable_sleep = scene.sleep;
    bd.is_awake = s.awake;
    const Result<BodyId> b = create_body(w.value, bd);
    if (!b.ok()) return fail("create_body", b.status, i);
    ShapeDef sd = default_shape_def();
    sd.friction = s.friction;
    sd.restitution = s.restitution;
    sd.density = s.density;
    if (!s.self_collide) {  // joint_grid: on layer 2, colliding with every layer but 2
      sd.filter.category_bits = 2;
      sd.filter.mask_bits = ~uint64_t{2};
    }
    for (const BoxPart& part : s.boxes) {
      Polygon box;
      if (!make_offset_box(part.half_width, part.half_height, Vec2{part.cx, part.cy}, Q32{}, Q32{}, &box).ok()) {
        *error = "make_offset_box (body " + std::to_string(i) + ") refused";
        (void)destroy_world(w.value);
        return false;
      }
      const Result<ShapeId> part_shape = create_polygon_shape(b.value, sd, box);
      if (!part_shape.ok()) return fail("create box part", part_shape.status, i);
    }
    for (const SegmentPart& part : s.segments) {
      const Result<ShapeId> part_shape =
          create_segment_shape(b.value, sd, Segment{{part.x1, part.y1}, {part.x2, part.y2}});
      if (!part_shape.ok()) return fail("create segment part", part_shape.status, i);
    }
    Result<ShapeId> sh;
    switch (s.shape) {
      case ShapeKind::none:
        break;
      case ShapeKind::circle:
        sh = create_circle_shape(b.value, sd, Circle{{}, s.radius});
        break;
      case ShapeKind::capsule:
        sh = create_capsule_shape(b.value, sd, Capsule{{-s.half_width, Q32{}}, {s.half_width, Q32{}}, s.radius});
        break;
      case ShapeKind::segment:
        sh = create_segment_shape(b.value, sd, Segment{{-s.half_width, Q32{}}, {s.half_width, Q32{}}});
        break;
      case ShapeKind::box: {
        Polygon box;
        const Status gs = make_offset_box(s.half_width, s.half_height, Vec2{}, Q32{}, s.rounding, &box);
        if (!gs.ok()) {
          *error = "make_box (body " + std::to_string(i) + ") refused";
          (void)destroy_world(w.value);
          return false;
        }
        sh = create_polygon_shape(b.value, sd, box);
        break;
      }
    }
    if (s.shape != ShapeKind::none && !sh.ok()) return fail("create shape", sh.status, i);
    bodies.push_back(b.value);
  }
  for (size_t i = 0; i < scene.joints.size(); ++i) {
    const RevoluteSpec& j = scene.joints[i];
    RevoluteJointDef rd = default_revolute_joint_def();
    rd.base.body_a = bodies[static_cast<size_t>(j.a)];
    rd.base.body_b = bodies[static_cast<size_t>(j.b)];
    rd.base.local_anchor_a = body_local_point(rd.base.body_a, Vec2{j.x, j.y});
    rd.base.local_anchor_b = body_local_point(rd.base.body_b, Vec2{j.x, j.y});
    rd.enable_motor = j.motor;
    rd.motor_speed = j.motor_speed;
    rd.max_motor_torque = j.max_motor_torque;
    const Result<JointId> joint = create_revolute_joint(w.value, rd);
    if (!joint.ok()) {
      *error = "create_revolute_joint (joint " + std::to_string(i) + "): " + joint.status.message;
      (void)destroy_world(w.value);
      return false;
    }
  }
  *out_world = w.value;
  return true;
}

RunResult run_tandem(BroadPhaseKind kind, int32_t workers, const SceneSpec& scene, int32_t warmup, int32_t steps) {
  RunResult result;
  WorldId world;
  std::vector<BodyId> bodies;
  if (!build_tandem(kind, workers, scene, &world, &bodies, &result.error)) return result;
  const auto fail = [&](const std::string& what, const Status& st) {
    result.error = what + ": " + st.message;
    (void)destroy_world(world);
    return result;
  };
  probe(scene, bodies, false, &result.quality);
  const Q32 dt = time_step();
  for (int32_t i = 0; i < warmup; ++i) {
    const StepResult r = world_step(world, dt);
    if (!r.ok()) return fail("world_step (warm-up " + std::to_string(i) + ")", r.status);
  }
  const StepTimer timer;
  for (int32_t i = 0; i < steps; ++i) {
    const StepResult r = world_step(world, dt);
    if (!r.ok()) return fail("world_step (" + std::to_string(i) + ")", r.status);
    result.profile.add(world_profile(world));  // a copy of a few integers; inside the timed loop
  }
  timer.stop(steps, &result);
  probe(scene, bodies, true, &result.quality);
  (void)destroy_world(world);
  return result;
}

class TandemRays final : public RaySession {
 public:
  TandemRays(WorldId world, std::vector<BodyId> bodies) : world_(world), bodies_(std::move(bodies)) {}
  ~TandemRays() override { (void)destroy_world(world_); }
  TandemRays(const TandemRays&) = delete;
  TandemRays& operator=(const TandemRays&) = delete;

  RayBatch batch(const std::vector<RaySpec>& rays) override {
    RayBatch b;
    (void)world_step(world_, time_step());
    if (rays.empty()) return b;
    // The first query after a step re-syncs the broad phase with the step's
    // poses (work the next step's broad phase then skips): timed apart.
    const auto s0 = std::chrono::steady_clock::now();
    (void)world_cast_ray_closest(world_, rays[0].origin, rays[0].translation);
    const auto s1 = std::chrono::steady_clock::now();
    b.sync_ms = std::chrono::duration<double, std::milli>(s1 - s0).count();
    Fnv fnv;
    const auto t0 = std::chrono::steady_clock::now();
    for (const RaySpec& ray : rays) {
      const Result<RayHit> hit = world_cast_ray_closest(world_, ray.origin, ray.translation);
      if (!hit.value.hit) continue;
      ++b.hits;
      fnv.add(hit.value.shape.index1);
      fnv.add(hit.value.fraction.raw);
    }
    const auto t1 = std::chrono::steady_clock::now();
    const double seconds = std::chrono::duration<double>(t1 - t0).count();
    b.rays_per_second = seconds > 0 ? static_cast<double>(rays.size()) / seconds : 0.0;
    b.has_fingerprint = true;
    b.fingerprint = fnv.h;
    return b;
  }

 private:
  WorldId world_;
  std::vector<BodyId> bodies_;
};

std::unique_ptr<RaySession> tandem_rays(BroadPhaseKind kind, int32_t workers, const SceneSpec& scene, int32_t warmup,
                                        std::string* error) {
  WorldId world;
  std::vector<BodyId> bodies;
  if (!build_tandem(kind, workers, scene, &world, &bodies, error)) return nullptr;
  for (int32_t i = 0; i < warmup; ++i) {
    const StepResult r = world_step(world, time_step());
    if (!r.ok()) {
      *error = "world_step (warm-up " + std::to_string(i) + "): " + r.status.message;
      (void)destroy_world(world);
      return nullptr;
    }
  }
  return std::make_unique<TandemRays>(world, std::move(bodies));
}

}  // namespace

std::vector<std::string> tandem_broad_phase_names() {
  std::vector<std::string> names;
  for (const NamedKind& k : k_kinds) names.emplace_back(k.name);
  return names;
}

bool tandem_engine(const std::string& broad_phase, int32_t workers, Engine* out) {
  for (const NamedKind& k : k_kinds) {
    if (broad_phase != k.name) continue;
    Engine e;
    e.engine = "tandem";
    e.broad_phase = k.name;
    e.is_peer = false;
    e.workers = workers;
    if (workers > 1) e.note = std::to_string(workers) + " workers";
    const BroadPhaseKind kind = k.kind;
    e.run = [kind, workers](const SceneSpec& scene, int32_t warmup, int32_t steps) {
      return run_tandem(kind, workers, scene, warmup, steps);
    };
    e.cast_rays = [kind, workers](const SceneSpec& scene, int32_t warmup, std::string* error) {
      return tandem_rays(kind, workers, scene, warmup, error);
    };
    *out = std::move(e);
    return true;
  }
  return false;
}

}  // namespace tandem::bench
