// harness.h — what one engine harness does with one scene (tools only).
//
// A harness builds a fresh world from a SceneSpec, steps it `warmup` steps
// untimed and `steps` steps timed (StepTimer around the timed loop only: wall
// clock and the process's CPU time), and probes the result. Quality numbers come from doubles read back from the
// engine after the run (display only; nothing flows back into a world):
//   ke_start / ke_end   total kinetic energy Σ ½mv² + ½Iω² of the dynamic
//                       bodies, J, as created and after warm-up + timed steps
//   track_y_*           the tracked body's height (pyramid top box), m
//   max_speed           fastest dynamic body at the end, m/s
//   escaped             dynamic bodies whose centre ends outside the container
//   moved               dynamic bodies that ended > 0.25 m sideways from their
//                       start (a pyramid that stands has none)
//   profile             Tandem only: world_profile() of every timed step
//   fingerprint         Tandem only: FNV-1a of every body's position,
//                       rotation and velocity raws at the end, so broad
//                       phases can be checked to give identical states
//
// Engines: Tandem with one broad phase per Engine (harness_tandem.cpp), and
// the peers (peers.h) when they are linked in.
#pragma once

#include <time.h>

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "fixed/vec2.h"
#include "profile_stats.h"
#include "scenes.h"

namespace tandem::bench {

/// Quality probes of one run (see the file comment).
struct Quality {
  double ke_start = 0;
  double ke_end = 0;
  double track_y_start = 0;
  double track_y_end = 0;
  double max_speed = 0;
  int32_t escaped = 0;
  int32_t moved = 0;  ///< dynamic bodies now more than 0.25 m sideways (x) from where they were made
  bool has_fingerprint = false;
  uint64_t fingerprint = 0;
};

/// One run: milliseconds per timed step and the probes; `error` non-empty
/// when the engine refused the scene (then nothing else is meaningful).
struct RunResult {
  double ms_per_step = 0;      ///< wall clock (steady_clock), ms per timed step
  double cpu_ms_per_step = 0;  ///< the process's CPU time (every thread), ms per timed step
  Quality quality;
  ProfileSeries profile;  ///< Tandem only: world_profile() after every timed step
  std::string error;
};

/// The process's CPU time so far, ms (CLOCK_PROCESS_CPUTIME_ID: the sum over
/// its threads, so it equals wall time only for a single-threaded run that
/// was never descheduled).
inline double process_cpu_ms() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) * 1e3 + static_cast<double>(t.tv_nsec) * 1e-6;
}

/// Times an engine's timed loop: construct just before it, call stop() just
/// after; writes wall and CPU ms per step into the result.
class StepTimer {
 public:
  StepTimer() : wall0_(std::chrono::steady_clock::now()), cpu0_(process_cpu_ms()) {}
  /// Writes ms per step over `steps` steps (0 when steps is 0).
  void stop(int32_t steps, RunResult* result) const {
    const double cpu = process_cpu_ms() - cpu0_;
    const double wall = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - wall0_).count();
    result->ms_per_step = steps > 0 ? wall / steps : 0.0;
    result->cpu_ms_per_step = steps > 0 ? cpu / steps : 0.0;
  }

 private:
  std::chrono::steady_clock::time_point wall0_;
  double cpu0_;
};

/// Runs one scene once: build, `warmup` untimed steps, `steps` timed steps.
using RunFunction = std::function<RunResult(const SceneSpec& scene, int32_t warmup, int32_t steps)>;

/// A ray of the ray-cast benchmark: origin and translation, m (exact Q32;
/// peers get them as doubles).
struct RaySpec {
  Vec2 origin;
  Vec2 translation;
};

/// One timed batch of the ray-cast benchmark (ray_bench.cpp).
struct RayBatch {
  double rays_per_second = 0;
  double sync_ms = -1;            ///< Tandem: the untimed first query after the step (broad-phase re-sync); −1: none
  int32_t hits = 0;               ///< rays that hit something
  bool has_fingerprint = false;   ///< Tandem only
  uint64_t fingerprint = 0;       ///< FNV-1a of the hits (shape index, fraction raw)
};

/// A scene built in one engine and stepped `warmup` steps, ready to cast
/// batches of rays; its destructor frees the world.
class RaySession {
 public:
  virtual ~RaySession() = default;
  /// One untimed step, then every ray cast once for its closest hit, timed
  /// (steady_clock).
  virtual RayBatch batch(const std::vector<RaySpec>& rays) = 0;
};

/// Builds a RaySession; null with *error set when the engine refuses the scene.
using RayFunction =
    std::function<std::unique_ptr<RaySession>(const SceneSpec& scene, int32_t warmup, std::string* error)>;

/// One engine configuration as it appears in the results.
struct Engine {
  std::string engine;       ///< "tandem", "box2d24", "chipmunk"
  std::string broad_phase;  ///< Tandem: naive, sap, grid, tree; peers: their default
  std::string note;         ///< printed beside the numbers (build caveats)
  bool is_peer = false;
  int32_t max_bodies = 0;   ///< skip scenes with more dynamic bodies (0: no limit)
  int32_t workers = 1;      ///< Tandem: WorldDef::worker_count; peers: 1
  RunFunction run;
  RayFunction cast_rays;    ///< the ray-cast benchmark; empty where not written (Chipmunk, Box2D v3)
};

/// Tandem's broad phases by short name: "naive", "sap", "grid", "tree".
std::vector<std::string> tandem_broad_phase_names();

/// The Tandem engine with the named broad phase ("naive", "sap", "grid",
/// "tree"); false when the name is unknown. A broad phase that the linked
/// physics library refuses shows up as a run error, not here.
/// `workers`: WorldDef::worker_count (1…16).
bool tandem_engine(const std::string& broad_phase, int32_t workers, Engine* out);

/// The peer engines linked into this program (peers.cpp: Box2D 2.4 and
/// Chipmunk2D when built with TANDEM_BUILD_BENCH, peers_none.cpp: none).
std::vector<Engine> peer_engines();

/// Why peer_engines() is empty, or "" when it is not.
const char* peers_unavailable_reason();

}  // namespace tandem::bench
