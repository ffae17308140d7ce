// capi_test_util.h — helpers shared by the C API tests (capi/tests/test_capi*.cpp):
// Q32 literals, error checks, a self-destroying world, boxes and snapshots.
#pragma once

#include <catch2/catch.hpp>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "physics/tandem.h"
#include "replay/state.h"
#include "scene/scene.h"
#include "tandem_c.h"

#ifndef TANDEM_SOURCE_DIR
#define TANDEM_SOURCE_DIR "."
#endif

namespace capi_test {

inline tandem_q32 qi(int32_t v) { return tandem_q32_from_int(v); }
inline tandem_q32 qt(const char* text) {
  tandem_q32 v = 0;
  REQUIRE(tandem_q32_from_text(text, &v) == TANDEM_OK);
  return v;
}
inline tandem_vec2 v2(int32_t x, int32_t y) { return {qi(x), qi(y)}; }
inline std::string last_message() { return tandem_last_error_message(); }

// The last error is `code` and its message contains `part`.
inline void require_error(tandem_status got, tandem_status code, const std::string& part) {
  INFO("message: " << last_message());
  REQUIRE(got == code);
  REQUIRE(tandem_last_error_code() == code);
  REQUIRE(last_message().find(part) != std::string::npos);
}

struct CWorld {
  tandem_world_id id{};
  CWorld() {
    const tandem_world_def def = tandem_default_world_def();
    REQUIRE(tandem_create_world(&def, &id) == TANDEM_OK);
  }
  ~CWorld() {
    if (tandem_world_is_valid(id)) tandem_destroy_world(id);
  }
};

inline tandem_body_id add_box(tandem_world_id world, int32_t type, tandem_vec2 position, tandem_q32 half) {
  tandem_body_def def = tandem_default_body_def();
  def.type = type;
  def.position = position;
  tandem_body_id body{};
  REQUIRE(tandem_create_body(world, &def, &body) == TANDEM_OK);
  tandem_polygon box;
  REQUIRE(tandem_make_box(half, half, &box) == TANDEM_OK);
  const tandem_shape_def sd = tandem_default_shape_def();
  tandem_shape_id shape{};
  REQUIRE(tandem_create_polygon_shape(body, &sd, &box, &shape) == TANDEM_OK);
  return body;
}

inline tandem_body_id add_ground(tandem_world_id world) {
  tandem_body_def def = tandem_default_body_def();
  tandem_body_id body{};
  REQUIRE(tandem_create_body(world, &def, &body) == TANDEM_OK);
  tandem_polygon box;
  REQUIRE(tandem_make_offset_box(qi(20), qi(1), v2(0, -1), 0, 0, &box) == TANDEM_OK);
  const tandem_shape_def sd = tandem_default_shape_def();
  tandem_shape_id shape{};
  REQUIRE(tandem_create_polygon_shape(body, &sd, &box, &shape) == TANDEM_OK);
  return body;
}

inline std::vector<uint8_t> snapshot(tandem_world_id world) {
  size_t size = 0;
  REQUIRE(tandem_world_snapshot(world, nullptr, 0, &size) == TANDEM_OK);
  REQUIRE(size == tandem_world_snapshot_size(world));
  std::vector<uint8_t> bytes(size);
  REQUIRE(tandem_world_snapshot(world, bytes.data(), bytes.size(), &size) == TANDEM_OK);
  REQUIRE(size == bytes.size());
  return bytes;
}

}  // namespace capi_test

using namespace capi_test;
