// debug_draw.h — a plain callback interface for drawing a world (Cairo
// pictures in tools/render, the web page's canvas in tools/web, a game's own
// debug overlay).
//
// world_draw() walks the world read-only and calls the callbacks the caller
// set, in a fixed order: bodies by ascending index, each body's shapes in
// body_shapes() order (the shape, then its AABB when asked), then joints by
// ascending index, then every contact's manifold points in World::contacts
// order (sorted by shape pair). A callback left null is skipped. Nothing
// here changes the world, its hashes or its golden chains.
//
// UNITS. Every coordinate is world space, metres, as Q32 (exact fixed
// point: local points are mapped with the fixed-point transform_point of
// fixed/vec2.h). A drawer that wants binary floating point converts at the
// edge with Q32::to_double() — display only, never fed back into a world.
// y is up.
#pragma once

#include <cstdint>

#include "fixed/fixed.h"
#include "fixed/vec2.h"
#include "physics/collision.h"
#include "physics/ids.h"
#include "physics/joint.h"
#include "physics/tandem.h"

namespace tandem {

/// How a shape's body stands, for colouring.
enum class DrawBodyState : int32_t {
  static_body = 0,     ///< a static body
  kinematic_body = 1,  ///< a kinematic body
  awake = 2,           ///< a dynamic body, awake
  asleep = 3,          ///< a dynamic body, sleeping
  disabled = 4,        ///< any body type, disabled (body_is_enabled false)
};

/// Which shape a shape callback draws and how it stands.
struct DrawShape {
  BodyId body;                          ///< its body
  ShapeId shape;                        ///< the shape
  ShapeType type = ShapeType::circle;   ///< its geometry kind (segment and chain_segment share draw_segment)
  DrawBodyState state = DrawBodyState::awake;
  bool sensor = false;                  ///< shape_is_sensor()
};

/// The callbacks and switches of world_draw(). Every callback receives
/// `context` as its last argument; null callbacks are skipped.
struct DebugDraw {
  void* context = nullptr;     ///< passed back to every callback
  bool draw_shapes = true;     ///< call the shape callbacks
  bool draw_aabbs = false;     ///< call draw_aabb after each shape (its world AABB, shape_aabb())
  bool draw_joints = true;     ///< call draw_joint for every joint
  bool draw_contacts = false;  ///< call draw_contact for every manifold point

  /// A convex polygon: `count` world vertices, counter-clockwise, and its
  /// rounding radius (m, ≥ 0; 0 for a sharp polygon).
  void (*draw_polygon)(const Vec2* vertices, int32_t count, Q32 radius, const DrawShape& shape, void* context) = nullptr;
  /// A circle: world centre, radius (m), and `rim`, the world point at
  /// centre + radius along the body's local x axis (a radius line shows rotation).
  void (*draw_circle)(Vec2 center, Q32 radius, Vec2 rim, const DrawShape& shape, void* context) = nullptr;
  /// A capsule: the world centres of its two caps and its radius (m).
  void (*draw_capsule)(Vec2 center1, Vec2 center2, Q32 radius, const DrawShape& shape, void* context) = nullptr;
  /// A segment or one segment of a chain (shape.type says which): world end points.
  void (*draw_segment)(Vec2 point1, Vec2 point2, const DrawShape& shape, void* context) = nullptr;
  /// A shape's world AABB (only with draw_aabbs).
  void (*draw_aabb)(const AABB& box, const DrawShape& shape, void* context) = nullptr;
  /// A joint: its kind, each body's origin and each world anchor. A mouse
  /// joint's anchor_a is its target; origin_a is body A's origin (the ground).
  void (*draw_joint)(JointId joint, JointType type, Vec2 origin_a, Vec2 anchor_a, Vec2 anchor_b, Vec2 origin_b,
                     void* context) = nullptr;
  /// One contact manifold point: world point, unit normal (from the lower
  /// shape index to the higher) and separation (m; ≤ 0 touching, > 0
  /// speculative).
  void (*draw_contact)(Vec2 point, Vec2 normal, Q32 separation, void* context) = nullptr;
};

/// Draws `world` through `draw` (see the file comment for the order).
/// Refuses a null or stale world handle and a world inside world_step() (the
/// only use of the returned status); draws nothing then.
Status world_draw(WorldId world, const DebugDraw& draw);

}  // namespace tandem
