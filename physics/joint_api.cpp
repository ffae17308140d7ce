// joint_api.cpp — the joint queries and setters of joint.h (creation and
// destruction are joint.cpp, the solver joint_solver.cpp).
//
// Getters return a neutral fallback for a stale handle; every setter resolves
// the handle (refusing null, stale, foreign and locked), checks every value on
// a copy of the joint, and only then stores it and wakes both bodies: a
// refused call changes nothing.
#include "physics/island.h"
#include "physics/world.h"

namespace tandem {

using joint_detail::check_angle;
using joint_detail::check_order;
using joint_detail::check_range;
using joint_detail::check_vec;
using joint_detail::joint_at;
using joint_detail::q;
using joint_detail::resolve_joint;

namespace {

bool find_joint(JointId id, World** out_world, int32_t* out_index) {
  return find_handle(id.index1, id.generation, id.world, &World::joint_pool, out_world, out_index);
}

template <typename T, typename F>
T get_joint(JointId id, T fallback, F f) {
  World* w = nullptr;
  int32_t i = 0;
  if (!find_joint(id, &w, &i)) return fallback;
  return f(*w, joint_at(w, i));
}

/// Resolves, runs `change` on a copy, and stores the copy when ok; wakes the
/// bodies.
template <typename F>
Status set_joint(JointId id, const char* function, F change) {
  World* w = nullptr;
  int32_t i = 0;
  Status s = resolve_joint(id, function, true, &w, &i);
  if (!s.ok()) return s;
  Joint copy = joint_at(w, i);
  s = change(*w, &copy);
  if (!s.ok()) return s;
  joint_at(w, i) = copy;
  wake_body_island(w, copy.body_a);
  wake_body_island(w, copy.body_b);
  return s;
}

Status wrong_kind(const char* function, JointId id, const char* what) {
  return make_status(StatusCode::invalid_argument,
                     std::string(function) + ": " + describe(id) + " is a kind of joint without " + what);
}

Q32 joint_frame_angle(const World& w, const Joint& j) {
  const Rot qa = w.body_sims[static_cast<size_t>(j.body_a)].transform.q;
  const Rot qb = w.body_sims[static_cast<size_t>(j.body_b)].transform.q;
  return relative_angle(qa, qb);
}

}  // namespace

// ---------------------------------------------------------------------------
// Queries
// ---------------------------------------------------------------------------

bool joint_is_valid(JointId id) {
  World* w = nullptr;
  int32_t i = 0;
  return find_joint(id, &w, &i);
}

Status joint_check(JointId id) {
  World* w = nullptr;
  int32_t i = 0;
  return resolve_joint(id, "joint_check", false, &w, &i);
}

JointType joint_type(JointId id) {
  return get_joint(id, JointType::revolute, [](const World&, const Joint& j) { return j.type; });
}
BodyId joint_body_a(JointId id) {
  return get_joint(id, BodyId{}, [](const World& w, const Joint& j) { return make_body_id(w, j.body_a); });
}
BodyId joint_body_b(JointId id) {
  return get_joint(id, BodyId{}, [](const World& w, const Joint& j) { return make_body_id(w, j.body_b); });
}
uint64_t joint_user_data(JointId id) {
  return get_joint(id, uint64_t{0}, [](const World&, const Joint& j) { return j.user_data; });
}
Vec2 joint_reaction_force(JointId id) {
  return get_joint(id, Vec2{}, [](const World&, const Joint& j) { return j.reaction_force; });
}
Q32 joint_reaction_torque(JointId id) {
  return get_joint(id, Q32::zero(), [](const World&, const Joint& j) { return j.reaction_torque; });
}

Vec2 joint_world_anchor_a(JointId id) {
  return get_joint(id, Vec2{}, [](const World& w, const Joint& j) {
    if (j.type == JointType::mouse) return j.target;
    return transform_point(w.body_sims[static_cast<size_t>(j.body_a)].transform, j.local_anchor_a);
  });
}

Vec2 joint_world_anchor_b(JointId id) {
  return get_joint(id, Vec2{}, [](const World& w, const Joint& j) {
    return transform_point(w.body_sims[static_cast<size_t>(j.body_b)].transform, j.local_anchor_b);
  });
}

Q32 joint_angle(JointId id) {
  return get_joint(id, Q32::zero(), [](const World& w, const Joint& j) {
    if (j.type == JointType::distance || j.type == JointType::mouse || j.type == JointType::motor) return Q32::zero();
    const Q32 a = joint_frame_angle(w, j) - j.reference_angle;
    // Back into [−π, π].
    if (a > k_pi) return a - k_two_pi;
    if (a < -k_pi) return a + k_two_pi;
    return a;
  });
}

Q32 joint_translation(JointId id) {
  return get_joint(id, Q32::zero(), [](const World& w, const Joint& j) {
    const Transform ta = w.body_sims[static_cast<size_t>(j.body_a)].transform;
    const Transform tb = w.body_sims[static_cast<size_t>(j.body_b)].transform;
    const Vec2 d = transform_point(tb, j.local_anchor_b) - transform_point(ta, j.local_anchor_a);
    if (j.type == JointType::distance) return length(d);
    if (j.type == JointType::prismatic || j.type == JointType::wheel) return dot(d, rotate(ta.q, j.local_axis_a));
    return Q32::zero();
  });
}

int32_t world_joints(WorldId world, JointId* out_ids, int32_t capacity) {
  const World* w = find_world(world);
  if (w == nullptr) return 0;
  int32_t n = 0;
  const int32_t end = id_pool_capacity(w->joint_pool);
  for (int32_t i = 0; i < end; ++i) {
    if (!id_pool_is_alive(w->joint_pool, i)) continue;
    if (n < capacity && out_ids != nullptr) out_ids[n] = make_joint_id(*w, i);
    ++n;
  }
  return n;
}

int32_t body_joints(BodyId body, JointId* out_ids, int32_t capacity) {
  World* w = nullptr;
  int32_t b = 0;
  if (!find_body(body, &w, &b)) return 0;
  int32_t n = 0;
  const int32_t end = id_pool_capacity(w->joint_pool);
  for (int32_t i = 0; i < end; ++i) {
    if (!id_pool_is_alive(w->joint_pool, i)) continue;
    const Joint& j = w->joints.joints[static_cast<size_t>(i)];
    if (j.body_a != b && j.body_b != b) continue;
    if (n < capacity && out_ids != nullptr) out_ids[n] = make_joint_id(*w, i);
    ++n;
  }
  return n;
}

// ---------------------------------------------------------------------------
// Setters
// ---------------------------------------------------------------------------

namespace {

bool has_motor(JointType t) {
  return t == JointType::revolute || t == JointType::prismatic || t == JointType::wheel || t == JointType::distance;
}
bool has_limit(JointType t) { return has_motor(t); }
bool has_spring(JointType t) { return has_motor(t); }
bool angular_motor(JointType t) { return t == JointType::revolute || t == JointType::wheel; }

}  // namespace

Status joint_enable_motor(JointId id, bool enable) {
  return set_joint(id, "joint_enable_motor", [&](const World&, Joint* j) {
    if (!has_motor(j->type)) return wrong_kind("joint_enable_motor", id, "a motor");
    j->enable_motor = enable;
    return Status{};
  });
}

Status joint_set_motor_speed(JointId id, Q32 speed) {
  const char* fn = "joint_set_motor_speed";
  return set_joint(id, fn, [&](const World&, Joint* j) {
    if (!has_motor(j->type)) return wrong_kind(fn, id, "a motor");
    Status s;
    const bool angular = angular_motor(j->type);
    const Q32 lim = angular ? k_max_angular_speed : k_max_linear_speed;
    if (!check_range(fn, "joint", "motor_speed", speed, -lim, lim, angular ? "rad/s" : "m/s", &s)) return s;
    j->motor_speed = speed;
    return s;
  });
}

Status joint_set_max_motor_force(JointId id, Q32 force) {
  const char* fn = "joint_set_max_motor_force";
  return set_joint(id, fn, [&](const World&, Joint* j) {
    if (!has_motor(j->type)) return wrong_kind(fn, id, "a motor");
    Status s;
    const bool angular = angular_motor(j->type);
    if (!check_range(fn, "joint", angular ? "max_motor_torque" : "max_motor_force", force, Q32::zero(),
                     angular ? k_max_joint_torque : k_max_joint_force, angular ? "N·m" : "N", &s)) {
      return s;
    }
    j->max_motor_force = force;
    return s;
  });
}

Status joint_enable_limit(JointId id, bool enable) {
  return set_joint(id, "joint_enable_limit", [&](const World&, Joint* j) {
    if (!has_limit(j->type)) return wrong_kind("joint_enable_limit", id, "limits");
    j->enable_limit = enable;
    return Status{};
  });
}

Status joint_set_limits(JointId id, Q32 lower, Q32 upper) {
  const char* fn = "joint_set_limits";
  return set_joint(id, fn, [&](const World&, Joint* j) {
    if (!has_limit(j->type)) return wrong_kind(fn, id, "limits");
    Status s;
    if (j->type == JointType::revolute) {
      if (!check_angle(fn, "joint", "lower", lower, &s) || !check_angle(fn, "joint", "upper", upper, &s)) return s;
    } else if (j->type == JointType::distance) {
      if (!check_range(fn, "joint", "upper (max_length)", upper, k_min_joint_length, k_max_joint_length, "m", &s) ||
          !check_range(fn, "joint", "lower (min_length)", lower, Q32::zero(), upper, "m", &s)) {
        return s;
      }
    } else if (!check_range(fn, "joint", "lower", lower, -k_max_joint_length, k_max_joint_length, "m", &s) ||
               !check_range(fn, "joint", "upper", upper, -k_max_joint_length, k_max_joint_length, "m", &s)) {
      return s;
    }
    if (!check_order(fn, "joint", "lower", lower, "upper", upper, &s)) return s;
    j->lower = lower;
    j->upper = upper;
    return s;
  });
}

Status joint_enable_spring(JointId id, bool enable) {
  return set_joint(id, "joint_enable_spring", [&](const World&, Joint* j) {
    if (!has_spring(j->type)) return wrong_kind("joint_enable_spring", id, "a spring");
    j->enable_spring = enable;
    return Status{};
  });
}

Status joint_set_spring(JointId id, Q32 hertz, Q32 damping_ratio) {
  const char* fn = "joint_set_spring";
  return set_joint(id, fn, [&](const World&, Joint* j) {
    if (!has_spring(j->type) && j->type != JointType::weld && j->type != JointType::mouse) {
      return wrong_kind(fn, id, "a spring");
    }
    Status s;
    const Q32 lo = j->type == JointType::mouse ? Q32::epsilon() : Q32::zero();
    if (!check_range(fn, "joint", "hertz", hertz, lo, k_max_joint_hertz, "Hz", &s) ||
        !check_range(fn, "joint", "damping_ratio", damping_ratio, Q32::zero(), k_max_joint_damping_ratio, "", &s)) {
      return s;
    }
    j->hertz = hertz;
    j->damping_ratio = damping_ratio;
    return s;
  });
}

Status joint_set_length(JointId id, Q32 length) {
  const char* fn = "joint_set_length";
  return set_joint(id, fn, [&](const World&, Joint* j) {
    if (j->type != JointType::distance) return wrong_kind(fn, id, "a length");
    Status s;
    if (!check_range(fn, "joint", "length", length, k_min_joint_length, k_max_joint_length, "m", &s)) return s;
    j->length = length;
    return s;
  });
}

Status joint_set_target(JointId id, Vec2 target) {
  const char* fn = "joint_set_target";
  return set_joint(id, fn, [&](const World& w, Joint* j) {
    if (j->type != JointType::mouse) return wrong_kind(fn, id, "a target");
    if (!aabb_contains_point(w.def.bounds, target)) {
      return make_status(StatusCode::invalid_argument,
                         std::string(fn) + ": target " + format_vec2(target) + " m is outside the world bounds");
    }
    j->target = target;
    return Status{};
  });
}

Status joint_set_offsets(JointId id, Vec2 linear_offset, Q32 angular_offset) {
  const char* fn = "joint_set_offsets";
  return set_joint(id, fn, [&](const World&, Joint* j) {
    if (j->type != JointType::motor) return wrong_kind(fn, id, "offsets");
    Status s;
    if (!check_vec(fn, "joint", "linear_offset", linear_offset, k_max_shape_size, "m", &s) ||
        !check_angle(fn, "joint", "angular_offset", angular_offset, &s)) {
      return s;
    }
    j->target = linear_offset;
    j->angular_offset = angular_offset;
    return s;
  });
}

Status joint_set_break_thresholds(JointId id, Q32 force, Q32 torque) {
  const char* fn = "joint_set_break_thresholds";
  return set_joint(id, fn, [&](const World&, Joint* j) {
    Status s;
    if (!check_range(fn, "joint", "break_force", force, Q32::zero(), k_max_joint_force, "N", &s) ||
        !check_range(fn, "joint", "break_torque", torque, Q32::zero(), k_max_joint_torque, "N·m", &s)) {
      return s;
    }
    j->break_force = force;
    j->break_torque = torque;
    return s;
  });
}

}  // namespace tandem
