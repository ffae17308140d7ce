// scene_joints.cpp — the scene reader's joints and scripted inputs
// (scene_read.h; docs/scene-format.md).
#include "scene_read.h"

#include "fixed/fixed_math.h"

namespace tandem::scene::detail {

int32_t resolve_body(const JsonValue& v, const std::string& path, const std::vector<SceneBody>& bodies) {
  if (v.kind == JsonValue::Kind::string) {
    for (size_t i = 0; i < bodies.size(); ++i)
      if (bodies[i].name == v.text) return static_cast<int32_t>(i);
    fail(path, "no body is named \"" + v.text + "\"");
  }
  if (bodies.empty()) fail(path, "the scene has no bodies");
  return static_cast<int32_t>(read_int(v, path, 0, static_cast<int64_t>(bodies.size()) - 1));
}

/// A joint: bodies by name or index; anchors as world points at the bodies'
/// initial poses (turned into body-frame anchors here).
SceneJoint read_joint(const JsonValue& v, const std::string& path, const std::vector<SceneBody>& bodies) {
  Obj o(v, path, {&k_joint_keys});
  static const std::vector<std::string> types = {"revolute", "distance", "rope", "weld",
                                                 "prismatic", "mouse",    "wheel", "motor"};
  const std::string type = read_enum(o.need("type"), o.at("type"), types);
  SceneJoint j;
  j.path = path;
  j.body_a = resolve_body(o.need("body_a"), o.at("body_a"), bodies);
  j.body_b = resolve_body(o.need("body_b"), o.at("body_b"), bodies);
  JointSpec& s = j.spec;
  const auto q = [&](const char* key, Q32 fallback) {
    const JsonValue* x = o.find(key);
    return x != nullptr ? read_q32(*x, o.at(key)) : fallback;
  };
  const auto vec = [&](const char* key, Vec2 fallback) {
    const JsonValue* x = o.find(key);
    return x != nullptr ? read_vec2(*x, o.at(key)) : fallback;
  };
  const auto local = [&](int32_t body, Vec2 world_point) {
    const BodyDef& d = bodies[static_cast<size_t>(body)].def;
    return inv_transform_point(Transform{d.position, d.rotation}, world_point);
  };
  const Vec2 pa = bodies[static_cast<size_t>(j.body_a)].def.position;
  const Vec2 pb = bodies[static_cast<size_t>(j.body_b)].def.position;
  const Vec2 anchor = vec("anchor", pb);
  s.local_anchor_a = local(j.body_a, vec("anchor_a", anchor));
  s.local_anchor_b = local(j.body_b, vec("anchor_b", anchor));
  opt(o, "collide_connected", [&](const JsonValue& x, const std::string& p) { s.collide_connected = read_bool(x, p); });
  s.break_force = q("break_force", Q32{});
  s.break_torque = q("break_torque", Q32{});
  opt(o, "user_data", [&](const JsonValue& x, const std::string& p) { s.user_data = read_u64(x, p); });
  s.reference_angle = q("reference_angle", Q32{});
  opt(o, "limit", [&](const JsonValue& x, const std::string& p) {
    const Vec2 l = read_vec2(x, p);
    s.enable_limit = true;
    s.lower = l.x;
    s.upper = l.y;
  });
  if (o.find("motor_speed") || o.find("max_motor_force")) s.enable_motor = true;
  s.motor_speed = q("motor_speed", Q32{});
  s.motor_force = q("max_motor_force", Q32{});
  if (o.find("hertz")) s.enable_spring = true;
  s.hertz = q("hertz", Q32{});
  s.damping_ratio = q("damping_ratio", Q32{});
  s.angular_hertz = q("angular_hertz", Q32{});
  s.angular_damping_ratio = q("angular_damping_ratio", Q32{});
  s.local_axis = vec("axis", Vec2{Q32::one(), Q32{}});
  if (type == "revolute") {
    s.type = JointType::revolute;
  } else if (type == "distance" || type == "rope") {
    s.type = JointType::distance;
    const Vec2 a = vec("anchor_a", anchor), b = vec("anchor_b", anchor);
    s.length = q("length", max(distance(a, b), k_min_joint_length));
    if (type == "rope") {  // a free rope: no spring force, only pulls at its length
      s.enable_spring = true;
      s.enable_limit = true;
      s.lower = Q32{};
      s.upper = s.length;
    } else if (!s.enable_limit) {
      s.upper = k_max_joint_length;
    }
  } else if (type == "weld") {
    s.type = JointType::weld;
  } else if (type == "prismatic") {
    s.type = JointType::prismatic;
  } else if (type == "wheel") {
    s.type = JointType::wheel;
    s.local_axis = vec("axis", Vec2{Q32{}, Q32::one()});
    if (!o.find("hertz")) {
      s.hertz = Q32::one();
      s.damping_ratio = q("damping_ratio", Q32::from_ratio(7, 10));
    }
    s.enable_spring = true;
  } else if (type == "mouse") {
    s.type = JointType::mouse;
    s.target = vec("target", pb);
    s.hertz = q("hertz", 5_q32);
    s.damping_ratio = q("damping_ratio", Q32::from_ratio(7, 10));
    s.max_force = q("max_force", 1000_q32);
  } else {
    s.type = JointType::motor;
    s.local_anchor_a = {};
    s.local_anchor_b = {};
    s.target = vec("linear_offset", local(j.body_a, pb));
    s.angular_offset = q("angular_offset", Q32{});
    s.max_force = q("max_force", 1_q32);
    s.max_torque = q("max_torque", 1_q32);
    s.correction_factor = q("correction_factor", Q32::from_ratio(3, 10));
  }
  (void)pa;
  return j;
}

SceneInput read_input(const JsonValue& v, const std::string& path, const std::vector<SceneBody>& bodies,
                      size_t joint_count) {
  if (v.kind != JsonValue::Kind::object) fail(path, "expected an object, " + got(v));
  static const std::vector<std::string> types = {
      "apply_force",         "apply_linear_impulse", "apply_torque", "apply_angular_impulse", "set_linear_velocity",
      "set_angular_velocity", "set_transform",       "set_awake",    "set_enabled",           "set_gravity",
      "destroy_body",        "set_joint_length",     "set_joint_limits",     "set_joint_motor_speed", "set_joint_target", "destroy_joint"};
  std::string type;
  for (size_t i = 0; i < v.keys.size(); ++i)
    if (v.keys[i] == "type") type = read_enum(v.items[i], path + "/type", types);
  if (type.empty()) fail(path, "missing key \"type\" (one of " + quoted_list(types) + ")");
  std::vector<std::string> keys;
  if (type == "apply_force") keys = {"force", "point", "wake"};
  else if (type == "apply_linear_impulse") keys = {"impulse", "point", "wake"};
  else if (type == "apply_torque") keys = {"torque", "wake"};
  else if (type == "apply_angular_impulse") keys = {"impulse", "wake"};
  else if (type == "set_linear_velocity" || type == "set_angular_velocity") keys = {"velocity"};
  else if (type == "set_transform") keys = {"position", "angle"};
  else if (type == "set_awake") keys = {"awake"};
  else if (type == "set_enabled") keys = {"enabled"};
  else if (type == "set_gravity") keys = {"gravity"};
  else if (type == "set_joint_length") keys = {"length"};
  else if (type == "set_joint_limits") keys = {"limit"};
  else if (type == "set_joint_motor_speed") keys = {"speed"};
  else if (type == "set_joint_target") keys = {"target"};
  Obj o(v, path, {&k_input_common_keys, &keys});
  SceneInput in;
  in.path = path;
  in.tick = read_int(o.need("tick"), o.at("tick"), 0, INT64_C(1) << 40);
  if (type.compare(0, 10, "set_joint_") == 0 || type == "destroy_joint") {
    // Joint inputs name a joint by its index in "joints": the scene's joints
    // are the first a fresh world creates, so joint i has the ref {i, 1}.
    if (o.find("body")) fail(o.at("body"), type + " takes a \"joint\", not a body");
    if (joint_count == 0) fail(o.at("joint"), "the scene has no joints");
    const JointRef joint{static_cast<uint32_t>(read_int(o.need("joint"), o.at("joint"), 0,
                                                        static_cast<int64_t>(joint_count) - 1)),
                         1};
    if (type == "set_joint_length") in.command = make_set_joint_length(joint, read_q32(o.need("length"), o.at("length")));
    else if (type == "set_joint_limits") {
      const Vec2 l = read_vec2(o.need("limit"), o.at("limit"));
      in.command = make_set_joint_limits(joint, l.x, l.y);
    } else if (type == "set_joint_motor_speed")
      in.command = make_set_joint_motor_speed(joint, read_q32(o.need("speed"), o.at("speed")));
    else if (type == "set_joint_target")
      in.command = make_set_joint_target(joint, read_vec2(o.need("target"), o.at("target")));
    else in.command = make_destroy_joint(joint);
    return in;
  }
  if (o.find("joint")) fail(o.at("joint"), type + " takes no joint");
  if (type == "set_gravity") {
    if (o.find("body")) fail(o.at("body"), "set_gravity takes no body");
    in.command = make_set_gravity(read_vec2(o.need("gravity"), o.at("gravity")));
    return in;
  }
  in.body = resolve_body(o.need("body"), o.at("body"), bodies);
  const BodyRef none{};
  const bool wake = o.find("wake") ? read_bool(*o.find("wake"), o.at("wake")) : true;
  auto vec = [&](const char* key) { return read_vec2(o.need(key), o.at(key)); };
  auto q = [&](const char* key) { return read_q32(o.need(key), o.at(key)); };
  if (type == "apply_force" || type == "apply_linear_impulse") {
    const bool force = type == "apply_force";
    const Vec2 amount = vec(force ? "force" : "impulse");
    if (o.find("point")) {
      const Vec2 point = vec("point");
      in.command = force ? make_apply_force(none, amount, point, wake) : make_apply_linear_impulse(none, amount, point, wake);
    } else {
      in.command = force ? make_apply_force_to_center(none, amount, wake)
                         : make_apply_linear_impulse_to_center(none, amount, wake);
    }
  } else if (type == "apply_torque") {
    in.command = make_apply_torque(none, q("torque"), wake);
  } else if (type == "apply_angular_impulse") {
    in.command = make_apply_angular_impulse(none, q("impulse"), wake);
  } else if (type == "set_linear_velocity") {
    in.command = make_set_linear_velocity(none, vec("velocity"));
  } else if (type == "set_angular_velocity") {
    in.command = make_set_angular_velocity(none, q("velocity"));
  } else if (type == "set_transform") {
    const Q32 angle = o.find("angle") ? q("angle") : Q32{};
    in.command = make_set_transform(none, vec("position"), rot_from_angle(angle));
  } else if (type == "set_awake") {
    in.command = make_set_awake(none, read_bool(o.need("awake"), o.at("awake")));
  } else if (type == "set_enabled") {
    in.command = make_set_enabled(none, read_bool(o.need("enabled"), o.at("enabled")));
  } else {
    in.command = make_destroy_body(none);
  }
  return in;
}

}  // namespace tandem::scene::detail
