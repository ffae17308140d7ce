/* tandem_c_geometry.h — single-shape geometry (physics/collision.h):
 * validation, mass, bounding boxes, point tests, ray casts against one shape
 * and the contact manifold of two shapes. Part of the C API; include
 * tandem_c.h (the umbrella) or this file alone. The conventions (numbers,
 * handles, errors, buffers) are in tandem_c.h. Shapes are in their local
 * frame, m; transforms place them in the world. */
#ifndef TANDEM_C_GEOMETRY_H
#define TANDEM_C_GEOMETRY_H

#include "tandem_c_base.h"
#include "tandem_c_world.h"

#ifdef __cplusplus
extern "C" {
#endif

/** A ray (RayCastInput): from origin along translation, up to max_fraction. */
typedef struct tandem_ray_cast_input {
  tandem_vec2 origin, translation;  /**< m */
  tandem_q32 max_fraction;          /**< of the translation; usually 1 */
} tandem_ray_cast_input;

/** A ray cast's result (CastOutput). */
typedef struct tandem_cast_output {
  tandem_vec2 normal;   /**< unit surface normal at the hit */
  tandem_vec2 point;    /**< m */
  tandem_q32 fraction;  /**< of the translation */
  int32_t iterations;
  bool hit;
} tandem_cast_output;

/** Check a shape's ranges (the message names the culprit); TANDEM_OK when valid. */
TANDEM_C_API tandem_status tandem_validate_circle(const tandem_circle* circle);
TANDEM_C_API tandem_status tandem_validate_capsule(const tandem_capsule* capsule);
TANDEM_C_API tandem_status tandem_validate_segment(const tandem_segment* segment);
TANDEM_C_API tandem_status tandem_validate_polygon(const tandem_polygon* polygon);

/** Mass properties at a density (kg/m²). */
TANDEM_C_API tandem_status tandem_compute_circle_mass(const tandem_circle* circle, tandem_q32 density,
                                                      tandem_mass_data* out_mass);
TANDEM_C_API tandem_status tandem_compute_capsule_mass(const tandem_capsule* capsule, tandem_q32 density,
                                                       tandem_mass_data* out_mass);
TANDEM_C_API tandem_status tandem_compute_polygon_mass(const tandem_polygon* polygon, tandem_q32 density,
                                                       tandem_mass_data* out_mass);

/** The bounding box of a shape placed by a transform (any kind, by its
 * geometry's type: TANDEM_SHAPE_*). */
TANDEM_C_API tandem_status tandem_compute_shape_aabb(const tandem_shape_geometry* shape, tandem_transform transform,
                                                     tandem_aabb* out_aabb);
/** True when the local point is inside or on the shape (circle, capsule,
 * polygon; false for segments and chain segments). */
TANDEM_C_API tandem_status tandem_point_in_shape(const tandem_shape_geometry* shape, tandem_vec2 point,
                                                 bool* out_inside);
/** A ray (local frame) against one shape (circle, capsule, polygon, segment
 * two-sided, chain segment one-sided). */
TANDEM_C_API tandem_status tandem_ray_cast_shape(const tandem_shape_geometry* shape,
                                                 const tandem_ray_cast_input* input, tandem_cast_output* out);
/** The contact manifold of two placed shapes (collide): points while the
 * separation is below the speculative distance; normal from A to B. Any
 * pair of kinds, either order (segments and chain segments against each
 * other give no points). */
TANDEM_C_API tandem_status tandem_collide(const tandem_shape_geometry* a, tandem_transform transform_a,
                                          const tandem_shape_geometry* b, tandem_transform transform_b,
                                          tandem_manifold* out_manifold);

#ifdef __cplusplus
}  /* extern "C" */
#endif

#endif /* TANDEM_C_GEOMETRY_H */
