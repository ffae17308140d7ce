// test_capi_replay.cpp — the C API of snapshots, hashes, commands, recorders,
// replays, the sync test and scenes (see test_capi.cpp).
#include "capi_test_util.h"

TEST_CASE("snapshots, restore, hashes and snapshot diffs", "[capi]") {
  CWorld w;
  add_ground(w.id);
  const tandem_body_id box = add_box(w.id, TANDEM_BODY_DYNAMIC, v2(0, 3), qt("0.5"));
  const std::vector<uint8_t> start = snapshot(w.id);
  const uint64_t start_hash = tandem_world_state_hash(w.id);
  std::vector<uint64_t> trail;
  for (int i = 0; i < 30; ++i) {
    REQUIRE(tandem_world_step(w.id, qt("0.0166"), nullptr) == TANDEM_OK);
    trail.push_back(tandem_world_state_hash(w.id));
  }
  const std::vector<uint8_t> end = snapshot(w.id);

  size_t size = 0;
  std::vector<uint8_t> small(10);
  require_error(tandem_world_snapshot(w.id, small.data(), small.size(), &size), TANDEM_ERROR_BUFFER_TOO_SMALL,
                "needs " + std::to_string(end.size()));
  CHECK(size == end.size());
  require_error(tandem_world_snapshot(w.id, small.data(), small.size(), nullptr), TANDEM_ERROR_NULL_POINTER, "out_size");
  require_error(tandem_world_snapshot(w.id, nullptr, 5, &size), TANDEM_ERROR_NULL_POINTER, "out_bytes");

  // Restore and re-run: the same hashes.
  REQUIRE(tandem_world_restore(w.id, start.data(), start.size()) == TANDEM_OK);
  CHECK(tandem_world_state_hash(w.id) == start_hash);
  for (uint64_t expected : trail) {
    REQUIRE(tandem_world_step(w.id, qt("0.0166"), nullptr) == TANDEM_OK);
    REQUIRE(tandem_world_state_hash(w.id) == expected);
  }
  // A corrupt image is refused and leaves the world unchanged.
  std::vector<uint8_t> corrupt = end;
  corrupt[0] = 'X';
  require_error(tandem_world_restore(w.id, corrupt.data(), corrupt.size()), TANDEM_ERROR_INVALID_ARGUMENT, "offset");
  require_error(tandem_world_restore(w.id, end.data(), end.size() - 3), TANDEM_ERROR_INVALID_ARGUMENT, "");
  require_error(tandem_world_restore(w.id, nullptr, 4), TANDEM_ERROR_NULL_POINTER, "bytes");
  CHECK(tandem_world_state_hash(w.id) == trail.back());

  tandem_world_id copy{};
  REQUIRE(tandem_create_world_from_snapshot(end.data(), end.size(), &copy) == TANDEM_OK);
  CHECK(tandem_world_state_hash(copy) == trail.back());
  require_error(tandem_create_world_from_snapshot(corrupt.data(), corrupt.size(), &copy), TANDEM_ERROR_INVALID_ARGUMENT,
                "");
  require_error(tandem_create_world_from_snapshot(end.data(), end.size(), nullptr), TANDEM_ERROR_NULL_POINTER,
                "out_world");

  // Body hashes.
  const uint64_t bh = tandem_body_state_hash(box);
  CHECK(bh != 0);
  int32_t count = 0;
  REQUIRE(tandem_world_body_hashes(w.id, nullptr, 0, &count) == TANDEM_OK);
  CHECK(count == 2);
  uint64_t hashes[2];
  REQUIRE(tandem_world_body_hashes(w.id, hashes, 2, &count) == TANDEM_OK);
  CHECK(hashes[1] == bh);
  uint64_t one[1];
  require_error(tandem_world_body_hashes(w.id, one, 1, &count), TANDEM_ERROR_BUFFER_TOO_SMALL, "result has 2");

  // Deltas: end as a delta against start, rebuilt exactly.
  size_t delta_size = 0;
  REQUIRE(tandem_encode_state_delta(start.data(), start.size(), end.data(), end.size(), nullptr, 0, &delta_size) ==
          TANDEM_OK);
  CHECK(delta_size < end.size());
  std::vector<uint8_t> delta(delta_size);
  REQUIRE(tandem_encode_state_delta(start.data(), start.size(), end.data(), end.size(), delta.data(), delta.size(),
                                    &delta_size) == TANDEM_OK);
  require_error(tandem_encode_state_delta(start.data(), start.size(), end.data(), end.size(), delta.data(), 2, &delta_size),
                TANDEM_ERROR_BUFFER_TOO_SMALL, "");
  std::vector<uint8_t> rebuilt(end.size());
  size_t rebuilt_size = 0;
  REQUIRE(tandem_apply_state_delta(start.data(), start.size(), delta.data(), delta.size(), rebuilt.data(), rebuilt.size(),
                                   &rebuilt_size) == TANDEM_OK);
  CHECK(rebuilt == end);
  require_error(tandem_apply_state_delta(end.data(), end.size(), delta.data(), delta.size(), rebuilt.data(),
                                         rebuilt.size(), &rebuilt_size),
                TANDEM_ERROR_PARSE, "");  // another base
  require_error(tandem_apply_state_delta(start.data(), start.size(), delta.data(), delta.size(), rebuilt.data(), 3,
                                         &rebuilt_size),
                TANDEM_ERROR_BUFFER_TOO_SMALL, "");
  require_error(tandem_apply_state_delta(start.data(), start.size(), nullptr, 4, rebuilt.data(), rebuilt.size(),
                                         &rebuilt_size),
                TANDEM_ERROR_NULL_POINTER, "");
  require_error(tandem_encode_state_delta(nullptr, 4, end.data(), end.size(), nullptr, 0, &delta_size),
                TANDEM_ERROR_NULL_POINTER, "");

  // Diffs.
  tandem_diff_report report;
  REQUIRE(tandem_diff_snapshots(start.data(), start.size(), end.data(), end.size(), &report) == TANDEM_OK);
  CHECK(report.differs);
  CHECK(report.located);
  INFO(report.difference_text);
  CHECK(std::string(report.difference_text).find(" a = ") != std::string::npos);
  CHECK(std::string(report.text).size() > 10);
  tandem_free_diff_report(&report);
  CHECK(report.text == nullptr);
  tandem_free_diff_report(&report);  // twice: harmless
  tandem_free_diff_report(nullptr);
  REQUIRE(tandem_diff_snapshots(end.data(), end.size(), end.data(), end.size(), &report) == TANDEM_OK);
  CHECK(!report.differs);
  tandem_free_diff_report(&report);
  CHECK(tandem_diff_snapshots(corrupt.data(), corrupt.size(), end.data(), end.size(), &report) != TANDEM_OK);
  CHECK(report.error != TANDEM_OK);
  tandem_free_diff_report(&report);
  require_error(tandem_diff_snapshots(nullptr, 3, end.data(), end.size(), &report), TANDEM_ERROR_NULL_POINTER, "");
  require_error(tandem_diff_snapshots(end.data(), end.size(), end.data(), end.size(), nullptr),
                TANDEM_ERROR_NULL_POINTER, "out_report");
  REQUIRE(tandem_destroy_world(copy) == TANDEM_OK);
}

TEST_CASE("commands, recorders, replays: record, verify, diff", "[capi]") {
  CWorld w;
  add_ground(w.id);
  tandem_recorder_id rec{};
  const tandem_recorder_options options = tandem_default_recorder_options();
  REQUIRE(tandem_recorder_create_memory(&options, &rec) == TANDEM_OK);
  require_error(tandem_recorder_create_memory(&options, nullptr), TANDEM_ERROR_NULL_POINTER, "out_recorder");
  const char scene[] = "{}";
  REQUIRE(tandem_recorder_begin(rec, w.id, reinterpret_cast<const uint8_t*>(scene), 2) == TANDEM_OK);

  // create_body with a box and a chain, through the recorder.
  tandem_shape_spec shapes[2] = {tandem_default_shape_spec(TANDEM_SHAPE_KIND_POLYGON),
                                 tandem_default_shape_spec(TANDEM_SHAPE_KIND_CHAIN)};
  REQUIRE(tandem_make_box(qt("0.5"), qt("0.5"), &shapes[0].polygon) == TANDEM_OK);
  const tandem_vec2 chain[] = {v2(-3, 1), v2(-2, 0), v2(2, 0), v2(3, 1)};
  shapes[1].chain_points = chain;
  shapes[1].chain_point_count = 4;
  tandem_command create = tandem_default_command(TANDEM_COMMAND_CREATE_BODY);
  create.body_def.type = TANDEM_BODY_DYNAMIC;
  create.body_def.position = v2(0, 3);
  create.shapes = shapes;
  create.shape_count = 2;
  REQUIRE(tandem_recorder_submit(rec, &create) == TANDEM_OK);
  uint32_t flags = 1;
  REQUIRE(tandem_recorder_step(rec, &flags) == TANDEM_OK);
  CHECK(tandem_recorder_tick_count(rec) == 1);
  CHECK(tandem_recorder_last_hash(rec) == tandem_world_state_hash(w.id));
  tandem_command push = tandem_default_command(TANDEM_COMMAND_APPLY_LINEAR_IMPULSE);
  push.body_index = 1;
  push.body_generation = 1;
  push.vector = v2(1, 0);
  REQUIRE(tandem_recorder_submit(rec, &push) == TANDEM_OK);
  const uint8_t payload[] = {1, 2, 3};
  REQUIRE(tandem_recorder_submit_payload(rec, payload, 3) == TANDEM_OK);
  require_error(tandem_recorder_submit_payload(rec, nullptr, 3), TANDEM_ERROR_NULL_POINTER, "payload");
  for (int i = 0; i < 20; ++i) REQUIRE(tandem_recorder_step(rec, nullptr) == TANDEM_OK);
  tandem_command bad = tandem_default_command(99);
  require_error(tandem_recorder_submit(rec, &bad), TANDEM_ERROR_INVALID_ARGUMENT, "command type 99");
  require_error(tandem_recorder_submit(rec, nullptr), TANDEM_ERROR_NULL_POINTER, "command");
  REQUIRE(tandem_recorder_finish(rec) == TANDEM_OK);
  size_t size = 0;
  REQUIRE(tandem_recorder_memory(rec, nullptr, 0, &size) == TANDEM_OK);
  std::vector<uint8_t> bytes(size);
  uint8_t tiny[4];
  require_error(tandem_recorder_memory(rec, tiny, 4, &size), TANDEM_ERROR_BUFFER_TOO_SMALL, "");
  REQUIRE(tandem_recorder_memory(rec, bytes.data(), bytes.size(), &size) == TANDEM_OK);
  REQUIRE(tandem_recorder_destroy(rec) == TANDEM_OK);
  require_error(tandem_recorder_destroy(rec), TANDEM_ERROR_INVALID_HANDLE, "recorder");
  require_error(tandem_recorder_step(rec, nullptr), TANDEM_ERROR_INVALID_HANDLE, "recorder");
  require_error(tandem_recorder_step(tandem_recorder_id{}, nullptr), TANDEM_ERROR_NULL_HANDLE, "null recorder");
  CHECK(tandem_recorder_tick_count(rec) == 0);
  CHECK(tandem_recorder_last_hash(rec) == 0);

  // Load, inspect, verify.
  tandem_replay_id replay{};
  REQUIRE(tandem_replay_load_memory(bytes.data(), bytes.size(), &replay) == TANDEM_OK);
  CHECK(tandem_replay_tick_count(replay) == 21);
  uint64_t h = 0;
  REQUIRE(tandem_replay_tick_hash(replay, 21, &h) == TANDEM_OK);
  CHECK(h == tandem_world_state_hash(w.id));
  require_error(tandem_replay_tick_hash(replay, 22, &h), TANDEM_ERROR_INVALID_ARGUMENT, "outside 1");
  require_error(tandem_replay_tick_hash(replay, 1, nullptr), TANDEM_ERROR_NULL_POINTER, "out_hash");
  tandem_world_id at10{};
  REQUIRE(tandem_replay_create_world_at(replay, 10, &at10) == TANDEM_OK);
  REQUIRE(tandem_replay_tick_hash(replay, 10, &h) == TANDEM_OK);
  CHECK(tandem_world_state_hash(at10) == h);
  // Seek an existing world back to tick 4, then forward to tick 10.
  REQUIRE(tandem_replay_seek(replay, at10, 4) == TANDEM_OK);
  REQUIRE(tandem_replay_tick_hash(replay, 4, &h) == TANDEM_OK);
  CHECK(tandem_world_state_hash(at10) == h);
  require_error(tandem_replay_seek(replay, at10, 99), TANDEM_ERROR_INVALID_ARGUMENT, "");
  REQUIRE(tandem_destroy_world(at10) == TANDEM_OK);
  require_error(tandem_replay_seek(replay, at10, 4), TANDEM_ERROR_INVALID_HANDLE, "world");
  require_error(tandem_replay_seek(tandem_replay_id{}, at10, 4), TANDEM_ERROR_NULL_HANDLE, "null replay");
  tandem_verify_report vr;
  REQUIRE(tandem_verify_replay(replay, INT64_MAX, true, &vr) == TANDEM_OK);
  CHECK(vr.ok);
  CHECK(vr.hashes_checked == 21);
  CHECK(std::string(vr.text).find("21") != std::string::npos);
  tandem_free_verify_report(&vr);
  tandem_free_verify_report(nullptr);

  // A tampered replay: verify names the tick; diff finds where the runs part.
  std::vector<uint8_t> other_bytes;
  {
    CWorld w2;
    add_ground(w2.id);
    tandem_recorder_id r2{};
    REQUIRE(tandem_recorder_create_memory(nullptr, &r2) == TANDEM_OK);
    REQUIRE(tandem_recorder_begin(r2, w2.id, nullptr, 0) == TANDEM_OK);
    REQUIRE(tandem_recorder_submit(r2, &create) == TANDEM_OK);
    for (int i = 0; i < 5; ++i) REQUIRE(tandem_recorder_step(r2, nullptr) == TANDEM_OK);
    push.vector = v2(2, 0);  // different input from tick 6 on
    REQUIRE(tandem_recorder_submit(r2, &push) == TANDEM_OK);
    for (int i = 0; i < 16; ++i) REQUIRE(tandem_recorder_step(r2, nullptr) == TANDEM_OK);
    REQUIRE(tandem_recorder_finish(r2) == TANDEM_OK);
    REQUIRE(tandem_recorder_memory(r2, nullptr, 0, &size) == TANDEM_OK);
    other_bytes.resize(size);
    REQUIRE(tandem_recorder_memory(r2, other_bytes.data(), size, &size) == TANDEM_OK);
    REQUIRE(tandem_recorder_destroy(r2) == TANDEM_OK);
  }
  tandem_replay_id other{};
  REQUIRE(tandem_replay_load_memory(other_bytes.data(), other_bytes.size(), &other) == TANDEM_OK);
  tandem_diff_report dr;
  REQUIRE(tandem_diff_replays(replay, other, &dr) == TANDEM_OK);
  CHECK(dr.differs);
  CHECK(dr.tick == 2);  // first input difference: tick 2 in one, tick 6 in the other
  tandem_free_diff_report(&dr);
  require_error(tandem_diff_replays(replay, tandem_replay_id{}, &dr), TANDEM_ERROR_NULL_HANDLE, "null replay");

  std::vector<uint8_t> broken = bytes;
  broken.resize(broken.size() / 2);
  broken[5] ^= 0xFF;
  tandem_replay_id nope{};
  require_error(tandem_replay_load_memory(broken.data(), broken.size(), &nope), TANDEM_ERROR_PARSE, "offset");
  require_error(tandem_replay_load_memory(bytes.data(), bytes.size(), nullptr), TANDEM_ERROR_NULL_POINTER, "out_replay");

  REQUIRE(tandem_replay_destroy(other) == TANDEM_OK);
  REQUIRE(tandem_replay_destroy(replay) == TANDEM_OK);
  require_error(tandem_replay_destroy(replay), TANDEM_ERROR_INVALID_HANDLE, "replay");
  CHECK(tandem_replay_tick_count(replay) == 0);
  require_error(tandem_verify_replay(replay, INT64_MAX, true, &vr), TANDEM_ERROR_INVALID_HANDLE, "replay");
  require_error(tandem_replay_create_world_at(replay, 1, &at10), TANDEM_ERROR_INVALID_HANDLE, "replay");

  // Files: record to a file, load it back.
  const std::string path = "capi_test_replay.tndr";
  tandem_recorder_id fr{};
  REQUIRE(tandem_recorder_create_file(path.c_str(), nullptr, &fr) == TANDEM_OK);
  REQUIRE(tandem_recorder_begin(fr, w.id, nullptr, 0) == TANDEM_OK);
  REQUIRE(tandem_recorder_step(fr, nullptr) == TANDEM_OK);
  REQUIRE(tandem_recorder_finish(fr) == TANDEM_OK);
  REQUIRE(tandem_recorder_destroy(fr) == TANDEM_OK);
  REQUIRE(tandem_replay_load_file(path.c_str(), &replay) == TANDEM_OK);
  CHECK(tandem_replay_tick_count(replay) == 1);
  REQUIRE(tandem_replay_destroy(replay) == TANDEM_OK);
  std::remove(path.c_str());
  require_error(tandem_replay_load_file("/nonexistent/x.tndr", &replay), TANDEM_ERROR_IO, "/nonexistent/x.tndr");
  require_error(tandem_recorder_create_file("/nonexistent/dir/x.tndr", nullptr, &fr), TANDEM_ERROR_IO, "/nonexistent");
  require_error(tandem_replay_load_file(nullptr, &replay), TANDEM_ERROR_NULL_POINTER, "path");

  // apply_command without a recorder.
  tandem_body_id created{};
  REQUIRE(tandem_apply_command(w.id, &create, &created) == TANDEM_OK);
  CHECK(tandem_body_is_valid(created));
  CHECK(tandem_body_shape_count(created) == 2);  // the box and the chain's one segment (4 points, open)
  tandem_command gravity = tandem_default_command(TANDEM_COMMAND_SET_GRAVITY);
  gravity.vector = v2(0, -3);
  REQUIRE(tandem_apply_command(w.id, &gravity, nullptr) == TANDEM_OK);
  CHECK(tandem_world_gravity(w.id).y == qi(-3));
  tandem_command destroy = tandem_default_command(TANDEM_COMMAND_DESTROY_BODY);
  destroy.body_index = 99;
  destroy.body_generation = 1;
  require_error(tandem_apply_command(w.id, &destroy, nullptr), TANDEM_ERROR_INVALID_HANDLE, "destroy_body");
  create.shape_count = 1;
  create.shapes = nullptr;
  require_error(tandem_apply_command(w.id, &create, nullptr), TANDEM_ERROR_NULL_POINTER, "shapes");
}

namespace {
struct SyncInputs {
  tandem_body_id body;
  int calls = 0;
};
void sync_inputs(tandem_world_id, int64_t tick, void* context) {
  auto* in = static_cast<SyncInputs*>(context);
  ++in->calls;
  if (tick % 10 == 0) tandem_body_apply_linear_impulse_to_center(in->body, v2(0, 1), true);
}
}  // namespace

TEST_CASE("the sync test through C", "[capi]") {
  CWorld w;
  add_ground(w.id);
  SyncInputs inputs{add_box(w.id, TANDEM_BODY_DYNAMIC, v2(0, 2), qt("0.5"))};
  tandem_synctest_options options = tandem_default_synctest_options();
  options.ticks = 40;
  options.rollback = 4;
  tandem_synctest_report report;
  REQUIRE(tandem_run_synctest(w.id, &options, &sync_inputs, &inputs, &report) == TANDEM_OK);
  CHECK(report.passed);
  CHECK(report.ticks_run == 40);
  CHECK(report.resimulated_ticks > 40);
  CHECK(inputs.calls > 40);
  CHECK(std::string(report.message).find("passed") != std::string::npos);
  tandem_free_synctest_report(&report);
  tandem_free_synctest_report(nullptr);
  options.rollback = 0;
  require_error(tandem_run_synctest(w.id, &options, nullptr, nullptr, &report), TANDEM_ERROR_INVALID_ARGUMENT, "rollback");
  tandem_free_synctest_report(&report);
  require_error(tandem_run_synctest(w.id, nullptr, nullptr, nullptr, &report), TANDEM_ERROR_NULL_POINTER, "options");
  require_error(tandem_run_synctest(w.id, &options, nullptr, nullptr, nullptr), TANDEM_ERROR_NULL_POINTER, "out_report");
}

TEST_CASE("scenes: load, build, inputs, errors", "[capi]") {
  tandem_scene_id scene{};
  const std::string path = std::string(TANDEM_SOURCE_DIR) + "/scenes/impulses.json";
  REQUIRE(tandem_scene_load_file(path.c_str(), &scene) == TANDEM_OK);
  tandem_scene_info info;
  REQUIRE(tandem_scene_get_info(scene, &info) == TANDEM_OK);
  CHECK(info.step_hz == 60);
  CHECK(info.ticks == 300);
  CHECK(info.input_count == 9);
  tandem_world_id world{};
  REQUIRE(tandem_scene_build(scene, &world) == TANDEM_OK);
  tandem_body_id first{};
  REQUIRE(tandem_scene_body(scene, world, 0, &first) == TANDEM_OK);
  CHECK(tandem_body_is_valid(first));
  require_error(tandem_scene_body(scene, world, info.body_count, &first), TANDEM_ERROR_INVALID_ARGUMENT, "body index");
  for (int64_t tick = 0; tick < 20; ++tick) {
    REQUIRE(tandem_scene_apply_inputs(scene, world, tick) == TANDEM_OK);
    REQUIRE(tandem_world_step(world, info.time_step, nullptr) == TANDEM_OK);
  }
  CWorld stranger;
  require_error(tandem_scene_apply_inputs(scene, stranger.id, 0), TANDEM_ERROR_INVALID_ARGUMENT, "not built");
  require_error(tandem_scene_body(scene, stranger.id, 0, &first), TANDEM_ERROR_INVALID_ARGUMENT, "not built");
  REQUIRE(tandem_destroy_world(world) == TANDEM_OK);
  REQUIRE(tandem_scene_destroy(scene) == TANDEM_OK);
  require_error(tandem_scene_destroy(scene), TANDEM_ERROR_INVALID_HANDLE, "scene");
  require_error(tandem_scene_get_info(scene, &info), TANDEM_ERROR_INVALID_HANDLE, "scene");
  require_error(tandem_scene_build(scene, &world), TANDEM_ERROR_INVALID_HANDLE, "scene");
  require_error(tandem_scene_get_info(tandem_scene_id{}, &info), TANDEM_ERROR_NULL_HANDLE, "null scene");

  const char text[] = R"({"bodies": [{"type": "dynamic", "positon": [0, 1]}]})";
  require_error(tandem_scene_load_text(text, sizeof text - 1, "bad.json", &scene), TANDEM_ERROR_PARSE, "bad.json");
  const char good[] = R"({"bodies": [{"type": "dynamic", "position": [0, 1], "shapes": [{"type": "circle", "radius": 0.5}]}]})";
  REQUIRE(tandem_scene_load_text(good, sizeof good - 1, nullptr, &scene) == TANDEM_OK);
  REQUIRE(tandem_scene_destroy(scene) == TANDEM_OK);
  require_error(tandem_scene_load_file("/nonexistent.json", &scene), TANDEM_ERROR_PARSE, "/nonexistent.json");
  require_error(tandem_scene_load_file(nullptr, &scene), TANDEM_ERROR_NULL_POINTER, "path");
  require_error(tandem_scene_load_text(good, sizeof good - 1, nullptr, nullptr), TANDEM_ERROR_NULL_POINTER, "out_scene");
}

// --- the C layer adds no arithmetic: C and C++ give the same hash every tick ---
