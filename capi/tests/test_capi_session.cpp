// test_capi_session.cpp — the session through the C API (tandem_c_session.h):
// two rollback peers, each a world and a C session, over an in-process
// loopback built from the C send callback (packets delivered two frames
// later, so inputs are predicted and rolled back); the game is C callbacks
// (make_commands pushing impulse commands, after_step counting, save/load of
// that count). Checked: both peers confirm the same hashes, which equal a
// plain C++ reference run of the same inputs; the recorded replay verifies;
// a perturbed peer desyncs with a report, state images and per-body hashes;
// every function's error paths.
#include "capi_test_util.h"

#include <deque>
#include <filesystem>

#include "replay/commands.h"
#include "replay/replay_file.h"
#include "replay/session.h"

namespace {

constexpr uint32_t k_players = 2;

struct Packet {
  uint64_t due;
  uint32_t from, to;
  std::vector<uint8_t> bytes;
};

struct Loopback;

// One peer's game: its world, bodies, a counter (the game state beyond the world).
struct Game {
  Loopback* net = nullptr;
  uint32_t endpoint = 0;
  tandem_world_id world{};
  tandem_body_id players[k_players]{};
  uint64_t score = 0;
  int64_t perturb_tick = 0;  // nudge a body after this tick (desync test)
};

struct Loopback {
  uint64_t frame = 0;
  std::deque<Packet> queue;
};

void send(void* context, uint32_t endpoint, const uint8_t* packet, size_t size) {
  auto* g = static_cast<Game*>(context);
  g->net->queue.push_back(Packet{g->net->frame + 2, g->endpoint, endpoint, std::vector<uint8_t>(packet, packet + size)});
}

// Input byte 0 of player p: 0 nothing, 1 push left, 2 push right.
tandem_status make_commands(void* context, int64_t, const uint8_t* inputs, uint32_t player_count,
                            uint32_t input_bytes, tandem_world_id, tandem_command_list* out) {
  auto* g = static_cast<Game*>(context);
  for (uint32_t p = 0; p < player_count; ++p) {
    const uint8_t in = inputs[p * input_bytes];
    if (in == 0) continue;
    tandem_command c = tandem_default_command(TANDEM_COMMAND_APPLY_LINEAR_IMPULSE);
    c.body_index = g->players[p].index1 - 1;
    c.body_generation = g->players[p].generation;
    c.vector = {in == 1 ? qi(-2) : qi(2), qi(1)};
    const tandem_status s = tandem_command_list_push(out, &c);
    if (s != TANDEM_OK) return s;
  }
  return TANDEM_OK;
}

void after_step(void* context, int64_t tick, tandem_world_id world) {
  auto* g = static_cast<Game*>(context);
  g->score += static_cast<uint64_t>(tick % 3);
  if (g->perturb_tick != 0 && tick == g->perturb_tick) {
    tandem_vec2 p = tandem_body_position(g->players[0]);
    p.x += 1;
    REQUIRE(tandem_body_set_transform(g->players[0], p, tandem_body_rotation(g->players[0])) == TANDEM_OK);
  }
  (void)world;
}

void save_game(void* context, tandem_bytes* out) {
  const auto* g = static_cast<const Game*>(context);
  uint8_t bytes[8];
  for (int i = 0; i < 8; ++i) bytes[i] = static_cast<uint8_t>(g->score >> (8 * i));
  REQUIRE(tandem_bytes_assign(out, bytes, 8) == TANDEM_OK);
}

void load_game(void* context, const uint8_t* state, size_t size) {
  auto* g = static_cast<Game*>(context);
  REQUIRE(size == 8);
  g->score = 0;
  for (int i = 0; i < 8; ++i) g->score |= uint64_t{state[i]} << (8 * i);
}

uint8_t input_of(uint32_t player, uint64_t frame) { return static_cast<uint8_t>((frame / 5 + player) % 3); }

void build(Game* g) {
  const tandem_world_def def = tandem_default_world_def();
  REQUIRE(tandem_create_world(&def, &g->world) == TANDEM_OK);
  add_ground(g->world);
  for (uint32_t p = 0; p < k_players; ++p)
    g->players[p] = add_box(g->world, TANDEM_BODY_DYNAMIC, v2(static_cast<int32_t>(p) * 3 - 1, 2), qt("0.5"));
}

tandem_session_callbacks callbacks(Game* g) {
  tandem_session_callbacks cb;
  std::memset(&cb, 0, sizeof cb);
  cb.context = g;
  cb.send = send;
  cb.make_commands = make_commands;
  cb.after_step = after_step;
  cb.save_game = save_game;
  cb.load_game = load_game;
  return cb;
}

struct Peers {
  Loopback net;
  Game games[k_players];
  tandem_session_id sessions[k_players]{};
  explicit Peers(const tandem_session_config& base) {
    for (uint32_t e = 0; e < k_players; ++e) {
      games[e].net = &net;
      games[e].endpoint = e;
      build(&games[e]);
      tandem_session_config config = base;
      config.local_endpoint = e;
      const tandem_session_callbacks cb = callbacks(&games[e]);
      INFO(last_message());
      REQUIRE(tandem_session_create(games[e].world, &config, &cb, &sessions[e]) == TANDEM_OK);
    }
  }
  ~Peers() {
    for (uint32_t e = 0; e < k_players; ++e) {
      (void)tandem_session_destroy(sessions[e]);
      (void)tandem_destroy_world(games[e].world);
    }
  }
  void frame() {
    for (uint32_t e = 0; e < k_players; ++e) {
      for (size_t i = 0; i < net.queue.size();) {
        if (net.queue[i].to == e && net.queue[i].due <= net.frame) {
          const Packet p = net.queue[i];
          net.queue.erase(net.queue.begin() + static_cast<std::ptrdiff_t>(i));
          REQUIRE(tandem_session_receive(sessions[e], p.from, p.bytes.data(), p.bytes.size()) == TANDEM_OK);
        } else {
          ++i;
        }
      }
      uint8_t input[4] = {input_of(e, net.frame), 0, 0, 0};
      int32_t result = -1;
      REQUIRE(tandem_session_advance_frame(sessions[e], input, sizeof input, &result) == TANDEM_OK);
      CHECK((result == TANDEM_ADVANCE_STEPPED || result == TANDEM_ADVANCE_STALLED || result == TANDEM_ADVANCE_STOPPED));
    }
    ++net.frame;
  }
};

tandem_session_config config_for_test() {
  tandem_session_config c = tandem_default_session_config();
  c.mode = TANDEM_SESSION_ROLLBACK;
  c.player_count = k_players;
  c.session_id = 42;
  c.record_replay = true;
  c.keyframe_interval = 30;
  c.input_delay = 0;  // remote inputs are always late: predictions and rollbacks
  return c;
}

}  // namespace

TEST_CASE("session: defaults, errors, null and stale handles", "[capi][session]") {
  const tandem_session_config d = tandem_default_session_config();
  CHECK(d.mode == TANDEM_SESSION_ROLLBACK);
  CHECK(d.player_count == 2);
  CHECK(d.input_bytes == 4);
  CHECK(d.time_step == tandem::Q32::from_ratio(1, 60).raw);
  CHECK(std::string(tandem_session_state_name(TANDEM_SESSION_DESYNCED)) == "desynced");
  CHECK(std::string(tandem_session_state_name(TANDEM_SESSION_PEER_LEFT)) == "peer left");
  CHECK(std::string(tandem_session_state_name(99)) == "unknown");

  Loopback net;
  Game g;
  g.net = &net;
  build(&g);
  tandem_session_callbacks cb = callbacks(&g);
  tandem_session_config c = config_for_test();
  tandem_session_id s{};
  require_error(tandem_session_create(g.world, nullptr, &cb, &s), TANDEM_ERROR_NULL_POINTER, "config");
  require_error(tandem_session_create(g.world, &c, nullptr, &s), TANDEM_ERROR_NULL_POINTER, "callbacks");
  require_error(tandem_session_create(g.world, &c, &cb, nullptr), TANDEM_ERROR_NULL_POINTER, "out_session");
  cb.send = nullptr;
  require_error(tandem_session_create(g.world, &c, &cb, &s), TANDEM_ERROR_NULL_POINTER, "callbacks.send");
  cb = callbacks(&g);
  cb.make_commands = nullptr;
  require_error(tandem_session_create(g.world, &c, &cb, &s), TANDEM_ERROR_NULL_POINTER, "make_commands");
  cb = callbacks(&g);
  c.mode = 7;
  require_error(tandem_session_create(g.world, &c, &cb, &s), TANDEM_ERROR_INVALID_ARGUMENT, "config.mode");
  c = config_for_test();
  c.player_count = 9;
  require_error(tandem_session_create(g.world, &c, &cb, &s), TANDEM_ERROR_INVALID_ARGUMENT, "player_count");
  c = config_for_test();
  require_error(tandem_session_create(tandem_world_id{}, &c, &cb, &s), TANDEM_ERROR_INVALID_ARGUMENT, "null world");

  REQUIRE(tandem_session_create(g.world, &c, &cb, &s) == TANDEM_OK);
  tandem_session_config back{};
  REQUIRE(tandem_session_get_config(s, &back) == TANDEM_OK);
  CHECK(back.session_id == 42);
  CHECK(back.keyframe_interval == 30);
  CHECK(back.record_replay);
  CHECK_FALSE(tandem_session_is_spectator(s));
  CHECK(tandem_session_state(s) == TANDEM_SESSION_RUNNING);
  CHECK(tandem_session_start_hash(s) == tandem_world_state_hash(g.world));
  int32_t result = 0;
  uint8_t input[4] = {};
  require_error(tandem_session_advance_frame(s, input, 3, &result), TANDEM_ERROR_INVALID_ARGUMENT, "input_bytes is 4");
  require_error(tandem_session_advance_frame(s, nullptr, 4, &result), TANDEM_ERROR_NULL_POINTER, "local_input");
  require_error(tandem_session_advance_frame(s, input, 4, nullptr), TANDEM_ERROR_NULL_POINTER, "out_result");
  require_error(tandem_session_idle_frame(s, nullptr), TANDEM_ERROR_NULL_POINTER, "out_result");
  require_error(tandem_session_receive(s, 1, nullptr, 5), TANDEM_ERROR_NULL_POINTER, "packet");
  // A malformed packet is counted, not an error.
  const uint8_t junk[3] = {1, 2, 3};
  REQUIRE(tandem_session_receive(s, 1, junk, sizeof junk) == TANDEM_OK);
  tandem_session_stats stats{};
  REQUIRE(tandem_session_get_stats(s, &stats) == TANDEM_OK);
  CHECK(stats.packets_rejected == 1);
  size_t length = 0;
  REQUIRE(tandem_session_last_rejection(s, nullptr, 0, &length) == TANDEM_OK);
  CHECK(length > 0);
  REQUIRE(tandem_session_idle_frame(s, &result) == TANDEM_OK);
  CHECK(result == TANDEM_ADVANCE_STALLED);
  require_error(tandem_session_state_image(s, 999, nullptr, 0, &length), TANDEM_ERROR_INVALID_ARGUMENT, "");
  require_error(tandem_session_write_artifacts(s, nullptr), TANDEM_ERROR_NULL_POINTER, "prefix");
  require_error(tandem_session_get_stop(s, nullptr), TANDEM_ERROR_NULL_POINTER, "out_stop");
  require_error(tandem_session_get_stats(s, nullptr), TANDEM_ERROR_NULL_POINTER, "out_stats");
  require_error(tandem_session_get_config(s, nullptr), TANDEM_ERROR_NULL_POINTER, "out_config");

  // The transport lost the other player: the session stops.
  REQUIRE(tandem_session_peer_disconnected(s, 1) == TANDEM_OK);
  CHECK(tandem_session_state(s) == TANDEM_SESSION_PEER_LEFT);
  tandem_session_stop stop{};
  REQUIRE(tandem_session_get_stop(s, &stop) == TANDEM_OK);
  CHECK(stop.state == TANDEM_SESSION_PEER_LEFT);
  CHECK(stop.endpoint == 1);
  REQUIRE(tandem_session_stop_message(s, nullptr, 0, &length) == TANDEM_OK);
  CHECK(length > 0);
  REQUIRE(tandem_session_advance_frame(s, input, 4, &result) == TANDEM_OK);
  CHECK(result == TANDEM_ADVANCE_STOPPED);

  // Stale and null handles: statuses say so, getters give defaults.
  REQUIRE(tandem_session_destroy(s) == TANDEM_OK);
  require_error(tandem_session_destroy(s), TANDEM_ERROR_INVALID_HANDLE, "session");
  require_error(tandem_session_advance_frame(s, input, 4, &result), TANDEM_ERROR_INVALID_HANDLE, "session");
  require_error(tandem_session_idle_frame(tandem_session_id{}, &result), TANDEM_ERROR_NULL_HANDLE, "session");
  require_error(tandem_session_receive(s, 1, junk, 3), TANDEM_ERROR_INVALID_HANDLE, "");
  require_error(tandem_session_peer_disconnected(s, 1), TANDEM_ERROR_INVALID_HANDLE, "");
  require_error(tandem_session_get_config(s, &back), TANDEM_ERROR_INVALID_HANDLE, "");
  require_error(tandem_session_get_stop(s, &stop), TANDEM_ERROR_INVALID_HANDLE, "");
  require_error(tandem_session_get_stats(s, &stats), TANDEM_ERROR_INVALID_HANDLE, "");
  require_error(tandem_session_stop_message(s, nullptr, 0, &length), TANDEM_ERROR_INVALID_HANDLE, "");
  require_error(tandem_session_last_rejection(s, nullptr, 0, &length), TANDEM_ERROR_INVALID_HANDLE, "");
  require_error(tandem_session_replay_bytes(s, nullptr, 0, &length), TANDEM_ERROR_INVALID_HANDLE, "");
  require_error(tandem_session_state_image(s, 0, nullptr, 0, &length), TANDEM_ERROR_INVALID_HANDLE, "");
  require_error(tandem_session_write_artifacts(s, "x"), TANDEM_ERROR_INVALID_HANDLE, "");
  require_error(tandem_session_request_body_hashes(s, 1, 0, 0, 1), TANDEM_ERROR_INVALID_HANDLE, "");
  int32_t n = 0;
  require_error(tandem_session_remote_body_hashes(s, nullptr, nullptr, nullptr, nullptr, 0, &n),
                TANDEM_ERROR_INVALID_HANDLE, "");
  require_error(tandem_session_local_body_hashes(s, 0, nullptr, 0, &n), TANDEM_ERROR_INVALID_HANDLE, "");
  tandem_last_error_code();
  const tandem_status before = tandem_last_error_code();
  CHECK(tandem_session_current_tick(s) == 0);
  CHECK(tandem_session_confirmed_tick(s) == 0);
  CHECK(tandem_session_remote_confirmed_through(s) == 0);
  CHECK(tandem_session_start_hash(s) == 0);
  CHECK(tandem_session_confirmed_hash(s, 1) == 0);
  CHECK(tandem_session_frames_ahead(s) == 0);
  CHECK(tandem_session_state(s) == TANDEM_SESSION_IDLE);
  CHECK_FALSE(tandem_session_is_spectator(s));
  CHECK(tandem_last_error_code() == before);  // value getters leave the last error alone
  require_error(tandem_bytes_assign(nullptr, junk, 3), TANDEM_ERROR_NULL_POINTER, "out");
  require_error(tandem_command_list_push(nullptr, nullptr), TANDEM_ERROR_NULL_POINTER, "list");
  CHECK(tandem_session_state_hash(g.world, nullptr, 0) == tandem_world_state_hash(g.world));
  REQUIRE(tandem_destroy_world(g.world) == TANDEM_OK);
}

TEST_CASE("session: two C peers over a loopback confirm the C++ reference hashes", "[capi][session][determinism]") {
  Peers peers(config_for_test());
  const int64_t target = 120;
  for (int f = 0; f < 1000 && (tandem_session_confirmed_tick(peers.sessions[0]) < target ||
                               tandem_session_confirmed_tick(peers.sessions[1]) < target);
       ++f) {
    peers.frame();
    (void)tandem_session_frames_ahead(peers.sessions[0]);
  }
  REQUIRE(tandem_session_state(peers.sessions[0]) == TANDEM_SESSION_RUNNING);
  REQUIRE(tandem_session_state(peers.sessions[1]) == TANDEM_SESSION_RUNNING);
  REQUIRE(tandem_session_confirmed_tick(peers.sessions[0]) >= target);
  CHECK(tandem_session_remote_confirmed_through(peers.sessions[0]) > 0);
  CHECK(tandem_session_current_tick(peers.sessions[0]) >= tandem_session_confirmed_tick(peers.sessions[0]));
  tandem_session_stats stats{};
  REQUIRE(tandem_session_get_stats(peers.sessions[0], &stats) == TANDEM_OK);
  CHECK(stats.rollbacks > 0);  // inputs arrive two frames late and change every 5 frames
  CHECK(stats.hashes_compared > 0);
  CHECK(stats.packets_sent > 0);

  // The C++ reference: the same inputs (the replay's user_input commands
  // hold them) applied to a fresh world with the C++ API; hashes mixed with
  // the game state as the session does.
  size_t size = 0;
  REQUIRE(tandem_session_replay_bytes(peers.sessions[0], nullptr, 0, &size) == TANDEM_OK);
  std::vector<uint8_t> replay_bytes(size);
  REQUIRE(tandem_session_replay_bytes(peers.sessions[0], replay_bytes.data(), size, &size) == TANDEM_OK);
  tandem::Replay replay;
  REQUIRE(tandem::read_replay(replay_bytes, &replay).ok());
  using namespace tandem;
  const WorldId ref = create_world(default_world_def()).value;
  {
    const BodyId ground = create_body(ref, default_body_def()).value;
    Polygon box;
    REQUIRE(make_offset_box(Q32::from_int(20), Q32::from_int(1), vec2(0, -1), Q32{}, Q32{}, &box).ok());
    REQUIRE(create_polygon_shape(ground, default_shape_def(), box).ok());
    for (int32_t p = 0; p < static_cast<int32_t>(k_players); ++p) {
      BodyDef def = default_body_def();
      def.type = BodyType::dynamic_body;
      def.position = vec2(p * 3 - 1, 2);
      const BodyId b = create_body(ref, def).value;
      REQUIRE(make_box(Q32::from_ratio(1, 2), Q32::from_ratio(1, 2), &box).ok());
      REQUIRE(create_polygon_shape(b, default_shape_def(), box).ok());
    }
  }
  REQUIRE(world_state_hash(ref) == tandem_session_start_hash(peers.sessions[0]));
  uint64_t score = 0;
  for (int64_t tick = 1; tick <= target; ++tick) {
    for (const Command& c : replay.tick_record(tick).commands)
      if (c.type != CommandType::user_input) REQUIRE(apply_command(ref, c).ok());
    REQUIRE(world_step(ref, Q32::from_ratio(1, 60)).ok());
    score += static_cast<uint64_t>(tick % 3);
    uint8_t game[8];
    for (int i = 0; i < 8; ++i) game[i] = static_cast<uint8_t>(score >> (8 * i));
    INFO("tick " << tick);
    const uint64_t expected = session_state_hash(ref, {game, 8});
    REQUIRE(tandem_session_confirmed_hash(peers.sessions[0], tick) == expected);
    REQUIRE(tandem_session_confirmed_hash(peers.sessions[1], tick) == expected);
  }
  REQUIRE(destroy_world(ref).ok());
  CHECK(tandem_session_state_hash(peers.games[0].world, nullptr, 0) == tandem_world_state_hash(peers.games[0].world));

  // The recorded replay verifies through the C replay API.
  tandem_replay_id r{};
  REQUIRE(tandem_replay_load_memory(replay_bytes.data(), replay_bytes.size(), &r) == TANDEM_OK);
  tandem_verify_report report{};
  REQUIRE(tandem_verify_replay(r, INT64_MAX, true, &report) == TANDEM_OK);
  CHECK(report.ok);
  tandem_free_verify_report(&report);
  REQUIRE(tandem_replay_destroy(r) == TANDEM_OK);

  // State images and per-body hashes of a tick in the ring; a request answered over the loopback.
  const int64_t t = tandem_session_confirmed_tick(peers.sessions[0]);
  REQUIRE(tandem_session_state_image(peers.sessions[0], t, nullptr, 0, &size) == TANDEM_OK);
  std::vector<uint8_t> image(size);
  require_error(tandem_session_state_image(peers.sessions[0], t, image.data(), 3, &size), TANDEM_ERROR_BUFFER_TOO_SMALL,
                "");
  REQUIRE(tandem_session_state_image(peers.sessions[0], t, image.data(), image.size(), &size) == TANDEM_OK);
  int32_t n = 0;
  REQUIRE(tandem_session_local_body_hashes(peers.sessions[0], t, nullptr, 0, &n) == TANDEM_OK);
  REQUIRE(n >= 3);
  std::vector<uint64_t> local(static_cast<size_t>(n));
  REQUIRE(tandem_session_local_body_hashes(peers.sessions[0], t, local.data(), n, &n) == TANDEM_OK);
  REQUIRE(tandem_session_request_body_hashes(peers.sessions[1], 0, t, 0, static_cast<uint32_t>(n)) == TANDEM_OK);
  for (int f = 0; f < 6; ++f) peers.frame();
  uint32_t endpoint = 9, first = 9;
  int64_t tick = 0;
  std::vector<uint64_t> remote(static_cast<size_t>(n));
  REQUIRE(tandem_session_remote_body_hashes(peers.sessions[1], &endpoint, &tick, &first, remote.data(), n, &n) ==
          TANDEM_OK);
  CHECK(endpoint == 0);
  CHECK(tick == t);
  CHECK(first == 0);
  CHECK(remote == local);
}

TEST_CASE("session: a perturbed C peer desyncs and reports it", "[capi][session]") {
  tandem_session_config c = config_for_test();
  c.mode = TANDEM_SESSION_LOCKSTEP;
  Peers peers(c);
  peers.games[1].perturb_tick = 20;
  for (int f = 0; f < 200 && tandem_session_state(peers.sessions[0]) == TANDEM_SESSION_RUNNING; ++f) peers.frame();
  REQUIRE(tandem_session_state(peers.sessions[0]) == TANDEM_SESSION_DESYNCED);
  tandem_session_stop stop{};
  REQUIRE(tandem_session_get_stop(peers.sessions[0], &stop) == TANDEM_OK);
  CHECK(stop.tick == 20);
  CHECK(stop.local_hash != stop.remote_hash);
  size_t length = 0;
  REQUIRE(tandem_session_stop_message(peers.sessions[0], nullptr, 0, &length) == TANDEM_OK);
  std::string message(length + 1, '\0');
  REQUIRE(tandem_session_stop_message(peers.sessions[0], message.data(), message.size(), &length) == TANDEM_OK);
  CHECK(message.find("20") != std::string::npos);
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "tandem_capi_session_test";
  std::filesystem::create_directories(dir);
  const std::string prefix = (dir / "peer0").string();
  REQUIRE(tandem_session_write_artifacts(peers.sessions[0], prefix.c_str()) == TANDEM_OK);
  CHECK(std::filesystem::exists(prefix + ".state"));
  CHECK(std::filesystem::exists(prefix + ".replay"));
  require_error(tandem_session_write_artifacts(peers.sessions[0], "/nonexistent-dir/x"), TANDEM_ERROR_IO, "");
  std::filesystem::remove_all(dir);
}
