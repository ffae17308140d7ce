// The joint golden scenes do what they claim (so their chains are never
// vacuous): joints break and are reported, bodies take their joints with
// them, the hook is attached and released, the car drives, the ragdolls
// sleep and wake.
#include <catch2/catch.hpp>

#include <string>

#include "golden_support.h"

using namespace tandem;
using namespace tandem::golden;

namespace {

const Scene& scene_named(const std::string& name) {
  for (const Scene& s : scenes()) {
    if (name == s.name) return s;
  }
  FAIL("no scene " << name);
  return scenes()[0];
}

struct Counts {
  int broke = 0;
  int with_body = 0;
  int max_joints = 0;
  int min_joints = 1 << 30;
  bool any_asleep = false;
  bool woke_after = false;
};

Counts watch(const std::string& name, std::function<void(SceneContext&, int32_t)> extra = nullptr) {
  Counts n;
  ChainOptions options;
  options.ticks = tick_cap();
  options.observe = [&](SceneContext& c, int32_t tick) {
    for (const JointEvent& e : world_joint_events(c.world).value) {
      if (e.kind == JointEventKind::broke) ++n.broke;
      if (e.kind == JointEventKind::destroyed_with_body) ++n.with_body;
    }
    const int joints = world_counters(c.world).joint_count;
    n.max_joints = std::max(n.max_joints, joints);
    n.min_joints = std::min(n.min_joints, joints);
    if (extra) extra(c, tick);
  };
  const Chain run = run_chain(scene_named(name), options);
  INFO(run.error);
  REQUIRE(run.error.empty());
  return n;
}

}  // namespace

TEST_CASE("golden joint scenes: bridge and chain lose a joint and a plank's two joints", "[golden][joint]") {
  const Counts n = watch("joints_bridge_chain");
  CHECK(n.max_joints == 52);
  if (tick_cap() >= 2401) {
    CHECK(n.with_body == 2);
    CHECK(n.min_joints == 49);
  }
}

TEST_CASE("golden joint scenes: the shelf and lamp break, the hook comes and goes", "[golden][joint]") {
  const Counts n = watch("joints_ropes_breaking");
  CHECK(n.max_joints == (tick_cap() > 900 ? 8 : 7));  // the hook is fired at tick 900
  if (tick_cap() >= 2601) {
    CHECK(n.broke == 2);
    CHECK(n.with_body == 5);  // three ropes and two springs go with the ceiling
    CHECK(n.min_joints == 0);
  }
}

TEST_CASE("golden joint scenes: the car drives and the machines keep their joints", "[golden][joint]") {
  Q32 start_x, end_x;
  const Counts n = watch("joints_machines", [&](SceneContext& c, int32_t tick) {
    if (tick == 1) start_x = body_position(c.bodies[1]).x;
    end_x = body_position(c.bodies[1]).x;
  });
  CHECK(n.min_joints == 7);
  CHECK(n.broke == 0);
  CHECK(end_x != start_x);
}

TEST_CASE("golden joint scenes: the ragdolls fall asleep and a kick wakes them", "[golden][joint]") {
  bool asleep_before = false, awake_after = false;
  watch("joints_ragdolls", [&](SceneContext& c, int32_t tick) {
    if (tick == 2399) asleep_before = !body_is_awake(c.bodies[2]);
    if (tick == 2400) awake_after = body_is_awake(c.bodies[2]);
  });
  if (tick_cap() >= 2400) {
    CHECK(asleep_before);
    CHECK(awake_after);
  }
}
