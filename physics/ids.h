// ids.h — handles: WorldId, BodyId, ShapeId, JointId. Index + generation,
// passed by value, never pointers.
//
// Layout. A world handle is {index1, generation}: the world's slot in the
// process-wide world registry plus one, and that slot's generation. A body,
// shape or joint handle is {index1, generation, world}: its slot in its
// world's pool plus one, the slot's generation, and the world handle. Storing
// index + 1 makes the all-zero handle the null handle (`BodyId id{}`), and a
// generation never equals 0 for a live object, so a zeroed handle can never
// name anything.
//
// Generations. Each slot's generation starts at 1 and is incremented when the
// object is destroyed (wrapping from 2^32 − 1 to 1, skipping 0; for worlds
// from 2^16 − 1 to 1). A handle is valid exactly while its slot is alive with
// the same generation, so a handle kept after a destroy fails the check
// instead of naming the slot's next occupant. Object generations are 32-bit:
// a slot reused every frame at 60 Hz wraps after 2.3 years (a 16-bit counter
// would wrap after 18 minutes, and the free list reuses slots eagerly).
//
// Embedding the world handle (with its generation) in every object handle is
// what lets free functions take only the object handle, and makes a handle
// from a destroyed world, or from another world where one is expected, a
// clear error rather than a lookup in the wrong arrays.
//
// Rejected: Box2D's 8-byte handles with a 16-bit world index and no world
// generation (a body handle outliving its world would silently name a body of
// the next world created in that slot). Tandem's object handles are 12 bytes,
// with no padding, so they can be hashed and compared bytewise.
//
// This header also holds TANDEM_ASSERT, the check for our own invariants
// (never for user input, which gets a Status): every physics file includes
// ids.h, and there is no separate core header yet.
#pragma once

#include <cstdint>

namespace tandem {

/// A world: registry slot + 1 (0 = null) and the slot's generation (≥ 1).
struct WorldId {
  uint16_t index1 = 0;      ///< slot index + 1; 0 is the null handle
  uint16_t generation = 0;  ///< slot generation, ≥ 1 for a live world
  friend constexpr bool operator==(WorldId, WorldId) = default;
};

/// A body: pool slot + 1 in its world (0 = null), the slot's generation and
/// the world.
struct BodyId {
  uint32_t index1 = 0;      ///< body index + 1; 0 is the null handle
  uint32_t generation = 0;  ///< slot generation, ≥ 1 for a live body
  WorldId world;            ///< the world the body lives in
  friend constexpr bool operator==(BodyId, BodyId) = default;
};

/// A shape: pool slot + 1 in its world (0 = null), the slot's generation and
/// the world.
struct ShapeId {
  uint32_t index1 = 0;      ///< shape index + 1; 0 is the null handle
  uint32_t generation = 0;  ///< slot generation, ≥ 1 for a live shape
  WorldId world;            ///< the world the shape lives in
  friend constexpr bool operator==(ShapeId, ShapeId) = default;
};

/// A joint: pool slot + 1 in its world (0 = null), the slot's generation and
/// the world. (Joints arrive with the joint task; the handle is fixed now.)
struct JointId {
  uint32_t index1 = 0;      ///< joint index + 1; 0 is the null handle
  uint32_t generation = 0;  ///< slot generation, ≥ 1 for a live joint
  WorldId world;            ///< the world the joint lives in
  friend constexpr bool operator==(JointId, JointId) = default;
};

static_assert(sizeof(WorldId) == 4 && sizeof(BodyId) == 12 && sizeof(ShapeId) == 12 && sizeof(JointId) == 12,
              "handles have no padding");

/// True for the null world handle (index1 == 0).
constexpr bool is_null(WorldId id) { return id.index1 == 0; }
/// True for the null body handle (index1 == 0).
constexpr bool is_null(BodyId id) { return id.index1 == 0; }
/// True for the null shape handle (index1 == 0).
constexpr bool is_null(ShapeId id) { return id.index1 == 0; }
/// True for the null joint handle (index1 == 0).
constexpr bool is_null(JointId id) { return id.index1 == 0; }

/// Reports a failed invariant (file, line, condition) to stderr and aborts.
[[noreturn]] void assert_failed(const char* condition, const char* file, int line);

}  // namespace tandem

/// Checks one of Tandem's own invariants (never user input). Active in builds
/// without NDEBUG or with TANDEM_ENABLE_ASSERT defined; aborts with the
/// condition, file and line.
#if !defined(NDEBUG) || defined(TANDEM_ENABLE_ASSERT)
#define TANDEM_ASSERT(condition) \
  ((condition) ? static_cast<void>(0) : ::tandem::assert_failed(#condition, __FILE__, __LINE__))
#else
// Unevaluated, but it keeps variables used only by asserts "used".
#define TANDEM_ASSERT(condition) static_cast<void>(sizeof((condition) ? 1 : 0))
#endif
