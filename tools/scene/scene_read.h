// scene_read.h — internal to tools/scene: the key tables, the error path
// and the field readers shared by scene.cpp (shapes, bodies, generators,
// world, the scene) and scene_joints.cpp (joints and inputs). Readers throw
// SceneError; the public functions in scene.cpp catch it.
#pragma once

#include <algorithm>
#include <initializer_list>
#include <string>
#include <vector>

#include "json_tree.h"
#include "scene.h"

namespace tandem::scene::detail {

// --- accepted keys (documented in docs/scene-format.md) -----------------------
inline const std::vector<std::string> k_top_keys = {"format", "version", "name",   "description", "comment",
                                             "step_hz", "ticks",  "view",   "world",       "bodies",
                                             "generators", "joints", "inputs"};
inline const std::vector<std::string> k_view_keys = {"lower", "upper", "comment"};
inline const std::vector<std::string> k_world_keys = {
    "gravity",           "sub_steps",           "contact_hertz",     "contact_damping_ratio",
    "max_contact_push_speed", "joint_hertz",    "joint_damping_ratio", "restitution_threshold",
    "hit_event_threshold", "max_linear_speed",  "bounds",            "sleep",
    "broad_phase",       "user_data",           "comment"};
inline const std::vector<std::string> k_body_keys = {
    "name",           "type",          "position",     "angle",   "linear_velocity", "angular_velocity",
    "linear_damping", "angular_damping", "gravity_scale", "user_data", "sleep",        "awake",
    "fixed_rotation", "bullet",        "enabled",      "shapes",  "comment"};
inline const std::vector<std::string> k_shape_common_keys = {"type",   "friction",   "restitution", "density", "filter",
                                                      "sensor", "hit_events", "user_data",   "comment"};
inline const std::vector<std::string> k_circle_keys = {"center", "radius"};
inline const std::vector<std::string> k_capsule_keys = {"center1", "center2", "radius"};
inline const std::vector<std::string> k_box_keys = {"half_width", "half_height", "center", "angle", "radius"};
inline const std::vector<std::string> k_polygon_keys = {"points", "radius"};
inline const std::vector<std::string> k_segment_keys = {"point1", "point2"};
inline const std::vector<std::string> k_chain_keys = {"points", "loop"};
inline const std::vector<std::string> k_filter_keys = {"category", "mask", "group", "comment"};
inline const std::vector<std::string> k_generator_grid_keys = {"type", "origin", "columns", "rows", "spacing", "body",
                                                        "comment"};
inline const std::vector<std::string> k_generator_pyramid_keys = {"type", "origin", "base", "spacing", "body", "comment"};
inline const std::vector<std::string> k_generator_random_keys = {"type",     "seed",  "count", "region", "kinds",
                                                          "size_min", "size_max", "speed", "body", "shape",
                                                          "comment"};
inline const std::vector<std::string> k_input_common_keys = {"tick", "type", "body", "joint", "comment"};
inline const std::vector<std::string> k_input_value_keys = {"force",    "impulse", "point",    "torque",  "velocity",
                                                     "position", "angle",   "awake",    "enabled", "gravity",
                                                     "wake",     "length",  "limit",    "speed",   "target"};
inline const std::vector<std::string> k_joint_keys = {
    "type",          "body_a",         "body_b",   "anchor",        "anchor_a",      "anchor_b",
    "collide_connected", "break_force", "break_torque", "user_data", "axis",          "reference_angle",
    "limit",         "motor_speed",    "max_motor_force", "hertz",  "damping_ratio", "angular_hertz",
    "angular_damping_ratio", "length", "target",   "max_force",     "max_torque",    "correction_factor",
    "linear_offset", "angular_offset", "comment"};
inline const std::vector<std::string> k_names = {
    // enum values
    "static", "kinematic", "dynamic", "circle", "capsule", "box", "polygon", "segment", "chain",
    "grid", "pyramid", "random", "naive", "sweep_and_prune", "tree",
    "apply_force", "apply_linear_impulse", "apply_torque", "apply_angular_impulse", "set_linear_velocity",
    "set_angular_velocity", "set_transform", "set_awake", "set_enabled", "set_gravity", "destroy_body",
    "set_joint_length", "set_joint_limits", "set_joint_motor_speed", "set_joint_target", "destroy_joint",
    "revolute", "distance", "rope", "weld", "prismatic", "mouse", "wheel", "motor"};

struct SceneError {
  std::string message;
};

/// "/" for the root, else the JSON pointer itself.
std::string show_path(const std::string& path);
/// Throws SceneError "<path>: <message>".
[[noreturn]] void fail(const std::string& path, const std::string& message);
/// The names quoted and joined: "a", "b" or "c".
std::string quoted_list(const std::vector<std::string>& names);
/// " (did you mean "x"?)" for the nearest known word, or "".
std::string did_you_mean(const std::string& word, const std::vector<std::string>& known);
/// "got 3.5", "got a string", ...: what a value was, for messages.
std::string got(const JsonValue& v);

// An object whose keys have been checked against the allowed lists.
class Obj {
 public:
  Obj(const JsonValue& v, std::string path, std::initializer_list<const std::vector<std::string>*> allowed)
      : v_(v), path_(std::move(path)) {
    if (v.kind != JsonValue::Kind::object) fail(path_, std::string("expected an object, ") + got(v));
    std::vector<std::string> all;
    for (const auto* list : allowed) all.insert(all.end(), list->begin(), list->end());
    for (const std::string& key : v.keys)
      if (std::find(all.begin(), all.end(), key) == all.end())
        fail(path_ + "/" + key, "unknown key" + did_you_mean(key, all) + "; expected one of " + quoted_list(all));
  }
  const JsonValue* find(const std::string& key) const {
    for (size_t i = 0; i < v_.keys.size(); ++i)
      if (v_.keys[i] == key) return &v_.items[i];
    return nullptr;
  }
  const JsonValue& need(const std::string& key) const {
    const JsonValue* p = find(key);
    if (!p) fail(path_, "missing key \"" + key + "\"");
    return *p;
  }
  std::string at(const std::string& key) const { return path_ + "/" + key; }
  const std::string& path() const { return path_; }

 private:
  const JsonValue& v_;
  std::string path_;
};

// --- scalar readers (each names the JSON pointer on failure) -------------------
Q32 read_q32(const JsonValue& v, const std::string& path);
Q32 read_q32_min(const JsonValue& v, const std::string& path, Q32 lo, bool exclusive);
int64_t read_int(const JsonValue& v, const std::string& path, int64_t lo, int64_t hi);
uint64_t read_u64(const JsonValue& v, const std::string& path);
bool read_bool(const JsonValue& v, const std::string& path);
std::string read_string(const JsonValue& v, const std::string& path);
std::string read_enum(const JsonValue& v, const std::string& path, const std::vector<std::string>& names);
Vec2 read_vec2(const JsonValue& v, const std::string& path);
std::vector<Vec2> read_points(const JsonValue& v, const std::string& path, size_t min_count, size_t max_count);
const std::vector<JsonValue>& read_array(const JsonValue& v, const std::string& path);
AABB read_box(const JsonValue& v, const std::string& path);

// Optional field helpers: assign only when present.
template <typename F>
void opt(const Obj& o, const char* key, F&& read) {
  if (const JsonValue* v = o.find(key)) read(*v, o.at(key));
}

// --- joints and inputs (scene_joints.cpp) --------------------------------------
/// A body named by "name" or by index into `bodies`.
int32_t resolve_body(const JsonValue& v, const std::string& path, const std::vector<SceneBody>& bodies);
/// A joint: bodies by name or index; anchors as world points at the bodies'
/// initial poses (turned into body-frame anchors).
SceneJoint read_joint(const JsonValue& v, const std::string& path, const std::vector<SceneBody>& bodies);
/// A scripted input; joints by index below joint_count.
SceneInput read_input(const JsonValue& v, const std::string& path, const std::vector<SceneBody>& bodies,
                      size_t joint_count);

}  // namespace tandem::scene::detail
