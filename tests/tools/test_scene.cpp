// test_scene.cpp — the scene loader (tools/scene): exact numbers, errors with
// JSON paths, generators, inputs, the bundled scenes, and the format document.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "replay/state.h"
#include "scene/scene.h"

using namespace tandem;
using namespace tandem::scene;

namespace {

const std::string k_source = TANDEM_SOURCE_DIR;

Scene load_ok(const std::string& text) {
  Result<Scene> r = load_scene_text(text, "test.json");
  INFO(r.status.message);
  REQUIRE(r.ok());
  return r.value;
}

std::string load_error(const std::string& text) {
  Result<Scene> r = load_scene_text(text, "test.json");
  REQUIRE_FALSE(r.ok());
  return r.status.message;
}

// Runs a built scene `ticks` steps with its inputs; returns the state hash.
uint64_t run_hash(const Scene& scene, int64_t ticks) {
  Result<BuiltScene> built = build_world(scene);
  INFO(built.status.message);
  REQUIRE(built.ok());
  for (int64_t t = 0; t < ticks; ++t) {
    const Status in = apply_scene_inputs(built.value, scene, t);
    INFO(in.message);
    REQUIRE(in.ok());
    const StepResult r = world_step(built.value.world, scene.time_step);
    REQUIRE(r.ok());
  }
  const uint64_t h = world_state_hash(built.value.world);
  REQUIRE(destroy_world(built.value.world).ok());
  return h;
}

const char* k_one_ball = R"({
  "world": {"gravity": [0, -9.81]},
  "bodies": [
    {"name": "ground", "shapes": [{"type": "box", "half_width": 10, "half_height": 0.5}]},
    {"name": "ball", "type": "dynamic", "position": [0.1, 3], "shapes": [{"type": "circle", "radius": 0.25, "friction": 0.1}]}
  ]
})";

}  // namespace

TEST_CASE("scene numbers convert exactly from their decimal text") {
  const Scene s = load_ok(k_one_ball);
  REQUIRE(s.bodies.size() == 2);
  // 0.1 is the decimal's nearest Q32.32, not the nearest of the binary64 0.1.
  CHECK(s.bodies[1].def.position.x.raw == parse_q32("0.1").value.raw);
  CHECK(s.bodies[1].def.position.x.raw == 429496730);
  CHECK(s.world.gravity.y.raw == parse_q32("-9.81").value.raw);
  CHECK(s.bodies[1].shapes[0].def.friction.raw == parse_q32("0.1").value.raw);
  // Many digits beyond what a double holds still decide the last raw bit.
  const Scene t = load_ok(R"({"bodies": [{"position": [0.50000000011641532182693481445312500001, 0]}]})");
  CHECK(t.bodies[0].def.position.x.raw == (int64_t{1} << 31) + 1);
  const Scene e = load_ok(R"({"bodies": [{"position": [1e-1, 25E-2]}]})");
  CHECK(e.bodies[0].def.position.x.raw == parse_q32("0.1").value.raw);
  CHECK(e.bodies[0].def.position.y.raw == parse_q32("0.25").value.raw);
}

TEST_CASE("scene defaults match the engine defaults") {
  const Scene s = load_ok(R"({"bodies": [{"shapes": [{"type": "circle", "radius": 1}]}]})");
  const WorldDef w = default_world_def();
  CHECK(s.world.gravity == w.gravity);
  CHECK(s.world.sub_step_count == w.sub_step_count);
  CHECK(s.step_hz == 60);
  CHECK(s.time_step == Q32::from_ratio(1, 60));
  CHECK(s.bodies[0].def.type == BodyType::static_body);
  CHECK(s.bodies[0].shapes[0].def.density == default_shape_def().density);
}

TEST_CASE("scene errors name the file, the JSON path and what was expected") {
  CHECK_THAT(load_error("{\"bodies\": [}"), Catch::Contains("test.json") && Catch::Contains("line 1, column 13"));
  CHECK_THAT(load_error(R"({"bodies": [{"shapes": [{"type": "circle", "radius": "big"}]}]})"),
             Catch::Contains("test.json: /bodies/0/shapes/0/radius: expected a number, got a string"));
  CHECK_THAT(load_error(R"({"bodies": [{"positon": [0, 0]}]})"),
             Catch::Contains("/bodies/0/positon: unknown key (did you mean \"position\"?)"));
  CHECK_THAT(load_error(R"({"world": {"sub_steps": 2.5}})"),
             Catch::Contains("/world/sub_steps: expected an integer in [1, 64] (no fraction or exponent), got 2.5"));
  CHECK_THAT(load_error(R"({"world": {"sub_steps": 65}})"), Catch::Contains("/world/sub_steps: expected an integer in [1, 64]"));
  CHECK_THAT(load_error(R"({"bodies": [{"position": [3000000000, 0]}]})"),
             Catch::Contains("/bodies/0/position/0: expected a number within"));
  CHECK_THAT(load_error(R"({"bodies": [{"type": "dynamik"}]})"),
             Catch::Contains("/bodies/0/type: unknown value \"dynamik\" (did you mean \"dynamic\"?)"));
  CHECK_THAT(load_error(R"({"joints": [{"type": "revolute"}]})"), Catch::Contains("/joints/0: missing key \"body_a\""));
  CHECK_THAT(load_error(R"({"bodies": [{"shapes": [{"type": "circle"}]}]})"),
             Catch::Contains("/bodies/0/shapes/0: missing key \"radius\""));
  CHECK_THAT(load_error(R"({"bodies": [{"shapes": [{"type": "polygon", "points": [[0,0],[1,0],[2,0]]}]}]})"),
             Catch::Contains("/bodies/0/shapes/0: "));
  CHECK_THAT(load_error(R"({"a": 1, "a": 2})"), Catch::Contains("duplicate key \"a\""));
  CHECK_THAT(load_error("[1, 2]"), Catch::Contains("/: expected an object, got an array"));
  CHECK_THAT(load_error(R"({"inputs": [{"tick": 1, "type": "set_awake", "body": "nobody", "awake": true}]})"),
             Catch::Contains("/inputs/0/body: no body is named \"nobody\""));
  CHECK_THAT(load_error(R"({"bodies": [{"user_data": -1}]})"), Catch::Contains("/bodies/0/user_data: expected an unsigned"));
  std::string deep(100, '[');
  CHECK_THAT(load_error(deep), Catch::Contains("nesting deeper than"));
}

TEST_CASE("scene file errors: missing file") {
  Result<Scene> r = load_scene_file(k_source + "/scenes/no-such-scene.json");
  REQUIRE_FALSE(r.ok());
  CHECK_THAT(r.status.message, Catch::Contains("no-such-scene.json: cannot open the file"));
}

TEST_CASE("physics refusals at build time carry the JSON path") {
  // Restitution 2 passes the loader (a number) and is refused by create_circle_shape.
  const Scene s = load_ok(R"({"bodies": [{}, {"type": "dynamic", "shapes": [{"type": "circle", "radius": 1},
                                                                          {"type": "circle", "radius": 1, "restitution": 2}]}]})");
  Result<BuiltScene> b = build_world(s);
  REQUIRE_FALSE(b.ok());
  CHECK_THAT(b.status.message, Catch::Contains("test.json: /bodies/1/shapes/1: ") && Catch::Contains("restitution"));
  const Scene v = load_ok(R"({"bodies": [{"type": "static", "linear_velocity": [1, 0]}]})");
  Result<BuiltScene> bv = build_world(v);
  REQUIRE_FALSE(bv.ok());
  CHECK_THAT(bv.status.message, Catch::Contains("/bodies/0: "));
  const Scene g = load_ok(R"({"generators": [{"type": "grid", "columns": 2, "rows": 1, "spacing": [2, 0],
      "body": {"type": "dynamic", "shapes": [{"type": "circle", "radius": 0.5}, {"type": "circle", "radius": 0.5, "friction": 1000}]}}]})");
  Result<BuiltScene> bg = build_world(g);
  REQUIRE_FALSE(bg.ok());
  CHECK_THAT(bg.status.message, Catch::Contains("/generators/0/body/shapes/1: ") && Catch::Contains("friction"));
  const Scene w = load_ok(R"({"world": {"contact_hertz": 0}})");
  Result<BuiltScene> bw = build_world(w);
  REQUIRE_FALSE(bw.ok());
  CHECK_THAT(bw.status.message, Catch::Contains("/world: "));
}

TEST_CASE("generators expand deterministically") {
  const char* text = R"({"generators": [
    {"type": "grid", "origin": [1, 2], "columns": 3, "rows": 2, "spacing": [1.5, 1],
     "body": {"type": "dynamic", "shapes": [{"type": "circle", "radius": 0.25}]}},
    {"type": "pyramid", "origin": [0, 10], "base": 4, "spacing": [1, 1],
     "body": {"type": "dynamic", "shapes": [{"type": "box", "half_width": 0.5, "half_height": 0.5}]}},
    {"type": "random", "seed": 42, "count": 20, "region": {"lower": [-5, 20], "upper": [5, 30]},
     "kinds": ["circle", "box", "capsule"], "size_min": 0.1, "size_max": 0.3, "speed": 2}]})";
  const Scene s = load_ok(text);
  REQUIRE(s.bodies.size() == 6 + 10 + 20);
  CHECK(s.bodies[5].def.position == Vec2{Q32(4), Q32(3)});
  CHECK(s.bodies[6 + 4 + 2].def.position == Vec2{0.5_q32 + 2_q32, 11_q32});  // row 1, column 2: shifted half a spacing
  CHECK(s.bodies[15].def.position == Vec2{1.5_q32, 13_q32});               // the top
  const Scene again = load_ok(text);
  for (size_t i = 16; i < s.bodies.size(); ++i) {
    CHECK(s.bodies[i].def.position == again.bodies[i].def.position);
    CHECK(s.bodies[i].def.linear_velocity == again.bodies[i].def.linear_velocity);
    CHECK(s.bodies[i].def.position.x >= -5_q32);
    CHECK(s.bodies[i].def.position.x <= 5_q32);
    const Q32 speed = length(s.bodies[i].def.linear_velocity);
    CHECK(abs(speed - 2_q32).raw < 64);
  }
  // A different seed gives a different draw.
  std::string other = text;
  other.replace(other.find("\"seed\": 42"), 10, "\"seed\": 43");
  CHECK_FALSE(load_ok(other).bodies[16].def.position == s.bodies[16].def.position);
  CHECK_THAT(load_error(R"({"generators": [{"type": "random", "count": 1000, "region": {"lower": [0, 0], "upper": [1, 1]},
                                            "size_min": 0.1, "size_max": 0.2}]})"),
             Catch::Contains("/generators/0: count 1000 does not fit"));
}

TEST_CASE("scripted inputs apply at their tick and map to engine commands") {
  const Scene s = load_ok(R"({"world": {"gravity": [0, 0]}, "bodies": [
      {"name": "b", "type": "dynamic", "shapes": [{"type": "circle", "radius": 0.5}]}],
    "inputs": [{"tick": 2, "type": "set_linear_velocity", "body": "b", "velocity": [1.5, 0]},
               {"tick": 0, "type": "set_gravity", "gravity": [0, -1]}]})");
  REQUIRE(s.inputs.size() == 2);
  CHECK(s.inputs[0].tick == 0);  // sorted by tick
  Result<BuiltScene> b = build_world(s);
  REQUIRE(b.ok());
  const std::vector<Command> at2 = scene_inputs_at(b.value, s, 2);
  REQUIRE(at2.size() == 1);
  CHECK(at2[0].type == CommandType::set_linear_velocity);
  CHECK(at2[0].body == body_ref(b.value.bodies[0]));
  for (int64_t t = 0; t < 3; ++t) {
    REQUIRE(apply_scene_inputs(b.value, s, t).ok());
    REQUIRE(world_step(b.value.world, s.time_step).ok());
  }
  CHECK(world_gravity(b.value.world).y == Q32(-1));
  CHECK(body_linear_velocity(b.value.bodies[0]).x == 1.5_q32);
  REQUIRE(destroy_world(b.value.world).ok());
}

TEST_CASE("bundled scenes load, run and repeat their hash") {
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(k_source + "/scenes")) {
    if (entry.path().extension() != ".json") continue;
    ++count;
    INFO(entry.path().string());
    Result<Scene> r = load_scene_file(entry.path().string());
    INFO(r.status.message);
    REQUIRE(r.ok());
    // A few hundred ticks each; the small scenes also run twice (the big ones
    // cost seconds under the sanitizers, and `tandem demo` reruns one).
    const uint64_t a = run_hash(r.value, 200);
    if (r.value.bodies.size() < 100) CHECK(a == run_hash(r.value, 200));
  }
  CHECK(count >= 8);
}

TEST_CASE("scene create commands rebuild the same world") {
  Result<Scene> r = load_scene_file(k_source + "/scenes/impulses.json");
  REQUIRE(r.ok());
  const Scene& s = r.value;
  Result<WorldId> w = create_world(s.world);
  REQUIRE(w.ok());
  for (const Command& c : scene_create_commands(s)) REQUIRE(apply_command(w.value, c).ok());
  Result<BuiltScene> b = build_world(s);
  REQUIRE(b.ok());
  CHECK(world_state_hash(w.value) == world_state_hash(b.value.world));
  REQUIRE(destroy_world(w.value).ok());
  REQUIRE(destroy_world(b.value.world).ok());
}

TEST_CASE("docs/scene-format.md mentions every key the loader accepts") {
  std::ifstream f(k_source + "/docs/scene-format.md");
  REQUIRE(f);
  std::stringstream text;
  text << f.rdbuf();
  const std::string doc = text.str();
  for (const std::string& key : scene_format_keys()) {
    INFO(key);
    CHECK(doc.find("`" + key + "`") != std::string::npos);
  }
}

TEST_CASE("every bundled scene hashes the same tick by tick with every broad phase, switched mid-run too") {
  // The broad-phase contract (physics/broad_phase.h): the same pairs in the
  // same order, so the same contacts and the same world hash every tick.
  // Naive is the reference; "switching" changes the kind every 7 ticks.
#ifdef NDEBUG
  const int ticks = 120;
#else
  const int ticks = 40;  // sanitizer builds: the rain and circles scenes cost seconds
#endif
  const BroadPhaseKind kinds[] = {BroadPhaseKind::naive, BroadPhaseKind::sweep_and_prune, BroadPhaseKind::grid,
                                  BroadPhaseKind::tree};
  int scenes = 0;
  for (const auto& entry : std::filesystem::directory_iterator(k_source + "/scenes")) {
    if (entry.path().extension() != ".json") continue;
    ++scenes;
    Result<Scene> r = load_scene_file(entry.path().string());
    REQUIRE(r.ok());
    std::vector<uint64_t> reference;
    for (int variant = 0; variant <= 4; ++variant) {  // 0–3: one kind throughout; 4: switching
      Scene s = r.value;
      s.world.broad_phase = kinds[variant == 4 ? 0 : variant];
      Result<BuiltScene> b = build_world(s);
      REQUIRE(b.ok());
      std::vector<uint64_t> chain;
      for (int t = 0; t < ticks; ++t) {
        if (variant == 4 && t % 7 == 0) REQUIRE(world_set_broad_phase(b.value.world, kinds[(t / 7) % 4]).ok());
        REQUIRE(apply_scene_inputs(b.value, s, t).ok());
        REQUIRE(world_step(b.value.world, s.time_step).ok());
        chain.push_back(world_state_hash(b.value.world));
      }
      if (variant == 0) {
        reference = chain;
      } else {
        size_t first = 0;
        while (first < chain.size() && chain[first] == reference[first]) ++first;
        INFO(entry.path().filename().string() << ", variant " << variant << " (4: switching every 7 ticks): first "
                                              << "differing tick " << first);
        CHECK(first == chain.size());
      }
      REQUIRE(destroy_world(b.value.world).ok());
    }
  }
  CHECK(scenes >= 8);
}

TEST_CASE("the README's scene example loads and runs") {
  std::ifstream f(k_source + "/README.md");
  REQUIRE(f);
  std::stringstream text;
  text << f.rdbuf();
  const std::string readme = text.str();
  const size_t begin = readme.find("```json\n");
  REQUIRE(begin != std::string::npos);
  const size_t end = readme.find("```", begin + 8);
  REQUIRE(end != std::string::npos);
  const Scene s = load_ok(readme.substr(begin + 8, end - begin - 8));
  CHECK(s.bodies.size() == 52);  // ground, ball and 50 generated bodies
  (void)run_hash(s, 120);
}

// --- size limits: every generator is counted before anything is expanded ----

namespace {

// A scene with `generator` (JSON object text) after `explicit_bodies` bodies.
std::string scene_with(const std::string& generator, int explicit_bodies = 0) {
  std::string bodies;
  for (int i = 0; i < explicit_bodies; ++i)
    bodies += std::string(i ? ", " : "") + R"({"position": [0, )" + std::to_string(i) + "]}";
  return R"({"bodies": [)" + bodies + R"(], "generators": [)" + generator + "]}";
}

const std::string k_template = R"("body": {"type": "dynamic", "shapes": [{"type": "circle", "radius": 0.5}]})";

std::string limit_error(const std::string& text, const SceneLimits& limits) {
  Result<Scene> r = load_scene_text(text, "big.json", limits);
  REQUIRE_FALSE(r.ok());
  return r.status.message;
}

}  // namespace

TEST_CASE("scene limits: a 155-byte grid of 10^6 bodies is refused before it is expanded") {
  const std::string text = R"({"generators": [{"type": "grid", "columns": 1000, "rows": 1000, "spacing": [1, 1],)"
                           R"( "body": {"shapes": [{"type": "circle", "radius": 0.4}]}}]})";
  CHECK(text.size() < 160);
  const std::string e = limit_error(text, SceneLimits{});
  CHECK_THAT(e, Catch::StartsWith("big.json: /generators/0: the grid generator asks for 1000 columns × 1000 rows = "
                                  "1000000 bodies"));
  CHECK_THAT(e, Catch::Contains("limit of 100000 bodies") && Catch::Contains("--max-bodies"));
}

TEST_CASE("scene limits: every generator kind is bounded, and the limit can be raised") {
  struct Case {
    std::string generator;
    int64_t bodies;
    std::string detail;
  };
  const std::vector<Case> cases = {
      {R"({"type": "grid", "columns": 30, "rows": 20, "spacing": [2, 2], )" + k_template + "}", 600,
       "30 columns × 20 rows = 600 bodies"},
      {R"({"type": "pyramid", "base": 40, "spacing": [1.1, 1], )" + k_template + "}", 820, "base 40: 820 bodies"},
      {R"({"type": "random", "count": 500, "size_min": 0.1, "size_max": 0.2,)"
       R"( "region": {"lower": [-100, 0], "upper": [100, 100]}})",
       500, "count 500 bodies"},
  };
  for (const Case& c : cases) {
    INFO(c.generator);
    SceneLimits tight;
    tight.max_bodies = c.bodies - 1;
    const std::string e = limit_error(scene_with(c.generator), tight);
    CHECK_THAT(e, Catch::Contains("/generators/0: ") && Catch::Contains(c.detail) &&
                      Catch::Contains("limit of " + std::to_string(c.bodies - 1) + " bodies"));
    // With explicit bodies before it, the message says so and counts them.
    SceneLimits exact;
    exact.max_bodies = c.bodies + 2;
    const std::string e2 = limit_error(scene_with(c.generator, 3), exact);
    CHECK_THAT(e2, Catch::Contains("on top of 3 before it"));
    // Exactly at the limit it loads, with that many bodies.
    Result<Scene> ok = load_scene_text(scene_with(c.generator, 2), "big.json", exact);
    INFO(ok.status.message);
    REQUIRE(ok.ok());
    CHECK(static_cast<int64_t>(ok.value.bodies.size()) == c.bodies + 2);
  }
}

TEST_CASE("scene limits: shapes are counted per template, explicit bodies too") {
  const std::string two_shapes = R"("body": {"shapes": [{"type": "circle", "radius": 0.2},)"
                                 R"( {"type": "box", "half_width": 0.2, "half_height": 0.2}]})";
  SceneLimits limits;
  limits.max_shapes = 99;
  const std::string e = limit_error(
      scene_with(R"({"type": "grid", "columns": 10, "rows": 5, "spacing": [1, 1], )" + two_shapes + "}"), limits);
  CHECK_THAT(e, Catch::Contains("/generators/0: the grid generator asks for 50 bodies × 2 shapes = 100 shapes") &&
                    Catch::Contains("limit of 99 shapes") && Catch::Contains("--max-shapes"));
  limits.max_shapes = 100;
  CHECK(load_scene_text(scene_with(R"({"type": "grid", "columns": 10, "rows": 5, "spacing": [1, 1], )" + two_shapes +
                                   "}"),
                        "big.json", limits)
            .ok());
  // Explicit bodies over the limit: named by their array.
  SceneLimits one;
  one.max_bodies = 1;
  CHECK_THAT(limit_error(R"({"bodies": [{}, {}]})", one),
             Catch::Contains("/bodies: the scene lists 2 bodies; the limit is 1"));
  // Two generators: the second one is named, with what came before it.
  SceneLimits hundred;
  hundred.max_bodies = 100;
  const std::string g = R"({"type": "grid", "columns": 10, "rows": 6, "spacing": [1, 1], )" + k_template + "}";
  CHECK_THAT(limit_error(scene_with(g + ", " + g), hundred),
             Catch::Contains("/generators/1: ") && Catch::Contains("60 bodies, on top of 60 before it"));
  // The engine's limit caps a raised limit.
  SceneLimits huge;
  huge.max_bodies = INT64_MAX;
  CHECK_THAT(limit_error(scene_with(R"({"type": "grid", "columns": 1000000, "rows": 1000000, "spacing": [1, 1], )" +
                                    k_template + "}"),
                         huge),
             Catch::Contains("limit of 16777216 bodies"));
  // A bad count is still named as before (the same range as expansion).
  CHECK_THAT(limit_error(scene_with(R"({"type": "pyramid", "base": 1001, "spacing": [1, 1], )" + k_template + "}"),
                         SceneLimits{}),
             Catch::Contains("/generators/0/base: expected an integer in [1, 1000]"));
}

TEST_CASE("scene limits: a chain in a template counts one shape per point") {
  // A 50-point chain copied 100 times is 5000 segments, not 100 shapes.
  std::string points;
  for (int i = 0; i < 50; ++i) points += std::string(i ? ", " : "") + "[" + std::to_string(i) + ", 0]";
  const std::string g = R"({"type": "grid", "columns": 10, "rows": 10, "spacing": [100, 100], "body": {"shapes": [)"
                        R"({"type": "chain", "points": [)" + points + "]}]}}";
  SceneLimits limits;
  limits.max_shapes = 4999;
  CHECK_THAT(limit_error(scene_with(g), limits),
             Catch::Contains("/generators/0: the grid generator asks for 100 bodies × 50 shapes = 5000 shapes"));
  limits.max_shapes = 5000;
  Result<Scene> ok = load_scene_text(scene_with(g), "chains.json", limits);
  INFO(ok.status.message);
  CHECK(ok.ok());
  // Explicit bodies: their chains count the same way.
  limits.max_shapes = 49;
  CHECK_THAT(limit_error(R"({"bodies": [{"shapes": [{"type": "chain", "points": [)" + points + "]}]}]}", limits),
             Catch::Contains("/bodies: the scene's bodies have 50 shapes; the limit is 49"));
}
