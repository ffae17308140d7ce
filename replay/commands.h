// commands.h — engine commands as plain data: what a game does to a world
// between two steps, in a form that can be recorded in a replay, sent to a
// peer, and applied again to give the same bits.
//
// DESIGN. A Command is one tagged plain struct (CommandType + the fields that
// type uses; the others stay at their defaults and are not encoded), not a
// std::variant or a class hierarchy: a scene loader, a network layer and a
// test can build one with the make_* helpers or by filling fields, and the
// encoding below names every field it writes. Bodies are addressed by
// BodyRef {index, generation} — the parts of a BodyId without the world —
// because a replay is applied to a different WorldId than the one it was
// recorded on; ids are allocated lowest-free-index first (tandem.h), so the
// same commands in the same order create the same refs on every machine.
//
// User input payloads (CommandType::user_input) are opaque bytes defined by
// the game: apply_command() ignores them; replay verification hands them to
// an optional callback that turns them into engine commands.
//
// ERRORS. apply_command() returns the engine's Status with the message
// prefixed by the command and the body ("set_linear_velocity body {index 3,
// generation 1}: ..."). create_body with shapes validates every shape's
// geometry before creating the body; if a shape is still refused after the
// body exists (mass limits), the body is destroyed again — the world is as
// before except that the body slot's generation has advanced (deterministic,
// so a replay that re-applies the same failing command stays in step).
//
// ENCODING (little-endian, replay/bytes.h). One command:
//   u8  type (CommandType, 1…19)
//   then by type:
//   create_body:        BodyDef, u32 shape count (≤ k_max_command_shapes), each ShapeSpec
//   destroy_body:       BodyRef
//   apply_force,
//   apply_linear_impulse: BodyRef, vec2 vector (N / N·s), u8 at_center (0/1),
//                       vec2 point (m; present only when at_center is 0), u8 wake
//   apply_torque,
//   apply_angular_impulse: BodyRef, q32 scalar (N·m / N·m·s), u8 wake
//   set_linear_velocity: BodyRef, vec2 vector (m/s)
//   set_angular_velocity: BodyRef, q32 scalar (rad/s)
//   set_transform:      BodyRef, vec2 vector (position, m), rot rotation (c, s)
//   set_awake, set_enabled: BodyRef, u8 flag
//   set_gravity:        vec2 vector (m/s²)
//   user_input:         u32 byte count (≤ k_max_user_payload_bytes), bytes
//   create_joint:       JointSpec = u8 type (JointType 0…6), BodyRef a, BodyRef b,
//                       vec2 anchor a, vec2 anchor b, u8 collide_connected,
//                       q32 break_force, q32 break_torque, u64 user_data,
//                       vec2 axis, q32 reference_angle, u8 enable_spring,
//                       u8 enable_limit, u8 enable_motor, q32 hertz,
//                       q32 damping_ratio, q32 angular_hertz,
//                       q32 angular_damping_ratio, q32 length, q32 lower,
//                       q32 upper, q32 motor_speed, q32 motor_force,
//                       vec2 target, q32 angular_offset, q32 max_force,
//                       q32 max_torque, q32 correction_factor
//   destroy_joint:      JointRef (u32 index, u32 generation)
//   set_joint_motor_speed, set_joint_length: JointRef, q32
//   set_joint_target:   JointRef, vec2
//   set_joint_limits:   JointRef, q32 lower, q32 upper
//   enable_joint_motor, enable_joint_limit, enable_joint_spring: JointRef, u8 flag
//   set_joint_max_motor_force: JointRef, q32 (N or N·m)
//   set_joint_spring:   JointRef, q32 hertz, q32 damping_ratio
//   set_joint_offsets:  JointRef, vec2 linear_offset, q32 angular_offset
//   set_joint_break_thresholds: JointRef, q32 force, q32 torque
// BodyRef = u32 index, u32 generation. vec2 = q32 x, q32 y; q32 = i64 raw;
// rot = q32 c, q32 s.
// BodyDef = u8 type (0…2), vec2 position, rot rotation, vec2 linear_velocity,
//   q32 angular_velocity, q32 linear_damping, q32 angular_damping,
//   q32 gravity_scale, u64 user_data, u8 enable_sleep, u8 is_awake,
//   u8 fixed_rotation, u8 is_bullet, u8 is_enabled (decoded into
//   default_body_def(), so the cookie is set).
// ShapeSpec = u8 kind (ShapeKind 0…4), ShapeDef, geometry:
//   ShapeDef = q32 friction, q32 restitution, q32 density, u64 category_bits,
//     u64 mask_bits, i32 group_index, u64 user_data, u8 is_sensor,
//     u8 enable_hit_events
//   circle: vec2 center, q32 radius
//   capsule: vec2 center1, vec2 center2, q32 radius
//   segment: vec2 point1, vec2 point2
//   polygon: u8 count (3…8), count × vec2 vertex, count × vec2 normal,
//     vec2 centroid, q32 radius (exact bits; create_polygon_shape validates)
//   chain: u32 point count (≤ k_max_chain_points), points × vec2, u8 loop
// Rejected: encoding a Polygon from its hull points and rebuilding it with
// make_polygon on decode — exact, but it would make the decoded polygon
// depend on make_polygon's rounding staying the same across versions.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "physics/tandem.h"
#include "replay/bytes.h"

namespace tandem {

/// The kinds of command (values are the encoded type byte; never reorder).
enum class CommandType : uint8_t {
  create_body = 1,
  destroy_body = 2,
  apply_force = 3,
  apply_torque = 4,
  apply_linear_impulse = 5,
  apply_angular_impulse = 6,
  set_linear_velocity = 7,
  set_angular_velocity = 8,
  set_transform = 9,
  set_awake = 10,
  set_enabled = 11,
  set_gravity = 12,
  user_input = 13,
  // Joints (replay/joint_commands.cpp).
  create_joint = 14,
  destroy_joint = 15,
  set_joint_motor_speed = 16,
  set_joint_target = 17,
  set_joint_length = 18,
  set_joint_limits = 19,
  enable_joint_motor = 20,
  set_joint_max_motor_force = 21,
  enable_joint_limit = 22,
  enable_joint_spring = 23,
  set_joint_spring = 24,
  set_joint_offsets = 25,
  set_joint_break_thresholds = 26,
};

/// The last command type (decoders accept 1…k_last_command_type).
inline constexpr uint8_t k_last_command_type = 26;

/// Most shapes in one create_body command.
inline constexpr uint32_t k_max_command_shapes = 1u << 16;
/// Most points in one chain shape.
inline constexpr uint32_t k_max_chain_points = 1u << 20;
/// Most bytes in one user input payload.
inline constexpr uint32_t k_max_user_payload_bytes = 1u << 24;

/// A body named by its pool index and generation in whatever world the
/// command is applied to (BodyId without the world).
struct BodyRef {
  uint32_t index = 0;       ///< body index (BodyId::index1 − 1)
  uint32_t generation = 0;  ///< slot generation, ≥ 1 for a live body
  friend constexpr bool operator==(BodyRef, BodyRef) = default;
};

/// The BodyRef of a body handle.
constexpr BodyRef body_ref(BodyId id) { return BodyRef{id.index1 - 1, id.generation}; }
/// The handle of a ref in `world`.
constexpr BodyId body_id(WorldId world, BodyRef ref) { return BodyId{ref.index + 1, ref.generation, world}; }

/// A joint named by its pool index and generation (JointId without the world).
struct JointRef {
  uint32_t index = 0;       ///< joint index (JointId::index1 − 1)
  uint32_t generation = 0;  ///< slot generation, ≥ 1 for a live joint
  friend constexpr bool operator==(JointRef, JointRef) = default;
};

/// The JointRef of a joint handle.
constexpr JointRef joint_ref(JointId id) { return JointRef{id.index1 - 1, id.generation}; }
/// The handle of a ref in `world`.
constexpr JointId joint_id(WorldId world, JointRef ref) { return JointId{ref.index + 1, ref.generation, world}; }

/// A joint of any kind for a create_joint command: the kind, its two bodies
/// and every setting a joint definition can carry (the kind's create
/// function reads the fields its definition has; see joint.h for units and
/// ranges: `lower`/`upper` are the angle, translation or min/max length
/// limits, `motor_force` the max motor force or torque, `target` the mouse
/// target or the motor joint's linear offset, `hertz`/`damping_ratio` the
/// spring or weld linear stiffness).
struct JointSpec {
  JointType type = JointType::revolute;
  BodyRef body_a, body_b;
  Vec2 local_anchor_a, local_anchor_b;
  bool collide_connected = false;
  Q32 break_force, break_torque;
  uint64_t user_data = 0;
  Vec2 local_axis{Q32::one(), Q32::zero()};
  Q32 reference_angle;
  bool enable_spring = false, enable_limit = false, enable_motor = false;
  Q32 hertz, damping_ratio, angular_hertz, angular_damping_ratio;
  Q32 length = Q32::one();
  Q32 lower, upper;
  Q32 motor_speed, motor_force;
  Vec2 target;
  Q32 angular_offset, max_force, max_torque, correction_factor;
  friend bool operator==(const JointSpec&, const JointSpec&) = default;
};

/// The geometry kinds a create_body command can attach.
enum class ShapeKind : uint8_t { circle = 0, capsule = 1, segment = 2, polygon = 3, chain = 4 };

/// One shape of a create_body command: its definition and its geometry (the
/// field that matches `kind`; body frame, m).
struct ShapeSpec {
  ShapeKind kind = ShapeKind::circle;
  ShapeDef def = default_shape_def();
  Circle circle;
  Capsule capsule;
  Segment segment;
  Polygon polygon;               ///< made by make_polygon / make_box*
  std::vector<Vec2> chain_points;  ///< chain: see create_chain_shapes
  bool chain_loop = false;
};

/// One engine command or user input (see the file comment for which fields
/// each type uses).
struct Command {
  CommandType type = CommandType::set_gravity;
  BodyRef body;                  ///< every body command
  BodyDef body_def = default_body_def();  ///< create_body
  std::vector<ShapeSpec> shapes;  ///< create_body, attached in order
  Vec2 vector;    ///< force (N), linear impulse (N·s), linear velocity (m/s), position (m), gravity (m/s²)
  Vec2 point;     ///< world point of a force / impulse, m (unless at_center)
  bool at_center = true;  ///< force / linear impulse at the centre of mass
  Q32 scalar;     ///< torque (N·m), angular impulse (N·m·s), angular velocity (rad/s)
  Rot rotation;   ///< set_transform
  bool flag = true;  ///< wake (forces, impulses), awake (set_awake), enabled (set_enabled)
  std::vector<uint8_t> payload;  ///< user_input: bytes defined by the game
  JointRef joint;     ///< joint commands but create_joint
  JointSpec joint_spec;  ///< create_joint
  Q32 scalar2;        ///< set_joint_limits: upper (scalar is lower)
};

/// Field-by-field equality (only the fields the type uses).
bool operator==(const Command& a, const Command& b);

/// The command type's name ("create_body", "apply_force", ...; "unknown").
const char* command_type_name(CommandType type);
/// "apply_force body {index 3, generation 1}" / "set_gravity" / "user_input (12 bytes)".
std::string describe(const Command& command);

// --- builders ---------------------------------------------------------------
/// A create_body command.
Command make_create_body(const BodyDef& def, std::vector<ShapeSpec> shapes);
/// A destroy_body command.
Command make_destroy_body(BodyRef body);
/// A force (N) at a world point (m).
Command make_apply_force(BodyRef body, Vec2 force, Vec2 world_point, bool wake = true);
/// A force (N) at the centre of mass.
Command make_apply_force_to_center(BodyRef body, Vec2 force, bool wake = true);
/// A torque (N·m).
Command make_apply_torque(BodyRef body, Q32 torque, bool wake = true);
/// A linear impulse (N·s) at a world point (m).
Command make_apply_linear_impulse(BodyRef body, Vec2 impulse, Vec2 world_point, bool wake = true);
/// A linear impulse (N·s) at the centre of mass.
Command make_apply_linear_impulse_to_center(BodyRef body, Vec2 impulse, bool wake = true);
/// An angular impulse (N·m·s).
Command make_apply_angular_impulse(BodyRef body, Q32 impulse, bool wake = true);
/// Sets the linear velocity (m/s).
Command make_set_linear_velocity(BodyRef body, Vec2 velocity);
/// Sets the angular velocity (rad/s).
Command make_set_angular_velocity(BodyRef body, Q32 angular_velocity);
/// Teleports the body origin (m) and rotation.
Command make_set_transform(BodyRef body, Vec2 position, Rot rotation);
/// Wakes the body or puts it to sleep.
Command make_set_awake(BodyRef body, bool awake);
/// Enables or disables the body.
Command make_set_enabled(BodyRef body, bool enabled);
/// Sets the world's gravity (m/s²).
Command make_set_gravity(Vec2 gravity);
/// An opaque user input payload.
Command make_user_input(std::vector<uint8_t> payload);
/// Creates a joint (JointSpec).
Command make_create_joint(const JointSpec& spec);
/// Destroys a joint.
Command make_destroy_joint(JointRef joint);
/// joint_set_motor_speed (rad/s or m/s).
Command make_set_joint_motor_speed(JointRef joint, Q32 speed);
/// joint_set_target (mouse joint, m).
Command make_set_joint_target(JointRef joint, Vec2 target);
/// joint_set_length (distance joint rest length, m).
Command make_set_joint_length(JointRef joint, Q32 length);
/// joint_set_limits (rad or m; a rope's min and max length).
Command make_set_joint_limits(JointRef joint, Q32 lower, Q32 upper);
/// joint_enable_motor.
Command make_enable_joint_motor(JointRef joint, bool enable);
/// joint_set_max_motor_force (N, or N·m for revolute and wheel joints).
Command make_set_joint_max_motor_force(JointRef joint, Q32 force_or_torque);
/// joint_enable_limit.
Command make_enable_joint_limit(JointRef joint, bool enable);
/// joint_enable_spring.
Command make_enable_joint_spring(JointRef joint, bool enable);
/// joint_set_spring (Hz, dimensionless damping ratio).
Command make_set_joint_spring(JointRef joint, Q32 hertz, Q32 damping_ratio);
/// joint_set_offsets (motor joint: m in body A's frame, rad).
Command make_set_joint_offsets(JointRef joint, Vec2 linear_offset, Q32 angular_offset);
/// joint_set_break_thresholds (N, N·m; 0 = never breaks).
Command make_set_joint_break_thresholds(JointRef joint, Q32 force, Q32 torque);

// Joint commands, shared with commands.cpp (joint_commands.cpp).
/// Applies a joint command (types create_joint…set_joint_break_thresholds).
Status apply_joint_command(WorldId world, const Command& command);
/// Encodes the fields of a joint command after its type byte.
void encode_joint_command(ByteWriter& writer, const Command& command);
/// Decodes the fields of a joint command after its type byte.
bool decode_joint_command(ByteReader& reader, Command* out_command);
/// Equality of the fields a joint command uses.
bool equal_joint_command(const Command& a, const Command& b);
/// True for the joint command types.
constexpr bool is_joint_command(CommandType t) {
  return static_cast<uint8_t>(t) >= static_cast<uint8_t>(CommandType::create_joint) &&
         static_cast<uint8_t>(t) <= k_last_command_type;
}

// --- applying -----------------------------------------------------------------
/// Applies an engine command to `world` through the public API (tandem.h).
/// user_input does nothing (ok). On failure returns the engine's status with
/// the message prefixed by describe(command); see the file comment for what
/// a failed create_body leaves behind. create_body writes the new body's
/// handle to *out_created when given (null handle on failure).
Status apply_command(WorldId world, const Command& command, BodyId* out_created = nullptr);

// --- encoding -----------------------------------------------------------------
/// Appends the encoding of `command` (see the file comment).
void encode_command(ByteWriter& writer, const Command& command);
/// Reads one command from *reader (advanced past it). On malformed input
/// returns invalid_argument whose message is the reader's error ("offset N:
/// expected ..."); the reader stays failed and *out_command is unspecified.
Status decode_command(ByteReader* reader, Command* out_command);
/// Reads a u32 count then that many commands (each at least 5 bytes) into
/// *out_commands (replaced); errors as decode_command.
Status decode_commands(ByteReader* reader, std::vector<Command>* out_commands);
/// Deprecated (removed next release): the bool forms; use the Status ones.
[[deprecated("use decode_command(&reader, out), which returns a Status")]] inline bool decode_command(
    ByteReader& reader, Command* out_command) {
  return decode_command(&reader, out_command).ok();
}
[[deprecated("use decode_commands(&reader, out), which returns a Status")]] inline bool decode_commands(
    ByteReader& reader, std::vector<Command>* out_commands) {
  return decode_commands(&reader, out_commands).ok();
}
/// Writes a u32 count then the commands.
void encode_commands(ByteWriter& writer, std::span<const Command> commands);

}  // namespace tandem
