// defs.cpp — every default in one place (see defs.h).
#include "physics/defs.h"

namespace tandem {

using namespace tandem::literals;

WorldDef default_world_def() {
  WorldDef def{};
  def.gravity = {0_q32, -10_q32};
  def.sub_step_count = 4;
  def.contact_hertz = 30_q32;
  def.contact_damping_ratio = 10_q32;
  def.max_contact_push_speed = 3_q32;
  def.joint_hertz = 60_q32;
  def.joint_damping_ratio = 2_q32;
  def.restitution_threshold = 1_q32;
  def.hit_event_threshold = 1_q32;
  // 400 m/s: 6.7 m per step at 60 Hz, faster than anything a game throws,
  // and well inside k_max_linear_speed.
  def.max_linear_speed = 400_q32;
  def.bounds = {{-k_max_world_coordinate, -k_max_world_coordinate}, {k_max_world_coordinate, k_max_world_coordinate}};
  def.enable_sleep = true;
  def.enable_continuous = true;
  def.broad_phase = BroadPhaseKind::naive;
  def.user_data = 0;
  def.worker_count = 1;
  def.enqueue_task = nullptr;
  def.finish_task = nullptr;
  def.user_task_context = nullptr;
  def.internal_cookie = k_def_cookie;
  return def;
}

BodyDef default_body_def() {
  BodyDef def{};
  def.type = BodyType::static_body;
  def.position = {};
  def.rotation = rot_identity();
  def.linear_velocity = {};
  def.angular_velocity = 0_q32;
  def.linear_damping = 0_q32;
  def.angular_damping = 0_q32;
  def.gravity_scale = 1_q32;
  def.user_data = 0;
  def.enable_sleep = true;
  def.is_awake = true;
  def.fixed_rotation = false;
  def.is_bullet = false;
  def.is_enabled = true;
  def.internal_cookie = k_def_cookie;
  return def;
}

ShapeDef default_shape_def() {
  ShapeDef def{};
  def.friction = 0.6_q32;
  def.restitution = 0_q32;
  def.density = 1_q32;
  def.filter = Filter{};
  def.user_data = 0;
  def.is_sensor = false;
  def.enable_hit_events = false;
  def.internal_cookie = k_def_cookie;
  return def;
}

}  // namespace tandem
