// state.h — the canonical encoding of a world's state: snapshot, restore,
// hash, decode and diff.
//
// WHAT IS ENCODED: everything that can change a later tick or a later query.
//   header    magic "TNDS", format version (k_state_format_version), kind (0)
//   world     WorldDef (every field but the cookie: broad-phase kind and
//             continuous collision included), step count, the last step's
//             simulated body count
//   pools     body and shape pools: capacity, then per slot generation and
//             alive flag. The free list is NOT stored: IdPool hands out the
//             lowest free slot (id_pool.h), so the free set — hence every
//             future allocation — follows from the alive flags
//   bodies    per live body, ascending index: Body (type, shape list head and
//             count, mass, inertia, sleep timer, sleep island, user data,
//             flags, shape extents for continuous collision) then BodySim (pose, centres, velocities, pending force
//             and torque, inverse mass and inertia, damping, gravity scale)
//   shapes    per live shape, ascending index: body, list links, type,
//             materials, filter, user data, world AABB, flags, then the
//             geometry of its type only (polygon: `count` vertices and normals)
//   contacts  World::contacts in their (sorted) order: shapes, generations,
//             bodies, flags, mixed materials, manifold (normal, point_count
//             points with feature ids) and the points' warm-start impulses
//   pairs     the touching pairs and sensor overlaps of the last step (they
//             decide the next step's begin/end events)
//   joints    (version 2 only, see k_state_format_version_joints) joint pool
//             slots, then per live joint its settings, warm-start impulses
//             and last reaction
//   events    (version 3 only) joint events waiting for the next step
//             (joints destroyed with a body since the last step)
// NOT encoded: scratch (arena, step context, contact scratch, the last step's
// event lists — empty after a restore until the next step), dead slots' stale
// records (reset to defaults on restore, as destroy does), polygon entries
// past `count`, inactive geometry variants, and the broad phase, whose output
// depends only on the shapes by contract (broad_phase.h): restore calls
// broad_phase_reset(). The custom collision filter (a function pointer) is
// not state: restore keeps the target world's, and a peer must install the
// same one (create_world_from_snapshot starts without one).
//
// FORMAT. Explicit little-endian (replay/bytes.h): u8/u32/u64/i32/i64 as
// such, Q32 as its raw int64, bools as one byte 0/1, Vec2 as x, y. Each
// section starts with a 4-byte ASCII tag ("WRLD", "BPOL", "BODY", "SPOL",
// "SHAP", "CONT", "TUCH", "SENS") so a corrupt image fails near the damage.
// Nothing depends on struct layout, padding, host endianness or addresses.
// Field order is defined once, by physics (physics/state_fields.h, reached
// through physics/state_access.h): one field list per record drives
// encoding, size, decoding and the named-field decoding used by diffs, so
// the four can never disagree.
//
// RESTORE decodes the whole image into scratch, validates it and only then
// replaces the world's state, so a refused image leaves the world untouched.
//   Structure: enum values, index ranges, shape lists consistent with
//   bodies, contacts sorted, no raw INT64_MIN, non-degenerate radii and
//   segments, nothing left over; every count is checked against the bytes
//   left before anything is allocated for it.
//   Values: every field against the limits the API enforces when the value
//   enters a world (limits.h, tandem.h: world settings, positions, speeds,
//   damping, forces, materials, geometry reach, sleep timers), widened only
//   where a legal step carries a value past its entry limit: linear speeds
//   after a contact solve ×4; a body that left the bounds (then disabled)
//   within ±2·k_max_world_coordinate; |ω| above 4·k_max_angular_speed only
//   while the rim speed |ω|·max_extent stays within 4·k_max_linear_speed.
//   Stored contact impulses within ±4e8 N·s per point and, summed over a
//   body's contacts, a warm-start velocity change (also at the rim) within
//   2^27 m/s. Rotations and normals unit within 2^-16.
//   Derived values: shape bounds, body mass, inertia, their inverses, the
//   centre of mass (local and world) and the continuous-collision extents
//   are recomputed from the image and must match bit for bit, so a crafted
//   image cannot feed the broad phase an inverted box or the solver a mass
//   its shapes do not have.
// A refusal names the byte offset, the record ("body 12", "shape 3",
// "contact 5 (shapes 2, 9)", "world"), the field, its value and the allowed
// range. Within these limits no arithmetic path wraps or saturates, so every
// build (x86-64 release, portable 128-bit, debug) computes the same bits from
// an accepted image. Handles stay valid: indices, generations and alive
// flags are those of the snapshot. Memory: a pool slot costs 5 image bytes
// but a full record in the restored world (about 600 bytes per shape slot),
// so an image of n bytes can make restore allocate up to ~120·n bytes (the
// size of the world it describes; pools are capped at k_max_bodies and
// k_max_shapes).
//
// HASH: XXH3-64 (seed 0) of the canonical encoding. Per-body hashes cover one
// body's record followed by its shapes' records (the same bytes as in the
// full encoding), so peers can locate a divergence without shipping state.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "physics/tandem.h"

namespace tandem {

/// The version of images of worlds that never had a joint (the format before
/// joints, byte for byte, so their hashes did not change).
inline constexpr uint32_t k_state_format_version = 1;
/// The version of images of worlds with joint slots: version 1 followed by
/// the joint sections "JPOL" (joint pool) and "JOIN" (per live joint,
/// ascending index: kind, bodies, anchors, axis, settings, accumulated
/// impulses, last reaction). Both versions are read.
inline constexpr uint32_t k_state_format_version_joints = 2;
/// The version of images taken while joint events wait for the next step
/// (joints destroyed with a body since the last step; that step reports
/// them): version 2 followed by "JEVP" (u32 count, then per event the joint's
/// and both bodies' index1 and generation, kind, force, torque, user data).
/// Images taken right after a step never have pending events, so their
/// bytes and hashes stay those of version 2. Versions 1, 2 and 3 are read.
inline constexpr uint32_t k_state_format_version_joint_events = 3;

/// The 4 magic bytes at the start of every state image.
inline constexpr uint8_t k_state_magic[4] = {'T', 'N', 'D', 'S'};

/// Replaces *out with the canonical encoding of the world's state (see the
/// file comment). Refuses an invalid world handle and a locked world (inside
/// world_step the state is mid-update); *out is unchanged then.
Status encode_world_state(WorldId world, std::vector<uint8_t>* out);

/// The exact size in bytes of the world's encoding, or 0 for an invalid
/// world handle.
size_t world_snapshot_size(WorldId world);

/// Writes the world's encoding into buffer[0, capacity) and sets *written to
/// its size. With capacity < world_snapshot_size(world) nothing is written
/// beyond the capacity, *written is the needed size and the status is
/// capacity_exceeded (its message names the needed size). Refuses an invalid
/// or locked world. `written` may be null.
Status world_snapshot(WorldId world, uint8_t* buffer, size_t capacity, size_t* written);

/// Appends the world's encoding to *out (existing bytes kept).
Status world_snapshot_append(WorldId world, std::vector<uint8_t>* out);

/// Replaces all of the world's state with a state image (from
/// encode_world_state / world_snapshot of this or another world). Refuses an
/// invalid or locked world, a wrong magic or version, and truncated,
/// inconsistent or trailing data, with a message naming the byte offset and
/// what was expected there; on any refusal the world is unchanged. After a
/// restore every later step is bit-identical to the run the image came from,
/// and handles of that run are valid in this world (same indices and
/// generations; world handle: this world's).
Status world_restore(WorldId world, const uint8_t* data, size_t size);

/// Creates a world (create_world(default_world_def())) and restores the image
/// into it; on failure the new world is destroyed and the status says why.
Result<WorldId> create_world_from_snapshot(const uint8_t* data, size_t size);

/// XXH3-64 of the world's canonical encoding; 0 for an invalid or locked
/// world. Allocation-free once the calling thread's scratch buffer has grown.
/// The broad-phase kind is hashed as naive (it changes no result), so the
/// hash of a tick is the same whichever broad phase computed it.
uint64_t world_state_hash(WorldId world);

/// XXH3-64 of one body's record followed by its shapes' records (ascending
/// shape index), as encoded in the full image; 0 for an invalid body.
uint64_t body_state_hash(BodyId body);

/// body_state_hash of every body slot in index order into *out (resized to
/// the body pool's capacity); dead slots get 0. Refuses an invalid world.
Status world_body_hashes(WorldId world, std::vector<uint64_t>* out);

// ---------------------------------------------------------------------------
// Compact rollback form: a delta against a base image
// ---------------------------------------------------------------------------
// A rollback keeps a base image (say, the last confirmed tick's) and, for the
// ticks after it, deltas: the XOR of each image with the base, run-length
// coded (runs of unchanged bytes cost a varint). Unchanged structure —
// static bodies and their geometry, pools, materials, the high bytes of
// most values — costs almost nothing; see tools/bench/bench_rollback.cpp for
// measured sizes. Format: magic "TNDD", u32 version (1), u64 image size, u64
// XXH3-64 of the base, then until the image is complete: varint (LEB128)
// count of bytes equal to the base, varint count n, n bytes XOR base.
// Copied runs must lie within the base, so the image size is bounded by
// base size + delta size, checked before anything is allocated.

/// Encodes `image` as a delta against `base` (both full state images, or
/// any bytes) into *out (replaced).
void encode_state_delta(const uint8_t* base, size_t base_size, const uint8_t* image, size_t image_size,
                        std::vector<uint8_t>* out);

/// Rebuilds the image from `base` and a delta made against it into
/// *out_image (replaced). Refuses a wrong magic or version, a different base
/// (hash mismatch), and truncated or inconsistent data, naming the byte
/// offset; *out_image is unspecified on failure.
Status apply_state_delta(const uint8_t* base, size_t base_size, const uint8_t* delta, size_t delta_size,
                         std::vector<uint8_t>* out_image);

// ---------------------------------------------------------------------------
// Generic decoding and diffs
// ---------------------------------------------------------------------------

/// One named value of a decoded record.
struct DecodedField {
  std::string name;   ///< "position.x", "linear_velocity.y", "point[1].normal_impulse"
  int64_t value = 0;  ///< the raw integer (Q32: raw = value · 2^32; bools 0/1; enums their number)
  bool is_q32 = false;  ///< true when value is a Q32.32 raw value
};

/// One record of a decoded state, in canonical order.
struct DecodedRecord {
  std::string kind;        ///< "header", "world", "body_slot", "body", "shape_slot", "shape",
                           ///< "contact", "touching", "sensor_overlap", "joint_slot", "joint",
                           ///< "joint_event" (index: position in the pending list)
  int64_t index = 0;       ///< slot / body / shape index; contacts and pairs: lower shape index
  int64_t index2 = -1;     ///< contacts and pairs: the higher shape index; −1 otherwise
  uint32_t generation = 0; ///< bodies and shapes: the slot's generation; 0 otherwise
  std::vector<DecodedField> fields;
};

/// A state image decoded into named records (for diffs and tools).
struct DecodedState {
  uint32_t version = 0;
  std::vector<DecodedRecord> records;
};

/// Decodes and validates a state image (the same checks as world_restore)
/// into named records. Errors name the byte offset and what was expected.
Status decode_world_state(const uint8_t* data, size_t size, DecodedState* out);

/// The byte offset of one field in a valid state image: `kind` is "world",
/// "body", "shape" or "contact"; `index` the body or shape index, or the
/// contact's position in the contact list (ignored for "world"); `field` a
/// name as decode_world_state reports it ("linear_velocity.x",
/// "aabb.lower.x", "points[0].normal_impulse"). For tools that patch or
/// explain images (and tests that craft them). Refuses an invalid image (as
/// decode_world_state) and an unknown record or field.
Status locate_state_field(const uint8_t* data, size_t size, const std::string& kind, int64_t index,
                          const std::string& field, size_t* out_offset);

/// The first difference between two decoded states, in canonical order.
struct StateDifference {
  bool differs = false;       ///< false: the states are identical
  std::string kind;           ///< record kind ("body")
  int64_t index = 0;          ///< record index
  int64_t index2 = -1;        ///< second key (contacts, pairs) or −1
  uint32_t generation = 0;    ///< the record's slot generation in a (the present side if missing)
  uint32_t generation_b = 0;  ///< the same in b (equal to `generation` when a record is missing)
  std::string field;          ///< differing field; empty when a record is missing on one side
  int64_t value_a = 0;        ///< raw values
  int64_t value_b = 0;
  bool is_q32 = false;
  bool missing_in_a = false;  ///< the record exists only in b
  bool missing_in_b = false;  ///< the record exists only in a
  /// "body 3 linear_velocity.x: a = 1.5 (raw 6442450944), b = ..." or
  /// "identical"; Q32 values are printed as exact decimals. The generation
  /// is named only when the two sides' generations differ: "joint 3
  /// (generation 1 in a, 2 in b) motor_impulse: ...".
  std::string describe() const;
};

/// Compares two decoded states record by record and field by field, in
/// canonical order, and returns the first difference (or differs = false).
StateDifference diff_world_states(const DecodedState& a, const DecodedState& b);

/// Exact decimal text of a Q32 raw value ("1.5", "-0.0000000002328306436538696289062"),
/// for diffs and tools.
std::string q32_raw_text(int64_t raw);

}  // namespace tandem
