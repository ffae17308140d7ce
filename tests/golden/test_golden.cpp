// Golden hash chains: every scene of golden_scenes.cpp, run for
// k_scene_ticks ticks, must reproduce tests/golden/<scene>.txt bit for bit —
// on every platform of tools/matrix.sh, with every broad phase, and across
// snapshot/restore round trips (same world and a new one). A mismatch names the first differing
// recorded tick. TANDEM_GOLDEN_REGENERATE=1 rewrites the files instead
// (docs/determinism.md); TANDEM_GOLDEN_TICKS=N runs only the first N ticks
// (records up to N compared, the chain not).
#include <catch2/catch.hpp>

#include <set>
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
void check_restores(const std::string& name) {
  if (regenerate_mode()) return;
  const Scene* scene = find_scene(name);
  REQUIRE(scene != nullptr);
  const Chain golden = read_golden(name);
  INFO(golden.error);
  REQUIRE(golden.error.empty());
  ChainOptions options;
  options.ticks = tick_cap();
  options.restore_count = 6;
  uint64_t seed = 0x5EED;
  for (const char ch : name) seed = seed * 131 + static_cast<uint8_t>(ch);
  options.restore_seed = seed;
  const Chain run = run_chain(*scene, options);
  INFO("scene " << name << ", " << run.restores << " restores (seed " << seed << ")");
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
                                        "create_destroy", "scripted", "kinematic", "random_mix"};
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
  TEST_CASE("golden chain: " name ", snapshot/restore", "[golden][restore]") { check_restores(name); }

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
