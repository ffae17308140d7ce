// commands.cpp — applying, encoding and decoding engine commands
// (commands.h documents the format and the error scheme).
#include "replay/commands.h"

#include <utility>

#include "fixed/str_cat.h"

namespace tandem {

namespace {

bool uses_body(CommandType t) {
  return t != CommandType::set_gravity && t != CommandType::user_input && t != CommandType::create_body &&
         !is_joint_command(t);
}

bool equal_shape_def(const ShapeDef& a, const ShapeDef& b) {
  return a.friction == b.friction && a.restitution == b.restitution && a.density == b.density &&
         a.filter.category_bits == b.filter.category_bits && a.filter.mask_bits == b.filter.mask_bits &&
         a.filter.group_index == b.filter.group_index && a.user_data == b.user_data && a.is_sensor == b.is_sensor &&
         a.enable_hit_events == b.enable_hit_events;
}

bool equal_body_def(const BodyDef& a, const BodyDef& b) {
  return a.type == b.type && a.position == b.position && a.rotation == b.rotation &&
         a.linear_velocity == b.linear_velocity && a.angular_velocity == b.angular_velocity &&
         a.linear_damping == b.linear_damping && a.angular_damping == b.angular_damping &&
         a.gravity_scale == b.gravity_scale && a.user_data == b.user_data && a.enable_sleep == b.enable_sleep &&
         a.is_awake == b.is_awake && a.fixed_rotation == b.fixed_rotation && a.is_bullet == b.is_bullet &&
         a.is_enabled == b.is_enabled;
}

bool equal_polygon(const Polygon& a, const Polygon& b) {
  if (a.count != b.count || a.centroid != b.centroid || a.radius != b.radius) return false;
  for (int32_t i = 0; i < a.count && i < k_max_polygon_vertices; ++i) {
    const auto k = static_cast<size_t>(i);
    if (a.vertices[k] != b.vertices[k] || a.normals[k] != b.normals[k]) return false;
  }
  return true;
}

bool equal_shape(const ShapeSpec& a, const ShapeSpec& b) {
  if (a.kind != b.kind || !equal_shape_def(a.def, b.def)) return false;
  switch (a.kind) {
    case ShapeKind::circle: return a.circle.center == b.circle.center && a.circle.radius == b.circle.radius;
    case ShapeKind::capsule:
      return a.capsule.center1 == b.capsule.center1 && a.capsule.center2 == b.capsule.center2 &&
             a.capsule.radius == b.capsule.radius;
    case ShapeKind::segment: return a.segment.point1 == b.segment.point1 && a.segment.point2 == b.segment.point2;
    case ShapeKind::polygon: return equal_polygon(a.polygon, b.polygon);
    case ShapeKind::chain: return a.chain_points == b.chain_points && a.chain_loop == b.chain_loop;
  }
  return false;
}

std::string ref_text(BodyRef r) {
  return "body {index " + std::to_string(r.index) + ", generation " + std::to_string(r.generation) + "}";
}

Status prefixed(const Command& c, Status s) {
  if (!s.ok()) s.message = describe(c) + ": " + s.message;
  return s;
}

Status invalid(const Command& c, const std::string& why) {
  return Status{StatusCode::invalid_argument, describe(c) + ": " + why};
}

const char* shape_kind_name(ShapeKind k) {
  switch (k) {
    case ShapeKind::circle: return "circle";
    case ShapeKind::capsule: return "capsule";
    case ShapeKind::segment: return "segment";
    case ShapeKind::polygon: return "polygon";
    case ShapeKind::chain: return "chain";
  }
  return "unknown";
}

Status validate_shape(const ShapeSpec& s) {
  switch (s.kind) {
    case ShapeKind::circle: return validate_circle(s.circle);
    case ShapeKind::capsule: return validate_capsule(s.capsule);
    case ShapeKind::segment: return validate_segment(s.segment);
    case ShapeKind::polygon: return validate_polygon(s.polygon);
    case ShapeKind::chain: {
      if (s.chain_points.size() > k_max_chain_points)
        return Status{StatusCode::invalid_argument, "chain has " + std::to_string(s.chain_points.size()) + " points, at most " +
                                         std::to_string(k_max_chain_points)};
      return Status{};  // create_chain_shapes checks the rest before creating anything
    }
  }
  return Status{StatusCode::invalid_argument, "unknown shape kind " + std::to_string(static_cast<int>(s.kind))};
}

Status attach_shape(BodyId body, const ShapeSpec& s) {
  switch (s.kind) {
    case ShapeKind::circle: return create_circle_shape(body, s.def, s.circle).status;
    case ShapeKind::capsule: return create_capsule_shape(body, s.def, s.capsule).status;
    case ShapeKind::segment: return create_segment_shape(body, s.def, s.segment).status;
    case ShapeKind::polygon: return create_polygon_shape(body, s.def, s.polygon).status;
    case ShapeKind::chain:
      return create_chain_shapes(body, s.def, s.chain_points.data(), static_cast<int32_t>(s.chain_points.size()),
                                 s.chain_loop, nullptr);
  }
  return Status{StatusCode::invalid_argument, "unknown shape kind"};
}

Status apply_create_body(WorldId world, const Command& c, BodyId* out_created) {
  for (size_t i = 0; i < c.shapes.size(); ++i) {
    const Status g = validate_shape(c.shapes[i]);
    if (!g.ok()) return invalid(c, "shape " + std::to_string(i) + " (" + shape_kind_name(c.shapes[i].kind) + "): " + g.message);
  }
  Result<BodyId> body = create_body(world, c.body_def);
  if (!body.ok()) return prefixed(c, body.status);
  for (size_t i = 0; i < c.shapes.size(); ++i) {
    Status s = attach_shape(body.value, c.shapes[i]);
    if (!s.ok()) {
      (void)destroy_body(body.value);
      s.message = describe(c) + ": shape " + std::to_string(i) + " (" + shape_kind_name(c.shapes[i].kind) +
                  "): " + s.message;
      return s;
    }
  }
  if (out_created != nullptr) *out_created = body.value;
  return Status{};
}

// --- encoding pieces ------------------------------------------------------------

void write_ref(ByteWriter& w, BodyRef r) {
  w.u32(r.index);
  w.u32(r.generation);
}

BodyRef read_ref(ByteReader& r) {
  BodyRef ref;
  ref.index = r.u32("body index");
  ref.generation = r.u32("body generation");
  return ref;
}

void write_body_def(ByteWriter& w, const BodyDef& d) {
  w.u8(static_cast<uint8_t>(d.type));
  w.vec2(d.position);
  w.rot(d.rotation);
  w.vec2(d.linear_velocity);
  w.q32(d.angular_velocity);
  w.q32(d.linear_damping);
  w.q32(d.angular_damping);
  w.q32(d.gravity_scale);
  w.u64(d.user_data);
  w.boolean(d.enable_sleep);
  w.boolean(d.is_awake);
  w.boolean(d.fixed_rotation);
  w.boolean(d.is_bullet);
  w.boolean(d.is_enabled);
}

BodyDef read_body_def(ByteReader& r) {
  BodyDef d = default_body_def();
  const size_t at = r.offset();
  const uint8_t type = r.u8("body_def.type");
  if (r.ok() && type > 2) r.fail_at(at, "expected body_def.type 0..2, got " + std::to_string(type));
  d.type = static_cast<BodyType>(type);
  d.position = r.vec2("body_def.position.x", "body_def.position.y");
  d.rotation = r.rot("body_def.rotation.c", "body_def.rotation.s");
  d.linear_velocity = r.vec2("body_def.linear_velocity.x", "body_def.linear_velocity.y");
  d.angular_velocity = r.q32("body_def.angular_velocity");
  d.linear_damping = r.q32("body_def.linear_damping");
  d.angular_damping = r.q32("body_def.angular_damping");
  d.gravity_scale = r.q32("body_def.gravity_scale");
  d.user_data = r.u64("body_def.user_data");
  d.enable_sleep = r.boolean("body_def.enable_sleep");
  d.is_awake = r.boolean("body_def.is_awake");
  d.fixed_rotation = r.boolean("body_def.fixed_rotation");
  d.is_bullet = r.boolean("body_def.is_bullet");
  d.is_enabled = r.boolean("body_def.is_enabled");
  return d;
}

void write_shape(ByteWriter& w, const ShapeSpec& s) {
  w.u8(static_cast<uint8_t>(s.kind));
  w.q32(s.def.friction);
  w.q32(s.def.restitution);
  w.q32(s.def.density);
  w.u64(s.def.filter.category_bits);
  w.u64(s.def.filter.mask_bits);
  w.i32(s.def.filter.group_index);
  w.u64(s.def.user_data);
  w.boolean(s.def.is_sensor);
  w.boolean(s.def.enable_hit_events);
  switch (s.kind) {
    case ShapeKind::circle:
      w.vec2(s.circle.center);
      w.q32(s.circle.radius);
      break;
    case ShapeKind::capsule:
      w.vec2(s.capsule.center1);
      w.vec2(s.capsule.center2);
      w.q32(s.capsule.radius);
      break;
    case ShapeKind::segment:
      w.vec2(s.segment.point1);
      w.vec2(s.segment.point2);
      break;
    case ShapeKind::polygon: {
      // A polygon not made by the builders may carry any count; clamp what is
      // written so the encoding stays readable (create refuses it anyway).
      int32_t n = s.polygon.count;
      if (n < 0) n = 0;
      if (n > k_max_polygon_vertices) n = k_max_polygon_vertices;
      w.u8(static_cast<uint8_t>(n));
      for (int32_t i = 0; i < n; ++i) w.vec2(s.polygon.vertices[static_cast<size_t>(i)]);
      for (int32_t i = 0; i < n; ++i) w.vec2(s.polygon.normals[static_cast<size_t>(i)]);
      w.vec2(s.polygon.centroid);
      w.q32(s.polygon.radius);
      break;
    }
    case ShapeKind::chain:
      w.u32(static_cast<uint32_t>(s.chain_points.size()));
      for (const Vec2& p : s.chain_points) w.vec2(p);
      w.boolean(s.chain_loop);
      break;
  }
}

bool read_shape(ByteReader& r, ShapeSpec* s) {
  const size_t at = r.offset();
  const uint8_t kind = r.u8("shape kind");
  if (!r.ok()) return false;
  if (kind > static_cast<uint8_t>(ShapeKind::chain)) {
    r.fail_at(at, "expected " + r.describe_what("shape kind") + " 0..4 (circle, capsule, segment, polygon, chain), got " +
                      std::to_string(kind));
    return false;
  }
  s->kind = static_cast<ShapeKind>(kind);
  s->def = default_shape_def();
  s->def.friction = r.q32("shape_def.friction");
  s->def.restitution = r.q32("shape_def.restitution");
  s->def.density = r.q32("shape_def.density");
  s->def.filter.category_bits = r.u64("shape_def.filter.category_bits");
  s->def.filter.mask_bits = r.u64("shape_def.filter.mask_bits");
  s->def.filter.group_index = r.i32("shape_def.filter.group_index");
  s->def.user_data = r.u64("shape_def.user_data");
  s->def.is_sensor = r.boolean("shape_def.is_sensor");
  s->def.enable_hit_events = r.boolean("shape_def.enable_hit_events");
  switch (s->kind) {
    case ShapeKind::circle:
      s->circle.center = r.vec2("circle.center.x", "circle.center.y");
      s->circle.radius = r.q32("circle.radius");
      break;
    case ShapeKind::capsule:
      s->capsule.center1 = r.vec2("capsule.center1.x", "capsule.center1.y");
      s->capsule.center2 = r.vec2("capsule.center2.x", "capsule.center2.y");
      s->capsule.radius = r.q32("capsule.radius");
      break;
    case ShapeKind::segment:
      s->segment.point1 = r.vec2("segment.point1.x", "segment.point1.y");
      s->segment.point2 = r.vec2("segment.point2.x", "segment.point2.y");
      break;
    case ShapeKind::polygon: {
      const size_t count_at = r.offset();
      const uint8_t n = r.u8("polygon.count");
      if (r.ok() && (n < 3 || n > k_max_polygon_vertices)) {
        r.fail_at(count_at, "expected " + r.describe_what("polygon.count") + " 3.." +
                                std::to_string(k_max_polygon_vertices) + ", got " + std::to_string(n));
        return false;
      }
      s->polygon = Polygon{};
      s->polygon.count = n;
      for (size_t i = 0; i < n; ++i) s->polygon.vertices[i] = r.vec2("polygon.vertex.x", "polygon.vertex.y");
      for (size_t i = 0; i < n; ++i) s->polygon.normals[i] = r.vec2("polygon.normal.x", "polygon.normal.y");
      s->polygon.centroid = r.vec2("polygon.centroid.x", "polygon.centroid.y");
      s->polygon.radius = r.q32("polygon.radius");
      break;
    }
    case ShapeKind::chain: {
      const uint32_t n = r.read_count("chain point count", 16, k_max_chain_points);
      if (!r.ok()) return false;
      s->chain_points.resize(n);
      for (uint32_t i = 0; i < n; ++i) s->chain_points[i] = r.vec2("chain point.x", "chain point.y");
      s->chain_loop = r.boolean("chain loop");
      break;
    }
  }
  return r.ok();
}

}  // namespace

bool operator==(const Command& a, const Command& b) {
  if (a.type != b.type) return false;
  if (is_joint_command(a.type)) return equal_joint_command(a, b);
  if (uses_body(a.type) && a.body != b.body) return false;
  switch (a.type) {
    case CommandType::create_body: {
      if (!equal_body_def(a.body_def, b.body_def) || a.shapes.size() != b.shapes.size()) return false;
      for (size_t i = 0; i < a.shapes.size(); ++i)
        if (!equal_shape(a.shapes[i], b.shapes[i])) return false;
      return true;
    }
    case CommandType::destroy_body: return true;
    case CommandType::apply_force:
    case CommandType::apply_linear_impulse:
      return a.vector == b.vector && a.at_center == b.at_center && (a.at_center || a.point == b.point) &&
             a.flag == b.flag;
    case CommandType::apply_torque:
    case CommandType::apply_angular_impulse: return a.scalar == b.scalar && a.flag == b.flag;
    case CommandType::set_linear_velocity: return a.vector == b.vector;
    case CommandType::set_angular_velocity: return a.scalar == b.scalar;
    case CommandType::set_transform: return a.vector == b.vector && a.rotation == b.rotation;
    case CommandType::set_awake:
    case CommandType::set_enabled: return a.flag == b.flag;
    case CommandType::set_gravity: return a.vector == b.vector;
    case CommandType::user_input: return a.payload == b.payload;
    default: break;  // joint commands: above
  }
  return false;
}

const char* command_type_name(CommandType type) {
  switch (type) {
    case CommandType::create_body: return "create_body";
    case CommandType::destroy_body: return "destroy_body";
    case CommandType::apply_force: return "apply_force";
    case CommandType::apply_torque: return "apply_torque";
    case CommandType::apply_linear_impulse: return "apply_linear_impulse";
    case CommandType::apply_angular_impulse: return "apply_angular_impulse";
    case CommandType::set_linear_velocity: return "set_linear_velocity";
    case CommandType::set_angular_velocity: return "set_angular_velocity";
    case CommandType::set_transform: return "set_transform";
    case CommandType::set_awake: return "set_awake";
    case CommandType::set_enabled: return "set_enabled";
    case CommandType::set_gravity: return "set_gravity";
    case CommandType::user_input: return "user_input";
    case CommandType::create_joint: return "create_joint";
    case CommandType::destroy_joint: return "destroy_joint";
    case CommandType::set_joint_motor_speed: return "set_joint_motor_speed";
    case CommandType::set_joint_target: return "set_joint_target";
    case CommandType::set_joint_length: return "set_joint_length";
    case CommandType::set_joint_limits: return "set_joint_limits";
    case CommandType::enable_joint_motor: return "enable_joint_motor";
    case CommandType::set_joint_max_motor_force: return "set_joint_max_motor_force";
    case CommandType::enable_joint_limit: return "enable_joint_limit";
    case CommandType::enable_joint_spring: return "enable_joint_spring";
    case CommandType::set_joint_spring: return "set_joint_spring";
    case CommandType::set_joint_offsets: return "set_joint_offsets";
    case CommandType::set_joint_break_thresholds: return "set_joint_break_thresholds";
  }
  return "unknown";
}

std::string describe(const Command& command) {
  std::string s = command_type_name(command.type);
  if (uses_body(command.type)) {
    s += ' ';
    s += ref_text(command.body);
  }
  if (command.type == CommandType::create_body) {
    s += " (";
    s += std::to_string(command.shapes.size());
    s += command.shapes.size() == 1 ? " shape)" : " shapes)";
  }
  if (is_joint_command(command.type) && command.type != CommandType::create_joint) {
    s += str_cat(" joint {index ", std::to_string(command.joint.index), ", generation ",
                 std::to_string(command.joint.generation), "}");
  }
  if (command.type == CommandType::user_input) {
    s += " (";
    s += std::to_string(command.payload.size());
    s += " bytes)";
  }
  return s;
}

// The builders name the fields each type uses (Command is an aggregate; the
// others keep their defaults).
// Designated initializers leave the other members at their defaults on
// purpose (g++ would warn about each of them).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
Command make_create_body(const BodyDef& def, std::vector<ShapeSpec> shapes) {
  return Command{.type = CommandType::create_body, .body_def = def, .shapes = std::move(shapes)};
}

Command make_destroy_body(BodyRef body) { return Command{.type = CommandType::destroy_body, .body = body}; }

Command make_apply_force(BodyRef body, Vec2 force, Vec2 world_point, bool wake) {
  return Command{.type = CommandType::apply_force, .body = body, .vector = force, .point = world_point,
                 .at_center = false, .flag = wake};
}

Command make_apply_force_to_center(BodyRef body, Vec2 force, bool wake) {
  return Command{.type = CommandType::apply_force, .body = body, .vector = force, .at_center = true, .flag = wake};
}

Command make_apply_torque(BodyRef body, Q32 torque, bool wake) {
  return Command{.type = CommandType::apply_torque, .body = body, .scalar = torque, .flag = wake};
}

Command make_apply_linear_impulse(BodyRef body, Vec2 impulse, Vec2 world_point, bool wake) {
  return Command{.type = CommandType::apply_linear_impulse, .body = body, .vector = impulse, .point = world_point,
                 .at_center = false, .flag = wake};
}

Command make_apply_linear_impulse_to_center(BodyRef body, Vec2 impulse, bool wake) {
  return Command{
      .type = CommandType::apply_linear_impulse, .body = body, .vector = impulse, .at_center = true, .flag = wake};
}

Command make_apply_angular_impulse(BodyRef body, Q32 impulse, bool wake) {
  return Command{.type = CommandType::apply_angular_impulse, .body = body, .scalar = impulse, .flag = wake};
}

Command make_set_linear_velocity(BodyRef body, Vec2 velocity) {
  return Command{.type = CommandType::set_linear_velocity, .body = body, .vector = velocity};
}

Command make_set_angular_velocity(BodyRef body, Q32 angular_velocity) {
  return Command{.type = CommandType::set_angular_velocity, .body = body, .scalar = angular_velocity};
}

Command make_set_transform(BodyRef body, Vec2 position, Rot rotation) {
  return Command{.type = CommandType::set_transform, .body = body, .vector = position, .rotation = rotation};
}

Command make_set_awake(BodyRef body, bool awake) {
  return Command{.type = CommandType::set_awake, .body = body, .flag = awake};
}

Command make_set_enabled(BodyRef body, bool enabled) {
  return Command{.type = CommandType::set_enabled, .body = body, .flag = enabled};
}

Command make_set_gravity(Vec2 gravity) { return Command{.type = CommandType::set_gravity, .vector = gravity}; }

Command make_user_input(std::vector<uint8_t> payload) {
  return Command{.type = CommandType::user_input, .payload = std::move(payload)};
}
#pragma GCC diagnostic pop

Status apply_command(WorldId world, const Command& c, BodyId* out_created) {
  if (out_created != nullptr) *out_created = BodyId{};
  if (c.type == CommandType::create_body) return apply_create_body(world, c, out_created);
  if (c.type == CommandType::user_input) return Status{};
  if (is_joint_command(c.type)) return prefixed(c, apply_joint_command(world, c));
  if (c.type == CommandType::set_gravity) return prefixed(c, world_set_gravity(world, c.vector));
  const BodyId body = body_id(world, c.body);
  if (c.body.generation == 0 || c.body.index == UINT32_MAX)
    return Status{StatusCode::invalid_handle, describe(c) + ": not a body handle (generation 0 or index out of range)"};
  // body_is_valid looks the handle up without building any text; only a
  // refused handle pays for body_check's message (the same one as before).
  if (!body_is_valid(body)) {
    const Status s = body_check(body, world);
    if (!s.ok()) return prefixed(c, s);
  }
  switch (c.type) {
    case CommandType::destroy_body: return prefixed(c, destroy_body(body));
    case CommandType::apply_force:
      return prefixed(c, c.at_center ? body_apply_force_to_center(body, c.vector, c.flag)
                                     : body_apply_force(body, c.vector, c.point, c.flag));
    case CommandType::apply_torque: return prefixed(c, body_apply_torque(body, c.scalar, c.flag));
    case CommandType::apply_linear_impulse:
      return prefixed(c, c.at_center ? body_apply_linear_impulse_to_center(body, c.vector, c.flag)
                                     : body_apply_linear_impulse(body, c.vector, c.point, c.flag));
    case CommandType::apply_angular_impulse: return prefixed(c, body_apply_angular_impulse(body, c.scalar, c.flag));
    case CommandType::set_linear_velocity: return prefixed(c, body_set_linear_velocity(body, c.vector));
    case CommandType::set_angular_velocity: return prefixed(c, body_set_angular_velocity(body, c.scalar));
    case CommandType::set_transform: return prefixed(c, body_set_transform(body, c.vector, c.rotation));
    case CommandType::set_awake: return prefixed(c, body_set_awake(body, c.flag));
    case CommandType::set_enabled: return prefixed(c, body_set_enabled(body, c.flag));
    default: break;
  }
  return Status{StatusCode::invalid_argument,
                "apply_command: unknown command type " + std::to_string(static_cast<int>(c.type))};
}

void encode_command(ByteWriter& w, const Command& c) {
  w.u8(static_cast<uint8_t>(c.type));
  switch (c.type) {
    case CommandType::create_body:
      write_body_def(w, c.body_def);
      w.u32(static_cast<uint32_t>(c.shapes.size()));
      for (const ShapeSpec& s : c.shapes) write_shape(w, s);
      break;
    case CommandType::destroy_body: write_ref(w, c.body); break;
    case CommandType::apply_force:
    case CommandType::apply_linear_impulse:
      write_ref(w, c.body);
      w.vec2(c.vector);
      w.boolean(c.at_center);
      if (!c.at_center) w.vec2(c.point);
      w.boolean(c.flag);
      break;
    case CommandType::apply_torque:
    case CommandType::apply_angular_impulse:
      write_ref(w, c.body);
      w.q32(c.scalar);
      w.boolean(c.flag);
      break;
    case CommandType::set_linear_velocity:
      write_ref(w, c.body);
      w.vec2(c.vector);
      break;
    case CommandType::set_angular_velocity:
      write_ref(w, c.body);
      w.q32(c.scalar);
      break;
    case CommandType::set_transform:
      write_ref(w, c.body);
      w.vec2(c.vector);
      w.rot(c.rotation);
      break;
    case CommandType::set_awake:
    case CommandType::set_enabled:
      write_ref(w, c.body);
      w.boolean(c.flag);
      break;
    case CommandType::set_gravity: w.vec2(c.vector); break;
    case CommandType::user_input:
      w.u32(static_cast<uint32_t>(c.payload.size()));
      w.bytes(c.payload.data(), c.payload.size());
      break;
    default: encode_joint_command(w, c); break;  // the joint commands
  }
}

static bool read_command(ByteReader& r, Command* out) {
  *out = Command{};
  const size_t at = r.offset();
  const uint8_t type = r.u8("command type");
  if (!r.ok()) return false;
  if (type < 1 || type > k_last_command_type) {
    r.fail_at(at, "expected " + r.describe_what("command type") + " 1.." + std::to_string(k_last_command_type) +
                      ", got " + std::to_string(type));
    return false;
  }
  out->type = static_cast<CommandType>(type);
  switch (out->type) {
    case CommandType::create_body: {
      out->body_def = read_body_def(r);
      // Each shape takes at least 1 (kind) + 54 (ShapeDef) + 5 (empty chain) bytes.
      const uint32_t n = r.read_count("shape count", 60, k_max_command_shapes);
      if (!r.ok()) return false;
      out->shapes.resize(n);
      for (uint32_t i = 0; i < n; ++i) {
        r.set_context("shape", static_cast<int64_t>(i));
        if (!read_shape(r, &out->shapes[i])) return false;
      }
      r.set_context(nullptr);
      break;
    }
    case CommandType::destroy_body: out->body = read_ref(r); break;
    case CommandType::apply_force:
    case CommandType::apply_linear_impulse:
      out->body = read_ref(r);
      out->vector = r.vec2("vector.x", "vector.y");
      out->at_center = r.boolean("at_center");
      if (!out->at_center) out->point = r.vec2("point.x", "point.y");
      out->flag = r.boolean("wake");
      break;
    case CommandType::apply_torque:
    case CommandType::apply_angular_impulse:
      out->body = read_ref(r);
      out->scalar = r.q32("scalar");
      out->flag = r.boolean("wake");
      break;
    case CommandType::set_linear_velocity:
      out->body = read_ref(r);
      out->vector = r.vec2("linear_velocity.x", "linear_velocity.y");
      break;
    case CommandType::set_angular_velocity:
      out->body = read_ref(r);
      out->scalar = r.q32("angular_velocity");
      break;
    case CommandType::set_transform:
      out->body = read_ref(r);
      out->vector = r.vec2("position.x", "position.y");
      out->rotation = r.rot("rotation.c", "rotation.s");
      break;
    case CommandType::set_awake:
    case CommandType::set_enabled:
      out->body = read_ref(r);
      out->flag = r.boolean(out->type == CommandType::set_awake ? "awake" : "enabled");
      break;
    case CommandType::set_gravity: out->vector = r.vec2("gravity.x", "gravity.y"); break;
    case CommandType::user_input: {
      const uint32_t n = r.read_count("payload byte count", 1, k_max_user_payload_bytes);
      if (!r.ok()) return false;
      const std::span<const uint8_t> bytes = r.bytes(n, "payload");
      out->payload.assign(bytes.begin(), bytes.end());
      break;
    }
    default:  // the joint commands
      if (!decode_joint_command(r, out)) return false;
      break;
  }
  return r.ok();
}

void encode_commands(ByteWriter& w, std::span<const Command> commands) {
  w.u32(static_cast<uint32_t>(commands.size()));
  for (const Command& c : commands) encode_command(w, c);
}

static bool read_commands(ByteReader& r, std::vector<Command>* out) {
  out->clear();
  // Every command takes at least 5 bytes; commands are appended one by one
  // (not resized up front) so memory follows the bytes actually decoded.
  const uint32_t n = r.read_count("command count", 5);
  if (!r.ok()) return false;
  for (uint32_t i = 0; i < n; ++i) {
    Command c;
    if (!read_command(r, &c)) return false;
    out->push_back(std::move(c));
  }
  return true;
}

// The reader's error ("offset N: expected ...") as a Status.
static Status reader_status(const ByteReader& r, const char* what) {
  if (r.ok()) return Status{StatusCode::invalid_argument, "offset " + std::to_string(r.offset()) + ": malformed " + what};
  return Status{StatusCode::invalid_argument, r.error()};
}

Status decode_command(ByteReader* reader, Command* out_command) {
  return read_command(*reader, out_command) && reader->ok() ? Status{} : reader_status(*reader, "command");
}

Status decode_commands(ByteReader* reader, std::vector<Command>* out_commands) {
  return read_commands(*reader, out_commands) && reader->ok() ? Status{} : reader_status(*reader, "command list");
}

}  // namespace tandem
