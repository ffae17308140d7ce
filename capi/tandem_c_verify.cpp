// tandem_c_verify.cpp — the C API of replay seeking, verify and diff with
// payload handlers, and decoded states (include/tandem_c_replay.h).
// (design and how to add a function: tandem_c_core.cpp's top comment).
#include "tandem_c_internal.h"

using namespace tandem_c_internal;

namespace {
using tandem_c_internal::to_c;
using tandem_c_internal::to_cpp;

// The C++ PayloadHandler calling a C one (unset for NULL).
PayloadHandler payload_handler(tandem_payload_fn fn, void* context) {
  if (fn == nullptr) return {};
  return [fn, context](int64_t tick, std::span<const uint8_t> payload, std::vector<Command>* out) {
    tandem_command_list list{out};
    const tandem_status s = fn(context, tick, payload.data(), payload.size(), &list);
    if (s == TANDEM_OK) return Status{};
    return Status{StatusCode::invalid_argument, "payload handler of tick " + std::to_string(tick) + " returned " +
                                                    tandem_status_name(s)};
  };
}

ProgressCallback progress_callback(tandem_progress_fn fn, void* context) {
  if (fn == nullptr) return {};
  return [fn, context](int64_t done, int64_t total) { fn(context, done, total); };
}

DiffOptions to_cpp(const tandem_diff_options* o) {
  DiffOptions d;
  if (o != nullptr) {
    d.payloads_a = payload_handler(o->payloads_a, o->context_a);
    d.payloads_b = payload_handler(o->payloads_b, o->context_b);
    d.progress = progress_callback(o->progress, o->progress_context);
  }
  return d;
}

tandem_status verify(const char* fn, tandem_replay_id replay, const VerifyOptions& options,
                     tandem_verify_report* out_report) {
  if (out_report == nullptr) return null_pointer(fn, "out_report");
  std::memset(out_report, 0, sizeof *out_report);
  return guard(fn, [&] {
    TANDEM_C_GET_REPLAY(r, fn, replay);
    const VerifyReport v = verify_replay(r->replay, options);
    tandem_verify_report o;
    std::memset(&o, 0, sizeof o);
    o.error = code_of(v.error.code);
    o.ok = v.ok();
    o.ticks_run = v.ticks_run;
    o.hashes_checked = v.hashes_checked;
    o.keyframes_checked = v.keyframes_checked;
    o.mismatch = v.mismatch;
    o.mismatch_tick = v.mismatch_tick;
    o.expected_hash = v.expected_hash;
    o.actual_hash = v.actual_hash;
    o.located = v.located;
    o.located_tick = v.located_tick;
    o.self_consistent = v.self_consistent;
    o.refused_commands = v.refused_commands;
    o.skipped_payloads = v.skipped_payloads;
    std::unique_ptr<char, decltype(&std::free)> diff(dup_text(v.located ? v.difference.describe() : std::string()),
                                                     &std::free);
    o.text = dup_text(format_verify_report(v));
    o.difference_text = diff.release();
    *out_report = o;
    return status(v.error);
  });
}

// Decoded states: library-owned, named by handles.
struct DecodedObject {
  DecodedState state;
};
Registry<DecodedObject>& decoded_states() {
  static Registry<DecodedObject> r("decoded state");
  return r;
}
#define TANDEM_C_GET_DECODED(var, fn, id)                                    \
  DecodedObject* var = decoded_states().get(fn, (id).index1, (id).generation); \
  if (var == nullptr) return t_code

tandem_status check_record(const char* fn, const DecodedState& s, int32_t record) {
  if (record < 0 || static_cast<size_t>(record) >= s.records.size()) {
    return fail(TANDEM_ERROR_INVALID_ARGUMENT, std::string(fn) + ": record " + std::to_string(record) +
                                                   " is outside 0…" + std::to_string(s.records.size()) + " − 1");
  }
  return TANDEM_OK;
}

}  // namespace

// --- replay positioning with payloads ----------------------------------------------------------
tandem_status tandem_replay_create_world_at_with(tandem_replay_id replay, int64_t tick, tandem_payload_fn payloads,
                                                 void* context, tandem_world_id* out_world) {
  static const char* fn = "tandem_replay_create_world_at";
  if (out_world == nullptr) return null_pointer(fn, "out_world");
  return guard(fn, [&] {
    TANDEM_C_GET_REPLAY(r, fn, replay);
    const Result<WorldId> w = r->replay.create_world_at(tick, payload_handler(payloads, context));
    if (w.ok()) {
      *out_world = to_c(w.value);
      g_filters[w.value.index1] = FilterSlot{};
    }
    return status(w.status);
  });
}
tandem_status tandem_replay_create_world_at(tandem_replay_id replay, int64_t tick, tandem_world_id* out_world) {
  return tandem_replay_create_world_at_with(replay, tick, nullptr, nullptr, out_world);
}

tandem_status tandem_replay_seek_with(tandem_replay_id replay, tandem_world_id world, int64_t tick,
                                      tandem_payload_fn payloads, void* context) {
  static const char* fn = "tandem_replay_seek";
  return guard(fn, [&] {
    TANDEM_C_GET_REPLAY(r, fn, replay);
    return status(r->replay.seek(to_cpp(world), tick, payload_handler(payloads, context)));
  });
}
tandem_status tandem_replay_seek(tandem_replay_id replay, tandem_world_id world, int64_t tick) {
  return tandem_replay_seek_with(replay, world, tick, nullptr, nullptr);
}

// --- verify --------------------------------------------------------------------------------------
tandem_verify_options tandem_default_verify_options(void) {
  const VerifyOptions v;
  tandem_verify_options o;
  std::memset(&o, 0, sizeof o);
  o.max_ticks = v.max_ticks;
  o.locate = v.locate;
  return o;
}

tandem_status tandem_verify_replay(tandem_replay_id replay, int64_t max_ticks, bool locate,
                                   tandem_verify_report* out_report) {
  VerifyOptions options;
  options.max_ticks = max_ticks;
  options.locate = locate;
  return verify("tandem_verify_replay", replay, options, out_report);
}

tandem_status tandem_verify_replay_with(tandem_replay_id replay, const tandem_verify_options* options,
                                        tandem_verify_report* out_report) {
  static const char* fn = "tandem_verify_replay_with";
  if (options == nullptr) return null_pointer(fn, "options");
  return guard(fn, [&] {
    VerifyOptions v;
    v.max_ticks = options->max_ticks;
    v.locate = options->locate;
    v.payloads = payload_handler(options->payloads, options->payload_context);
    v.progress = progress_callback(options->progress, options->progress_context);
    return verify(fn, replay, v, out_report);
  });
}

void tandem_free_verify_report(tandem_verify_report* report) {
  if (report == nullptr) return;
  std::free(report->difference_text);
  std::free(report->text);
  std::memset(report, 0, sizeof *report);
}

// --- diffs ---------------------------------------------------------------------------------------
tandem_status tandem_diff_replays_with(tandem_replay_id a, tandem_replay_id b, const tandem_diff_options* options,
                                       tandem_diff_report* out_report) {
  static const char* fn = "tandem_diff_replays";
  if (out_report == nullptr) return null_pointer(fn, "out_report");
  std::memset(out_report, 0, sizeof *out_report);
  return guard(fn, [&] {
    TANDEM_C_GET_REPLAY(ra, fn, a);
    TANDEM_C_GET_REPLAY(rb, fn, b);
    const DiffReport r = diff_replays(ra->replay, rb->replay, to_cpp(options));
    fill_diff_report(r, out_report);
    return status(r.error);
  });
}
tandem_status tandem_diff_replays(tandem_replay_id a, tandem_replay_id b, tandem_diff_report* out_report) {
  return tandem_diff_replays_with(a, b, nullptr, out_report);
}

tandem_status tandem_diff_replay_live(tandem_replay_id replay, tandem_world_id live, tandem_live_tick_fn advance,
                                      void* context, int64_t ticks, const tandem_diff_options* options,
                                      tandem_diff_report* out_report) {
  static const char* fn = "tandem_diff_replay_live";
  if (out_report == nullptr) return null_pointer(fn, "out_report");
  std::memset(out_report, 0, sizeof *out_report);
  if (advance == nullptr) return null_pointer(fn, "advance");
  return guard(fn, [&] {
    TANDEM_C_GET_REPLAY(r, fn, replay);
    const LiveTick tick = [advance, context](int64_t t) {
      const tandem_status s = advance(context, t);
      if (s == TANDEM_OK) return Status{};
      return Status{StatusCode::invalid_argument,
                    "live tick callback of tick " + std::to_string(t) + " returned " + tandem_status_name(s)};
    };
    const DiffReport d = diff_replay_live(r->replay, to_cpp(live), tick, ticks, to_cpp(options));
    fill_diff_report(d, out_report);
    return status(d.error);
  });
}

// --- decoded states ------------------------------------------------------------------------------
tandem_status tandem_decode_world_state(const uint8_t* bytes, size_t size, tandem_decoded_state_id* out_state) {
  static const char* fn = "tandem_decode_world_state";
  if (bytes == nullptr && size != 0) return null_pointer(fn, "bytes");
  if (out_state == nullptr) return null_pointer(fn, "out_state");
  return guard(fn, [&] {
    auto d = std::make_unique<DecodedObject>();
    const Status s = decode_world_state(bytes, size, &d->state);
    if (!s.ok()) return fail(TANDEM_ERROR_PARSE, std::string(fn) + ": " + s.message);
    const auto [index1, generation] = decoded_states().add(std::move(d));
    *out_state = tandem_decoded_state_id{index1, generation};
    return succeed();
  });
}

tandem_status tandem_decoded_state_destroy(tandem_decoded_state_id state) {
  static const char* fn = "tandem_decoded_state_destroy";
  return guard(fn, [&] { return decoded_states().remove(fn, state.index1, state.generation); });
}

tandem_status tandem_decoded_state_info(tandem_decoded_state_id state, uint32_t* out_version,
                                        int32_t* out_record_count) {
  static const char* fn = "tandem_decoded_state_info";
  return guard(fn, [&] {
    TANDEM_C_GET_DECODED(d, fn, state);
    if (out_version != nullptr) *out_version = d->state.version;
    if (out_record_count != nullptr) *out_record_count = static_cast<int32_t>(d->state.records.size());
    return succeed();
  });
}

tandem_status tandem_decoded_state_record(tandem_decoded_state_id state, int32_t record,
                                          tandem_decoded_record* out_record) {
  static const char* fn = "tandem_decoded_state_record";
  if (out_record == nullptr) return null_pointer(fn, "out_record");
  return guard(fn, [&] {
    TANDEM_C_GET_DECODED(d, fn, state);
    if (const tandem_status s = check_record(fn, d->state, record); s != TANDEM_OK) return s;
    const DecodedRecord& r = d->state.records[static_cast<size_t>(record)];
    *out_record = tandem_decoded_record{r.kind.c_str(), r.index, r.index2, r.generation,
                                        static_cast<int32_t>(r.fields.size())};
    return succeed();
  });
}

tandem_status tandem_decoded_state_field(tandem_decoded_state_id state, int32_t record, int32_t field,
                                         tandem_decoded_field* out_field) {
  static const char* fn = "tandem_decoded_state_field";
  if (out_field == nullptr) return null_pointer(fn, "out_field");
  return guard(fn, [&] {
    TANDEM_C_GET_DECODED(d, fn, state);
    if (const tandem_status s = check_record(fn, d->state, record); s != TANDEM_OK) return s;
    const DecodedRecord& r = d->state.records[static_cast<size_t>(record)];
    if (field < 0 || static_cast<size_t>(field) >= r.fields.size()) {
      return fail(TANDEM_ERROR_INVALID_ARGUMENT, std::string(fn) + ": field " + std::to_string(field) +
                                                     " is outside 0…" + std::to_string(r.fields.size()) +
                                                     " − 1 of record " + std::to_string(record));
    }
    const DecodedField& f = r.fields[static_cast<size_t>(field)];
    *out_field = tandem_decoded_field{f.name.c_str(), f.value, f.is_q32};
    return succeed();
  });
}

tandem_status tandem_diff_decoded_states(tandem_decoded_state_id a, tandem_decoded_state_id b,
                                         tandem_state_difference* out_difference) {
  static const char* fn = "tandem_diff_decoded_states";
  if (out_difference == nullptr) return null_pointer(fn, "out_difference");
  std::memset(out_difference, 0, sizeof *out_difference);
  return guard(fn, [&] {
    TANDEM_C_GET_DECODED(da, fn, a);
    TANDEM_C_GET_DECODED(db, fn, b);
    const StateDifference d = diff_world_states(da->state, db->state);
    using Text = std::unique_ptr<char, decltype(&std::free)>;
    Text kind(dup_text(d.kind), &std::free);
    Text field(dup_text(d.field), &std::free);
    Text text(dup_text(d.describe()), &std::free);
    tandem_state_difference& o = *out_difference;
    o.differs = d.differs;
    o.index = d.index;
    o.index2 = d.index2;
    o.generation = d.generation;
    o.value_a = d.value_a;
    o.value_b = d.value_b;
    o.is_q32 = d.is_q32;
    o.missing_in_a = d.missing_in_a;
    o.missing_in_b = d.missing_in_b;
    o.kind = kind.release();
    o.field = field.release();
    o.text = text.release();
    return succeed();
  });
}

void tandem_free_state_difference(tandem_state_difference* difference) {
  if (difference == nullptr) return;
  std::free(difference->kind);
  std::free(difference->field);
  std::free(difference->text);
  std::memset(difference, 0, sizeof *difference);
}

tandem_status tandem_locate_state_field(const uint8_t* bytes, size_t size, const char* kind, int64_t index,
                                        const char* field, size_t* out_offset) {
  static const char* fn = "tandem_locate_state_field";
  if (bytes == nullptr && size != 0) return null_pointer(fn, "bytes");
  if (kind == nullptr) return null_pointer(fn, "kind");
  if (field == nullptr) return null_pointer(fn, "field");
  if (out_offset == nullptr) return null_pointer(fn, "out_offset");
  return guard(fn, [&] {
    const Status s = locate_state_field(bytes, size, kind, index, field, out_offset);
    return s.ok() ? succeed() : fail(TANDEM_ERROR_PARSE, std::string(fn) + ": " + s.message);
  });
}
