// task.cpp — the built-in worker pool, the user task system adapter and the
// inline path (task.h explains the design and why the bits do not depend on
// any of them).
//
// Memory orders: the pool publishes a stage by writing the plain fields of
// one of two job slots and then storing its serial number; a thread that
// sees the serial reads them. Block results are published by `done`
// (release per block, acquire by the stepping thread), which returns as soon
// as every block ran — it never waits for a thread that is asleep or not
// scheduled. A pool thread enters a slot (`inside`) and then re-checks that
// the serial still names it; the stepping thread rewrites a slot only when
// nobody is inside, two stages later. These pairs use sequentially
// consistent operations, so either the thread sees the newer serial and
// leaves, or the stepping thread sees it inside and waits. The ticket protocol (user tasks) uses
// sequentially consistent operations on `inflight` and `active` so that
// either a call sees the task deactivated, or the stepping thread sees the
// call in flight and waits for it.
#include "physics/task.h"

#include <array>
#include <atomic>
#include <string>

#include "physics/arena.h"

#if TANDEM_THREADS
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <thread>
#include <vector>
#endif

namespace tandem {

Status make_status(StatusCode code, std::string message);  // world.cpp

namespace {

/// Hint to the processor that this is a spin-wait loop.
inline void spin_pause() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#endif
}

}  // namespace

// ---------------------------------------------------------------------------
// Tickets: the task_context of user tasks, one per world slot, never freed
// ---------------------------------------------------------------------------

/// The user task running now, as the trampoline sees it.
struct ActiveTask {
  BlockFunction fn = nullptr;
  void* context = nullptr;
  int32_t count = 0;        ///< items of the stage
  int32_t block_size = 1;
  int32_t block_count = 0;  ///< the item_count handed to enqueue_task
  int32_t* states = nullptr;  ///< per block: 0 not run, 1 running, 2 done (task.h's atomic_* helpers)
  std::atomic<int32_t> repeated{0};
  std::atomic<int32_t> bad_ranges{0};
};

struct TaskTicket {
  std::atomic<ActiveTask*> active{nullptr};
  std::atomic<int32_t> inflight{0};
  std::atomic<int32_t> stray_calls{0};
};

namespace {

std::array<TaskTicket, static_cast<size_t>(k_max_worlds)> g_tickets;

/// Runs block b of a task: the items [b·block_size, min(count, (b+1)·block_size)).
inline void run_block(const ActiveTask& task, int32_t b) {
  const int32_t begin = b * task.block_size;
  const int32_t end = task.count - begin < task.block_size ? task.count : begin + task.block_size;
  task.fn(task.context, begin, end);
}

/// Claims block b (0 → 1); true when this caller must run it.
inline bool claim_block(int32_t* state) {
  return atomic_exchange_if(state, 0, 1);
}

/// The TaskFunction handed to enqueue_task.
void task_entry(int32_t begin, int32_t end, void* task_context) {
  auto* ticket = static_cast<TaskTicket*>(task_context);
  if (ticket == nullptr) return;
  ticket->inflight.fetch_add(1, std::memory_order_seq_cst);
  ActiveTask* task = ticket->active.load(std::memory_order_seq_cst);
  if (task == nullptr) {
    ticket->stray_calls.fetch_add(1, std::memory_order_relaxed);
  } else if (begin < 0 || end < begin || end > task->block_count) {
    task->bad_ranges.fetch_add(1, std::memory_order_relaxed);
  } else {
    for (int32_t b = begin; b < end; ++b) {
      int32_t* state = &task->states[b];
      if (!claim_block(state)) {
        task->repeated.fetch_add(1, std::memory_order_relaxed);
        continue;
      }
      run_block(*task, b);
      atomic_store_release(state, 2);
    }
  }
  ticket->inflight.fetch_sub(1, std::memory_order_seq_cst);
}

/// Records one misuse kind; the first one names the stage.
void note_failure(TaskFailure* f, const char* stage, const char* what) {
  if (f->stage == nullptr) {
    f->stage = stage;
    f->what = what;
  }
}

}  // namespace

// ---------------------------------------------------------------------------
// The built-in pool
// ---------------------------------------------------------------------------

#if TANDEM_THREADS

class WorkerPool {
 public:
  explicit WorkerPool(int32_t thread_count) {
    threads_.reserve(static_cast<size_t>(thread_count));
    for (int32_t i = 0; i < thread_count; ++i) threads_.emplace_back([this, i] { worker_main(i + 1); });
  }

  ~WorkerPool() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_.store(true, std::memory_order_seq_cst);
      serial_.fetch_add(1, std::memory_order_seq_cst);
    }
    wake_.notify_all();
    for (std::thread& t : threads_) t.join();
  }

  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  int32_t thread_count() const { return static_cast<int32_t>(threads_.size()); }

  /// Runs every block of a stage; returns when all have run.
  void run(BlockFunction fn, void* context, int32_t count, int32_t block_size) {
    const uint64_t serial = serial_.load(std::memory_order_relaxed) + 1;  // only this thread writes it
    Job& job = jobs_[serial & 1];
    // A thread may still be inside the stage before last, which used this
    // slot (it found no block left and is leaving): wait for it.
    while (job.inside.load(std::memory_order_seq_cst) != 0) spin_pause();
    job.fn = fn;
    job.context = context;
    job.count = count;
    job.block_size = block_size;
    job.block_count = block_count_of(count, block_size);
    // Participant p (0: this thread, 1…: the pool's threads) owns the
    // contiguous blocks [p·B/P, (p+1)·B/P).
    const int32_t participants = static_cast<int32_t>(threads_.size()) + 1;
    job.participants = participants;
    for (int32_t p = 0; p < participants; ++p) {
      const int64_t lo = int64_t{p} * job.block_count / participants;
      const int64_t hi = int64_t{p + 1} * job.block_count / participants;
      job.ranges[p].store(pack_range(static_cast<uint32_t>(lo), static_cast<uint32_t>(hi)), std::memory_order_relaxed);
    }
    job.done.store(0, std::memory_order_relaxed);
    {
      // Under the lock so a thread about to sleep either sees the new serial
      // or is woken by the notify.
      std::lock_guard<std::mutex> lock(mutex_);
      serial_.store(serial, std::memory_order_seq_cst);
    }
    if (sleepers_.load(std::memory_order_seq_cst) > 0) wake_.notify_all();
    work(job, 0);
    for (uint32_t spins = 0; job.done.load(std::memory_order_acquire) < job.block_count; ++spins) {
      if (spins < 256) {
        spin_pause();
      } else {
        std::this_thread::yield();
      }
    }
  }

 private:
  /// A published stage. Its plain fields are written only while no thread
  /// is inside it (inside == 0) and before serial_ names it.
  struct Job {
    BlockFunction fn = nullptr;
    void* context = nullptr;
    int32_t count = 0;
    int32_t block_size = 1;
    int32_t block_count = 0;
    int32_t participants = 1;        ///< threads that may run blocks: the pool's and the stepping thread
    /// Per participant, the blocks [lo, hi) not yet claimed of its share
    /// (pack_range): the owner claims from the front, others from the back.
    std::atomic<uint64_t> ranges[k_max_workers];
    std::atomic<int32_t> done{0};    ///< blocks finished
    std::atomic<int32_t> inside{0};  ///< pool threads inside this stage
  };

  static uint64_t pack_range(uint32_t lo, uint32_t hi) { return (uint64_t{lo} << 32) | hi; }

  /// Claims one block of range r from its front (the owner) or its back
  /// (another participant); -1 when the range is empty.
  static int32_t claim(std::atomic<uint64_t>& r, bool front) {
    uint64_t v = r.load(std::memory_order_relaxed);
    for (;;) {
      const uint32_t lo = static_cast<uint32_t>(v >> 32), hi = static_cast<uint32_t>(v);
      if (lo >= hi) return -1;
      const uint64_t next = front ? pack_range(lo + 1, hi) : pack_range(lo, hi - 1);
      if (r.compare_exchange_weak(v, next, std::memory_order_relaxed, std::memory_order_relaxed)) {
        return static_cast<int32_t>(front ? lo : hi - 1);
      }
    }
  }

  static void run_one(Job& job, int32_t b) {
    const int32_t begin = b * job.block_size;
    const int32_t end = job.count - begin < job.block_size ? job.count : begin + job.block_size;
    job.fn(job.context, begin, end);
    job.done.fetch_add(1, std::memory_order_release);
  }

  /// Claims and runs blocks until none is left: first its own share, front
  /// to back (neighbouring blocks touch neighbouring bodies, so a thread
  /// keeps the same region of the world in its cache from stage to stage),
  /// then the other shares from their back. Which thread runs a block never
  /// changes what the block computes (task.h).
  static void work(Job& job, int32_t self) {
    const int32_t participants = job.participants;  // > self: every pool thread is one of them
    for (int32_t b; (b = claim(job.ranges[self], true)) >= 0;) run_one(job, b);
    for (int32_t k = 1; k < participants; ++k) {
      const int32_t other = (self + k) % participants;
      for (int32_t b; (b = claim(job.ranges[other], false)) >= 0;) run_one(job, b);
    }
  }

  void worker_main(int32_t self) {
    uint64_t seen = 0;
    for (;;) {
      // Spin (cheap between the stages of one step), then yield, then sleep
      // (between steps).
      uint64_t now = serial_.load(std::memory_order_seq_cst);
      if (now == seen) {
        const auto start = std::chrono::steady_clock::now();
        for (uint32_t spins = 0; now == seen; ++spins) {
          if (spins < 512) {
            spin_pause();
          } else if ((spins & 63) != 0 || std::chrono::steady_clock::now() - start < std::chrono::microseconds(500)) {
            std::this_thread::yield();
          } else {
            std::unique_lock<std::mutex> lock(mutex_);
            sleepers_.fetch_add(1, std::memory_order_seq_cst);
            wake_.wait(lock, [&] { return serial_.load(std::memory_order_seq_cst) != seen; });
            sleepers_.fetch_sub(1, std::memory_order_seq_cst);
          }
          now = serial_.load(std::memory_order_seq_cst);
        }
      }
      seen = now;
      if (stop_.load(std::memory_order_seq_cst)) return;
      // Enter the stage only if it is still the current one: then the
      // stepping thread cannot reuse its slot until this thread leaves.
      Job& job = jobs_[now & 1];
      job.inside.fetch_add(1, std::memory_order_seq_cst);
      if (serial_.load(std::memory_order_seq_cst) == now) work(job, self);
      job.inside.fetch_sub(1, std::memory_order_seq_cst);
    }
  }

  std::vector<std::thread> threads_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::atomic<uint64_t> serial_{0};
  std::atomic<bool> stop_{false};
  std::atomic<int32_t> sleepers_{0};
  Job jobs_[2];
};

#else

class WorkerPool {};  // no threads in this build: stages run inline

#endif

// ---------------------------------------------------------------------------
// TaskSystem
// ---------------------------------------------------------------------------

TaskSystem::TaskSystem() = default;
TaskSystem::~TaskSystem() { task_system_shutdown(this); }

Status validate_task_settings(const char* function, int32_t worker_count, EnqueueTaskFunction enqueue,
                              FinishTaskFunction finish) {
  if (worker_count < 1 || worker_count > k_max_workers) {
    return make_status(StatusCode::invalid_argument, std::string(function) + ": worker_count " +
                                                         std::to_string(worker_count) + " is outside [1, " +
                                                         std::to_string(k_max_workers) + "]");
  }
  if ((enqueue == nullptr) != (finish == nullptr)) {
    return make_status(StatusCode::invalid_argument,
                       std::string(function) + ": enqueue_task and finish_task must both be set or both be null (" +
                           (enqueue == nullptr ? "enqueue_task" : "finish_task") + " is null)");
  }
  return Status{};
}

void task_system_configure(TaskSystem* tasks, int32_t world_slot, Arena* arena, int32_t worker_count,
                           EnqueueTaskFunction enqueue, FinishTaskFunction finish, void* user_task_context) {
  tasks->ticket = &g_tickets[static_cast<size_t>(world_slot)];
  tasks->ticket->stray_calls.store(0, std::memory_order_relaxed);
  tasks->arena = arena;
  tasks->worker_count = worker_count;
  tasks->enqueue_task = enqueue;
  tasks->finish_task = finish;
  tasks->user_task_context = user_task_context;
#if TANDEM_THREADS
  const int32_t threads = enqueue == nullptr && worker_count > 1 ? worker_count - 1 : 0;
  if (threads == 0) {
    tasks->pool.reset();
  } else if (tasks->pool == nullptr || tasks->pool->thread_count() != threads) {
    tasks->pool.reset();
    tasks->pool = std::make_unique<WorkerPool>(threads);
  }
#endif
}

void task_system_shutdown(TaskSystem* tasks) {
  tasks->pool.reset();
  tasks->ticket = nullptr;
}

bool task_system_is_parallel(const TaskSystem& tasks) {
  return tasks.worker_count > 1 && (tasks.enqueue_task != nullptr || tasks.pool != nullptr);
}

void task_system_collect_strays(TaskSystem* tasks) {
  if (tasks->ticket == nullptr) return;
  const int32_t strays = tasks->ticket->stray_calls.exchange(0, std::memory_order_relaxed);
  if (strays == 0) return;
  tasks->failure.stray_calls += strays;
  note_failure(&tasks->failure, "(between tasks)",
               "the task function was called while no task of this world was running (after finish_task returned)");
}

namespace {

/// One stage through the user's enqueue_task / finish_task.
void run_user_task(TaskSystem* tasks, const char* stage, int32_t count, int32_t block_size, BlockFunction fn,
                   void* context) {
  ActiveTask task;
  task.fn = fn;
  task.context = context;
  task.count = count;
  task.block_size = block_size;
  task.block_count = block_count_of(count, block_size);
  task.states = arena_allocate_array<int32_t>(tasks->arena, task.block_count, "task_block_states");
  for (int32_t b = 0; b < task.block_count; ++b) task.states[b] = 0;
  TaskTicket* ticket = tasks->ticket;
  ticket->active.store(&task, std::memory_order_seq_cst);
  void* handle = tasks->enqueue_task(&task_entry, task.block_count, 1, ticket, tasks->user_task_context);
  TaskFailure& f = tasks->failure;
  if (handle == nullptr) {
    ++f.null_handles;
    note_failure(&f, stage, "enqueue_task returned null");
  } else {
    tasks->finish_task(handle, tasks->user_task_context);
  }
  // Blocks never passed run here, in block order; a block some late call is
  // running is waited for.
  int32_t missed = 0;
  for (int32_t b = 0; b < task.block_count; ++b) {
    int32_t* state = &task.states[b];
    if (claim_block(state)) {
      run_block(task, b);
      atomic_store_release(state, 2);
      ++missed;
      continue;
    }
    for (uint32_t spins = 0; atomic_load_acquire(state) != 2; ++spins) {
      spin_pause();
    }
  }
  ticket->active.store(nullptr, std::memory_order_seq_cst);
  while (ticket->inflight.load(std::memory_order_seq_cst) != 0) spin_pause();
  if (handle != nullptr && missed > 0) {
    f.missed_blocks += missed;
    note_failure(&f, stage, "finish_task returned before every item had run");
  }
  const int32_t repeated = task.repeated.load(std::memory_order_relaxed);
  if (repeated > 0) {
    f.repeated_blocks += repeated;
    note_failure(&f, stage, "an item was passed to the task function more than once");
  }
  const int32_t bad = task.bad_ranges.load(std::memory_order_relaxed);
  if (bad > 0) {
    f.bad_ranges += bad;
    note_failure(&f, stage, "the task function was called with a range outside [0, item_count) or begin > end");
  }
  arena_free(tasks->arena, task.states);
}

}  // namespace

void run_blocks(TaskSystem* tasks, const char* stage, int32_t count, int32_t block_size, BlockFunction fn,
                void* context) {
  if (count <= 0) return;
  if (tasks->worker_count > 1 && tasks->enqueue_task != nullptr) {
    run_user_task(tasks, stage, count, block_size, fn, context);
    return;
  }
#if TANDEM_THREADS
  if (tasks->pool != nullptr) {
    tasks->pool->run(fn, context, count, block_size);
    return;
  }
#endif
  (void)stage;
  for (int32_t begin = 0; begin < count; begin += block_size) {
    fn(context, begin, count - begin < block_size ? count : begin + block_size);
  }
}

}  // namespace tandem
