// Tests for physics/limits.h.
#include <catch2/catch.hpp>

#include "fixed/vec2.h"
#include "physics/limits.h"

using namespace tandem;

TEST_CASE("limits keep solver products inside Q32.32", "[physics][limits]") {
  // mass × speed, inertia × angular speed and coordinate differences must not
  // saturate: each stays at least 20× below the Q32.32 maximum.
  const Q32 headroom = Q32::max() / 20;
  CHECK(k_max_body_mass * k_max_linear_speed <= headroom);
  CHECK(k_max_rotational_inertia * k_max_angular_speed <= headroom);
  CHECK(k_max_world_coordinate * 2 <= headroom);
  CHECK(k_max_density * k_max_shape_size <= Q32::max());
  CHECK(k_min_body_mass < k_max_body_mass);
}

TEST_CASE("check_limit names the value and the range", "[physics][limits]") {
  std::string message;
  CHECK(check_limit("body 3 mass", 5_q32, k_min_body_mass, k_max_body_mass, "kg", &message));
  CHECK(message.empty());
  CHECK_FALSE(check_limit("body 3 mass", 0.0001_q32, k_min_body_mass, k_max_body_mass, "kg", &message));
  CHECK(message.rfind("body 3 mass 0.0001", 0) == 0);
  CHECK(message.find("is outside [0.000999999", 0) != std::string::npos);
  CHECK(message.find("100000] kg") != std::string::npos);
}
