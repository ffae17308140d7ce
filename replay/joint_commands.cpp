// joint_commands.cpp — the joint commands of replay/commands.h: create and
// destroy a joint and every joint setter of physics/joint.h (motor speed,
// enable and max force; target; length; limits and their enable; spring and
// its enable; motor joint offsets; break thresholds). Their encoding is
// listed in commands.h and written down once, in visit_joint_fields(): the
// encoder, the decoder and equality all walk that one field list, so a field
// added there is written, read and compared in the same place and order.
// Applying goes through the public joint API, so a refused command changes
// nothing and its Status names the field.
#include "replay/commands.h"

namespace tandem {

namespace {

/// The fields of a joint command after its type byte, in encoding order, for
/// a visitor V with flag, q32, u64, vec2 and ref members (Writer, Reader
/// below). C is Command or const Command. create_joint's JointSpec type byte
/// is handled by the caller (the decoder checks its range first).
template <typename V, typename C>
void visit_joint_fields(V& v, C& c) {
  if (c.type == CommandType::create_joint) {
    auto& s = c.joint_spec;
    v.ref(s.body_a.index, s.body_a.generation, "body_a.index", "body_a.generation");
    v.ref(s.body_b.index, s.body_b.generation, "body_b.index", "body_b.generation");
    v.vec2(s.local_anchor_a, "local_anchor_a.x", "local_anchor_a.y");
    v.vec2(s.local_anchor_b, "local_anchor_b.x", "local_anchor_b.y");
    v.flag(s.collide_connected, "collide_connected");
    v.q32(s.break_force, "break_force");
    v.q32(s.break_torque, "break_torque");
    v.u64(s.user_data, "user_data");
    v.vec2(s.local_axis, "local_axis.x", "local_axis.y");
    v.q32(s.reference_angle, "reference_angle");
    v.flag(s.enable_spring, "enable_spring");
    v.flag(s.enable_limit, "enable_limit");
    v.flag(s.enable_motor, "enable_motor");
    v.q32(s.hertz, "hertz");
    v.q32(s.damping_ratio, "damping_ratio");
    v.q32(s.angular_hertz, "angular_hertz");
    v.q32(s.angular_damping_ratio, "angular_damping_ratio");
    v.q32(s.length, "length");
    v.q32(s.lower, "lower");
    v.q32(s.upper, "upper");
    v.q32(s.motor_speed, "motor_speed");
    v.q32(s.motor_force, "motor_force");
    v.vec2(s.target, "target.x", "target.y");
    v.q32(s.angular_offset, "angular_offset");
    v.q32(s.max_force, "max_force");
    v.q32(s.max_torque, "max_torque");
    v.q32(s.correction_factor, "correction_factor");
    return;
  }
  v.ref(c.joint.index, c.joint.generation, "joint.index", "joint.generation");
  switch (c.type) {
    case CommandType::set_joint_motor_speed: v.q32(c.scalar, "motor_speed"); break;
    case CommandType::set_joint_length: v.q32(c.scalar, "length"); break;
    case CommandType::set_joint_target: v.vec2(c.vector, "target.x", "target.y"); break;
    case CommandType::set_joint_limits:
      v.q32(c.scalar, "lower");
      v.q32(c.scalar2, "upper");
      break;
    case CommandType::enable_joint_motor: v.flag(c.flag, "enable_motor"); break;
    case CommandType::set_joint_max_motor_force: v.q32(c.scalar, "max_motor_force"); break;
    case CommandType::enable_joint_limit: v.flag(c.flag, "enable_limit"); break;
    case CommandType::enable_joint_spring: v.flag(c.flag, "enable_spring"); break;
    case CommandType::set_joint_spring:
      v.q32(c.scalar, "hertz");
      v.q32(c.scalar2, "damping_ratio");
      break;
    case CommandType::set_joint_offsets:
      v.vec2(c.vector, "linear_offset.x", "linear_offset.y");
      v.q32(c.scalar, "angular_offset");
      break;
    case CommandType::set_joint_break_thresholds:
      v.q32(c.scalar, "break_force");
      v.q32(c.scalar2, "break_torque");
      break;
    default: break;  // destroy_joint: the ref only
  }
}

/// Writes each field (visit_joint_fields).
struct Writer {
  ByteWriter& w;
  void flag(bool v, const char*) { w.boolean(v); }
  void q32(Q32 v, const char*) { w.q32(v); }
  void u64(uint64_t v, const char*) { w.u64(v); }
  void vec2(Vec2 v, const char*, const char*) { w.vec2(v); }
  void ref(uint32_t index, uint32_t generation, const char*, const char*) {
    w.u32(index);
    w.u32(generation);
  }
};

/// Reads each field, naming it in errors (visit_joint_fields).
struct Reader {
  ByteReader& r;
  void flag(bool& v, const char* what) { v = r.boolean(what); }
  void q32(Q32& v, const char* what) { v = r.q32(what); }
  void u64(uint64_t& v, const char* what) { v = r.u64(what); }
  void vec2(Vec2& v, const char* x, const char* y) { v = r.vec2(x, y); }
  void ref(uint32_t& index, uint32_t& generation, const char* what_index, const char* what_generation) {
    index = r.u32(what_index);
    generation = r.u32(what_generation);
  }
};

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

// The settings groups several joint kinds share, copied from the spec into a
// kind's def (the members that differ by kind are named by the caller).
template <typename D>
void copy_spring(const JointSpec& s, D* d) {
  d->enable_spring = s.enable_spring;
  d->hertz = s.hertz;
  d->damping_ratio = s.damping_ratio;
}
template <typename D>
void copy_limit(const JointSpec& s, D* d, Q32 D::*lower, Q32 D::*upper) {
  d->enable_limit = s.enable_limit;
  d->*lower = s.lower;
  d->*upper = s.upper;
}
template <typename D>
void copy_motor(const JointSpec& s, D* d, Q32 D::*max_motor) {
  d->enable_motor = s.enable_motor;
  d->motor_speed = s.motor_speed;
  d->*max_motor = s.motor_force;
}

// Each kind's own settings, from the spec (the shared groups above).
void fill(const JointSpec& s, RevoluteJointDef* d) {
  d->reference_angle = s.reference_angle;
  copy_limit(s, d, &RevoluteJointDef::lower_angle, &RevoluteJointDef::upper_angle);
  copy_motor(s, d, &RevoluteJointDef::max_motor_torque);
  copy_spring(s, d);
}
void fill(const JointSpec& s, DistanceJointDef* d) {
  d->length = s.length;
  copy_spring(s, d);
  copy_limit(s, d, &DistanceJointDef::min_length, &DistanceJointDef::max_length);
  copy_motor(s, d, &DistanceJointDef::max_motor_force);
}
void fill(const JointSpec& s, WeldJointDef* d) {
  d->reference_angle = s.reference_angle;
  d->linear_hertz = s.hertz;
  d->linear_damping_ratio = s.damping_ratio;
  d->angular_hertz = s.angular_hertz;
  d->angular_damping_ratio = s.angular_damping_ratio;
}
void fill(const JointSpec& s, PrismaticJointDef* d) {
  d->local_axis_a = s.local_axis;
  d->reference_angle = s.reference_angle;
  copy_limit(s, d, &PrismaticJointDef::lower_translation, &PrismaticJointDef::upper_translation);
  copy_motor(s, d, &PrismaticJointDef::max_motor_force);
  copy_spring(s, d);
}
void fill(const JointSpec& s, MouseJointDef* d) {
  d->target = s.target;
  d->hertz = s.hertz;
  d->damping_ratio = s.damping_ratio;
  d->max_force = s.max_force;
}
void fill(const JointSpec& s, WheelJointDef* d) {
  d->local_axis_a = s.local_axis;
  copy_spring(s, d);
  copy_limit(s, d, &WheelJointDef::lower_translation, &WheelJointDef::upper_translation);
  copy_motor(s, d, &WheelJointDef::max_motor_torque);
}
void fill(const JointSpec& s, MotorJointDef* d) {
  d->linear_offset = s.target;
  d->angular_offset = s.angular_offset;
  d->max_force = s.max_force;
  d->max_torque = s.max_torque;
  d->correction_factor = s.correction_factor;
}

/// Creates a joint of one kind: its default def, the spec's base and settings.
template <typename D>
Status create_as(WorldId world, const JointSpec& s, D d, Result<JointId> (*create)(WorldId, const D&)) {
  d.base = base_of(world, s);
  fill(s, &d);
  return create(world, d).status;
}

Status create_from_spec(WorldId world, const JointSpec& s) {
  switch (s.type) {
    case JointType::revolute: return create_as(world, s, default_revolute_joint_def(), create_revolute_joint);
    case JointType::distance: return create_as(world, s, default_distance_joint_def(), create_distance_joint);
    case JointType::weld: return create_as(world, s, default_weld_joint_def(), create_weld_joint);
    case JointType::prismatic: return create_as(world, s, default_prismatic_joint_def(), create_prismatic_joint);
    case JointType::mouse: return create_as(world, s, default_mouse_joint_def(), create_mouse_joint);
    case JointType::wheel: return create_as(world, s, default_wheel_joint_def(), create_wheel_joint);
    case JointType::motor: return create_as(world, s, default_motor_joint_def(), create_motor_joint);
  }
  return Status{StatusCode::invalid_argument, "create_joint: unknown joint type"};
}

}  // namespace

// The builders name the fields each type uses (Command is an aggregate).
// Designated initializers leave the other members at their defaults on
// purpose (g++ would warn about each of them).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
Command make_create_joint(const JointSpec& spec) {
  return Command{.type = CommandType::create_joint, .joint_spec = spec};
}

Command make_destroy_joint(JointRef joint) { return Command{.type = CommandType::destroy_joint, .joint = joint}; }

Command make_set_joint_motor_speed(JointRef joint, Q32 speed) {
  return Command{.type = CommandType::set_joint_motor_speed, .scalar = speed, .joint = joint};
}

Command make_set_joint_target(JointRef joint, Vec2 target) {
  return Command{.type = CommandType::set_joint_target, .vector = target, .joint = joint};
}

Command make_set_joint_length(JointRef joint, Q32 length) {
  return Command{.type = CommandType::set_joint_length, .scalar = length, .joint = joint};
}

Command make_set_joint_limits(JointRef joint, Q32 lower, Q32 upper) {
  return Command{.type = CommandType::set_joint_limits, .scalar = lower, .joint = joint, .scalar2 = upper};
}

Command make_enable_joint_motor(JointRef joint, bool enable) {
  return Command{.type = CommandType::enable_joint_motor, .flag = enable, .joint = joint};
}

Command make_set_joint_max_motor_force(JointRef joint, Q32 force_or_torque) {
  return Command{.type = CommandType::set_joint_max_motor_force, .scalar = force_or_torque, .joint = joint};
}

Command make_enable_joint_limit(JointRef joint, bool enable) {
  return Command{.type = CommandType::enable_joint_limit, .flag = enable, .joint = joint};
}

Command make_enable_joint_spring(JointRef joint, bool enable) {
  return Command{.type = CommandType::enable_joint_spring, .flag = enable, .joint = joint};
}

Command make_set_joint_spring(JointRef joint, Q32 hertz, Q32 damping_ratio) {
  return Command{.type = CommandType::set_joint_spring, .scalar = hertz, .joint = joint, .scalar2 = damping_ratio};
}

Command make_set_joint_offsets(JointRef joint, Vec2 linear_offset, Q32 angular_offset) {
  return Command{
      .type = CommandType::set_joint_offsets, .vector = linear_offset, .scalar = angular_offset, .joint = joint};
}

Command make_set_joint_break_thresholds(JointRef joint, Q32 force, Q32 torque) {
  return Command{.type = CommandType::set_joint_break_thresholds, .scalar = force, .joint = joint, .scalar2 = torque};
}
#pragma GCC diagnostic pop

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
    case CommandType::enable_joint_motor: return joint_enable_motor(j, c.flag);
    case CommandType::set_joint_max_motor_force: return joint_set_max_motor_force(j, c.scalar);
    case CommandType::enable_joint_limit: return joint_enable_limit(j, c.flag);
    case CommandType::enable_joint_spring: return joint_enable_spring(j, c.flag);
    case CommandType::set_joint_spring: return joint_set_spring(j, c.scalar, c.scalar2);
    case CommandType::set_joint_offsets: return joint_set_offsets(j, c.vector, c.scalar);
    case CommandType::set_joint_break_thresholds: return joint_set_break_thresholds(j, c.scalar, c.scalar2);
    default: break;
  }
  return Status{StatusCode::invalid_argument, "not a joint command"};
}

void encode_joint_command(ByteWriter& w, const Command& c) {
  if (c.type == CommandType::create_joint) w.u8(static_cast<uint8_t>(static_cast<int32_t>(c.joint_spec.type)));
  Writer writer{w};
  visit_joint_fields(writer, c);
}

bool decode_joint_command(ByteReader& r, Command* out) {
  if (out->type == CommandType::create_joint) {
    const size_t at = r.offset();
    const uint8_t type = r.u8("joint type");
    if (!r.ok()) return false;
    if (type > static_cast<uint8_t>(JointType::motor)) {
      r.fail_at(at, "expected " + r.describe_what("joint type") + " 0..6, got " + std::to_string(type));
      return false;
    }
    out->joint_spec.type = static_cast<JointType>(type);
  }
  Reader reader{r};
  visit_joint_fields(reader, *out);
  return r.ok();
}

bool equal_joint_command(const Command& a, const Command& b) {
  // Equal when the fields the type uses are: their encodings (one field
  // list, visit_joint_fields) are the same bytes.
  if (a.type != b.type || !is_joint_command(a.type)) return false;
  std::vector<uint8_t> ea, eb;
  ByteWriter wa(&ea), wb(&eb);
  encode_joint_command(wa, a);
  encode_joint_command(wb, b);
  return ea == eb;
}

}  // namespace tandem
