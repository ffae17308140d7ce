// Tests of replay/state.h: canonical encoding, restore at every tick (into a
// fresh world and into the same world), handles after restore, refusal of
// corrupt images, buffers too small, diffs that pinpoint a planted
// difference, and the byte layout (which the s390x run checks against the
// same expected values, so nothing here may be endian-dependent).
//
// Restore coverage: every tick of 600, in two chained runs per scene (one
// restoring its own snapshot into itself before every step, one moving into
// a fresh world made from the snapshot before every step) whose hash chains
// must equal the original's to the end; plus single restores (original
// state from tick t, then run to the end) at every 100th tick in both modes.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstring>
#include <random>
#include <vector>

#define XXH_INLINE_ALL
#include <xxhash.h>

#include "replay/bytes.h"
#include "replay/state.h"
#include "replay_test_scenes.h"

namespace tandem {
namespace {

using namespace tandem::replay_test;
using namespace tandem::literals;

constexpr int64_t k_ticks = 600;

using OwnedWorld = UniqueWorld;

/// The original run: hash after each tick (index t = after t steps) and the
/// snapshot before each tick.
struct Run {
  std::vector<uint64_t> hashes;
  std::vector<std::vector<uint8_t>> snapshots;
};

Run run_original(Scene scene, bool keep_snapshots) {
  OwnedWorld w(make_scene_world(scene));
  Run run;
  run.hashes.push_back(world_state_hash(w.id));
  for (int64_t t = 0; t < k_ticks; ++t) {
    if (keep_snapshots) {
      std::vector<uint8_t> snap;
      REQUIRE(encode_world_state(w.id, &snap).ok());
      run.snapshots.push_back(std::move(snap));
    }
    step_scene(scene, w.id, t);
    run.hashes.push_back(world_state_hash(w.id));
  }
  return run;
}

TEST_CASE("state: snapshot size, encoding and hash agree", "[replay][state]") {
  OwnedWorld w(make_scene_world(Scene::create_destroy));
  for (int64_t t = 0; t < 120; ++t) step_scene(Scene::create_destroy, w.id, t);
  std::vector<uint8_t> a;
  REQUIRE(encode_world_state(w.id, &a).ok());
  CHECK(a.size() == world_snapshot_size(w.id));
  std::vector<uint8_t> buffer(a.size() + 16, 0xAB);
  size_t written = 0;
  REQUIRE(world_snapshot(w.id, buffer.data(), buffer.size(), &written).ok());
  CHECK(written == a.size());
  CHECK(std::memcmp(buffer.data(), a.data(), a.size()) == 0);
  CHECK(buffer[a.size()] == 0xAB);
  std::vector<uint8_t> appended = {1, 2, 3};
  REQUIRE(world_snapshot_append(w.id, &appended).ok());
  REQUIRE(appended.size() == a.size() + 3);
  CHECK(std::memcmp(appended.data() + 3, a.data(), a.size()) == 0);
  CHECK(world_state_hash(w.id) == world_state_hash(w.id));
  // Decoding every record and field succeeds and names them.
  DecodedState d;
  REQUIRE(decode_world_state(a.data(), a.size(), &d).ok());
  CHECK(d.version == k_state_format_version);
  REQUIRE(!d.records.empty());
  CHECK(d.records.front().kind == "world");
  // The per-body hashes: one per slot, 0 for dead slots, equal to body_state_hash.
  std::vector<uint64_t> hashes;
  REQUIRE(world_body_hashes(w.id, &hashes).ok());
  const std::vector<BodyId> bodies = dynamic_bodies(w.id);
  REQUIRE(!bodies.empty());
  for (BodyId b : bodies) CHECK(hashes[b.index1 - 1] == body_state_hash(b));
}

TEST_CASE("state: a buffer too small is refused with the needed size and nothing written past it",
          "[replay][state]") {
  OwnedWorld w(make_scene_world(Scene::pile));
  const size_t needed = world_snapshot_size(w.id);
  REQUIRE(needed > 100);
  std::vector<uint8_t> buffer(needed, 0xCD);
  size_t written = 0;
  const Status s = world_snapshot(w.id, buffer.data(), needed - 1 - 50, &written);
  CHECK(s.code == StatusCode::capacity_exceeded);
  CHECK(written == needed);
  CHECK(s.message.find(std::to_string(needed)) != std::string::npos);
  for (size_t i = needed - 51; i < needed; ++i) REQUIRE(buffer[i] == 0xCD);
  CHECK(world_snapshot(w.id, nullptr, 0, &written).code == StatusCode::capacity_exceeded);
  CHECK(written == needed);
}

TEST_CASE("state: restore at every tick reproduces the hash chain to the end", "[replay][state]") {
  for (int32_t si = 0; si < static_cast<int32_t>(Scene::count); ++si) {
    const Scene scene = static_cast<Scene>(si);
    INFO("scene " << scene_name(scene));
    const Run original = run_original(scene, true);

    // Chained, same world: restore its own snapshot before every step.
    {
      OwnedWorld w(make_scene_world(scene));
      std::vector<uint8_t> snap;
      for (int64_t t = 0; t < k_ticks; ++t) {
        REQUIRE(encode_world_state(w.id, &snap).ok());
        REQUIRE(snap == original.snapshots[static_cast<size_t>(t)]);
        const Status s = world_restore(w.id, snap.data(), snap.size());
        REQUIRE(s.ok());
        step_scene(scene, w.id, t);
        INFO("same world, tick " << t);
        REQUIRE(world_state_hash(w.id) == original.hashes[static_cast<size_t>(t) + 1]);
      }
    }
    // Chained, fresh world: before every step move into a new world made
    // from the snapshot.
    {
      WorldId current = make_scene_world(scene);
      std::vector<uint8_t> snap;
      for (int64_t t = 0; t < k_ticks; ++t) {
        REQUIRE(encode_world_state(current, &snap).ok());
        Result<WorldId> next = create_world_from_snapshot(snap.data(), snap.size());
        REQUIRE(next.ok());
        REQUIRE(destroy_world(current).ok());
        current = next.value;
        step_scene(scene, current, t);
        INFO("fresh world, tick " << t);
        REQUIRE(world_state_hash(current) == original.hashes[static_cast<size_t>(t) + 1]);
      }
      REQUIRE(destroy_world(current).ok());
    }
    // Single restores from the original's snapshots, to the end.
    for (int64_t t0 = 0; t0 < k_ticks; t0 += 100) {
      const std::vector<uint8_t>& snap = original.snapshots[static_cast<size_t>(t0)];
      Result<WorldId> fresh = create_world_from_snapshot(snap.data(), snap.size());
      REQUIRE(fresh.ok());
      OwnedWorld f(fresh.value);
      OwnedWorld same(make_scene_world(scene));  // some other state first
      for (int64_t t = 0; t < 37; ++t) step_scene(scene, same.id, t);
      REQUIRE(world_restore(same.id, snap.data(), snap.size()).ok());
      REQUIRE(world_state_hash(f.id) == original.hashes[static_cast<size_t>(t0)]);
      REQUIRE(world_state_hash(same.id) == original.hashes[static_cast<size_t>(t0)]);
      for (int64_t t = t0; t < k_ticks; ++t) {
        step_scene(scene, f.id, t);
        step_scene(scene, same.id, t);
        INFO("single restore at " << t0 << ", tick " << t);
        REQUIRE(world_state_hash(f.id) == original.hashes[static_cast<size_t>(t) + 1]);
        REQUIRE(world_state_hash(same.id) == original.hashes[static_cast<size_t>(t) + 1]);
      }
    }
  }
}

TEST_CASE("state: restore into the same world is exact with every broad phase", "[replay][state]") {
  // The broad phase keeps persistent structures (sorted end points, grid,
  // tree) that restore resets; a stale one would change the pairs.
  const Scene scene = Scene::create_destroy;
  for (BroadPhaseKind kind : {BroadPhaseKind::naive, BroadPhaseKind::sweep_and_prune, BroadPhaseKind::grid,
                              BroadPhaseKind::tree}) {
    INFO("broad phase " << static_cast<int32_t>(kind));
    OwnedWorld a(make_scene_world(scene));
    OwnedWorld b(make_scene_world(scene));
    REQUIRE(world_set_broad_phase(a.id, kind).ok());
    REQUIRE(world_set_broad_phase(b.id, kind).ok());
    std::vector<uint8_t> snap;
    std::vector<uint8_t> older;
    for (int64_t t = 0; t < 300; ++t) {
      step_scene(scene, a.id, t);
      // b: step, then jump back one tick and redo it (its structures saw a
      // different state in between).
      REQUIRE(encode_world_state(b.id, &older).ok());
      step_scene(scene, b.id, t);
      step_scene(scene, b.id, t + 1);
      REQUIRE(world_restore(b.id, older.data(), older.size()).ok());
      step_scene(scene, b.id, t);
      REQUIRE(world_state_hash(b.id) == world_state_hash(a.id));
    }
  }
}

TEST_CASE("state: handles stay valid after restore and the next create gets the original's id",
          "[replay][state]") {
  const Scene scene = Scene::create_destroy;
  OwnedWorld a(make_scene_world(scene));
  // Past several destroys, so the free list holds slots.
  for (int64_t t = 0; t < 140; ++t) step_scene(scene, a.id, t);
  std::vector<uint8_t> snap;
  REQUIRE(encode_world_state(a.id, &snap).ok());
  const std::vector<BodyId> before = dynamic_bodies(a.id);

  Result<WorldId> fresh = create_world_from_snapshot(snap.data(), snap.size());
  REQUIRE(fresh.ok());
  OwnedWorld b(fresh.value);
  const std::vector<BodyId> after = dynamic_bodies(b.id);
  REQUIRE(after.size() == before.size());
  for (size_t i = 0; i < before.size(); ++i) {
    CHECK(after[i].index1 == before[i].index1);
    CHECK(after[i].generation == before[i].generation);
    BodyId same_handle = before[i];
    same_handle.world = b.id;
    CHECK(body_is_valid(same_handle));
    CHECK(body_position(same_handle) == body_position(before[i]));
  }
  // The next create (body and shape) gets the same ids in both worlds.
  const BodyId na = add_body(a.id, BodyType::dynamic_body, {0_q32, 9_q32});
  const BodyId nb = add_body(b.id, BodyType::dynamic_body, {0_q32, 9_q32});
  CHECK(na.index1 == nb.index1);
  CHECK(na.generation == nb.generation);
  const ShapeId sa = add_circle(na, 0.25_q32);
  const ShapeId sb = add_circle(nb, 0.25_q32);
  CHECK(sa.index1 == sb.index1);
  CHECK(sa.generation == sb.generation);
  // Some slot below the new one was reused (the free list mattered): the
  // scene destroyed bodies before tick 140.
  CHECK(world_state_hash(a.id) == world_state_hash(b.id));
}

TEST_CASE("state: corrupt, truncated and foreign images are refused and the world is unchanged",
          "[replay][state]") {
  OwnedWorld src(make_scene_world(Scene::filtered_sensors));
  for (int64_t t = 0; t < 90; ++t) step_scene(Scene::filtered_sensors, src.id, t);
  std::vector<uint8_t> good;
  REQUIRE(encode_world_state(src.id, &good).ok());

  OwnedWorld target(make_scene_world(Scene::pyramid));
  for (int64_t t = 0; t < 10; ++t) step_scene(Scene::pyramid, target.id, t);
  const uint64_t target_hash = world_state_hash(target.id);

  const auto refused = [&](const std::vector<uint8_t>& image, const char* expect_in_message) {
    const Status s = world_restore(target.id, image.data(), image.size());
    INFO(s.message);
    CHECK(!s.ok());
    CHECK(s.message.find("offset ") != std::string::npos);
    CHECK(s.message.find(expect_in_message) != std::string::npos);
    CHECK(world_state_hash(target.id) == target_hash);
    return s;
  };

  std::vector<uint8_t> bad = good;
  bad[0] = 'X';
  (void)refused(bad, "magic");
  bad = good;
  bad[4] = 4;  // 1, 2 (with joints) and 3 (with pending joint events) are valid
  (void)refused(bad, "version");
  // Truncated at every length in the first 200 bytes and a spread of others.
  for (size_t n = 0; n < good.size(); n += (n < 200 ? 1 : 97)) {
    std::vector<uint8_t> cut(good.begin(), good.begin() + static_cast<std::ptrdiff_t>(n));
    const Status s = refused(cut, "expected");
    REQUIRE(s.message.find("left") != std::string::npos);
  }
  // Trailing data.
  bad = good;
  bad.push_back(0);
  (void)refused(bad, "end of the image");
  // A body type out of range: the first body record follows the body pool.
  {
    DecodedState d;
    REQUIRE(decode_world_state(good.data(), good.size(), &d).ok());
    // Find the byte: search for the "BODY" tag; the type byte follows it.
    const uint8_t tag[4] = {'B', 'O', 'D', 'Y'};
    auto it = std::search(good.begin(), good.end(), tag, tag + 4);
    REQUIRE(it != good.end());
    const size_t type_offset = static_cast<size_t>(it - good.begin()) + 4;
    bad = good;
    bad[type_offset] = 7;
    const Status s = refused(bad, "type 0..2, got 7");
    CHECK(s.message.find("offset " + std::to_string(type_offset)) != std::string::npos);
    CHECK(s.message.find("body 0") != std::string::npos);
  }
  // Random single-byte corruptions: refused or accepted, never a crash, and
  // on refusal the world is unchanged (seeded; raw integers only).
  std::mt19937_64 rng(0x5EED5EEDu);
  int32_t refusals = 0;
  for (int32_t i = 0; i < 150; ++i) {
    bad = good;
    const size_t at = static_cast<size_t>(rng() % good.size());
    bad[at] = static_cast<uint8_t>(bad[at] ^ static_cast<uint8_t>(1u + rng() % 255u));
    const Status s = world_restore(target.id, bad.data(), bad.size());
    if (!s.ok()) {
      ++refusals;
      REQUIRE(world_state_hash(target.id) == target_hash);
    } else {
      // Accepted (the byte was a plain value): put the target back.
      std::vector<uint8_t> t;
      REQUIRE(world_restore(target.id, good.data(), good.size()).ok());
      REQUIRE(encode_world_state(target.id, &t).ok());
      REQUIRE(t == good);
      OwnedWorld fresh(make_scene_world(Scene::pyramid));
      for (int64_t k = 0; k < 10; ++k) step_scene(Scene::pyramid, fresh.id, k);
      REQUIRE(encode_world_state(fresh.id, &t).ok());
      REQUIRE(world_restore(target.id, t.data(), t.size()).ok());
      REQUIRE(world_state_hash(target.id) == target_hash);
    }
  }
  CHECK(refusals > 0);
  // A locked world and an invalid handle are refused.
  CHECK(world_restore(WorldId{}, good.data(), good.size()).code == StatusCode::null_handle);
  Result<WorldId> none = create_world_from_snapshot(bad.data(), 3);
  CHECK(!none.ok());
}

struct LockedProbe {
  WorldId world;
  const std::vector<uint8_t>* image = nullptr;
  StatusCode restore_code = StatusCode::ok;
  StatusCode snapshot_code = StatusCode::ok;
  uint64_t hash = 1;
  int32_t calls = 0;
};

bool probe_filter(ShapeId, ShapeId, void* context) {
  LockedProbe* p = static_cast<LockedProbe*>(context);
  if (p->calls++ == 0) {
    p->restore_code = world_restore(p->world, p->image->data(), p->image->size()).code;
    std::vector<uint8_t> out;
    p->snapshot_code = encode_world_state(p->world, &out).code;
    p->hash = world_state_hash(p->world);
  }
  return true;
}

TEST_CASE("state: a locked world (inside world_step) is refused", "[replay][state]") {
  OwnedWorld w(make_scene_world(Scene::pile));
  std::vector<uint8_t> image;
  REQUIRE(encode_world_state(w.id, &image).ok());
  LockedProbe probe;
  probe.world = w.id;
  probe.image = &image;
  REQUIRE(world_set_custom_filter(w.id, probe_filter, &probe).ok());
  for (int64_t t = 0; t < 60 && probe.calls == 0; ++t) step_scene(Scene::pile, w.id, t);
  REQUIRE(probe.calls > 0);
  CHECK(probe.restore_code == StatusCode::world_locked);
  CHECK(probe.snapshot_code == StatusCode::world_locked);
  CHECK(probe.hash == 0);
  REQUIRE(world_set_custom_filter(w.id, nullptr, nullptr).ok());
}

TEST_CASE("state: a one-raw-unit perturbation is pinpointed by hash chain and diff", "[replay][state]") {
  const Scene scene = Scene::pile;
  const Run original = run_original(scene, true);
  constexpr int64_t k_perturb_tick = 123;
  OwnedWorld w(make_scene_world(scene));
  const std::vector<BodyId> bodies = dynamic_bodies(w.id);
  const BodyId victim = bodies[5];
  std::vector<uint8_t> perturbed_snapshot;
  int64_t first_bad_tick = -1;
  for (int64_t t = 0; t < k_ticks; ++t) {
    if (t == k_perturb_tick) {
      Vec2 v = body_linear_velocity(victim);
      v.y = Q32::from_raw(v.y.raw + 1);
      REQUIRE(body_set_linear_velocity(victim, v).ok());
      REQUIRE(encode_world_state(w.id, &perturbed_snapshot).ok());
    }
    step_scene(scene, w.id, t);
    if (first_bad_tick < 0 && world_state_hash(w.id) != original.hashes[static_cast<size_t>(t) + 1]) {
      first_bad_tick = t;
    }
  }
  // The hash chain first differs after the perturbed tick's step.
  CHECK(first_bad_tick == k_perturb_tick);
  DecodedState a;
  DecodedState b;
  const std::vector<uint8_t>& clean = original.snapshots[static_cast<size_t>(k_perturb_tick)];
  REQUIRE(decode_world_state(clean.data(), clean.size(), &a).ok());
  REQUIRE(decode_world_state(perturbed_snapshot.data(), perturbed_snapshot.size(), &b).ok());
  const StateDifference d = diff_world_states(a, b);
  INFO(d.describe());
  REQUIRE(d.differs);
  CHECK(d.kind == "body");
  CHECK(d.index == static_cast<int64_t>(victim.index1) - 1);
  CHECK(d.generation == victim.generation);
  CHECK(d.field == "linear_velocity.y");
  CHECK(d.value_b == d.value_a + 1);
  CHECK(d.is_q32);
  CHECK(d.describe().find("linear_velocity.y") != std::string::npos);
  CHECK(!diff_world_states(a, a).differs);
  // The per-body hashes locate the body too.
  OwnedWorld wa(create_world_from_snapshot(clean.data(), clean.size()).value);
  OwnedWorld wb(create_world_from_snapshot(perturbed_snapshot.data(), perturbed_snapshot.size()).value);
  std::vector<uint64_t> ha;
  std::vector<uint64_t> hb;
  REQUIRE(world_body_hashes(wa.id, &ha).ok());
  REQUIRE(world_body_hashes(wb.id, &hb).ok());
  REQUIRE(ha.size() == hb.size());
  for (size_t i = 0; i < ha.size(); ++i) CHECK((ha[i] != hb[i]) == (static_cast<int64_t>(i) == d.index));
}

TEST_CASE("state: diff reports records present on one side only", "[replay][state]") {
  OwnedWorld w(make_scene_world(Scene::create_destroy));
  std::vector<uint8_t> before;
  REQUIRE(encode_world_state(w.id, &before).ok());
  const BodyId extra = add_body(w.id, BodyType::dynamic_body, {0_q32, 9_q32});
  std::vector<uint8_t> after;
  REQUIRE(encode_world_state(w.id, &after).ok());
  DecodedState a;
  DecodedState b;
  REQUIRE(decode_world_state(before.data(), before.size(), &a).ok());
  REQUIRE(decode_world_state(after.data(), after.size(), &b).ok());
  const StateDifference d = diff_world_states(a, b);
  INFO(d.describe());
  REQUIRE(d.differs);
  // The new slot appears first (body pool), then its body record.
  CHECK(d.kind == "body_slot");
  CHECK(d.index == static_cast<int64_t>(extra.index1) - 1);
  CHECK(d.missing_in_a);
}

TEST_CASE("state: deltas against a base rebuild every image and refuse a wrong base or corruption",
          "[replay][state]") {
  const Scene scene = Scene::create_destroy;
  const Run original = run_original(scene, true);
  std::vector<uint8_t> delta;
  std::vector<uint8_t> rebuilt;
  size_t full_bytes = 0;
  size_t delta_bytes = 0;
  for (size_t t = 8; t < original.snapshots.size(); t += 3) {
    const std::vector<uint8_t>& base = original.snapshots[t - 8];
    const std::vector<uint8_t>& image = original.snapshots[t];
    encode_state_delta(base.data(), base.size(), image.data(), image.size(), &delta);
    const Status s = apply_state_delta(base.data(), base.size(), delta.data(), delta.size(), &rebuilt);
    INFO("tick " << t << ": " << s.message);
    REQUIRE(s.ok());
    REQUIRE(rebuilt == image);
    full_bytes += image.size();
    delta_bytes += delta.size();
  }
  CHECK(delta_bytes < full_bytes);  // unchanged structure costs little
  // Identical images: a header and a single run.
  const std::vector<uint8_t>& b0 = original.snapshots[100];
  encode_state_delta(b0.data(), b0.size(), b0.data(), b0.size(), &delta);
  CHECK(delta.size() < 40);
  REQUIRE(apply_state_delta(b0.data(), b0.size(), delta.data(), delta.size(), &rebuilt).ok());
  CHECK(rebuilt == b0);
  // Wrong base, wrong magic, truncation, trailing bytes.
  const std::vector<uint8_t>& b1 = original.snapshots[101];
  encode_state_delta(b0.data(), b0.size(), b1.data(), b1.size(), &delta);
  Status s = apply_state_delta(b1.data(), b1.size(), delta.data(), delta.size(), &rebuilt);
  CHECK(s.message.find("another base") != std::string::npos);
  std::vector<uint8_t> bad = delta;
  bad[1] = 'X';
  CHECK(apply_state_delta(b0.data(), b0.size(), bad.data(), bad.size(), &rebuilt).message.find("magic") !=
        std::string::npos);
  for (size_t n = 0; n < delta.size(); n += 5) {
    s = apply_state_delta(b0.data(), b0.size(), delta.data(), n, &rebuilt);
    INFO(n << ": " << s.message);
    CHECK(!s.ok());
    CHECK(s.message.find("offset ") != std::string::npos);
  }
  bad = delta;
  bad.push_back(0);
  CHECK(!apply_state_delta(b0.data(), b0.size(), bad.data(), bad.size(), &rebuilt).ok());
  // A huge claimed image size is refused before allocating.
  bad = delta;
  for (size_t k = 8; k < 16; ++k) bad[k] = 0xFF;
  s = apply_state_delta(b0.data(), b0.size(), bad.data(), bad.size(), &rebuilt);
  CHECK(s.message.find("image size") != std::string::npos);
}

TEST_CASE("state: byte layout is explicit little-endian (same bytes on every host)", "[replay][state]") {
  std::vector<uint8_t> v;
  ByteWriter w(&v);
  w.u16(0x0102);
  w.u32(0x03040506u);
  w.u64(0x0708090A0B0C0D0Eull);
  w.i32(-2);
  w.q32(Q32::from_raw(-1));
  const std::vector<uint8_t> expected = {0x02, 0x01, 0x06, 0x05, 0x04, 0x03, 0x0E, 0x0D, 0x0C, 0x0B, 0x0A, 0x09,
                                         0x08, 0x07, 0xFE, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF,
                                         0xFF, 0xFF};
  CHECK(v == expected);
  ByteReader r(v.data(), v.size());
  CHECK(r.u16("a") == 0x0102);
  CHECK(r.u32("b") == 0x03040506u);
  CHECK(r.u64("c") == 0x0708090A0B0C0D0Eull);
  CHECK(r.i32("d") == -2);
  CHECK(r.q32("e").raw == -1);
  CHECK(r.at_end());
  r.set_context("body", 17);
  CHECK(r.u64("linear_velocity.x") == 0);
  CHECK(!r.ok());
  CHECK(r.error() == "offset 26: expected 8 bytes of body 17 linear_velocity.x, 0 left");
  CHECK(r.u8("later") == 0);  // every later read fails too
  ByteReader counted(expected.data(), 4);
  CHECK(counted.read_count("items", 8) == 0);  // 0x03040102... far beyond the 0 bytes left
  CHECK(!counted.ok());

  // A buffer writer never writes past its capacity and counts the rest.
  uint8_t small[3] = {9, 9, 9};
  ByteWriter b(small, 2);
  b.u32(0xAABBCCDDu);
  CHECK(b.overflowed());
  CHECK(b.size() == 4);
  CHECK(small[2] == 9);

  // The hash is XXH3-64 of exactly the encoded bytes.
  OwnedWorld world(make_scene_world(Scene::pyramid));
  for (int64_t t = 0; t < 30; ++t) step_scene(Scene::pyramid, world.id, t);
  std::vector<uint8_t> image;
  REQUIRE(encode_world_state(world.id, &image).ok());
  // Header: magic, version 1, kind 0, then the world section tag.
  const std::vector<uint8_t> header = {'T', 'N', 'D', 'S', 1, 0, 0, 0, 0, 0, 0, 0, 'W', 'R', 'L', 'D'};
  CHECK(std::vector<uint8_t>(image.begin(), image.begin() + 16) == header);
  CHECK(XXH3_64bits(image.data(), image.size()) == world_state_hash(world.id));
}

}  // namespace
}  // namespace tandem
