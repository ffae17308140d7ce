// verify_replay and the diffs: a clean recording verifies; a run perturbed by
// one raw unit of one body's velocity at a known tick fails verification at
// that tick, and the diffs name that tick, that body and that field.
#include <catch2/catch.hpp>

#include "replay/verify.h"
#include "replay_file_test_support.h"

using namespace tandem;
using namespace tandem::literals;
using namespace tandem::replay_file_test;

namespace {

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

constexpr uint32_t k_perturbed_body = 3;  // the floating ball (touches nothing)

}  // namespace

TEST_CASE("a recorded run verifies", "[replay][verify]") {
  RecordSpec spec;
  spec.ticks = 30;
  const Replay r = read_ok(record_scene(spec));
  const VerifyReport rep = verify_replay(r);
  INFO(format_verify_report(rep));
  REQUIRE(rep.ok());
  CHECK(verify_exit_code(rep) == 0);
  CHECK(rep.ticks_run == 30);
  CHECK(rep.hashes_checked == 30);
  CHECK(rep.keyframes_checked == 7);
  CHECK(rep.refused_commands == 0);
  CHECK(contains(format_verify_report(rep), "OK: every recorded hash matches"));

  SECTION("max_ticks limits the check") {
    VerifyOptions o;
    o.max_ticks = 12;
    int64_t last_progress = 0;
    o.progress = [&](int64_t done, int64_t total) {
      CHECK(total == 12);
      last_progress = done;
    };
    const VerifyReport part = verify_replay(r, o);
    CHECK(part.ok());
    CHECK(part.ticks_run == 12);
    CHECK(last_progress == 12);
  }
  SECTION("every broad phase verifies (the state hash ignores the kind, keyframes keep it)") {
    for (BroadPhaseKind kind : {BroadPhaseKind::sweep_and_prune, BroadPhaseKind::grid, BroadPhaseKind::tree}) {
      RecordSpec other = spec;
      other.broad_phase = kind;
      const Replay ro = read_ok(record_scene(other));
      const VerifyReport k = verify_replay(ro);
      INFO(format_verify_report(k));
      CHECK(k.ok());
      CHECK(k.keyframes_checked == 7);
      // Same simulation, same hash chain, whatever the broad phase.
      CHECK_FALSE(diff_replays(r, ro).differs);
    }
  }
  SECTION("a recording without hashes is checked at its keyframes") {
    RecordSpec no_hash = spec;
    no_hash.hashes = false;
    const VerifyReport k = verify_replay(read_ok(record_scene(no_hash)));
    CHECK(k.ok());
    CHECK(k.hashes_checked == 0);
    CHECK(k.keyframes_checked == 7);
  }
}

TEST_CASE("user payloads go through the callback", "[replay][verify]") {
  RecordSpec spec;
  spec.ticks = 25;
  spec.with_payloads = true;
  const Replay r = read_ok(record_scene(spec));
  VerifyOptions with;
  with.payloads = payload_to_commands;
  const VerifyReport ok = verify_replay(r, with);
  INFO(format_verify_report(ok));
  CHECK(ok.ok());
  // Without the callback the payloads' impulses are missing: tick 2 is the
  // first with a payload (and its impulse is not zero: 2 % 5 = 2 eighths).
  const VerifyReport skipped = verify_replay(r);
  CHECK(skipped.mismatch);
  CHECK(skipped.mismatch_tick == 2);
  CHECK(skipped.skipped_payloads == 1);
  CHECK(contains(format_verify_report(skipped), "user input payloads skipped (no handler to turn them into commands): 1"));
  CHECK(ok.skipped_payloads == 0);
  // A callback that fails stops the run with an error (exit code 2).
  VerifyOptions failing;
  failing.payloads = [](int64_t, std::span<const uint8_t>, std::vector<Command>*) {
    return Status{StatusCode::invalid_argument, "unknown input"};
  };
  const VerifyReport err = verify_replay(r, failing);
  CHECK(verify_exit_code(err) == 2);
  CHECK(err.error.message == "verify: tick 2: payload handler: unknown input");
}

TEST_CASE("a one-raw-unit desync is found at its tick, body and field", "[replay][verify]") {
  RecordSpec clean_spec;
  clean_spec.ticks = 24;
  clean_spec.keyframe_interval = 5;
  const Replay clean = read_ok(record_scene(clean_spec));

  SECTION("on a keyframe tick: exact") {
    RecordSpec spec = clean_spec;
    spec.perturb_tick = 10;
    const Replay bad = read_ok(record_scene(spec));
    const VerifyReport rep = verify_replay(bad);
    INFO(format_verify_report(rep));
    REQUIRE(rep.mismatch);
    CHECK(verify_exit_code(rep) == 1);
    CHECK(rep.mismatch_tick == 10);
    CHECK(rep.expected_hash == bad.ticks[9].hash);
    CHECK(rep.actual_hash == clean.ticks[9].hash);
    CHECK(rep.hashes_checked == 9);
    CHECK(rep.self_consistent);
    REQUIRE(rep.located);
    CHECK(rep.located_tick == 10);
    CHECK(rep.difference.kind == "body");
    CHECK(rep.difference.index == k_perturbed_body);
    CHECK(rep.difference.field == "linear_velocity.x");
    CHECK(rep.difference.value_a == rep.difference.value_b + 1);  // a = recorded (perturbed)
    const std::string text = format_verify_report(rep);
    CHECK(contains(text, "MISMATCH at tick 10"));
    CHECK(contains(text, "body 3 linear_velocity.x"));

    // Replay against replay: the hash chains part at tick 10.
    const DiffReport d = diff_replays(clean, bad);
    INFO(format_diff_report(d));
    REQUIRE(d.differs);
    CHECK(diff_exit_code(d) == 1);
    CHECK(d.method == "hash chain");
    CHECK(d.tick == 10);
    CHECK_FALSE(d.inputs_differ);
    REQUIRE(d.located);
    CHECK(d.located_tick == 10);
    CHECK(d.difference.kind == "body");
    CHECK(d.difference.index == k_perturbed_body);
    CHECK(d.difference.field == "linear_velocity.x");
    CHECK(d.difference.value_b == d.difference.value_a + 1);
    CHECK(d.difference.is_q32);
    CHECK(contains(format_diff_report(d, "clean", "bad"), "DIFFERENT from tick 10"));
  }
  SECTION("between keyframes: the tick exactly, the body at the next keyframe") {
    RecordSpec spec = clean_spec;
    spec.perturb_tick = 12;
    const Replay bad = read_ok(record_scene(spec));
    const VerifyReport rep = verify_replay(bad);
    INFO(format_verify_report(rep));
    REQUIRE(rep.mismatch);
    CHECK(rep.mismatch_tick == 12);
    REQUIRE(rep.located);
    CHECK(rep.located_tick == 15);
    CHECK(rep.difference.kind == "body");
    CHECK(rep.difference.index == k_perturbed_body);
    CHECK(contains(rep.note, "next keyframe, tick 15"));

    const DiffReport d = diff_replays(clean, bad);
    INFO(format_diff_report(d));
    CHECK(d.tick == 12);
    REQUIRE(d.located);
    CHECK(d.located_tick == 15);
    CHECK(d.difference.index == k_perturbed_body);
  }
  SECTION("a replay against a live run: exact at any tick") {
    OwnedWorld live;
    REQUIRE(world_restore(live.id, clean.keyframes[0].state.data(), clean.keyframes[0].state.size()).ok());
    const int64_t perturb = 13;
    const LiveTick advance = [&](int64_t t) {
      for (const Command& c : scene_commands(t)) (void)apply_command(live.id, c);
      StepResult s = world_step(live.id, clean.header.time_step);
      if (!s.ok()) return s.status;
      if (t == perturb) {
        const BodyId b = body_id(live.id, BodyRef{k_perturbed_body, 1});
        Vec2 v = body_linear_velocity(b);
        v.x.raw -= 1;
        return body_set_linear_velocity(b, v);
      }
      return Status{};
    };
    const DiffReport d = diff_replay_live(clean, live.id, advance, 100);
    INFO(format_diff_report(d));
    REQUIRE(d.differs);
    CHECK(d.method == "live run");
    CHECK(d.tick == perturb);
    CHECK(d.ticks_compared == perturb);
    REQUIRE(d.located);
    CHECK(d.difference.kind == "body");
    CHECK(d.difference.index == k_perturbed_body);
    CHECK(d.difference.field == "linear_velocity.x");
    CHECK(d.difference.value_b == d.difference.value_a - 1);
  }
  SECTION("without hashes both runs are re-simulated") {
    RecordSpec spec = clean_spec;
    spec.hashes = false;
    const Replay a = read_ok(record_scene(spec));
    Replay b = a;
    // A recorded input that differs by one raw unit at tick 17.
    b.ticks[16].commands.push_back(make_set_angular_velocity(BodyRef{k_perturbed_body, 1}, Q32::from_raw(1)));
    const DiffReport d = diff_replays(a, b);
    INFO(format_diff_report(d));
    CHECK(d.method == "resimulation");
    CHECK(d.inputs_differ);
    CHECK(d.inputs_differ_tick == 17);
    CHECK(d.tick == 17);
    REQUIRE(d.located);
    CHECK(d.difference.index == k_perturbed_body);
    CHECK(d.difference.field == "angular_velocity");
  }
  SECTION("identical replays and different lengths") {
    const DiffReport same = diff_replays(clean, clean);
    CHECK_FALSE(same.differs);
    CHECK(diff_exit_code(same) == 0);
    CHECK(same.ticks_compared == 24);
    Replay shorter = clean;
    shorter.ticks.resize(20);
    const DiffReport len = diff_replays(clean, shorter);
    CHECK(len.differs);
    CHECK(len.length_differs);
    CHECK(contains(format_diff_report(len), "A has 24 ticks, B has 20"));
  }
}

TEST_CASE("snapshots diff to the record and field", "[replay][verify]") {
  const Replay r = read_ok(record_scene(RecordSpec{}));
  Result<WorldId> w = r.create_world_at(7);
  REQUIRE(w.ok());
  OwnedWorld world(w.value);
  std::vector<uint8_t> a, b;
  REQUIRE(encode_world_state(world.id, &a).ok());
  const BodyId body = body_id(world.id, BodyRef{2, 1});
  REQUIRE(body_set_angular_velocity(body, body_angular_velocity(body) + Q32::from_raw(1)).ok());
  REQUIRE(encode_world_state(world.id, &b).ok());
  const DiffReport d = diff_snapshots(a, b);
  INFO(format_diff_report(d));
  REQUIRE(d.differs);
  CHECK(d.method == "snapshot");
  CHECK(d.difference.index == 2);
  CHECK(d.difference.field == "angular_velocity");
  CHECK(diff_snapshots(a, a).differs == false);
  std::vector<uint8_t> broken(a.begin(), a.begin() + 10);
  const DiffReport bad = diff_snapshots(a, broken);
  CHECK(diff_exit_code(bad) == 2);
  CHECK(contains(bad.error.message, "B state: "));
}
