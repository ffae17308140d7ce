// joint_state.h — internal: joint records (World::joints) and the step
// stages that solve them (joint.cpp, joint_solver.cpp). Not installed; the
// public joint API (definitions, handles, getters, setters, events) is joint.h.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "physics/contact_solver.h"
#include "physics/id_pool.h"
#include "physics/joint.h"

namespace tandem {

struct World;
struct StepContext;

/// A joint record. Settings and accumulated impulses are state (snapshots);
/// the `step_*` fields are per-step solver scratch.
struct Joint {
  JointType type = JointType::revolute;
  int32_t body_a = 0;              ///< body index
  int32_t body_b = 0;
  Vec2 local_anchor_a;             ///< A's frame, from A's origin, m
  Vec2 local_anchor_b;
  Vec2 local_axis_a;               ///< unit (prismatic, wheel)
  Q32 reference_angle;             ///< rad
  bool collide_connected = false;
  bool enable_spring = false;
  bool enable_limit = false;
  bool enable_motor = false;
  Q32 break_force;                 ///< N, 0 never
  Q32 break_torque;                ///< N·m, 0 never
  uint64_t user_data = 0;
  Q32 hertz;                       ///< spring, or weld linear; Hz
  Q32 damping_ratio;
  Q32 angular_hertz;               ///< weld angular; Hz
  Q32 angular_damping_ratio;
  Q32 length;                      ///< distance rest length, m
  Q32 lower;                       ///< rad or m (distance: min length)
  Q32 upper;                       ///< rad or m (distance: max length)
  Q32 motor_speed;                 ///< rad/s or m/s
  Q32 max_motor_force;             ///< N or N·m
  Vec2 target;                     ///< mouse, m; motor joint: linear offset
  Q32 angular_offset;              ///< motor joint, rad
  Q32 max_force;                   ///< mouse, motor joint; N
  Q32 max_torque;                  ///< motor joint; N·m
  Q32 correction_factor;           ///< motor joint
  // Accumulated impulses (warm starting), N·s or N·m·s.
  Vec2 linear_impulse;             ///< point constraint; prismatic/wheel: x = perpendicular
  Q32 angular_impulse;
  Q32 axial_impulse;               ///< rigid distance
  Q32 spring_impulse;
  Q32 motor_impulse;
  Q32 lower_impulse;
  Q32 upper_impulse;
  Vec2 reaction_force;             ///< N, last step
  Q32 reaction_torque;             ///< N·m, last step
  // Per-step scratch (not state).
  int32_t step_solver_a = -1;
  int32_t step_solver_b = -1;
  bool step_active = false;
  bool step_broken = false;
  Q32 step_inv_mass_a, step_inv_inertia_a, step_inv_mass_b, step_inv_inertia_b;
  Vec2 step_center_a, step_center_b;  ///< pose of a body that is not simulated
  Rot step_rotation_a, step_rotation_b;
  Vec2 step_local_a, step_local_b;    ///< anchors from each centre of mass, body frame, m
  Softness step_soft;                 ///< rigid parts
  Softness step_spring;               ///< spring / weld linear / mouse
  Softness step_angular_spring;       ///< weld angular
};

/// The world's joints (their slots are World::joint_pool).
struct JointWorld {
  std::vector<Joint> joints;                ///< by joint index
  std::vector<uint64_t> no_collide_keys;    ///< (low body << 32 | high body) of joints without collide_connected, sorted
  std::vector<JointEvent> events;           ///< reported by the last step
  std::vector<JointEvent> pending;          ///< destroyed with bodies since the last step
};

/// The handle of the live joint at `index`.
JointId make_joint_id(const World& world, int32_t index);
/// Rebuilds JointWorld::no_collide_keys from the live joints (after create,
/// destroy, restore).
void rebuild_joint_filter(World* world);
/// True when a live joint without collide_connected joins the two bodies.
bool joint_blocks_collision(const World& world, int32_t body_a, int32_t body_b);
/// destroy_body: destroys every joint of the body (ascending joint index),
/// waking the other bodies and queueing destroyed_with_body events.
void destroy_body_joints(World* world, int32_t body_index);
/// Frees a joint slot (no checks, no events).
void free_joint(World* world, int32_t index);

/// Step stage before prepare_bodies: wakes sleeping bodies joined to awake
/// moving ones.
void stage_wake_joined(World* world, StepContext* context);
/// Prepares the joints of the step (after prepare_contacts).
void stage_prepare_joints(World* world, StepContext* context);
/// Sub-step stages, called before the contact stages of the same name.
void stage_warm_start_joints(World* world, StepContext* context);
void stage_solve_joints(World* world, StepContext* context);
void stage_relax_joints(World* world, StepContext* context);
/// After store_impulses: reaction forces, breaking (destroys broken joints and
/// records their events), and the joint event list of the step.
void stage_store_joints(World* world, StepContext* context);
/// After continuous collision: the rigid position pass of the revolute joints
/// (joint_solver.cpp), repeated, so a body that continuous collision stopped
/// short does not leave its joint partners behind.
void stage_project_joints(World* world, StepContext* context);

/// Helpers shared by joint.cpp (creation, destruction) and joint_api.cpp
/// (queries, setters). Messages read "function: Def.field value unit ...".
namespace joint_detail {
/// The joint record at a live index.
Joint& joint_at(World* world, int32_t index);
/// Exact decimal text of a value, for messages.
std::string q(Q32 v);
/// True when lo ≤ value ≤ hi; otherwise writes "function: def_name.field value
/// unit is outside [lo, hi] unit" to *out.
bool check_range(const char* function, const char* def_name, const char* field, Q32 value, Q32 lo, Q32 hi,
                 const char* unit, Status* out);
/// True when both components lie within ±limit; otherwise writes the field and range.
bool check_vec(const char* function, const char* def_name, const char* field, Vec2 v, Q32 limit, const char* unit,
               Status* out);
/// True when lo ≤ hi; otherwise names both fields.
bool check_order(const char* function, const char* def_name, const char* lo_name, Q32 lo, const char* hi_name, Q32 hi,
                 Status* out);
/// check_range over [−π, π] rad.
bool check_angle(const char* function, const char* def_name, const char* field, Q32 angle, Status* s);
/// Resolves a joint handle (refusing null, stale, foreign and, when
/// `mutating`, locked worlds) to its world and index.
Status resolve_joint(JointId id, const char* function, bool mutating, World** out_world, int32_t* out_index);
}  // namespace joint_detail

}  // namespace tandem
