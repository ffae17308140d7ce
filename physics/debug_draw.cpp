// debug_draw.cpp — world_draw() (see debug_draw.h). Reads the world only:
// public getters for bodies, shapes and joints, World::contacts for the
// manifold points (the one internal read, owned here so drawers need not
// include physics/world.h).
#include "physics/debug_draw.h"

#include <vector>

#include "physics/contact.h"
#include "physics/world.h"

namespace tandem {
namespace {

DrawBodyState body_state(BodyId b) {
  if (!body_is_enabled(b)) return DrawBodyState::disabled;
  switch (body_type(b)) {
    case BodyType::static_body: return DrawBodyState::static_body;
    case BodyType::kinematic_body: return DrawBodyState::kinematic_body;
    default: return body_is_awake(b) ? DrawBodyState::awake : DrawBodyState::asleep;
  }
}

void draw_shape(const DebugDraw& dd, const ShapeGeometry& g, const Transform& xf, const DrawShape& info) {
  switch (g.type) {
    case ShapeType::circle:
      if (dd.draw_circle != nullptr) {
        const Vec2 rim = g.circle.center + Vec2{g.circle.radius, Q32{}};
        dd.draw_circle(transform_point(xf, g.circle.center), g.circle.radius, transform_point(xf, rim), info,
                       dd.context);
      }
      break;
    case ShapeType::capsule:
      if (dd.draw_capsule != nullptr)
        dd.draw_capsule(transform_point(xf, g.capsule.center1), transform_point(xf, g.capsule.center2),
                        g.capsule.radius, info, dd.context);
      break;
    case ShapeType::polygon:
      if (dd.draw_polygon != nullptr) {
        Vec2 vertices[k_max_polygon_vertices];
        const int32_t count = g.polygon.count;
        for (int32_t i = 0; i < count; ++i)
          vertices[i] = transform_point(xf, g.polygon.vertices[static_cast<size_t>(i)]);
        dd.draw_polygon(vertices, count, g.polygon.radius, info, dd.context);
      }
      break;
    case ShapeType::segment:
    case ShapeType::chain_segment:
      if (dd.draw_segment != nullptr) {
        const Segment& s = g.type == ShapeType::segment ? g.segment : g.chain_segment.segment;
        dd.draw_segment(transform_point(xf, s.point1), transform_point(xf, s.point2), info, dd.context);
      }
      break;
    default: break;
  }
}

}  // namespace

Status world_draw(WorldId world, const DebugDraw& dd) {
  World* w = nullptr;
  Status status = resolve_world(world, "world_draw", false, &w);
  if (!status.ok()) return status;
  if (w->locked) return make_status(StatusCode::world_locked, "world_draw: the world is inside world_step()");

  if (dd.draw_shapes || dd.draw_aabbs) {
    const int32_t body_count = world_bodies(world, nullptr, 0);
    std::vector<BodyId> bodies(static_cast<size_t>(body_count));
    world_bodies(world, bodies.data(), body_count);
    std::vector<ShapeId> shapes;
    for (const BodyId b : bodies) {
      const Transform xf = body_transform(b);
      const DrawBodyState state = body_state(b);
      shapes.resize(static_cast<size_t>(body_shape_count(b)));
      body_shapes(b, shapes.data(), static_cast<int32_t>(shapes.size()));
      for (const ShapeId s : shapes) {
        const ShapeGeometry g = shape_geometry(s);
        const DrawShape info{b, s, g.type, state, shape_is_sensor(s)};
        if (dd.draw_shapes) draw_shape(dd, g, xf, info);
        if (dd.draw_aabbs && dd.draw_aabb != nullptr) dd.draw_aabb(shape_aabb(s), info, dd.context);
      }
    }
  }
  if (dd.draw_joints && dd.draw_joint != nullptr) {
    const int32_t joint_count = world_joints(world, nullptr, 0);
    std::vector<JointId> joints(static_cast<size_t>(joint_count));
    world_joints(world, joints.data(), joint_count);
    for (const JointId j : joints) {
      dd.draw_joint(j, joint_type(j), body_position(joint_body_a(j)), joint_world_anchor_a(j),
                    joint_world_anchor_b(j), body_position(joint_body_b(j)), dd.context);
    }
  }
  if (dd.draw_contacts && dd.draw_contact != nullptr) {
    for (const Contact& c : w->contacts) {
      const Manifold& m = c.manifold;
      for (int i = 0; i < m.point_count; ++i) {
        const ManifoldPoint& p = m.points[static_cast<size_t>(i)];
        dd.draw_contact(p.point, m.normal, p.separation, dd.context);
      }
    }
  }
  return status;
}

}  // namespace tandem
