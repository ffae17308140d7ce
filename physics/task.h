// task.h — running a step's stages on worker threads with the same bits
// (internal).
//
// DETERMINISM: a parallel stage is a loop over items (bodies, contacts,
// constraints of one graph colour) cut into blocks of a fixed number of
// items (the k_*_block constants where the stages live), so a block's items
// are a function of the data alone, never of the worker count. Each item's
// work writes only that item's own records (a constraint of one colour
// touches bodies no other constraint of the colour changes, contact_solver.cpp),
// so it gives the same bits whichever thread runs it and in whatever order
// the blocks run. A shared effect (a step flag, a counter) is written per
// block and combined afterwards in block order on the stepping thread;
// idempotent marks (every writer stores the same value) use relaxed atomic
// stores. Nothing decides an order by locks, atomics or thread timing.
//
// Three ways to run the blocks of a stage (run_blocks):
//   * inline on the stepping thread, in block order: worker_count 1, a stage
//     of one block, or a build without threads;
//   * the built-in pool (TaskSystem::pool): worker_count − 1 std::threads made
//     by task_system_configure (create_world, world_set_worker_count), never
//     inside a step. A stage is published with a serial number; every thread
//     (the stepping one too) owns a contiguous share of the blocks, claims
//     its own from the front and then the others' from their back (one
//     packed atomic range per thread), and the stepping thread returns when
//     every block has run (task.cpp explains why a late thread never reads a
//     newer stage's fields). Contiguous shares keep a thread on the same
//     region of the world from stage to stage (with the parallel
//     preparation: pyramid-100 on two cores 1.36–1.50× → 1.73–1.80× of one,
//     against one counter that dealt blocks alternately; docs/benchmarks.md,
//     "Workers"). Idle threads spin briefly, then yield,
//     then sleep on a condition variable;
//   * the user's task system (WorldDef::enqueue_task / finish_task): one
//     enqueue/finish pair per stage, items = blocks. The task_context handed
//     out is this world slot's TaskTicket, which lives for the whole process,
//     so a late call (after finish_task, or after destroy_world) finds no
//     active task and does nothing instead of touching freed memory. Every
//     block has a state (0 not run, 1 running, 2 done) claimed by
//     compare-exchange, so a block passed twice runs once; after finish_task
//     the stepping thread runs any block never passed. Each misuse is
//     recorded in TaskSystem::failure and reported by world_step.
//
// Rejected: splitting by thread id (work per task would depend on the
// worker count); per-worker partial sums combined by whichever finishes
// first (order by timing); a global thread pool shared by worlds (a world
// must not wait for another world's step).
#pragma once

#include <cstdint>
#include <memory>

#include <type_traits>

#include "physics/tandem.h"

namespace tandem {

struct Arena;
class WorkerPool;
struct TaskTicket;

/// Runs items [begin, end) of a stage (end − begin ≤ the stage's block size;
/// begin is a multiple of it).
using BlockFunction = void (*)(void* context, int32_t begin, int32_t end);

/// What went wrong with a user task system in the current step (the first
/// misuse; counts of every kind). Plain data: recording it allocates nothing.
struct TaskFailure {
  const char* stage = nullptr;  ///< the stage of the first misuse (static text), or null when none
  const char* what = nullptr;   ///< the first misuse (static text)
  int32_t null_handles = 0;     ///< enqueue_task returned null
  int32_t missed_blocks = 0;    ///< blocks never passed, run after finish_task
  int32_t repeated_blocks = 0;  ///< blocks passed again after they ran (skipped)
  int32_t bad_ranges = 0;       ///< calls with a range outside [0, item_count) or begin > end (ignored)
  int32_t stray_calls = 0;      ///< calls while no task of this world was running (ignored)
};

/// How a world runs its parallel stages.
struct TaskSystem {
  int32_t worker_count = 1;                  ///< 1…k_max_workers
  EnqueueTaskFunction enqueue_task = nullptr;
  FinishTaskFunction finish_task = nullptr;
  void* user_task_context = nullptr;
  std::unique_ptr<WorkerPool> pool;          ///< the built-in pool, or null (1 worker, callbacks, no threads)
  TaskTicket* ticket = nullptr;              ///< this world slot's ticket (process lifetime)
  Arena* arena = nullptr;                    ///< block states for user tasks
  TaskFailure failure;                       ///< reset by world_step
  TaskSystem();
  ~TaskSystem();
  TaskSystem(const TaskSystem&) = delete;
  TaskSystem& operator=(const TaskSystem&) = delete;
};

/// Checks worker_count (1…k_max_workers) and the callbacks (both or
/// neither); `function` names the caller in the message. Changes nothing.
Status validate_task_settings(const char* function, int32_t worker_count, EnqueueTaskFunction enqueue,
                              FinishTaskFunction finish);

/// Applies validated settings: starts or stops pool threads as needed (so
/// never call it inside a step). `world_slot` (0…k_max_worlds − 1) picks the
/// ticket; `arena` is the world's.
void task_system_configure(TaskSystem* tasks, int32_t world_slot, Arena* arena, int32_t worker_count,
                           EnqueueTaskFunction enqueue, FinishTaskFunction finish, void* user_task_context);

/// Stops the pool (joins its threads) and detaches the ticket.
void task_system_shutdown(TaskSystem* tasks);

/// True when a stage of more than one block is handed to workers.
bool task_system_is_parallel(const TaskSystem& tasks);

/// Adds the stray calls the ticket saw since the last call to the failure
/// record (world_step calls it once per step, after the stages).
void task_system_collect_strays(TaskSystem* tasks);

/// Runs fn over the items [0, count) in blocks of block_size (> 0) items
/// (see the file comment); returns when every block has run. `stage` is
/// static text naming the stage for failure reports.
void run_blocks(TaskSystem* tasks, const char* stage, int32_t count, int32_t block_size, BlockFunction fn,
                void* context);

/// run_blocks over a callable body(begin, end).
template <typename Body>
void parallel_for(TaskSystem* tasks, const char* stage, int32_t count, int32_t block_size, Body&& body) {
  if (count <= 0) return;
  if (count <= block_size || !task_system_is_parallel(*tasks)) {
    for (int32_t begin = 0; begin < count; begin += block_size) {
      body(begin, count - begin < block_size ? count : begin + block_size);
    }
    return;
  }
  using B = std::remove_reference_t<Body>;
  run_blocks(
      tasks, stage, count, block_size,
      [](void* context, int32_t begin, int32_t end) { (*static_cast<B*>(context))(begin, end); },
      const_cast<void*>(static_cast<const void*>(&body)));
}

// Atomic access to plain arena data (block states, bounce marks, flags).
// std::atomic_ref would do, but libc++ 14 (the wasm32 build) lacks it; the
// GCC/Clang __atomic builtins are the same operations on every compiler we
// build with.
/// Stores v with relaxed order.
inline void atomic_store_relaxed(int32_t* p, int32_t v) { __atomic_store_n(p, v, __ATOMIC_RELAXED); }
inline void atomic_store_relaxed(bool* p, bool v) { __atomic_store_n(p, v, __ATOMIC_RELAXED); }
/// Stores v with release order.
inline void atomic_store_release(int32_t* p, int32_t v) { __atomic_store_n(p, v, __ATOMIC_RELEASE); }
/// Loads with acquire order.
inline int32_t atomic_load_acquire(const int32_t* p) { return __atomic_load_n(p, __ATOMIC_ACQUIRE); }
/// Replaces *p by desired when it equals expected (acquire on success);
/// true when it did.
inline bool atomic_exchange_if(int32_t* p, int32_t expected, int32_t desired) {
  return __atomic_compare_exchange_n(p, &expected, desired, false, __ATOMIC_ACQUIRE, __ATOMIC_RELAXED);
}

/// The number of blocks of block_size items in count items.
inline int32_t block_count_of(int32_t count, int32_t block_size) {
  return count <= 0 ? 0 : (count - 1) / block_size + 1;
}

}  // namespace tandem
