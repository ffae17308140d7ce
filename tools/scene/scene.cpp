// scene.cpp — the scene reader (JsonValue tree → Scene), generators, and
// building a world. See scene.h and docs/scene-format.md.
//
// The reader throws SceneError internally (tools code, never across the
// public functions, which return Result/Status) so that each field read is
// one line. Key lists are tables at the top: the reader refuses keys not in
// them, and scene_format_keys() hands them to the documentation test.
#include "scene.h"

#include "fixed/splitmix64.h"

#include <algorithm>
#include <array>
#include <fstream>
#include <sstream>

#include "fixed/fixed_math.h"
#include "json_tree.h"
#include "scene_read.h"

namespace tandem::scene {
namespace {

using namespace detail;

// --- shapes -------------------------------------------------------------------
void read_shape_material(const Obj& o, ShapeDef* def) {
  opt(o, "friction", [&](const JsonValue& v, const std::string& p) { def->friction = read_q32(v, p); });
  opt(o, "restitution", [&](const JsonValue& v, const std::string& p) { def->restitution = read_q32(v, p); });
  opt(o, "density", [&](const JsonValue& v, const std::string& p) { def->density = read_q32(v, p); });
  opt(o, "sensor", [&](const JsonValue& v, const std::string& p) { def->is_sensor = read_bool(v, p); });
  opt(o, "hit_events", [&](const JsonValue& v, const std::string& p) { def->enable_hit_events = read_bool(v, p); });
  opt(o, "user_data", [&](const JsonValue& v, const std::string& p) { def->user_data = read_u64(v, p); });
  opt(o, "filter", [&](const JsonValue& v, const std::string& p) {
    Obj f(v, p, {&k_filter_keys});
    opt(f, "category", [&](const JsonValue& w, const std::string& q) { def->filter.category_bits = read_u64(w, q); });
    opt(f, "mask", [&](const JsonValue& w, const std::string& q) { def->filter.mask_bits = read_u64(w, q); });
    opt(f, "group", [&](const JsonValue& w, const std::string& q) {
      def->filter.group_index = static_cast<int32_t>(read_int(w, q, INT32_MIN, INT32_MAX));
    });
  });
}

void check_geometry(const Status& status, const std::string& path) {
  if (!status.ok()) fail(path, status.message);
}

ShapeSpec read_shape(const JsonValue& v, const std::string& path) {
  if (v.kind != JsonValue::Kind::object) fail(path, "expected an object, " + got(v));
  const std::vector<std::string> kinds = {"circle", "capsule", "box", "polygon", "segment", "chain"};
  std::string kind;
  for (size_t i = 0; i < v.keys.size(); ++i)
    if (v.keys[i] == "type") kind = read_enum(v.items[i], path + "/type", kinds);
  if (kind.empty()) fail(path, "missing key \"type\" (one of " + quoted_list(kinds) + ")");
  const std::vector<std::string>* specific = kind == "circle"    ? &k_circle_keys
                                             : kind == "capsule" ? &k_capsule_keys
                                             : kind == "box"     ? &k_box_keys
                                             : kind == "polygon" ? &k_polygon_keys
                                             : kind == "segment" ? &k_segment_keys
                                                                 : &k_chain_keys;
  Obj o(v, path, {&k_shape_common_keys, specific});
  ShapeSpec s;
  read_shape_material(o, &s.def);
  auto vec_or = [&](const char* key, Vec2 fallback) {
    const JsonValue* f = o.find(key);
    return f ? read_vec2(*f, o.at(key)) : fallback;
  };
  auto q_or = [&](const char* key, Q32 fallback) {
    const JsonValue* f = o.find(key);
    return f ? read_q32(*f, o.at(key)) : fallback;
  };
  if (kind == "circle") {
    s.kind = ShapeKind::circle;
    s.circle = Circle{vec_or("center", Vec2{}), read_q32(o.need("radius"), o.at("radius"))};
    check_geometry(validate_circle(s.circle), path);
  } else if (kind == "capsule") {
    s.kind = ShapeKind::capsule;
    s.capsule = Capsule{read_vec2(o.need("center1"), o.at("center1")), read_vec2(o.need("center2"), o.at("center2")),
                        read_q32(o.need("radius"), o.at("radius"))};
    check_geometry(validate_capsule(s.capsule), path);
  } else if (kind == "box") {
    s.kind = ShapeKind::polygon;
    const Q32 hw = read_q32(o.need("half_width"), o.at("half_width"));
    const Q32 hh = read_q32(o.need("half_height"), o.at("half_height"));
    check_geometry(make_offset_box(hw, hh, vec_or("center", Vec2{}), q_or("angle", Q32{}), q_or("radius", Q32{}),
                                   &s.polygon),
                   path);
  } else if (kind == "polygon") {
    s.kind = ShapeKind::polygon;
    const std::vector<Vec2> points =
        read_points(o.need("points"), o.at("points"), 3, static_cast<size_t>(k_max_hull_input_points));
    check_geometry(make_polygon_from_points(points.data(), static_cast<int32_t>(points.size()), q_or("radius", Q32{}),
                                            &s.polygon),
                   path);
  } else if (kind == "segment") {
    s.kind = ShapeKind::segment;
    s.segment = Segment{read_vec2(o.need("point1"), o.at("point1")), read_vec2(o.need("point2"), o.at("point2"))};
    check_geometry(validate_segment(s.segment), path);
  } else {
    s.kind = ShapeKind::chain;
    s.chain_points = read_points(o.need("points"), o.at("points"), 3, 1u << 20);
    if (const JsonValue* f = o.find("loop")) s.chain_loop = read_bool(*f, o.at("loop"));
    if (!s.chain_loop && s.chain_points.size() < 4)
      fail(o.at("points"), "an open chain needs at least 4 points (the first and last are ghost vertices)");
  }
  return s;
}

// --- bodies -------------------------------------------------------------------
// Reads body fields into *body. A template (generators) may not carry a name.
void read_body_into(const JsonValue& v, const std::string& path, SceneBody* body, bool is_template) {
  Obj o(v, path, {&k_body_keys});
  BodyDef& d = body->def;
  body->path = path;
  opt(o, "name", [&](const JsonValue& w, const std::string& p) {
    if (is_template) fail(p, "a generator's body template cannot have a name");
    body->name = read_string(w, p);
  });
  opt(o, "type", [&](const JsonValue& w, const std::string& p) {
    const std::string t = read_enum(w, p, {"static", "kinematic", "dynamic"});
    d.type = t == "static" ? BodyType::static_body : t == "kinematic" ? BodyType::kinematic_body : BodyType::dynamic_body;
  });
  opt(o, "position", [&](const JsonValue& w, const std::string& p) { d.position = read_vec2(w, p); });
  opt(o, "angle", [&](const JsonValue& w, const std::string& p) { d.rotation = rot_from_angle(read_q32(w, p)); });
  opt(o, "linear_velocity", [&](const JsonValue& w, const std::string& p) { d.linear_velocity = read_vec2(w, p); });
  opt(o, "angular_velocity", [&](const JsonValue& w, const std::string& p) { d.angular_velocity = read_q32(w, p); });
  opt(o, "linear_damping", [&](const JsonValue& w, const std::string& p) { d.linear_damping = read_q32(w, p); });
  opt(o, "angular_damping", [&](const JsonValue& w, const std::string& p) { d.angular_damping = read_q32(w, p); });
  opt(o, "gravity_scale", [&](const JsonValue& w, const std::string& p) { d.gravity_scale = read_q32(w, p); });
  opt(o, "user_data", [&](const JsonValue& w, const std::string& p) { d.user_data = read_u64(w, p); });
  opt(o, "sleep", [&](const JsonValue& w, const std::string& p) { d.enable_sleep = read_bool(w, p); });
  opt(o, "awake", [&](const JsonValue& w, const std::string& p) { d.is_awake = read_bool(w, p); });
  opt(o, "fixed_rotation", [&](const JsonValue& w, const std::string& p) { d.fixed_rotation = read_bool(w, p); });
  opt(o, "bullet", [&](const JsonValue& w, const std::string& p) { d.is_bullet = read_bool(w, p); });
  opt(o, "enabled", [&](const JsonValue& w, const std::string& p) { d.is_enabled = read_bool(w, p); });
  opt(o, "shapes", [&](const JsonValue& w, const std::string& p) {
    const auto& items = read_array(w, p);
    for (size_t i = 0; i < items.size(); ++i) {
      const std::string sp = p + "/" + std::to_string(i);
      body->shapes.push_back(read_shape(items[i], sp));
      body->shape_paths.push_back(sp);
    }
  });
}

// --- generators ---------------------------------------------------------------
// splitmix64 (Steele, Lea, Flood 2014): fully specified, so every platform
// draws the same numbers.
struct SplitMix64 {
  uint64_t state;
  uint64_t next() {
    return splitmix64_next(&state);
  }
  // A value in [lo, hi] (raw units; modulo draw, a bias below 2^-30 here).
  Q32 between(Q32 lo, Q32 hi) {
    const uint64_t span = static_cast<uint64_t>(hi.raw) - static_cast<uint64_t>(lo.raw);
    const uint64_t r = span == UINT64_MAX ? next() : next() % (span + 1);
    return Q32::from_raw(static_cast<int64_t>(static_cast<uint64_t>(lo.raw) + r));
  }
};

// Generated coordinates are computed on raw values with overflow checks: a
// far-out origin or spacing is an error naming the generator, never a
// saturation (which stops debug builds).
Q32 checked_mul(Q32 v, int64_t n, const std::string& path) {
  int64_t r = 0;
  if (__builtin_mul_overflow(v.raw, n, &r)) fail(path, "generated coordinates leave the Q32.32 range");
  return Q32::from_raw(r);
}
Q32 checked_add(Q32 a, Q32 b, const std::string& path) {
  int64_t r = 0;
  if (__builtin_add_overflow(a.raw, b.raw, &r)) fail(path, "generated coordinates leave the Q32.32 range");
  return Q32::from_raw(r);
}
Vec2 checked_add(Vec2 a, Vec2 b, const std::string& path) {
  return Vec2{checked_add(a.x, b.x, path), checked_add(a.y, b.y, path)};
}

SceneBody template_body(const Obj& g, bool required) {
  SceneBody t;
  if (const JsonValue* b = g.find("body")) read_body_into(*b, g.at("body"), &t, true);
  else if (required) fail(g.path(), "missing key \"body\" (the body template)");
  return t;
}

void place_copy(const SceneBody& t, Vec2 offset, const std::string& path, std::vector<SceneBody>* out) {
  SceneBody b = t;
  b.def.position = checked_add(b.def.position, offset, path);
  b.path = path;  // the generator; shape_paths stay the template's (/generators/N/body/shapes/M)
  out->push_back(std::move(b));
}

void expand_grid(const Obj& g, std::vector<SceneBody>* out) {
  const SceneBody t = template_body(g, true);
  const Vec2 origin = g.find("origin") ? read_vec2(*g.find("origin"), g.at("origin")) : Vec2{};
  const int64_t cols = read_int(g.need("columns"), g.at("columns"), 1, 1000000);
  const int64_t rows = read_int(g.need("rows"), g.at("rows"), 1, 1000000);
  const Vec2 spacing = read_vec2(g.need("spacing"), g.at("spacing"));
  for (int64_t r = 0; r < rows; ++r)
    for (int64_t c = 0; c < cols; ++c)
      place_copy(t,
                 checked_add(origin, Vec2{checked_mul(spacing.x, c, g.path()), checked_mul(spacing.y, r, g.path())},
                             g.path()),
                 g.path(), out);
}

void expand_pyramid(const Obj& g, std::vector<SceneBody>* out) {
  const SceneBody t = template_body(g, true);
  const Vec2 origin = g.find("origin") ? read_vec2(*g.find("origin"), g.at("origin")) : Vec2{};
  const int64_t base = read_int(g.need("base"), g.at("base"), 1, 1000);
  const Vec2 spacing = read_vec2(g.need("spacing"), g.at("spacing"));
  for (int64_t r = 0; r < base; ++r)
    for (int64_t c = 0; c < base - r; ++c)
      place_copy(t,
                 checked_add(origin,
                             Vec2{checked_add(checked_mul(spacing.x, c, g.path()), checked_mul(spacing.x, r, g.path()) / 2,
                                              g.path()),
                                  checked_mul(spacing.y, r, g.path())},
                             g.path()),
                 g.path(), out);
}

void expand_random(const Obj& g, std::vector<SceneBody>* out) {
  SceneBody t = template_body(g, false);
  if (!g.find("body")) t.def.type = BodyType::dynamic_body;
  if (!t.shapes.empty()) fail(g.at("body") + "/shapes", "the random generator makes the shapes itself (see \"kinds\")");
  ShapeDef material = default_shape_def();
  if (const JsonValue* s = g.find("shape")) {
    static const std::vector<std::string> material_keys = {"friction",   "restitution", "density", "filter",
                                                           "sensor",     "hit_events",  "user_data", "comment"};
    Obj so(*s, g.at("shape"), {&material_keys});
    read_shape_material(so, &material);
  }
  const uint64_t seed = g.find("seed") ? read_u64(*g.find("seed"), g.at("seed")) : 0;
  const int64_t count = read_int(g.need("count"), g.at("count"), 0, 1000000);
  const AABB region = read_box(g.need("region"), g.at("region"));
  std::vector<std::string> kinds = {"circle"};
  if (const JsonValue* k = g.find("kinds")) {
    kinds.clear();
    const auto& items = read_array(*k, g.at("kinds"));
    if (items.empty()) fail(g.at("kinds"), "expected at least one kind");
    for (size_t i = 0; i < items.size(); ++i)
      kinds.push_back(read_enum(items[i], g.at("kinds") + "/" + std::to_string(i), {"circle", "box", "capsule"}));
  }
  const Q32 size_min = read_q32_min(g.need("size_min"), g.at("size_min"), Q32{}, true);
  const Q32 size_max = read_q32_min(g.need("size_max"), g.at("size_max"), size_min, false);
  if (size_max > k_max_shape_size) fail(g.at("size_max"), "expected at most " + to_string(k_max_shape_size) + " m");
  const Q32 speed = g.find("speed") ? read_q32_min(*g.find("speed"), g.at("speed"), Q32{}, false) : Q32{};
  // Jittered grid: one cell per body, 2.2 × size_max wide, filled row by row
  // from region.lower, so no two bodies start overlapping.
  const Q32 cell = size_max * 2 + size_max / 5;
  const Q32 width = checked_add(region.upper.x, -region.lower.x, g.at("region"));
  const Q32 height = checked_add(region.upper.y, -region.lower.y, g.at("region"));
  const int64_t cols = width.raw / cell.raw, rows = height.raw / cell.raw;  // floor: both positive
  if (cols < 1 || rows < 1 || (count > 0 && rows < (count + cols - 1) / cols))
    fail(g.path(), "count " + std::to_string(count) + " does not fit: the region holds at most " +
                       std::to_string(std::max<int64_t>(0, cols) * std::max<int64_t>(0, rows)) +  // < 10^12 when it fails
                       " bodies of size_max " + to_string(size_max));
  SplitMix64 rng{seed};
  for (int64_t i = 0; i < count; ++i) {
    // Draw order (documented): kind, size, jitter x, jitter y, angle, direction.
    const std::string& kind = kinds[static_cast<size_t>(rng.next() % kinds.size())];
    const Q32 size = rng.between(size_min, size_max);
    const Q32 slack = cell / 2 - size;
    const Q32 jx = rng.between(-slack, slack), jy = rng.between(-slack, slack);
    const Q32 angle = rng.between(-k_pi, k_pi);
    const Q32 direction = rng.between(-k_pi, k_pi);
    SceneBody b = t;
    b.path = g.path();
    b.def.position = Vec2{region.lower.x + cell * (i % cols) + cell / 2 + jx, region.lower.y + cell * (i / cols) + cell / 2 + jy};
    ShapeSpec s;
    s.def = material;
    if (kind == "circle") {
      s.kind = ShapeKind::circle;
      s.circle = Circle{Vec2{}, size};
    } else if (kind == "box") {
      s.kind = ShapeKind::polygon;
      const Q32 half = size * 7 / 10;  // the box fits inside the size circle
      check_geometry(make_box(half, half, &s.polygon), g.path());
      b.def.rotation = rot_from_angle(angle);
    } else {
      s.kind = ShapeKind::capsule;
      const Q32 half = size / 2;
      s.capsule = Capsule{Vec2{-half, Q32{}}, Vec2{half, Q32{}}, half};
      b.def.rotation = rot_from_angle(angle);
    }
    if (speed > Q32{}) {
      const Rot d = rot_from_angle(direction);
      b.def.linear_velocity = Vec2{d.c * speed, d.s * speed};
    }
    b.shapes.push_back(s);
    b.shape_paths.push_back(g.path());
    out->push_back(std::move(b));
  }
}

// What a generator asks for, read from its parameters alone (nothing is
// expanded): bodies, and shapes per body (the template's "shapes" array, a
// chain counting one per point; the random generator makes one). Parameters
// are checked as expansion checks them, so an error names the same key
// either way.
struct GeneratorSize {
  std::string type;
  std::string detail;  // "1000 columns × 1000 rows = ", for the error message
  int64_t bodies = 0;
  int64_t shapes_per_body = 0;
};

std::string generator_type(const JsonValue& v, const std::string& path) {
  if (v.kind != JsonValue::Kind::object) fail(path, "expected an object, " + got(v));
  std::string type;
  for (size_t i = 0; i < v.keys.size(); ++i)
    if (v.keys[i] == "type") type = read_enum(v.items[i], path + "/type", {"grid", "pyramid", "random"});
  if (type.empty()) fail(path, "missing key \"type\" (one of \"grid\", \"pyramid\" or \"random\")");
  return type;
}

// What one shape of a template costs against max_shapes: a chain one per
// point (each point pair becomes a segment), anything else 1.
int64_t shape_weight(const JsonValue& shape) {
  if (shape.kind != JsonValue::Kind::object) return 1;
  for (size_t i = 0; i < shape.keys.size(); ++i)
    if (shape.keys[i] == "points" && shape.items[i].kind == JsonValue::Kind::array) {
      for (size_t t = 0; t < shape.keys.size(); ++t)
        if (shape.keys[t] == "type" && shape.items[t].kind == JsonValue::Kind::string && shape.items[t].text == "chain")
          return std::max<int64_t>(1, static_cast<int64_t>(shape.items[i].items.size()));
    }
  return 1;
}

GeneratorSize generator_size(const JsonValue& v, const std::string& path) {
  GeneratorSize n;
  n.type = generator_type(v, path);
  auto need = [&](const char* key) -> const JsonValue& {
    for (size_t i = 0; i < v.keys.size(); ++i)
      if (v.keys[i] == key) return v.items[i];
    fail(path, std::string("missing key \"") + key + "\"");
  };
  if (n.type == "grid") {
    const int64_t cols = read_int(need("columns"), path + "/columns", 1, 1000000);
    const int64_t rows = read_int(need("rows"), path + "/rows", 1, 1000000);
    n.bodies = cols * rows;  // ≤ 10^12
    n.detail = std::to_string(cols) + " columns × " + std::to_string(rows) + " rows = ";
  } else if (n.type == "pyramid") {
    const int64_t base = read_int(need("base"), path + "/base", 1, 1000);
    n.bodies = base * (base + 1) / 2;
    n.detail = "base " + std::to_string(base) + ": ";
  } else {
    n.bodies = read_int(need("count"), path + "/count", 0, 1000000);
    n.detail = "count ";
  }
  if (n.type == "random") {
    n.shapes_per_body = 1;
  } else {
    for (size_t i = 0; i < v.keys.size(); ++i) {
      if (v.keys[i] != "body" || v.items[i].kind != JsonValue::Kind::object) continue;
      const JsonValue& body = v.items[i];
      for (size_t k = 0; k < body.keys.size(); ++k)
        if (body.keys[k] == "shapes" && body.items[k].kind == JsonValue::Kind::array)
          for (const JsonValue& shape : body.items[k].items) n.shapes_per_body += shape_weight(shape);
    }
  }
  return n;
}

// Refuses a scene whose bodies or shapes would pass `limits`, before any
// generator is expanded. `explicit_bodies` are already read (their JSON text
// holds them, so they cost no more than the text).
void check_scene_size(const std::vector<SceneBody>& explicit_bodies, const JsonValue* generators,
                      const std::string& generators_path, const SceneLimits& limits) {
  const int64_t max_bodies = std::clamp<int64_t>(limits.max_bodies, 0, k_max_bodies);
  const int64_t max_shapes = std::clamp<int64_t>(limits.max_shapes, 0, k_max_shapes);
  const std::string raise_bodies = " (raise it with --max-bodies or SceneLimits::max_bodies)";
  const std::string raise_shapes = " (raise it with --max-shapes or SceneLimits::max_shapes)";
  int64_t bodies = static_cast<int64_t>(explicit_bodies.size());
  int64_t shapes = 0;
  for (const SceneBody& b : explicit_bodies)
    for (const ShapeSpec& shape : b.shapes)
      shapes += shape.kind == ShapeKind::chain ? std::max<int64_t>(1, static_cast<int64_t>(shape.chain_points.size())) : 1;
  if (bodies > max_bodies)
    fail("/bodies", "the scene lists " + std::to_string(bodies) + " bodies; the limit is " +
                        std::to_string(max_bodies) + raise_bodies);
  if (shapes > max_shapes)
    fail("/bodies", "the scene's bodies have " + std::to_string(shapes) + " shapes; the limit is " +
                        std::to_string(max_shapes) + raise_shapes);
  if (generators == nullptr) return;
  const auto& items = read_array(*generators, generators_path);
  for (size_t i = 0; i < items.size(); ++i) {
    const std::string path = generators_path + "/" + std::to_string(i);
    const GeneratorSize n = generator_size(items[i], path);
    if (n.bodies > max_bodies - bodies)
      fail(path, "the " + n.type + " generator asks for " + n.detail + std::to_string(n.bodies) + " bodies, " +
                     (bodies > 0 ? "on top of " + std::to_string(bodies) + " before it, " : std::string()) +
                     "over the limit of " + std::to_string(max_bodies) + " bodies per scene" + raise_bodies);
    bodies += n.bodies;
    // n.bodies ≤ k_max_bodies (2^24) and shapes_per_body < 2^31 (an array in
    // the text): the product fits.
    const int64_t more = n.bodies * n.shapes_per_body;
    if (more > max_shapes - shapes)
      fail(path, "the " + n.type + " generator asks for " + std::to_string(n.bodies) + " bodies × " +
                     std::to_string(n.shapes_per_body) + " shapes = " + std::to_string(more) + " shapes, " +
                     (shapes > 0 ? "on top of " + std::to_string(shapes) + " before it, " : std::string()) +
                     "over the limit of " + std::to_string(max_shapes) + " shapes per scene" + raise_shapes);
    shapes += more;
  }
}

void read_generator(const JsonValue& v, const std::string& path, std::vector<SceneBody>* out) {
  const std::string type = generator_type(v, path);
  if (type == "grid") expand_grid(Obj(v, path, {&k_generator_grid_keys}), out);
  else if (type == "pyramid") expand_pyramid(Obj(v, path, {&k_generator_pyramid_keys}), out);
  else expand_random(Obj(v, path, {&k_generator_random_keys}), out);
}

// --- world, inputs --------------------------------------------------------------
void read_world(const JsonValue& v, const std::string& path, WorldDef* w) {
  Obj o(v, path, {&k_world_keys});
  opt(o, "gravity", [&](const JsonValue& x, const std::string& p) { w->gravity = read_vec2(x, p); });
  opt(o, "sub_steps", [&](const JsonValue& x, const std::string& p) {
    w->sub_step_count = static_cast<int32_t>(read_int(x, p, 1, k_max_sub_steps));
  });
  opt(o, "contact_hertz", [&](const JsonValue& x, const std::string& p) { w->contact_hertz = read_q32(x, p); });
  opt(o, "contact_damping_ratio",
      [&](const JsonValue& x, const std::string& p) { w->contact_damping_ratio = read_q32(x, p); });
  opt(o, "max_contact_push_speed",
      [&](const JsonValue& x, const std::string& p) { w->max_contact_push_speed = read_q32(x, p); });
  opt(o, "joint_hertz", [&](const JsonValue& x, const std::string& p) { w->joint_hertz = read_q32(x, p); });
  opt(o, "joint_damping_ratio",
      [&](const JsonValue& x, const std::string& p) { w->joint_damping_ratio = read_q32(x, p); });
  opt(o, "restitution_threshold",
      [&](const JsonValue& x, const std::string& p) { w->restitution_threshold = read_q32(x, p); });
  opt(o, "hit_event_threshold",
      [&](const JsonValue& x, const std::string& p) { w->hit_event_threshold = read_q32(x, p); });
  opt(o, "max_linear_speed", [&](const JsonValue& x, const std::string& p) { w->max_linear_speed = read_q32(x, p); });
  opt(o, "bounds", [&](const JsonValue& x, const std::string& p) { w->bounds = read_box(x, p); });
  opt(o, "sleep", [&](const JsonValue& x, const std::string& p) { w->enable_sleep = read_bool(x, p); });
  opt(o, "user_data", [&](const JsonValue& x, const std::string& p) { w->user_data = read_u64(x, p); });
  opt(o, "broad_phase", [&](const JsonValue& x, const std::string& p) {
    const std::string b = read_enum(x, p, {"naive", "sweep_and_prune", "grid", "tree"});
    w->broad_phase = b == "naive"             ? BroadPhaseKind::naive
                     : b == "sweep_and_prune" ? BroadPhaseKind::sweep_and_prune
                     : b == "grid"            ? BroadPhaseKind::grid
                                              : BroadPhaseKind::tree;
  });
}

Scene read_scene(const JsonValue& root, const SceneLimits& limits) {
  Obj o(root, "", {&k_top_keys});
  Scene s;
  opt(o, "format", [&](const JsonValue& v, const std::string& p) { read_enum(v, p, {k_scene_format}); });
  opt(o, "version", [&](const JsonValue& v, const std::string& p) { read_int(v, p, 1, k_scene_version); });
  opt(o, "name", [&](const JsonValue& v, const std::string& p) { s.title = read_string(v, p); });
  opt(o, "description", [&](const JsonValue& v, const std::string& p) { s.description = read_string(v, p); });
  opt(o, "comment", [&](const JsonValue&, const std::string&) {});
  opt(o, "step_hz", [&](const JsonValue& v, const std::string& p) { s.step_hz = static_cast<int32_t>(read_int(v, p, 1, 10000)); });
  s.time_step = Q32::from_ratio(1, s.step_hz);
  opt(o, "ticks", [&](const JsonValue& v, const std::string& p) { s.ticks = read_int(v, p, 0, INT64_C(1) << 40); });
  opt(o, "view", [&](const JsonValue& v, const std::string& p) {
    s.view = read_box(v, p);
    s.has_view = true;
  });
  opt(o, "world", [&](const JsonValue& v, const std::string& p) { read_world(v, p, &s.world); });
  opt(o, "bodies", [&](const JsonValue& v, const std::string& p) {
    const auto& items = read_array(v, p);
    for (size_t i = 0; i < items.size(); ++i) {
      SceneBody b;
      read_body_into(items[i], p + "/" + std::to_string(i), &b, false);
      if (!b.name.empty())
        for (const SceneBody& other : s.bodies)
          if (other.name == b.name) fail(p + "/" + std::to_string(i) + "/name", "duplicate body name \"" + b.name + "\"");
      s.bodies.push_back(std::move(b));
    }
  });
  check_scene_size(s.bodies, o.find("generators"), o.at("generators"), limits);
  opt(o, "generators", [&](const JsonValue& v, const std::string& p) {
    const auto& items = read_array(v, p);
    for (size_t i = 0; i < items.size(); ++i) read_generator(items[i], p + "/" + std::to_string(i), &s.bodies);
  });
  opt(o, "joints", [&](const JsonValue& v, const std::string& p) {
    const auto& items = read_array(v, p);
    for (size_t i = 0; i < items.size(); ++i) s.joints.push_back(read_joint(items[i], p + "/" + std::to_string(i), s.bodies));
  });
  opt(o, "inputs", [&](const JsonValue& v, const std::string& p) {
    const auto& items = read_array(v, p);
    for (size_t i = 0; i < items.size(); ++i) s.inputs.push_back(read_input(items[i], p + "/" + std::to_string(i), s.bodies, s.joints.size()));
  });
  std::stable_sort(s.inputs.begin(), s.inputs.end(),
                   [](const SceneInput& a, const SceneInput& b) { return a.tick < b.tick; });
  return s;
}

Status error_status(std::string message) { return Status{StatusCode::invalid_argument, std::move(message)}; }

}  // namespace

Result<Scene> load_scene_text(std::string_view text, const std::string& name, const SceneLimits& limits) {
  Result<Scene> out;
  JsonParse parsed = parse_json_tree(text);
  if (!parsed.ok()) {
    out.status = error_status(name + ": " + parsed.error);
    return out;
  }
  try {
    out.value = read_scene(parsed.value, limits);
  } catch (const SceneError& e) {
    out.status = error_status(name + ": " + e.message);
    return out;
  }
  out.value.name = name;
  return out;
}

Result<Scene> load_scene_file(const std::string& path, const SceneLimits& limits) {
  std::ifstream file(path, std::ios::binary);
  if (!file) {
    Result<Scene> out;
    out.status = error_status(path + ": cannot open the file");
    return out;
  }
  std::ostringstream text;
  text << file.rdbuf();
  if (file.bad()) {
    Result<Scene> out;
    out.status = error_status(path + ": cannot read the file");
    return out;
  }
  return load_scene_text(text.str(), path, limits);
}

Result<BuiltScene> build_world(const Scene& scene) {
  Result<BuiltScene> out;
  Result<WorldId> world = create_world(scene.world);
  if (!world.ok()) {
    out.status = error_status(scene.name + ": /world: " + world.status.message);
    return out;
  }
  BuiltScene built;
  built.world = world.value;
  auto refuse = [&](const std::string& path, const Status& status) {
    (void)destroy_world(built.world);  // created above: cannot fail
    out.status = error_status(scene.name + ": " + show_path(path) + ": " + status.message);
    return out;
  };
  for (const SceneBody& b : scene.bodies) {
    Result<BodyId> body = create_body(built.world, b.def);
    if (!body.ok()) return refuse(b.path, body.status);
    for (size_t i = 0; i < b.shapes.size(); ++i) {
      const ShapeSpec& s = b.shapes[i];
      Status status;
      switch (s.kind) {
        case ShapeKind::circle: status = create_circle_shape(body.value, s.def, s.circle).status; break;
        case ShapeKind::capsule: status = create_capsule_shape(body.value, s.def, s.capsule).status; break;
        case ShapeKind::segment: status = create_segment_shape(body.value, s.def, s.segment).status; break;
        case ShapeKind::polygon: status = create_polygon_shape(body.value, s.def, s.polygon).status; break;
        case ShapeKind::chain:
          status = create_chain_shapes(body.value, s.def, s.chain_points.data(),
                                       static_cast<int32_t>(s.chain_points.size()), s.chain_loop, nullptr);
          break;
      }
      if (!status.ok()) return refuse(i < b.shape_paths.size() ? b.shape_paths[i] : b.path, status);
    }
    built.bodies.push_back(body.value);
  }
  for (const SceneJoint& j : scene.joints) {
    JointSpec spec = j.spec;
    spec.body_a = body_ref(built.bodies[static_cast<size_t>(j.body_a)]);
    spec.body_b = body_ref(built.bodies[static_cast<size_t>(j.body_b)]);
    const Status status = apply_command(built.world, make_create_joint(spec));
    if (!status.ok()) return refuse(j.path, status);
  }
  out.value = std::move(built);
  return out;
}

std::vector<Command> scene_inputs_at(const BuiltScene& built, const Scene& scene, int64_t tick) {
  std::vector<Command> out;
  auto it = std::lower_bound(scene.inputs.begin(), scene.inputs.end(), tick,
                             [](const SceneInput& in, int64_t t) { return in.tick < t; });
  for (; it != scene.inputs.end() && it->tick == tick; ++it) {
    Command c = it->command;
    if (it->body >= 0 && static_cast<size_t>(it->body) < built.bodies.size())
      c.body = body_ref(built.bodies[static_cast<size_t>(it->body)]);
    out.push_back(std::move(c));
  }
  return out;
}

Status apply_scene_inputs(const BuiltScene& built, const Scene& scene, int64_t tick) {
  auto it = std::lower_bound(scene.inputs.begin(), scene.inputs.end(), tick,
                             [](const SceneInput& in, int64_t t) { return in.tick < t; });
  const std::vector<Command> commands = scene_inputs_at(built, scene, tick);
  for (const Command& c : commands) {
    const Status status = apply_command(built.world, c);
    if (!status.ok())
      return error_status(scene.name + ": " + it->path + " (tick " + std::to_string(tick) + "): " + status.message);
    ++it;
  }
  return {};
}

std::vector<Command> scene_create_commands(const Scene& scene) {
  std::vector<Command> out;
  out.reserve(scene.bodies.size());
  for (const SceneBody& b : scene.bodies) out.push_back(make_create_body(b.def, b.shapes));
  // Then the joints: a fresh world gives body i the ref {i, 1}.
  for (const SceneJoint& j : scene.joints) {
    JointSpec spec = j.spec;
    spec.body_a = BodyRef{static_cast<uint32_t>(j.body_a), 1};
    spec.body_b = BodyRef{static_cast<uint32_t>(j.body_b), 1};
    out.push_back(make_create_joint(spec));
  }
  return out;
}

std::vector<std::string> scene_format_keys() {
  std::vector<std::string> out;
  for (const auto* list : {&k_top_keys, &k_view_keys, &k_world_keys, &k_body_keys, &k_shape_common_keys,
                           &k_circle_keys, &k_capsule_keys, &k_box_keys, &k_polygon_keys, &k_segment_keys,
                           &k_chain_keys, &k_filter_keys, &k_generator_grid_keys, &k_generator_pyramid_keys,
                           &k_generator_random_keys, &k_input_common_keys, &k_input_value_keys, &k_joint_keys,
                           &k_names})
    out.insert(out.end(), list->begin(), list->end());
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace tandem::scene
