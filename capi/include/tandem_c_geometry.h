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

/* --- Distance, shape cast, time of impact (GJK; physics/collision.h) ---- */

/** A convex point set with a radius (ShapeProxy): circle 1 point, capsule
 * and segment 2, polygon its vertices. */
typedef struct tandem_shape_proxy {
  tandem_vec2 points[TANDEM_MAX_POLYGON_VERTICES];
  int32_t count;
  tandem_q32 radius;
} tandem_shape_proxy;

/** Input of tandem_shape_distance (DistanceInput). */
typedef struct tandem_distance_input {
  tandem_shape_proxy proxy_a, proxy_b;
  tandem_transform transform_a, transform_b;
  bool use_radii;  /**< subtract the radii from the core distance */
} tandem_distance_input;

/** Closest points and distance (DistanceOutput). */
typedef struct tandem_distance_output {
  tandem_vec2 point_a, point_b;  /**< world, m */
  tandem_vec2 normal;            /**< unit, from A to B (zero if the cores overlap) */
  tandem_q32 distance;           /**< m, ≥ 0 */
  int32_t iterations, simplex_count;
} tandem_distance_output;

/** Input of tandem_shape_cast (ShapeCastInput): B moves by translation_b. */
typedef struct tandem_shape_cast_input {
  tandem_shape_proxy proxy_a, proxy_b;
  tandem_transform transform_a, transform_b;
  tandem_vec2 translation_b;  /**< m */
  tandem_q32 max_fraction;
  bool can_encroach;
} tandem_shape_cast_input;

/** A body's motion over a step (Sweep). */
typedef struct tandem_sweep {
  tandem_vec2 local_center;  /**< centre of mass in the body frame, m */
  tandem_vec2 c1, c2;        /**< world centre of mass at t = 0 and 1 */
  tandem_rot q1, q2;         /**< rotation at t = 0 and 1 */
} tandem_sweep;

/** Time-of-impact states (ToiState). */
#define TANDEM_TOI_UNKNOWN 0
#define TANDEM_TOI_FAILED 1
#define TANDEM_TOI_OVERLAPPED 2
#define TANDEM_TOI_HIT 3
#define TANDEM_TOI_SEPARATED 4

/** Input and output of tandem_time_of_impact (ToiInput, ToiOutput). */
typedef struct tandem_toi_input {
  tandem_shape_proxy proxy_a, proxy_b;
  tandem_sweep sweep_a, sweep_b;
  tandem_q32 max_fraction;
} tandem_toi_input;
typedef struct tandem_toi_output {
  int32_t state;  /**< TANDEM_TOI_* */
  tandem_q32 fraction;
  int32_t iterations;
} tandem_toi_output;

/** A proxy from points (count clamped to 8; none: one point at the origin). */
TANDEM_C_API tandem_status tandem_make_proxy(const tandem_vec2* points, int32_t count, tandem_q32 radius,
                                             tandem_shape_proxy* out_proxy);
/** The proxy of a circle, capsule, segment or polygon (not a chain segment). */
TANDEM_C_API tandem_status tandem_make_shape_proxy(const tandem_shape_geometry* shape, tandem_shape_proxy* out_proxy);
/** GJK distance with witness points (shape_distance). */
TANDEM_C_API tandem_status tandem_shape_distance(const tandem_distance_input* input, tandem_distance_output* out);
/** Linear shape cast: the first fraction at which B touches A (shape_cast). */
TANDEM_C_API tandem_status tandem_shape_cast(const tandem_shape_cast_input* input, tandem_cast_output* out);
/** The transform of a sweep at t in [0, 1] (sweep_transform). */
TANDEM_C_API tandem_status tandem_sweep_transform(const tandem_sweep* sweep, tandem_q32 t,
                                                  tandem_transform* out_transform);
/** Time of impact of two moving shapes (time_of_impact). */
TANDEM_C_API tandem_status tandem_time_of_impact(const tandem_toi_input* input, tandem_toi_output* out);

#ifdef __cplusplus
}  /* extern "C" */
#endif

#endif /* TANDEM_C_GEOMETRY_H */
