// tandem_c_session.cpp — the C API of the session (include/tandem_c_session.h).
// (design and how to add a function: tandem_c_core.cpp's top comment).
//
// Sessions live in a registry like recorders and replays. Each SessionObject
// keeps a copy of the C callbacks; the C++ std::function callbacks are thin
// adapters that convert the arguments and call them with the user context.
// A make_commands status other than TANDEM_OK becomes a C++ Status naming the
// callback (the session then stops with state error, as in C++).
#include "replay/session.h"
#include "tandem_c_internal.h"

using namespace tandem_c_internal;

// The config's field list (global namespace: found by def_to_c / def_to_cpp).
template <bool D>
void map(SessionConfig& a, tandem_session_config& b) {
  f<D>(a.mode, b.mode), f<D>(a.player_count, b.player_count), f<D>(a.spectator_count, b.spectator_count);
  f<D>(a.local_endpoint, b.local_endpoint), f<D>(a.input_bytes, b.input_bytes), f<D>(a.input_delay, b.input_delay);
  f<D>(a.prediction_window, b.prediction_window), f<D>(a.session_id, b.session_id);
  f<D>(a.time_step, b.time_step), f<D>(a.history_ticks, b.history_ticks);
  f<D>(a.disconnect_timeout_frames, b.disconnect_timeout_frames), f<D>(a.record_replay, b.record_replay);
  f<D>(a.keyframe_interval, b.keyframe_interval);
}

namespace {
using tandem_c_internal::to_c;
using tandem_c_internal::to_cpp;

struct SessionObject {
  Session session;
  tandem_session_callbacks callbacks{};
};

Registry<SessionObject>& sessions() {
  static Registry<SessionObject> r("session");
  return r;
}

#define TANDEM_C_GET_SESSION(var, fn, id)                              \
  SessionObject* var = sessions().get(fn, (id).index1, (id).generation); \
  if (var == nullptr) return t_code

tandem_session_config to_c(const SessionConfig& c) { return def_to_c<tandem_session_config>(c); }
SessionConfig to_cpp(const tandem_session_config& c) { return def_to_cpp<SessionConfig>(c); }

// The C++ callbacks calling the C ones (cb is the SessionObject's copy).
SessionCallbacks adapt(const tandem_session_callbacks* cb) {
  SessionCallbacks o;
  o.send = [cb](uint32_t endpoint, std::span<const uint8_t> packet) {
    cb->send(cb->context, endpoint, packet.data(), packet.size());
  };
  o.make_commands = [cb](int64_t tick, const SessionTickInputs& in, WorldId world, std::vector<Command>* out) {
    tandem_command_list list{out};
    const tandem_status s = cb->make_commands(cb->context, tick, in.data, in.player_count, in.input_bytes,
                                              tandem_c_internal::to_c(world), &list);
    if (s == TANDEM_OK) return Status{};
    return Status{StatusCode::invalid_argument, "make_commands callback of tick " + std::to_string(tick) +
                                                    " returned " + tandem_status_name(s)};
  };
  if (cb->after_step != nullptr) {
    o.after_step = [cb](int64_t tick, WorldId world) {
      cb->after_step(cb->context, tick, tandem_c_internal::to_c(world));
    };
  }
  if (cb->save_game != nullptr) {
    o.save_game = [cb](std::vector<uint8_t>* out) {
      tandem_bytes bytes{out};
      cb->save_game(cb->context, &bytes);
    };
  }
  if (cb->load_game != nullptr) {
    o.load_game = [cb](std::span<const uint8_t> state) { cb->load_game(cb->context, state.data(), state.size()); };
  }
  return o;
}

// A getter on a live session (fallback for a bad handle, last error untouched).
template <typename T, typename F>
T session_value(tandem_session_id id, T fallback, F&& get) {
  return guard_value(fallback, [&] {
    const tandem_status code = t_code;
    const std::string message = t_message;
    SessionObject* s = sessions().get("session getter", id.index1, id.generation);
    t_code = code;  // value getters leave the last error alone
    t_message = message;
    return s == nullptr ? fallback : get(s->session);
  });
}

// A text of a live session (text rule).
template <typename Get>
tandem_status session_text(const char* fn, tandem_session_id session, char* out, size_t capacity, size_t* out_length,
                           Get&& get) {
  return guard(fn, [&] {
    TANDEM_C_GET_SESSION(s, fn, session);
    return copy_text(fn, get(s->session), out, capacity, out_length);
  });
}

tandem_status advance_result(AdvanceResult r, int32_t* out) {
  *out = static_cast<int32_t>(r);
  return succeed();
}

}  // namespace

tandem_status tandem_bytes_assign(tandem_bytes* out, const uint8_t* data, size_t size) {
  static const char* fn = "tandem_bytes_assign";
  if (out == nullptr || out->out == nullptr) return null_pointer(fn, "out");
  if (data == nullptr && size != 0) return null_pointer(fn, "data");
  return guard(fn, [&] {
    out->out->assign(data, data + size);
    return succeed();
  });
}

tandem_session_config tandem_default_session_config(void) { return to_c(SessionConfig{}); }

const char* tandem_session_state_name(int32_t state) {
  if (state < TANDEM_SESSION_IDLE || state > TANDEM_SESSION_ERROR) return "unknown";
  return session_state_name(static_cast<SessionState>(state));
}

uint64_t tandem_session_state_hash(tandem_world_id world, const uint8_t* game_state, size_t size) {
  if (game_state == nullptr) size = 0;
  return guard_value(uint64_t{0}, [&] { return session_state_hash(to_cpp(world), {game_state, size}); });
}

tandem_status tandem_session_create(tandem_world_id world, const tandem_session_config* config,
                                    const tandem_session_callbacks* callbacks, tandem_session_id* out_session) {
  static const char* fn = "tandem_session_create";
  if (config == nullptr) return null_pointer(fn, "config");
  if (callbacks == nullptr) return null_pointer(fn, "callbacks");
  if (callbacks->send == nullptr) return null_pointer(fn, "callbacks.send");
  if (callbacks->make_commands == nullptr) return null_pointer(fn, "callbacks.make_commands");
  if (out_session == nullptr) return null_pointer(fn, "out_session");
  if (config->mode != TANDEM_SESSION_LOCKSTEP && config->mode != TANDEM_SESSION_ROLLBACK) {
    return fail(TANDEM_ERROR_INVALID_ARGUMENT,
                std::string(fn) + ": config.mode " + std::to_string(config->mode) + " is not 0 or 1 (TANDEM_SESSION_*)");
  }
  return guard(fn, [&] {
    auto object = std::make_unique<SessionObject>();
    object->callbacks = *callbacks;
    const Status s = object->session.start(to_cpp(world), to_cpp(*config), adapt(&object->callbacks));
    if (!s.ok()) return status(s);
    const auto [index1, generation] = sessions().add(std::move(object));
    *out_session = tandem_session_id{index1, generation};
    return succeed();
  });
}

tandem_status tandem_session_destroy(tandem_session_id session) {
  static const char* fn = "tandem_session_destroy";
  return guard(fn, [&] { return sessions().remove(fn, session.index1, session.generation); });
}

tandem_status tandem_session_advance_frame(tandem_session_id session, const uint8_t* local_input, size_t size,
                                           int32_t* out_result) {
  static const char* fn = "tandem_session_advance_frame";
  if (out_result == nullptr) return null_pointer(fn, "out_result");
  if (local_input == nullptr && size != 0) return null_pointer(fn, "local_input");
  return guard(fn, [&] {
    TANDEM_C_GET_SESSION(s, fn, session);
    if (!s->session.is_spectator() && size != s->session.config().input_bytes) {
      return fail(TANDEM_ERROR_INVALID_ARGUMENT, std::string(fn) + ": the input has " + std::to_string(size) +
                                                     " bytes, config.input_bytes is " +
                                                     std::to_string(s->session.config().input_bytes));
    }
    return advance_result(s->session.advance_frame({local_input, size}), out_result);
  });
}

tandem_status tandem_session_idle_frame(tandem_session_id session, int32_t* out_result) {
  static const char* fn = "tandem_session_idle_frame";
  if (out_result == nullptr) return null_pointer(fn, "out_result");
  return guard(fn, [&] {
    TANDEM_C_GET_SESSION(s, fn, session);
    return advance_result(s->session.idle_frame(), out_result);
  });
}

tandem_status tandem_session_receive(tandem_session_id session, uint32_t from_endpoint, const uint8_t* packet,
                                     size_t size) {
  static const char* fn = "tandem_session_receive";
  if (packet == nullptr && size != 0) return null_pointer(fn, "packet");
  return guard(fn, [&] {
    TANDEM_C_GET_SESSION(s, fn, session);
    s->session.receive(from_endpoint, {packet, size});
    return succeed();
  });
}

tandem_status tandem_session_peer_disconnected(tandem_session_id session, uint32_t endpoint) {
  static const char* fn = "tandem_session_peer_disconnected";
  return guard(fn, [&] {
    TANDEM_C_GET_SESSION(s, fn, session);
    s->session.peer_disconnected(endpoint);
    return succeed();
  });
}

int32_t tandem_session_frames_ahead(tandem_session_id session) {
  return session_value(session, int32_t{0}, [](const Session& s) { return s.frames_ahead(); });
}
int64_t tandem_session_current_tick(tandem_session_id session) {
  return session_value(session, int64_t{0}, [](const Session& s) { return s.current_tick(); });
}
int64_t tandem_session_confirmed_tick(tandem_session_id session) {
  return session_value(session, int64_t{0}, [](const Session& s) { return s.confirmed_tick(); });
}
int64_t tandem_session_remote_confirmed_through(tandem_session_id session) {
  return session_value(session, int64_t{0}, [](const Session& s) { return s.remote_confirmed_through(); });
}
uint64_t tandem_session_start_hash(tandem_session_id session) {
  return session_value(session, uint64_t{0}, [](const Session& s) { return s.start_hash(); });
}
uint64_t tandem_session_confirmed_hash(tandem_session_id session, int64_t tick) {
  return session_value(session, uint64_t{0}, [tick](const Session& s) { return s.confirmed_hash(tick); });
}
int32_t tandem_session_state(tandem_session_id session) {
  return session_value(session, int32_t{TANDEM_SESSION_IDLE},
                       [](const Session& s) { return static_cast<int32_t>(s.state()); });
}
bool tandem_session_is_spectator(tandem_session_id session) {
  return session_value(session, false, [](const Session& s) { return s.is_spectator(); });
}

tandem_status tandem_session_get_config(tandem_session_id session, tandem_session_config* out_config) {
  static const char* fn = "tandem_session_get_config";
  if (out_config == nullptr) return null_pointer(fn, "out_config");
  return guard(fn, [&] {
    TANDEM_C_GET_SESSION(s, fn, session);
    *out_config = to_c(s->session.config());
    return succeed();
  });
}

tandem_status tandem_session_get_stop(tandem_session_id session, tandem_session_stop* out_stop) {
  static const char* fn = "tandem_session_get_stop";
  if (out_stop == nullptr) return null_pointer(fn, "out_stop");
  return guard(fn, [&] {
    TANDEM_C_GET_SESSION(s, fn, session);
    const SessionStop& st = s->session.stop_info();
    std::memset(out_stop, 0, sizeof *out_stop);
    out_stop->state = static_cast<int32_t>(st.state);
    out_stop->tick = st.tick;
    out_stop->endpoint = st.endpoint;
    out_stop->local_hash = st.local_hash;
    out_stop->remote_hash = st.remote_hash;
    out_stop->last_heard_tick = st.last_heard_tick;
    return succeed();
  });
}

tandem_status tandem_session_stop_message(tandem_session_id session, char* out_text, size_t capacity,
                                          size_t* out_length) {
  return session_text("tandem_session_stop_message", session, out_text, capacity, out_length,
                      [](const Session& s) -> const std::string& { return s.stop_info().message; });
}

tandem_status tandem_session_get_stats(tandem_session_id session, tandem_session_stats* out_stats) {
  static const char* fn = "tandem_session_get_stats";
  if (out_stats == nullptr) return null_pointer(fn, "out_stats");
  return guard(fn, [&] {
    TANDEM_C_GET_SESSION(s, fn, session);
    const SessionStats& st = s->session.stats();
    *out_stats = tandem_session_stats{st.frames,           st.stalls,           st.rollbacks,
                                      st.max_rollback_depth, st.resimulated_ticks, st.ticks_simulated,
                                      st.packets_sent,     st.bytes_sent,       st.packets_received,
                                      st.bytes_received,   st.packets_rejected, st.packets_stale,
                                      st.commands_refused, st.hashes_compared,  st.hashes_skipped};
    return succeed();
  });
}

tandem_status tandem_session_last_rejection(tandem_session_id session, char* out_text, size_t capacity,
                                            size_t* out_length) {
  return session_text("tandem_session_last_rejection", session, out_text, capacity, out_length,
                      [](const Session& s) -> const std::string& { return s.stats().last_rejection; });
}

tandem_status tandem_session_replay_bytes(tandem_session_id session, uint8_t* out_bytes, size_t capacity,
                                          size_t* out_size) {
  static const char* fn = "tandem_session_replay_bytes";
  return guard(fn, [&] {
    TANDEM_C_GET_SESSION(s, fn, session);
    const std::vector<uint8_t> bytes = s->session.replay_bytes();
    return fill(fn, std::span<const uint8_t>(bytes), out_bytes, capacity, out_size, same<uint8_t>);
  });
}

tandem_status tandem_session_state_image(tandem_session_id session, int64_t tick, uint8_t* out_bytes,
                                         size_t capacity, size_t* out_size) {
  static const char* fn = "tandem_session_state_image";
  return guard(fn, [&] {
    TANDEM_C_GET_SESSION(s, fn, session);
    std::vector<uint8_t> image;
    if (const Status st = s->session.state_image(tick, &image); !st.ok()) return status(st);
    return fill(fn, std::span<const uint8_t>(image), out_bytes, capacity, out_size, same<uint8_t>);
  });
}

tandem_status tandem_session_write_artifacts(tandem_session_id session, const char* prefix) {
  static const char* fn = "tandem_session_write_artifacts";
  if (prefix == nullptr) return null_pointer(fn, "prefix");
  return guard(fn, [&] {
    TANDEM_C_GET_SESSION(s, fn, session);
    const Status st = s->session.write_artifacts(prefix);
    return st.ok() ? succeed() : fail(TANDEM_ERROR_IO, std::string(fn) + ": " + st.message);
  });
}

tandem_status tandem_session_request_body_hashes(tandem_session_id session, uint32_t endpoint, int64_t tick,
                                                 uint32_t first_body, uint32_t count) {
  static const char* fn = "tandem_session_request_body_hashes";
  return guard(fn, [&] {
    TANDEM_C_GET_SESSION(s, fn, session);
    return status(s->session.request_body_hashes(endpoint, tick, first_body, count));
  });
}

tandem_status tandem_session_remote_body_hashes(tandem_session_id session, uint32_t* out_endpoint,
                                                int64_t* out_tick, uint32_t* out_first_body, uint64_t* out_hashes,
                                                int32_t capacity, int32_t* out_count) {
  static const char* fn = "tandem_session_remote_body_hashes";
  return guard(fn, [&] {
    TANDEM_C_GET_SESSION(s, fn, session);
    const Session::BodyHashes& h = s->session.remote_body_hashes();
    if (out_endpoint != nullptr) *out_endpoint = h.endpoint;
    if (out_tick != nullptr) *out_tick = h.tick;
    if (out_first_body != nullptr) *out_first_body = h.first_body;
    return fill(fn, std::span<const uint64_t>(h.hashes), out_hashes, capacity, out_count, same<uint64_t>);
  });
}

tandem_status tandem_session_local_body_hashes(tandem_session_id session, int64_t tick, uint64_t* out_hashes,
                                               int32_t capacity, int32_t* out_count) {
  static const char* fn = "tandem_session_local_body_hashes";
  return guard(fn, [&] {
    TANDEM_C_GET_SESSION(s, fn, session);
    std::vector<uint64_t> hashes;
    if (const Status st = s->session.local_body_hashes(tick, &hashes); !st.ok()) return status(st);
    return fill(fn, std::span<const uint64_t>(hashes), out_hashes, capacity, out_count, same<uint64_t>);
  });
}
