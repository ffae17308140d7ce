// Golden hash chains on both contact solver paths (physics/contact_lanes.h):
// the scalar reference, one constraint at a time, and the lane blocks must
// each reproduce every golden file bit for bit, whichever path this build
// selects by default (CMake TANDEM_CONTACT_LANES), and with workers and a
// shuffled task order on the lanes (block boundaries of the lanes are not
// those of the scalar loops). The other golden tests run the build's default
// path; this file runs the scalar path and the lanes explicitly.
#include <catch2/catch.hpp>

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "golden_support.h"
#include "physics/contact_solver.h"

using namespace tandem;
using namespace tandem::golden;

namespace {

/// Selects a contact solver path for the lifetime of the object.
struct PathScope {
  ContactSolverPath saved = contact_solver_path();
  explicit PathScope(ContactSolverPath path) { set_contact_solver_path(path); }
  ~PathScope() { set_contact_solver_path(saved); }
  PathScope(const PathScope&) = delete;
  PathScope& operator=(const PathScope&) = delete;
};

std::string run_against_golden(const Scene& scene, const ChainOptions& options) {
  const Chain run = run_chain(scene, options);
  if (!run.error.empty()) return run.error;
  const Chain golden = read_golden(scene.name);
  if (!golden.error.empty()) return golden.error;
  const std::string diff = compare(golden, run);
  return diff.empty() ? "" : golden_dir() + "/" + scene.name + ".txt: " + diff;
}

/// A single-threaded task system that runs each task's items one at a
/// time in a seeded random order.
struct ShuffledItems {
  std::mt19937_64 rng;
  TaskFunction task = nullptr;
  int32_t item_count = 0;
  void* task_context = nullptr;
  std::vector<int32_t> order;
};

void* shuffled_enqueue(TaskFunction task, int32_t item_count, int32_t, void* task_context, void* user_context) {
  auto* s = static_cast<ShuffledItems*>(user_context);
  s->task = task;
  s->item_count = item_count;
  s->task_context = task_context;
  return s;
}

void shuffled_finish(void*, void* user_context) {
  auto* s = static_cast<ShuffledItems*>(user_context);
  s->order.clear();
  for (int32_t i = 0; i < s->item_count; ++i) s->order.push_back(i);
  for (size_t i = s->order.size(); i > 1; --i) std::swap(s->order[i - 1], s->order[static_cast<size_t>(s->rng() % i)]);
  for (const int32_t i : s->order) s->task(i, i + 1, s->task_context);
}

}  // namespace

TEST_CASE("golden chain on the scalar contact solver path: every scene", "[golden][lanes]") {
  if (regenerate_mode()) return;
  const PathScope scope(ContactSolverPath::scalar);
  for (const Scene& scene : scenes()) {
    ChainOptions options;
    options.ticks = tick_cap();
    INFO("scene " << scene.name << ", scalar contact path");
    CHECK(run_against_golden(scene, options) == "");
  }
}

TEST_CASE("golden chain on the lane contact solver path: every scene, 1 and 3 workers, shuffled", "[golden][lanes]") {
  if (regenerate_mode()) return;
  const PathScope scope(ContactSolverPath::lanes);
  for (const Scene& scene : scenes()) {
    ChainOptions options;
    options.ticks = tick_cap();
    INFO("scene " << scene.name << ", lane contact path, 1 worker");
    CHECK(run_against_golden(scene, options) == "");
  }
  uint64_t seed = 0x1a7e5;
  for (const Scene& scene : scenes()) {
    ShuffledItems system;
    system.rng.seed(seed++);
    ChainOptions options;
    options.ticks = tick_cap() < 600 ? tick_cap() : 600;
    options.worker_count = 3;
    options.enqueue_task = &shuffled_enqueue;
    options.finish_task = &shuffled_finish;
    options.user_task_context = &system;
    INFO("scene " << scene.name << ", lane contact path, shuffled items, " << options.ticks << " ticks");
    CHECK(run_against_golden(scene, options) == "");
  }
}

TEST_CASE("contact solver path: switching between steps keeps the chain", "[golden][lanes]") {
  if (regenerate_mode()) return;
  const PathScope scope(ContactSolverPath::lanes);
  for (const Scene& scene : scenes()) {
    ChainOptions options;
    options.ticks = tick_cap() < 900 ? tick_cap() : 900;
    // After each tick: alternate the path every 5 ticks.
    options.observe = [](SceneContext&, int32_t tick) {
      set_contact_solver_path((tick / 5) % 2 == 0 ? ContactSolverPath::lanes : ContactSolverPath::scalar);
    };
    INFO("scene " << scene.name << ", path switched every 5 ticks");
    CHECK(run_against_golden(scene, options) == "");
  }
}
