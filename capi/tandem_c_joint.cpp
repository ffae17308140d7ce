// tandem_c_joint.cpp — the C API of joints (include/tandem_c_joint.h).
// (design and how to add a function: tandem_c_core.cpp's top comment).
//
// The seven definitions are converted field by field in both directions by
// one map() per struct, templated on the direction (f<>, def_to_c in
// tandem_c_internal.h), so the field lists are written once.
#include "tandem_c_internal.h"

using namespace tandem_c_internal;

// The field lists (global namespace, the C structs' own: def_to_c / def_to_cpp
// in tandem_c_internal.h find them by argument-dependent lookup).
template <bool D>
void map(JointBaseDef& a, tandem_joint_base_def& b) {
  f<D>(a.body_a, b.body_a), f<D>(a.body_b, b.body_b);
  f<D>(a.local_anchor_a, b.local_anchor_a), f<D>(a.local_anchor_b, b.local_anchor_b);
  f<D>(a.collide_connected, b.collide_connected);
  f<D>(a.break_force, b.break_force), f<D>(a.break_torque, b.break_torque);
  f<D>(a.user_data, b.user_data);
}
template <bool D>
void map(RevoluteJointDef& a, tandem_revolute_joint_def& b) {
  map<D>(a.base, b.base);
  f<D>(a.reference_angle, b.reference_angle);
  f<D>(a.enable_limit, b.enable_limit), f<D>(a.lower_angle, b.lower_angle), f<D>(a.upper_angle, b.upper_angle);
  f<D>(a.enable_motor, b.enable_motor), f<D>(a.motor_speed, b.motor_speed);
  f<D>(a.max_motor_torque, b.max_motor_torque);
  f<D>(a.enable_spring, b.enable_spring), f<D>(a.hertz, b.hertz), f<D>(a.damping_ratio, b.damping_ratio);
  f<D>(a.internal_cookie, b.internal_cookie);
}
template <bool D>
void map(DistanceJointDef& a, tandem_distance_joint_def& b) {
  map<D>(a.base, b.base);
  f<D>(a.length, b.length);
  f<D>(a.enable_spring, b.enable_spring), f<D>(a.hertz, b.hertz), f<D>(a.damping_ratio, b.damping_ratio);
  f<D>(a.enable_limit, b.enable_limit), f<D>(a.min_length, b.min_length), f<D>(a.max_length, b.max_length);
  f<D>(a.enable_motor, b.enable_motor), f<D>(a.motor_speed, b.motor_speed);
  f<D>(a.max_motor_force, b.max_motor_force);
  f<D>(a.internal_cookie, b.internal_cookie);
}
template <bool D>
void map(WeldJointDef& a, tandem_weld_joint_def& b) {
  map<D>(a.base, b.base);
  f<D>(a.reference_angle, b.reference_angle);
  f<D>(a.linear_hertz, b.linear_hertz), f<D>(a.linear_damping_ratio, b.linear_damping_ratio);
  f<D>(a.angular_hertz, b.angular_hertz), f<D>(a.angular_damping_ratio, b.angular_damping_ratio);
  f<D>(a.internal_cookie, b.internal_cookie);
}
template <bool D>
void map(PrismaticJointDef& a, tandem_prismatic_joint_def& b) {
  map<D>(a.base, b.base);
  f<D>(a.local_axis_a, b.local_axis_a), f<D>(a.reference_angle, b.reference_angle);
  f<D>(a.enable_limit, b.enable_limit);
  f<D>(a.lower_translation, b.lower_translation), f<D>(a.upper_translation, b.upper_translation);
  f<D>(a.enable_motor, b.enable_motor), f<D>(a.motor_speed, b.motor_speed);
  f<D>(a.max_motor_force, b.max_motor_force);
  f<D>(a.enable_spring, b.enable_spring), f<D>(a.hertz, b.hertz), f<D>(a.damping_ratio, b.damping_ratio);
  f<D>(a.internal_cookie, b.internal_cookie);
}
template <bool D>
void map(MouseJointDef& a, tandem_mouse_joint_def& b) {
  map<D>(a.base, b.base);
  f<D>(a.target, b.target), f<D>(a.hertz, b.hertz), f<D>(a.damping_ratio, b.damping_ratio);
  f<D>(a.max_force, b.max_force);
  f<D>(a.internal_cookie, b.internal_cookie);
}
template <bool D>
void map(WheelJointDef& a, tandem_wheel_joint_def& b) {
  map<D>(a.base, b.base);
  f<D>(a.local_axis_a, b.local_axis_a);
  f<D>(a.enable_spring, b.enable_spring), f<D>(a.hertz, b.hertz), f<D>(a.damping_ratio, b.damping_ratio);
  f<D>(a.enable_limit, b.enable_limit);
  f<D>(a.lower_translation, b.lower_translation), f<D>(a.upper_translation, b.upper_translation);
  f<D>(a.enable_motor, b.enable_motor), f<D>(a.motor_speed, b.motor_speed);
  f<D>(a.max_motor_torque, b.max_motor_torque);
  f<D>(a.internal_cookie, b.internal_cookie);
}
template <bool D>
void map(MotorJointDef& a, tandem_motor_joint_def& b) {
  map<D>(a.base, b.base);
  f<D>(a.linear_offset, b.linear_offset), f<D>(a.angular_offset, b.angular_offset);
  f<D>(a.max_force, b.max_force), f<D>(a.max_torque, b.max_torque);
  f<D>(a.correction_factor, b.correction_factor);
  f<D>(a.internal_cookie, b.internal_cookie);
}

namespace {
using tandem_c_internal::to_c;
using tandem_c_internal::to_cpp;

// create_*_joint for a C definition.
template <typename Cpp, typename C, typename Create>
tandem_status create(const char* fn, tandem_world_id world, const C* def, tandem_joint_id* out, Create&& create_fn) {
  if (def == nullptr) return null_pointer(fn, "def");
  if (out == nullptr) return null_pointer(fn, "out_joint");
  return guard(fn, [&] {
    const Result<JointId> r = create_fn(to_cpp(world), def_to_cpp<Cpp>(*def));
    if (r.ok()) *out = to_c(r.value);
    return status(r.status);
  });
}

// A joint handle list (world_joints / body_joints: count, then fill).
template <typename Owner, typename List, typename Check>
tandem_status joint_list(const char* fn, Owner owner, Check&& check, List&& list, tandem_joint_id* out, int32_t capacity,
                         int32_t* out_count) {
  return guard(fn, [&] {
    if (const Status s = check(owner); !s.ok()) return status(s);
    std::vector<JointId> ids(static_cast<size_t>(list(owner, nullptr, 0)));
    list(owner, ids.data(), static_cast<int32_t>(ids.size()));
    return fill(fn, std::span<const JointId>(ids), out, capacity, out_count, [](JointId j) { return to_c(j); });
  });
}

}  // namespace

// --- definitions and creation ------------------------------------------------------
tandem_revolute_joint_def tandem_default_revolute_joint_def(void) {
  return def_to_c<tandem_revolute_joint_def>(default_revolute_joint_def());
}
tandem_distance_joint_def tandem_default_distance_joint_def(void) {
  return def_to_c<tandem_distance_joint_def>(default_distance_joint_def());
}
tandem_weld_joint_def tandem_default_weld_joint_def(void) { return def_to_c<tandem_weld_joint_def>(default_weld_joint_def()); }
tandem_prismatic_joint_def tandem_default_prismatic_joint_def(void) {
  return def_to_c<tandem_prismatic_joint_def>(default_prismatic_joint_def());
}
tandem_mouse_joint_def tandem_default_mouse_joint_def(void) {
  return def_to_c<tandem_mouse_joint_def>(default_mouse_joint_def());
}
tandem_wheel_joint_def tandem_default_wheel_joint_def(void) {
  return def_to_c<tandem_wheel_joint_def>(default_wheel_joint_def());
}
tandem_motor_joint_def tandem_default_motor_joint_def(void) {
  return def_to_c<tandem_motor_joint_def>(default_motor_joint_def());
}

tandem_status tandem_create_revolute_joint(tandem_world_id world, const tandem_revolute_joint_def* def,
                                           tandem_joint_id* out_joint) {
  return create<RevoluteJointDef>("tandem_create_revolute_joint", world, def, out_joint,
                                  [](WorldId w, const RevoluteJointDef& d) { return create_revolute_joint(w, d); });
}
tandem_status tandem_create_distance_joint(tandem_world_id world, const tandem_distance_joint_def* def,
                                           tandem_joint_id* out_joint) {
  return create<DistanceJointDef>("tandem_create_distance_joint", world, def, out_joint,
                                  [](WorldId w, const DistanceJointDef& d) { return create_distance_joint(w, d); });
}
tandem_status tandem_create_weld_joint(tandem_world_id world, const tandem_weld_joint_def* def,
                                       tandem_joint_id* out_joint) {
  return create<WeldJointDef>("tandem_create_weld_joint", world, def, out_joint,
                              [](WorldId w, const WeldJointDef& d) { return create_weld_joint(w, d); });
}
tandem_status tandem_create_prismatic_joint(tandem_world_id world, const tandem_prismatic_joint_def* def,
                                            tandem_joint_id* out_joint) {
  return create<PrismaticJointDef>("tandem_create_prismatic_joint", world, def, out_joint,
                                   [](WorldId w, const PrismaticJointDef& d) { return create_prismatic_joint(w, d); });
}
tandem_status tandem_create_mouse_joint(tandem_world_id world, const tandem_mouse_joint_def* def,
                                        tandem_joint_id* out_joint) {
  return create<MouseJointDef>("tandem_create_mouse_joint", world, def, out_joint,
                               [](WorldId w, const MouseJointDef& d) { return create_mouse_joint(w, d); });
}
tandem_status tandem_create_wheel_joint(tandem_world_id world, const tandem_wheel_joint_def* def,
                                        tandem_joint_id* out_joint) {
  return create<WheelJointDef>("tandem_create_wheel_joint", world, def, out_joint,
                               [](WorldId w, const WheelJointDef& d) { return create_wheel_joint(w, d); });
}
tandem_status tandem_create_motor_joint(tandem_world_id world, const tandem_motor_joint_def* def,
                                        tandem_joint_id* out_joint) {
  return create<MotorJointDef>("tandem_create_motor_joint", world, def, out_joint,
                               [](WorldId w, const MotorJointDef& d) { return create_motor_joint(w, d); });
}

// --- handles ----------------------------------------------------------------------------
tandem_status tandem_destroy_joint(tandem_joint_id joint) {
  return guard("tandem_destroy_joint", [&] { return status(destroy_joint(to_cpp(joint))); });
}
bool tandem_joint_is_valid(tandem_joint_id joint) { return joint_is_valid(to_cpp(joint)); }
tandem_status tandem_joint_check(tandem_joint_id joint) {
  return guard("tandem_joint_check", [&] { return status(joint_check(to_cpp(joint))); });
}
tandem_status tandem_joint_describe(tandem_joint_id joint, char* out_text, size_t capacity, size_t* out_length) {
  static const char* fn = "tandem_joint_describe";
  return guard(fn, [&] { return copy_text(fn, describe(to_cpp(joint)), out_text, capacity, out_length); });
}

// --- getters ------------------------------------------------------------------------------
int32_t tandem_joint_type(tandem_joint_id joint) { return static_cast<int32_t>(joint_type(to_cpp(joint))); }
tandem_body_id tandem_joint_body_a(tandem_joint_id joint) { return to_c(joint_body_a(to_cpp(joint))); }
tandem_body_id tandem_joint_body_b(tandem_joint_id joint) { return to_c(joint_body_b(to_cpp(joint))); }
uint64_t tandem_joint_user_data(tandem_joint_id joint) { return joint_user_data(to_cpp(joint)); }

tandem_status tandem_world_joints(tandem_world_id world, tandem_joint_id* out_joints, int32_t capacity,
                                  int32_t* out_count) {
  return joint_list("tandem_world_joints", to_cpp(world), [](WorldId w) { return world_check(w); },
                    [](WorldId w, JointId* o, int32_t c) { return world_joints(w, o, c); }, out_joints, capacity,
                    out_count);
}
tandem_status tandem_body_joints(tandem_body_id body, tandem_joint_id* out_joints, int32_t capacity,
                                 int32_t* out_count) {
  return joint_list("tandem_body_joints", to_cpp(body), [](BodyId b) { return body_check(b); },
                    [](BodyId b, JointId* o, int32_t c) { return body_joints(b, o, c); }, out_joints, capacity,
                    out_count);
}

tandem_vec2 tandem_joint_reaction_force(tandem_joint_id joint) { return to_c(joint_reaction_force(to_cpp(joint))); }
tandem_q32 tandem_joint_reaction_torque(tandem_joint_id joint) { return joint_reaction_torque(to_cpp(joint)).raw; }
tandem_vec2 tandem_joint_world_anchor_a(tandem_joint_id joint) { return to_c(joint_world_anchor_a(to_cpp(joint))); }
tandem_vec2 tandem_joint_world_anchor_b(tandem_joint_id joint) { return to_c(joint_world_anchor_b(to_cpp(joint))); }
tandem_q32 tandem_joint_angle(tandem_joint_id joint) { return joint_angle(to_cpp(joint)).raw; }
tandem_q32 tandem_joint_translation(tandem_joint_id joint) { return joint_translation(to_cpp(joint)).raw; }

// --- setters -------------------------------------------------------------------------------
tandem_status tandem_joint_enable_motor(tandem_joint_id joint, bool enable) {
  return guard("tandem_joint_enable_motor", [&] { return status(joint_enable_motor(to_cpp(joint), enable)); });
}
tandem_status tandem_joint_set_motor_speed(tandem_joint_id joint, tandem_q32 speed) {
  return guard("tandem_joint_set_motor_speed", [&] { return status(joint_set_motor_speed(to_cpp(joint), q(speed))); });
}
tandem_status tandem_joint_set_max_motor_force(tandem_joint_id joint, tandem_q32 force_or_torque) {
  return guard("tandem_joint_set_max_motor_force",
               [&] { return status(joint_set_max_motor_force(to_cpp(joint), q(force_or_torque))); });
}
tandem_status tandem_joint_enable_limit(tandem_joint_id joint, bool enable) {
  return guard("tandem_joint_enable_limit", [&] { return status(joint_enable_limit(to_cpp(joint), enable)); });
}
tandem_status tandem_joint_set_limits(tandem_joint_id joint, tandem_q32 lower, tandem_q32 upper) {
  return guard("tandem_joint_set_limits", [&] { return status(joint_set_limits(to_cpp(joint), q(lower), q(upper))); });
}
tandem_status tandem_joint_enable_spring(tandem_joint_id joint, bool enable) {
  return guard("tandem_joint_enable_spring", [&] { return status(joint_enable_spring(to_cpp(joint), enable)); });
}
tandem_status tandem_joint_set_spring(tandem_joint_id joint, tandem_q32 hertz, tandem_q32 damping_ratio) {
  return guard("tandem_joint_set_spring",
               [&] { return status(joint_set_spring(to_cpp(joint), q(hertz), q(damping_ratio))); });
}
tandem_status tandem_joint_set_length(tandem_joint_id joint, tandem_q32 length) {
  return guard("tandem_joint_set_length", [&] { return status(joint_set_length(to_cpp(joint), q(length))); });
}
tandem_status tandem_joint_set_target(tandem_joint_id joint, tandem_vec2 target) {
  return guard("tandem_joint_set_target", [&] { return status(joint_set_target(to_cpp(joint), to_cpp(target))); });
}
tandem_status tandem_joint_set_offsets(tandem_joint_id joint, tandem_vec2 linear_offset, tandem_q32 angular_offset) {
  return guard("tandem_joint_set_offsets",
               [&] { return status(joint_set_offsets(to_cpp(joint), to_cpp(linear_offset), q(angular_offset))); });
}
tandem_status tandem_joint_set_break_thresholds(tandem_joint_id joint, tandem_q32 force, tandem_q32 torque) {
  return guard("tandem_joint_set_break_thresholds",
               [&] { return status(joint_set_break_thresholds(to_cpp(joint), q(force), q(torque))); });
}

// --- events ----------------------------------------------------------------------------------
tandem_status tandem_world_joint_events(tandem_world_id world, tandem_joint_event* out_events, int32_t capacity,
                                        int32_t* out_count) {
  static const char* fn = "tandem_world_joint_events";
  return guard(fn, [&] {
    const Result<std::span<const JointEvent>> r = world_joint_events(to_cpp(world));
    if (!r.ok()) return status(r.status);
    return fill(fn, r.value, out_events, capacity, out_count, [](const JointEvent& e) {
      tandem_joint_event o;
      std::memset(&o, 0, sizeof o);
      o.joint = to_c(e.joint);
      o.body_a = to_c(e.body_a);
      o.body_b = to_c(e.body_b);
      o.kind = static_cast<int32_t>(e.kind);
      o.force = to_c(e.force);
      o.torque = e.torque.raw;
      o.user_data = e.user_data;
      return o;
    });
  });
}
