// island.cpp — sleep timers, per-step union-find islands, sleeping and
// waking (design in island.h).
//
// Determinism: every loop runs in ascending body index or in contact order
// (sorted by shape-pair key); union always makes the lower root the parent,
// so the root of a set is its lowest body index whatever the union order;
// path halving only shortens paths. Nothing depends on addresses.
//
// Workers (task.h): the per-body passes (sleep timers, the start states of
// stage_wake_touched) and stage_wake_touched's scan for its first waking
// contact run in fixed blocks on any thread, each block writing its own
// slots and a per-block count or first index that the stepping thread
// combines in block order. Waking (from the first waking contact on) and the
// islands (union-find in contact order, then joint order) stay on the
// stepping thread, so the order of wakes and unions is the data's. The
// islands are built only when some body's timer has run out: a step in
// which every awake body still moves, or no body is awake, pays only the
// timer pass.
#include "physics/island.h"

#include "physics/world.h"

namespace tandem {

namespace {

bool is_dynamic_simulated(const Body& b) { return b.type == BodyType::dynamic_body && body_is_simulated(b); }

/// The body is asleep (non-static, enabled, not awake).
bool is_sleeping(const Body& b) { return b.type != BodyType::static_body && b.enabled && !b.awake; }

/// An awake body that wakes sleepers it touches: dynamic, or kinematic and
/// moving in the last step (or just woken).
bool wakes_others(const Body& b) {
  if (!body_is_simulated(b)) return false;
  return b.type == BodyType::dynamic_body || b.sleep_time == Q32::zero();
}

void wake_one(Body* b) {
  b->awake = true;
  b->sleep_time = Q32::zero();
  b->sleep_island = k_null_index;
}

/// Bodies per block of the parallel per-body passes (sleep timers, wake
/// start states).
constexpr int32_t k_sleep_block = 256;
/// Contacts per block of the parallel scan for the first waking contact.
constexpr int32_t k_wake_scan_block = 512;

/// Root of `i` with path halving; parents always have lower indices.
int32_t find_root(int32_t* parent, int32_t i) {
  while (parent[i] != i) {
    parent[i] = parent[parent[i]];
    i = parent[i];
  }
  return i;
}

}  // namespace

int32_t wake_touching_count(World* world, int32_t body_index);

void wake_body_island(World* world, int32_t body_index) {
  ++world->wake_count;  // the awake contact index may be incomplete now (world.h)
  Body& body = world->bodies[static_cast<size_t>(body_index)];
  if (body.type == BodyType::static_body) return;
  if (body.awake || body.sleep_island == k_null_index) {
    wake_one(&body);
    return;
  }
  const int32_t island = body.sleep_island;
  const int32_t end = id_pool_capacity(world->body_pool);
  for (int32_t b = 0; b < end; ++b) {
    Body& other = world->bodies[static_cast<size_t>(b)];
    if (!id_pool_is_alive(world->body_pool, b) || other.awake || other.sleep_island != island) continue;
    wake_one(&other);
  }
  wake_one(&body);
}

void wake_touching(World* world, int32_t body_index) {
  (void)wake_touching_count(world, body_index);
}

void wake_body_and_touching(World* world, int32_t body_index, bool wake_lone_sleeper) {
  const int32_t touching = wake_touching_count(world, body_index);
  if (touching > 0 || wake_lone_sleeper || world->bodies[static_cast<size_t>(body_index)].awake) {
    wake_body_island(world, body_index);
  }
}

void wake_overlapping_sleepers(World* world, int32_t body_index) {
  const Body& body = world->bodies[static_cast<size_t>(body_index)];
  for (int32_t si = body.head_shape; si != k_null_index; si = world->shapes[static_cast<size_t>(si)].next_shape) {
    const AABB moved = world->shapes[static_cast<size_t>(si)].aabb;
    for (size_t other = 0; other < world->shapes.size(); ++other) {
      if (!id_pool_is_alive(world->shape_pool, static_cast<int32_t>(other))) continue;
      const Shape& shape = world->shapes[other];
      if (shape.body_index == body_index) continue;
      if (!is_sleeping(world->bodies[static_cast<size_t>(shape.body_index)])) continue;
      if (aabb_overlaps(moved, shape.aabb)) wake_body_island(world, shape.body_index);
    }
  }
}

int32_t wake_touching_count(World* world, int32_t body_index) {
  int32_t touching = 0;
  for (const Contact& c : world->contacts) {
    if ((c.flags & k_contact_touching) == 0) continue;
    int32_t other = k_null_index;
    if (c.body_a == body_index) other = c.body_b;
    if (c.body_b == body_index) other = c.body_a;
    if (other == k_null_index || other == body_index) continue;
    ++touching;
    if (!id_pool_is_alive(world->body_pool, other)) continue;
    if (is_sleeping(world->bodies[static_cast<size_t>(other)])) wake_body_island(world, other);
  }
  return touching;
}

void put_body_to_sleep(World* world, int32_t body_index) {
  Body& body = world->bodies[static_cast<size_t>(body_index)];
  BodySim& sim = world->body_sims[static_cast<size_t>(body_index)];
  body.awake = false;
  body.sleep_time = Q32::zero();
  body.sleep_island = body_index;
  sim.linear_velocity = {};
  sim.angular_velocity = Q32::zero();
  sim.force = {};
  sim.torque = Q32::zero();
}

void wake_all_bodies(World* world) {
  ++world->wake_count;
  const int32_t end = id_pool_capacity(world->body_pool);
  for (int32_t b = 0; b < end; ++b) {
    Body& body = world->bodies[static_cast<size_t>(b)];
    if (!id_pool_is_alive(world->body_pool, b) || body.type == BodyType::static_body) continue;
    wake_one(&body);
  }
}

void stage_wake_touched(World* world, StepContext* context) {
  // The rule, contact by contact in contact order: a touching contact wakes
  // the island of a sleeping body whose other body wakes others. Bodies only
  // go from asleep to awake here, so until the first wake of this pass every
  // body's state is still its state at the start. So the pass is in two
  // parts: the first contact that wakes something is found from the start
  // states alone (a pure test: blocks of k_wake_scan_block contacts on any
  // thread, each reporting its first candidate, combined in block order into
  // the lowest); from there on the contacts are walked serially reading the
  // Body records (a woken body now wakes others). Same wakes in the same
  // order as testing the records for every contact.
  //
  // Only a contact with a body that wakes others — a simulated one — can
  // wake, and at the start of this pass (right after update_contacts, before
  // any wake) those are exactly the awake index's contacts: the scan reads
  // only them (World::awake_contacts, in contact order), not the contacts of
  // sleeping islands (while awake_contacts_all the index is the whole list:
  // the scan reads it all). The start states come from one of two places, the
  // cheaper for the counts at hand (both give the same answer):
  //   * few awake contacts for the bodies (a sleeping pile): the scan reads
  //     the Body records themselves, so no pass over every body;
  //   * otherwise a per-body byte array of start states, filled in parallel,
  //     which also counts the sleepers: with none (everything awake) the
  //     scan is skipped.
  const int32_t end = id_pool_capacity(world->body_pool);
  constexpr uint8_t k_sleeping = 1, k_wakes_others = 2;
  Arena* arena = &world->arena;
  const int32_t contact_count = static_cast<int32_t>(world->contacts.size());
  int32_t first = contact_count;  // the first contact whose start states wake a sleeper
  const int32_t scan_count = awake_contact_count(*world);
  const bool use_states = 2 * static_cast<int64_t>(scan_count) > end;
  uint8_t* start = nullptr;
  int32_t* sleepers_per_block = nullptr;
  int32_t sleepers = 1;  // unknown without the states: scan
  if (use_states) {
    start = arena_allocate_array<uint8_t>(arena, end, "wake_start_states");
    const int32_t body_blocks = block_count_of(end, k_sleep_block);
    sleepers_per_block = arena_allocate_array<int32_t>(arena, body_blocks, "wake_sleepers_per_block");
    const World* w = world;
    uint8_t* states = start;
    int32_t* per_block = sleepers_per_block;
    parallel_for(context->tasks, "wake_start_states", end, k_sleep_block, [=](int32_t begin, int32_t stop) {
      int32_t count = 0;
      for (int32_t b = begin; b < stop; ++b) {
        const Body& body = w->bodies[static_cast<size_t>(b)];
        uint8_t state = 0;
        if (id_pool_is_alive(w->body_pool, b)) {
          if (is_sleeping(body)) state = k_sleeping;
          if (wakes_others(body)) state = k_wakes_others;
        }
        count += state == k_sleeping ? 1 : 0;
        states[b] = state;
      }
      per_block[begin / k_sleep_block] = count;
    });
    sleepers = 0;
    for (int32_t k = 0; k < body_blocks; ++k) sleepers += sleepers_per_block[k];
  }
  if (sleepers > 0 && scan_count > 0) {
    world->contacts_read_after_update += scan_count;
    const int32_t scan_blocks = block_count_of(scan_count, k_wake_scan_block);
    int32_t* first_per_block = arena_allocate_array<int32_t>(arena, scan_blocks, "wake_first_per_block");
    const Contact* contacts = world->contacts.data();
    const int32_t* scan = world->awake_contacts_all ? nullptr : world->awake_contacts.data();
    const Body* bodies = world->bodies.data();
    const uint8_t* states = start;
    parallel_for(context->tasks, "wake_touched_scan", scan_count, k_wake_scan_block,
                 [=](int32_t begin, int32_t stop) {
                   int32_t found = stop;
                   for (int32_t k = begin; k < stop; ++k) {
                     const Contact& c = contacts[scan != nullptr ? scan[k] : k];
                     if ((c.flags & k_contact_touching) == 0) continue;
                     bool wakes;
                     if (states != nullptr) {
                       const uint8_t sa = states[c.body_a], sb = states[c.body_b];
                       wakes = (sa == k_sleeping && sb == k_wakes_others) || (sb == k_sleeping && sa == k_wakes_others);
                     } else {
                       const Body& a = bodies[c.body_a];
                       const Body& b = bodies[c.body_b];
                       wakes = (is_sleeping(a) && wakes_others(b)) || (is_sleeping(b) && wakes_others(a));
                     }
                     if (wakes) {
                       found = k;
                       break;
                     }
                   }
                   first_per_block[begin / k_wake_scan_block] = found;
                 });
    for (int32_t k = 0; k < scan_blocks; ++k) {
      const int32_t block_end = k == scan_blocks - 1 ? scan_count : (k + 1) * k_wake_scan_block;
      if (first_per_block[k] < block_end) {
        first = scan != nullptr ? scan[first_per_block[k]] : first_per_block[k];
        break;
      }
    }
    arena_free(arena, first_per_block);
  }
  world->contacts_read_after_update += contact_count - first;
  for (int32_t i = first; i < contact_count; ++i) {
    const Contact& c = world->contacts[static_cast<size_t>(i)];
    if ((c.flags & k_contact_touching) == 0) continue;
    Body& a = world->bodies[static_cast<size_t>(c.body_a)];
    Body& b = world->bodies[static_cast<size_t>(c.body_b)];
    if (is_sleeping(a) && wakes_others(b)) wake_body_island(world, c.body_a);
    if (is_sleeping(b) && wakes_others(a)) wake_body_island(world, c.body_b);
  }
  if (use_states) {
    arena_free(arena, sleepers_per_block);
    arena_free(arena, start);
  }
}

void stage_update_sleep(World* world, StepContext* context) {
  const int32_t end = id_pool_capacity(world->body_pool);
  const bool enabled = world->def.enable_sleep;
  const Q32 dt = context->dt;

  // 1. Timers of the bodies simulated this step (finalize may have disabled
  //    some: they are skipped), per body in blocks of k_sleep_block on any
  //    thread (a body writes only its own timer). Each block also counts its
  //    bodies whose timer has run out; the counts are summed in block order.
  Arena* arena = &world->arena;
  const int32_t blocks = block_count_of(end, k_sleep_block);
  int32_t* ready_per_block = arena_allocate_array<int32_t>(arena, blocks, "sleep_ready_per_block");
  {
    World* w = world;
    parallel_for(context->tasks, "sleep_timers", end, k_sleep_block, [=](int32_t begin, int32_t stop) {
      int32_t ready = 0;
      for (int32_t b = begin; b < stop; ++b) {
        Body& body = w->bodies[static_cast<size_t>(b)];
        if (!id_pool_is_alive(w->body_pool, b) || !body_is_simulated(body)) continue;
        const BodySim& sim = w->body_sims[static_cast<size_t>(b)];
        const bool still = enabled && body.enable_sleep &&
                           !length_exceeds(sim.linear_velocity, k_linear_sleep_tolerance) &&
                           abs(sim.angular_velocity) <= k_angular_sleep_tolerance;
        // sleep_time ≤ k_time_to_sleep and dt ≤ k_max_time_step: the sum fits.
        body.sleep_time = still ? min(body.sleep_time + dt, k_time_to_sleep) : Q32::zero();
        ready += body.sleep_time < k_time_to_sleep ? 0 : 1;
      }
      ready_per_block[begin / k_sleep_block] = ready;
    });
  }
  int32_t ready = 0;
  for (int32_t k = 0; k < blocks; ++k) ready += ready_per_block[k];
  arena_free(arena, ready_per_block);
  if (!enabled) return;
  // Only a simulated body whose timer has run out can fall asleep (any other
  // blocks its own island, step 3), so with none the islands need not be
  // built: this is every step in which all awake bodies still move, or none
  // is awake.
  if (ready == 0) return;

  // 2. Union-find over touching contacts between two simulated dynamic bodies.
  int32_t* parent = arena_allocate_array<int32_t>(arena, end, "island_parent");
  uint8_t* blocked = arena_allocate_array<uint8_t>(arena, end, "island_blocked");
  for (int32_t b = 0; b < end; ++b) {
    parent[b] = b;
    blocked[b] = 0;
  }
  //    Contacts of sleeping islands are not read while the awake index is
  //    complete (for_each_awake_contact: no wake this step; finalize may
  //    only have disabled bodies, which the test below skips).
  const Contact* contacts = world->contacts.data();
  for_each_awake_contact(*world, [&](int32_t ci) {
    const Contact& c = contacts[ci];
    if ((c.flags & k_contact_touching) == 0) return;
    if (!is_dynamic_simulated(world->bodies[static_cast<size_t>(c.body_a)]) ||
        !is_dynamic_simulated(world->bodies[static_cast<size_t>(c.body_b)])) {
      return;
    }
    const int32_t ra = find_root(parent, c.body_a), rb = find_root(parent, c.body_b);
    if (ra < rb) parent[rb] = ra;
    if (rb < ra) parent[ra] = rb;
  });
  // 2b. Joints between two simulated dynamic bodies, in joint index order.
  for (int32_t ji = 0; ji < id_pool_capacity(world->joint_pool); ++ji) {
    if (!id_pool_is_alive(world->joint_pool, ji)) continue;
    const Joint& j = world->joints.joints[static_cast<size_t>(ji)];
    if (!is_dynamic_simulated(world->bodies[static_cast<size_t>(j.body_a)]) ||
        !is_dynamic_simulated(world->bodies[static_cast<size_t>(j.body_b)])) {
      continue;
    }
    const int32_t ra = find_root(parent, j.body_a), rb = find_root(parent, j.body_b);
    if (ra < rb) parent[rb] = ra;
    if (rb < ra) parent[ra] = rb;
  }

  // 3. An island may sleep when every body in it has been still long enough.
  for (int32_t b = 0; b < end; ++b) {
    const Body& body = world->bodies[static_cast<size_t>(b)];
    if (!id_pool_is_alive(world->body_pool, b) || !body_is_simulated(body)) continue;
    if (body.sleep_time < k_time_to_sleep) blocked[find_root(parent, b)] = 1;
  }
  // 3b. A moving kinematic body (its timer not run out) keeps the island of
  //     every dynamic body joined to it awake: the joint drives that body, so
  //     it would be woken again by stage_wake_joined the next step.
  for (int32_t ji = 0; ji < id_pool_capacity(world->joint_pool); ++ji) {
    if (!id_pool_is_alive(world->joint_pool, ji)) continue;
    const Joint& j = world->joints.joints[static_cast<size_t>(ji)];
    const Body& a = world->bodies[static_cast<size_t>(j.body_a)];
    const Body& b = world->bodies[static_cast<size_t>(j.body_b)];
    const auto moving_kinematic = [](const Body& k) {
      return k.type == BodyType::kinematic_body && body_is_simulated(k) && k.sleep_time < k_time_to_sleep;
    };
    if (is_dynamic_simulated(a) && moving_kinematic(b)) blocked[find_root(parent, j.body_a)] = 1;
    if (is_dynamic_simulated(b) && moving_kinematic(a)) blocked[find_root(parent, j.body_b)] = 1;
  }
  for (int32_t b = 0; b < end; ++b) {
    const Body& body = world->bodies[static_cast<size_t>(b)];
    if (!id_pool_is_alive(world->body_pool, b) || !body_is_simulated(body)) continue;
    const int32_t root = find_root(parent, b);
    if (blocked[root] != 0) continue;
    put_body_to_sleep(world, b);
    world->bodies[static_cast<size_t>(b)].sleep_island = root;
  }
  arena_free(arena, blocked);
  arena_free(arena, parent);
}

}  // namespace tandem
