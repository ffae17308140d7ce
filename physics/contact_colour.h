// contact_colour.h — graph colouring of the contact constraints (internal).
//
// Each step, prepare_contact_constraints (contact_prepare.cpp) stores its
// constraints colour by colour; this module decides the colours. The
// colouring is a pure function of the contact list (in contact order, i.e.
// sorted by shape-pair key) and of which bodies are simulated and movable:
// no timing, address or worker count enters it, so every peer and every
// worker count gets the same colours (contact_colour.cpp has the design
// notes).
#pragma once

#include <cstdint>

#include "physics/contact_solver.h"

namespace tandem {

struct World;
struct StepContext;

/// One constraint prepare_contact_constraints builds, as the colouring pass
/// found it: the contact and its bodies' solver indices (so the preparation
/// does not read the contact's flags and body_to_solver a second time) and
/// its colour.
struct ConstraintJob {
  int32_t contact;   ///< into World::contacts
  int32_t solver_a;  ///< solver index of body A, or k_null_index
  int32_t solver_b;  ///< solver index of body B, or k_null_index
  int32_t colour;    ///< 0 … k_contact_colour_count (the last: the overflow colour)
  /// Its place among the constraints of its colour (contact order): the
  /// constraint is stored at colour_offsets[colour] + rank.
  int32_t rank;
};

/// Colours the `count` constraints prepare_contact_constraints will build
/// (touching contacts with at least one simulated body, in contact order):
/// returns an arena array of their `count` jobs, in contact order, that the
/// caller frees, and writes context->colour_offsets, colour_count and
/// overflow_constraint_count. Job n's constraint belongs at
/// colour_offsets[colour] + rank (colour by colour, contact order within a
/// colour).
ConstraintJob* colour_contact_constraints(World* world, StepContext* context, int32_t count);

}  // namespace tandem
