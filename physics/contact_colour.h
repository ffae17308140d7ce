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

/// Colours the `count` constraints prepare_contact_constraints will build
/// (touching contacts with at least one simulated body, in contact order):
/// returns an arena array (`count` entries, colour 0 … k_contact_colour_count,
/// the last being the overflow colour) that the caller frees, and writes
/// context->colour_offsets, colour_count and overflow_constraint_count.
/// *out_cursor[k] receives the first constraint slot of colour k (the caller
/// advances it while storing constraints colour by colour).
int32_t* colour_contact_constraints(World* world, StepContext* context, int32_t count,
                                    int32_t (*out_cursor)[k_contact_colour_count + 2]);

}  // namespace tandem
