// Tests of replay/synctest.h: a normal scene passes; a planted
// nondeterminism (an input callback that depends on how often it has been
// called) is caught at the right tick and located by the diff.
#include <catch2/catch.hpp>

#include "replay/synctest.h"
#include "replay_test_scenes.h"

namespace tandem {
namespace {

using namespace tandem::replay_test;
using namespace tandem::literals;

TEST_CASE("synctest: scenes with inputs pass with rollback 8", "[replay][synctest]") {
  for (Scene scene : {Scene::create_destroy, Scene::elastic_crowd}) {
    INFO(scene_name(scene));
    const WorldId w = make_scene_world(scene);
    SyncTestOptions options;
    options.ticks = 240;
    options.rollback = 8;
    SyncTestReport report;
    const Status s = run_synctest(w, options, [scene](WorldId world, int64_t tick) {
      apply_scene_inputs(scene, world, tick);
    }, &report);
    INFO(s.message << " / " << report.message);
    CHECK(s.ok());
    CHECK(report.passed);
    CHECK(report.ticks_run == 240);
    CHECK(report.resimulated_ticks == (240 - 7) * 8);
    CHECK(report.first_mismatch_tick == -1);
    // The world ends where a plain run ends.
    const WorldId plain = make_scene_world(scene);
    for (int64_t t = 0; t < 240; ++t) step_scene(scene, plain, t);
    CHECK(world_state_hash(plain) == world_state_hash(w));
    REQUIRE(destroy_world(plain).ok());
    REQUIRE(destroy_world(w).ok());
  }
}

TEST_CASE("synctest: an input callback that depends on its call count is caught", "[replay][synctest]") {
  const WorldId w = make_scene_world(Scene::pile);
  const std::vector<BodyId> bodies = dynamic_bodies(w);
  const BodyId target = bodies[2];
  int64_t calls = 0;
  SyncTestOptions options;
  options.ticks = 100;
  options.rollback = 4;
  SyncTestReport report;
  // On its 51st call (first pass or resimulation, whichever it is) the
  // callback nudges a body; no other call of that tick does.
  int64_t nudged_tick = -1;
  const Status s = run_synctest(w, options, [&](WorldId, int64_t tick) {
    ++calls;
    if (calls == 51) {
      nudged_tick = tick;
      REQUIRE(body_apply_linear_impulse_to_center(target, {0_q32, 0.25_q32}, true).ok());
    }
  }, &report);
  INFO(report.message);
  REQUIRE(s.ok());
  CHECK(!report.passed);
  REQUIRE(nudged_tick > 0);
  CHECK(report.first_mismatch_tick == nudged_tick);
  CHECK(report.detected_at_tick >= nudged_tick);
  CHECK(report.detected_at_tick < nudged_tick + options.rollback);
  CHECK(report.expected_hash != report.actual_hash);
  REQUIRE(report.difference.differs);
  CHECK(report.difference.kind == "body");
  CHECK(report.difference.index == static_cast<int64_t>(target.index1) - 1);
  CHECK(report.message.find("tick " + std::to_string(nudged_tick)) != std::string::npos);
  REQUIRE(destroy_world(w).ok());
}

TEST_CASE("synctest: bad options and handles are refused", "[replay][synctest]") {
  SyncTestReport report;
  SyncTestOptions options;
  options.ticks = 10;
  options.rollback = 0;
  const WorldId w = make_scene_world(Scene::pile);
  CHECK(run_synctest(w, options, nullptr, &report).code == StatusCode::invalid_argument);
  options.rollback = 2;
  CHECK(run_synctest(WorldId{}, options, nullptr, &report).code == StatusCode::null_handle);
  CHECK(run_synctest(w, options, nullptr, &report).ok());
  CHECK(report.passed);
  REQUIRE(destroy_world(w).ok());
}

}  // namespace
}  // namespace tandem
