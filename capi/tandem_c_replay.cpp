// tandem_c_replay.cpp — the C API of snapshots, hashes, commands, recorders,
// replays, verify/diff, the sync test and scenes.
// (design and how to add a function: tandem_c_core.cpp's top comment).
#include "tandem_c_internal.h"

#include "replay/rollback.h"

using namespace tandem_c_internal;

// --- snapshots and hashes ---------------------------------------------------------------------
size_t tandem_world_snapshot_size(tandem_world_id world) {
  return guard_value(size_t{0}, [&] { return world_snapshot_size(to_cpp(world)); });
}

tandem_status tandem_world_snapshot(tandem_world_id world, uint8_t* out_bytes, size_t capacity, size_t* out_size) {
  static const char* fn = "tandem_world_snapshot";
  if (out_size == nullptr) return null_pointer(fn, "out_size");
  if (out_bytes == nullptr && capacity != 0) return null_pointer(fn, "out_bytes (with a non-zero capacity)");
  return guard(fn, [&] {
    const WorldId w = to_cpp(world);
    if (const Status s = world_check(w); !s.ok()) return status(s);
    const size_t needed = world_snapshot_size(w);
    *out_size = needed;
    if (out_bytes == nullptr) return succeed();  // size query
    if (capacity < needed) {
      return fail(TANDEM_ERROR_BUFFER_TOO_SMALL, std::string(fn) + ": the buffer holds " + std::to_string(capacity) +
                                                     " bytes, the snapshot needs " + std::to_string(needed));
    }
    size_t written = 0;
    const Status s = world_snapshot(w, out_bytes, capacity, &written);
    *out_size = written;
    return status(s);
  });
}

tandem_status tandem_world_restore(tandem_world_id world, const uint8_t* bytes, size_t size) {
  static const char* fn = "tandem_world_restore";
  if (bytes == nullptr && size != 0) return null_pointer(fn, "bytes");
  return guard(fn, [&] { return status(world_restore(to_cpp(world), bytes, size)); });
}

tandem_status tandem_create_world_from_snapshot(const uint8_t* bytes, size_t size, tandem_world_id* out_world) {
  static const char* fn = "tandem_create_world_from_snapshot";
  if (bytes == nullptr && size != 0) return null_pointer(fn, "bytes");
  if (out_world == nullptr) return null_pointer(fn, "out_world");
  return guard(fn, [&] {
    const Result<WorldId> r = create_world_from_snapshot(bytes, size);
    if (r.ok()) {
      *out_world = to_c(r.value);
      g_filters[r.value.index1] = FilterSlot{};
    }
    return status(r.status);
  });
}

uint64_t tandem_world_state_hash(tandem_world_id world) {
  return guard_value(uint64_t{0}, [&] { return world_state_hash(to_cpp(world)); });
}
uint64_t tandem_body_state_hash(tandem_body_id body) {
  return guard_value(uint64_t{0}, [&] { return body_state_hash(to_cpp(body)); });
}

tandem_status tandem_world_body_hashes(tandem_world_id world, uint64_t* out_hashes, int32_t capacity, int32_t* out_count) {
  static const char* fn = "tandem_world_body_hashes";
  return guard(fn, [&] {
    std::vector<uint64_t> hashes;
    const Status s = world_body_hashes(to_cpp(world), &hashes);
    if (!s.ok()) return status(s);
    return fill(fn, std::span<const uint64_t>(hashes), out_hashes, capacity, out_count, same<uint64_t>);
  });
}

tandem_status tandem_encode_state_delta(const uint8_t* base, size_t base_size, const uint8_t* image, size_t image_size,
                                        uint8_t* out_delta, size_t capacity, size_t* out_size) {
  static const char* fn = "tandem_encode_state_delta";
  if ((base == nullptr && base_size != 0) || (image == nullptr && image_size != 0)) return null_pointer(fn, "an image");
  return guard(fn, [&] {
    std::vector<uint8_t> delta;
    encode_state_delta(base, base_size, image, image_size, &delta);
    return fill(fn, std::span<const uint8_t>(delta), out_delta, capacity, out_size, same<uint8_t>);
  });
}

tandem_status tandem_apply_state_delta(const uint8_t* base, size_t base_size, const uint8_t* delta, size_t delta_size,
                                       uint8_t* out_image, size_t capacity, size_t* out_size) {
  static const char* fn = "tandem_apply_state_delta";
  if ((base == nullptr && base_size != 0) || (delta == nullptr && delta_size != 0)) return null_pointer(fn, "an input");
  return guard(fn, [&] {
    std::vector<uint8_t> image;
    if (const Status s = apply_state_delta(base, base_size, delta, delta_size, &image); !s.ok()) {
      return fail(TANDEM_ERROR_PARSE, std::string(fn) + ": " + s.message);
    }
    return fill(fn, std::span<const uint8_t>(image), out_image, capacity, out_size, same<uint8_t>);
  });
}

tandem_status tandem_diff_snapshots(const uint8_t* a, size_t a_size, const uint8_t* b, size_t b_size,
                                    tandem_diff_report* out_report) {
  static const char* fn = "tandem_diff_snapshots";
  if (out_report == nullptr) return null_pointer(fn, "out_report");
  std::memset(out_report, 0, sizeof *out_report);
  if ((a == nullptr && a_size != 0) || (b == nullptr && b_size != 0)) return null_pointer(fn, "a snapshot");
  return guard(fn, [&] {
    const DiffReport r = diff_snapshots(std::span<const uint8_t>(a, a_size), std::span<const uint8_t>(b, b_size));
    fill_diff_report(r, out_report);
    return status(r.error);
  });
}

void tandem_free_diff_report(tandem_diff_report* report) {
  if (report == nullptr) return;
  std::free(report->difference_text);
  std::free(report->text);
  std::memset(report, 0, sizeof *report);
}

// --- commands ------------------------------------------------------------------------------------
tandem_command tandem_default_command(int32_t type) {
  tandem_command c;
  std::memset(&c, 0, sizeof c);
  c.type = type;
  c.body_def = tandem_default_body_def();
  c.at_center = true;
  c.rotation = tandem_rot_identity();
  c.flag = true;
  const JointSpec spec;  // the C++ defaults (unit axis, length 1)
  c.joint_spec.local_axis = to_c(spec.local_axis);
  c.joint_spec.length = spec.length.raw;
  return c;
}

const char* tandem_command_type_name(int32_t type) {
  if (type < 1 || type > k_last_command_type) return "unknown";
  return command_type_name(static_cast<CommandType>(type));
}

tandem_shape_spec tandem_default_shape_spec(int32_t kind) {
  tandem_shape_spec s;
  std::memset(&s, 0, sizeof s);
  s.kind = kind;
  s.def = tandem_default_shape_def();
  return s;
}

tandem_status tandem_apply_command(tandem_world_id world, const tandem_command* command, tandem_body_id* out_created) {
  static const char* fn = "tandem_apply_command";
  return guard(fn, [&] {
    Command c;
    if (const tandem_status s = command_to_cpp(fn, command, &c); s != TANDEM_OK) return s;
    BodyId created;
    const Status s = apply_command(to_cpp(world), c, &created);
    if (out_created != nullptr) *out_created = to_c(created);
    return status(s);
  });
}

// --- recorders -------------------------------------------------------------------------------------
tandem_recorder_options tandem_default_recorder_options(void) {
  const RecorderOptions o;
  tandem_recorder_options c;
  std::memset(&c, 0, sizeof c);
  c.keyframe_interval = o.keyframe_interval;
  c.record_hashes = o.record_hashes;
  c.flush_every = o.flush_every;
  c.time_step = o.time_step.raw;
  return c;
}

namespace {
using tandem_c_internal::to_c;
using tandem_c_internal::to_cpp;
RecorderOptions to_cpp(const tandem_recorder_options* o) {
  RecorderOptions r;
  if (o != nullptr) {
    r.keyframe_interval = o->keyframe_interval;
    r.record_hashes = o->record_hashes;
    r.flush_every = o->flush_every;
    r.time_step = q(o->time_step);
  }
  return r;
}

tandem_status add_recorder(std::unique_ptr<RecorderObject> rec, tandem_recorder_id* out) {
  const auto [index1, generation] = recorders().add(std::move(rec));
  *out = tandem_recorder_id{index1, generation};
  return succeed();
}
}  // namespace

tandem_status tandem_recorder_create_memory(const tandem_recorder_options* options, tandem_recorder_id* out_recorder) {
  static const char* fn = "tandem_recorder_create_memory";
  if (out_recorder == nullptr) return null_pointer(fn, "out_recorder");
  return guard(fn, [&] {
    auto rec = std::make_unique<RecorderObject>();
    rec->recorder.open_memory(to_cpp(options));
    return add_recorder(std::move(rec), out_recorder);
  });
}

tandem_status tandem_recorder_create_file(const char* path, const tandem_recorder_options* options,
                                          tandem_recorder_id* out_recorder) {
  static const char* fn = "tandem_recorder_create_file";
  if (path == nullptr) return null_pointer(fn, "path");
  if (out_recorder == nullptr) return null_pointer(fn, "out_recorder");
  return guard(fn, [&] {
    auto rec = std::make_unique<RecorderObject>();
    const Status s = rec->recorder.open_file(path, to_cpp(options));
    if (!s.ok()) return fail(TANDEM_ERROR_IO, std::string(fn) + ": " + s.message);
    return add_recorder(std::move(rec), out_recorder);
  });
}

tandem_status tandem_recorder_destroy(tandem_recorder_id recorder) {
  return guard("tandem_recorder_destroy",
               [&] { return recorders().remove("tandem_recorder_destroy", recorder.index1, recorder.generation); });
}

#define TANDEM_C_GET_RECORDER(fn, id)                                          \
  RecorderObject* rec = recorders().get(fn, (id).index1, (id).generation);    \
  if (rec == nullptr) return t_code

tandem_status tandem_recorder_begin(tandem_recorder_id recorder, tandem_world_id world, const uint8_t* scene,
                                    size_t scene_size) {
  static const char* fn = "tandem_recorder_begin";
  if (scene == nullptr && scene_size != 0) return null_pointer(fn, "scene");
  return guard(fn, [&] {
    TANDEM_C_GET_RECORDER(fn, recorder);
    return status(rec->recorder.begin(to_cpp(world), std::span<const uint8_t>(scene, scene_size)));
  });
}

tandem_status tandem_recorder_submit(tandem_recorder_id recorder, const tandem_command* command) {
  static const char* fn = "tandem_recorder_submit";
  return guard(fn, [&] {
    TANDEM_C_GET_RECORDER(fn, recorder);
    Command c;
    if (const tandem_status s = command_to_cpp(fn, command, &c); s != TANDEM_OK) return s;
    return status(rec->recorder.submit(c));
  });
}

tandem_status tandem_recorder_submit_payload(tandem_recorder_id recorder, const uint8_t* payload, size_t size) {
  static const char* fn = "tandem_recorder_submit_payload";
  if (payload == nullptr && size != 0) return null_pointer(fn, "payload");
  return guard(fn, [&] {
    TANDEM_C_GET_RECORDER(fn, recorder);
    if (size > k_max_user_payload_bytes) {
      return fail(TANDEM_ERROR_INVALID_ARGUMENT, std::string(fn) + ": " + std::to_string(size) + " bytes exceed " +
                                                     std::to_string(k_max_user_payload_bytes));
    }
    return status(rec->recorder.submit_payload(std::vector<uint8_t>(payload, payload + size)));
  });
}

tandem_status tandem_recorder_step(tandem_recorder_id recorder, uint32_t* out_flags) {
  static const char* fn = "tandem_recorder_step";
  return guard(fn, [&] {
    TANDEM_C_GET_RECORDER(fn, recorder);
    const StepResult r = rec->recorder.step();
    if (out_flags != nullptr) *out_flags = r.flags;
    return status(r.status);
  });
}

tandem_status tandem_recorder_finish(tandem_recorder_id recorder) {
  static const char* fn = "tandem_recorder_finish";
  return guard(fn, [&] {
    TANDEM_C_GET_RECORDER(fn, recorder);
    return status(rec->recorder.finish());
  });
}

int64_t tandem_recorder_tick_count(tandem_recorder_id recorder) {
  return guard_value(int64_t{0}, [&] {
    const tandem_status saved = t_code;
    const std::string message = t_message;
    RecorderObject* rec = recorders().get("tandem_recorder_tick_count", recorder.index1, recorder.generation);
    t_code = saved;  // getters leave the last error alone
    t_message = message;
    return rec != nullptr ? rec->recorder.tick_count() : 0;
  });
}

uint64_t tandem_recorder_last_hash(tandem_recorder_id recorder) {
  return guard_value(uint64_t{0}, [&] {
    const tandem_status saved = t_code;
    const std::string message = t_message;
    RecorderObject* rec = recorders().get("tandem_recorder_last_hash", recorder.index1, recorder.generation);
    t_code = saved;
    t_message = message;
    return rec != nullptr ? rec->recorder.last_hash() : 0;
  });
}

tandem_status tandem_recorder_memory(tandem_recorder_id recorder, uint8_t* out_bytes, size_t capacity, size_t* out_size) {
  static const char* fn = "tandem_recorder_memory";
  return guard(fn, [&] {
    TANDEM_C_GET_RECORDER(fn, recorder);
    const std::vector<uint8_t>& m = rec->recorder.memory();
    return fill(fn, std::span<const uint8_t>(m), out_bytes, capacity, out_size, same<uint8_t>);
  });
}

// --- replays ------------------------------------------------------------------------------------------
namespace {
using tandem_c_internal::to_c;
using tandem_c_internal::to_cpp;
tandem_status add_replay(std::unique_ptr<ReplayObject> r, tandem_replay_id* out) {
  const auto [index1, generation] = replays().add(std::move(r));
  *out = tandem_replay_id{index1, generation};
  return succeed();
}

// A getter's replay lookup that leaves the last error alone.
ReplayObject* peek_replay(tandem_replay_id id) {
  const tandem_status saved = t_code;
  const std::string message = t_message;
  ReplayObject* r = replays().get("", id.index1, id.generation);
  t_code = saved;
  t_message = message;
  return r;
}
}  // namespace

bool tandem_is_replay_image(const uint8_t* bytes, size_t size) {
  return bytes != nullptr && is_replay_image(std::span<const uint8_t>(bytes, size));
}

tandem_status tandem_replay_load_memory(const uint8_t* bytes, size_t size, tandem_replay_id* out_replay) {
  static const char* fn = "tandem_replay_load_memory";
  if (bytes == nullptr && size != 0) return null_pointer(fn, "bytes");
  if (out_replay == nullptr) return null_pointer(fn, "out_replay");
  return guard(fn, [&] {
    auto r = std::make_unique<ReplayObject>();
    const Status s = read_replay(std::span<const uint8_t>(bytes, size), &r->replay);
    if (!s.ok()) return fail(TANDEM_ERROR_PARSE, std::string(fn) + ": " + s.message);
    return add_replay(std::move(r), out_replay);
  });
}

tandem_status tandem_replay_load_file(const char* path, tandem_replay_id* out_replay) {
  static const char* fn = "tandem_replay_load_file";
  if (path == nullptr) return null_pointer(fn, "path");
  if (out_replay == nullptr) return null_pointer(fn, "out_replay");
  return guard(fn, [&] {
    std::vector<uint8_t> bytes;
    if (const Status s = read_file_bytes(path, &bytes); !s.ok())
      return fail(TANDEM_ERROR_IO, std::string(fn) + ": " + s.message);
    auto r = std::make_unique<ReplayObject>();
    const Status s = read_replay(bytes, &r->replay);
    if (!s.ok()) return fail(TANDEM_ERROR_PARSE, std::string(fn) + ": " + path + ": " + s.message);
    return add_replay(std::move(r), out_replay);
  });
}

tandem_status tandem_replay_destroy(tandem_replay_id replay) {
  return guard("tandem_replay_destroy",
               [&] { return replays().remove("tandem_replay_destroy", replay.index1, replay.generation); });
}

int64_t tandem_replay_tick_count(tandem_replay_id replay) {
  return guard_value(int64_t{0}, [&] {
    const ReplayObject* r = peek_replay(replay);
    return r != nullptr ? r->replay.tick_count() : 0;
  });
}


tandem_status tandem_replay_tick_hash(tandem_replay_id replay, int64_t tick, uint64_t* out_hash) {
  static const char* fn = "tandem_replay_tick_hash";
  if (out_hash == nullptr) return null_pointer(fn, "out_hash");
  return guard(fn, [&] {
    TANDEM_C_GET_REPLAY(r, fn, replay);
    if (tick < 1 || tick > r->replay.tick_count()) {
      return fail(TANDEM_ERROR_INVALID_ARGUMENT, std::string(fn) + ": tick " + std::to_string(tick) + " is outside 1…" +
                                                     std::to_string(r->replay.tick_count()));
    }
    const TickRecord& t = r->replay.tick_record(tick);
    if (!t.has_hash) {
      return fail(TANDEM_ERROR_INVALID_ARGUMENT, std::string(fn) + ": tick " + std::to_string(tick) + " has no hash");
    }
    *out_hash = t.hash;
    return succeed();
  });
}

// --- sync test -----------------------------------------------------------------------------------------
tandem_synctest_options tandem_default_synctest_options(void) {
  const SyncTestOptions o;
  tandem_synctest_options c;
  std::memset(&c, 0, sizeof c);
  c.ticks = o.ticks;
  c.rollback = o.rollback;
  c.time_step = o.time_step.raw;
  return c;
}

tandem_status tandem_run_synctest(tandem_world_id world, const tandem_synctest_options* options,
                                  tandem_synctest_input_fn inputs, void* context, tandem_synctest_report* out_report) {
  static const char* fn = "tandem_run_synctest";
  if (options == nullptr) return null_pointer(fn, "options");
  if (out_report == nullptr) return null_pointer(fn, "out_report");
  std::memset(out_report, 0, sizeof *out_report);
  return guard(fn, [&] {
    SyncTestOptions o;
    o.ticks = options->ticks;
    o.rollback = options->rollback;
    o.time_step = q(options->time_step);
    SyncTestReport r;
    const Status s = run_synctest(to_cpp(world), o, [&](WorldId w, int64_t tick) {
      if (inputs != nullptr) inputs(to_c(w), tick, context);
    }, &r);
    tandem_synctest_report c;
    std::memset(&c, 0, sizeof c);
    c.passed = r.passed;
    c.ticks_run = r.ticks_run;
    c.resimulated_ticks = r.resimulated_ticks;
    c.first_mismatch_tick = r.first_mismatch_tick;
    c.detected_at_tick = r.detected_at_tick;
    c.expected_hash = r.expected_hash;
    c.actual_hash = r.actual_hash;
    c.message = dup_text(s.ok() ? r.message : s.message);
    *out_report = c;
    return status(s);
  });
}

void tandem_free_synctest_report(tandem_synctest_report* report) {
  if (report == nullptr) return;
  std::free(report->message);
  std::memset(report, 0, sizeof *report);
}

// --- scenes ----------------------------------------------------------------------------------------------
#if TANDEM_C_HAS_SCENES
namespace {
using tandem_c_internal::to_c;
using tandem_c_internal::to_cpp;
tandem_status add_scene(Result<scene::Scene> loaded, const char* fn, tandem_scene_id* out) {
  if (!loaded.ok()) return fail(TANDEM_ERROR_PARSE, std::string(fn) + ": " + loaded.status.message);
  auto obj = std::make_unique<SceneObject>();
  obj->scene = std::move(loaded.value);
  const auto [index1, generation] = scenes().add(std::move(obj));
  *out = tandem_scene_id{index1, generation};
  return succeed();
}

#define TANDEM_C_GET_SCENE(var, fn, id)                                   \
  SceneObject* var = scenes().get(fn, (id).index1, (id).generation);     \
  if (var == nullptr) return t_code

const scene::BuiltScene* find_build(const SceneObject* s, tandem_world_id world) {
  for (const scene::BuiltScene& b : s->builds)
    if (b.world == to_cpp(world)) return &b;
  return nullptr;
}

tandem_status not_built(const char* fn, tandem_world_id world) {
  return fail(TANDEM_ERROR_INVALID_ARGUMENT,
              std::string(fn) + ": " + describe(to_cpp(world)) + " was not built from this scene (tandem_scene_build)");
}
}  // namespace

tandem_status tandem_scene_load_file(const char* path, tandem_scene_id* out_scene) {
  static const char* fn = "tandem_scene_load_file";
  if (path == nullptr) return null_pointer(fn, "path");
  if (out_scene == nullptr) return null_pointer(fn, "out_scene");
  return guard(fn, [&] { return add_scene(scene::load_scene_file(path), fn, out_scene); });
}

tandem_status tandem_scene_load_text(const char* text, size_t size, const char* name, tandem_scene_id* out_scene) {
  static const char* fn = "tandem_scene_load_text";
  if (text == nullptr && size != 0) return null_pointer(fn, "text");
  if (out_scene == nullptr) return null_pointer(fn, "out_scene");
  return guard(fn, [&] {
    return add_scene(scene::load_scene_text(std::string_view(text, size), name != nullptr ? name : "scene"), fn, out_scene);
  });
}

tandem_status tandem_scene_destroy(tandem_scene_id scene) {
  return guard("tandem_scene_destroy", [&] { return scenes().remove("tandem_scene_destroy", scene.index1, scene.generation); });
}

tandem_status tandem_scene_get_info(tandem_scene_id scene, tandem_scene_info* out_info) {
  static const char* fn = "tandem_scene_get_info";
  if (out_info == nullptr) return null_pointer(fn, "out_info");
  return guard(fn, [&] {
    TANDEM_C_GET_SCENE(s, fn, scene);
    tandem_scene_info i;
    std::memset(&i, 0, sizeof i);
    i.step_hz = s->scene.step_hz;
    i.time_step = s->scene.time_step.raw;
    i.ticks = s->scene.ticks;
    i.body_count = static_cast<int32_t>(s->scene.bodies.size());
    i.input_count = static_cast<int32_t>(s->scene.inputs.size());
    *out_info = i;
    return succeed();
  });
}

tandem_status tandem_scene_build(tandem_scene_id scene, tandem_world_id* out_world) {
  static const char* fn = "tandem_scene_build";
  if (out_world == nullptr) return null_pointer(fn, "out_world");
  return guard(fn, [&] {
    TANDEM_C_GET_SCENE(s, fn, scene);
    std::erase_if(s->builds, [](const scene::BuiltScene& b) { return !world_is_valid(b.world); });
    Result<scene::BuiltScene> built = scene::build_world(s->scene);
    if (!built.ok()) return status(built.status);
    *out_world = to_c(built.value.world);
    g_filters[built.value.world.index1] = FilterSlot{};
    s->builds.push_back(std::move(built.value));
    return succeed();
  });
}

tandem_status tandem_scene_body(tandem_scene_id scene, tandem_world_id world, int32_t index, tandem_body_id* out_body) {
  static const char* fn = "tandem_scene_body";
  if (out_body == nullptr) return null_pointer(fn, "out_body");
  return guard(fn, [&] {
    TANDEM_C_GET_SCENE(s, fn, scene);
    const scene::BuiltScene* b = find_build(s, world);
    if (b == nullptr) return not_built(fn, world);
    if (index < 0 || static_cast<size_t>(index) >= b->bodies.size()) {
      return fail(TANDEM_ERROR_INVALID_ARGUMENT, std::string(fn) + ": body index " + std::to_string(index) +
                                                     " is outside 0…" + std::to_string(b->bodies.size()) + " − 1");
    }
    *out_body = to_c(b->bodies[static_cast<size_t>(index)]);
    return succeed();
  });
}

tandem_status tandem_scene_apply_inputs(tandem_scene_id scene, tandem_world_id world, int64_t tick) {
  static const char* fn = "tandem_scene_apply_inputs";
  return guard(fn, [&] {
    TANDEM_C_GET_SCENE(s, fn, scene);
    const scene::BuiltScene* b = find_build(s, world);
    if (b == nullptr) return not_built(fn, world);
    return status(scene::apply_scene_inputs(*b, s->scene, tick));
  });
}
#else
namespace {
using tandem_c_internal::to_c;
using tandem_c_internal::to_cpp;
tandem_status no_scenes(const char* fn) {
  return fail(TANDEM_ERROR_UNSUPPORTED, std::string(fn) + ": this build has no scene loader (TANDEM_BUILD_TOOLS=OFF)");
}
}  // namespace
tandem_status tandem_scene_load_file(const char*, tandem_scene_id*) { return no_scenes("tandem_scene_load_file"); }
tandem_status tandem_scene_load_text(const char*, size_t, const char*, tandem_scene_id*) {
  return no_scenes("tandem_scene_load_text");
}
tandem_status tandem_scene_destroy(tandem_scene_id) { return no_scenes("tandem_scene_destroy"); }
tandem_status tandem_scene_get_info(tandem_scene_id, tandem_scene_info*) { return no_scenes("tandem_scene_get_info"); }
tandem_status tandem_scene_build(tandem_scene_id, tandem_world_id*) { return no_scenes("tandem_scene_build"); }
tandem_status tandem_scene_body(tandem_scene_id, tandem_world_id, int32_t, tandem_body_id*) {
  return no_scenes("tandem_scene_body");
}
tandem_status tandem_scene_apply_inputs(tandem_scene_id, tandem_world_id, int64_t) {
  return no_scenes("tandem_scene_apply_inputs");
}
#endif

// --- command lists (callback sinks) ----------------------------------------------------------------
tandem_status tandem_command_list_push(tandem_command_list* list, const tandem_command* command) {
  static const char* fn = "tandem_command_list_push";
  if (list == nullptr || list->out == nullptr) return null_pointer(fn, "list");
  return guard(fn, [&] {
    Command c;
    if (const tandem_status s = command_to_cpp(fn, command, &c); s != TANDEM_OK) return s;
    list->out->push_back(std::move(c));
    return succeed();
  });
}

// --- compact rollback snapshots (replay/rollback.h) ------------------------------
struct tandem_rollback_buffer {
  RollbackBuffer buffer;
};
static_assert(TANDEM_ROLLBACK_FORMAT_VERSION == k_rollback_format_version);

tandem_status tandem_rollback_buffer_create(tandem_rollback_buffer** out_buffer) {
  if (out_buffer == nullptr) return null_pointer("tandem_rollback_buffer_create", "out_buffer");
  return guard("tandem_rollback_buffer_create", [&] {
    *out_buffer = new tandem_rollback_buffer();
    return succeed();
  });
}
void tandem_rollback_buffer_free(tandem_rollback_buffer* buffer) { delete buffer; }
tandem_status tandem_rollback_buffer_copy(tandem_rollback_buffer* dst, const tandem_rollback_buffer* src) {
  if (dst == nullptr) return null_pointer("tandem_rollback_buffer_copy", "dst");
  if (src == nullptr) return null_pointer("tandem_rollback_buffer_copy", "src");
  return guard("tandem_rollback_buffer_copy", [&] {
    if (dst != src) dst->buffer = src->buffer;
    return succeed();
  });
}
tandem_status tandem_rollback_save(tandem_world_id world, tandem_rollback_buffer* buffer) {
  if (buffer == nullptr) return null_pointer("tandem_rollback_save", "buffer");
  return guard("tandem_rollback_save", [&] { return status(rollback_save(to_cpp(world), &buffer->buffer)); });
}
tandem_status tandem_rollback_restore(tandem_world_id world, const tandem_rollback_buffer* buffer) {
  if (buffer == nullptr) return null_pointer("tandem_rollback_restore", "buffer");
  return guard("tandem_rollback_restore", [&] { return status(rollback_restore(to_cpp(world), buffer->buffer)); });
}
uint64_t tandem_rollback_hash(const tandem_rollback_buffer* buffer) {
  return buffer == nullptr ? 0 : rollback_hash(buffer->buffer);
}
size_t tandem_rollback_image_size(const tandem_rollback_buffer* buffer) {
  return buffer == nullptr ? 0 : rollback_image_size(buffer->buffer);
}
