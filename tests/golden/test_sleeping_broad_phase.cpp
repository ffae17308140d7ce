// The broad phase's carry-over (broad_phase.cpp, "Carry-over"): an update
// searches only the proxies whose box, kind or filter changed since the last
// one and keeps the pairs between unchanged proxies. This must give exactly
// the full search's pair list, for every broad phase, through sleep, waking,
// restores, bodies created and destroyed next to a sleeping pile, a filter
// changed on a sleeping shape, and a joint (collide_connected = false) made
// and removed between two sleeping boxes. The reference world is the same
// scene with a custom filter that accepts everything: a custom filter turns
// the carry-over off, so its every update is the full search. And while the
// pile sleeps untouched, the broad phase searches only the awake proxies
// (BroadPhaseStats::proxies_searched), never the pile's.
#include <catch2/catch.hpp>

#include <cstdint>
#include <vector>

#include "../physics/physics_test_support.h"
#include "physics/joint.h"
#include "physics/tandem.h"
#include "physics/world.h"
#include "replay/state.h"

using namespace tandem;

namespace {

constexpr int32_t k_columns = 16;
constexpr int32_t k_rows = 6;
constexpr int32_t k_steps = 140;

bool accept_all(ShapeId, ShapeId, void*) { return true; }

/// One world of the scene and the handles the scripted edits use.
struct PileWorld {
  WorldId id;
  std::vector<BodyId> block;  ///< column-major: block[c * k_rows + r]
  JointId joint;
};

BodyId add_box(WorldId world, Q32 x, Q32 y, bool awake) {
  BodyDef bd = test_support::body_def_at({x, y});
  bd.is_awake = awake;
  return test_support::add_box_body(world, bd, 0.25_q32, 0.25_q32);
}

PileWorld make_pile_world(BroadPhaseKind kind, int32_t workers, bool reference) {
  WorldDef wd = default_world_def();
  wd.worker_count = workers;
  wd.broad_phase = kind;
  const Result<WorldId> w = create_world(wd);
  REQUIRE(w.ok());
  PileWorld pw;
  pw.id = w.value;
  if (reference) REQUIRE(world_set_custom_filter(pw.id, accept_all, nullptr).ok());
  test_support::add_box_body(pw.id, test_support::body_def_at({0_q32, -1_q32}, BodyType::static_body), 60_q32, 1_q32);
  for (int32_t c = 0; c < k_columns; ++c) {
    for (int32_t r = 0; r < k_rows; ++r) {
      pw.block.push_back(add_box(pw.id, Q32::from_ratio(c, 2), Q32::from_ratio(2 * r + 1, 4), false));
    }
  }
  for (int32_t i = 0; i < 5; ++i) add_box(pw.id, -20_q32, Q32::from_ratio(2 * i + 1, 4), true);  // an awake stack
  BodyDef bd = test_support::body_def_at({-4_q32, 0.5_q32});
  bd.linear_velocity = {4_q32, 0_q32};
  test_support::add_ball_body(pw.id, bd, 0.5_q32, 4_q32);
  return pw;
}

/// The scripted edits, applied between steps to every world alike.
void edit(PileWorld* pw, int32_t step) {
  const auto at = [&](int32_t c, int32_t r) { return pw->block[static_cast<size_t>(c * k_rows + r)]; };
  switch (step) {
    case 20:  // a sleeping box created touching the pile's right side
      add_box(pw->id, Q32::from_ratio(k_columns, 2), 0.25_q32, false);
      break;
    case 28: {  // a sleeping shape stops colliding with anything
      ShapeId s[1];
      REQUIRE(body_shapes(at(8, 2), s, 1) == 1);
      Filter f = shape_filter(s[0]);
      f.mask_bits = 0;
      REQUIRE(shape_set_filter(s[0], f).ok());
      break;
    }
    case 34: {  // a joint between two touching boxes of the pile: their pair goes
      RevoluteJointDef jd = default_revolute_joint_def();
      jd.base.body_a = at(12, 3);
      jd.base.body_b = at(12, 4);
      const Result<JointId> j = create_revolute_joint(pw->id, jd);
      REQUIRE(j.ok());
      pw->joint = j.value;
      break;
    }
    case 44:  // and comes back
      REQUIRE(destroy_joint(pw->joint).ok());
      break;
    case 50:  // a top box of the pile destroyed
      REQUIRE(destroy_body(at(14, k_rows - 1)).ok());
      break;
    default: break;
  }
}

std::vector<uint64_t> pair_keys(WorldId id) {
  std::vector<uint64_t> keys;
  for (const ShapePair& p : find_world(id)->broad_phase.pairs) keys.push_back(shape_pair_key(p.shape_a, p.shape_b));
  return keys;
}

/// What one run records, per step.
struct PileRun {
  std::vector<std::vector<uint64_t>> pairs;
  std::vector<uint64_t> hashes;
  int32_t most_searched_asleep = 0;  ///< most proxies_searched over steps 5…15 (pile asleep, untouched)
  int32_t least_carried_asleep = INT32_MAX;
  int32_t pairs_asleep = 0;          ///< pairs at step 10
  int64_t carried_total = 0;
};

PileRun run_pile(BroadPhaseKind kind, int32_t workers, bool reference, int32_t restore_every) {
  PileWorld pw = make_pile_world(kind, workers, reference);
  PileRun run;
  std::vector<uint8_t> image;
  for (int32_t i = 1; i <= k_steps; ++i) {
    edit(&pw, i);
    REQUIRE(world_step(pw.id, Q32::from_ratio(1, 60)).ok());
    run.pairs.push_back(pair_keys(pw.id));
    run.hashes.push_back(world_state_hash(pw.id));
    const BroadPhaseStats s = world_broad_phase_stats(pw.id);
    run.carried_total += s.pairs_carried;
    if (i >= 5 && i <= 15) {
      if (s.proxies_searched > run.most_searched_asleep) run.most_searched_asleep = s.proxies_searched;
      if (s.pairs_carried < run.least_carried_asleep) run.least_carried_asleep = s.pairs_carried;
    }
    if (i == 10) run.pairs_asleep = s.pairs;
    if (restore_every > 0 && i % restore_every == 0) {
      image.clear();
      REQUIRE(world_snapshot_append(pw.id, &image).ok());
      REQUIRE(world_restore(pw.id, image.data(), image.size()).ok());
    }
  }
  bool woke = false;
  for (const BodyId b : pw.block) woke = woke || (body_is_valid(b) && body_is_awake(b));
  CHECK(woke);  // the ball reached the pile
  REQUIRE(destroy_world(pw.id).ok());
  return run;
}

}  // namespace

TEST_CASE("carried-over broad-phase pairs equal the full search for every kind, through sleep, wake and edits",
          "[golden][sleep][broad_phase]") {
  const PileRun reference = run_pile(BroadPhaseKind::naive, 1, true, 0);
  CHECK(reference.carried_total == 0);  // a custom filter: every update searched everything
  for (const BroadPhaseKind kind : {BroadPhaseKind::naive, BroadPhaseKind::sweep_and_prune, BroadPhaseKind::grid,
                                    BroadPhaseKind::tree}) {
    INFO("broad phase " << static_cast<int32_t>(kind));
    const PileRun run = run_pile(kind, 1, false, 0);
    for (int32_t i = 0; i < k_steps; ++i) {
      INFO("step " << i + 1);
      REQUIRE(run.pairs[static_cast<size_t>(i)] == reference.pairs[static_cast<size_t>(i)]);
    }
    CHECK(run.hashes == reference.hashes);
    CHECK(run.carried_total > 0);
    // While the pile sleeps untouched, only the awake stack and the ball
    // (6 proxies) are searched and the pile's pairs are carried over.
    INFO("searched " << run.most_searched_asleep << ", carried " << run.least_carried_asleep << " of "
                     << run.pairs_asleep);
    CHECK(run.most_searched_asleep <= 6);
    CHECK(run.least_carried_asleep + 20 >= run.pairs_asleep);
    CHECK(run.pairs_asleep > 200);
  }
  INFO("2 workers; restored from its own snapshot every 7 steps");
  CHECK(run_pile(BroadPhaseKind::grid, 2, false, 0).hashes == reference.hashes);
  CHECK(run_pile(BroadPhaseKind::grid, 1, false, 7).hashes == reference.hashes);
  CHECK(run_pile(BroadPhaseKind::tree, 3, false, 5).hashes == reference.hashes);
  CHECK(run_pile(BroadPhaseKind::sweep_and_prune, 2, false, 6).hashes == reference.hashes);
}
