// peer_chipmunk.cpp — the Chipmunk2D 7 harness (see peers.h for the
// matching choices). Chipmunk works in binary64: it gets the spec's values
// exactly.
#include <chipmunk/chipmunk.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "peers.h"

namespace tandem::bench {
namespace {

void probe(const SceneSpec& scene, const std::vector<cpBody*>& bodies, bool end, Quality* q) {
  double ke = 0;
  for (size_t i = 0; i < bodies.size(); ++i) {
    if (!scene.bodies[i].dynamic) continue;
    cpBody* b = bodies[i];
    const cpVect v = cpBodyGetVelocity(b);
    const double w = cpBodyGetAngularVelocity(b);
    ke += 0.5 * cpBodyGetMass(b) * (v.x * v.x + v.y * v.y) + 0.5 * cpBodyGetMoment(b) * w * w;
  }
  const double track_y =
      scene.track_index >= 0 ? cpBodyGetPosition(bodies[static_cast<size_t>(scene.track_index)]).y : 0.0;
  if (!end) {
    q->ke_start = ke;
    q->track_y_start = track_y;
    return;
  }
  q->ke_end = ke;
  q->track_y_end = track_y;
  for (size_t i = 0; i < bodies.size(); ++i) {
    if (!scene.bodies[i].dynamic) continue;
    const cpVect p = cpBodyGetPosition(bodies[i]);
    const cpVect v = cpBodyGetVelocity(bodies[i]);
    q->max_speed = std::max(q->max_speed, std::hypot(v.x, v.y));
    const Container& c = scene.container;
    if (p.x < c.min_x || p.x > c.max_x || p.y < c.min_y || p.y > c.max_y) ++q->escaped;
    if (std::fabs(p.x - to_double(scene.bodies[i].x)) > 0.25) ++q->moved;
  }
}

RunResult run_chipmunk(const SceneSpec& scene, int32_t warmup, int32_t steps) {
  RunResult result;
  if (!scene.joints.empty()) {  // not wired here: the joint scenes compare Tandem with the Box2Ds
    result.error = "the Chipmunk2D harness builds no joints (joint_grid, tumbler, spinner)";
    return result;
  }
  cpSpace* space = cpSpaceNew();
  cpSpaceSetGravity(space, cpv(to_double(scene.gravity_x), to_double(scene.gravity_y)));
  if (scene.sleep) {
    // Box2D's sleep rule: 0.5 s below 0.05 m/s (Chipmunk's idle speed
    // otherwise comes from gravity, which smash has none of).
    cpSpaceSetSleepTimeThreshold(space, 0.5);
    cpSpaceSetIdleSpeedThreshold(space, 0.05);
  }
  cpBody* static_body = cpSpaceGetStaticBody(space);
  std::vector<cpBody*> bodies;  // static shapes share the space's static body
  std::vector<cpBody*> owned;
  std::vector<cpShape*> shapes;
  bodies.reserve(scene.bodies.size());
  for (const BodySpec& s : scene.bodies) {
    cpBody* body = static_body;
    const double x = to_double(s.x), y = to_double(s.y);
    if (s.dynamic) {
      double m = 0, inertia = 0;
      spec_mass(s, &m, &inertia);
      body = cpSpaceAddBody(space, cpBodyNew(m, inertia));
      cpBodySetPosition(body, cpv(x, y));
      cpBodySetVelocity(body, cpv(to_double(s.vx), to_double(s.vy)));
      owned.push_back(body);
    }
    // Static shapes are placed in the static body's frame (at the origin).
    const double ox = s.dynamic ? 0.0 : x, oy = s.dynamic ? 0.0 : y;
    cpShape* shape = nullptr;
    switch (s.shape) {
      case ShapeKind::circle:
        shape = cpCircleShapeNew(body, to_double(s.radius), cpv(ox, oy));
        break;
      case ShapeKind::box: {
        const double hx = to_double(s.half_width), hy = to_double(s.half_height);
        shape = cpBoxShapeNew2(body, cpBBNew(ox - hx, oy - hy, ox + hx, oy + hy), 0.0);
        break;
      }
      case ShapeKind::capsule: {
        const double hl = to_double(s.half_width);
        shape = cpSegmentShapeNew(body, cpv(ox - hl, oy), cpv(ox + hl, oy), to_double(s.radius));
        break;
      }
      case ShapeKind::segment: {
        const double hl = to_double(s.half_width);
        shape = cpSegmentShapeNew(body, cpv(ox - hl, oy), cpv(ox + hl, oy), 0.0);
        break;
      }
      case ShapeKind::none:  // only the joint scenes, refused above
        break;
    }
    if (shape == nullptr) {
      bodies.push_back(body);
      continue;
    }
    cpShapeSetFriction(shape, std::sqrt(to_double(s.friction)));
    cpShapeSetElasticity(shape, std::sqrt(to_double(s.restitution)));
    cpSpaceAddShape(space, shape);
    shapes.push_back(shape);
    bodies.push_back(body);
  }
  for (size_t i = 0; i < scene.bodies.size(); ++i) {
    if (scene.sleep && scene.bodies[i].dynamic && !scene.bodies[i].awake) cpBodySleep(bodies[i]);
  }
  probe(scene, bodies, false, &result.quality);
  const double dt = to_double(time_step());
  for (int32_t i = 0; i < warmup; ++i) cpSpaceStep(space, dt);
  const StepTimer timer;
  for (int32_t i = 0; i < steps; ++i) cpSpaceStep(space, dt);
  timer.stop(steps, &result);
  probe(scene, bodies, true, &result.quality);
  for (cpShape* sh : shapes) {
    cpSpaceRemoveShape(space, sh);
    cpShapeFree(sh);
  }
  for (cpBody* b : owned) {
    cpSpaceRemoveBody(space, b);
    cpBodyFree(b);
  }
  cpSpaceFree(space);
  return result;
}

}  // namespace

Engine chipmunk_engine() {
  Engine e;
  e.engine = "chipmunk";
  e.broad_phase = "bb-tree";
  e.note = "Chipmunk2D 7.0.3 (Debian libchipmunk: debug checks on, 30-43 % slower on circles than an optimised build), "
           "10 iterations, slop 0.1 m";
  e.is_peer = true;
  e.run = run_chipmunk;
  return e;
}

}  // namespace tandem::bench
