// world.cpp — the world registry, world creation and settings, and
// world_step() as a fixed list of stages (see world.h for the list).
//
// Registry: a fixed table of k_max_worlds atomic World pointers plus a
// generation per slot, guarded by a mutex for create/destroy. A lookup loads
// the pointer and compares the handle's generation with the one stored in
// the World, so a handle of a destroyed world fails even after its slot is
// reused. The slot a new world gets (lowest free) only affects its handle,
// never the simulation.
//
// Profile: world_step() reads std::chrono::steady_clock between stages and
// adds the differences to World::profile (integer nanoseconds). Nothing in
// the step reads the profile back, and it is neither hashed nor saved, so it
// cannot change a result. About 40 clock reads a step at 4 sub-steps
// (~1 µs in all on x86-64 Linux, where steady_clock is a vDSO call). A new
// stage gets its own profile_lap (or shares its neighbour's field).
//
// Settings are validated as a whole definition: every setter copies the
// current WorldDef, changes one field, validates the copy and only then
// stores it, so cross-field rules (push speed ≤ max speed) hold after any
// sequence of calls and a refused call changes nothing.
#include "physics/world.h"

#include <array>
#include <atomic>
#include <chrono>
#include <mutex>
#include <utility>

namespace tandem {

namespace {

std::mutex g_registry_mutex;
std::array<std::atomic<World*>, static_cast<size_t>(k_max_worlds)> g_worlds{};
std::array<uint16_t, static_cast<size_t>(k_max_worlds)> g_world_generations{};  // 0: slot never used

std::string q32_text(Q32 v) { return to_string(v); }

/// "function: WorldDef.field value unit is outside [lo, hi] unit".
bool check_closed(const char* function, const char* field, Q32 value, Q32 lo, Q32 hi, const char* unit,
                  Status* out) {
  if (lo <= value && value <= hi) return true;
  *out = make_status(StatusCode::invalid_argument, std::string(function) + ": " + field + " " + q32_text(value) +
                                                       " " + unit + " is outside [" + q32_text(lo) + ", " +
                                                       q32_text(hi) + "] " + unit);
  return false;
}

/// As check_closed for the interval (0, hi].
bool check_positive(const char* function, const char* field, Q32 value, Q32 hi, const char* unit, Status* out) {
  if (Q32::zero() < value && value <= hi) return true;
  *out = make_status(StatusCode::invalid_argument, std::string(function) + ": " + field + " " + q32_text(value) +
                                                       " " + unit + " is outside (0, " + q32_text(hi) + "] " + unit);
  return false;
}

Status validate_world_def(const WorldDef& def, const char* function) {
  Status s;
  if (def.internal_cookie != k_def_cookie) {
    return make_status(StatusCode::invalid_definition,
                       std::string(function) + ": the WorldDef was not made by default_world_def()");
  }
  if (!check_closed(function, "gravity.x", def.gravity.x, -k_max_gravity, k_max_gravity, "m/s²", &s)) return s;
  if (!check_closed(function, "gravity.y", def.gravity.y, -k_max_gravity, k_max_gravity, "m/s²", &s)) return s;
  if (def.sub_step_count < 1 || def.sub_step_count > k_max_sub_steps) {
    return make_status(StatusCode::invalid_argument, std::string(function) + ": sub_step_count " +
                                                         std::to_string(def.sub_step_count) + " is outside [1, " +
                                                         std::to_string(k_max_sub_steps) + "]");
  }
  if (!check_positive(function, "max_linear_speed", def.max_linear_speed, k_max_linear_speed, "m/s", &s)) return s;
  if (!check_positive(function, "contact_hertz", def.contact_hertz, k_max_hertz, "Hz", &s)) return s;
  if (!check_closed(function, "contact_damping_ratio", def.contact_damping_ratio, Q32::zero(), k_max_damping_ratio,
                    "", &s)) {
    return s;
  }
  if (!check_closed(function, "max_contact_push_speed", def.max_contact_push_speed, Q32::zero(),
                    def.max_linear_speed, "m/s", &s)) {
    return s;
  }
  if (!check_positive(function, "joint_hertz", def.joint_hertz, k_max_hertz, "Hz", &s)) return s;
  if (!check_closed(function, "joint_damping_ratio", def.joint_damping_ratio, Q32::zero(), k_max_damping_ratio, "",
                    &s)) {
    return s;
  }
  if (!check_closed(function, "restitution_threshold", def.restitution_threshold, Q32::zero(), def.max_linear_speed,
                    "m/s", &s)) {
    return s;
  }
  if (!check_closed(function, "hit_event_threshold", def.hit_event_threshold, Q32::zero(), def.max_linear_speed,
                    "m/s", &s)) {
    return s;
  }
  const AABB& b = def.bounds;
  const Q32 m = k_max_world_coordinate;
  if (!(b.lower.x < b.upper.x && b.lower.y < b.upper.y) || b.lower.x < -m || b.lower.y < -m || b.upper.x > m ||
      b.upper.y > m) {
    return make_status(StatusCode::invalid_argument,
                       std::string(function) + ": bounds [" + format_vec2(b.lower) + ", " + format_vec2(b.upper) +
                           "] m must have lower < upper and lie within ±" + q32_text(m) + " m");
  }
  if (static_cast<int32_t>(def.broad_phase) < static_cast<int32_t>(BroadPhaseKind::naive) ||
      static_cast<int32_t>(def.broad_phase) > static_cast<int32_t>(BroadPhaseKind::tree)) {
    return make_status(StatusCode::invalid_argument, std::string(function) + ": unknown broad_phase " +
                                                         std::to_string(static_cast<int32_t>(def.broad_phase)));
  }
  return validate_task_settings(function, def.worker_count, def.enqueue_task, def.finish_task);
}

/// The world's settings with the task fields it runs with: a restored
/// snapshot replaces World::def but not the workers (they are not state).
WorldDef current_def(const World& world) {
  WorldDef def = world.def;
  def.worker_count = world.tasks.worker_count;
  def.enqueue_task = world.tasks.enqueue_task;
  def.finish_task = world.tasks.finish_task;
  def.user_task_context = world.tasks.user_task_context;
  return def;
}

/// Applies a changed copy of the settings after validating it.
template <typename Change>
Status change_settings(WorldId id, const char* function, Change change) {
  World* world = nullptr;
  Status s = resolve_world(id, function, true, &world);
  if (!s.ok()) return s;
  WorldDef def = current_def(*world);
  change(&def);
  s = validate_world_def(def, function);
  if (s.ok()) world->def = def;
  return s;
}

}  // namespace

// ---------------------------------------------------------------------------
// Status and naming
// ---------------------------------------------------------------------------

Status make_status(StatusCode code, std::string message) {
  Status s;
  s.code = code;
  s.message = std::move(message);
  return s;
}

const char* status_code_name(StatusCode code) {
  switch (code) {
    case StatusCode::ok: return "ok";
    case StatusCode::null_handle: return "null handle";
    case StatusCode::invalid_handle: return "invalid handle";
    case StatusCode::foreign_handle: return "foreign handle";
    case StatusCode::world_locked: return "world locked";
    case StatusCode::invalid_definition: return "invalid definition";
    case StatusCode::invalid_argument: return "invalid argument";
    case StatusCode::capacity_exceeded: return "capacity exceeded";
  }
  return "unknown status";
}

std::string describe(WorldId id) {
  if (is_null(id)) return "null world";
  return "world {index " + std::to_string(id.index1 - 1) + ", generation " + std::to_string(id.generation) + "}";
}

std::string describe(BodyId id) {
  if (is_null(id)) return "null body";
  return "body {index " + std::to_string(id.index1 - 1) + ", generation " + std::to_string(id.generation) + "}";
}

std::string describe(ShapeId id) {
  if (is_null(id)) return "null shape";
  return "shape {index " + std::to_string(id.index1 - 1) + ", generation " + std::to_string(id.generation) + "}";
}

std::string format_vec2(Vec2 v) {
  // Appended piece by piece: g++ 12 -O3 warns (-Wrestrict, a false positive)
  // on "(" + std::string.
  std::string text = "(";
  text += q32_text(v.x);
  text += ", ";
  text += q32_text(v.y);
  text += ")";
  return text;
}

// ---------------------------------------------------------------------------
// Registry
// ---------------------------------------------------------------------------

World* find_world(WorldId id) {
  if (id.index1 == 0 || id.index1 > k_max_worlds) return nullptr;
  World* w = g_worlds[static_cast<size_t>(id.index1 - 1)].load(std::memory_order_acquire);
  if (w == nullptr || w->id.generation != id.generation) return nullptr;
  return w;
}

Status resolve_handle(const char* function, const char* kind, uint32_t index1, uint32_t generation, WorldId world_id,
                      WorldId expected_world, bool mutating, IdPool World::*pool, World** out_world,
                      int32_t* out_index) {
  // The message text is built only on a refusal: a handle that resolves
  // allocates nothing (command application on the hot path).
  const auto prefix = [&] { return std::string(function) + ": "; };
  if (index1 == 0) return make_status(StatusCode::null_handle, prefix() + "the " + kind + " handle is null");
  // The handle as describe() names it ("body {index 3, generation 1}").
  const auto what = [&] {
    return prefix() + kind + " {index " + std::to_string(index1 - 1) + ", generation " + std::to_string(generation) +
           "}";
  };
  if (!is_null(expected_world) && world_id != expected_world) {
    return make_status(StatusCode::foreign_handle,
                       what() + " belongs to " + describe(world_id) + ", not " + describe(expected_world));
  }
  World* w = find_world(world_id);
  if (w == nullptr) {
    return make_status(StatusCode::invalid_handle,
                       what() + " belongs to " + describe(world_id) + ", which was destroyed or never existed");
  }
  const IdPool& ids = w->*pool;
  if (index1 > static_cast<uint32_t>(id_pool_capacity(ids))) {
    return make_status(StatusCode::invalid_handle, what() + " was never created in " + describe(world_id));
  }
  const int32_t index = static_cast<int32_t>(index1 - 1);
  if (!id_pool_is_valid(ids, index, generation)) {
    const uint32_t now = id_pool_generation(ids, index);
    if (generation != 0 && generation < now) {
      return make_status(StatusCode::invalid_handle, what() + " was destroyed");
    }
    return make_status(StatusCode::invalid_handle, what() + " does not name a live " + kind + " of " +
                                                       describe(world_id) + " (the slot is at generation " +
                                                       std::to_string(now) + ")");
  }
  if (mutating && w->locked) {
    return make_status(StatusCode::world_locked,
                       prefix() + describe(world_id) + " is locked inside world_step(); change it between steps");
  }
  *out_world = w;
  *out_index = index;
  return Status{};
}

bool find_handle(uint32_t index1, uint32_t generation, WorldId world_id, IdPool World::*pool, World** out_world,
                 int32_t* out_index) {
  if (index1 == 0) return false;
  World* w = find_world(world_id);
  if (w == nullptr) return false;
  const IdPool& ids = w->*pool;
  if (index1 > static_cast<uint32_t>(id_pool_capacity(ids))) return false;
  const int32_t index = static_cast<int32_t>(index1 - 1);
  if (!id_pool_is_valid(ids, index, generation)) return false;
  *out_world = w;
  *out_index = index;
  return true;
}

Status resolve_world(WorldId id, const char* function, bool mutating, World** out_world) {
  if (is_null(id)) return make_status(StatusCode::null_handle, std::string(function) + ": the world handle is null");
  World* w = find_world(id);
  if (w == nullptr) {
    return make_status(StatusCode::invalid_handle,
                       std::string(function) + ": " + describe(id) + " was destroyed or never existed");
  }
  if (mutating && w->locked) {
    return make_status(StatusCode::world_locked, std::string(function) + ": " + describe(id) +
                                                     " is locked inside world_step(); change it between steps");
  }
  *out_world = w;
  return Status{};
}

Result<WorldId> create_world(const WorldDef& def) {
  Result<WorldId> result;
  result.status = validate_world_def(def, "create_world");
  if (!result.ok()) return result;
  std::lock_guard<std::mutex> lock(g_registry_mutex);
  int32_t slot = -1;
  for (int32_t i = 0; i < k_max_worlds; ++i) {
    if (g_worlds[static_cast<size_t>(i)].load(std::memory_order_relaxed) == nullptr) {
      slot = i;
      break;
    }
  }
  if (slot < 0) {
    result.status = make_status(StatusCode::capacity_exceeded, "create_world: all " + std::to_string(k_max_worlds) +
                                                                   " world slots are in use; destroy a world first");
    return result;
  }
  uint16_t& generation = g_world_generations[static_cast<size_t>(slot)];
  if (generation == 0) generation = 1;
  auto* world = new World{};
  world->id = WorldId{static_cast<uint16_t>(slot + 1), generation};
  world->def = def;
  arena_init(&world->arena, 0);
  task_system_configure(&world->tasks, slot, &world->arena, def.worker_count, def.enqueue_task, def.finish_task,
                        def.user_task_context);
  g_worlds[static_cast<size_t>(slot)].store(world, std::memory_order_release);
  result.value = world->id;
  return result;
}

Status destroy_world(WorldId id) {
  World* world = nullptr;
  Status s = resolve_world(id, "destroy_world", true, &world);
  if (!s.ok()) return s;
  {
    std::lock_guard<std::mutex> lock(g_registry_mutex);
    const size_t slot = static_cast<size_t>(id.index1 - 1);
    g_worlds[slot].store(nullptr, std::memory_order_release);
    uint16_t& generation = g_world_generations[slot];
    generation = generation == UINT16_MAX ? uint16_t{1} : static_cast<uint16_t>(generation + 1);
  }
  delete world;
  return s;
}

bool world_is_valid(WorldId id) { return find_world(id) != nullptr; }

Status world_check(WorldId id) {
  World* world = nullptr;
  return resolve_world(id, "world_check", false, &world);
}

bool world_is_locked(WorldId id) {
  const World* w = find_world(id);
  return w != nullptr && w->locked;
}

// ---------------------------------------------------------------------------
// Settings
// ---------------------------------------------------------------------------

WorldDef world_def(WorldId id) {
  const World* w = find_world(id);
  return w != nullptr ? current_def(*w) : default_world_def();
}

Status world_set_worker_count(WorldId id, int32_t worker_count) {
  Status s = change_settings(id, "world_set_worker_count", [&](WorldDef* d) { d->worker_count = worker_count; });
  if (!s.ok()) return s;
  World* w = find_world(id);
  TaskSystem& t = w->tasks;
  task_system_configure(&t, id.index1 - 1, &w->arena, worker_count, t.enqueue_task, t.finish_task,
                        t.user_task_context);
  return s;
}

int32_t world_worker_count(WorldId id) {
  const World* w = find_world(id);
  return w != nullptr ? w->tasks.worker_count : 1;
}

Vec2 world_gravity(WorldId id) {
  const World* w = find_world(id);
  return w != nullptr ? w->def.gravity : Vec2{};
}

Status world_set_gravity(WorldId id, Vec2 gravity) {
  return change_settings(id, "world_set_gravity", [&](WorldDef* d) { d->gravity = gravity; });
}

Status world_set_sub_step_count(WorldId id, int32_t sub_step_count) {
  return change_settings(id, "world_set_sub_step_count", [&](WorldDef* d) { d->sub_step_count = sub_step_count; });
}

Status world_set_contact_tuning(WorldId id, Q32 hertz, Q32 damping_ratio, Q32 push_speed) {
  return change_settings(id, "world_set_contact_tuning", [&](WorldDef* d) {
    d->contact_hertz = hertz;
    d->contact_damping_ratio = damping_ratio;
    d->max_contact_push_speed = push_speed;
  });
}

Status world_set_joint_tuning(WorldId id, Q32 hertz, Q32 damping_ratio) {
  return change_settings(id, "world_set_joint_tuning", [&](WorldDef* d) {
    d->joint_hertz = hertz;
    d->joint_damping_ratio = damping_ratio;
  });
}

Status world_set_restitution_threshold(WorldId id, Q32 threshold) {
  return change_settings(id, "world_set_restitution_threshold",
                         [&](WorldDef* d) { d->restitution_threshold = threshold; });
}

Status world_set_hit_event_threshold(WorldId id, Q32 threshold) {
  return change_settings(id, "world_set_hit_event_threshold",
                         [&](WorldDef* d) { d->hit_event_threshold = threshold; });
}

Status world_set_max_linear_speed(WorldId id, Q32 max_linear_speed) {
  return change_settings(id, "world_set_max_linear_speed",
                         [&](WorldDef* d) { d->max_linear_speed = max_linear_speed; });
}

Status world_enable_sleep(WorldId id, bool enable) {
  Status s = change_settings(id, "world_enable_sleep", [&](WorldDef* d) { d->enable_sleep = enable; });
  if (s.ok() && !enable) wake_all_bodies(find_world(id));
  return s;
}

Status world_enable_continuous(WorldId id, bool enable) {
  return change_settings(id, "world_enable_continuous", [&](WorldDef* d) { d->enable_continuous = enable; });
}

Status world_set_user_data(WorldId id, uint64_t user_data) {
  return change_settings(id, "world_set_user_data", [&](WorldDef* d) { d->user_data = user_data; });
}

uint64_t world_user_data(WorldId id) {
  const World* w = find_world(id);
  return w != nullptr ? w->def.user_data : 0;
}

WorldCounters world_counters(WorldId id) {
  WorldCounters c;
  const World* w = find_world(id);
  if (w == nullptr) return c;
  c.body_count = w->body_pool.alive_count;
  c.shape_count = w->shape_pool.alive_count;
  c.joint_count = w->joint_pool.alive_count;
  c.solver_body_count = w->last_solver_body_count;
  c.step_count = w->step_count;
  c.arena_capacity = w->arena.capacity;
  return c;
}

int32_t world_bodies(WorldId id, BodyId* out_ids, int32_t capacity) {
  const World* w = find_world(id);
  if (w == nullptr) return 0;
  int32_t n = 0;
  const int32_t end = id_pool_capacity(w->body_pool);
  for (int32_t i = 0; i < end; ++i) {
    if (!id_pool_is_alive(w->body_pool, i)) continue;
    if (n < capacity && out_ids != nullptr) out_ids[n] = make_body_id(*w, i);
    ++n;
  }
  return n;
}

WorldProfile world_profile(WorldId id) {
  const World* w = find_world(id);
  return w != nullptr ? w->profile : WorldProfile{};
}

// ---------------------------------------------------------------------------
// The step
// ---------------------------------------------------------------------------

namespace {

/// steady_clock now, ns since its epoch (timing only).
int64_t profile_now() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

/// Adds now − *mark (≥ 0: the clock is steady) to *field and moves the mark
/// to now.
void profile_lap(int64_t* field, int64_t* mark) {
  const int64_t now = profile_now();
  *field += now - *mark;
  *mark = now;
}

}  // namespace

StepResult world_step(WorldId id, Q32 time_step) {
  const int64_t step_start = profile_now();
  StepResult result;
  World* world = nullptr;
  result.status = resolve_world(id, "world_step", true, &world);
  if (!result.ok()) return result;
  if (time_step < Q32::zero() || time_step > k_max_time_step) {
    result.status = make_status(StatusCode::invalid_argument, "world_step: time_step " + q32_text(time_step) +
                                                                  " s is outside [0, " + q32_text(k_max_time_step) +
                                                                  "] s");
    return result;
  }
  if (time_step == Q32::zero()) return result;  // nothing moves, nothing changes
  const int32_t n = world->def.sub_step_count;
  const Q32 h = time_step / n;  // rounded to nearest, ties away from zero
  if (h == Q32::zero()) {
    result.status = make_status(StatusCode::invalid_argument,
                                "world_step: time_step " + q32_text(time_step) + " s is too small for " +
                                    std::to_string(n) + " sub-steps (the sub-step rounds to 0)");
    return result;
  }

  world->locked = true;
  StepContext* context = &world->context;
  *context = StepContext{};
  context->dt = time_step;
  context->h = h;
  context->sub_step_count = n;
  context->max_linear_speed = world->def.max_linear_speed;
  // h ≥ 2^-32 s, so the quotient is ≤ π/16 · 2^32 ≈ 8.4e8: no saturation.
  context->max_angular_speed = min(k_max_angular_speed, k_max_rotation_per_sub_step / h);
  context->tasks = &world->tasks;
  world->tasks.failure = TaskFailure{};

  // The stages, in order (world.h explains each); each lap adds its time
  // to the profile.
  WorldProfile profile;
  int64_t mark = profile_now();
  stage_update_contacts(world, context);
  profile_lap(&profile.narrow_phase_ns, &mark);
  // The broad phase times itself inside update_contacts: move that part.
  const int64_t broad = static_cast<int64_t>(world->broad_phase.stats.update_nanoseconds);
  profile.broad_phase_ns = broad < profile.narrow_phase_ns ? broad : profile.narrow_phase_ns;
  profile.narrow_phase_ns -= profile.broad_phase_ns;
  stage_wake_touched(world, context);  // sleepers touched by awake bodies (island.cpp)
  stage_wake_joined(world, context);   // sleepers joined to awake bodies (joint_solver.cpp)
  profile_lap(&profile.islands_ns, &mark);
  events_after_contacts(world);  // start transforms and hit candidates (events.cpp)
  profile_lap(&profile.events_ns, &mark);
  stage_prepare_bodies(world, context);
  stage_prepare_contacts(world, context);
  stage_prepare_joints(world, context);  // joint stages: nothing without joints (joint_solver.cpp)
  profile_lap(&profile.prepare_ns, &mark);
  for (int32_t i = 0; i < n; ++i) {
    context->sub_step_index = i;
    stage_record_approach(world, context);
    profile_lap(&profile.restitution_ns, &mark);
    stage_integrate_velocities(world, context);
    profile_lap(&profile.integrate_velocities_ns, &mark);
    stage_warm_start_joints(world, context);
    stage_warm_start(world, context);
    profile_lap(&profile.warm_start_ns, &mark);
    stage_solve_joints(world, context);
    stage_solve(world, context);
    profile_lap(&profile.solve_ns, &mark);
    stage_integrate_positions(world, context);
    profile_lap(&profile.integrate_positions_ns, &mark);
    stage_relax_joints(world, context);
    stage_relax(world, context);
    profile_lap(&profile.relax_ns, &mark);
  }
  stage_restitution(world, context);
  profile_lap(&profile.restitution_ns, &mark);
  stage_store_impulses(world, context);
  stage_store_joints(world, context);  // reactions, breaking, joint events
  profile_lap(&profile.store_impulses_ns, &mark);
  stage_continuous(world, context);  // fast bodies stop at their time of impact (continuous.cpp)
  stage_project_joints(world, context);  // revolute joints closed again after it (joint_solver.cpp)
  profile_lap(&profile.continuous_ns, &mark);
  stage_finalize_bodies(world, context);
  profile_lap(&profile.finalize_ns, &mark);
  stage_update_sleep(world, context);  // sleep timers and islands (island.cpp)
  profile_lap(&profile.islands_ns, &mark);
  events_after_step(world);  // contact, hit, sensor and move events (events.cpp)
  profile_lap(&profile.events_ns, &mark);

  // The arena is empty again; let it grow (outside the step's timing) if this
  // step spilled to the heap.
  arena_grow(&world->arena);
  reserve_contact_headroom(world);
  broad_phase_reserve_headroom(world);
  events_reserve_headroom(world);
  world->last_solver_body_count = context->solver_body_count;
  ++world->step_count;
  world->locked = false;
  task_system_collect_strays(&world->tasks);
  const TaskFailure& failure = world->tasks.failure;
  if (failure.stage != nullptr) {
    context->flags |= k_step_flag_task_failure;
    result.task_status = make_status(
        StatusCode::invalid_argument,
        std::string("world_step: task system: stage '") + failure.stage + "': " + failure.what +
            " (null handles " + std::to_string(failure.null_handles) + ", items run after finish_task " +
            std::to_string(failure.missed_blocks) + ", items passed twice " + std::to_string(failure.repeated_blocks) +
            ", bad ranges " + std::to_string(failure.bad_ranges) + ", calls outside a task " +
            std::to_string(failure.stray_calls) + "); the step completed with the same results");
  }
  result.flags = context->flags;
  profile.total_ns = profile_now() - step_start;
  world->profile = profile;
  return result;
}

}  // namespace tandem
