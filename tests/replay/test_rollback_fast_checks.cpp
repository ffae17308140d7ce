// test_rollback_fast_checks.cpp — rollback_restore's fast checks
// (physics/state_compact_fast.cpp) give the same verdict, message and
// restored world as the detailed checks alone, for every scene's image and
// thousands of corruptions of it: single bytes, single bits, 8-byte values
// at and around the range limits, truncations and inconsistent structure
// copies.
#include <catch2/catch.hpp>

#include <cstdint>
#include <string>
#include <vector>

#include "fixed/splitmix64.h"
#include "physics/state_access.h"
#include "replay/rollback.h"
#include "replay_test_scenes.h"

namespace {

using namespace tandem;
using namespace tandem::replay_test;

/// Turns the fast checks off for a scope.
struct DetailedChecksOnly {
  DetailedChecksOnly() { state_access::set_compact_fast_checks(false); }
  ~DetailedChecksOnly() { state_access::set_compact_fast_checks(true); }
  DetailedChecksOnly(const DetailedChecksOnly&) = delete;
  DetailedChecksOnly& operator=(const DetailedChecksOnly&) = delete;
};

struct Outcome {
  bool ok = false;
  std::string message;
  std::vector<uint8_t> restored;  // the world's image after an accepted restore
};

Outcome restore_into(WorldId w, const RollbackBuffer& buffer) {
  Outcome o;
  const Status s = rollback_restore(w, buffer);
  o.ok = s.ok();
  o.message = s.message;
  if (o.ok) {
    RollbackBuffer again;
    REQUIRE(rollback_save(w, &again).ok());
    o.restored = again.image;
  }
  return o;
}

/// A small deterministic generator (splitmix64).
struct Random {
  uint64_t state;
  uint64_t next() { return splitmix64_next(&state); }
  size_t below(size_t n) { return static_cast<size_t>(next() % n); }
};

/// Raw values at and around the limits restore checks (Q32 raw units).
std::vector<int64_t> interesting_values() {
  const int64_t one = int64_t{1} << 32;
  const int64_t limits[] = {one,
                            one + (int64_t{1} << 16),
                            one / 2,
                            100 * one,
                            1000 * 4 * one,
                            100 * 64 * one,
                            10000 * one,
                            100000 * one,
                            100000000 * one,
                            2000000 * one,
                            int64_t{400000000} << 32};
  std::vector<int64_t> v = {0, 1, -1, INT64_MIN, INT64_MAX, INT64_MIN + 1};
  for (const int64_t l : limits) {
    for (const int64_t d : {int64_t{-1}, int64_t{0}, int64_t{1}}) {
      v.push_back(l + d);
      v.push_back(-l + d);
    }
  }
  return v;
}

void put_le64(std::vector<uint8_t>* bytes, size_t at, int64_t value) {
  for (size_t i = 0; i < 8 && at + i < bytes->size(); ++i) {
    (*bytes)[at + i] = static_cast<uint8_t>(static_cast<uint64_t>(value) >> (8 * i));
  }
}

}  // namespace

TEST_CASE("rollback: the fast checks agree with the detailed checks on corrupt images", "[replay][rollback]") {
  const std::vector<int64_t> values = interesting_values();
  for (int32_t si = 0; si < static_cast<int32_t>(Scene::count); ++si) {
    const Scene scene = static_cast<Scene>(si);
    INFO(scene_name(scene));
    const WorldId source = make_scene_world(scene);
    for (int64_t t = 0; t < 40; ++t) step_scene(scene, source, t);
    RollbackBuffer good;
    REQUIRE(rollback_save(source, &good).ok());
    // Two targets that receive the same images: one restored with the fast
    // checks, one with the detailed checks alone.
    const WorldId fast_target = make_scene_world(scene);
    const WorldId detailed_target = make_scene_world(scene);
    const auto compare = [&](const RollbackBuffer& bad, const std::string& what) {
      const Outcome fast = restore_into(fast_target, bad);
      Outcome detailed;
      {
        DetailedChecksOnly only;
        detailed = restore_into(detailed_target, bad);
      }
      INFO(what << ": " << detailed.message);
      REQUIRE(fast.ok == detailed.ok);
      REQUIRE(fast.message == detailed.message);
      REQUIRE(fast.restored == detailed.restored);
    };
    compare(good, "the good image");
    Random rng{0x5EED0000u + static_cast<uint64_t>(si)};
    const size_t n = good.image.size();
    for (int32_t k = 0; k < 1500; ++k) {
      RollbackBuffer bad = good;
      const size_t at = 9 + rng.below(n - 9);
      switch (k % 4) {
        case 0: bad.image[at] = static_cast<uint8_t>(rng.next()); break;
        case 1: bad.image[at] ^= static_cast<uint8_t>(1u << rng.below(8)); break;
        case 2: put_le64(&bad.image, at, values[rng.below(values.size())]); break;
        default: bad.image.resize(at); break;
      }
      compare(bad, "corruption " + std::to_string(k) + " at " + std::to_string(at));
    }
    // Inconsistent structure copies.
    {
      RollbackBuffer bad = good;
      for (ShapeGeometry& g : bad.geometries) {
        if (g.type == ShapeType::polygon) g.polygon.count = 9;
      }
      compare(bad, "polygon counts");
      bad = good;
      if (!bad.geometries.empty()) bad.geometries.pop_back();
      compare(bad, "geometries short");
      bad = good;
      if (!bad.masses.empty()) bad.masses.pop_back();
      compare(bad, "masses short");
    }
    (void)destroy_world(source);
    (void)destroy_world(fast_target);
    (void)destroy_world(detailed_target);
  }
}
