// peer_box2d3.cpp — the Box2D v3 harness (optional; built only when the
// CMake cache variable TANDEM_BOX2D_V3_DIR names a built Box2D v3 checkout:
// its include/ and build/src/libbox2d.a. Nothing here downloads it and none
// of its code is in this repository; docs/benchmarks.md says how to build
// it outside the tree).
//
// Matching choices: b2DefaultWorldDef() with the scene's gravity, 4
// sub-steps per 1/60 s step (Tandem's default, and v3's benchmark),
// continuous collision on (its default), sleeping as the scene says (on for
// smash, off elsewhere), its built-in scheduler with `workers` workers (1 or
// 2 here). Shapes: b2MakeBox, b2Circle, b2Capsule and b2Segment, density,
// friction and restitution from the spec; v3 mixes friction as
// sqrt(a·b) and restitution as max(a, b), as Tandem does. v3 works in
// binary32: the spec's exact doubles are rounded once to float. Joints:
// b2DefaultRevoluteJointDef() (v3's joint softness defaults) anchored at the
// spec's world point; the spinner's ring is 360 segments where v3's own
// benchmark has one loop chain.
//
// The include path of this file alone points at v3's headers (Box2D 2.4's
// are also <box2d/box2d.h>); v3's API is C, so its symbols cannot collide
// with 2.4's C++ ones.
#include <box2d/box2d.h>

#include <cmath>
#include <string>
#include <vector>

#include "peers.h"

namespace tandem::bench {
namespace {

float f32(Q32 v) { return static_cast<float>(to_double(v)); }

void probe(const SceneSpec& scene, const std::vector<b2BodyId>& bodies, bool end, Quality* q) {
  double ke = 0;
  for (size_t i = 0; i < bodies.size(); ++i) {
    if (!scene.bodies[i].dynamic) continue;
    const b2Vec2 v = b2Body_GetLinearVelocity(bodies[i]);
    const double w = b2Body_GetAngularVelocity(bodies[i]);
    ke += 0.5 * double(b2Body_GetMass(bodies[i])) * (double(v.x) * v.x + double(v.y) * v.y) +
          0.5 * double(b2Body_GetRotationalInertia(bodies[i])) * w * w;
  }
  const double track_y =
      scene.track_index >= 0 ? double(b2Body_GetPosition(bodies[static_cast<size_t>(scene.track_index)]).y) : 0.0;
  if (!end) {
    q->ke_start = ke;
    q->track_y_start = track_y;
    return;
  }
  q->ke_end = ke;
  q->track_y_end = track_y;
  for (size_t i = 0; i < bodies.size(); ++i) {
    if (!scene.bodies[i].dynamic) continue;
    const b2Pos p = b2Body_GetPosition(bodies[i]);
    const b2Vec2 v = b2Body_GetLinearVelocity(bodies[i]);
    q->max_speed = std::max(q->max_speed, std::hypot(double(v.x), double(v.y)));
    const Container& c = scene.container;
    if (p.x < c.min_x || p.x > c.max_x || p.y < c.min_y || p.y > c.max_y) ++q->escaped;
    if (std::fabs(double(p.x) - to_double(scene.bodies[i].x)) > 0.25) ++q->moved;
  }
}

RunResult run_box2d3(int32_t workers, const SceneSpec& scene, int32_t warmup, int32_t steps) {
  RunResult result;
  b2WorldDef wd = b2DefaultWorldDef();
  wd.gravity = b2Vec2{f32(scene.gravity_x), f32(scene.gravity_y)};
  wd.enableSleep = scene.sleep;
  wd.workerCount = workers;
  const b2WorldId world = b2CreateWorld(&wd);
  std::vector<b2BodyId> bodies;
  bodies.reserve(scene.bodies.size());
  for (const BodySpec& s : scene.bodies) {
    b2BodyDef bd = b2DefaultBodyDef();
    bd.type = s.dynamic ? b2_dynamicBody : b2_staticBody;
    bd.position.x = f32(s.x);
    bd.position.y = f32(s.y);
    bd.linearVelocity = b2Vec2{f32(s.vx), f32(s.vy)};
    bd.enableSleep = scene.sleep;
    bd.isAwake = s.awake;
    const b2BodyId body = b2CreateBody(world, &bd);
    b2ShapeDef sd = b2DefaultShapeDef();
    sd.density = f32(s.density);
    sd.material.friction = f32(s.friction);
    sd.material.restitution = f32(s.restitution);
    if (!s.self_collide) {  // joint_grid: v3's category 2, mask ~2
      sd.filter.categoryBits = 2;
      sd.filter.maskBits = ~uint64_t{2};
    }
    for (const BoxPart& part : s.boxes) {
      const b2Polygon box = b2MakeOffsetBox(f32(part.half_width), f32(part.half_height),
                                            b2Vec2{f32(part.cx), f32(part.cy)}, b2Rot_identity);
      b2CreatePolygonShape(body, &sd, &box);
    }
    for (const SegmentPart& part : s.segments) {
      const b2Segment segment{{f32(part.x1), f32(part.y1)}, {f32(part.x2), f32(part.y2)}};
      b2CreateSegmentShape(body, &sd, &segment);
    }
    switch (s.shape) {
      case ShapeKind::none:
        break;
      case ShapeKind::circle: {
        const b2Circle circle{{0.0f, 0.0f}, f32(s.radius)};
        b2CreateCircleShape(body, &sd, &circle);
        break;
      }
      case ShapeKind::box: {
        const b2Polygon box = b2MakeRoundedBox(f32(s.half_width), f32(s.half_height), f32(s.rounding));
        b2CreatePolygonShape(body, &sd, &box);
        break;
      }
      case ShapeKind::capsule: {
        const b2Capsule capsule{{-f32(s.half_width), 0.0f}, {f32(s.half_width), 0.0f}, f32(s.radius)};
        b2CreateCapsuleShape(body, &sd, &capsule);
        break;
      }
      case ShapeKind::segment: {
        const b2Segment segment{{-f32(s.half_width), 0.0f}, {f32(s.half_width), 0.0f}};
        b2CreateSegmentShape(body, &sd, &segment);
        break;
      }
    }
    bodies.push_back(body);
  }
  for (const RevoluteSpec& j : scene.joints) {
    b2RevoluteJointDef jd = b2DefaultRevoluteJointDef();
    jd.base.bodyIdA = bodies[static_cast<size_t>(j.a)];
    jd.base.bodyIdB = bodies[static_cast<size_t>(j.b)];
    b2Pos anchor;
    anchor.x = f32(j.x);
    anchor.y = f32(j.y);
    jd.base.localFrameA.p = b2Body_GetLocalPoint(jd.base.bodyIdA, anchor);
    jd.base.localFrameB.p = b2Body_GetLocalPoint(jd.base.bodyIdB, anchor);
    jd.enableMotor = j.motor;
    jd.motorSpeed = f32(j.motor_speed);
    jd.maxMotorTorque = f32(j.max_motor_torque);
    b2CreateRevoluteJoint(world, &jd);
  }
  probe(scene, bodies, false, &result.quality);
  const float dt = static_cast<float>(to_double(time_step()));
  constexpr int sub_steps = 4;
  for (int32_t i = 0; i < warmup; ++i) b2World_Step(world, dt, sub_steps);
  const StepTimer timer;
  for (int32_t i = 0; i < steps; ++i) b2World_Step(world, dt, sub_steps);
  timer.stop(steps, &result);
  probe(scene, bodies, true, &result.quality);
  b2DestroyWorld(world);
  return result;
}

}  // namespace

Engine box2d3_engine(int32_t workers) {
  Engine e;
  e.engine = "box2d3-w" + std::to_string(workers);
  e.workers = workers;
  e.broad_phase = "dyn-tree";
  const b2Version v = b2GetVersion();
  e.note = "Box2D v" + std::to_string(v.major) + "." + std::to_string(v.minor) + "." + std::to_string(v.revision) +
           " (built from source outside the repository, TANDEM_BOX2D_V3_DIR), " + std::to_string(workers) +
           (workers == 1 ? " worker" : " workers") + ", 4 sub-steps";
  e.is_peer = true;
  e.run = [workers](const SceneSpec& scene, int32_t warmup, int32_t steps) {
    return run_box2d3(workers, scene, warmup, steps);
  };
  return e;
}

}  // namespace tandem::bench
