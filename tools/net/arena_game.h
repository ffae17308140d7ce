// arena_game.h — the bundled session game (tools, tests and `tandem session`):
// a walled top-down arena without gravity, one disc per player and a grid of
// crates. Each player's input is 4 bytes: i8 force x, i8 force y (units of
// 0.5 N), u8 buttons (bit 0: dash, an impulse along the force) and a spare
// byte. Game state beyond physics: one score per player, +1 every tick its
// disc is inside the centre square (|x|, |y| < 2 m). Bots draw inputs from a
// seeded splitmix64 stream as a pure function of (seed, player, tick).
// Header-only; integer and fixed-point only.
#pragma once

#include <cstdint>
#include <cstdio>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "fixed/fixed_math.h"
#include "fixed/splitmix64.h"
#include "physics/collision.h"
#include "physics/tandem.h"
#include "replay/bytes.h"
#include "replay/commands.h"
#include "replay/session.h"

namespace tandem::arena {

using namespace tandem::literals;

/// Most crates.
inline constexpr uint32_t k_max_crates = 1000;
/// Input bytes per player per tick.
inline constexpr uint32_t k_input_bytes = 4;

/// The arena: the refs of the players' discs and the scores.
struct Game {
  std::vector<BodyRef> players;
  std::vector<int64_t> scores;

  /// Builds the arena into an empty world: walls, `player_count` discs on a
  /// circle of radius 6 m and `crates` boxes (0…1000) on a grid. Same calls,
  /// same refs on every peer.
  Status build(WorldId world, uint32_t player_count, uint32_t crates) {
    players.clear();
    scores.assign(player_count, 0);
    const Q32 half = 12_q32;
    struct Wall {
      Vec2 p;
      Q32 hw, hh;
    };
    const Wall walls[4] = {{{Q32::zero(), -half - 0.5_q32}, half + 1_q32, 0.5_q32},
                           {{Q32::zero(), half + 0.5_q32}, half + 1_q32, 0.5_q32},
                           {{-half - 0.5_q32, Q32::zero()}, 0.5_q32, half},
                           {{half + 0.5_q32, Q32::zero()}, 0.5_q32, half}};
    for (const Wall& w : walls) {
      BodyDef bd = default_body_def();
      bd.type = BodyType::static_body;
      bd.position = w.p;
      const Result<BodyId> b = create_body(world, bd);
      if (!b.ok()) return b.status;
      Polygon box;
      if (!make_box(w.hw, w.hh, &box).ok()) return Status{StatusCode::invalid_argument, "arena wall box"};
      const Result<ShapeId> s = create_polygon_shape(b.value, default_shape_def(), box);
      if (!s.ok()) return s.status;
    }
    for (uint32_t p = 0; p < player_count; ++p) {
      const Status s = add_disc(world, p, player_count);
      if (!s.ok()) return s;
    }
    if (crates > k_max_crates) crates = k_max_crates;
    for (uint32_t i = 0; i < crates; ++i) {
      BodyDef bd = default_body_def();
      bd.type = BodyType::dynamic_body;
      bd.gravity_scale = Q32::zero();
      bd.linear_damping = 1_q32;
      bd.angular_damping = 1_q32;
      // 36 columns 0.6 m apart from (−10.5, −10.5): 1000 crates fill 28 rows.
      bd.position = Vec2{Q32::from_ratio(static_cast<int64_t>(i % 36) * 3, 5) - 10.5_q32,
                         Q32::from_ratio(static_cast<int64_t>(i / 36) * 3, 5) - 10.5_q32};
      const Result<BodyId> b = create_body(world, bd);
      if (!b.ok()) return b.status;
      Polygon box;
      if (!make_box(0.2_q32, 0.2_q32, &box).ok()) return Status{StatusCode::invalid_argument, "arena crate box"};
      const Result<ShapeId> s = create_polygon_shape(b.value, default_shape_def(), box);
      if (!s.ok()) return s.status;
    }
    return {};
  }

  /// Adds the players' discs (as build() does) after whatever the world holds
  /// already: an arena loaded from a scene file (scenes/arena.json: walls,
  /// crates). The discs' indices follow the world's bodies.
  Status add_players(WorldId world, uint32_t player_count) {
    players.clear();
    scores.assign(player_count, 0);
    for (uint32_t p = 0; p < player_count; ++p) {
      const Status s = add_disc(world, p, player_count);
      if (!s.ok()) return s;
    }
    return {};
  }

  /// The session's make_commands: one force per player (and a dash impulse).
  Status make_commands(int64_t, const SessionTickInputs& in, WorldId, std::vector<Command>* out) const {
    for (uint32_t p = 0; p < in.player_count && p < players.size(); ++p) {
      const std::span<const uint8_t> b = in.input(p);
      const Vec2 f{Q32::from_ratio(static_cast<int8_t>(b[0]), 2), Q32::from_ratio(static_cast<int8_t>(b[1]), 2)};
      if (f.x.raw != 0 || f.y.raw != 0) out->push_back(make_apply_force_to_center(players[p], f));
      if ((b[2] & 1u) != 0) out->push_back(make_apply_linear_impulse_to_center(players[p], f * Q32::from_ratio(1, 16)));
    }
    return {};
  }

  /// The session's after_step: scores.
  void after_step(int64_t, WorldId world) {
    for (size_t p = 0; p < players.size(); ++p) {
      const Vec2 x = body_position(body_id(world, players[p]));
      if (abs(x.x) < 2_q32 && abs(x.y) < 2_q32) ++scores[p];
    }
  }

  /// The session's save_game / load_game.
  void save(std::vector<uint8_t>* out) const {
    out->clear();
    ByteWriter w(out);
    for (int64_t s : scores) w.i64(s);
  }
  void load(std::span<const uint8_t> state) {
    ByteReader r(state);
    for (int64_t& s : scores) s = r.i64("score");
  }

  /// Player p's disc on a circle of radius 6 m; appends its ref to `players`.
  Status add_disc(WorldId world, uint32_t p, uint32_t player_count) {
    BodyDef bd = default_body_def();
    bd.type = BodyType::dynamic_body;
    bd.gravity_scale = Q32::zero();
    bd.linear_damping = 0.5_q32;
    const SinCos<Q32> sc = sincos(Q32::from_ratio(2 * static_cast<int64_t>(p), static_cast<int64_t>(player_count)) * k_pi);
    bd.position = Vec2{sc.cos * 6_q32, sc.sin * 6_q32};
    const Result<BodyId> b = create_body(world, bd);
    if (!b.ok()) return b.status;
    Circle c;
    c.radius = 0.5_q32;
    const Result<ShapeId> s = create_circle_shape(b.value, default_shape_def(), c);
    if (!s.ok()) return s.status;
    players.push_back(body_ref(b.value));
    return {};
  }

  /// Callbacks bound to this game (it must outlive the session).
  SessionCallbacks callbacks(std::function<void(uint32_t, std::span<const uint8_t>)> send) {
    SessionCallbacks c;
    c.send = std::move(send);
    c.make_commands = [this](int64_t t, const SessionTickInputs& in, WorldId w, std::vector<Command>* out) {
      return make_commands(t, in, w, out);
    };
    c.after_step = [this](int64_t t, WorldId w) { after_step(t, w); };
    c.save_game = [this](std::vector<uint8_t>* out) { save(out); };
    c.load_game = [this](std::span<const uint8_t> s) { load(s); };
    return c;
  }
};

/// The replay scene bytes that name an arena game (SessionConfig::replay_scene):
/// "tandem arena 1: players P, first disc body B" — the discs are bodies B…B+P−1
/// of generation 1 (4 after build()'s walls; after the scene's bodies with add_players()).
inline std::vector<uint8_t> replay_scene(uint32_t player_count, uint32_t first_disc) {
  const std::string t =
      "tandem arena 1: players " + std::to_string(player_count) + ", first disc body " + std::to_string(first_disc);
  return std::vector<uint8_t>(t.begin(), t.end());
}

/// Parses replay_scene()'s bytes; false for anything else (another game, no scene).
inline bool parse_replay_scene(std::span<const uint8_t> bytes, uint32_t* player_count, uint32_t* first_disc) {
  const std::string t(bytes.begin(), bytes.end());
  unsigned p = 0, b = 0;
  int used = 0;
  if (std::sscanf(t.c_str(), "tandem arena 1: players %u, first disc body %u%n", &p, &b, &used) != 2 ||
      static_cast<size_t>(used) != t.size() || p < 1 || p > k_session_max_players || b > (1u << 24)) {
    return false;
  }
  *player_count = p;
  *first_disc = b;
  return true;
}

/// The arena's game logic for verify_replay (VerifyOptions::game): scores
/// from the recorded start, one after_step per tick, for the discs named by
/// replay_scene().
inline Status verify_game_step(uint32_t player_count, uint32_t first_disc,
                               std::function<Status(int64_t, WorldId, std::span<const uint8_t>, std::vector<uint8_t>*)>* out) {
  auto game = std::make_shared<Game>();
  for (uint32_t p = 0; p < player_count; ++p) game->players.push_back(BodyRef{first_disc + p, 1});
  game->scores.assign(player_count, 0);
  *out = [game](int64_t tick, WorldId world, std::span<const uint8_t> before, std::vector<uint8_t>* after) {
    if (before.size() != game->scores.size() * 8)
      return Status{StatusCode::invalid_argument, "arena game state of " + std::to_string(before.size()) +
                                                      " bytes, expected " + std::to_string(game->scores.size() * 8)};
    game->load(before);
    game->after_step(tick, world);
    game->save(after);
    return Status{};
  };
  return Status{};
}

/// A bot's input for `tick`: a pure function of (seed, player, tick / change_every).
inline void bot_input(uint64_t seed, uint32_t player, int64_t tick, uint32_t change_every, uint8_t out[k_input_bytes]) {
  // tick ≥ 0; hashed as its u64 bits.
  uint64_t state = seed ^ (uint64_t{player} * 0xD1B54A32D192ED03ull) ^ ((static_cast<uint64_t>(tick) / (change_every == 0 ? 1 : change_every)) * 0x9E3779B97F4A7C15ull);
  const uint64_t r = splitmix64_next(&state);
  out[0] = static_cast<uint8_t>(static_cast<int8_t>(static_cast<int64_t>(r & 31) - 15));
  out[1] = static_cast<uint8_t>(static_cast<int8_t>(static_cast<int64_t>((r >> 8) & 31) - 15));
  out[2] = static_cast<uint8_t>(((r >> 16) & 15) == 0 ? 1 : 0);
  out[3] = 0;
}

}  // namespace tandem::arena
