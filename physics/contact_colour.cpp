// contact_colour.cpp — graph colouring of the contact constraints.
//
// Greedy, in contact order: each constraint takes the lowest colour not yet
// used by either of its movable bodies (a body with zero inverse mass and
// inertia — kinematic — is never changed by the solver, so it constrains
// nothing); constraints that find no free colour go to the overflow colour,
// solved last. The pass hands prepare_contact_constraints each constraint's
// contact, solver indices and colour (ConstraintJob, in contact order), which
// then stores the constraints colour by colour, in contact order within a
// colour, without walking the awake index again. Consecutive constraints of
// one colour touch disjoint bodies, so the scalar loops carry no memory
// dependency from one to the next and a wide solver can take a colour in
// lanes.
//
// Cost: one pass over the contacts with a 32-bit colour mask per solver body:
// ~70 instructions per constraint on x86-64, the job record (with its rank
// in its colour) included (pyramid-100, callgrind), 7 % of the
// preparation's ~1,000 (docs/benchmarks.md).
//
// Rejected (for now): incremental colouring (a persistent contact keeps last
// step's colour, as Box2D v3's constraint graph does). The colour decides the
// solve order and so the results; a colour carried from the previous step
// would be state that snapshots, rollback and replays must carry too (or
// rebuild exactly, which is this pass), and the most it could save is the
// pass's ~55 instructions per constraint (the job record is needed anyway),
// while checking which contacts kept their bodies and neighbours costs a
// good part of that. The pass stays a pure function of this step's contact
// list.
#include "physics/contact_colour.h"

#include <bit>

#include "physics/arena.h"
#include "physics/world.h"

namespace tandem {

ConstraintJob* colour_contact_constraints(World* world, StepContext* context, int32_t count) {
  Arena* arena = &world->arena;
  ConstraintJob* jobs = arena_allocate_array_for_overwrite<ConstraintJob>(arena, count, "constraint_jobs");
  uint32_t* colour_masks = arena_allocate_array<uint32_t>(arena, context->solver_body_count, "colour_masks");
  for (int32_t i = 0; i < context->solver_body_count; ++i) colour_masks[i] = 0;
  int32_t colour_start[k_contact_colour_count + 2] = {};  // per colour k: count at [k + 1], then first slot at [k]
  const auto movable = [context](int32_t solver_index) {
    if (solver_index < 0) return false;
    const SolverBodyParams& p = context->params[solver_index];
    return p.inv_mass != Q32::zero() || p.inv_inertia != Q32::zero();
  };
  int32_t n = 0;
  const Contact* contacts = world->contacts.data();
  for_each_awake_contact(*world, [&](int32_t ci) {
    const Contact& c = contacts[ci];
    if ((c.flags & k_contact_touching) == 0) return;
    const int32_t ia = context->body_to_solver[static_cast<size_t>(c.body_a)];
    const int32_t ib = context->body_to_solver[static_cast<size_t>(c.body_b)];
    if (ia == k_null_index && ib == k_null_index) return;
    const bool ma = movable(ia), mb = movable(ib);
    const uint32_t used = (ma ? colour_masks[ia] : 0u) | (mb ? colour_masks[ib] : 0u);
    const uint32_t free = ~used & ((uint32_t{1} << k_contact_colour_count) - 1u);
    int32_t colour = k_contact_colour_count;  // overflow
    if (free != 0) {
      colour = std::countr_zero(free);
      if (ma) colour_masks[ia] |= uint32_t{1} << colour;
      if (mb) colour_masks[ib] |= uint32_t{1} << colour;
    }
    jobs[n++] = ConstraintJob{ci, ia, ib, colour, colour_start[colour + 1]++};
  });
  for (int32_t k = 0; k <= k_contact_colour_count; ++k) colour_start[k + 1] += colour_start[k];
  for (int32_t k = 0; k <= k_contact_colour_count + 1; ++k) context->colour_offsets[k] = colour_start[k];
  context->colour_count = 0;
  for (int32_t k = 0; k <= k_contact_colour_count; ++k)
    if (colour_start[k + 1] > colour_start[k]) context->colour_count = k + 1;
  context->overflow_constraint_count = colour_start[k_contact_colour_count + 1] - colour_start[k_contact_colour_count];
  arena_free(arena, colour_masks);
  return jobs;
}

}  // namespace tandem
