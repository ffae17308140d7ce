// The per-stage profile (world_profile, physics/tandem.h): every stage is
// filled and non-negative, the stages sum to at most the total, and reading
// the profile after every tick leaves the golden chains bit-identical (the
// profile is timing only, never state).
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <utility>

#include "golden_support.h"

using namespace tandem;
using namespace tandem::golden;

namespace {

/// The profile's fields with their names, in declaration order.
std::array<std::pair<const char*, int64_t>, 14> stages(const WorldProfile& p) {
  return {{{"broad_phase", p.broad_phase_ns},
           {"narrow_phase", p.narrow_phase_ns},
           {"islands", p.islands_ns},
           {"events", p.events_ns},
           {"prepare", p.prepare_ns},
           {"integrate_velocities", p.integrate_velocities_ns},
           {"warm_start", p.warm_start_ns},
           {"solve", p.solve_ns},
           {"integrate_positions", p.integrate_positions_ns},
           {"relax", p.relax_ns},
           {"restitution", p.restitution_ns},
           {"store_impulses", p.store_impulses_ns},
           {"continuous", p.continuous_ns},
           {"finalize", p.finalize_ns}}};
}

const Scene* find_scene(const std::string& name) {
  for (const Scene& s : scenes()) {
    if (name == s.name) return &s;
  }
  return nullptr;
}

}  // namespace

TEST_CASE("profile: stages filled, non-negative, summing to at most the total, chains unchanged",
          "[golden][profile]") {
  if (regenerate_mode()) return;
  for (const char* name : {"pyramid", "friction_restitution", "sleep_wake", "random_mix"}) {
    const Scene* scene = find_scene(name);
    REQUIRE(scene != nullptr);
    std::array<int64_t, 14> most{};  // largest value each stage took over the run
    int64_t most_total = 0;
    std::string problem;
    ChainOptions options;
    options.ticks = tick_cap();
    options.observe = [&](SceneContext& ctx, int32_t tick) {
      const WorldProfile p = world_profile(ctx.world);
      int64_t sum = 0;
      const auto named = stages(p);
      for (size_t i = 0; i < named.size(); ++i) {
        if (named[i].second < 0 && problem.empty()) {
          problem = "tick " + std::to_string(tick) + ": " + named[i].first + " = " + std::to_string(named[i].second);
        }
        sum += named[i].second;
        most[i] = std::max(most[i], named[i].second);
      }
      if (sum > p.total_ns && problem.empty()) {
        problem = "tick " + std::to_string(tick) + ": stages sum to " + std::to_string(sum) + " ns > total " +
                  std::to_string(p.total_ns) + " ns";
      }
      most_total = std::max(most_total, p.total_ns);
    };
    const Chain run = run_chain(*scene, options);
    INFO("scene " << name);
    REQUIRE(run.error.empty());
    CHECK(problem.empty());
    INFO(problem);
    CHECK(most_total > 0);
    const auto named = stages(WorldProfile{});
    for (size_t i = 0; i < most.size(); ++i) {
      INFO("stage " << named[i].first << " never took any time");
      CHECK(most[i] > 0);
    }
    // Reading the profile after every tick changed no bit of the run.
    const Chain golden = read_golden(name);
    INFO(golden.error);
    REQUIRE(golden.error.empty());
    const std::string diff = compare(golden, run);
    INFO(diff);
    CHECK(diff.empty());
  }
}

TEST_CASE("profile: zeroes for an invalid world, an empty or refused step leaves it unchanged", "[golden][profile]") {
  const WorldProfile none = world_profile(WorldId{});
  CHECK(none.total_ns == 0);
  CHECK(none.solve_ns == 0);
  const Result<WorldId> made = create_world(default_world_def());
  REQUIRE(made.ok());
  const WorldId w = made.value;
  CHECK(world_profile(w).total_ns == 0);  // before the first step
  BodyDef def = default_body_def();
  def.type = BodyType::dynamic_body;
  const Result<BodyId> body = create_body(w, def);
  REQUIRE(body.ok());
  REQUIRE(world_step(w, Q32::from_ratio(1, 60)).ok());
  const WorldProfile after = world_profile(w);
  CHECK(after.total_ns > 0);
  REQUIRE(world_step(w, Q32::zero()).ok());  // 0 s: nothing happens
  CHECK(world_profile(w).total_ns == after.total_ns);
  CHECK_FALSE(world_step(w, -Q32::one()).ok());  // refused
  CHECK(world_profile(w).total_ns == after.total_ns);
  REQUIRE(destroy_world(w).ok());
  CHECK(world_profile(w).total_ns == 0);  // destroyed: an invalid handle
}
