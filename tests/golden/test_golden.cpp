// Golden hash chains: every scene of golden_scenes.cpp, run for
// k_scene_ticks ticks, must reproduce tests/golden/<scene>.txt bit for bit —
// on every platform of tools/matrix.sh, with every broad phase, and across
// snapshot/restore round trips (same world and a new one). A mismatch names the first differing
// recorded tick. TANDEM_GOLDEN_REGENERATE=1 rewrites the files instead
// (docs/determinism.md); TANDEM_GOLDEN_TICKS=N runs only the first N ticks
// (records up to N compared, the chain not).
#include <catch2/catch.hpp>

#include <algorithm>
#include <functional>
#include <set>
#include <utility>
#include <string>

#include "golden_support.h"

using namespace tandem;
using namespace tandem::golden;

namespace {

const Scene* find_scene(const std::string& name) {
  for (const Scene& s : scenes()) {
    if (name == s.name) return &s;
  }
  return nullptr;
}

const char* kind_name(BroadPhaseKind k) {
  switch (k) {
    case BroadPhaseKind::naive: return "naive";
    case BroadPhaseKind::sweep_and_prune: return "sweep_and_prune";
    case BroadPhaseKind::grid: return "grid";
    case BroadPhaseKind::tree: return "tree";
  }
  return "?";
}

/// The naive-broad-phase run against the golden file (or, in regeneration
/// mode, written to it).
void check_chain(const std::string& name) {
  const Scene* scene = find_scene(name);
  REQUIRE(scene != nullptr);
  ChainOptions options;
  options.ticks = tick_cap();
  const Chain run = run_chain(*scene, options);
  INFO("scene " << name << ": " << scene->covers);
  REQUIRE(run.error.empty());  // Chain::error names the tick and the failed call
  if (regenerate_mode()) {
    REQUIRE(options.ticks == k_scene_ticks);  // TANDEM_GOLDEN_TICKS must be unset to regenerate
    const std::string err = write_golden(name, *scene, run);
    INFO(err);
    REQUIRE(err.empty());
    WARN("regenerated " << golden_dir() << "/" << name << ".txt");
    return;
  }
  const Chain golden = read_golden(name);
  INFO(golden.error);
  REQUIRE(golden.error.empty());
  const std::string diff = compare(golden, run);
  INFO(golden_dir() << "/" << name << ".txt: " << diff);
  CHECK(diff.empty());
}

/// Every other broad phase must give the naive one's chain.
void check_broad_phases(const std::string& name) {
  if (regenerate_mode()) return;
  const Scene* scene = find_scene(name);
  REQUIRE(scene != nullptr);
  const Chain golden = read_golden(name);
  INFO(golden.error);
  REQUIRE(golden.error.empty());
  for (const BroadPhaseKind kind : {BroadPhaseKind::sweep_and_prune, BroadPhaseKind::grid, BroadPhaseKind::tree}) {
    ChainOptions options;
    options.ticks = tick_cap();
    options.broad_phase = kind;
    const Chain run = run_chain(*scene, options);
    INFO("scene " << name << ", broad phase " << kind_name(kind));
    REQUIRE(run.error.empty());
    const std::string diff = compare(golden, run);
    INFO(diff);
    CHECK(diff.empty());
  }
  ChainOptions cycle;  // naive, then every kind in turn, switched every 300 ticks
  cycle.ticks = tick_cap();
  cycle.cycle_broad_phase = true;
  const Chain run = run_chain(*scene, cycle);
  INFO("scene " << name << ", broad phase switched every 300 ticks");
  REQUIRE(run.error.empty());
  const std::string diff = compare(golden, run);
  INFO(diff);
  CHECK(diff.empty());
}

/// The chain again with snapshot/restore round trips at seeded random ticks
/// (a detour of 1..40 ticks rolled back each time, into the same world or a
/// new one): the restored worlds must go on exactly as the golden run.
void check_restores(const std::string& name, bool compact = false) {
  if (regenerate_mode()) return;
  const Scene* scene = find_scene(name);
  REQUIRE(scene != nullptr);
  const Chain golden = read_golden(name);
  INFO(golden.error);
  REQUIRE(golden.error.empty());
  ChainOptions options;
  options.ticks = tick_cap();
  options.restore_count = compact ? 12 : 6;
  options.compact = compact;
  uint64_t seed = compact ? 0xC0DE : 0x5EED;
  for (const char ch : name) seed = seed * 131 + static_cast<uint8_t>(ch);
  options.restore_seed = seed;
  const Chain run = run_chain(*scene, options);
  INFO("scene " << name << ", " << run.restores << " restores (seed " << seed << ")");
  INFO(run.error);
  REQUIRE(run.error.empty());
  CHECK(run.restores >= 1);
  const std::string diff = compare(golden, run);
  INFO(diff);
  CHECK(diff.empty());
}

}  // namespace

TEST_CASE("golden: every scene has a golden test case and a file", "[golden]") {
  // Keep the list below (one GOLDEN_SCENE line per scene) in step with scenes().
  const std::set<std::string> listed = {"circles",   "capsules", "pyramid",   "segments",       "chains",
                                        "friction_restitution", "sleep_wake", "filtering", "sensors",
                                        "create_destroy", "scripted", "kinematic", "random_mix",
                                        "joints_bridge_chain", "joints_machines", "joints_ropes_breaking",
                                        "joints_ragdolls"};
  std::set<std::string> defined;
  for (const Scene& s : scenes()) defined.insert(s.name);
  CHECK(listed == defined);
  CHECK(defined.size() >= 12);
}

TEST_CASE("golden: the comparison names the first differing recorded tick", "[golden]") {
  Chain golden;
  golden.hash_source = k_hash_source;
  golden.ticks = 180;
  golden.records = {{60, 1}, {120, 2}, {180, 3}};
  golden.chain = 99;
  Chain run = golden;
  CHECK(compare(golden, run).empty());
  run.records[1].hash = 7;
  run.chain = 98;
  CHECK(compare(golden, run).find("first differing recorded tick 120") != std::string::npos);
  run = golden;
  run.chain = 5;
  CHECK(compare(golden, run).find("chain differs") != std::string::npos);
  run = golden;
  run.hash_source = "other";
  CHECK(compare(golden, run).find("regenerate") != std::string::npos);
  run = golden;  // a capped run compares its records only
  run.ticks = 120;
  run.records.pop_back();
  run.chain = 1234;
  CHECK(compare(golden, run).empty());
}

#define GOLDEN_SCENE(name)                                                                  \
  TEST_CASE("golden chain: " name, "[golden]") { check_chain(name); }                        \
  TEST_CASE("golden chain: " name ", every broad phase", "[golden][broad_phase]") {        \
    check_broad_phases(name);                                                              \
  }                                                                                        \
  TEST_CASE("golden chain: " name ", snapshot/restore", "[golden][restore]") { check_restores(name); }     \
  TEST_CASE("golden chain: " name ", compact rollback", "[golden][rollback]") { check_restores(name, true); }

GOLDEN_SCENE("circles")
GOLDEN_SCENE("capsules")
GOLDEN_SCENE("pyramid")
GOLDEN_SCENE("segments")
GOLDEN_SCENE("chains")
GOLDEN_SCENE("friction_restitution")
GOLDEN_SCENE("sleep_wake")
GOLDEN_SCENE("filtering")
GOLDEN_SCENE("sensors")
GOLDEN_SCENE("create_destroy")
GOLDEN_SCENE("scripted")
GOLDEN_SCENE("kinematic")
GOLDEN_SCENE("random_mix")
GOLDEN_SCENE("joints_bridge_chain")
GOLDEN_SCENE("joints_machines")
GOLDEN_SCENE("joints_ropes_breaking")
GOLDEN_SCENE("joints_ragdolls")

// --- the scenes do what they claim (so a golden chain is never vacuous) -------

namespace {

Chain observe(const std::string& name, int32_t ticks, std::function<void(SceneContext&, int32_t)> f) {
  const Scene* scene = find_scene(name);
  REQUIRE(scene != nullptr);
  ChainOptions options;
  options.ticks = ticks;
  options.observe = std::move(f);
  return run_chain(*scene, options);
}

}  // namespace

TEST_CASE("golden scenes: together they touch every pair of shape kinds", "[golden]") {
  std::set<std::pair<int, int>> seen;
  for (const Scene& s : scenes()) {
    const Chain run = observe(s.name, tick_cap(), [&](SceneContext& c, int32_t) {
      const Result<ContactEvents> ev = world_contact_events(c.world);
      for (const ContactBeginEvent& e : ev.value.begin) {
        const int a = static_cast<int>(shape_type(e.shape_a)), b = static_cast<int>(shape_type(e.shape_b));
        seen.insert({std::min(a, b), std::max(a, b)});
      }
    });
    INFO(run.error);
    REQUIRE(run.error.empty());
  }
  const auto t = [](ShapeType k) { return static_cast<int>(k); };
  for (const ShapeType solid : {ShapeType::circle, ShapeType::capsule, ShapeType::polygon}) {
    for (const ShapeType other :
         {ShapeType::circle, ShapeType::capsule, ShapeType::polygon, ShapeType::segment, ShapeType::chain_segment}) {
      INFO("shape kinds " << t(solid) << " and " << t(other));
      CHECK(seen.count({std::min(t(solid), t(other)), std::max(t(solid), t(other))}) == 1);
    }
  }
}

TEST_CASE("golden scenes: the pyramid sleeps, and the impulse at tick 2400 wakes it", "[golden]") {
  bool asleep_before = false, awake_after = false;
  const Chain run = observe("pyramid", 2401, [&](SceneContext& c, int32_t tick) {
    if (tick == 2399) {
      asleep_before = true;
      for (const BodyId b : c.bodies) asleep_before = asleep_before && !body_is_awake(b);
    }
    if (tick == 2401) awake_after = body_is_awake(c.bodies[0]) && body_is_awake(c.bodies[1]);
  });
  REQUIRE(run.error.empty());
  CHECK(asleep_before);
  CHECK(awake_after);
}

TEST_CASE("golden scenes: filtering keeps layers apart until the filter changes", "[golden]") {
  int before = 0, after = 0, group_pairs = 0;
  const Chain run = observe("filtering", 2400, [&](SceneContext& c, int32_t tick) {
    for (const ContactBeginEvent& e : world_contact_events(c.world).value.begin) {
      const Filter a = shape_filter(e.shape_a), b = shape_filter(e.shape_b);
      // a layer-2 box and one of the scene's circles (layer 4, then layer 2 from tick 1500)
      const bool circle_a = std::find(c.shapes.begin(), c.shapes.end(), e.shape_a) != c.shapes.end();
      const bool circle_b = std::find(c.shapes.begin(), c.shapes.end(), e.shape_b) != c.shapes.end();
      const bool box_a = shape_type(e.shape_a) == ShapeType::polygon && a.category_bits == 2;
      const bool box_b = shape_type(e.shape_b) == ShapeType::polygon && b.category_bits == 2;
      if ((circle_a && box_b) || (circle_b && box_a)) (tick < 1500 ? before : after) += 1;
      if (a.group_index == -1 && b.group_index == -1) ++group_pairs;
    }
  });
  REQUIRE(run.error.empty());
  CHECK(before == 0);
  CHECK(group_pairs == 0);
  CHECK(after > 0);
}

TEST_CASE("golden scenes: sensors report visitors entering and leaving", "[golden]") {
  int begins = 0, ends = 0;
  const Chain run = observe("sensors", 2400, [&](SceneContext& c, int32_t) {
    const Result<SensorEvents> ev = world_sensor_events(c.world);
    begins += static_cast<int>(ev.value.begin.size());
    ends += static_cast<int>(ev.value.end.size());
  });
  REQUIRE(run.error.empty());
  CHECK(begins > 10);
  CHECK(ends > 10);
}

TEST_CASE("golden scenes: create_destroy reuses slots with new generations", "[golden]") {
  uint32_t max_generation = 0;
  int32_t max_bodies = 0;
  const Chain run = observe("create_destroy", 2100, [&](SceneContext& c, int32_t) {
    for (const BodyId b : c.bodies) max_generation = std::max(max_generation, b.generation);
    max_bodies = std::max(max_bodies, world_counters(c.world).body_count);
  });
  REQUIRE(run.error.empty());
  CHECK(max_generation > 2);
  CHECK(max_bodies == 25);  // the container and 24 spawned bodies
}
