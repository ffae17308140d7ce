// Golden hash chains with worker threads: every scene must reproduce its
// golden file with any WorldDef::worker_count, through the built-in pool and
// through a user task system that runs the items of every task in a
// shuffled (seeded per scene) or reversed order, and when the worker count
// changes between steps (physics/task.h explains why the bits cannot
// depend on any of these).
//
// Time: the full chains (3600 ticks) run with 2 workers and through the
// shuffling task system; the worker count changes over the first
// k_changing_ticks; the sweep over 3, 4, 8 and 16 workers and the reversed
// task system run the first k_short_ticks (the records up to there are
// compared). About 9 s of CPU in a release build, most of it the two full
// runs.
#include <catch2/catch.hpp>

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "golden_support.h"

using namespace tandem;
using namespace tandem::golden;

namespace {

/// Ticks of the shorter runs (the worker-count sweep, the reversed order).
constexpr int32_t k_short_ticks = 300;
/// Ticks of the run whose worker count changes every 7 ticks.
constexpr int32_t k_changing_ticks = 1200;

/// A single-threaded task system that runs each task's items at finish, in
/// random ranges of 1–3 items taken in a shuffled order (or one item at a
/// time from the last to the first), so no stage can rely on block order.
struct OrderScramblingTasks {
  std::mt19937_64 rng;
  bool reverse = false;
  // The task enqueued last (world_step finishes each task before the next).
  TaskFunction task = nullptr;
  int32_t item_count = 0;
  void* task_context = nullptr;
  int64_t tasks = 0;  ///< tasks run
  int64_t items = 0;  ///< items run
  std::vector<std::pair<int32_t, int32_t>> ranges;
};

void* scrambling_enqueue(TaskFunction task, int32_t item_count, int32_t min_range, void* task_context,
                         void* user_context) {
  (void)min_range;
  auto* s = static_cast<OrderScramblingTasks*>(user_context);
  s->task = task;
  s->item_count = item_count;
  s->task_context = task_context;
  return s;
}

void scrambling_finish(void* user_task, void* user_context) {
  auto* s = static_cast<OrderScramblingTasks*>(user_context);
  if (user_task != s) return;  // never: the handle is the system itself
  s->ranges.clear();
  if (s->reverse) {
    for (int32_t i = s->item_count - 1; i >= 0; --i) s->ranges.push_back({i, i + 1});
  } else {
    for (int32_t i = 0; i < s->item_count;) {
      const int32_t n = 1 + static_cast<int32_t>(s->rng() % 3);
      const int32_t end = i + n < s->item_count ? i + n : s->item_count;
      s->ranges.push_back({i, end});
      i = end;
    }
    // Fisher-Yates with the generator's raw output (std::shuffle's algorithm
    // is the library's choice).
    for (size_t i = s->ranges.size(); i > 1; --i) {
      const size_t j = static_cast<size_t>(s->rng() % i);
      std::swap(s->ranges[i - 1], s->ranges[j]);
    }
  }
  for (const auto& [begin, end] : s->ranges) s->task(begin, end, s->task_context);
  ++s->tasks;
  s->items += s->item_count;
}

/// Runs one scene with `options` and compares it with its golden file;
/// returns "" or the difference.
std::string run_against_golden(const Scene& scene, const ChainOptions& options) {
  const Chain run = run_chain(scene, options);
  if (!run.error.empty()) return run.error;
  const Chain golden = read_golden(scene.name);
  if (!golden.error.empty()) return golden.error;
  const std::string diff = compare(golden, run);
  return diff.empty() ? "" : golden_dir() + "/" + scene.name + ".txt: " + diff;
}

int32_t capped(int32_t ticks) { return ticks < tick_cap() ? ticks : tick_cap(); }

}  // namespace

TEST_CASE("golden chain with 2 workers (built-in pool): every scene", "[golden][workers]") {
  if (regenerate_mode()) return;
  for (const Scene& scene : scenes()) {
    ChainOptions options;
    options.ticks = tick_cap();
    options.worker_count = 2;
    INFO("scene " << scene.name << ", 2 workers");
    CHECK(run_against_golden(scene, options) == "");
  }
}

TEST_CASE("golden chain with 3 to 16 workers (built-in pool): every scene", "[golden][workers]") {
  if (regenerate_mode()) return;
  for (const int32_t workers : {3, 4, 8, 16}) {
    for (const Scene& scene : scenes()) {
      ChainOptions options;
      options.ticks = capped(k_short_ticks);
      options.worker_count = workers;
      INFO("scene " << scene.name << ", " << workers << " workers, " << options.ticks << " ticks");
      CHECK(run_against_golden(scene, options) == "");
    }
  }
}

TEST_CASE("golden chain through a task system that shuffles the order: every scene", "[golden][workers]") {
  if (regenerate_mode()) return;
  int64_t tasks = 0, items = 0;
  uint64_t seed = 0x5eed0001;
  for (const Scene& scene : scenes()) {
    OrderScramblingTasks system;
    system.rng.seed(seed++);
    ChainOptions options;
    options.ticks = tick_cap();
    options.worker_count = 4;
    options.enqueue_task = &scrambling_enqueue;
    options.finish_task = &scrambling_finish;
    options.user_task_context = &system;
    INFO("scene " << scene.name << ", shuffled task order, seed " << seed - 1);
    CHECK(run_against_golden(scene, options) == "");
    tasks += system.tasks;
    items += system.items;
  }
  // The scenes are big enough that stages split into several blocks.
  WARN("shuffled: " << tasks << " tasks, " << items << " items over all scenes");
  CHECK(tasks > 1000);
  CHECK(items > 2 * tasks);
}

TEST_CASE("golden chain through a task system that runs items in reverse: every scene", "[golden][workers]") {
  if (regenerate_mode()) return;
  int64_t tasks = 0;
  for (const Scene& scene : scenes()) {
    OrderScramblingTasks system;
    system.reverse = true;
    ChainOptions options;
    options.ticks = capped(k_short_ticks);
    options.worker_count = 2;
    options.enqueue_task = &scrambling_enqueue;
    options.finish_task = &scrambling_finish;
    options.user_task_context = &system;
    INFO("scene " << scene.name << ", reversed task order");
    CHECK(run_against_golden(scene, options) == "");
    tasks += system.tasks;
  }
  CHECK(tasks > 0);
}

TEST_CASE("golden chain with the worker count changed between steps: every scene", "[golden][workers]") {
  if (regenerate_mode()) return;
  for (const Scene& scene : scenes()) {
    ChainOptions options;
    options.ticks = capped(k_changing_ticks);
    std::string failure;
    // After each tick: 1, 2, 3, 16, 1, ... workers, switching every 7 ticks.
    options.observe = [&failure](SceneContext& ctx, int32_t tick) {
      static constexpr int32_t k_counts[] = {1, 2, 3, 16};
      if (tick % 7 != 0) return;
      const int32_t workers = k_counts[(tick / 7) % 4];
      const Status s = world_set_worker_count(ctx.world, workers);
      if (!s.ok() && failure.empty()) failure = s.message;
      if (world_worker_count(ctx.world) != workers && failure.empty()) failure = "worker count not applied";
    };
    INFO("scene " << scene.name << ", worker count changing every 7 ticks");
    CHECK(run_against_golden(scene, options) == "");
    CHECK(failure == "");
  }
}
