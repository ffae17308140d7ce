// The README's fixed-point example, compiled and checked, so the README
// cannot drift from the API. Keep the body identical to the README block.
#include <catch2/catch.hpp>

#include <cstdio>
#include <string>

#include "fixed/fixed.h"
#include "fixed/fixed_math.h"
#include "fixed/vec2.h"

using namespace tandem;
using namespace tandem::literals;

TEST_CASE("README fixed-point example", "[fixed][readme]") {
  Q32 dt = Q32::from_ratio(1, 60);          // the raw value nearest 1/60 s
  Q32 g = -9.81_q32;                        // literal parsed exactly at compile time
  auto parsed = parse_q32("0.016666");      // exact decimal parse, never through a double
  if (!parsed.ok()) {
    std::puts(describe_parse_error("0.016666", parsed.error, parsed.error_offset).c_str());
  }
  Q32 v = g * dt;                           // rounded once, to nearest, ties away from zero
  Q32 r = sqrt(2_q32);                      // correctly rounded
  SinCos<Q32> sc = sincos(k_pi / 6);        // one call, both values
  Q32 angle = atan2(sc.sin, sc.cos);        // back to ~π/6
  Vec2 p{30000_q32, 40000_q32};
  Q32 len = length(p);                      // 50000 exactly: squares formed in 128 bits
  Rot q = rot_from_angle(angle);
  Vec2 turned = rotate(q, Vec2{1_q32, 0_q32});
  Q16 compact = to_q16(len / 2);            // to the network format, rounded to nearest
  std::string text = to_string(v);          // exact decimal: "-0.1634999993257224559783935546875"

  CHECK(parsed.ok());
  CHECK(text == "-0.1634999993257224559783935546875");
  CHECK(r.raw == 6074001000);               // round(√2 · 2^32)
  CHECK(abs(angle - k_pi / 6).raw <= 3);
  CHECK(len == 50000_q32);
  CHECK(abs(turned.x - sc.cos).raw <= 3);
  CHECK(compact == 25000_q16);
  CHECK(describe_parse_error("1.2x", parse_q32("1.2x").error, 3) == "unexpected character 'x' at offset 3 in \"1.2x\"");
}
