// peer_box2d24.cpp — the Box2D 2.4 harness (see peers.h for the matching
// choices). Box2D 2.4 works in binary32: the spec's exact doubles are
// rounded once to float when the bodies are made.
#include <box2d/box2d.h>

#include <chrono>
#include <cmath>
#include <memory>
#include <vector>

#include "peers.h"

namespace tandem::bench {
namespace {

float f32(Q32 v) { return static_cast<float>(to_double(v)); }

void probe(const SceneSpec& scene, const std::vector<b2Body*>& bodies, bool end, Quality* q) {
  double ke = 0;
  for (size_t i = 0; i < bodies.size(); ++i) {
    if (!scene.bodies[i].dynamic) continue;
    const b2Body* b = bodies[i];
    const b2Vec2 v = b->GetLinearVelocity();
    const double w = b->GetAngularVelocity();
    ke += 0.5 * b->GetMass() * (double(v.x) * v.x + double(v.y) * v.y) + 0.5 * double(b->GetInertia()) * w * w;
  }
  const double track_y =
      scene.track_index >= 0 ? double(bodies[static_cast<size_t>(scene.track_index)]->GetPosition().y) : 0.0;
  if (!end) {
    q->ke_start = ke;
    q->track_y_start = track_y;
    return;
  }
  q->ke_end = ke;
  q->track_y_end = track_y;
  for (size_t i = 0; i < bodies.size(); ++i) {
    if (!scene.bodies[i].dynamic) continue;
    const b2Vec2 p = bodies[i]->GetPosition();
    const b2Vec2 v = bodies[i]->GetLinearVelocity();
    q->max_speed = std::max(q->max_speed, std::hypot(double(v.x), double(v.y)));
    const Container& c = scene.container;
    if (p.x < c.min_x || p.x > c.max_x || p.y < c.min_y || p.y > c.max_y) ++q->escaped;
    if (std::fabs(double(p.x) - to_double(scene.bodies[i].x)) > 0.25) ++q->moved;
  }
}

/// Builds the scene in a new b2World; its bodies in spec order into *out_bodies.
std::unique_ptr<b2World> build_box2d24(const SceneSpec& scene, std::vector<b2Body*>* out_bodies) {
  auto world = std::make_unique<b2World>(b2Vec2(f32(scene.gravity_x), f32(scene.gravity_y)));
  world->SetAllowSleeping(scene.sleep);
  std::vector<b2Body*>& bodies = *out_bodies;
  bodies.clear();
  bodies.reserve(scene.bodies.size());
  for (const BodySpec& s : scene.bodies) {
    b2BodyDef bd;
    bd.type = s.dynamic ? b2_dynamicBody : b2_staticBody;
    bd.position.Set(f32(s.x), f32(s.y));
    bd.linearVelocity.Set(f32(s.vx), f32(s.vy));
    bd.allowSleep = scene.sleep;
    bd.awake = s.awake;
    b2Body* body = world->CreateBody(&bd);
    b2FixtureDef fd;
    fd.friction = f32(s.friction);
    fd.restitution = f32(s.restitution);
    fd.density = f32(s.density);
    if (!s.self_collide) {  // joint_grid: category 2, mask ~2 (2.4's bits are 16-bit)
      fd.filter.categoryBits = 2;
      fd.filter.maskBits = static_cast<uint16>(~2u);
    }
    for (const BoxPart& part : s.boxes) {
      b2PolygonShape poly;
      poly.SetAsBox(f32(part.half_width), f32(part.half_height), b2Vec2(f32(part.cx), f32(part.cy)), 0.0f);
      fd.shape = &poly;
      body->CreateFixture(&fd);
    }
    for (const SegmentPart& part : s.segments) {
      b2EdgeShape edge;
      edge.SetTwoSided(b2Vec2(f32(part.x1), f32(part.y1)), b2Vec2(f32(part.x2), f32(part.y2)));
      fd.shape = &edge;
      body->CreateFixture(&fd);
    }
    switch (s.shape) {
      case ShapeKind::none:
        break;
      case ShapeKind::circle: {
        b2CircleShape circle;
        circle.m_radius = f32(s.radius);
        fd.shape = &circle;
        body->CreateFixture(&fd);
        break;
      }
      case ShapeKind::box: {
        b2PolygonShape poly;
        poly.SetAsBox(f32(s.half_width), f32(s.half_height));
        fd.shape = &poly;
        body->CreateFixture(&fd);
        break;
      }
      case ShapeKind::segment: {
        b2EdgeShape edge;
        edge.SetTwoSided(b2Vec2(-f32(s.half_width), 0.0f), b2Vec2(f32(s.half_width), 0.0f));
        fd.shape = &edge;
        body->CreateFixture(&fd);
        break;
      }
      case ShapeKind::capsule: {
        b2PolygonShape poly;
        poly.SetAsBox(f32(s.half_width), f32(s.radius));
        fd.shape = &poly;
        body->CreateFixture(&fd);
        for (int side = -1; side <= 1; side += 2) {
          b2CircleShape end;
          end.m_radius = f32(s.radius);
          end.m_p.Set(static_cast<float>(side) * f32(s.half_width), 0.0f);
          fd.shape = &end;
          body->CreateFixture(&fd);
        }
        double m = 0, inertia = 0;
        spec_mass(s, &m, &inertia);
        b2MassData md;
        md.mass = static_cast<float>(m);
        md.center.SetZero();
        md.I = static_cast<float>(inertia);
        body->SetMassData(&md);
        break;
      }
    }
    bodies.push_back(body);
  }
  for (const RevoluteSpec& j : scene.joints) {
    b2RevoluteJointDef jd;
    jd.Initialize(bodies[static_cast<size_t>(j.a)], bodies[static_cast<size_t>(j.b)], b2Vec2(f32(j.x), f32(j.y)));
    jd.enableMotor = j.motor;
    jd.motorSpeed = f32(j.motor_speed);
    jd.maxMotorTorque = f32(j.max_motor_torque);
    world->CreateJoint(&jd);
  }
  return world;
}

RunResult run_box2d24(const SceneSpec& scene, int32_t warmup, int32_t steps) {
  RunResult result;
  std::vector<b2Body*> bodies;
  const std::unique_ptr<b2World> world = build_box2d24(scene, &bodies);
  probe(scene, bodies, false, &result.quality);
  const float dt = static_cast<float>(to_double(time_step()));
  constexpr int32_t velocity_iterations = 8, position_iterations = 3;
  for (int32_t i = 0; i < warmup; ++i) world->Step(dt, velocity_iterations, position_iterations);
  const StepTimer timer;
  for (int32_t i = 0; i < steps; ++i) world->Step(dt, velocity_iterations, position_iterations);
  timer.stop(steps, &result);
  probe(scene, bodies, true, &result.quality);
  return result;
}

/// Closest hit through b2World::RayCast: the callback returns the hit's
/// fraction, so the ray is clipped to it (Box2D's documented closest-hit use).
class ClosestCallback : public b2RayCastCallback {
 public:
  float ReportFixture(b2Fixture* /*fixture*/, const b2Vec2& /*point*/, const b2Vec2& /*normal*/,
                      float fraction) override {
    hit = true;
    best = fraction;
    return fraction;
  }
  bool hit = false;
  float best = 1.0f;
};

class Box2d24Rays final : public RaySession {
 public:
  explicit Box2d24Rays(std::unique_ptr<b2World> world) : world_(std::move(world)) {}

  RayBatch batch(const std::vector<RaySpec>& rays) override {
    RayBatch b;
    world_->Step(static_cast<float>(to_double(time_step())), 8, 3);
    from_.clear();
    to_.clear();
    for (const RaySpec& r : rays) {
      from_.emplace_back(f32(r.origin.x), f32(r.origin.y));
      to_.emplace_back(static_cast<float>(to_double(r.origin.x) + to_double(r.translation.x)),
                       static_cast<float>(to_double(r.origin.y) + to_double(r.translation.y)));
    }
    const auto t0 = std::chrono::steady_clock::now();
    for (size_t i = 0; i < from_.size(); ++i) {
      if (from_[i].x == to_[i].x && from_[i].y == to_[i].y) continue;  // Box2D asserts on a zero-length ray
      ClosestCallback cb;
      world_->RayCast(&cb, from_[i], to_[i]);
      b.hits += cb.hit ? 1 : 0;
    }
    const auto t1 = std::chrono::steady_clock::now();
    const double seconds = std::chrono::duration<double>(t1 - t0).count();
    b.rays_per_second = seconds > 0 ? static_cast<double>(rays.size()) / seconds : 0.0;
    return b;
  }

 private:
  std::unique_ptr<b2World> world_;
  std::vector<b2Vec2> from_, to_;
};

std::unique_ptr<RaySession> box2d24_rays(const SceneSpec& scene, int32_t warmup, std::string* /*error*/) {
  std::vector<b2Body*> bodies;
  std::unique_ptr<b2World> world = build_box2d24(scene, &bodies);
  const float dt = static_cast<float>(to_double(time_step()));
  for (int32_t i = 0; i < warmup; ++i) world->Step(dt, 8, 3);  // 8 velocity / 3 position iterations
  return std::make_unique<Box2d24Rays>(std::move(world));
}

}  // namespace

void spec_mass(const BodySpec& b, double* mass, double* inertia) {
  const double pi = 3.14159265358979323846;
  const double rho = to_double(b.density);
  switch (b.shape) {
    case ShapeKind::circle: {
      const double r = to_double(b.radius);
      *mass = rho * pi * r * r;
      *inertia = 0.5 * *mass * r * r;
      return;
    }
    case ShapeKind::box: {
      const double w = 2 * to_double(b.half_width), h = 2 * to_double(b.half_height);
      *mass = rho * w * h;
      *inertia = *mass * (w * w + h * h) / 12.0;
      return;
    }
    case ShapeKind::segment:
    case ShapeKind::none:
      break;  // no area (static only), or no shape
    case ShapeKind::capsule: {
      const double r = to_double(b.radius), hl = to_double(b.half_width), len = 2 * hl;
      const double m_rect = rho * len * 2 * r;
      const double i_rect = m_rect * (len * len + 4 * r * r) / 12.0;
      const double m_half = rho * pi * r * r / 2;  // each end is a half disc
      const double d = 4 * r / (3 * pi);          // its centroid beyond the segment end
      const double i_half = m_half * r * r / 2 - m_half * d * d + m_half * (hl + d) * (hl + d);
      *mass = m_rect + 2 * m_half;
      *inertia = i_rect + 2 * i_half;
      return;
    }
  }
  *mass = 0;
  *inertia = 0;
}

Engine box2d24_engine() {
  Engine e;
  e.engine = "box2d24";
  e.broad_phase = "dyn-tree";
  e.note = "Box2D 2.4.1 (Debian libbox2d), 8 velocity / 3 position iterations";
  e.is_peer = true;
  e.run = run_box2d24;
  e.cast_rays = box2d24_rays;
  return e;
}

}  // namespace tandem::bench
