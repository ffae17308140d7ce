// joint.h — joints: revolute, distance (and rope), weld, prismatic, mouse
// (target), wheel and motor joints. Public API (included by tandem.h) plus the
// world's internal joint records.
//
// A joint ties two bodies, A and B. Anchors are given in each body's own frame
// (m, from the body origin); angles are the relative angle of B to A minus the
// joint's reference angle (radians, counter-clockwise positive). Joints are
// created and destroyed between steps and named by JointId handles (index +
// generation, like bodies). Every definition comes from its default_*_def()
// function (which stamps the cookie), as for bodies and shapes.
//
// SOLVER (joint_solver.cpp): the same sub-stepped soft solver as contacts —
// per step a prepare pass, then per sub-step warm start, a biased solve and a
// relax pass without bias, joints BEFORE contacts in each stage, joints in
// ascending joint index. Rigid parts are softened by the world's joint_hertz
// and joint_damping_ratio; springs use the joint's own hertz and damping
// ratio. Accumulated impulses persist across steps (warm starting). All
// arithmetic is Q32.32.
//
// REACTION: the force (N) and torque (N·m) the joint applied to body B during
// the last sub-step of the last step (impulse / sub-step). A joint with a
// non-zero break_force (break_torque) whose reaction force magnitude (torque
// magnitude) exceeds it at the end of a step is destroyed at the end of that
// step and reported once by world_joint_events().
//
// COLLISION: collide_connected = false (the default) keeps the shapes of the
// two joined bodies from forming contacts while the joint lives.
//
// SLEEP: two dynamic bodies joined by a joint are in one sleep island; waking
// one wakes the other. A joint between a sleeping body and an awake moving
// one wakes the sleeper at the next step.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "fixed/fixed.h"
#include "fixed/vec2.h"
#include "physics/ids.h"
#include "physics/limits.h"
#include "physics/tandem.h"

namespace tandem {

/// The kinds of joint.
enum class JointType : int32_t {
  revolute = 0,   ///< a shared point; relative rotation free (limits, motor, spring)
  distance = 1,   ///< the anchors kept at a length (rigid, spring, or a rope between min and max)
  weld = 2,       ///< relative pose fixed (rigid or soft)
  prismatic = 3,  ///< slides along an axis of A; relative rotation fixed (limits, motor, spring)
  mouse = 4,      ///< pulls an anchor of B to a world target (soft, force-limited); A is ignored
  wheel = 5,      ///< slides along an axis of A with a spring (suspension); rotation free (motor)
  motor = 6,      ///< drives B's pose relative to A towards offsets with limited force and torque
};

/// Fields shared by every joint definition.
struct JointBaseDef {
  BodyId body_a;                 ///< the first body; must be live and of the world
  BodyId body_b;                 ///< the second body; live, of the world, not body_a; not both static
  Vec2 local_anchor_a;           ///< anchor in A's frame, m; default 0; |x|, |y| ≤ k_max_shape_size
  Vec2 local_anchor_b;           ///< anchor in B's frame, m; default 0; |x|, |y| ≤ k_max_shape_size
  bool collide_connected = false;  ///< let the two bodies' shapes collide; default false
  Q32 break_force;               ///< N; 0 (default) never breaks; [0, k_max_joint_force]
  Q32 break_torque;              ///< N·m; 0 (default) never breaks; [0, k_max_joint_torque]
  uint64_t user_data = 0;        ///< any integer; default 0
};

/// Revolute joint: the anchors coincide; B turns freely about them.
struct RevoluteJointDef {
  JointBaseDef base;
  Q32 reference_angle;        ///< angle of B relative to A at which the joint angle is 0, rad; default 0; [−π, π]
  bool enable_limit = false;  ///< default false
  Q32 lower_angle;            ///< rad; default 0; [−π, π], ≤ upper_angle
  Q32 upper_angle;            ///< rad; default 0; [−π, π]
  bool enable_motor = false;  ///< default false
  Q32 motor_speed;            ///< target relative angular speed, rad/s; default 0; |·| ≤ k_max_angular_speed
  Q32 max_motor_torque;       ///< N·m; default 0; [0, k_max_joint_torque]
  bool enable_spring = false; ///< rotational spring towards angle 0; default false
  Q32 hertz;                  ///< spring stiffness, Hz; default 0 (no spring force); [0, k_max_joint_hertz]
  Q32 damping_ratio;          ///< spring damping, dimensionless; default 0; [0, k_max_joint_damping_ratio]
  int32_t internal_cookie = 0;  ///< set by default_revolute_joint_def(); do not touch
};

/// Distance joint: keeps |anchor_b − anchor_a| at `length` (rigid), or — with
/// enable_spring — pulls towards it with a spring, and with enable_limit keeps
/// it within [min_length, max_length]. A rope: enable_spring with hertz 0,
/// enable_limit, min_length 0, max_length = the rope length (it only pulls).
struct DistanceJointDef {
  JointBaseDef base;
  Q32 length;                 ///< rest length, m; default 1; [k_min_joint_length, k_max_joint_length]
  bool enable_spring = false; ///< soft (spring) instead of rigid; default false
  Q32 hertz;                  ///< Hz; default 0; [0, k_max_joint_hertz]
  Q32 damping_ratio;          ///< dimensionless; default 0; [0, k_max_joint_damping_ratio]
  bool enable_limit = false;  ///< keep the length within [min_length, max_length]; default false
  Q32 min_length;             ///< m; default 0; [0, max_length]
  Q32 max_length;             ///< m; default k_max_joint_length; [k_min_joint_length, k_max_joint_length]
  bool enable_motor = false;  ///< default false
  Q32 motor_speed;            ///< target lengthening speed, m/s; default 0; |·| ≤ k_max_linear_speed
  Q32 max_motor_force;        ///< N; default 0; [0, k_max_joint_force]
  int32_t internal_cookie = 0;
};

/// Weld joint: B's pose relative to A is fixed (rigid with hertz 0, else a
/// spring of that stiffness).
struct WeldJointDef {
  JointBaseDef base;
  Q32 reference_angle;        ///< rad; default 0; [−π, π]
  Q32 linear_hertz;           ///< Hz; default 0 (rigid); [0, k_max_joint_hertz]
  Q32 linear_damping_ratio;   ///< dimensionless; default 0; [0, k_max_joint_damping_ratio]
  Q32 angular_hertz;          ///< Hz; default 0 (rigid); [0, k_max_joint_hertz]
  Q32 angular_damping_ratio;  ///< dimensionless; default 0; [0, k_max_joint_damping_ratio]
  int32_t internal_cookie = 0;
};

/// Prismatic joint: B slides along local_axis_a (in A's frame) with the
/// relative rotation fixed; translation = (anchor_b − anchor_a)·axis, m.
struct PrismaticJointDef {
  JointBaseDef base;
  Vec2 local_axis_a;          ///< unit axis in A's frame; default (1, 0); |axis| within 1e-6 of 1
  Q32 reference_angle;        ///< rad; default 0; [−π, π]
  bool enable_limit = false;  ///< default false
  Q32 lower_translation;      ///< m; default 0; |·| ≤ k_max_joint_length, ≤ upper_translation
  Q32 upper_translation;      ///< m; default 0
  bool enable_motor = false;  ///< default false
  Q32 motor_speed;            ///< m/s; default 0; |·| ≤ k_max_linear_speed
  Q32 max_motor_force;        ///< N; default 0; [0, k_max_joint_force]
  bool enable_spring = false; ///< spring towards translation 0; default false
  Q32 hertz;                  ///< Hz; default 0; [0, k_max_joint_hertz]
  Q32 damping_ratio;          ///< dimensionless; default 0; [0, k_max_joint_damping_ratio]
  int32_t internal_cookie = 0;
};

/// Mouse (target) joint: pulls B's anchor (base.local_anchor_b) towards a
/// world target with a spring, never harder than max_force. body_a is only
/// the joint's other end for bookkeeping (usually a static ground body).
struct MouseJointDef {
  JointBaseDef base;
  Vec2 target;                ///< world point, m; default 0; inside the world bounds
  Q32 hertz;                  ///< Hz; default 5; (0, k_max_joint_hertz]
  Q32 damping_ratio;          ///< dimensionless; default 0.7; [0, k_max_joint_damping_ratio]
  Q32 max_force;              ///< N; default 1000; [0, k_max_joint_force]
  int32_t internal_cookie = 0;
};

/// Wheel joint: B slides along local_axis_a with a suspension spring and
/// turns freely (motor optional).
struct WheelJointDef {
  JointBaseDef base;
  Vec2 local_axis_a;          ///< unit axis in A's frame; default (0, 1); |axis| within 1e-6 of 1
  bool enable_spring = true;  ///< default true
  Q32 hertz;                  ///< Hz; default 1; [0, k_max_joint_hertz]
  Q32 damping_ratio;          ///< dimensionless; default 0.7; [0, k_max_joint_damping_ratio]
  bool enable_limit = false;  ///< default false
  Q32 lower_translation;      ///< m; default 0; |·| ≤ k_max_joint_length, ≤ upper_translation
  Q32 upper_translation;      ///< m; default 0
  bool enable_motor = false;  ///< default false
  Q32 motor_speed;            ///< rad/s; default 0; |·| ≤ k_max_angular_speed
  Q32 max_motor_torque;       ///< N·m; default 0; [0, k_max_joint_torque]
  int32_t internal_cookie = 0;
};

/// Motor joint: drives B's pose relative to A towards (linear_offset in A's
/// frame, angular_offset) with at most max_force and max_torque. The anchors
/// of base are ignored (the bodies' origins are used).
struct MotorJointDef {
  JointBaseDef base;
  Vec2 linear_offset;         ///< B's origin in A's frame, m; default 0; |x|, |y| ≤ k_max_shape_size
  Q32 angular_offset;         ///< rad; default 0; [−π, π]
  Q32 max_force;              ///< N; default 1; [0, k_max_joint_force]
  Q32 max_torque;             ///< N·m; default 1; [0, k_max_joint_torque]
  Q32 correction_factor;      ///< fraction of the pose error corrected per sub-step, dimensionless; default 0.3;
                              ///< [0, 1]
  int32_t internal_cookie = 0;
};

/// Definitions with every default filled in (see each struct).
RevoluteJointDef default_revolute_joint_def();
DistanceJointDef default_distance_joint_def();
WeldJointDef default_weld_joint_def();
PrismaticJointDef default_prismatic_joint_def();
MouseJointDef default_mouse_joint_def();
WheelJointDef default_wheel_joint_def();
MotorJointDef default_motor_joint_def();

/// Creates a joint in `world`. Refuses (changing nothing; the message names
/// the definition field and its allowed range): a definition without the
/// cookie, a body that is null, destroyed or of another world, body_a ==
/// body_b, two static bodies, any value outside the ranges stated on the
/// definition. Wakes both bodies. Refused inside world_step().
Result<JointId> create_revolute_joint(WorldId world, const RevoluteJointDef& def);
Result<JointId> create_distance_joint(WorldId world, const DistanceJointDef& def);
Result<JointId> create_weld_joint(WorldId world, const WeldJointDef& def);
Result<JointId> create_prismatic_joint(WorldId world, const PrismaticJointDef& def);
Result<JointId> create_mouse_joint(WorldId world, const MouseJointDef& def);
Result<JointId> create_wheel_joint(WorldId world, const WheelJointDef& def);
Result<JointId> create_motor_joint(WorldId world, const MotorJointDef& def);

/// Destroys a joint and wakes its bodies. Refused inside world_step().
Status destroy_joint(JointId joint);
/// True when the handle names a live joint.
bool joint_is_valid(JointId joint);
/// Ok when the handle names a live joint; otherwise says why not.
Status joint_check(JointId joint);
/// "joint {index 3, generation 1}" ("null joint" for null).
std::string describe(JointId id);

/// The joint's kind; revolute for an invalid handle.
JointType joint_type(JointId joint);
/// The joint's bodies; null for an invalid handle.
BodyId joint_body_a(JointId joint);
BodyId joint_body_b(JointId joint);
/// The joint's user data; 0 for an invalid handle.
uint64_t joint_user_data(JointId joint);
/// Writes up to `capacity` handles of live joints of the world, ascending
/// joint index; returns the number of live joints (0 for an invalid world).
int32_t world_joints(WorldId world, JointId* out_ids, int32_t capacity);
/// Writes up to `capacity` handles of the body's joints, ascending joint
/// index; returns their number (0 for an invalid body).
int32_t body_joints(BodyId body, JointId* out_ids, int32_t capacity);

/// Force applied to B during the last sub-step of the last step, N (world
/// frame); zero for an invalid handle or before the first step.
Vec2 joint_reaction_force(JointId joint);
/// Torque applied to B during the last sub-step of the last step, N·m.
Q32 joint_reaction_torque(JointId joint);

/// World position of the joint's anchor on A (mouse joint: the target) and
/// on B, m; zero for an invalid handle.
Vec2 joint_world_anchor_a(JointId joint);
Vec2 joint_world_anchor_b(JointId joint);

/// Current joint angle (relative angle of B to A minus the reference angle,
/// rad, in [−π, π]) for revolute, weld, prismatic and wheel joints; 0
/// otherwise.
Q32 joint_angle(JointId joint);
/// Current translation along the axis for prismatic and wheel joints, m;
/// the current anchor distance for distance joints; 0 otherwise.
Q32 joint_translation(JointId joint);

/// Motor settings (revolute: rad/s and N·m; prismatic and distance: m/s and
/// N; wheel: rad/s and N·m). Refused for kinds without a motor and for
/// values outside the definition's ranges. Wake the bodies.
Status joint_enable_motor(JointId joint, bool enable);
Status joint_set_motor_speed(JointId joint, Q32 speed);
Status joint_set_max_motor_force(JointId joint, Q32 force_or_torque);
/// Limits (revolute: rad; prismatic and wheel: m; distance: min and max
/// length, m). Refused for kinds without limits and lower > upper.
Status joint_enable_limit(JointId joint, bool enable);
Status joint_set_limits(JointId joint, Q32 lower, Q32 upper);
/// Spring (revolute, prismatic, wheel, distance): Hz and damping ratio.
Status joint_enable_spring(JointId joint, bool enable);
Status joint_set_spring(JointId joint, Q32 hertz, Q32 damping_ratio);
/// Distance joint rest length, m, [k_min_joint_length, k_max_joint_length]
/// (a rope's max_length follows when the limit is enabled and the new length
/// exceeds it: use joint_set_limits for a rope).
Status joint_set_length(JointId joint, Q32 length);
/// Mouse joint target, m, inside the world bounds.
Status joint_set_target(JointId joint, Vec2 target);
/// Motor joint offsets (m in A's frame, rad).
Status joint_set_offsets(JointId joint, Vec2 linear_offset, Q32 angular_offset);
/// Break thresholds (N, N·m; 0 = never).
Status joint_set_break_thresholds(JointId joint, Q32 force, Q32 torque);

/// Why a joint event was raised.
enum class JointEventKind : int32_t {
  broke = 0,               ///< the reaction exceeded a break threshold; the joint was destroyed
  destroyed_with_body = 1, ///< destroy_body() destroyed the joint with one of its bodies (reported at the next step)
};

/// A joint that is gone.
struct JointEvent {
  JointId joint;        ///< the (now stale) handle
  BodyId body_a;        ///< may be stale
  BodyId body_b;        ///< may be stale
  JointEventKind kind = JointEventKind::broke;
  Vec2 force;           ///< the reaction that broke it, N (0 for destroyed_with_body)
  Q32 torque;           ///< N·m
  uint64_t user_data = 0;
};

/// The joint events of the last step, by (kind order of occurrence: bodies
/// destroyed before the step first, then breaks), each group in ascending
/// joint index. Valid until the next step or world change, as events.h.
Result<std::span<const JointEvent>> world_joint_events(WorldId world);

}  // namespace tandem
