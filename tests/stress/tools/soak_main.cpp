// soak_main.cpp — tandem_soak: runs a scene for a long time while recording
// a replay, and measures whether memory stays flat and step time does not
// drift (issue 14's soak; scripts/soak.sh runs it for one hour of simulated
// time, 216,000 ticks at 60 Hz, on scenes/tumbler_soak.json).
//
//   tandem_soak [--scene FILE] [--ticks N] [--out REPLAY] [--keyframe-every K]
//               [--window W] [--verify] [--max-heap-growth BYTES]
//
// Measured:
//   heap   live bytes from operator new/delete (this file replaces the global
//          allocation functions with counting ones; each allocation carries a
//          16-byte size header) and the number of live allocations;
//   RSS    VmRSS from /proc/self/status;
//   at ticks 1,000, 50,000, 100,000, 150,000 and the last tick (those past
//   the run are skipped; for runs under 50,000 ticks: 1/6, 1/2 and the end).
//   step   the wall time of each recorded tick (step + hash + replay write),
//          steady clock; the median of the early window [1000, 1000 + W) and
//          of the last W ticks (W = 10,000, or ticks / 6 when shorter).
// Checks (exit 1 when one fails): every step accepted; live heap at the end
// minus live heap at the first sample after warm-up (the second sample) ≤
// --max-heap-growth (default 262,144 bytes); with --verify, the replay read
// back and re-simulated from its tick-0 keyframe matches every tick's hash.
// Step-time drift is reported, not asserted (the machine is shared).
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <new>
#include <string>
#include <vector>

#define XXH_INLINE_ALL
#include <xxhash.h>

#include "replay/replay_file.h"
#include "replay/state.h"
#include "replay/verify.h"
#include "scene/scene.h"

// --- counting allocator ---------------------------------------------------------

namespace {

// Relaxed counters: the soak is single-threaded; atomics keep any stray
// library thread from racing.
std::atomic<int64_t> g_live_bytes{0};
std::atomic<int64_t> g_live_blocks{0};
constexpr size_t k_header = 16;  // keeps the 16-byte alignment malloc gives

void* counted_alloc(size_t size) {
  void* p = std::malloc(size + k_header);
  if (p == nullptr) return nullptr;
  std::memcpy(p, &size, sizeof size);
  g_live_bytes.fetch_add(static_cast<int64_t>(size), std::memory_order_relaxed);
  g_live_blocks.fetch_add(1, std::memory_order_relaxed);
  return static_cast<char*>(p) + k_header;
}

void counted_free(void* q) {
  if (q == nullptr) return;
  char* p = static_cast<char*>(q) - k_header;
  size_t size = 0;
  std::memcpy(&size, p, sizeof size);
  g_live_bytes.fetch_sub(static_cast<int64_t>(size), std::memory_order_relaxed);
  g_live_blocks.fetch_sub(1, std::memory_order_relaxed);
  std::free(p);
}

}  // namespace

void* operator new(size_t size) {
  void* p = counted_alloc(size);
  if (p == nullptr) throw std::bad_alloc();
  return p;
}
void* operator new[](size_t size) {
  void* p = counted_alloc(size);
  if (p == nullptr) throw std::bad_alloc();
  return p;
}
void* operator new(size_t size, const std::nothrow_t&) noexcept { return counted_alloc(size); }
void* operator new[](size_t size, const std::nothrow_t&) noexcept { return counted_alloc(size); }
void operator delete(void* p) noexcept { counted_free(p); }
void operator delete[](void* p) noexcept { counted_free(p); }
void operator delete(void* p, size_t) noexcept { counted_free(p); }
void operator delete[](void* p, size_t) noexcept { counted_free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { counted_free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { counted_free(p); }

namespace {

using namespace tandem;

int64_t rss_kib() {
  std::FILE* f = std::fopen("/proc/self/status", "r");
  if (f == nullptr) return -1;
  char line[256];
  int64_t kib = -1;
  while (std::fgets(line, sizeof line, f) != nullptr) {
    if (std::strncmp(line, "VmRSS:", 6) == 0) {
      kib = std::strtoll(line + 6, nullptr, 10);
      break;
    }
  }
  std::fclose(f);
  return kib;
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2.0;
}

bool parse_i64(const char* text, int64_t* out) {
  char* end = nullptr;
  const long long v = std::strtoll(text, &end, 10);
  if (end == text || *end != '\0' || v < 0) return false;
  *out = v;
  return true;
}

int usage(const std::string& why) {
  std::fprintf(stderr,
               "tandem_soak: %s\nusage: tandem_soak [--scene FILE] [--ticks N] [--out REPLAY] [--keyframe-every K] "
               "[--window W] [--verify] [--max-heap-growth BYTES]\n",
               why.c_str());
  return 2;
}

struct Sample {
  int64_t tick;
  int64_t heap_bytes;
  int64_t heap_blocks;
  int64_t rss;  // KiB
};

}  // namespace

int main(int argc, char** argv) {
  std::string scene_path = "scenes/tumbler_soak.json";
  std::string out = "soak.tandem-replay";
  int64_t ticks = 216000, keyframe_every = 6000, window = -1, max_growth = 262144;
  bool verify = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto num = [&](int64_t* v) { return i + 1 < argc && parse_i64(argv[++i], v); };
    if (a == "--scene" && i + 1 < argc) scene_path = argv[++i];
    else if (a == "--out" && i + 1 < argc) out = argv[++i];
    else if (a == "--ticks") { if (!num(&ticks) || ticks < 6) return usage("--ticks needs a number ≥ 6"); }
    else if (a == "--keyframe-every") { if (!num(&keyframe_every) || keyframe_every > UINT32_MAX) return usage("--keyframe-every needs a number"); }
    else if (a == "--window") { if (!num(&window) || window < 1) return usage("--window needs a number ≥ 1"); }
    else if (a == "--max-heap-growth") { if (!num(&max_growth)) return usage("--max-heap-growth needs a number"); }
    else if (a == "--verify") verify = true;
    else return usage("unknown or incomplete argument " + a);
  }
  if (window < 0) window = std::min<int64_t>(10000, ticks / 6);
  const int64_t early_start = std::min<int64_t>(1000, ticks / 6);
  if (early_start + window > ticks) return usage("--window too long for --ticks");

  std::vector<int64_t> sample_ticks;
  if (ticks >= 50000) {
    for (int64_t t : {int64_t{1000}, int64_t{50000}, int64_t{100000}, int64_t{150000}})
      if (t < ticks) sample_ticks.push_back(t);
  } else {
    sample_ticks = {ticks / 6, ticks / 2};
  }
  sample_ticks.push_back(ticks);

  Result<scene::Scene> loaded = scene::load_scene_file(scene_path);
  if (!loaded.ok()) return usage(loaded.status.message);
  const scene::Scene& sc = loaded.value;
  Result<scene::BuiltScene> built = scene::build_world(sc);
  if (!built.ok()) return usage(built.status.message);
  std::vector<uint8_t> text;
  if (Status st = read_file_bytes(scene_path, &text); !st.ok()) return usage(st.message);

  RecorderOptions options;
  options.keyframe_interval = static_cast<uint32_t>(keyframe_every);
  options.time_step = sc.time_step;
  options.flush_every = 60;
  ReplayRecorder recorder;
  if (Status st = recorder.open_file(out, options); !st.ok()) return usage(st.message);
  if (Status st = recorder.begin(built.value.world, text, XXH3_64bits(text.data(), text.size())); !st.ok())
    return usage(st.message);

  std::printf("soak: %s, %" PRId64 " ticks (%.1f min simulated), replay %s, keyframe every %" PRId64 " ticks\n",
              scene_path.c_str(), ticks, static_cast<double>(ticks) / sc.step_hz / 60.0, out.c_str(), keyframe_every);
  std::vector<double> step_ms(static_cast<size_t>(ticks), 0.0);
  std::vector<Sample> samples;
  size_t next_sample = 0;
  const auto t_start = std::chrono::steady_clock::now();
  int failures = 0;
  for (int64_t t = 0; t < ticks; ++t) {
    for (const Command& c : scene::scene_inputs_at(built.value, sc, t)) (void)recorder.submit(c);
    const auto a = std::chrono::steady_clock::now();
    const StepResult r = recorder.step();
    const auto b = std::chrono::steady_clock::now();
    step_ms[static_cast<size_t>(t)] = std::chrono::duration<double, std::milli>(b - a).count();
    if (!r.ok()) {
      std::printf("FAIL step %" PRId64 ": %s\n", t + 1, r.status.message.c_str());
      return 1;
    }
    if (next_sample < sample_ticks.size() && t + 1 == sample_ticks[next_sample]) {
      const Sample s{t + 1, g_live_bytes.load(), g_live_blocks.load(), rss_kib()};
      samples.push_back(s);
      std::printf("tick %7" PRId64 ": live heap %" PRId64 " bytes in %" PRId64 " blocks, RSS %" PRId64
                  " KiB, %.0f s wall so far\n",
                  s.tick, s.heap_bytes, s.heap_blocks, s.rss,
                  std::chrono::duration<double>(b - t_start).count());
      std::fflush(stdout);
      ++next_sample;
    }
  }
  if (Status st = recorder.finish(); !st.ok()) {
    std::printf("FAIL finishing the replay: %s\n", st.message.c_str());
    return 1;
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
  const uint64_t final_hash = world_state_hash(built.value.world);

  // Bodies still inside the drum: the drum turns about the origin, so a body
  // inside stays within the drum's inner circle of corners (8 m half size →
  // 7.5 m inner half width, 10.61 m to a corner).
  BodyId bodies[1024];
  const int32_t n = world_bodies(built.value.world, bodies, 1024);
  int32_t outside = 0;
  for (int32_t i = 0; i < n && i < 1024; ++i) {
    const Vec2 c = body_world_center(bodies[i]);
    if (length(c) > 10.61_q32) ++outside;
  }

  std::vector<double> early(step_ms.begin() + early_start, step_ms.begin() + early_start + window);
  std::vector<double> late(step_ms.end() - window, step_ms.end());
  const double m_early = median(early), m_late = median(late);
  std::printf("steps: median %.4f ms over ticks %" PRId64 "-%" PRId64 ", %.4f ms over the last %" PRId64
              " ticks (late/early %.3f); whole run %.1f s wall, %.4f ms per tick overall\n",
              m_early, early_start + 1, early_start + window, m_late, window, m_late / m_early, wall,
              1000.0 * wall / static_cast<double>(ticks));
  std::printf("bodies: %d, outside the drum at the end: %d; final hash %016" PRIx64 "\n", n, outside, final_hash);
  if (samples.size() >= 2) {
    const int64_t growth = samples.back().heap_bytes - samples[1].heap_bytes;
    std::printf("heap growth from tick %" PRId64 " to %" PRId64 ": %" PRId64 " bytes (limit %" PRId64
                "); RSS %" PRId64 " -> %" PRId64 " KiB\n",
                samples[1].tick, samples.back().tick, growth, max_growth, samples[1].rss, samples.back().rss);
    if (growth > max_growth) {
      std::printf("FAIL heap grew by %" PRId64 " bytes after warm-up\n", growth);
      ++failures;
    }
  }
  if (outside != 0) {
    std::printf("FAIL %d bodies left the drum\n", outside);
    ++failures;
  }
  if (verify) {
    Replay replay;
    if (Status st = read_replay_file(out, &replay); !st.ok()) {
      std::printf("FAIL reading the replay back: %s\n", st.message.c_str());
      return 1;
    }
    const auto v0 = std::chrono::steady_clock::now();
    const VerifyReport report = verify_replay(replay);
    const double vs = std::chrono::duration<double>(std::chrono::steady_clock::now() - v0).count();
    std::printf("verify: %" PRIu64 " ticks re-simulated, %" PRIu64 " hashes checked, %s (%.1f s)\n", report.ticks_run,
                report.hashes_checked, verify_exit_code(report) == 0 ? "all matched" : "MISMATCH", vs);
    if (verify_exit_code(report) != 0) {
      std::printf("FAIL %s", format_verify_report(report).c_str());
      ++failures;
    }
  }
  (void)destroy_world(built.value.world);
  std::printf("%s\n", failures == 0 ? "soak: ok" : "soak: FAILED");
  return failures == 0 ? 0 : 1;
}
