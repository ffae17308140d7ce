// Scenes shared by the replay state and sync-test tests: five small worlds
// (to keep every-tick restores fast under sanitizers) and their per-tick
// inputs, which depend only on the world's state and the tick, so a world
// restored at any tick receives exactly the inputs the original did.
#pragma once

#include <catch2/catch.hpp>

#include <cstdint>
#include <string>
#include <vector>

#include "physics/collision.h"
#include "physics/tandem.h"

namespace tandem::replay_test {

using namespace tandem::literals;

/// The tick: the raw value nearest 1/60 s.
inline const Q32 k_dt = Q32::from_ratio(1, 60);

enum class Scene : int32_t { pile = 0, pyramid, elastic_crowd, filtered_sensors, create_destroy, count };

inline const char* scene_name(Scene s) {
  switch (s) {
    case Scene::pile: return "pile";
    case Scene::pyramid: return "pyramid";
    case Scene::elastic_crowd: return "elastic crowd";
    case Scene::filtered_sensors: return "filtered and sensor shapes";
    case Scene::create_destroy: return "create and destroy";
    case Scene::count: break;
  }
  return "?";
}

inline BodyId add_body(WorldId w, BodyType type, Vec2 p, Q32 angle = Q32::zero()) {
  BodyDef bd = default_body_def();
  bd.type = type;
  bd.position = p;
  bd.rotation = rot_from_angle(angle);
  Result<BodyId> b = create_body(w, bd);
  REQUIRE(b.ok());
  return b.value;
}

inline ShapeId add_box(BodyId b, Q32 hw, Q32 hh, const ShapeDef& sd = default_shape_def()) {
  Polygon poly;
  REQUIRE(make_box(hw, hh, &poly).ok());
  Result<ShapeId> s = create_polygon_shape(b, sd, poly);
  REQUIRE(s.ok());
  return s.value;
}

inline ShapeId add_circle(BodyId b, Q32 r, const ShapeDef& sd = default_shape_def()) {
  Circle c;
  c.radius = r;
  Result<ShapeId> s = create_circle_shape(b, sd, c);
  REQUIRE(s.ok());
  return s.value;
}

/// A static floor at y = 0 and, with walls, two walls at x = ±half_width.
inline void add_ground(WorldId w, Q32 half_width, bool walls) {
  const BodyId g = add_body(w, BodyType::static_body, {Q32::zero(), -1_q32});
  add_box(g, half_width, 1_q32);
  if (walls) {
    const BodyId l = add_body(w, BodyType::static_body, {-half_width - 0.5_q32, 5_q32});
    add_box(l, 0.5_q32, 6_q32);
    const BodyId r = add_body(w, BodyType::static_body, {half_width + 0.5_q32, 5_q32});
    add_box(r, 0.5_q32, 6_q32);
  }
}

/// Builds a scene into an empty world.
inline void build_scene(Scene scene, WorldId w) {
  switch (scene) {
    case Scene::pile: {
      add_ground(w, 4_q32, true);
      for (int32_t i = 0; i < 12; ++i) {
        const Vec2 p{Q32::from_ratio(i % 4 - 2, 1) + Q32::from_ratio(i, 7), Q32::from_int(1 + i)};
        const BodyId b = add_body(w, BodyType::dynamic_body, p, Q32::from_ratio(i, 5));
        if (i % 2 == 0) {
          add_box(b, 0.4_q32, 0.3_q32);
        } else {
          add_circle(b, 0.35_q32);
        }
      }
      break;
    }
    case Scene::pyramid: {
      add_ground(w, 6_q32, false);
      const int32_t rows = 5;
      for (int32_t row = 0; row < rows; ++row) {
        for (int32_t i = 0; i < rows - row; ++i) {
          const Vec2 p{Q32::from_ratio(2 * i - (rows - row - 1), 2) * 1.05_q32,
                       0.5_q32 + Q32::from_int(row) * 1.0_q32};
          const BodyId b = add_body(w, BodyType::dynamic_body, p);
          add_box(b, 0.5_q32, 0.5_q32);
        }
      }
      break;
    }
    case Scene::elastic_crowd: {
      add_ground(w, 4_q32, true);
      ShapeDef sd = default_shape_def();
      sd.restitution = 0.9_q32;
      sd.friction = 0.1_q32;
      for (int32_t i = 0; i < 14; ++i) {
        const Vec2 p{Q32::from_ratio(i % 5 - 2, 1) * 1.2_q32, Q32::from_int(1 + i / 5) * 1.5_q32};
        const BodyId b = add_body(w, BodyType::dynamic_body, p);
        add_circle(b, 0.3_q32, sd);
        REQUIRE(body_set_linear_velocity(b, {Q32::from_int(i % 3 - 1) * 2_q32, Q32::from_int(i % 4)}).ok());
      }
      break;
    }
    case Scene::filtered_sensors: {
      add_ground(w, 5_q32, true);
      const BodyId sensor_body = add_body(w, BodyType::static_body, {Q32::zero(), 1.5_q32});
      ShapeDef sensor = default_shape_def();
      sensor.is_sensor = true;
      add_box(sensor_body, 2_q32, 1_q32, sensor);
      for (int32_t i = 0; i < 10; ++i) {
        ShapeDef sd = default_shape_def();
        sd.enable_hit_events = (i % 2) == 0;
        sd.filter.category_bits = i % 3 == 0 ? 2 : 1;
        sd.filter.mask_bits = i % 3 == 0 ? ~uint64_t{2} : UINT64_MAX;  // category-2 shapes pass through each other
        sd.filter.group_index = i % 5 == 4 ? -1 : 0;
        const BodyId b = add_body(w, BodyType::dynamic_body, {Q32::from_ratio(i % 5 - 2, 1), Q32::from_int(3 + i)});
        if (i % 2 == 0) {
          add_circle(b, 0.4_q32, sd);
        } else {
          add_box(b, 0.35_q32, 0.35_q32, sd);
        }
      }
      break;
    }
    case Scene::create_destroy: {
      add_ground(w, 5_q32, true);
      for (int32_t i = 0; i < 6; ++i) {
        const BodyId b = add_body(w, BodyType::dynamic_body, {Q32::from_int(i - 3), Q32::from_int(1 + i)});
        add_box(b, 0.4_q32, 0.4_q32);
      }
      break;
    }
    case Scene::count:
      break;
  }
}

/// Live dynamic bodies, ascending index.
inline std::vector<BodyId> dynamic_bodies(WorldId w) {
  std::vector<BodyId> all(static_cast<size_t>(world_bodies(w, nullptr, 0)));
  world_bodies(w, all.data(), static_cast<int32_t>(all.size()));
  std::vector<BodyId> out;
  for (BodyId b : all) {
    if (body_type(b) == BodyType::dynamic_body) out.push_back(b);
  }
  return out;
}

/// The scene's inputs before step `tick` (0-based): impulses, and for
/// create_destroy, bodies created and destroyed. A function of the world's
/// state and the tick only.
inline void apply_scene_inputs(Scene scene, WorldId w, int64_t tick) {
  if (scene == Scene::elastic_crowd && tick % 40 == 7) {
    const std::vector<BodyId> bodies = dynamic_bodies(w);
    const BodyId b = bodies[static_cast<size_t>(tick / 40) % bodies.size()];
    REQUIRE(body_apply_linear_impulse_to_center(b, {1.5_q32, 2_q32}, true).ok());
  }
  if (scene == Scene::pile && tick == 300) {
    const std::vector<BodyId> bodies = dynamic_bodies(w);
    REQUIRE(body_apply_linear_impulse_to_center(bodies[3], {0.5_q32, 3_q32}, true).ok());
  }
  if (scene == Scene::create_destroy) {
    if (tick % 25 == 10) {
      const std::vector<BodyId> bodies = dynamic_bodies(w);
      if (bodies.size() > 2) REQUIRE(destroy_body(bodies[static_cast<size_t>(tick / 25) % bodies.size()]).ok());
    }
    if (tick % 20 == 5 && tick < 500) {
      const BodyId b = add_body(w, BodyType::dynamic_body,
                                {Q32::from_int(static_cast<int32_t>(tick % 7) - 3), 8_q32}, Q32::from_ratio(1, 3));
      if (tick % 40 == 5) {
        add_circle(b, 0.3_q32);
      } else {
        add_box(b, 0.3_q32, 0.45_q32);
        add_circle(b, 0.2_q32);  // a second shape on the same body
      }
    }
    if (tick % 17 == 3) {
      const std::vector<BodyId> bodies = dynamic_bodies(w);
      if (!bodies.empty()) {
        REQUIRE(body_apply_linear_impulse_to_center(bodies.back(), {-1_q32, 1_q32}, true).ok());
      }
    }
  }
}

/// Creates a world, builds the scene into it and returns it (the caller
/// destroys it).
inline WorldId make_scene_world(Scene scene) {
  Result<WorldId> w = create_world(default_world_def());
  REQUIRE(w.ok());
  build_scene(scene, w.value);
  return w.value;
}

/// Steps once with the scene's inputs; requires success.
inline void step_scene(Scene scene, WorldId w, int64_t tick) {
  apply_scene_inputs(scene, w, tick);
  REQUIRE(world_step(w, k_dt).ok());
}

}  // namespace tandem::replay_test
