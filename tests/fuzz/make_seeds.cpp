// make_seeds.cpp — writes the seed inputs of the commands, decimal and
// session_packet targets (tests/fuzz/corpus/commands, .../decimal,
// .../session_packet): one file per command kind, encoded as decode_commands
// reads them; a few decimal strings; and real packets that endpoint 1 of a
// two-player rollback session sent to endpoint 0 (inputs with and without
// hashes, a body hash request and reply, a desync notice).
// (The replay and snapshot seeds are recorded by the tandem command line:
// scripts/fuzz.sh --make-seeds.) Usage: fuzz_make_seeds CORPUS_DIR
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "physics/collision.h"
#include "replay/bytes.h"
#include "replay/commands.h"
#include "replay/session.h"
#include "replay/session_packet.h"

using namespace tandem;

namespace {

void write(const std::filesystem::path& path, const std::vector<uint8_t>& bytes) {
  std::ofstream f(path, std::ios::binary);
  f.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

std::vector<uint8_t> encode(const std::vector<Command>& commands) {
  std::vector<uint8_t> out;
  ByteWriter w(&out);
  encode_commands(w, commands);
  return out;
}

// A floor and a box, as in the session_packet target (fuzz_targets.cpp).
WorldId small_world(BodyId* box_body) {
  const WorldId w = create_world(default_world_def()).value;
  const BodyId floor = create_body(w, default_body_def()).value;
  Polygon box{};
  (void)make_box(Q32::from_int(20), Q32::from_int(1), &box);
  (void)create_polygon_shape(floor, default_shape_def(), box);
  BodyDef d = default_body_def();
  d.type = BodyType::dynamic_body;
  d.position = Vec2{Q32{}, Q32::from_int(3)};
  *box_body = create_body(w, d).value;
  (void)make_box(Q32::from_ratio(1, 2), Q32::from_ratio(1, 2), &box);
  (void)create_polygon_shape(*box_body, default_shape_def(), box);
  return w;
}

// Plays two sessions (the target's config) delivering every packet at once
// and writes what endpoint 1 sent to endpoint 0 at chosen moments.
void write_session_packets(const std::filesystem::path& dir) {
  std::vector<std::pair<uint32_t, std::vector<uint8_t>>> to[2];  // inboxes: (from, bytes)
  std::vector<std::vector<uint8_t>> from1;                        // everything 1 sent to 0
  Session s[2];
  BodyId boxes[2];
  WorldId worlds[2];
  for (uint32_t e = 0; e < 2; ++e) {
    worlds[e] = small_world(&boxes[e]);
    SessionConfig config;
    config.player_count = 2;
    config.local_endpoint = e;
    config.input_bytes = 4;
    config.history_ticks = 16;
    SessionCallbacks cb;
    cb.send = [e, &to, &from1](uint32_t dest, std::span<const uint8_t> p) {
      to[dest].push_back({e, std::vector<uint8_t>(p.begin(), p.end())});
      if (e == 1) from1.emplace_back(p.begin(), p.end());
    };
    const BodyRef ref = body_ref(boxes[e]);
    cb.make_commands = [ref](int64_t, const SessionTickInputs& in, WorldId, std::vector<Command>* out) {
      out->push_back(make_apply_force_to_center(ref, Vec2{Q32::from_int(static_cast<int8_t>(in.input(1)[0])), Q32{}}));
      return Status{};
    };
    (void)s[e].start(worlds[e], config, std::move(cb));
  }
  auto deliver = [&] {
    for (uint32_t e = 0; e < 2; ++e) {
      auto inbox = std::move(to[e]);
      to[e].clear();
      for (auto& [f, bytes] : inbox) s[e].receive(f, bytes);
    }
  };
  for (uint32_t frame = 0; frame < 40; ++frame) {
    const uint8_t in0[4] = {static_cast<uint8_t>(frame % 3), 0, 0, 0};
    const uint8_t in1[4] = {static_cast<uint8_t>(frame % 5), 1, 2, static_cast<uint8_t>(frame)};
    (void)s[0].advance_frame(in0);
    (void)s[1].advance_frame(in1);
    deliver();
  }
  const size_t inputs = from1.size();
  (void)s[1].request_body_hashes(0, s[1].confirmed_tick(), 0, 2);  // 1 -> 0: request
  (void)s[0].request_body_hashes(1, s[0].confirmed_tick(), 0, 2);  // 0 -> 1, and 1 answers 0
  deliver();
  deliver();
  int n = 0;
  for (size_t i : {size_t{0}, size_t{1}, size_t{4}, size_t{12}, inputs / 2, inputs - 1})
    if (i < inputs) write(dir / ("input_" + std::to_string(n++)), from1[i]);
  for (size_t i = inputs; i < from1.size(); ++i) {
    SessionPacket p;
    if (!decode_session_packet(from1[i].data(), from1[i].size(), {}, &p).ok()) continue;
    if (p.type == SessionPacketType::body_hash_request) write(dir / "body_hash_request", from1[i]);
    if (p.type == SessionPacketType::body_hash_reply) write(dir / "body_hash_reply", from1[i]);
  }
  SessionPacket desync;
  desync.type = SessionPacketType::desync;
  desync.sender = 1;
  desync.sequence = 1000;
  desync.tick = 20;
  desync.hash = 0x0123456789abcdefULL;
  std::vector<uint8_t> bytes;
  (void)encode_session_packet(desync, &bytes);  // a valid packet
  write(dir / "desync", bytes);
  for (uint32_t e = 0; e < 2; ++e) (void)destroy_world(worlds[e]);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: fuzz_make_seeds CORPUS_DIR\n");
    return 2;
  }
  const std::filesystem::path root = argv[1];
  std::filesystem::create_directories(root / "commands");
  std::filesystem::create_directories(root / "decimal");
  std::filesystem::create_directories(root / "session_packet");
  write_session_packets(root / "session_packet");

  const BodyRef b0{0, 1}, b1{1, 1}, b2{2, 1};
  BodyDef dyn = default_body_def();
  dyn.type = BodyType::dynamic_body;
  dyn.position = Vec2{Q32::from_int(1), Q32::from_int(4)};
  ShapeSpec circle;
  circle.kind = ShapeKind::circle;
  circle.circle = Circle{Vec2{}, Q32::from_ratio(1, 2)};
  ShapeSpec box;
  box.kind = ShapeKind::polygon;
  (void)make_box(Q32::from_ratio(1, 2), Q32::from_ratio(1, 4), &box.polygon);
  ShapeSpec capsule;
  capsule.kind = ShapeKind::capsule;
  capsule.capsule = Capsule{Vec2{Q32::from_int(-1), Q32{}}, Vec2{Q32::from_int(1), Q32{}}, Q32::from_ratio(1, 4)};
  ShapeSpec segment;
  segment.kind = ShapeKind::segment;
  segment.segment = Segment{Vec2{Q32::from_int(-5), Q32{}}, Vec2{Q32::from_int(5), Q32{}}};
  ShapeSpec chain;
  chain.kind = ShapeKind::chain;
  chain.chain_points = {Vec2{Q32::from_int(-4), Q32{}}, Vec2{Q32::from_int(0), Q32::from_int(-1)},
                        Vec2{Q32::from_int(4), Q32{}}, Vec2{Q32::from_int(4), Q32::from_int(3)}};
  BodyDef ground = default_body_def();

  const std::vector<std::pair<const char*, std::vector<Command>>> seeds = {
      {"create_circle", {make_create_body(dyn, {circle})}},
      {"create_box_capsule", {make_create_body(dyn, {box, capsule})}},
      {"create_ground_chain", {make_create_body(ground, {segment, chain})}},
      {"destroy", {make_destroy_body(b1)}},
      {"forces",
       {make_apply_force(b1, Vec2{Q32::from_int(10), Q32{}}, Vec2{Q32::from_int(1), Q32::from_int(2)}),
        make_apply_force_to_center(b2, Vec2{Q32{}, Q32::from_int(50)}, false),
        make_apply_torque(b1, Q32::from_int(3))}},
      {"impulses",
       {make_apply_linear_impulse(b2, Vec2{Q32::from_int(1), Q32::from_int(1)}, Vec2{Q32{}, Q32::from_int(2)}),
        make_apply_linear_impulse_to_center(b1, Vec2{Q32::from_int(-1), Q32{}}),
        make_apply_angular_impulse(b2, Q32::from_ratio(1, 3))}},
      {"set_state",
       {make_set_linear_velocity(b1, Vec2{Q32::from_int(2), Q32::from_int(-1)}),
        make_set_angular_velocity(b2, Q32::from_int(-2)),
        make_set_transform(b1, Vec2{Q32::from_int(3), Q32::from_int(5)}, Rot{Q32::from_int(1), Q32{}}),
        make_set_awake(b2, false), make_set_enabled(b0, true)}},
      {"gravity_user", {make_set_gravity(Vec2{Q32{}, Q32::from_int(-20)}), make_user_input({1, 2, 3, 4, 5})}},
      {"empty", {}},
  };
  for (const auto& [name, commands] : seeds) write(root / "commands" / name, encode(commands));

  const char* decimals[] = {"0", "-0", "1", "-1.5", "3.14159265358979323846", "2147483647.99999999976716935634613037109375",
                            "-2147483647", "1e3", "1.25E-2", "+0.5", "0.000000000116415321826934814453125",
                            "32767.99998474121", "1e-30", "00012.5000"};
  int i = 0;
  for (const char* d : decimals) {
    const std::string s = d;
    write(root / "decimal" / ("d" + std::to_string(i++)), std::vector<uint8_t>(s.begin(), s.end()));
  }
  return 0;
}
