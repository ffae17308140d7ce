// state_access.h — the one door through which replay/ reaches a world's
// persistent state (internal to the engine's libraries: not installed, and
// no public header includes it). replay/ owns the bytes (the canonical
// encoding, hashes, images, deltas, diffs); physics owns what the bytes hold:
// which records and fields a world's state has, in which order
// (state_fields.h, the single list of persistent fields), how a decoded
// image is checked against the engine's limits and derived values, and how a
// world is rebuilt from it. Nothing here names World, Body, Shape or Contact:
// replay sees a world's state as an opaque WorldState and a decoded image as
// an opaque StateImage, and walks their fields through a FieldVisitor.
//
// DESIGN. replay implements FieldVisitor once per job (write bytes, read
// bytes with checks, describe named fields, find a field's byte offset);
// physics runs the field lists of state_fields.h over a world or an image
// with it. The visitor is virtual so that the field lists stay in physics and
// their structs out of replay; a call per field costs a few nanoseconds next
// to the byte work each field does (docs/benchmarks.md measures the hash and
// the snapshot). Rejected: a template visitor header (replay would include
// the internal structs again) and a table of field offsets (variable-length
// records — polygons, manifold points — need code between the fields).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "fixed/fixed.h"
#include "fixed/vec2.h"
#include "physics/collision.h"
#include "physics/ids.h"
#include "physics/status.h"

namespace tandem::state_access {

/// The lists of the canonical state whose length is stored before them.
enum class StateList : uint8_t {
  body_slots,
  shape_slots,
  joint_slots,
  contacts,
  touching,
  sensor_overlaps,
  pending_joint_events,
};

/// The record kinds a field can be looked up in (offsets, messages).
enum class RecordKind : uint8_t { world, body, shape, contact, joint };

/// The output of a writing visitor that lets physics write the bytes itself
/// (FieldVisitor::output_buffer): bytes go to data[size, capacity); a value
/// that does not fit whole is counted in size but not written.
struct OutputBuffer {
  uint8_t* data = nullptr;
  size_t capacity = 0;
  size_t size = 0;
};

/// Walks the fields of the canonical state, in canonical order. Every field
/// is passed by reference: a reading visitor fills it, the others read it.
class FieldVisitor {
 public:
  virtual ~FieldVisitor() = default;
  /// A writing visitor may return its output here; visit_world then writes
  /// the canonical little-endian bytes of every field directly — exactly
  /// what the visitor's own methods would write (8 bytes for Q32, u64 and
  /// each Vec2 component, 4 for i32, u32 and counts, 2 for u16, 1 for bools,
  /// enums and a slot's alive flag, after its u32 generation; the 4 tag
  /// characters) — saving a virtual call per field on the hash path. The
  /// encoding tests compare both paths byte for byte.
  virtual OutputBuffer* output_buffer() { return nullptr; }
  /// True when fields are filled from bytes (decoding into a StateImage).
  virtual bool reading() const = 0;
  /// A record starts: its kind ("body"), index (slot index; for contacts and
  /// pairs the shape pair in index and index2) and slot generation (0: none).
  virtual void record(const char* kind, int64_t index, int64_t index2, uint32_t generation) = 0;
  /// Reading only, right after record(): the record's position in its
  /// section (slot index, or order in a list), for messages and offsets.
  virtual void begin_read(const char* kind, int64_t position) {
    (void)kind;
    (void)position;
  }
  /// A 4-character section tag.
  virtual void tag(const char* tag) = 0;
  virtual void q32(const char* name, Q32& v) = 0;
  virtual void vec2(const char* name_x, const char* name_y, Vec2& v) = 0;
  virtual void i32(const char* name, int32_t& v) = 0;
  virtual void u32(const char* name, uint32_t& v) = 0;
  virtual void u16(const char* name, uint16_t& v) = 0;
  virtual void u64(const char* name, uint64_t& v) = 0;
  virtual void boolean(const char* name, bool& v) = 0;
  /// An enum's value, which must lie in [0, max] (checked when reading; the
  /// value is left unchanged by a failed read).
  virtual void enum8(const char* name, int32_t& v, int32_t max) = 0;
  /// A value that must lie in [lo, hi] (checked when reading).
  virtual void ranged_i32(const char* name, int32_t& v, int32_t lo, int32_t hi) = 0;
  /// The length of `list` ("capacity" of a pool, "count" of a list), at
  /// most `max`; `context` names the list in messages. Reading visitors
  /// also check it against the bytes left before physics sizes anything.
  virtual void count(StateList list, const char* context, const char* name, uint32_t& n, uint32_t max) = 0;
  /// One pool slot: its generation (≥ 1) and whether it is alive.
  virtual void slot(const char* kind, uint32_t index, uint32_t& generation, bool& alive) = 0;
  /// False after a failed read: the walk stops.
  virtual bool ok() const = 0;
};

/// A live world's state (opaque; the world itself).
struct WorldState;
/// A decoded image: a scratch world that is never registered or stepped.
struct StateImage;
struct StateImageDeleter {
  void operator()(StateImage* image) const;
};
using StateImagePtr = std::unique_ptr<StateImage, StateImageDeleter>;

/// The world of a handle; null when there is none, or (unlocked_only) when
/// it is inside world_step().
WorldState* find_world_state(WorldId id, bool unlocked_only);
/// The world of a handle for `function` (named in the refusal); `mutating`
/// also refuses a locked world.
Status resolve_world_state(WorldId id, const char* function, bool mutating, WorldState** out);
/// The world and body index of a live body handle; null when there is none
/// or the world is locked.
WorldState* find_body_state(BodyId id, int32_t* out_index);

/// Which sections follow the version-1 ones.
struct StateSections {
  bool joints = false;        ///< joint pool and joint records
  bool joint_events = false;  ///< pending joint events (needs joints)
};

/// What a world holds, for computing its encoded size without walking it.
struct StateCensus {
  size_t body_slots = 0;
  size_t bodies = 0;
  size_t shape_slots = 0;
  size_t shapes_by_type[5] = {};  ///< live shapes by ShapeType
  size_t polygon_vertices = 0;    ///< over live polygons, each count clamped to [0, 8]
  size_t contacts = 0;
  size_t contact_points = 0;      ///< over contacts, each clamped to [0, 2]
  size_t touching = 0;
  size_t sensor_overlaps = 0;
  size_t joint_slots = 0;
  size_t joints = 0;
  size_t pending_joint_events = 0;
};
StateCensus census(const WorldState& world);

/// Walks the whole state: the world record (WorldDef, step count, solver
/// body count), pools, bodies, shapes, contacts, touching pairs, sensor
/// overlaps, then the sections named. broad_phase_as_naive: the world's
/// broad-phase kind is visited as naive (the hash sees every kind alike).
void visit_world(WorldState& world, FieldVisitor& v, StateSections sections, bool broad_phase_as_naive);
/// The world record alone (WorldDef, step count, solver body count).
void visit_world_header(WorldState& world, FieldVisitor& v, bool broad_phase_as_naive);
/// One live body and then its shapes in list order.
void visit_body_with_shapes(WorldState& world, int32_t body, FieldVisitor& v);
/// Whether slot `body` holds a live body.
bool body_alive(const WorldState& world, int32_t body);

/// The records at their defaults, for measuring record sizes: the world
/// record; a body; a shape of `variant` = ShapeType with no polygon
/// vertices; a contact with `variant` points; a joint; a joint event.
enum class DefaultRecord : uint8_t { world, body, shape, contact, joint, joint_event };
void visit_default_record(DefaultRecord record, int32_t variant, FieldVisitor& v);

/// A new empty image, and the calling thread's scratch image (reused, so a
/// warm restore loop does not allocate).
StateImagePtr new_image();
StateImage& scratch_image();
/// Reads an image's state with a reading visitor, or walks a decoded image
/// with any other (describe).
void visit_image(StateImage& image, FieldVisitor& v, StateSections sections);
/// Walks one record of a decoded image (world: its WorldDef only). False
/// when the image has no such record (a dead slot, an index out of range).
bool visit_image_record(StateImage& image, RecordKind kind, int64_t index, FieldVisitor& v);

/// Why an image was refused, and where: `where` none (the message alone),
/// record (at the start of record `index` of `kind`), or field (at `field`
/// of that record).
struct StateRefusal {
  enum class Where : uint8_t { none, record, field } where = Where::none;
  RecordKind kind = RecordKind::world;
  int64_t index = 0;
  const char* field = nullptr;
  std::string message;
};
/// Checks a structurally decoded image: cross references (shape lists, pool
/// indices, sort orders), every value against the limits the public API
/// enforces (widened where a legal simulation can exceed them), and every
/// cached value against the value derived from the others, bit for bit.
/// False (and *out filled) on the first failure.
bool check_image(StateImage& image, StateRefusal* out);
/// Replaces the world's state with a checked image and rebuilds what is
/// derived from it (joint filter, broad phase, event buffers, headroom).
/// The image's buffers are swapped with the world's (no allocation in a warm
/// loop); the image is left holding the world's old state.
void commit_image(WorldState& world, StateImage& image);

// ---------------------------------------------------------------------------
// The compact rollback image (replay/rollback.h). physics writes, checks and
// applies its records itself (physics/state_compact.cpp lays them out): which
// fields a record keeps, packs into flag bits, leaves out when at their
// default, carries beside the image or recomputes is a property of the
// physics records, decided next to them, and the records kept whole run the
// field lists of state_fields.h. replay owns the image's header (magic,
// version), the buffer and the hash. The records start with one byte, the
// broad-phase kind, which the hash skips (the kind does not change results).
// ---------------------------------------------------------------------------

/// What travels beside a compact image, by record index (not hashed).
struct CompactStructure {
  std::vector<ShapeGeometry>* geometries;   ///< each live shape's geometry
  std::vector<RollbackBodyMass>* masses;    ///< each live body's mass data
};
/// The same, read-only (restore).
struct CompactStructureView {
  const std::vector<ShapeGeometry>* geometries;
  const std::vector<RollbackBodyMass>* masses;
};

/// An upper bound of the bytes write_compact_records writes for the world.
size_t compact_records_bound(const WorldState& world);
/// Writes the world's compact records at `out` (compact_records_bound bytes
/// available) and the structure beside them (grown as needed, capacity
/// reused); returns the bytes written.
size_t write_compact_records(WorldState& world, uint8_t* out, CompactStructure structure);
/// Checks the compact records at image[from, size) against the structure:
/// bytes left, enums, indices, cross references and value ranges; nothing is
/// changed. False with *error = "offset N: <record> <field> ..." (offsets
/// from the start of `image`) on the first failure.
bool check_compact_records(const uint8_t* image, size_t size, size_t from, CompactStructureView structure,
                           std::string* error);
/// Whether check_compact_records tries its fast checks first (the default):
/// off, every image goes through the detailed checks alone. Both give the same
/// verdict and message for every image; tests compare them.
void set_compact_fast_checks(bool on);
/// Replaces the world's state with checked compact records and rebuilds what
/// is derived from them (as commit_image); cannot fail.
void apply_compact_records(WorldState& world, const uint8_t* image, size_t size, size_t from,
                           CompactStructureView structure);

}  // namespace tandem::state_access
