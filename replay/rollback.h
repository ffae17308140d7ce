// rollback.h — the compact rollback snapshot: save, restore and hash a world
// in a few hundred bytes per moving body, for rollback netcode that saves
// every tick and restores several times a second.
//
// WHAT IT HOLDS. Only what the next step cannot recompute, as an explicit
// little-endian canonical image (replay/bytes.h rules: every field stored
// value by value, never struct bytes), plus a copy of the structure the image
// refers to:
//   image      header, WorldDef, step count, body / shape / joint pools, per
//              live body its flags, pose and (when not zero / default) its
//              velocity, force, sleep state, user data, damping and gravity
//              scale; per live shape its body, type, flags and (when not
//              default) materials, filter and user data; per contact its
//              shape pair, point count and per point the feature id and the
//              two warm-start impulses; touching pairs (or one byte saying
//              they are the touching contacts), sensor overlaps, joints and
//              joint events waiting for the next step.
//   structure  per live shape its geometry and per live body its mass data
//              (mass, inertia, their inverses, local centre, extents): never
//              changed by a step, derived from the shapes or fixed at shape
//              creation, so they travel beside the image as copies and are
//              not hashed (the image holds every shape's type and density, so
//              a changed shape shows in the hash through its generation).
// NOT held, recomputed by restore: body world centres (from pose and local
// centre), shape bounds (from geometry and pose), body shape lists (shapes are
// listed in ascending index), contact bodies and generations. NOT held,
// recomputed by the next step: the manifold geometry (normal, points,
// anchors, separations) and mixed materials of every contact whose two
// bodies are simulated (awake, enabled, not static) at save time — the next
// update_contacts recomputes those from the poses, matching the stored
// feature ids to carry the impulses, exactly as it does without a restore.
// Contacts with a body that is not simulated (static ground, sleepers) keep
// their full record, because the next step may carry them unchanged.
//
// EXACTNESS. After rollback_restore, every later step is bit-identical to the
// run the buffer was saved from (tests/replay/test_rollback.cpp: every golden
// scene, joints, sleep, bodies woken, put to sleep, created and destroyed
// between save and restore, every broad phase). Two documented differences
// from a portable restore, neither of which changes a later step:
//   * before the next step, world_state_hash() of the restored world differs
//     from the saved tick's (the omitted manifold geometry reads as zero);
//     rollback_hash() of a save made right after the restore is equal;
//   * if inputs applied between the restore and the next step make BOTH
//     bodies of such a contact non-simulated (put both to sleep, say), that
//     step carries the contact without recomputing it, so its manifold
//     geometry stays zero until one of them wakes (impulses and feature ids,
//     which waking uses, are kept). world_state_hash() differs meanwhile;
//     rollback_hash() and every simulated value do not.
//
// SAME BUILD ONLY. The image is canonical (hashable and comparable between
// peers of the same version) but has no compatibility promise across
// versions; replay files and cross-machine diffs use the portable format of
// state.h. rollback_restore checks the image like any input: magic, version,
// sizes, counts against the bytes left, indices, enums and value ranges,
// refusing with the byte offset and field; a refused restore changes nothing.
//
// LAYOUT. replay writes the header (magic, version) and hashes; physics
// writes, checks and applies the records after it through its state door
// (physics/state_access.h; physics/state_compact.cpp lays them out).
//
// COST (990-box pyramid, tools/bench/bench_rollback.cpp, docs/benchmarks.md):
// no allocation after the first save into a buffer of the same scene.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "physics/tandem.h"

namespace tandem {

/// The version of the compact rollback image (same build only).
inline constexpr uint32_t k_rollback_format_version = 1;

/// The 4 magic bytes at the start of a compact rollback image.
inline constexpr uint8_t k_rollback_magic[4] = {'T', 'N', 'D', 'R'};

/// A reusable compact snapshot. Default-constructed empty; rollback_save fills
/// it (reusing its capacity), rollback_restore reads it. Copyable (a ring of
/// buffers is a std::vector<RollbackBuffer>).
struct RollbackBuffer {
  /// The canonical image (what rollback_hash hashes). Tests may corrupt it.
  std::vector<uint8_t> image;
  /// Geometry of each live shape at save time, by shape index (dead slots:
  /// unspecified).
  std::vector<ShapeGeometry> geometries;
  /// Mass data of each live body at save time, by body index
  /// (RollbackBodyMass: physics/collision.h).
  std::vector<RollbackBodyMass> masses;
};

/// Saves the world's state into *buffer (replaced; capacity reused, so a
/// save into a buffer that held the same scene does not allocate). Refuses
/// an invalid or locked world; *buffer is unchanged then.
Status rollback_save(WorldId world, RollbackBuffer* buffer);

/// Replaces the world's state with the buffer's (see the file comment for the
/// two ways the restored world differs from a portable restore before its
/// next step). Refuses an invalid or locked world and a wrong, truncated,
/// inconsistent or out-of-range image with a message naming the byte offset,
/// record and field; on any refusal the world is unchanged. The buffer may
/// come from another world of the same build (handles then refer to the
/// buffer's bodies, as after world_restore).
Status rollback_restore(WorldId world, const RollbackBuffer& buffer);

/// XXH3-64 (seed 0) of the buffer's image; 0 for an empty buffer. Equal
/// states give equal hashes; the broad-phase kind is hashed as naive (as
/// world_state_hash), so it does not depend on the broad phase either.
uint64_t rollback_hash(const RollbackBuffer& buffer);

/// The image size in bytes (what a peer would send or store per tick).
inline size_t rollback_image_size(const RollbackBuffer& buffer) { return buffer.image.size(); }

}  // namespace tandem
