// Worker threads (physics/task.h): the settings are checked, and a user task
// system that misbehaves — returns no handle, never runs the items, runs
// them twice, passes bad ranges, calls after its task finished or after the
// world is gone — is reported by world_step (k_step_flag_task_failure,
// StepResult::task_status) while the results stay bit-identical to one
// worker's. The golden chains across worker counts and task orders are in
// tests/golden/test_golden_workers.cpp.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "physics_test_support.h"

using namespace tandem;
using namespace tandem::test_support;

namespace {

/// A pyramid of `base` rows of unit boxes on a static ground (sleep off, so
/// every step has work for several blocks).
std::vector<BodyId> build_pyramid(WorldId w, int base) {
  add_box_body(w, body_def_at({0_q32, -1_q32}, BodyType::static_body), 100_q32, 1_q32);
  std::vector<BodyId> bodies;
  for (int row = 0; row < base; ++row) {
    for (int k = 0; k < base - row; ++k) {
      const Vec2 p = {Q32::from_int(k) - Q32::from_ratio(base - row - 1, 2) + Q32::from_ratio(row, 7),
                      Q32::from_int(row) + 0.5_q32};
      bodies.push_back(add_box_body(w, body_def_at(p), 0.5_q32, 0.5_q32));
    }
  }
  return bodies;
}

WorldDef awake_def() {
  WorldDef def = default_world_def();
  def.enable_sleep = false;
  return def;
}

/// Every body's pose and velocity, raw.
std::vector<int64_t> state_of(const std::vector<BodyId>& bodies) {
  std::vector<int64_t> s;
  for (BodyId b : bodies) {
    const Vec2 p = body_position(b), v = body_linear_velocity(b);
    const Rot q = body_rotation(b);
    s.insert(s.end(), {p.x.raw, p.y.raw, q.c.raw, q.s.raw, v.x.raw, v.y.raw, body_angular_velocity(b).raw});
  }
  return s;
}

constexpr int k_base = 14;   // 105 boxes: two body blocks, several constraint blocks per colour
constexpr int k_steps = 30;

/// The reference: one worker.
std::vector<int64_t> reference_state() {
  ScopedWorld w(awake_def());
  const std::vector<BodyId> bodies = build_pyramid(w.id, k_base);
  for (int i = 0; i < k_steps; ++i) REQUIRE(world_step(w.id, k_dt).ok());
  return state_of(bodies);
}

/// A task system with a chosen fault. Runs everything on the calling thread.
struct FaultyTasks {
  enum Fault { none, null_handle, never_run, run_twice, bad_range, keep_for_later };
  Fault fault = none;
  TaskFunction task = nullptr;
  int32_t item_count = 0;
  void* task_context = nullptr;
  int64_t enqueued = 0;
};

void* faulty_enqueue(TaskFunction task, int32_t item_count, int32_t, void* task_context, void* user_context) {
  auto* f = static_cast<FaultyTasks*>(user_context);
  f->task = task;
  f->item_count = item_count;
  f->task_context = task_context;
  ++f->enqueued;
  return f->fault == FaultyTasks::null_handle ? nullptr : f;
}

void faulty_finish(void* user_task, void* user_context) {
  auto* f = static_cast<FaultyTasks*>(user_context);
  REQUIRE(user_task == f);
  switch (f->fault) {
    case FaultyTasks::none:
    case FaultyTasks::keep_for_later:
    case FaultyTasks::null_handle: f->task(0, f->item_count, f->task_context); break;
    case FaultyTasks::never_run: break;
    case FaultyTasks::run_twice:
      f->task(0, f->item_count, f->task_context);
      f->task(0, f->item_count, f->task_context);
      break;
    case FaultyTasks::bad_range:
      f->task(-1, f->item_count, f->task_context);
      f->task(0, f->item_count + 5, f->task_context);
      f->task(2, 1, f->task_context);
      f->task(0, f->item_count, f->task_context);
      break;
  }
}

/// Steps the pyramid through a faulty task system; checks the results equal
/// one worker's and returns the first task_status message ("" when none)
/// and, through *out_flags, the OR of the step flags.
std::string run_faulty(FaultyTasks::Fault fault, uint32_t* out_flags) {
  FaultyTasks f;
  f.fault = fault;
  WorldDef def = awake_def();
  def.worker_count = 3;
  def.enqueue_task = &faulty_enqueue;
  def.finish_task = &faulty_finish;
  def.user_task_context = &f;
  ScopedWorld w(def);
  const std::vector<BodyId> bodies = build_pyramid(w.id, k_base);
  std::string message;
  uint32_t flags = 0;
  for (int i = 0; i < k_steps; ++i) {
    const StepResult r = world_step(w.id, k_dt);
    REQUIRE(r.ok());  // the step itself is always accepted
    flags |= r.flags;
    if ((r.flags & k_step_flag_task_failure) != 0) {
      CHECK(r.task_status.code == StatusCode::invalid_argument);
      if (message.empty()) message = r.task_status.message;
    } else {
      CHECK(r.task_status.ok());
    }
  }
  CHECK(f.enqueued > 0);
  CHECK(state_of(bodies) == reference_state());
  *out_flags = flags;
  return message;
}

}  // namespace

TEST_CASE("worker_count outside 1..16 and half-set task callbacks are refused", "[physics][workers]") {
  for (const int32_t bad : {0, -1, 17, 1000}) {
    WorldDef def = default_world_def();
    def.worker_count = bad;
    const Result<WorldId> r = create_world(def);
    REQUIRE_FALSE(r.ok());
    CHECK(r.status.code == StatusCode::invalid_argument);
    CHECK(r.status.message == "create_world: worker_count " + std::to_string(bad) + " is outside [1, 16]");
  }
  WorldDef half = default_world_def();
  half.enqueue_task = &faulty_enqueue;
  Result<WorldId> r = create_world(half);
  REQUIRE_FALSE(r.ok());
  CHECK(r.status.message ==
        "create_world: enqueue_task and finish_task must both be set or both be null (finish_task is null)");
  half = default_world_def();
  half.finish_task = &faulty_finish;
  r = create_world(half);
  REQUIRE_FALSE(r.ok());
  CHECK(r.status.message.find("(enqueue_task is null)") != std::string::npos);

  WorldDef def = default_world_def();
  CHECK(def.worker_count == 1);
  def.worker_count = k_max_workers;
  ScopedWorld w(def);
  CHECK(world_worker_count(w.id) == 16);
  CHECK(world_def(w.id).worker_count == 16);
}

TEST_CASE("world_set_worker_count: range, handles, between steps only", "[physics][workers]") {
  ScopedWorld w(awake_def());
  const std::vector<BodyId> bodies = build_pyramid(w.id, 4);
  CHECK(world_set_worker_count(w.id, 2).ok());
  CHECK(world_worker_count(w.id) == 2);
  for (const int32_t bad : {0, 17}) {
    const Status s = world_set_worker_count(w.id, bad);
    CHECK(s.code == StatusCode::invalid_argument);
    CHECK(s.message == "world_set_worker_count: worker_count " + std::to_string(bad) + " is outside [1, 16]");
    CHECK(world_worker_count(w.id) == 2);  // unchanged
    CHECK(world_def(w.id).worker_count == 2);
  }
  CHECK(world_set_worker_count(WorldId{}, 2).code == StatusCode::null_handle);
  CHECK(world_worker_count(WorldId{}) == 1);
  // Inside the step (from a custom filter, which the broad phase calls):
  // refused, and the step goes on.
  struct Probe {
    WorldId world;
    Status status;
  } probe{w.id, {}};
  REQUIRE(world_set_custom_filter(
              w.id,
              [](ShapeId, ShapeId, void* context) {
                auto* p = static_cast<Probe*>(context);
                if (p->status.ok()) p->status = world_set_worker_count(p->world, 4);
                return true;
              },
              &probe)
              .ok());
  for (int i = 0; i < 3; ++i) REQUIRE(world_step(w.id, k_dt).ok());
  CHECK(probe.status.code == StatusCode::world_locked);
  CHECK(world_worker_count(w.id) == 2);
}

TEST_CASE("a correct task system gives one worker's bits and no failure", "[physics][workers]") {
  uint32_t flags = 0;
  CHECK(run_faulty(FaultyTasks::none, &flags) == "");
  CHECK(flags == 0);
}

TEST_CASE("a task system that misbehaves is reported, never fatal, same bits", "[physics][workers]") {
  struct Case {
    FaultyTasks::Fault fault;
    const char* expected;
  };
  const Case cases[] = {
      {FaultyTasks::null_handle, "enqueue_task returned null"},
      {FaultyTasks::never_run, "finish_task returned before every item had run"},
      {FaultyTasks::run_twice, "an item was passed to the task function more than once"},
      {FaultyTasks::bad_range, "the task function was called with a range outside [0, item_count) or begin > end"},
  };
  for (const Case& c : cases) {
    INFO("expected: " << c.expected);
    uint32_t flags = 0;
    const std::string message = run_faulty(c.fault, &flags);
    CHECK((flags & k_step_flag_task_failure) != 0);
    CHECK(message.rfind("world_step: task system: stage '", 0) == 0);
    CHECK(message.find(c.expected) != std::string::npos);
    CHECK(message.find("the step completed with the same results") != std::string::npos);
  }
}

TEST_CASE("a task function called after its task, or after the world is gone, does nothing", "[physics][workers]") {
  FaultyTasks f;
  WorldDef def = awake_def();
  def.worker_count = 2;
  def.enqueue_task = &faulty_enqueue;
  def.finish_task = &faulty_finish;
  def.user_task_context = &f;
  const Result<WorldId> made = create_world(def);
  REQUIRE(made.ok());
  const WorldId w = made.value;
  const std::vector<BodyId> bodies = build_pyramid(w, k_base);
  for (int i = 0; i < k_steps; ++i) {
    const StepResult r = world_step(w, k_dt);
    REQUIRE(r.ok());
    CHECK(r.flags == 0);
  }
  REQUIRE(f.task != nullptr);
  const std::vector<int64_t> before = state_of(bodies);
  // A late call between steps: ignored (nothing moves), reported by the next
  // step.
  f.task(0, f.item_count, f.task_context);
  CHECK(state_of(bodies) == before);
  const StepResult next = world_step(w, k_dt);
  REQUIRE(next.ok());
  CHECK((next.flags & k_step_flag_task_failure) != 0);
  CHECK(next.task_status.message.find("while no task of this world was running") != std::string::npos);
  const StepResult after = world_step(w, k_dt);
  CHECK(after.flags == 0);  // reported once
  // After destroy_world: the context outlives the world; the call does nothing.
  REQUIRE(destroy_world(w).ok());
  f.task(0, f.item_count, f.task_context);
  f.task(0, 1, f.task_context);
  CHECK_FALSE(world_is_valid(w));
}

TEST_CASE("worker counts give the same bits as one worker (built-in pool)", "[physics][workers]") {
  const std::vector<int64_t> reference = reference_state();
  for (const int32_t workers : {2, 3, 16}) {
    WorldDef def = awake_def();
    def.worker_count = workers;
    ScopedWorld w(def);
    const std::vector<BodyId> bodies = build_pyramid(w.id, k_base);
    for (int i = 0; i < k_steps; ++i) {
      const StepResult r = world_step(w.id, k_dt);
      REQUIRE(r.ok());
      CHECK(r.flags == 0);
    }
    INFO(workers << " workers");
    CHECK(state_of(bodies) == reference);
  }
}
