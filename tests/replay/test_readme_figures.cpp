// test_readme_figures.cpp — the snapshot sizes README.md quotes ("Replay"),
// computed on the scene tools/bench/bench_rollback.cpp measured before the
// compact rollback snapshot (it now measures a 990-box pyramid; 1000
// dynamic bodies, alternating 0.4 m boxes and 0.35 m circles, dropped in a
// 40 m walled pit, 90 ticks at 1/60 s) and checked against the README text
// at the precision quoted (tests/readme_quote.h). Sizes are deterministic,
// so they are asserted; the timings next to them are benchmark measurements.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "fixed/str_cat.h"
#include "physics/collision.h"
#include "physics/tandem.h"
#include "replay/state.h"
#include "replay_file_test_support.h"
#include "tests/readme_quote.h"

using namespace tandem;
using namespace tandem::literals;

namespace {

const Q32 k_tick = Q32::from_ratio(1, 60);
constexpr int32_t k_pile_bodies = 1000;

BodyId pile_body(WorldId w, BodyType type, Vec2 p) {
  BodyDef bd = default_body_def();
  bd.type = type;
  bd.position = p;
  Result<BodyId> b = create_body(w, bd);
  REQUIRE(b.ok());
  return b.value;
}

void pile_box(BodyId b, Q32 hw, Q32 hh) {
  Polygon poly;
  REQUIRE(make_box(hw, hh, &poly).ok());
  REQUIRE(create_polygon_shape(b, default_shape_def(), poly).ok());
}

/// The pile bench_rollback.cpp's make_pile() built before issue 15, stepped 90 ticks.
void build_pile(WorldId w) {
  pile_box(pile_body(w, BodyType::static_body, {0_q32, -1_q32}), 21_q32, 1_q32);
  pile_box(pile_body(w, BodyType::static_body, {-20.5_q32, 20_q32}), 0.5_q32, 21_q32);
  pile_box(pile_body(w, BodyType::static_body, {20.5_q32, 20_q32}), 0.5_q32, 21_q32);
  for (int32_t i = 0; i < k_pile_bodies; ++i) {
    const int32_t col = i % 40;
    const int32_t row = i / 40;
    const Vec2 p{Q32::from_int(col - 20) + 0.5_q32 + Q32::from_ratio(row % 3, 10), 1_q32 + Q32::from_int(row)};
    const BodyId b = pile_body(w, BodyType::dynamic_body, p);
    if (i % 2 == 0) {
      pile_box(b, 0.4_q32, 0.4_q32);
    } else {
      Circle c;
      c.radius = 0.35_q32;
      REQUIRE(create_circle_shape(b, default_shape_def(), c).ok());
    }
  }
  for (int32_t t = 0; t < 90; ++t) REQUIRE(world_step(w, k_tick).ok());
}

size_t tag_offset(const std::vector<uint8_t>& image, const char* tag) {
  const uint8_t* t = reinterpret_cast<const uint8_t*>(tag);
  const auto it = std::search(image.begin(), image.end(), t, t + 4);
  REQUIRE(it != image.end());
  return static_cast<size_t>(it - image.begin());
}

}  // namespace

TEST_CASE("README figures: snapshot and delta sizes of the 1000-body pile", "[replay][readme]") {
  WorldDef def = default_world_def();
  def.broad_phase = BroadPhaseKind::grid;
  replay_file_test::OwnedWorld w(def);
  build_pile(w.id);
  std::vector<uint8_t> base;
  REQUIRE(encode_world_state(w.id, &base).ok());
  const BroadPhaseStats stats = world_broad_phase_stats(w.id);
  const long double per_body = static_cast<long double>(base.size()) / k_pile_bodies;
  const long double contact_share =
      static_cast<long double>(tag_offset(base, "TUCH") - tag_offset(base, "CONT")) / static_cast<long double>(base.size());
  // Deltas 1 and 8 ticks after the base (what bench_rollback's BM_DeltaSnapshot measured).
  long double delta_per_body[2] = {};
  int32_t index = 0;
  std::vector<uint8_t> image, delta;
  for (int32_t t = 1; t <= 8; ++t) {
    REQUIRE(world_step(w.id, k_tick).ok());
    if (t != 1 && t != 8) continue;
    REQUIRE(encode_world_state(w.id, &image).ok());
    encode_state_delta(base.data(), base.size(), image.data(), image.size(), &delta);
    delta_per_body[index++] = static_cast<long double>(delta.size()) / k_pile_bodies;
    // And the delta rebuilds the image.
    std::vector<uint8_t> rebuilt;
    REQUIRE(apply_state_delta(base.data(), base.size(), delta.data(), delta.size(), &rebuilt).ok());
    CHECK(rebuilt == image);
  }
  WARN("pile: " << base.size() << " bytes (" << per_body << " per body), " << stats.touching_pairs
                << " touching contacts, contact section " << contact_share * 100 << " %, delta 1 tick "
                << delta_per_body[0] << " and 8 ticks " << delta_per_body[1] << " bytes per body");
  // Quoted: contacts to the nearest 50, bytes per body to the byte, the
  // contact share to 5 %, the delta range to 10 bytes.
  const auto nearest = [](long double v, long double step) {
    return std::to_string(static_cast<int64_t>(v / step + 0.5L) * static_cast<int64_t>(step));
  };
  readme::check_quotes(str_cat("~", nearest(stats.pairs, 50), " contacts, ", nearest(stats.touching_pairs, 50),
                               " of them touching"));
  readme::check_quotes(str_cat("the full image is ", nearest(per_body, 1), " bytes per moving body"));
  readme::check_quotes(
      str_cat("about ", nearest(contact_share * 100, 5), " % of it is contact manifolds and impulses"));
  readme::check_quotes(str_cat("brings a rollback snapshot to ", nearest(delta_per_body[0], 10), "–",
                               nearest(delta_per_body[1], 10), " bytes per body 1–8 ticks after its base"));
}
