// test_capi_verify.cpp — payload handlers, progress callbacks, replay vs live
// diffs and decoded states through the C API (tandem_c_replay.h).
//
// The recording: a game whose input is a one-byte payload per tick ("push
// body 1 left / right") applies the push itself (tandem_body_apply_linear_
// impulse_to_center, not a recorded command) and records only the payload.
// Re-running without a payload handler therefore cannot reproduce the
// hashes; with a C handler that turns the payload into the same impulse
// command it does.
#include "capi_test_util.h"

namespace {

constexpr int64_t k_ticks = 90;

uint8_t payload_of(int64_t tick) { return static_cast<uint8_t>(tick % 4); }  // 0, 1 left, 2 right, 3 up

tandem_vec2 push_of(uint8_t p) {
  if (p == 1) return v2(-1, 0);
  if (p == 2) return v2(1, 0);
  return v2(0, 2);
}

struct Recording {
  std::vector<uint8_t> bytes;
  tandem_body_id body{};
};

Recording record() {
  CWorld w;
  add_ground(w.id);
  Recording out;
  out.body = add_box(w.id, TANDEM_BODY_DYNAMIC, v2(0, 2), qt("0.5"));
  tandem_recorder_options options = tandem_default_recorder_options();
  options.keyframe_interval = 30;
  tandem_recorder_id rec{};
  REQUIRE(tandem_recorder_create_memory(&options, &rec) == TANDEM_OK);
  REQUIRE(tandem_recorder_begin(rec, w.id, nullptr, 0) == TANDEM_OK);
  for (int64_t tick = 1; tick <= k_ticks; ++tick) {
    const uint8_t p = payload_of(tick);
    if (p != 0) {
      REQUIRE(tandem_recorder_submit_payload(rec, &p, 1) == TANDEM_OK);
      REQUIRE(tandem_body_apply_linear_impulse_to_center(out.body, push_of(p), true) == TANDEM_OK);
    }
    REQUIRE(tandem_recorder_step(rec, nullptr) == TANDEM_OK);
  }
  REQUIRE(tandem_recorder_finish(rec) == TANDEM_OK);
  size_t size = 0;
  REQUIRE(tandem_recorder_memory(rec, nullptr, 0, &size) == TANDEM_OK);
  out.bytes.resize(size);
  REQUIRE(tandem_recorder_memory(rec, out.bytes.data(), size, &size) == TANDEM_OK);
  REQUIRE(tandem_recorder_destroy(rec) == TANDEM_OK);
  return out;
}

struct Handler {
  tandem_body_id body{};
  int calls = 0;
  bool fail = false;
};

tandem_status payload_handler(void* context, int64_t, const uint8_t* payload, size_t size, tandem_command_list* out) {
  auto* h = static_cast<Handler*>(context);
  ++h->calls;
  if (h->fail) return TANDEM_ERROR_INVALID_ARGUMENT;
  REQUIRE(size == 1);
  tandem_command c = tandem_default_command(TANDEM_COMMAND_APPLY_LINEAR_IMPULSE);
  c.body_index = h->body.index1 - 1;
  c.body_generation = h->body.generation;
  c.vector = push_of(payload[0]);
  return tandem_command_list_push(out, &c);
}

void progress(void* context, int64_t done, int64_t total) {
  auto* calls = static_cast<std::vector<std::pair<int64_t, int64_t>>*>(context);
  calls->emplace_back(done, total);
}

// The live run of diff_replay_live: the game's own loop (push, step), with
// an optional nudge after one tick.
struct Live {
  tandem_world_id world{};
  tandem_body_id body{};
  int64_t nudge_tick = 0;
};

tandem_status live_tick(void* context, int64_t tick) {
  auto* l = static_cast<Live*>(context);
  const uint8_t p = payload_of(tick);
  if (p != 0) REQUIRE(tandem_body_apply_linear_impulse_to_center(l->body, push_of(p), true) == TANDEM_OK);
  const tandem_status s = tandem_world_step(l->world, tandem_default_recorder_options().time_step, nullptr);
  if (tick == l->nudge_tick) {
    tandem_vec2 v = tandem_body_linear_velocity(l->body);
    v.x += 1;
    REQUIRE(tandem_body_set_linear_velocity(l->body, v) == TANDEM_OK);
  }
  return s;
}

}  // namespace

TEST_CASE("verify, seek and diffs with C payload handlers and progress callbacks", "[capi][verify]") {
  const Recording recording = record();
  CHECK(tandem_is_replay_image(recording.bytes.data(), recording.bytes.size()));
  CHECK_FALSE(tandem_is_replay_image(recording.bytes.data(), 3));
  CHECK_FALSE(tandem_is_replay_image(nullptr, 0));
  CHECK(std::string(tandem_command_type_name(TANDEM_COMMAND_SET_JOINT_LIMITS)) == "set_joint_limits");
  CHECK(std::string(tandem_command_type_name(TANDEM_COMMAND_APPLY_FORCE)) == "apply_force");
  CHECK(std::string(tandem_command_type_name(0)) == "unknown");
  CHECK(std::string(tandem_command_type_name(300)) == "unknown");
  tandem_replay_id r{};
  REQUIRE(tandem_replay_load_memory(recording.bytes.data(), recording.bytes.size(), &r) == TANDEM_OK);

  // Without a handler the payloads are skipped and the run differs.
  tandem_verify_report report{};
  REQUIRE(tandem_verify_replay(r, INT64_MAX, false, &report) == TANDEM_OK);
  CHECK(report.mismatch);
  CHECK(report.skipped_payloads > 0);
  tandem_free_verify_report(&report);

  // With the handler every hash matches; progress is reported.
  Handler handler{recording.body, 0, false};
  std::vector<std::pair<int64_t, int64_t>> calls;
  tandem_verify_options options = tandem_default_verify_options();
  CHECK(options.max_ticks == INT64_MAX);
  CHECK(options.locate);
  options.payloads = payload_handler;
  options.payload_context = &handler;
  options.progress = progress;
  options.progress_context = &calls;
  REQUIRE(tandem_verify_replay_with(r, &options, &report) == TANDEM_OK);
  INFO(report.text);
  CHECK(report.ok);
  CHECK(report.skipped_payloads == 0);
  CHECK(report.refused_commands == 0);
  CHECK(report.hashes_checked == k_ticks);
  CHECK(handler.calls > 0);
  REQUIRE_FALSE(calls.empty());
  CHECK(calls.back().first == calls.back().second);
  tandem_free_verify_report(&report);
  require_error(tandem_verify_replay_with(r, nullptr, &report), TANDEM_ERROR_NULL_POINTER, "options");
  require_error(tandem_verify_replay_with(r, &options, nullptr), TANDEM_ERROR_NULL_POINTER, "out_report");
  // A failing handler stops the run: the report says it could not run.
  handler.fail = true;
  CHECK(tandem_verify_replay_with(r, &options, &report) != TANDEM_OK);
  CHECK(std::string(report.text).find("payload handler") != std::string::npos);
  tandem_free_verify_report(&report);
  handler.fail = false;

  // Seek and create_world_at with the handler reproduce the recorded hash.
  uint64_t recorded = 0;
  REQUIRE(tandem_replay_tick_hash(r, 45, &recorded) == TANDEM_OK);
  tandem_world_id at{};
  REQUIRE(tandem_replay_create_world_at_with(r, 45, payload_handler, &handler, &at) == TANDEM_OK);
  CHECK(tandem_world_state_hash(at) == recorded);
  REQUIRE(tandem_replay_seek_with(r, at, 10, payload_handler, &handler) == TANDEM_OK);
  REQUIRE(tandem_replay_seek_with(r, at, 60, payload_handler, &handler) == TANDEM_OK);
  REQUIRE(tandem_replay_tick_hash(r, 60, &recorded) == TANDEM_OK);
  CHECK(tandem_world_state_hash(at) == recorded);
  // Without a handler, from the keyframe of tick 30 on the pushes are missing.
  REQUIRE(tandem_replay_tick_hash(r, 50, &recorded) == TANDEM_OK);
  REQUIRE(tandem_replay_seek_with(r, at, 50, nullptr, nullptr) == TANDEM_OK);
  CHECK(tandem_world_state_hash(at) != recorded);
  REQUIRE(tandem_replay_seek(r, at, 50) == TANDEM_OK);
  CHECK(tandem_world_state_hash(at) != recorded);
  require_error(tandem_replay_create_world_at_with(r, 45, nullptr, nullptr, nullptr), TANDEM_ERROR_NULL_POINTER,
                "out_world");
  REQUIRE(tandem_destroy_world(at) == TANDEM_OK);

  // Two replays with handlers on both sides: identical.
  tandem_diff_options diff_options;
  std::memset(&diff_options, 0, sizeof diff_options);
  diff_options.payloads_a = payload_handler;
  diff_options.context_a = &handler;
  diff_options.payloads_b = payload_handler;
  diff_options.context_b = &handler;
  diff_options.progress = progress;
  diff_options.progress_context = &calls;
  tandem_diff_report diff{};
  REQUIRE(tandem_diff_replays_with(r, r, &diff_options, &diff) == TANDEM_OK);
  CHECK_FALSE(diff.differs);
  CHECK(diff.ticks_a == k_ticks);
  CHECK(diff.ticks_b == k_ticks);
  CHECK_FALSE(diff.length_differs);
  CHECK_FALSE(diff.inputs_differ);
  tandem_free_diff_report(&diff);
  require_error(tandem_diff_replays_with(r, tandem_replay_id{}, nullptr, &diff), TANDEM_ERROR_NULL_HANDLE, "replay");

  // A replay against a live run: identical, then nudged after tick 50.
  for (const int64_t nudge : {int64_t{0}, int64_t{50}}) {
    Live live;
    REQUIRE(tandem_replay_create_world_at(r, 0, &live.world) == TANDEM_OK);
    live.body = recording.body;
    live.body.world = live.world;
    live.nudge_tick = nudge;
    REQUIRE(tandem_diff_replay_live(r, live.world, live_tick, &live, INT64_MAX, &diff_options, &diff) == TANDEM_OK);
    INFO(diff.text);
    CHECK(diff.differs == (nudge != 0));
    CHECK(diff.ticks_compared > 0);
    if (nudge != 0) {
      CHECK(diff.tick == nudge);
      CHECK(diff.located);
      CHECK(std::string(diff.difference_text).find("linear_velocity.x") != std::string::npos);
    }
    tandem_free_diff_report(&diff);
    REQUIRE(tandem_destroy_world(live.world) == TANDEM_OK);
  }
  require_error(tandem_diff_replay_live(r, tandem_world_id{}, nullptr, nullptr, 10, nullptr, &diff),
                TANDEM_ERROR_NULL_POINTER, "advance");
  require_error(tandem_diff_replay_live(r, tandem_world_id{}, live_tick, nullptr, 10, nullptr, nullptr),
                TANDEM_ERROR_NULL_POINTER, "out_report");
  REQUIRE(tandem_replay_destroy(r) == TANDEM_OK);
  require_error(tandem_diff_replay_live(r, tandem_world_id{}, live_tick, nullptr, 10, nullptr, &diff),
                TANDEM_ERROR_INVALID_HANDLE, "replay");
}

TEST_CASE("decoded states: records, fields, diffs and field offsets", "[capi][verify]") {
  CWorld w;
  add_ground(w.id);
  const tandem_body_id body = add_box(w.id, TANDEM_BODY_DYNAMIC, v2(0, 3), qt("0.5"));
  const std::vector<uint8_t> a = snapshot(w.id);
  REQUIRE(tandem_world_step(w.id, qt("0.0166666667"), nullptr) == TANDEM_OK);
  const std::vector<uint8_t> b = snapshot(w.id);

  tandem_decoded_state_id da{}, db{};
  REQUIRE(tandem_decode_world_state(a.data(), a.size(), &da) == TANDEM_OK);
  REQUIRE(tandem_decode_world_state(b.data(), b.size(), &db) == TANDEM_OK);
  uint32_t version = 0;
  int32_t records = 0;
  REQUIRE(tandem_decoded_state_info(da, &version, &records) == TANDEM_OK);
  CHECK(version >= 1);
  REQUIRE(records > 2);
  // Find body 1's record and its position.y field; compare with the getter.
  bool found = false;
  for (int32_t i = 0; i < records && !found; ++i) {
    tandem_decoded_record rec{};
    REQUIRE(tandem_decoded_state_record(da, i, &rec) == TANDEM_OK);
    if (std::string(rec.kind) != "body" || rec.index != body.index1 - 1) continue;
    CHECK(rec.generation == body.generation);
    for (int32_t f = 0; f < rec.field_count; ++f) {
      tandem_decoded_field field{};
      REQUIRE(tandem_decoded_state_field(da, i, f, &field) == TANDEM_OK);
      if (std::string(field.name) == "position.y") {
        CHECK(field.is_q32);
        CHECK(field.value == qi(3));
        found = true;
      }
    }
    tandem_decoded_field field{};
    require_error(tandem_decoded_state_field(da, i, rec.field_count, &field), TANDEM_ERROR_INVALID_ARGUMENT,
                  "field " + std::to_string(rec.field_count));
  }
  CHECK(found);
  tandem_decoded_record rec{};
  require_error(tandem_decoded_state_record(da, records, &rec), TANDEM_ERROR_INVALID_ARGUMENT, "record");
  require_error(tandem_decoded_state_record(da, -1, &rec), TANDEM_ERROR_INVALID_ARGUMENT, "record -1");
  require_error(tandem_decoded_state_record(da, 0, nullptr), TANDEM_ERROR_NULL_POINTER, "out_record");
  tandem_decoded_field field{};
  require_error(tandem_decoded_state_field(da, -1, 0, &field), TANDEM_ERROR_INVALID_ARGUMENT, "record");
  require_error(tandem_decoded_state_field(da, 0, 0, nullptr), TANDEM_ERROR_NULL_POINTER, "out_field");

  // Diffs: a against b differs in the body; a against itself is identical.
  tandem_state_difference d{};
  REQUIRE(tandem_diff_decoded_states(da, db, &d) == TANDEM_OK);
  CHECK(d.differs);
  CHECK(std::string(d.text).find(d.kind) != std::string::npos);
  CHECK(std::string(d.field).size() > 0);
  tandem_free_state_difference(&d);
  CHECK(d.text == nullptr);
  tandem_free_state_difference(nullptr);
  REQUIRE(tandem_diff_decoded_states(da, da, &d) == TANDEM_OK);
  CHECK_FALSE(d.differs);
  CHECK(std::string(d.text) == "identical");
  tandem_free_state_difference(&d);
  require_error(tandem_diff_decoded_states(da, db, nullptr), TANDEM_ERROR_NULL_POINTER, "out_difference");

  // Field offsets: the raw bytes at the offset are the body's position.y (little-endian).
  size_t offset = 0;
  REQUIRE(tandem_locate_state_field(a.data(), a.size(), "body", body.index1 - 1, "position.y", &offset) == TANDEM_OK);
  REQUIRE(offset + 8 <= a.size());
  uint64_t raw = 0;
  for (int i = 0; i < 8; ++i) raw |= uint64_t{a[offset + static_cast<size_t>(i)]} << (8 * i);
  CHECK(static_cast<tandem_q32>(raw) == qi(3));
  require_error(tandem_locate_state_field(a.data(), a.size(), "body", body.index1 - 1, "no_such_field", &offset),
                TANDEM_ERROR_PARSE, "no_such_field");
  require_error(tandem_locate_state_field(a.data(), a.size(), nullptr, 0, "x", &offset), TANDEM_ERROR_NULL_POINTER,
                "kind");
  require_error(tandem_locate_state_field(a.data(), a.size(), "body", 0, nullptr, &offset), TANDEM_ERROR_NULL_POINTER,
                "field");
  require_error(tandem_locate_state_field(a.data(), a.size(), "body", 0, "x", nullptr), TANDEM_ERROR_NULL_POINTER,
                "out_offset");

  // Malformed images, NULL pointers, stale handles.
  tandem_decoded_state_id bad{};
  require_error(tandem_decode_world_state(a.data(), 10, &bad), TANDEM_ERROR_PARSE, "offset");
  require_error(tandem_decode_world_state(nullptr, 10, &bad), TANDEM_ERROR_NULL_POINTER, "bytes");
  require_error(tandem_decode_world_state(a.data(), a.size(), nullptr), TANDEM_ERROR_NULL_POINTER, "out_state");
  REQUIRE(tandem_decoded_state_destroy(da) == TANDEM_OK);
  require_error(tandem_decoded_state_destroy(da), TANDEM_ERROR_INVALID_HANDLE, "decoded state");
  require_error(tandem_decoded_state_info(da, &version, &records), TANDEM_ERROR_INVALID_HANDLE, "decoded state");
  require_error(tandem_decoded_state_record(tandem_decoded_state_id{}, 0, &rec), TANDEM_ERROR_NULL_HANDLE, "");
  require_error(tandem_decoded_state_field(da, 0, 0, &field), TANDEM_ERROR_INVALID_HANDLE, "");
  require_error(tandem_diff_decoded_states(da, db, &d), TANDEM_ERROR_INVALID_HANDLE, "");
  REQUIRE(tandem_decoded_state_destroy(db) == TANDEM_OK);
}
