// ray_bench.cpp — the ray-cast benchmark (`tandem bench --rays N`, suite.h):
// closest-hit rays per second in each selected engine on the same scene
// (default rain-4000) in one run.
//
// Rays: N rays from a fixed integer generator (SplitMix64, seed 2024), each an
// origin uniform in the scene's container (an open top is closed at the
// container's width above its floor: rain-4000's rays start in x ∈ ±40 m,
// y ∈ [0, 80] m, the pile's lower half of that) and a translation uniform in a
// square of half side a quarter of the container's width (so rays cross a few
// metres to tens of metres of the pile, as line-of-sight and bullet rays do),
// zero-length ones redrawn (Box2D asserts on them). The values are exact Q32
// (raw multiples of 2^-16 m); the peers get them as doubles, then floats.
//
// Every engine builds the scene and steps `warmup` steps (default 600, the
// stepping benchmark's length: the rain has landed in a pile). Then `runs`
// rounds: in each, every engine in turn (the order rotating by one each round,
// so a burst of load on the shared machine does not always hit the same
// engine) steps once, untimed, and casts every ray once, timed. In
// Tandem the first query after a step re-syncs the broad phase with the
// step's poses (physics/broad_phase.h, "Queries") — work the next step's
// broad phase then skips, so a per-step cost moved, not added: it is timed
// apart (one untimed query before the batch, reported as "sync ms"). Box2D
// 2.4 moves its proxies inside Step, and its RayCast callback returns the
// hit's fraction (clipping the ray: the closest hit). Reported: the median rays/s over the batches
// (min–max), the rays that hit in the last batch, and Tandem ÷ peer. Every
// Tandem broad phase must give the same hits (FNV-1a of shape index and
// fraction): the suite warns otherwise.
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <memory>

#include "suite.h"

namespace tandem::bench {
namespace {

uint64_t splitmix(uint64_t* state) {
  uint64_t z = (*state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

/// A raw Q32 multiple of 2^-16 m uniform in [lo, hi] m (container bounds are
/// finite for the scenes this runs on; clamped to ±1000 m otherwise).
Q32 uniform_metres(uint64_t* state, double lo, double hi) {
  lo = std::max(lo, -1000.0);
  hi = std::min(hi, 1000.0);
  const int64_t a = static_cast<int64_t>(lo * 65536.0), b = static_cast<int64_t>(hi * 65536.0);
  const uint64_t span = static_cast<uint64_t>(b - a) + 1;
  return Q32::from_raw((a + static_cast<int64_t>(splitmix(state) % span)) * 65536);
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  if (n == 0) return 0;
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

std::vector<RaySpec> make_rays(const SceneSpec& scene, int32_t count) {
  Container c = scene.container;
  c.min_x = std::max(c.min_x, -1000.0);
  c.max_x = std::min(c.max_x, 1000.0);
  c.min_y = std::max(c.min_y, -1000.0);
  // An open top (rain): a square region from the floor up.
  c.max_y = std::min(c.max_y, c.min_y + (c.max_x - c.min_x));
  const double reach = 0.25 * (c.max_x - c.min_x);
  uint64_t state = 2024;
  std::vector<RaySpec> rays;
  while (static_cast<int32_t>(rays.size()) < count) {
    RaySpec r;
    r.origin = {uniform_metres(&state, c.min_x, c.max_x), uniform_metres(&state, c.min_y, c.max_y)};
    r.translation = {uniform_metres(&state, -reach, reach), uniform_metres(&state, -reach, reach)};
    if (r.translation.x.raw == 0 && r.translation.y.raw == 0) continue;
    rays.push_back(r);
  }
  return rays;
}

int run_ray_bench(const BenchOptions& o, const std::vector<SceneSpec>& scenes, const std::vector<Engine>& engines,
                  const std::string& machine) {
  const int32_t warmup = o.warmup >= 0 ? o.warmup : 600;
  std::printf("\nTandem ray-cast benchmark — %s\n", machine.c_str());
  std::printf("%d rays per batch (closest hit), %d rounds after %d warm-up steps; each round every engine steps once "
              "(untimed) and casts its batch, in a rotating order. Median rays/s over the rounds (min-max); ratio = "
              "Tandem / peer (above 1: Tandem faster).\n\n",
              o.rays, o.runs, warmup);
  std::ofstream csv;
  if (!o.csv.empty()) {
    csv.open(o.csv);
    if (!csv) {
      std::fprintf(stderr, "bench: cannot write CSV file '%s'\n", o.csv.c_str());
      return 2;
    }
    csv << "scene,engine,broad_phase,rays,batches,median_rays_per_s,min,max,hits,median_sync_ms\n";
  }
  int status = 0;
  for (const SceneSpec& scene : scenes) {
    const std::vector<RaySpec> rays = make_rays(scene, o.rays);
    struct Line {
      std::string label;
      bool peer = false;
      std::unique_ptr<RaySession> session;
      std::string error;
      std::vector<RayBatch> batches;
    };
    std::vector<Line> lines;
    for (const Engine& e : engines) {
      if (!e.cast_rays || (e.max_bodies > 0 && scene.dynamic_count > e.max_bodies)) continue;
      Line line;
      line.label = e.is_peer ? e.engine : e.engine + "/" + e.broad_phase;
      line.peer = e.is_peer;
      if (!o.quiet) std::fprintf(stderr, "  %-14s %-16s building, %d warm-up steps\n", scene.name.c_str(),
                                 line.label.c_str(), warmup);
      line.session = e.cast_rays(scene, warmup, &line.error);
      if (line.session == nullptr && line.error.empty()) line.error = "refused";
      lines.push_back(std::move(line));
    }
    const size_t n = lines.size();
    for (int32_t round = 0; round < o.runs; ++round) {
      const RayBatch* reference = nullptr;
      std::string reference_label;
      for (size_t k = 0; k < n; ++k) {
        Line& l = lines[(k + static_cast<size_t>(round)) % n];
        if (l.session == nullptr) continue;
        l.batches.push_back(l.session->batch(rays));
        const RayBatch& b = l.batches.back();
        if (!b.has_fingerprint) continue;
        // Every Tandem engine is at the same tick in a round: same hits.
        if (reference == nullptr) {
          reference = &b;
          reference_label = l.label;
        } else if (b.fingerprint != reference->fingerprint || b.hits != reference->hits) {
          std::fprintf(stderr, "bench: WARNING: %s round %d: %s hits differ from %s\n", scene.name.c_str(), round,
                       l.label.c_str(), reference_label.c_str());
          status = 1;
        }
      }
      if (!o.quiet) std::fprintf(stderr, "  %-14s round %d/%d done\n", scene.name.c_str(), round + 1, o.runs);
    }
    std::vector<double> medians(n, 0.0);
    for (size_t i = 0; i < n; ++i) {
      std::vector<double> rps;
      for (const RayBatch& b : lines[i].batches) rps.push_back(b.rays_per_second);
      medians[i] = median(rps);
    }
    std::printf("%-14s %-16s %12s %-25s %7s %8s  %s\n", "scene", "engine", "rays/s", "min-max", "hits", "sync ms",
                "ratios");
    for (size_t i = 0; i < n; ++i) {
      const Line& l = lines[i];
      if (l.session == nullptr) {
        std::printf("%-14s %-16s error: %s\n", scene.name.c_str(), l.label.c_str(), l.error.c_str());
        continue;
      }
      std::vector<double> rps, sync;
      for (const RayBatch& b : l.batches) {
        rps.push_back(b.rays_per_second);
        if (b.sync_ms >= 0) sync.push_back(b.sync_ms);
      }
      const double lo = rps.empty() ? 0 : *std::min_element(rps.begin(), rps.end());
      const double hi = rps.empty() ? 0 : *std::max_element(rps.begin(), rps.end());
      const int32_t hits = l.batches.empty() ? 0 : l.batches.back().hits;
      char range[64];
      std::snprintf(range, sizeof range, "%.0f-%.0f", lo, hi);
      std::printf("%-14s %-16s %12.0f %-25s %7d ", scene.name.c_str(), l.label.c_str(), medians[i], range, hits);
      if (sync.empty()) {
        std::printf("%8s ", "-");
      } else {
        std::printf("%8.3f ", median(sync));
      }
      if (!l.peer) {
        for (size_t k = 0; k < n; ++k) {
          if (lines[k].peer && medians[k] > 0) std::printf(" /%s %.2f", lines[k].label.c_str(), medians[i] / medians[k]);
        }
      }
      std::printf("\n");
      if (csv) {
        csv << scene.name << ',' << (l.peer ? l.label : "tandem") << ','
            << (l.peer ? "" : l.label.substr(l.label.find('/') + 1)) << ',' << o.rays << ',' << l.batches.size()
            << ',' << medians[i] << ',' << lo << ',' << hi << ',' << hits << ',' << (sync.empty() ? 0.0 : median(sync))
            << '\n';
      }
    }
  }
  return status;
}

}  // namespace tandem::bench
