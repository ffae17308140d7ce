// tandem_web.cpp — the web page's glue: a C interface (exported from the
// Emscripten module tandem_web.js / .wasm) over one current world, made from
// a scene file (tools/scene) or a replay file (replay/). tools/web/tandem.js
// wraps it for the page.
//
// Everything the simulation sees comes through the same code the `tandem`
// command line runs: load_scene_text + build_world + apply_scene_inputs +
// world_step for a scene (as `tandem run`), read_replay + run_tick /
// Replay::seek / verify_replay for a replay (as `tandem replay` / `verify`),
// and world_state_hash for the hash. Error texts are the CLI's (after its
// "tandem run: " prefix): the file name, then the JSON pointer or byte offset.
//
// Binary floating point appears only at this edge: drawing coordinates
// (world_draw's Q32 → double) and the statistics of tw_info(). Nothing
// converted here flows back into a world.
//
// Strings returned point into static buffers valid until the next call of
// the same function. Single-threaded (the page calls from its main thread).
#include <emscripten/emscripten.h>

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "physics/debug_draw.h"
#include "physics/tandem.h"
#include "replay/replay_file.h"
#include "replay/state.h"
#include "replay/verify.h"
#include "scene/scene.h"

using namespace tandem;

namespace {

enum class Mode { none, scene, replay };

struct Current {
  Mode mode = Mode::none;
  std::string name;
  scene::Scene scene;           // Mode::scene
  scene::BuiltScene built;      // Mode::scene (built.world is the world)
  Replay replay;                // Mode::replay
  bool has_view = false;        // the scene's "view" (a replay: its embedded scene's, if it parses)
  AABB view;
  WorldId world{};
  int64_t tick = 0;
  Q32 time_step;
};

Current g_current;
std::string g_error;
std::string g_text;
std::vector<double> g_draw;

void destroy_current() {
  if (world_is_valid(g_current.world)) (void)destroy_world(g_current.world);
  g_current = Current{};
}

int fail(const std::string& message) {
  g_error = message;
  return 2;
}

BroadPhaseKind broad_phase_of(int32_t code, BroadPhaseKind fallback) {
  switch (code) {
    case 0: return BroadPhaseKind::naive;
    case 1: return BroadPhaseKind::sweep_and_prune;
    case 2: return BroadPhaseKind::grid;
    case 3: return BroadPhaseKind::tree;
    default: return fallback;
  }
}

const char* broad_phase_name(BroadPhaseKind k) {
  switch (k) {
    case BroadPhaseKind::naive: return "naive";
    case BroadPhaseKind::sweep_and_prune: return "sap";
    case BroadPhaseKind::grid: return "grid";
    case BroadPhaseKind::tree: return "tree";
  }
  return "?";
}

std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\') out += '\\', out += c;
    else if (static_cast<unsigned char>(c) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", static_cast<unsigned>(c));
      out += buf;
    } else out += c;
  }
  return out + "\"";
}

// --- drawing: world_draw callbacks append to g_draw (see tandem.js for the layout)
double d(Q32 v) { return v.to_double(); }
void put(std::initializer_list<double> values) { g_draw.insert(g_draw.end(), values); }
double state_code(const DrawShape& s) { return static_cast<double>(static_cast<int32_t>(s.state)); }

void on_polygon(const Vec2* v, int32_t count, Q32 radius, const DrawShape& s, void*) {
  put({1, state_code(s), s.sensor ? 1.0 : 0.0, static_cast<double>(count), d(radius)});
  for (int32_t i = 0; i < count; ++i) put({d(v[i].x), d(v[i].y)});
}
void on_circle(Vec2 c, Q32 r, Vec2 rim, const DrawShape& s, void*) {
  put({2, state_code(s), s.sensor ? 1.0 : 0.0, d(c.x), d(c.y), d(r), d(rim.x), d(rim.y)});
}
void on_capsule(Vec2 a, Vec2 b, Q32 r, const DrawShape& s, void*) {
  put({3, state_code(s), s.sensor ? 1.0 : 0.0, d(a.x), d(a.y), d(b.x), d(b.y), d(r)});
}
void on_segment(Vec2 a, Vec2 b, const DrawShape& s, void*) {
  put({4, state_code(s), s.sensor ? 1.0 : 0.0, d(a.x), d(a.y), d(b.x), d(b.y)});
}
void on_joint(JointId, JointType type, Vec2 oa, Vec2 a, Vec2 b, Vec2 ob, void*) {
  put({5, static_cast<double>(static_cast<int32_t>(type)), d(oa.x), d(oa.y), d(a.x), d(a.y), d(b.x), d(b.y), d(ob.x),
       d(ob.y)});
}
void on_contact(Vec2 p, Vec2 n, Q32 separation, void*) {
  put({6, d(p.x), d(p.y), d(n.x), d(n.y), d(separation)});
}
void on_aabb(const AABB& box, const DrawShape&, void*) {
  put({7, d(box.lower.x), d(box.lower.y), d(box.upper.x), d(box.upper.y)});
}

}  // namespace

extern "C" {

/// The message of the last failed call (empty if none failed yet).
EMSCRIPTEN_KEEPALIVE const char* tw_error() { return g_error.c_str(); }

/// Loads scene text (UTF-8, `size` bytes) named `name` (error messages start
/// with it) and builds its world, replacing the current one. broad_phase: 0
/// naive, 1 sap, 2 grid, 3 tree, anything else the scene's own. Returns 0,
/// or 2 with tw_error() set; the current world is kept on failure.
EMSCRIPTEN_KEEPALIVE int tw_load_scene(const char* text, int32_t size, const char* name, int32_t broad_phase) {
  if (size < 0) return fail(std::string(name) + ": negative size");
  Result<scene::Scene> loaded = scene::load_scene_text(std::string_view(text, static_cast<size_t>(size)), name);
  if (!loaded.ok()) return fail(loaded.status.message);
  loaded.value.world.broad_phase = broad_phase_of(broad_phase, loaded.value.world.broad_phase);
  Result<scene::BuiltScene> built = scene::build_world(loaded.value);
  if (!built.ok()) return fail(built.status.message);
  destroy_current();
  g_current.mode = Mode::scene;
  g_current.name = name;
  g_current.scene = std::move(loaded.value);
  g_current.built = std::move(built.value);
  g_current.world = g_current.built.world;
  g_current.time_step = g_current.scene.time_step;
  g_current.has_view = g_current.scene.has_view;
  g_current.view = g_current.scene.view;
  return 0;
}

/// Loads a replay file image (`size` bytes) named `name` and puts a world in
/// its tick-0 state, replacing the current one. Returns 0, or 2 with
/// tw_error() set to the CLI's text ("name: offset N: ..."); the current
/// world is kept on failure.
EMSCRIPTEN_KEEPALIVE int tw_load_replay(const uint8_t* bytes, int32_t size, const char* name) {
  if (size < 0) return fail(std::string(name) + ": negative size");
  Replay replay;
  ReplayReadInfo info;
  Status s = read_replay(std::span<const uint8_t>(bytes, static_cast<size_t>(size)), &replay, &info);
  if (!s.ok()) return fail(std::string(name) + ": " + s.message);
  Result<WorldId> created = create_world_from_snapshot(replay.keyframes[0].state.data(), replay.keyframes[0].state.size());
  if (!created.ok()) return fail(std::string(name) + ": initial keyframe: " + created.status.message);
  destroy_current();
  g_current.mode = Mode::replay;
  g_current.name = name;
  g_current.world = created.value;
  g_current.time_step = replay.header.time_step;
  if (replay.header.has_scene_bytes) {  // the embedded scene's view, if it parses (as `tandem render`)
    const std::vector<uint8_t>& text = replay.header.scene_bytes;
    const Result<scene::Scene> embedded = scene::load_scene_text(
        std::string_view(reinterpret_cast<const char*>(text.data()), text.size()), name);
    if (embedded.ok() && embedded.value.has_view) g_current.has_view = true, g_current.view = embedded.value.view;
  }
  g_current.replay = std::move(replay);
  g_error = info.warning.empty() ? "" : std::string(name) + ": " + info.warning;
  return 0;
}

/// True when the first bytes are a replay file's magic.
EMSCRIPTEN_KEEPALIVE int tw_is_replay(const uint8_t* bytes, int32_t size) {
  return size > 0 && is_replay_image(std::span<const uint8_t>(bytes, static_cast<size_t>(size))) ? 1 : 0;
}

/// Steps the current world `count` times (scene: its scripted inputs, then
/// world_step; replay: the next recorded tick). Returns 0; 1 when a replay
/// ended (no step taken); 2 with tw_error() on a refusal or without a world.
EMSCRIPTEN_KEEPALIVE int tw_step(int32_t count) {
  for (int32_t i = 0; i < count; ++i) {
    switch (g_current.mode) {
      case Mode::none: return fail("no scene loaded");
      case Mode::scene: {
        const Status in = scene::apply_scene_inputs(g_current.built, g_current.scene, g_current.tick);
        if (!in.ok()) return fail(in.message);
        const StepResult r = world_step(g_current.world, g_current.time_step);
        if (!r.ok())
          return fail(g_current.name + ": step " + std::to_string(g_current.tick + 1) + " refused: " + r.status.message);
        break;
      }
      case Mode::replay: {
        if (g_current.tick >= static_cast<int64_t>(g_current.replay.tick_count())) return 1;
        const Status st = run_tick(g_current.world, g_current.replay.ticks[static_cast<size_t>(g_current.tick)],
                                   g_current.time_step);
        if (!st.ok()) return fail(g_current.name + ": tick " + std::to_string(g_current.tick + 1) + ": " + st.message);
        break;
      }
    }
    ++g_current.tick;
  }
  return 0;
}

/// Replay only: puts the world in its state after `tick` ticks (the nearest
/// keyframe, then the recorded ticks). Returns 0, or 2 with tw_error().
EMSCRIPTEN_KEEPALIVE int tw_seek(int32_t tick) {
  if (g_current.mode != Mode::replay) return fail("seek: only a replay can be scrubbed");
  if (tick < 0 || tick > g_current.replay.tick_count())
    return fail(g_current.name + ": tick " + std::to_string(tick) + " is outside 0.." +
                std::to_string(g_current.replay.tick_count()));
  const Status s = g_current.replay.seek(g_current.world, tick);
  if (!s.ok()) return fail(g_current.name + ": " + s.message);
  g_current.tick = tick;
  return 0;
}

/// Ticks stepped since the load (or the tick sought).
EMSCRIPTEN_KEEPALIVE double tw_tick() { return static_cast<double>(g_current.tick); }

/// world_state_hash of the current world as the CLI prints it (16 hex digits).
EMSCRIPTEN_KEEPALIVE const char* tw_hash() {
  g_text = world_is_valid(g_current.world) ? hash_text(world_state_hash(g_current.world)) : "";
  return g_text.c_str();
}

/// The replay's recorded hash after `tick` (1..count) as hex, or "" when none.
EMSCRIPTEN_KEEPALIVE const char* tw_recorded_hash(int32_t tick) {
  g_text.clear();
  if (g_current.mode == Mode::replay && tick >= 1 && tick <= g_current.replay.tick_count()) {
    const TickRecord& r = g_current.replay.tick_record(tick);
    if (r.has_hash) g_text = hash_text(r.hash);
  }
  return g_text.c_str();
}

/// Verifies the loaded replay (verify_replay, as `tandem verify`). Returns
/// 0 all matched, 1 mismatch, 2 could not run; tw_error() then holds the
/// report text (format_verify_report) or the error. The current world is
/// not touched.
EMSCRIPTEN_KEEPALIVE int tw_verify() {
  if (g_current.mode != Mode::replay) return fail("verify: no replay loaded");
  const VerifyReport rep = verify_replay(g_current.replay);
  const int rc = verify_exit_code(rep);
  g_error = rc == 2 ? g_current.name + ": " + rep.error.message : format_verify_report(rep);
  return rc;
}

/// Draws the current world into a buffer of doubles (layout in tandem.js)
/// and returns its length; tw_draw_buffer() is its address. flags: bit 0
/// AABBs, bit 1 contacts, bit 2 joints.
EMSCRIPTEN_KEEPALIVE int32_t tw_draw(int32_t flags) {
  g_draw.clear();
  if (!world_is_valid(g_current.world)) return 0;
  DebugDraw dd;
  dd.draw_aabbs = (flags & 1) != 0;
  dd.draw_contacts = (flags & 2) != 0;
  dd.draw_joints = (flags & 4) != 0;
  dd.draw_polygon = on_polygon;
  dd.draw_circle = on_circle;
  dd.draw_capsule = on_capsule;
  dd.draw_segment = on_segment;
  dd.draw_joint = on_joint;
  dd.draw_contact = on_contact;
  dd.draw_aabb = on_aabb;
  const Status s = world_draw(g_current.world, dd);
  if (!s.ok()) {
    fail(s.message);
    return 0;
  }
  return static_cast<int32_t>(g_draw.size());
}
/// The buffer tw_draw() filled.
EMSCRIPTEN_KEEPALIVE const double* tw_draw_buffer() { return g_draw.data(); }

/// A JSON object describing the current world: mode, name, title,
/// description, step_hz, scene ticks, replay ticks, counts (bodies, dynamic
/// bodies, shapes, joints), gravity (m/s²), broad phase, view (the scene's
/// or a replay's embedded scene's, else every shape's AABB within ±1000 m), the dynamic bodies' mean and
/// maximum speed (m/s), their circles' count and radius range (m) and their
/// shapes' mean restitution — binary floating point, display only.
EMSCRIPTEN_KEEPALIVE const char* tw_info() {
  const WorldId w = g_current.world;
  if (!world_is_valid(w)) {
    g_text = "{\"mode\": \"none\"}";
    return g_text.c_str();
  }
  const WorldCounters counters = world_counters(w);
  const int32_t body_count = world_bodies(w, nullptr, 0);
  std::vector<BodyId> bodies(static_cast<size_t>(body_count));
  world_bodies(w, bodies.data(), body_count);
  int32_t dynamic = 0;
  double speed_sum = 0, speed_max = 0;
  double radius_min = 0, radius_max = 0, restitution_sum = 0;
  int32_t circles = 0, dynamic_shapes = 0;
  double lx = 0, ly = 0, ux = 0, uy = 0;
  bool any = false;
  std::vector<ShapeId> shapes;
  for (const BodyId b : bodies) {
    if (body_type(b) == BodyType::dynamic_body) {
      const Vec2 v = body_linear_velocity(b);
      const double s = std::hypot(d(v.x), d(v.y));
      ++dynamic;
      speed_sum += s;
      speed_max = std::max(speed_max, s);
    }
    shapes.resize(static_cast<size_t>(body_shape_count(b)));
    body_shapes(b, shapes.data(), static_cast<int32_t>(shapes.size()));
    for (const ShapeId sh : shapes) {
      if (body_type(b) == BodyType::dynamic_body) {
        ++dynamic_shapes;
        restitution_sum += d(shape_restitution(sh));
        const ShapeGeometry g = shape_geometry(sh);
        if (g.type == ShapeType::circle) {
          const double r = d(g.circle.radius);
          radius_min = circles == 0 ? r : std::min(radius_min, r);
          radius_max = circles == 0 ? r : std::max(radius_max, r);
          ++circles;
        }
      }
      const AABB box = shape_aabb(sh);
      const double a = std::max(d(box.lower.x), -1000.0), bb = std::max(d(box.lower.y), -1000.0);
      const double c = std::min(d(box.upper.x), 1000.0), e = std::min(d(box.upper.y), 1000.0);
      if (a > c || bb > e) continue;
      if (!any) lx = a, ly = bb, ux = c, uy = e, any = true;
      lx = std::min(lx, a), ly = std::min(ly, bb), ux = std::max(ux, c), uy = std::max(uy, e);
    }
  }
  const bool scene_mode = g_current.mode == Mode::scene;
  if (g_current.has_view) {
    const AABB& v = g_current.view;
    lx = d(v.lower.x), ly = d(v.lower.y), ux = d(v.upper.x), uy = d(v.upper.y), any = true;
  }
  if (!any) lx = -10, ly = -10, ux = 10, uy = 10;
  const Vec2 gravity = world_gravity(w);
  char buf[1536];
  std::snprintf(buf, sizeof buf,
                "\"step_hz\": %.6f, \"scene_ticks\": %" PRId64 ", \"replay_ticks\": %" PRId64
                ", \"bodies\": %d, \"dynamic_bodies\": %d, \"shapes\": %d, \"joints\": %d, \"gravity\": [%.9g, %.9g], "
                "\"broad_phase\": \"%s\", \"view\": [%.9g, %.9g, %.9g, %.9g], \"mean_speed\": %.9g, \"max_speed\": %.9g, "
                "\"circles\": %d, \"radius_min\": %.9g, \"radius_max\": %.9g, \"mean_restitution\": %.9g}",
                1.0 / d(g_current.time_step), scene_mode ? g_current.scene.ticks : int64_t{0},
                g_current.mode == Mode::replay ? g_current.replay.tick_count() : int64_t{0}, counters.body_count, dynamic,
                counters.shape_count, counters.joint_count, d(gravity.x), d(gravity.y),
                broad_phase_name(world_def(w).broad_phase), lx, ly, ux, uy,
                dynamic > 0 ? speed_sum / dynamic : 0.0, speed_max, circles, radius_min, radius_max,
                dynamic_shapes > 0 ? restitution_sum / dynamic_shapes : 0.0);
  g_text = "{\"mode\": " + json_string(scene_mode ? "scene" : "replay") + ", \"name\": " + json_string(g_current.name) +
           ", \"title\": " + json_string(scene_mode ? g_current.scene.title : "") +
           ", \"description\": " + json_string(scene_mode ? g_current.scene.description : "") + ", " + buf;
  return g_text.c_str();
}

/// Allocates `size` bytes in the module's heap for passing text or files in
/// (free with tw_free).
EMSCRIPTEN_KEEPALIVE uint8_t* tw_alloc(int32_t size) { return new uint8_t[static_cast<size_t>(std::max(size, 1))]; }
/// Frees what tw_alloc returned.
EMSCRIPTEN_KEEPALIVE void tw_free(uint8_t* p) { delete[] p; }

}  // extern "C"
