/* tandem_c_joint.h — joints (physics/joint.h): revolute, distance (and rope),
 * weld, prismatic, mouse, wheel and motor joints. Part of the C API; include
 * tandem_c.h (the umbrella) or this file alone. The conventions (numbers,
 * handles, errors, buffers) are in tandem_c.h; units and ranges of every
 * field are those of physics/joint.h (anchors in each body's frame, m;
 * angles rad; forces N; torques N·m; stiffness Hz).
 *
 * A joint is named by a tandem_joint_id (index + 1, generation, world); a
 * destroyed joint's handle is stale and refused. Every definition comes from
 * its tandem_default_*_joint_def() (which stamps internal_cookie). */
#ifndef TANDEM_C_JOINT_H
#define TANDEM_C_JOINT_H

#include "tandem_c_base.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Joint kinds (tandem_joint_type; JointType). */
#define TANDEM_JOINT_REVOLUTE 0  /**< a shared point; rotation free (limits, motor, spring) */
#define TANDEM_JOINT_DISTANCE 1  /**< anchors at a length (rigid, spring, or a rope between min and max) */
#define TANDEM_JOINT_WELD 2      /**< relative pose fixed (rigid or soft) */
#define TANDEM_JOINT_PRISMATIC 3 /**< slides along an axis of A (limits, motor, spring) */
#define TANDEM_JOINT_MOUSE 4     /**< pulls an anchor of B to a world target; A is bookkeeping only */
#define TANDEM_JOINT_WHEEL 5     /**< slides along an axis with a suspension spring; rotation free */
#define TANDEM_JOINT_MOTOR 6     /**< drives B's pose relative to A with limited force and torque */

/** Joint event kinds (JointEventKind). */
#define TANDEM_JOINT_EVENT_BROKE 0               /**< a break threshold was exceeded; the joint is gone */
#define TANDEM_JOINT_EVENT_DESTROYED_WITH_BODY 1 /**< destroyed with one of its bodies */

/** Fields shared by every joint definition (JointBaseDef). */
typedef struct tandem_joint_base_def {
  tandem_body_id body_a, body_b;   /**< live bodies of the world; different; not both static */
  tandem_vec2 local_anchor_a;      /**< in A's frame, m */
  tandem_vec2 local_anchor_b;      /**< in B's frame, m */
  bool collide_connected;          /**< let the two bodies' shapes collide; default false */
  tandem_q32 break_force;          /**< N; 0 = never breaks */
  tandem_q32 break_torque;         /**< N·m; 0 = never breaks */
  uint64_t user_data;
} tandem_joint_base_def;

/** Revolute joint (RevoluteJointDef). */
typedef struct tandem_revolute_joint_def {
  tandem_joint_base_def base;
  tandem_q32 reference_angle;
  bool enable_limit;
  tandem_q32 lower_angle, upper_angle;
  bool enable_motor;
  tandem_q32 motor_speed, max_motor_torque;
  bool enable_spring;
  tandem_q32 hertz, damping_ratio;
  int32_t internal_cookie;  /**< set by the default function; do not touch */
} tandem_revolute_joint_def;

/** Distance joint (DistanceJointDef). A rope: enable_spring with hertz 0,
 * enable_limit, min_length 0, max_length = the rope's length. */
typedef struct tandem_distance_joint_def {
  tandem_joint_base_def base;
  tandem_q32 length;
  bool enable_spring;
  tandem_q32 hertz, damping_ratio;
  bool enable_limit;
  tandem_q32 min_length, max_length;
  bool enable_motor;
  tandem_q32 motor_speed, max_motor_force;
  int32_t internal_cookie;
} tandem_distance_joint_def;

/** Weld joint (WeldJointDef): hertz 0 = rigid. */
typedef struct tandem_weld_joint_def {
  tandem_joint_base_def base;
  tandem_q32 reference_angle;
  tandem_q32 linear_hertz, linear_damping_ratio;
  tandem_q32 angular_hertz, angular_damping_ratio;
  int32_t internal_cookie;
} tandem_weld_joint_def;

/** Prismatic joint (PrismaticJointDef). */
typedef struct tandem_prismatic_joint_def {
  tandem_joint_base_def base;
  tandem_vec2 local_axis_a;  /**< unit axis in A's frame */
  tandem_q32 reference_angle;
  bool enable_limit;
  tandem_q32 lower_translation, upper_translation;
  bool enable_motor;
  tandem_q32 motor_speed, max_motor_force;
  bool enable_spring;
  tandem_q32 hertz, damping_ratio;
  int32_t internal_cookie;
} tandem_prismatic_joint_def;

/** Mouse (target) joint (MouseJointDef). */
typedef struct tandem_mouse_joint_def {
  tandem_joint_base_def base;
  tandem_vec2 target;  /**< world point, m */
  tandem_q32 hertz, damping_ratio, max_force;
  int32_t internal_cookie;
} tandem_mouse_joint_def;

/** Wheel joint (WheelJointDef). */
typedef struct tandem_wheel_joint_def {
  tandem_joint_base_def base;
  tandem_vec2 local_axis_a;  /**< unit axis in A's frame */
  bool enable_spring;
  tandem_q32 hertz, damping_ratio;
  bool enable_limit;
  tandem_q32 lower_translation, upper_translation;
  bool enable_motor;
  tandem_q32 motor_speed, max_motor_torque;
  int32_t internal_cookie;
} tandem_wheel_joint_def;

/** Motor joint (MotorJointDef); the anchors of base are ignored. */
typedef struct tandem_motor_joint_def {
  tandem_joint_base_def base;
  tandem_vec2 linear_offset;  /**< B's origin in A's frame, m */
  tandem_q32 angular_offset;  /**< rad */
  tandem_q32 max_force, max_torque, correction_factor;
  int32_t internal_cookie;
} tandem_motor_joint_def;

/** A joint that is gone (JointEvent). */
typedef struct tandem_joint_event {
  tandem_joint_id joint;           /**< now stale */
  tandem_body_id body_a, body_b;   /**< may be stale */
  int32_t kind;                    /**< TANDEM_JOINT_EVENT_* */
  tandem_vec2 force;               /**< the reaction that broke it, N */
  tandem_q32 torque;               /**< N·m */
  uint64_t user_data;
} tandem_joint_event;

/** Definitions with every default filled in (physics/joint.h). */
TANDEM_C_API tandem_revolute_joint_def tandem_default_revolute_joint_def(void);
TANDEM_C_API tandem_distance_joint_def tandem_default_distance_joint_def(void);
TANDEM_C_API tandem_weld_joint_def tandem_default_weld_joint_def(void);
TANDEM_C_API tandem_prismatic_joint_def tandem_default_prismatic_joint_def(void);
TANDEM_C_API tandem_mouse_joint_def tandem_default_mouse_joint_def(void);
TANDEM_C_API tandem_wheel_joint_def tandem_default_wheel_joint_def(void);
TANDEM_C_API tandem_motor_joint_def tandem_default_motor_joint_def(void);

/** Create a joint in `world` into *out_joint. Refused (nothing changed, the
 * message names the field and its range): no cookie, a bad or foreign body,
 * body_a == body_b, two static bodies, a value out of range, inside a step. */
TANDEM_C_API tandem_status tandem_create_revolute_joint(tandem_world_id world, const tandem_revolute_joint_def* def,
                                                        tandem_joint_id* out_joint);
TANDEM_C_API tandem_status tandem_create_distance_joint(tandem_world_id world, const tandem_distance_joint_def* def,
                                                        tandem_joint_id* out_joint);
TANDEM_C_API tandem_status tandem_create_weld_joint(tandem_world_id world, const tandem_weld_joint_def* def,
                                                    tandem_joint_id* out_joint);
TANDEM_C_API tandem_status tandem_create_prismatic_joint(tandem_world_id world, const tandem_prismatic_joint_def* def,
                                                         tandem_joint_id* out_joint);
TANDEM_C_API tandem_status tandem_create_mouse_joint(tandem_world_id world, const tandem_mouse_joint_def* def,
                                                     tandem_joint_id* out_joint);
TANDEM_C_API tandem_status tandem_create_wheel_joint(tandem_world_id world, const tandem_wheel_joint_def* def,
                                                     tandem_joint_id* out_joint);
TANDEM_C_API tandem_status tandem_create_motor_joint(tandem_world_id world, const tandem_motor_joint_def* def,
                                                     tandem_joint_id* out_joint);

/** Destroys a joint and wakes its bodies. Refused inside a step. */
TANDEM_C_API tandem_status tandem_destroy_joint(tandem_joint_id joint);
/** True when the handle names a live joint. */
TANDEM_C_API bool tandem_joint_is_valid(tandem_joint_id joint);
/** TANDEM_OK when the handle names a live joint; otherwise says why not. */
TANDEM_C_API tandem_status tandem_joint_check(tandem_joint_id joint);
/** "joint {index 3, generation 1}" into out_text (as tandem_q32_to_text:
 * *out_length gets the length without the NUL; out_text NULL and capacity 0
 * asks for the length). */
TANDEM_C_API tandem_status tandem_joint_describe(tandem_joint_id joint, char* out_text, size_t capacity,
                                                 size_t* out_length);

/** The joint's kind (TANDEM_JOINT_*); TANDEM_JOINT_REVOLUTE for an invalid handle. */
TANDEM_C_API int32_t tandem_joint_type(tandem_joint_id joint);
/** The joint's bodies; null handles for an invalid joint. */
TANDEM_C_API tandem_body_id tandem_joint_body_a(tandem_joint_id joint);
TANDEM_C_API tandem_body_id tandem_joint_body_b(tandem_joint_id joint);
/** The joint's user data; 0 for an invalid handle. */
TANDEM_C_API uint64_t tandem_joint_user_data(tandem_joint_id joint);
/** Live joints of the world, ascending joint index (buffer rule). */
TANDEM_C_API tandem_status tandem_world_joints(tandem_world_id world, tandem_joint_id* out_joints, int32_t capacity,
                                               int32_t* out_count);
/** The body's joints, ascending joint index (buffer rule). */
TANDEM_C_API tandem_status tandem_body_joints(tandem_body_id body, tandem_joint_id* out_joints, int32_t capacity,
                                              int32_t* out_count);

/** Force (N, world frame) / torque (N·m) applied to B in the last sub-step
 * of the last step; zero for an invalid handle or before the first step. */
TANDEM_C_API tandem_vec2 tandem_joint_reaction_force(tandem_joint_id joint);
TANDEM_C_API tandem_q32 tandem_joint_reaction_torque(tandem_joint_id joint);
/** World anchors on A (mouse: the target) and B, m; zero for an invalid handle. */
TANDEM_C_API tandem_vec2 tandem_joint_world_anchor_a(tandem_joint_id joint);
TANDEM_C_API tandem_vec2 tandem_joint_world_anchor_b(tandem_joint_id joint);
/** Joint angle (revolute, weld, prismatic, wheel), rad in [−π, π]; 0 otherwise. */
TANDEM_C_API tandem_q32 tandem_joint_angle(tandem_joint_id joint);
/** Translation (prismatic, wheel) or anchor distance (distance), m; 0 otherwise. */
TANDEM_C_API tandem_q32 tandem_joint_translation(tandem_joint_id joint);

/** Motor (revolute, wheel: rad/s, N·m; prismatic, distance: m/s, N). Refused
 * for kinds without a motor and out-of-range values. Wake the bodies. */
TANDEM_C_API tandem_status tandem_joint_enable_motor(tandem_joint_id joint, bool enable);
TANDEM_C_API tandem_status tandem_joint_set_motor_speed(tandem_joint_id joint, tandem_q32 speed);
TANDEM_C_API tandem_status tandem_joint_set_max_motor_force(tandem_joint_id joint, tandem_q32 force_or_torque);
/** Limits (revolute: rad; prismatic, wheel: m; distance: min/max length, m). */
TANDEM_C_API tandem_status tandem_joint_enable_limit(tandem_joint_id joint, bool enable);
TANDEM_C_API tandem_status tandem_joint_set_limits(tandem_joint_id joint, tandem_q32 lower, tandem_q32 upper);
/** Spring (revolute, prismatic, wheel, distance): Hz and damping ratio. */
TANDEM_C_API tandem_status tandem_joint_enable_spring(tandem_joint_id joint, bool enable);
TANDEM_C_API tandem_status tandem_joint_set_spring(tandem_joint_id joint, tandem_q32 hertz, tandem_q32 damping_ratio);
/** Distance joint rest length, m. */
TANDEM_C_API tandem_status tandem_joint_set_length(tandem_joint_id joint, tandem_q32 length);
/** Mouse joint target, m, inside the world bounds. */
TANDEM_C_API tandem_status tandem_joint_set_target(tandem_joint_id joint, tandem_vec2 target);
/** Motor joint offsets (m in A's frame, rad). */
TANDEM_C_API tandem_status tandem_joint_set_offsets(tandem_joint_id joint, tandem_vec2 linear_offset,
                                                    tandem_q32 angular_offset);
/** Break thresholds (N, N·m; 0 = never). */
TANDEM_C_API tandem_status tandem_joint_set_break_thresholds(tandem_joint_id joint, tandem_q32 force,
                                                             tandem_q32 torque);

/** Joint events of the last step (broken joints, joints destroyed with a
 * body), in the C++ order (buffer rule). */
TANDEM_C_API tandem_status tandem_world_joint_events(tandem_world_id world, tandem_joint_event* out_events,
                                                     int32_t capacity, int32_t* out_count);

#ifdef __cplusplus
}  /* extern "C" */
#endif

#endif /* TANDEM_C_JOINT_H */
