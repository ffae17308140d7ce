// make_seeds.cpp — writes the seed inputs of the commands and decimal
// targets (tests/fuzz/corpus/commands, .../decimal): one file per command
// kind, encoded as decode_commands reads them, and a few decimal strings.
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

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: fuzz_make_seeds CORPUS_DIR\n");
    return 2;
  }
  const std::filesystem::path root = argv[1];
  std::filesystem::create_directories(root / "commands");
  std::filesystem::create_directories(root / "decimal");

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
