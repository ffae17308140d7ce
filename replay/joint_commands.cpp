// joint_commands.cpp — the joint commands of replay/commands.h: create and
// destroy a joint, set its motor speed, target, length and limits. Their
// encoding is listed in commands.h; applying goes through the public joint
// API (physics/joint.h), so a refused command changes nothing and its
// Status names the field.
#include "replay/commands.h"

namespace tandem {

namespace {

void write_joint_ref(ByteWriter& w, JointRef r) {
  w.u32(r.index);
  w.u32(r.generation);
}

JointRef read_joint_ref(ByteReader& r) {
  JointRef j;
  j.index = r.u32("joint.index");
  j.generation = r.u32("joint.generation");
  return j;
}

JointBaseDef base_of(WorldId world, const JointSpec& s) {
  JointBaseDef b;
  b.body_a = body_id(world, s.body_a);
  b.body_b = body_id(world, s.body_b);
  b.local_anchor_a = s.local_anchor_a;
  b.local_anchor_b = s.local_anchor_b;
  b.collide_connected = s.collide_connected;
  b.break_force = s.break_force;
  b.break_torque = s.break_torque;
  b.user_data = s.user_data;
  return b;
}

Status create_from_spec(WorldId world, const JointSpec& s) {
  switch (s.type) {
    case JointType::revolute: {
      RevoluteJointDef d = default_revolute_joint_def();
      d.base = base_of(world, s);
      d.reference_angle = s.reference_angle;
      d.enable_limit = s.enable_limit;
      d.lower_angle = s.lower;
      d.upper_angle = s.upper;
      d.enable_motor = s.enable_motor;
      d.motor_speed = s.motor_speed;
      d.max_motor_torque = s.motor_force;
      d.enable_spring = s.enable_spring;
      d.hertz = s.hertz;
      d.damping_ratio = s.damping_ratio;
      return create_revolute_joint(world, d).status;
    }
    case JointType::distance: {
      DistanceJointDef d = default_distance_joint_def();
      d.base = base_of(world, s);
      d.length = s.length;
      d.enable_spring = s.enable_spring;
      d.hertz = s.hertz;
      d.damping_ratio = s.damping_ratio;
      d.enable_limit = s.enable_limit;
      d.min_length = s.lower;
      d.max_length = s.upper;
      d.enable_motor = s.enable_motor;
      d.motor_speed = s.motor_speed;
      d.max_motor_force = s.motor_force;
      return create_distance_joint(world, d).status;
    }
    case JointType::weld: {
      WeldJointDef d = default_weld_joint_def();
      d.base = base_of(world, s);
      d.reference_angle = s.reference_angle;
      d.linear_hertz = s.hertz;
      d.linear_damping_ratio = s.damping_ratio;
      d.angular_hertz = s.angular_hertz;
      d.angular_damping_ratio = s.angular_damping_ratio;
      return create_weld_joint(world, d).status;
    }
    case JointType::prismatic: {
      PrismaticJointDef d = default_prismatic_joint_def();
      d.base = base_of(world, s);
      d.local_axis_a = s.local_axis;
      d.reference_angle = s.reference_angle;
      d.enable_limit = s.enable_limit;
      d.lower_translation = s.lower;
      d.upper_translation = s.upper;
      d.enable_motor = s.enable_motor;
      d.motor_speed = s.motor_speed;
      d.max_motor_force = s.motor_force;
      d.enable_spring = s.enable_spring;
      d.hertz = s.hertz;
      d.damping_ratio = s.damping_ratio;
      return create_prismatic_joint(world, d).status;
    }
    case JointType::mouse: {
      MouseJointDef d = default_mouse_joint_def();
      d.base = base_of(world, s);
      d.target = s.target;
      d.hertz = s.hertz;
      d.damping_ratio = s.damping_ratio;
      d.max_force = s.max_force;
      return create_mouse_joint(world, d).status;
    }
    case JointType::wheel: {
      WheelJointDef d = default_wheel_joint_def();
      d.base = base_of(world, s);
      d.local_axis_a = s.local_axis;
      d.enable_spring = s.enable_spring;
      d.hertz = s.hertz;
      d.damping_ratio = s.damping_ratio;
      d.enable_limit = s.enable_limit;
      d.lower_translation = s.lower;
      d.upper_translation = s.upper;
      d.enable_motor = s.enable_motor;
      d.motor_speed = s.motor_speed;
      d.max_motor_torque = s.motor_force;
      return create_wheel_joint(world, d).status;
    }
    case JointType::motor: {
      MotorJointDef d = default_motor_joint_def();
      d.base = base_of(world, s);
      d.linear_offset = s.target;
      d.angular_offset = s.angular_offset;
      d.max_force = s.max_force;
      d.max_torque = s.max_torque;
      d.correction_factor = s.correction_factor;
      return create_motor_joint(world, d).status;
    }
  }
  return Status{StatusCode::invalid_argument, "create_joint: unknown joint type"};
}

void write_body_ref(ByteWriter& w, BodyRef r) {
  w.u32(r.index);
  w.u32(r.generation);
}

BodyRef read_body_ref(ByteReader& r, const char* index_name, const char* generation_name) {
  BodyRef b;
  b.index = r.u32(index_name);
  b.generation = r.u32(generation_name);
  return b;
}

}  // namespace

Command make_create_joint(const JointSpec& spec) {
  Command c;
  c.type = CommandType::create_joint;
  c.joint_spec = spec;
  return c;
}

Command make_destroy_joint(JointRef joint) {
  Command c;
  c.type = CommandType::destroy_joint;
  c.joint = joint;
  return c;
}

Command make_set_joint_motor_speed(JointRef joint, Q32 speed) {
  Command c;
  c.type = CommandType::set_joint_motor_speed;
  c.joint = joint;
  c.scalar = speed;
  return c;
}

Command make_set_joint_target(JointRef joint, Vec2 target) {
  Command c;
  c.type = CommandType::set_joint_target;
  c.joint = joint;
  c.vector = target;
  return c;
}

Command make_set_joint_length(JointRef joint, Q32 length) {
  Command c;
  c.type = CommandType::set_joint_length;
  c.joint = joint;
  c.scalar = length;
  return c;
}

Command make_set_joint_limits(JointRef joint, Q32 lower, Q32 upper) {
  Command c;
  c.type = CommandType::set_joint_limits;
  c.joint = joint;
  c.scalar = lower;
  c.scalar2 = upper;
  return c;
}

Status apply_joint_command(WorldId world, const Command& c) {
  if (c.type == CommandType::create_joint) return create_from_spec(world, c.joint_spec);
  if (c.joint.generation == 0 || c.joint.index == UINT32_MAX) {
    return Status{StatusCode::invalid_handle, "not a joint handle (generation 0 or index out of range)"};
  }
  const JointId j = joint_id(world, c.joint);
  switch (c.type) {
    case CommandType::destroy_joint: return destroy_joint(j);
    case CommandType::set_joint_motor_speed: return joint_set_motor_speed(j, c.scalar);
    case CommandType::set_joint_target: return joint_set_target(j, c.vector);
    case CommandType::set_joint_length: return joint_set_length(j, c.scalar);
    case CommandType::set_joint_limits: return joint_set_limits(j, c.scalar, c.scalar2);
    default: break;
  }
  return Status{StatusCode::invalid_argument, "not a joint command"};
}

void encode_joint_command(ByteWriter& w, const Command& c) {
  if (c.type == CommandType::create_joint) {
    const JointSpec& s = c.joint_spec;
    w.u8(static_cast<uint8_t>(static_cast<int32_t>(s.type)));
    write_body_ref(w, s.body_a);
    write_body_ref(w, s.body_b);
    w.vec2(s.local_anchor_a);
    w.vec2(s.local_anchor_b);
    w.boolean(s.collide_connected);
    w.q32(s.break_force);
    w.q32(s.break_torque);
    w.u64(s.user_data);
    w.vec2(s.local_axis);
    w.q32(s.reference_angle);
    w.boolean(s.enable_spring);
    w.boolean(s.enable_limit);
    w.boolean(s.enable_motor);
    w.q32(s.hertz);
    w.q32(s.damping_ratio);
    w.q32(s.angular_hertz);
    w.q32(s.angular_damping_ratio);
    w.q32(s.length);
    w.q32(s.lower);
    w.q32(s.upper);
    w.q32(s.motor_speed);
    w.q32(s.motor_force);
    w.vec2(s.target);
    w.q32(s.angular_offset);
    w.q32(s.max_force);
    w.q32(s.max_torque);
    w.q32(s.correction_factor);
    return;
  }
  write_joint_ref(w, c.joint);
  switch (c.type) {
    case CommandType::set_joint_motor_speed:
    case CommandType::set_joint_length: w.q32(c.scalar); break;
    case CommandType::set_joint_target: w.vec2(c.vector); break;
    case CommandType::set_joint_limits:
      w.q32(c.scalar);
      w.q32(c.scalar2);
      break;
    default: break;
  }
}

bool decode_joint_command(ByteReader& r, Command* out) {
  if (out->type == CommandType::create_joint) {
    JointSpec& s = out->joint_spec;
    const size_t at = r.offset();
    const uint8_t type = r.u8("joint type");
    if (!r.ok()) return false;
    if (type > static_cast<uint8_t>(JointType::motor)) {
      r.fail_at(at, "expected " + r.describe_what("joint type") + " 0..6, got " + std::to_string(type));
      return false;
    }
    s.type = static_cast<JointType>(type);
    s.body_a = read_body_ref(r, "body_a.index", "body_a.generation");
    s.body_b = read_body_ref(r, "body_b.index", "body_b.generation");
    s.local_anchor_a = r.vec2("local_anchor_a.x", "local_anchor_a.y");
    s.local_anchor_b = r.vec2("local_anchor_b.x", "local_anchor_b.y");
    s.collide_connected = r.boolean("collide_connected");
    s.break_force = r.q32("break_force");
    s.break_torque = r.q32("break_torque");
    s.user_data = r.u64("user_data");
    s.local_axis = r.vec2("local_axis.x", "local_axis.y");
    s.reference_angle = r.q32("reference_angle");
    s.enable_spring = r.boolean("enable_spring");
    s.enable_limit = r.boolean("enable_limit");
    s.enable_motor = r.boolean("enable_motor");
    s.hertz = r.q32("hertz");
    s.damping_ratio = r.q32("damping_ratio");
    s.angular_hertz = r.q32("angular_hertz");
    s.angular_damping_ratio = r.q32("angular_damping_ratio");
    s.length = r.q32("length");
    s.lower = r.q32("lower");
    s.upper = r.q32("upper");
    s.motor_speed = r.q32("motor_speed");
    s.motor_force = r.q32("motor_force");
    s.target = r.vec2("target.x", "target.y");
    s.angular_offset = r.q32("angular_offset");
    s.max_force = r.q32("max_force");
    s.max_torque = r.q32("max_torque");
    s.correction_factor = r.q32("correction_factor");
    return r.ok();
  }
  out->joint = read_joint_ref(r);
  switch (out->type) {
    case CommandType::set_joint_motor_speed: out->scalar = r.q32("motor_speed"); break;
    case CommandType::set_joint_length: out->scalar = r.q32("length"); break;
    case CommandType::set_joint_target: out->vector = r.vec2("target.x", "target.y"); break;
    case CommandType::set_joint_limits:
      out->scalar = r.q32("lower");
      out->scalar2 = r.q32("upper");
      break;
    default: break;
  }
  return r.ok();
}

bool equal_joint_command(const Command& a, const Command& b) {
  switch (a.type) {
    case CommandType::create_joint: return a.joint_spec == b.joint_spec;
    case CommandType::destroy_joint: return a.joint == b.joint;
    case CommandType::set_joint_motor_speed:
    case CommandType::set_joint_length: return a.joint == b.joint && a.scalar == b.scalar;
    case CommandType::set_joint_target: return a.joint == b.joint && a.vector == b.vector;
    case CommandType::set_joint_limits: return a.joint == b.joint && a.scalar == b.scalar && a.scalar2 == b.scalar2;
    default: return false;
  }
}

}  // namespace tandem
