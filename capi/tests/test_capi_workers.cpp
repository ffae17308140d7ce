// test_capi_workers.cpp — worker threads and user task systems through the C
// API (tandem_world_def.worker_count / enqueue_task / finish_task,
// tandem_world_set_worker_count, tandem_world_step_ex) and the compact
// rollback buffer (tandem_rollback_*): hash chains equal to the plain
// single-threaded, uninterrupted run; bad input refused with a message.
#include "capi_test_util.h"

namespace {

constexpr int k_ticks = 90;

// A C task system that runs the items at once, on the calling thread, one at
// a time and in REVERSE order (a legal order: any order gives the same bits).
struct ReverseTasks {
  int32_t enqueued = 0;
  int32_t finished = 0;
  int32_t items = 0;
  int handle = 0;  // enqueue_task's non-null handle points here
};
extern "C" void* reverse_enqueue(tandem_task_fn task, int32_t item_count, int32_t /*min_range*/, void* task_context,
                                 void* user_context) {
  auto* tasks = static_cast<ReverseTasks*>(user_context);
  ++tasks->enqueued;
  tasks->items += item_count;
  for (int32_t i = item_count - 1; i >= 0; --i) task(i, i + 1, task_context);
  return &tasks->handle;
}
extern "C" void reverse_finish(void* user_task, void* user_context) {
  auto* tasks = static_cast<ReverseTasks*>(user_context);
  if (user_task == &tasks->handle) ++tasks->finished;
}

// A task system that runs each task on a new thread, items in reverse, two
// at a time; finish_task joins it.
extern "C" void* thread_enqueue(tandem_task_fn task, int32_t item_count, int32_t, void* task_context,
                                void* user_context) {
  ++*static_cast<int32_t*>(user_context);
  return new std::thread([=] {
    for (int32_t end = item_count; end > 0; end -= 2) task(end >= 2 ? end - 2 : 0, end, task_context);
  });
}
extern "C" void thread_finish(void* user_task, void*) {
  auto* thread = static_cast<std::thread*>(user_task);
  thread->join();
  delete thread;
}

// A broken task system: enqueue_task refuses every task (returns NULL).
extern "C" void* null_enqueue(tandem_task_fn, int32_t, int32_t, void*, void* user_context) {
  ++*static_cast<int32_t*>(user_context);
  return nullptr;
}
extern "C" void null_finish(void*, void*) {}

// Ground and a 6×6 grid of falling boxes: enough contacts and bodies for the
// parallel stages to split into several blocks.
void build(tandem_world_id world) {
  add_ground(world);
  for (int32_t row = 0; row < 6; ++row) {
    for (int32_t col = 0; col < 6; ++col) {
      const tandem_vec2 p = {tandem_q32_from_int(col - 3) + qt("0.1") * row, qi(1 + row)};
      add_box(world, TANDEM_BODY_DYNAMIC, p, qt("0.45"));
    }
  }
}

// The world's state hash after each of k_ticks steps.
std::vector<uint64_t> chain(tandem_world_id world) {
  tandem_q32 dt = 0;
  REQUIRE(tandem_q32_from_ratio(1, 60, &dt) == TANDEM_OK);
  std::vector<uint64_t> hashes;
  for (int t = 0; t < k_ticks; ++t) {
    tandem_step_result r;
    REQUIRE(tandem_world_step_ex(world, dt, &r) == TANDEM_OK);
    REQUIRE(r.task_status == TANDEM_OK);
    REQUIRE((r.flags & TANDEM_STEP_FLAG_TASK_FAILURE) == 0u);
    REQUIRE(r.task_message[0] == '\0');
    hashes.push_back(tandem_world_state_hash(world));
  }
  return hashes;
}

std::vector<uint64_t> run_with(const tandem_world_def& def) {
  tandem_world_id world{};
  REQUIRE(tandem_create_world(&def, &world) == TANDEM_OK);
  build(world);
  std::vector<uint64_t> hashes = chain(world);
  REQUIRE(tandem_destroy_world(world) == TANDEM_OK);
  return hashes;
}

}  // namespace

TEST_CASE("C worlds with 2 workers and with a C task system hash like 1 worker", "[capi][workers]") {
  const tandem_world_def one = tandem_default_world_def();
  REQUIRE(one.worker_count == 1);
  REQUIRE(one.enqueue_task == nullptr);
  REQUIRE(one.finish_task == nullptr);
  REQUIRE(one.user_task_context == nullptr);
  const std::vector<uint64_t> reference = run_with(one);
  REQUIRE(reference.size() == static_cast<size_t>(k_ticks));
  REQUIRE(reference.front() != reference.back());

  tandem_world_def two = one;
  two.worker_count = 2;
  CHECK(run_with(two) == reference);

  ReverseTasks tasks;
  tandem_world_def user = one;
  user.worker_count = 4;
  user.enqueue_task = reverse_enqueue;
  user.finish_task = reverse_finish;
  user.user_task_context = &tasks;
  CHECK(run_with(user) == reference);
  CHECK(tasks.enqueued > 0);  // the callbacks really ran the work
  CHECK(tasks.finished == tasks.enqueued);
  CHECK(tasks.items >= tasks.enqueued);

  int32_t threaded_tasks = 0;
  tandem_world_def threaded = one;
  threaded.worker_count = 3;
  threaded.enqueue_task = thread_enqueue;
  threaded.finish_task = thread_finish;
  threaded.user_task_context = &threaded_tasks;
  CHECK(run_with(threaded) == reference);
  CHECK(threaded_tasks > 0);

  // The settings read back, and the worker count changes between steps.
  tandem_world_id world{};
  REQUIRE(tandem_create_world(&user, &world) == TANDEM_OK);
  const tandem_world_def back = tandem_world_get_def(world);
  CHECK(back.worker_count == 4);
  CHECK(back.enqueue_task == reverse_enqueue);
  CHECK(back.finish_task == reverse_finish);
  CHECK(back.user_task_context == &tasks);
  CHECK(tandem_world_worker_count(world) == 4);
  build(world);
  tandem_q32 dt = 0;
  REQUIRE(tandem_q32_from_ratio(1, 60, &dt) == TANDEM_OK);
  std::vector<uint64_t> mixed;
  for (int t = 0; t < k_ticks; ++t) {
    REQUIRE(tandem_world_set_worker_count(world, 1 + t % 3) == TANDEM_OK);
    REQUIRE(tandem_world_worker_count(world) == 1 + t % 3);
    uint32_t flags = 0;
    REQUIRE(tandem_world_step(world, dt, &flags) == TANDEM_OK);
    CHECK((flags & TANDEM_STEP_FLAG_TASK_FAILURE) == 0u);
    mixed.push_back(tandem_world_state_hash(world));
  }
  CHECK(mixed == reference);
  REQUIRE(tandem_destroy_world(world) == TANDEM_OK);
}

TEST_CASE("a failing C task system is reported by tandem_world_step_ex; the bits do not change", "[capi][workers]") {
  int32_t refused = 0;
  tandem_world_def def = tandem_default_world_def();
  def.worker_count = 2;
  def.enqueue_task = null_enqueue;
  def.finish_task = null_finish;
  def.user_task_context = &refused;
  tandem_world_id world{};
  REQUIRE(tandem_create_world(&def, &world) == TANDEM_OK);
  build(world);
  tandem_q32 dt = 0;
  REQUIRE(tandem_q32_from_ratio(1, 60, &dt) == TANDEM_OK);
  // Every step's bits equal a correct run's; the steps whose parallel stages
  // went to the task system (small steps may run inline) report the failure.
  const std::vector<uint64_t> reference = run_with(tandem_default_world_def());
  int failed_steps = 0;
  for (int t = 0; t < k_ticks; ++t) {
    const int32_t refused_before = refused;
    tandem_step_result r;
    REQUIRE(tandem_world_step_ex(world, dt, &r) == TANDEM_OK);
    CHECK(tandem_last_error_code() == TANDEM_OK);  // the step itself succeeded
    CHECK(tandem_world_state_hash(world) == reference[static_cast<size_t>(t)]);
    const bool failed = (r.flags & TANDEM_STEP_FLAG_TASK_FAILURE) != 0u;
    CHECK(failed == (refused > refused_before));
    if (failed) {
      ++failed_steps;
      CHECK(r.task_status == TANDEM_ERROR_INVALID_ARGUMENT);
      INFO("task message: " << r.task_message);
      CHECK(std::string(r.task_message).find("enqueue_task returned null") != std::string::npos);
    } else {
      CHECK(r.task_status == TANDEM_OK);
      CHECK(r.task_message[0] == '\0');
    }
  }
  CHECK(failed_steps > 0);
  // NULL result pointer: only the status.
  REQUIRE(tandem_world_step_ex(world, dt, nullptr) == TANDEM_OK);
  REQUIRE(tandem_destroy_world(world) == TANDEM_OK);
}

TEST_CASE("worker settings refuse bad input with a message", "[capi][workers]") {
  for (const int32_t bad : {0, 17, -1}) {
    tandem_world_def def = tandem_default_world_def();
    def.worker_count = bad;
    tandem_world_id world{};
    const tandem_status s = tandem_create_world(&def, &world);
    INFO("worker_count " << bad << ": " << last_message());
    CHECK(s != TANDEM_OK);
    CHECK(last_message().find("worker_count " + std::to_string(bad) + " is outside [1, 16]") != std::string::npos);
    CHECK_FALSE(tandem_world_is_valid(world));
  }
  {
    tandem_world_def def = tandem_default_world_def();
    def.worker_count = 2;
    def.enqueue_task = reverse_enqueue;  // finish_task left NULL
    tandem_world_id world{};
    CHECK(tandem_create_world(&def, &world) != TANDEM_OK);
    CHECK(last_message().find("finish_task is null") != std::string::npos);
  }
  CWorld w;
  require_error(tandem_world_set_worker_count(w.id, 0), TANDEM_ERROR_INVALID_ARGUMENT,
                "worker_count 0 is outside [1, 16]");
  require_error(tandem_world_set_worker_count(w.id, 17), TANDEM_ERROR_INVALID_ARGUMENT,
                "worker_count 17 is outside [1, 16]");
  CHECK(tandem_world_worker_count(w.id) == 1);  // nothing half-applied
  REQUIRE(tandem_world_set_worker_count(w.id, TANDEM_MAX_WORKERS) == TANDEM_OK);
  CHECK(tandem_world_worker_count(w.id) == TANDEM_MAX_WORKERS);

  // Null and stale handles.
  const tandem_world_id null_world{};
  require_error(tandem_world_set_worker_count(null_world, 2), TANDEM_ERROR_NULL_HANDLE, "world_set_worker_count");
  CHECK(tandem_world_worker_count(null_world) == 1);
  tandem_world_id stale{};
  {
    CWorld gone;
    stale = gone.id;
  }
  require_error(tandem_world_set_worker_count(stale, 2), TANDEM_ERROR_INVALID_HANDLE, "world_set_worker_count");
  CHECK(tandem_world_worker_count(stale) == 1);
  tandem_step_result r;
  r.flags = 77;
  require_error(tandem_world_step_ex(stale, qt("0.016"), &r), TANDEM_ERROR_INVALID_HANDLE, "world");
  CHECK(r.flags == 0u);  // zeroed on refusal
}

TEST_CASE("rollback buffer: save, step, restore, step gives the uninterrupted hashes", "[capi][rollback]") {
  const std::vector<uint64_t> reference = run_with(tandem_default_world_def());
  CWorld w;
  build(w.id);
  tandem_rollback_buffer* saved = nullptr;
  tandem_rollback_buffer* ring = nullptr;
  REQUIRE(tandem_rollback_buffer_create(&saved) == TANDEM_OK);
  REQUIRE(tandem_rollback_buffer_create(&ring) == TANDEM_OK);
  CHECK(tandem_rollback_hash(saved) == 0u);
  CHECK(tandem_rollback_image_size(saved) == 0u);
  tandem_q32 dt = 0;
  REQUIRE(tandem_q32_from_ratio(1, 60, &dt) == TANDEM_OK);
  constexpr int k_save_tick = 30, k_rewind = 12;
  for (int t = 0; t < k_save_tick; ++t) REQUIRE(tandem_world_step(w.id, dt, nullptr) == TANDEM_OK);
  REQUIRE(tandem_rollback_save(w.id, saved) == TANDEM_OK);
  const uint64_t saved_hash = tandem_rollback_hash(saved);
  CHECK(saved_hash != 0u);
  CHECK(tandem_rollback_image_size(saved) > 0u);
  REQUIRE(tandem_rollback_buffer_copy(ring, saved) == TANDEM_OK);
  CHECK(tandem_rollback_hash(ring) == saved_hash);
  CHECK(tandem_rollback_image_size(ring) == tandem_rollback_image_size(saved));
  // Steps past the save (a prediction), then roll back and re-simulate.
  for (int t = 0; t < k_rewind; ++t) REQUIRE(tandem_world_step(w.id, dt, nullptr) == TANDEM_OK);
  CHECK(tandem_world_state_hash(w.id) == reference[k_save_tick + k_rewind - 1]);
  REQUIRE(tandem_rollback_restore(w.id, ring) == TANDEM_OK);
  tandem_rollback_buffer* again = nullptr;
  REQUIRE(tandem_rollback_buffer_create(&again) == TANDEM_OK);
  REQUIRE(tandem_rollback_save(w.id, again) == TANDEM_OK);
  CHECK(tandem_rollback_hash(again) == saved_hash);  // restored = saved, by the compact hash
  for (int t = k_save_tick; t < k_ticks; ++t) {
    REQUIRE(tandem_world_step(w.id, dt, nullptr) == TANDEM_OK);
    CHECK(tandem_world_state_hash(w.id) == reference[static_cast<size_t>(t)]);
  }
  // The buffer from this world restores into another world of the same build.
  CWorld other;
  REQUIRE(tandem_rollback_restore(other.id, saved) == TANDEM_OK);
  REQUIRE(tandem_world_step(other.id, dt, nullptr) == TANDEM_OK);
  CHECK(tandem_world_state_hash(other.id) == reference[k_save_tick]);

  // Bad input: NULL buffers, empty buffer, null and stale worlds.
  require_error(tandem_rollback_buffer_create(nullptr), TANDEM_ERROR_NULL_POINTER, "out_buffer");
  require_error(tandem_rollback_save(w.id, nullptr), TANDEM_ERROR_NULL_POINTER, "tandem_rollback_save: buffer");
  require_error(tandem_rollback_restore(w.id, nullptr), TANDEM_ERROR_NULL_POINTER, "tandem_rollback_restore: buffer");
  require_error(tandem_rollback_buffer_copy(nullptr, saved), TANDEM_ERROR_NULL_POINTER, "dst");
  require_error(tandem_rollback_buffer_copy(ring, nullptr), TANDEM_ERROR_NULL_POINTER, "src");
  CHECK(tandem_rollback_hash(nullptr) == 0u);
  CHECK(tandem_rollback_image_size(nullptr) == 0u);
  tandem_rollback_buffer* empty = nullptr;
  REQUIRE(tandem_rollback_buffer_create(&empty) == TANDEM_OK);
  const uint64_t before = tandem_world_state_hash(w.id);
  CHECK(tandem_rollback_restore(w.id, empty) != TANDEM_OK);
  CHECK_FALSE(last_message().empty());
  CHECK(tandem_world_state_hash(w.id) == before);  // a refused restore changes nothing
  const tandem_world_id null_world{};
  require_error(tandem_rollback_save(null_world, empty), TANDEM_ERROR_NULL_HANDLE, "world");
  CHECK(tandem_rollback_image_size(empty) == 0u);  // unchanged by the refused save
  tandem_world_id stale{};
  {
    CWorld gone;
    stale = gone.id;
  }
  require_error(tandem_rollback_save(stale, empty), TANDEM_ERROR_INVALID_HANDLE, "world");
  require_error(tandem_rollback_restore(stale, saved), TANDEM_ERROR_INVALID_HANDLE, "world");
  tandem_rollback_buffer_free(empty);
  tandem_rollback_buffer_free(again);
  tandem_rollback_buffer_free(ring);
  tandem_rollback_buffer_free(saved);
  tandem_rollback_buffer_free(nullptr);  // allowed
}
