// contact.cpp — contact lifetime and narrow phase.
//
// ORDERING CHAIN (why every peer processes contacts in the same order):
//   1. Shape indices come from the shape id pool, lowest free index first, so
//      the same calls in the same order give the same indices (id_pool.h).
//   2. The broad phase reports pairs as (lower index, higher index) sorted by
//      that key, with no duplicates (broad_phase.h; the naive one generates
//      them in that order, others must sort on the unique key).
//   3. update_contacts merges that list with the previous contact list (also
//      sorted by key) in one forward pass: a key in both keeps its contact
//      (impulses carried), a key only in the pairs creates a contact, a key
//      only in the old list is destroyed. The result is again sorted by key.
//   4. Within a contact, manifold points come in collide()'s order; old
//      impulses are matched by feature id, first match wins (ids within one
//      manifold are distinct).
//   5. The solver builds one constraint per touching contact that has a
//      simulated body, in contact order, and solves them in that order
//      (scalar Gauss-Seidel); impulses go back to the contacts by index.
//   Nothing here depends on addresses, hash order or thread timing.
//
// Workers (task.h): the merge with the pair list (step 3) is one serial
// pass that fixes every contact's slot and its old contact; the manifolds
// (step 4) are then computed in blocks of k_contact_block contacts, on any
// thread in any order: each reads the shapes, the start-of-step poses and
// its old contact, and writes only its own slot. This stage has no other
// shared effect (begin/end touch events are derived later from the flags,
// events.cpp, in contact order).
//
// Sleeping: a contact whose two bodies are both not simulated (asleep,
// static, disabled) is carried over unchanged — no narrow phase, impulses
// kept — so a sleeping island costs only its broad-phase pairs (island.h).
//
// Awake contacts: the update also lists, in World::awake_contacts, the
// contacts with a simulated body (ascending index), which the later stages
// walk instead of the whole list while no body woke (for_each_awake_contact,
// world.h). When the pairs are exactly the old contacts' keys and
// generations the list is updated in place (no contact copied) and
// World::contact_set_unchanged tells events_after_step whether any touching
// flag changed. Both are derived every step, never state, so a restored
// world steps identically.
//
// Memory: World::contacts and World::contact_scratch are swapped each step
// (the new list is built in the scratch vector); both only grow, so after the
// first steps of a scene no allocation happens here.
#include "physics/contact.h"

#include <utility>

#include "physics/broad_phase.h"
#include "physics/world.h"

namespace tandem {

uint64_t contact_key(const Contact& contact) { return shape_pair_key(contact.shape_a, contact.shape_b); }

namespace {

/// mix_friction's body, inlined into the narrow phase.
inline Q32 mix_friction_inline(Q32 a, Q32 b) {
  // Equal frictions above 1/2 mix to themselves, bit for bit, without the
  // root: with x = a.raw > 2^31, a·a rounds to r where |r·2^32 − x²| ≤ 2^31,
  // so √(r·2^32) lies within 2^31/(2x) < 1/2 raw unit of x and the correctly
  // rounded root is x.
  if (a == b && a.raw > (int64_t{1} << 31)) return a;
  // a, b ≤ k_max_friction = 100: the product ≤ 1e4, no saturation.
  return sqrt(a * b);
}

}  // namespace

Q32 mix_friction(Q32 a, Q32 b) { return mix_friction_inline(a, b); }

Q32 mix_restitution(Q32 a, Q32 b) { return max(a, b); }

namespace {

/// Recomputes the manifold of `c` and carries impulses from `old` (the same
/// contact last step, or null) by feature id.
void update_manifold(const World& world, Contact* c, const Contact* old) {
  const size_t sa = static_cast<size_t>(c->shape_a);
  const size_t sb = static_cast<size_t>(c->shape_b);
  const Shape& shape_a = world.shapes[sa];
  const Shape& shape_b = world.shapes[sb];
  const Transform xf_a = world.body_sims[static_cast<size_t>(shape_a.body_index)].transform;
  const Transform xf_b = world.body_sims[static_cast<size_t>(shape_b.body_index)].transform;
  if (old != nullptr && (old->flags & k_contact_touching) != 0) {
    collide_persistent(world.shape_geometries[sa], xf_a, world.shape_geometries[sb], xf_b, old->manifold, &c->manifold);
  } else {
    c->manifold = collide(world.shape_geometries[sa], xf_a, world.shape_geometries[sb], xf_b);
  }
  c->friction = mix_friction_inline(shape_a.friction, shape_b.friction);
  c->restitution = max(shape_a.restitution, shape_b.restitution);  // mix_restitution
  c->normal_impulse = {};
  c->tangent_impulse = {};
  const int32_t count = c->manifold.point_count;
  c->flags = count > 0 ? (c->flags | k_contact_touching) : (c->flags & ~k_contact_touching);
  if (old == nullptr) return;
  for (int32_t i = 0; i < count; ++i) {
    const uint16_t id = c->manifold.points[static_cast<size_t>(i)].id;
    for (int32_t j = 0; j < old->manifold.point_count; ++j) {
      if (old->manifold.points[static_cast<size_t>(j)].id != id) continue;
      c->normal_impulse[static_cast<size_t>(i)] = old->normal_impulse[static_cast<size_t>(j)];
      c->tangent_impulse[static_cast<size_t>(i)] = old->tangent_impulse[static_cast<size_t>(j)];
      break;
    }
  }
}

}  // namespace

namespace {

/// Contacts per block of the parallel narrow phase.
constexpr int32_t k_contact_block = 32;
/// old_of[] marks: a new contact (no old one), or one carried over unchanged.
constexpr int32_t k_no_old_contact = -1;
constexpr int32_t k_carried_contact = -2;

}  // namespace

void update_contacts(World* world) {
  broad_phase_update_pairs(world);
  const std::vector<ShapePair>& pairs = world->broad_phase.pairs;
  std::vector<Contact>& old_list = world->contacts;
  std::vector<int32_t>& awake = world->awake_contacts;
  awake.clear();
  world->contacts_read_after_update = 0;
  Arena* arena = &world->arena;
  world->awake_contacts_wake_count = world->wake_count;

  // In place when the pairs are the old contacts' keys with the same
  // generations (a scene whose pairs did not change: every sleeping step, and
  // most steps of a resting pile): no list is rebuilt and the carried-over
  // contacts are not copied. Same contents as the merge below, which would
  // keep every contact in its slot.
  bool in_place = pairs.size() == old_list.size();
  for (size_t i = 0; in_place && i < pairs.size(); ++i) {
    const ShapePair& pair = pairs[i];
    const Contact& c = old_list[i];
    in_place = c.shape_a == pair.shape_a && c.shape_b == pair.shape_b &&
               c.generation_a == id_pool_generation(world->shape_pool, pair.shape_a) &&
               c.generation_b == id_pool_generation(world->shape_pool, pair.shape_b);
  }
  const auto simulated = [world](int32_t body) {
    return body_is_simulated(world->bodies[static_cast<size_t>(body)]);
  };
  const World& w = *world;
  if (in_place) {
    // Per body: 1 when simulated (awake, enabled, not static), from one pass
    // over the bodies rather than two Body records per contact.
    const int32_t body_count = id_pool_capacity(world->body_pool);
    uint8_t* moving = arena_allocate_array<uint8_t>(arena, body_count, "contact_body_moving");
    for (int32_t b = 0; b < body_count; ++b) {
      moving[b] = id_pool_is_alive(world->body_pool, b) && simulated(b) ? 1 : 0;
    }
    const int32_t count = static_cast<int32_t>(old_list.size());
    for (int32_t i = 0; i < count; ++i) {
      const Contact& c = old_list[static_cast<size_t>(i)];
      if (moving[c.body_a] != 0 || moving[c.body_b] != 0) awake.push_back(i);
    }
    // The narrow phase over the awake contacts, each from a copy of itself
    // (its old contact), rebuilt from zero as the merge path builds it.
    const int32_t awake_count = static_cast<int32_t>(awake.size());
    const int32_t blocks = block_count_of(awake_count, k_contact_block);
    uint8_t* flipped = arena_allocate_array<uint8_t>(arena, blocks, "contact_touching_flipped");
    Contact* slots = old_list.data();
    const int32_t* index = awake.data();
    parallel_for(&world->tasks, "narrow_phase", awake_count, k_contact_block,
                 [&w, slots, index, flipped](int32_t begin, int32_t end) {
                   uint8_t changed = 0;
                   for (int32_t k = begin; k < end; ++k) {
                     Contact& c = slots[index[k]];
                     const Contact old = c;
                     c = Contact{};
                     c.shape_a = old.shape_a;
                     c.shape_b = old.shape_b;
                     c.generation_a = old.generation_a;
                     c.generation_b = old.generation_b;
                     c.body_a = old.body_a;
                     c.body_b = old.body_b;
                     c.flags = old.flags;
                     update_manifold(w, &c, &old);
                     changed |= static_cast<uint8_t>(((c.flags ^ old.flags) & k_contact_touching) != 0 ? 1 : 0);
                   }
                   flipped[begin / k_contact_block] = changed;
                 });
    bool unchanged = true;
    for (int32_t k = 0; k < blocks; ++k) unchanged = unchanged && flipped[k] == 0;
    world->contact_set_unchanged = unchanged;
    arena_free(arena, flipped);
    arena_free(arena, moving);
    return;
  }
  world->contact_set_unchanged = false;

  std::vector<Contact>& next = world->contact_scratch;
  next.clear();
  // Per new contact: the index of its old contact, or a k_* mark above.
  int32_t* old_of = arena_allocate_array<int32_t>(arena, static_cast<int32_t>(pairs.size()), "contact_old_index");
  size_t cursor = 0;
  for (const ShapePair& pair : pairs) {
    const uint64_t key = shape_pair_key(pair.shape_a, pair.shape_b);
    // (the key computed inline: contact_key() lives out of line for other files)
    const auto old_key = [&old_list](size_t i) { return shape_pair_key(old_list[i].shape_a, old_list[i].shape_b); };
    while (cursor < old_list.size() && old_key(cursor) < key) ++cursor;  // destroyed
    const Contact* old = nullptr;
    const uint32_t gen_a = id_pool_generation(world->shape_pool, pair.shape_a);
    const uint32_t gen_b = id_pool_generation(world->shape_pool, pair.shape_b);
    if (cursor < old_list.size() && old_key(cursor) == key) {
      const Contact& candidate = old_list[cursor];
      if (candidate.generation_a == gen_a && candidate.generation_b == gen_b) old = &candidate;
      ++cursor;
    }
    const int32_t body_a = world->shapes[static_cast<size_t>(pair.shape_a)].body_index;
    const int32_t body_b = world->shapes[static_cast<size_t>(pair.shape_b)].body_index;
    const bool moves = simulated(body_a) || simulated(body_b);
    if (old != nullptr && !moves) {
      // Neither body moves (asleep, static or disabled): the manifold and the
      // impulses are still valid; keep them for when the island wakes.
      old_of[next.size()] = k_carried_contact;
      next.push_back(*old);
      continue;
    }
    // A new contact between two bodies that do not move is still computed
    // (it has no manifold yet) but is not an awake contact: no stage after
    // this one has work for it (no constraint, no wake, no island).
    if (moves) awake.push_back(static_cast<int32_t>(next.size()));
    old_of[next.size()] = old != nullptr ? static_cast<int32_t>(old - old_list.data()) : k_no_old_contact;
    Contact& c = next.emplace_back();  // zeroed in place (no copy); the narrow phase fills the manifold
    c.shape_a = pair.shape_a;
    c.shape_b = pair.shape_b;
    c.generation_a = gen_a;
    c.generation_b = gen_b;
    c.body_a = body_a;
    c.body_b = body_b;
    c.flags = old != nullptr ? old->flags : 0;
  }
  // The narrow phase, per contact (see the file comment).
  Contact* slots = next.data();
  const Contact* olds = old_list.data();
  parallel_for(&world->tasks, "narrow_phase", static_cast<int32_t>(next.size()), k_contact_block,
               [&w, slots, olds, old_of](int32_t begin, int32_t end) {
                 for (int32_t i = begin; i < end; ++i) {
                   const int32_t o = old_of[i];
                   if (o == k_carried_contact) continue;
                   update_manifold(w, &slots[i], o >= 0 ? &olds[o] : nullptr);
                 }
               });
  arena_free(arena, old_of);
  std::swap(world->contacts, world->contact_scratch);
}

namespace {

/// Grows only when the use passes 3/4 of the capacity, then to twice the
/// use plus 64, so a scene whose counts drift a little never reallocates.
template <typename T>
void reserve_for(std::vector<T>* v, size_t use) {
  if (4 * use + 4 <= 3 * v->capacity()) return;
  v->reserve(2 * use + 64);
}

}  // namespace

void reserve_contact_headroom(World* world) {
  const size_t contacts = world->contacts.size();
  reserve_for(&world->contacts, contacts);
  reserve_for(&world->contact_scratch, contacts);
  reserve_for(&world->awake_contacts, contacts);
  BroadPhase& bp = world->broad_phase;
  reserve_for(&bp.pairs, bp.pairs.size());
  const size_t shapes = static_cast<size_t>(id_pool_capacity(world->shape_pool));
  reserve_for(&bp.proxies, shapes);
  reserve_for(&bp.fat_bounds, shapes);
}

}  // namespace tandem
