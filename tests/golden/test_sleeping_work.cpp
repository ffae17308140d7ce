// Work not done while a world sleeps (World::awake_contacts, contact.cpp,
// island.cpp, events.cpp): a large block of boxes created asleep on the
// ground next to an awake part (a settling stack and a ball rolling into the
// block, which wakes it). The skipped work must change nothing: the per-step
// state hashes are the same for every worker count and when the world is
// restored from its own snapshot every few steps (a restored world starts
// with no awake index and no events in sync, so its next step takes the full
// passes); and while the block sleeps, the stages after the contact update
// read only the awake contacts (BroadPhaseStats::contacts_read_after_update),
// not the block's.
#include <catch2/catch.hpp>

#include <cstdint>
#include <vector>

#include "../physics/physics_test_support.h"
#include "physics/tandem.h"
#include "replay/state.h"

using namespace tandem;

namespace {

constexpr int32_t k_columns = 40;
constexpr int32_t k_rows = 10;

/// What one run records.
struct SleepingRun {
  std::vector<uint64_t> hashes;  ///< world_state_hash after each step
  int32_t contacts = 0;          ///< contacts while the block sleeps (step 10)
  int32_t awake_contacts = 0;    ///< of them with a simulated body
  int64_t most_read = 0;         ///< most contacts_read_after_update over steps 5…15
  bool block_woke = false;       ///< some box of the block was awake after some step (the ball
                                 ///< reaches it at step ~75; it may sleep again by step 150)
};

/// `restore_every` > 0: snapshot and restore the world into itself after every
/// that many steps.
SleepingRun run_sleeping_world(int32_t workers, int32_t steps, int32_t restore_every) {
  WorldDef wd = default_world_def();
  wd.worker_count = workers;
  test_support::ScopedWorld scoped(wd);
  const WorldId world = scoped.id;
  test_support::add_box_body(world, test_support::body_def_at({0_q32, -1_q32}, BodyType::static_body), 100_q32, 1_q32);
  std::vector<BodyId> block;
  for (int32_t c = 0; c < k_columns; ++c) {
    for (int32_t r = 0; r < k_rows; ++r) {
      BodyDef bd = test_support::body_def_at({Q32::from_ratio(c, 2), Q32::from_ratio(2 * r + 1, 4)});
      bd.is_awake = false;
      block.push_back(test_support::add_box_body(world, bd, 0.25_q32, 0.25_q32));
    }
  }
  for (int32_t i = 0; i < 5; ++i) {  // an awake stack far from the block
    test_support::add_box_body(world, test_support::body_def_at({-30_q32, Q32::from_ratio(2 * i + 1, 4)}), 0.25_q32,
                               0.25_q32);
  }
  BodyDef ball = test_support::body_def_at({-4_q32, 0.5_q32});
  ball.linear_velocity = {4_q32, 0_q32};
  test_support::add_ball_body(world, ball, 0.5_q32, 4_q32);

  SleepingRun run;
  const Q32 dt = Q32::from_ratio(1, 60);
  std::vector<uint8_t> image;
  for (int32_t i = 1; i <= steps; ++i) {
    const StepResult r = world_step(world, dt);
    REQUIRE(r.ok());
    run.hashes.push_back(world_state_hash(world));
    for (BodyId b : block) run.block_woke = run.block_woke || body_is_awake(b);
    const BroadPhaseStats s = world_broad_phase_stats(world);
    if (i >= 5 && i <= 15 && s.contacts_read_after_update > run.most_read) run.most_read = s.contacts_read_after_update;
    if (i == 10) {
      run.contacts = s.pairs;
      run.awake_contacts = s.awake_contacts;
    }
    if (restore_every > 0 && i % restore_every == 0) {
      image.clear();
      REQUIRE(world_snapshot_append(world, &image).ok());
      REQUIRE(world_restore(world, image.data(), image.size()).ok());
    }
  }
  return run;
}

}  // namespace

TEST_CASE("a sleeping block next to an awake part: same bits for every worker count and after restores",
          "[golden][sleep][workers]") {
  // Every build runs the same steps: the ball, slowed to rolling, reaches the
  // block after about 75 (70 in the sanitizer builds was too few to wake it).
  constexpr int32_t k_steps = 150;
  const SleepingRun reference = run_sleeping_world(1, k_steps, 0);
  CHECK(reference.block_woke);  // the ball reached the block and woke part of it
  for (const int32_t workers : {2, 3}) {
    INFO(workers << " workers");
    CHECK(run_sleeping_world(workers, k_steps, 0).hashes == reference.hashes);
  }
  INFO("restored from its own snapshot every 7 steps");
  CHECK(run_sleeping_world(1, k_steps, 7).hashes == reference.hashes);
  CHECK(run_sleeping_world(2, k_steps, 7).hashes == reference.hashes);
}

TEST_CASE("while the block sleeps, the stages after the contact update read only the awake contacts",
          "[golden][sleep]") {
  const SleepingRun run = run_sleeping_world(1, 16, 0);
  INFO("contacts " << run.contacts << ", awake " << run.awake_contacts << ", most read " << run.most_read);
  CHECK(run.contacts > 1000);                        // the block's contacts (40 × 10 boxes on the ground)
  CHECK(run.awake_contacts > 0);                     // the stack and the ball on the ground
  CHECK(run.awake_contacts * 50 < run.contacts);     // the block's are not awake
  // Prepare counts and builds, the colouring, the wake scan and the islands
  // each read the awake contacts once: at most 5 passes, never the block.
  CHECK(run.most_read <= 5 * static_cast<int64_t>(run.awake_contacts));
  CHECK(run.most_read > 0);
}

TEST_CASE("a sleeper touched only by awake bodies wakes while every contact has a simulated body",
          "[golden][sleep]") {
  // No gravity and no static body: a box created asleep and a ball flying
  // into it. Every contact then has a simulated body (the ball), so the
  // contact update leaves the awake index unwritten (awake_contacts_all,
  // contact.cpp) and the wake scan (island.cpp) must read the whole list to
  // find the sleeper the ball touches. Same bits for 1 and 2 workers.
  const auto run = [](int32_t workers, std::vector<uint64_t>* hashes) {
    WorldDef wd = default_world_def();
    wd.gravity = {0_q32, 0_q32};
    wd.worker_count = workers;
    test_support::ScopedWorld w(wd);
    BodyDef sleeper_def = test_support::body_def_at({0_q32, 0_q32});
    sleeper_def.is_awake = false;
    const BodyId sleeper = test_support::add_box_body(w.id, sleeper_def, 0.5_q32, 0.5_q32);
    BodyDef ball_def = test_support::body_def_at({-2_q32, 0_q32});
    ball_def.linear_velocity = {3_q32, 0_q32};
    test_support::add_ball_body(w.id, ball_def, 0.25_q32);
    bool counted_all = false;
    for (int32_t i = 0; i < 60; ++i) {
      REQUIRE(world_step(w.id, Q32::from_ratio(1, 60)).ok());
      hashes->push_back(world_state_hash(w.id));
      const BroadPhaseStats s = world_broad_phase_stats(w.id);
      if (s.pairs > 0) {
        CHECK(s.awake_contacts == s.pairs);  // the ball's contact: awake
        counted_all = true;
      }
    }
    CHECK(counted_all);
    return body_is_awake(sleeper);
  };
  std::vector<uint64_t> one, two;
  CHECK(run(1, &one));
  CHECK(run(2, &two));
  CHECK(one == two);
}
