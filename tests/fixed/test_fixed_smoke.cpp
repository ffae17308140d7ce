#include <catch2/catch.hpp>
#include "fixed/fixed.h"
using namespace tandem;
using namespace tandem::literals;
TEST_CASE("smoke", "[fixed]") {
  CHECK((1.5_q32 * 2.0_q32) == 3_q32);
  CHECK((1_q32 / 3_q32).raw == 1431655765);
  CHECK(to_string(-1.5_q32) == "-1.5");
  CHECK(parse_q32("0.1").value.raw == 429496730);
  CHECK(parse_q32("1e-1").value.raw == 429496730);
}
