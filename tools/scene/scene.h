// scene.h — JSON scene files: load, build a world, apply scripted inputs
// (tools only; the format is documented in docs/scene-format.md).
//
// DESIGN. Loading and building are separate: load_scene_text() turns the
// text into a Scene — plain definitions (WorldDef, BodyDef, the replay
// module's ShapeSpec and Command), with generators already expanded and body
// references resolved — and build_world() turns a Scene into a live world.
// So a scene can be inspected, recorded as create_body commands, or built
// twice (the replay verifier builds it once per run).
//
// EXACT NUMBERS. Every number goes from its decimal text straight to Q32.32
// with parse_q32 (json_tree.h keeps the text), never through binary floating
// point, so one file gives the same bits on every machine. Integer fields
// refuse fractions. Random generators draw from splitmix64 with integer
// arithmetic only.
//
// ERRORS name the file, the JSON pointer of the culprit and what was
// expected: `circles.json: /bodies/3/shapes/0/radius: expected a number,
// got a string`. Unknown keys are errors (with "did you mean" when a known
// key is close). Refusals of the physics API at build time carry the JSON
// pointer of the object that caused them. Nothing here throws to the caller.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "physics/tandem.h"
#include "replay/commands.h"

namespace tandem::scene {

/// The value of the optional top-level "format" key.
inline constexpr const char* k_scene_format = "tandem-scene";
/// The newest scene format version this loader reads.
inline constexpr int32_t k_scene_version = 1;

/// One body of a scene: its definition and shapes, and where it came from.
struct SceneBody {
  std::string name;               ///< "name" key; empty if none
  BodyDef def = default_body_def();
  std::vector<ShapeSpec> shapes;  ///< attached in this order
  std::vector<std::string> shape_paths;  ///< JSON pointer of each shape (for build errors)
  std::string path;               ///< JSON pointer of the body (or its generator)
};

/// One scripted input: a command applied before step `tick + 1`.
struct SceneInput {
  int64_t tick = 0;    ///< steps completed before it applies (0: before the first step)
  Command command;     ///< its body ref is filled in by apply_scene_inputs
  int32_t body = -1;   ///< index into Scene::bodies, or −1 (set_gravity)
  std::string path;    ///< JSON pointer of the input
};

/// One joint of a scene (built after every body, in file order).
struct SceneJoint {
  JointSpec spec;      ///< body refs filled in by build_world
  int32_t body_a = 0;  ///< index into Scene::bodies
  int32_t body_b = 0;
  std::string path;    ///< JSON pointer of the joint
};

/// A loaded scene, ready to build.
struct Scene {
  std::string name;         ///< the file name given to the loader
  std::string title;        ///< "name" key
  std::string description;  ///< "description" key
  WorldDef world = default_world_def();
  int32_t step_hz = 60;     ///< steps per simulated second
  Q32 time_step;            ///< 1/step_hz s, rounded to nearest
  int64_t ticks = 600;      ///< suggested run length, steps
  bool has_view = false;    ///< "view" given: the region a renderer shows, m
  AABB view;
  std::vector<SceneBody> bodies;   ///< explicit bodies, then generated ones
  std::vector<SceneJoint> joints;  ///< "joints", in file order
  std::vector<SceneInput> inputs;  ///< ascending tick; file order within a tick
};

/// Default cap on a scene's bodies (explicit plus generated): about 80 MB of
/// loaded scene. Raise it with SceneLimits::max_bodies or `--max-bodies`.
inline constexpr int64_t k_default_scene_max_bodies = 100000;
/// Default cap on a scene's shapes (each body's shapes summed).
inline constexpr int64_t k_default_scene_max_shapes = 400000;

/// What a scene may ask for. Generators are counted from their parameters
/// before anything is expanded, so a few bytes of JSON never allocate more
/// than these limits allow. Values above the engine's k_max_bodies /
/// k_max_shapes are lowered to them.
struct SceneLimits {
  int64_t max_bodies = k_default_scene_max_bodies;  ///< bodies in all, ≥ 0
  int64_t max_shapes = k_default_scene_max_shapes;  ///< shapes in all (a chain: one per point), ≥ 0
};

/// Parses scene text; `name` (usually the file path) prefixes every error.
/// A scene (or one generator) over `limits` is refused with the JSON pointer
/// of the generator or array, the requested count and the limit.
Result<Scene> load_scene_text(std::string_view text, const std::string& name, const SceneLimits& limits = {});
/// Reads and parses a scene file (errors: unreadable file, then as
/// load_scene_text).
Result<Scene> load_scene_file(const std::string& path, const SceneLimits& limits = {});

/// A world built from a scene and its body handles (parallel to
/// Scene::bodies).
struct BuiltScene {
  WorldId world;
  std::vector<BodyId> bodies;
};

/// Creates the world, bodies, shapes and joints. On a refusal destroys what it made
/// and returns the engine's message prefixed with the JSON pointer of the
/// object that caused it. The caller owns the world (destroy_world).
Result<BuiltScene> build_world(const Scene& scene);

/// The commands the scene scripts before step `tick + 1`, with body refs
/// filled in from `built` (in file order).
std::vector<Command> scene_inputs_at(const BuiltScene& built, const Scene& scene, int64_t tick);
/// Applies the scene's inputs for `tick` (apply_command); stops at the first
/// refusal and returns it prefixed with the input's JSON pointer and tick.
Status apply_scene_inputs(const BuiltScene& built, const Scene& scene, int64_t tick);

/// The scene's bodies as create_body commands, in order, then its joints as
/// create_joint commands (applying them to a fresh world made from
/// Scene::world gives the same world as build_world).
std::vector<Command> scene_create_commands(const Scene& scene);

/// Every key the loader accepts (for the documentation test).
std::vector<std::string> scene_format_keys();

}  // namespace tandem::scene
