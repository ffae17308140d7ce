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
// world.h). While every contact has a simulated body (nothing asleep, the
// usual case) the list is not written: World::awake_contacts_all says the
// index is the whole list (awake_contact_count, world.h). When the pairs are exactly the old contacts' keys and
// generations the list is updated in place (no contact copied) and
// World::contact_set_unchanged tells events_after_step whether any touching
// flag changed. Both are derived every step, never state, so a restored
// world steps identically.
//
// Memory: World::contacts and World::contact_scratch are swapped each step
// (the new list is built in the scratch vector); both only grow, so after the
// first steps of a scene no allocation happens here.
#include "physics/contact.h"

#include <array>
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

/// What warm starting needs of a contact's previous step: its point ids and
/// impulses (a copy, so the manifold can be rewritten in place).
struct PreviousPoints {
  int32_t count = 0;
  std::array<uint16_t, 2> ids{};
  std::array<Q32, 2> normal_impulse{};
  std::array<Q32, 2> tangent_impulse{};
};

inline PreviousPoints previous_points(const Contact& c) {
  PreviousPoints p;
  p.count = c.manifold.point_count;
  p.ids = {c.manifold.points[0].id, c.manifold.points[1].id};
  p.normal_impulse = c.normal_impulse;
  p.tangent_impulse = c.tangent_impulse;
  return p;
}

/// Recomputes the manifold of `c` (whose key, generations, bodies and flags
/// are set) and writes every other field of it — manifold, friction,
/// restitution, impulses, the touching flag — so a contact updated in its
/// own slot ends with the same bytes as a fresh zeroed one (the merge path).
/// `previous` is last step's manifold (null for a new contact; it may be
/// c->manifold itself: collide_persistent reads it before writing) and
/// `old` its points and impulses, carried to the new points by feature id.
void update_manifold(const World& world, Contact* c, const Manifold* previous, const PreviousPoints& old) {
  const size_t sa = static_cast<size_t>(c->shape_a);
  const size_t sb = static_cast<size_t>(c->shape_b);
  const Shape& shape_a = world.shapes[sa];
  const Shape& shape_b = world.shapes[sb];
  const Transform& xf_a = world.body_sims[static_cast<size_t>(shape_a.body_index)].transform;
  const Transform& xf_b = world.body_sims[static_cast<size_t>(shape_b.body_index)].transform;
  if (previous != nullptr && (c->flags & k_contact_touching) != 0) {
    collide_persistent(world.shape_geometries[sa], xf_a, world.shape_geometries[sb], xf_b, *previous, &c->manifold);
  } else {
    c->manifold = collide(world.shape_geometries[sa], xf_a, world.shape_geometries[sb], xf_b);
  }
  c->friction = mix_friction_inline(shape_a.friction, shape_b.friction);
  c->restitution = max(shape_a.restitution, shape_b.restitution);  // mix_restitution
  const int32_t count = c->manifold.point_count;
  c->flags = count > 0 ? (c->flags | k_contact_touching) : (c->flags & ~k_contact_touching);
  for (size_t i = 0; i < 2; ++i) {
    Q32 normal{}, tangent{};
    if (static_cast<int32_t>(i) < count) {
      const uint16_t id = c->manifold.points[i].id;
      for (int32_t j = 0; j < old.count; ++j) {
        if (old.ids[static_cast<size_t>(j)] != id) continue;
        normal = old.normal_impulse[static_cast<size_t>(j)];
        tangent = old.tangent_impulse[static_cast<size_t>(j)];
        break;
      }
    }
    c->normal_impulse[i] = normal;
    c->tangent_impulse[i] = tangent;
  }
}

/// Builds World::awake_contacts lazily, for both paths of update_contacts:
/// contacts are noted in ascending index, and the list is written only from
/// the first contact with no moving body on (the ones before it filled in
/// then), so while every contact has a simulated body it stays empty and
/// `all` stays true (World::awake_contacts_all).
struct AwakeIndexBuilder {
  std::vector<int32_t>* awake;  ///< World::awake_contacts, cleared
  bool all = true;
  void note(int32_t index, bool moves) {
    if (all && !moves) {
      all = false;
      for (int32_t k = 0; k < index; ++k) awake->push_back(k);
    } else if (!all && moves) {
      awake->push_back(index);
    }
  }
};

/// Sets the fields that name a contact (key, generations, bodies) and its
/// carried flags; update_manifold writes the rest. The merge path calls it
/// on a zeroed slot; the in-place path keeps these fields as they are.
inline void set_contact_identity(Contact* c, const ShapePair& pair, uint32_t gen_a, uint32_t gen_b, int32_t body_a,
                                 int32_t body_b, uint32_t flags) {
  c->shape_a = pair.shape_a;
  c->shape_b = pair.shape_b;
  c->generation_a = gen_a;
  c->generation_b = gen_b;
  c->body_a = body_a;
  c->body_b = body_b;
  c->flags = flags;
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
  // (id_pool_generation's test written once: a slot outside the pool has
  // generation 0.)
  const uint32_t* generations = world->shape_pool.generations.data();
  const uint32_t shape_capacity = static_cast<uint32_t>(id_pool_capacity(world->shape_pool));
  const auto generation_of = [generations, shape_capacity](int32_t shape) {
    return static_cast<uint32_t>(shape) < shape_capacity ? generations[static_cast<uint32_t>(shape)] : 0u;
  };
  bool in_place = pairs.size() == old_list.size();
  for (size_t i = 0, n = in_place ? pairs.size() : 0; i < n; ++i) {
    const ShapePair& pair = pairs[i];
    const Contact& c = old_list[i];
    if (c.shape_a != pair.shape_a || c.shape_b != pair.shape_b || c.generation_a != generation_of(pair.shape_a) ||
        c.generation_b != generation_of(pair.shape_b)) {
      in_place = false;
      break;
    }
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
    // The awake index, only once a contact without a simulated body turns
    // up (before it every contact is awake; with none, awake_contacts_all).
    const int32_t count = static_cast<int32_t>(old_list.size());
    AwakeIndexBuilder index_builder{&awake};
    for (int32_t i = 0; i < count; ++i) {
      const Contact& c = old_list[static_cast<size_t>(i)];
      index_builder.note(i, (moving[c.body_a] | moving[c.body_b]) != 0);
    }
    const bool all = index_builder.all;
    world->awake_contacts_all = all;
    // The narrow phase over the awake contacts, each in its own slot: the
    // key, generations, bodies and flags stay (set_contact_identity's
    // fields), update_manifold writes every other field from last step's
    // points, as the merge path does for a zeroed slot.
    const int32_t awake_count = all ? count : static_cast<int32_t>(awake.size());
    const int32_t blocks = block_count_of(awake_count, k_contact_block);
    uint8_t* flipped = arena_allocate_array<uint8_t>(arena, blocks, "contact_touching_flipped");
    Contact* slots = old_list.data();
    const int32_t* index = all ? nullptr : awake.data();
    parallel_for(&world->tasks, "narrow_phase", awake_count, k_contact_block,
                 [&w, slots, index, flipped](int32_t begin, int32_t end) {
                   uint32_t changed = 0;
                   for (int32_t k = begin; k < end; ++k) {
                     Contact& c = slots[index != nullptr ? index[k] : k];
                     const uint32_t old_flags = c.flags;
                     update_manifold(w, &c, &c.manifold, previous_points(c));
                     changed |= (c.flags ^ old_flags) & k_contact_touching;
                   }
                   flipped[begin / k_contact_block] = changed != 0 ? 1 : 0;
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
  AwakeIndexBuilder index_builder{&awake};
  size_t cursor = 0;
  for (const ShapePair& pair : pairs) {
    const uint64_t key = shape_pair_key(pair.shape_a, pair.shape_b);
    // (the key computed inline: contact_key() lives out of line for other files)
    const auto old_key = [&old_list](size_t i) { return shape_pair_key(old_list[i].shape_a, old_list[i].shape_b); };
    while (cursor < old_list.size() && old_key(cursor) < key) ++cursor;  // destroyed
    const Contact* old = nullptr;
    const uint32_t gen_a = generation_of(pair.shape_a);
    const uint32_t gen_b = generation_of(pair.shape_b);
    if (cursor < old_list.size() && old_key(cursor) == key) {
      const Contact& candidate = old_list[cursor];
      if (candidate.generation_a == gen_a && candidate.generation_b == gen_b) old = &candidate;
      ++cursor;
    }
    const int32_t body_a = world->shapes[static_cast<size_t>(pair.shape_a)].body_index;
    const int32_t body_b = world->shapes[static_cast<size_t>(pair.shape_b)].body_index;
    const bool moves = simulated(body_a) || simulated(body_b);
    // A new contact between two bodies that do not move is still computed
    // (it has no manifold yet) but is not an awake contact: no stage after
    // this one has work for it (no constraint, no wake, no island).
    index_builder.note(static_cast<int32_t>(next.size()), moves);
    if (old != nullptr && !moves) {
      // Neither body moves (asleep, static or disabled): the manifold and the
      // impulses are still valid; keep them for when the island wakes.
      old_of[next.size()] = k_carried_contact;
      next.push_back(*old);
      continue;
    }
    old_of[next.size()] = old != nullptr ? static_cast<int32_t>(old - old_list.data()) : k_no_old_contact;
    Contact& c = next.emplace_back();  // zeroed in place (no copy); the narrow phase fills the manifold
    set_contact_identity(&c, pair, gen_a, gen_b, body_a, body_b, old != nullptr ? old->flags : 0);
  }
  world->awake_contacts_all = index_builder.all;
  // The narrow phase, per contact (see the file comment).
  Contact* slots = next.data();
  const Contact* olds = old_list.data();
  parallel_for(&world->tasks, "narrow_phase", static_cast<int32_t>(next.size()), k_contact_block,
               [&w, slots, olds, old_of](int32_t begin, int32_t end) {
                 for (int32_t i = begin; i < end; ++i) {
                   const int32_t o = old_of[i];
                   if (o == k_carried_contact) continue;
                   if (o >= 0) {
                     update_manifold(w, &slots[i], &olds[o].manifold, previous_points(olds[o]));
                   } else {
                     update_manifold(w, &slots[i], nullptr, PreviousPoints{});
                   }
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
