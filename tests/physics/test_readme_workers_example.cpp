// The README's worker-threads example, compiled and run, and checked to be
// in README.md verbatim (the block between the markers), so the README
// cannot drift from the API.
#include <catch2/catch.hpp>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "physics/tandem.h"

using namespace tandem;
using namespace tandem::literals;

namespace {

/// Drops `count` balls in a world made from `def`; returns the last one's
/// height after 120 steps (raw), with 2 workers from step 60 on.
int64_t run(WorldDef def, int count) {
  // --- README workers example begins ---
  def.worker_count = 4;                    // 1..16 threads; the same bits for every count
  WorldId world = create_world(def).value; // its own pool: 3 threads + the caller
  // ... bodies and shapes ...
  // --- README workers example ends ---
  std::vector<BodyId> balls;
  for (int i = 0; i < count; ++i) {
    BodyDef b = default_body_def();
    b.type = BodyType::dynamic_body;
    b.position = {Q32::from_int(i % 20), Q32::from_int(1 + i / 20)};
    balls.push_back(create_body(world, b).value);
    REQUIRE(create_circle_shape(balls.back(), default_shape_def(), Circle{{}, 0.4_q32}).ok());
  }
  for (int tick = 0; tick < 120; ++tick) {
    if (tick == 60) REQUIRE(world_set_worker_count(world, 2).ok());  // between steps: results unchanged
    REQUIRE(world_step(world, Q32::from_ratio(1, 60)).ok());
  }
  const int64_t y = body_position(balls.back()).y.raw;
  CHECK(destroy_world(world).ok());
  return y;
}

// --- README task system example begins ---
// Each parallel stage arrives as items [0, n): run each item once, on any
// thread, in any order, before finish_task returns.
void* enqueue(TaskFunction task, int32_t items, int32_t min_range, void* task_context, void* jobs) {
  (void)min_range;                          // e.g. split [0, items) into ranges for your workers
  task(0, items, task_context);             // (here: all at once, on this thread)
  return jobs;                              // any non-null handle
}
void finish(void* handle, void* jobs) { (void)handle; (void)jobs; }  // wait for the ranges
// ... def.enqueue_task = enqueue; def.finish_task = finish; def.user_task_context = &my_jobs;
// --- README task system example ends ---

std::string between(const std::string& text, const std::string& begin, const std::string& end) {
  const size_t b = text.find(begin), e = text.find(end);
  if (b == std::string::npos || e == std::string::npos) return "<markers missing>";
  const size_t from = text.find('\n', b) + 1;
  const size_t to = text.rfind('\n', e);
  return text.substr(from, to - from);
}

}  // namespace

TEST_CASE("README worker example: 4 then 2 workers, or a task system, give one worker's bits", "[physics][readme]") {
  WorldDef plain = default_world_def();
  const int64_t y_workers = run(plain, 200);
  WorldDef jobs = default_world_def();
  int my_jobs = 0;
  jobs.enqueue_task = enqueue;
  jobs.finish_task = finish;
  jobs.user_task_context = &my_jobs;
  const int64_t y_tasks = run(jobs, 200);
  // One worker, for reference.
  WorldDef one = default_world_def();
  const WorldId w = create_world(one).value;
  std::vector<BodyId> balls;
  for (int i = 0; i < 200; ++i) {
    BodyDef b = default_body_def();
    b.type = BodyType::dynamic_body;
    b.position = {Q32::from_int(i % 20), Q32::from_int(1 + i / 20)};
    balls.push_back(create_body(w, b).value);
    REQUIRE(create_circle_shape(balls.back(), default_shape_def(), Circle{{}, 0.4_q32}).ok());
  }
  for (int tick = 0; tick < 120; ++tick) REQUIRE(world_step(w, Q32::from_ratio(1, 60)).ok());
  const int64_t y_one = body_position(balls.back()).y.raw;
  CHECK(destroy_world(w).ok());
  CHECK(y_workers == y_one);
  CHECK(y_tasks == y_one);

  // The README quotes both blocks verbatim.
  std::string source = TANDEM_README_PATH;  // <repo>/README.md
  source = source.substr(0, source.size() - 9) + "tests/physics/test_readme_workers_example.cpp";
  std::ifstream self(source);
  std::ifstream readme(TANDEM_README_PATH);
  REQUIRE(self.good());
  REQUIRE(readme.good());
  std::stringstream s, r;
  s << self.rdbuf();
  r << readme.rdbuf();
  for (const char* name : {"workers", "task system"}) {
    const std::string begin = std::string("// --- README ") + name + " example begins ---";
    const std::string end = std::string("// --- README ") + name + " example ends ---";
    const std::string block = between(s.str(), begin, end);
    INFO("README block: " << name << "\n" << block);
    // In the README the blocks sit in a list item: every line two spaces in.
    // (A block written at column 0 here gets them added.)
    const std::string pad = block.rfind("  ", 0) == 0 ? "" : "  ";
    std::string indented;
    for (size_t at = 0; at < block.size();) {
      const size_t nl = block.find('\n', at);
      const std::string line = block.substr(at, nl == std::string::npos ? std::string::npos : nl - at);
      indented += pad + line + (nl == std::string::npos ? "" : "\n");
      at = nl == std::string::npos ? block.size() : nl + 1;
    }
    CHECK(r.str().find(indented) != std::string::npos);
  }
}
