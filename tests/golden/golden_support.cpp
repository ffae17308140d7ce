// golden_support.cpp — the golden-chain runner, the per-tick hash and the
// golden file reader/writer (see golden_support.h for the design).
#include "golden_support.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>

#define XXH_INLINE_ALL
#include <xxhash.h>

#include "replay/rollback.h"
#include "replay/state.h"

namespace tandem::golden {

#ifndef TANDEM_GOLDEN_SOURCE_DIR
#define TANDEM_GOLDEN_SOURCE_DIR "tests/golden"
#endif

const std::string k_hash_source = "world_state_hash, state format " + std::to_string(k_state_format_version) +
                                  "; chain XXH3-64 of the little-endian tick hashes";

void SceneContext::check(const Status& s, const char* what) {
  if (!s.ok() && error.empty()) error = std::string(what) + ": " + s.message;
}

namespace {

/// The byte of a state image that holds WorldDef::broad_phase, found by
/// encoding two empty worlds that differ only in it (so nothing here depends
/// on the field order of physics/state_fields.h); npos when they differ elsewhere too.
size_t broad_phase_byte() {
  static const size_t offset = [] {
    std::vector<uint8_t> images[2];
    for (int i = 0; i < 2; ++i) {
      WorldDef def = default_world_def();
      def.broad_phase = i == 0 ? BroadPhaseKind::naive : BroadPhaseKind::tree;
      const Result<WorldId> w = create_world(def);
      if (!w.ok()) return std::string::npos;
      (void)encode_world_state(w.value, &images[i]);
      (void)destroy_world(w.value);
    }
    if (images[0].size() != images[1].size()) return std::string::npos;
    size_t found = std::string::npos;
    for (size_t i = 0; i < images[0].size(); ++i) {
      if (images[0][i] == images[1][i]) continue;
      if (found != std::string::npos) return std::string::npos;
      found = i;
    }
    return found;
  }();
  return offset;
}

/// world_state_hash, or — for a world whose broad phase is not the naive
/// one — the same hash of its state image with the broad-phase byte set to
/// naive's (every kind must give the same state otherwise).
uint64_t tick_hash(WorldId w, std::vector<uint8_t>& scratch) {
  if (world_broad_phase(w) == BroadPhaseKind::naive) return world_state_hash(w);
  scratch.clear();
  (void)encode_world_state(w, &scratch);
  const size_t at = broad_phase_byte();
  if (at >= scratch.size()) return 0;
  scratch[at] = static_cast<uint8_t>(BroadPhaseKind::naive);
  return XXH3_64bits(scratch.data(), scratch.size());
}

/// The chain: XXH3-64 (seed 0) of the per-tick hashes as 8 little-endian
/// bytes each, in tick order.
uint64_t chain_hash(const std::vector<uint64_t>& ticks) {
  std::vector<uint8_t> bytes;
  bytes.reserve(ticks.size() * 8);
  for (const uint64_t h : ticks) {
    for (int i = 0; i < 8; ++i) bytes.push_back(static_cast<uint8_t>(h >> (8 * i)));
  }
  return XXH3_64bits(bytes.data(), bytes.size());
}

/// Points every handle the context keeps at world w (after a restore into a
/// new world: same indices and generations, new world handle).
void rebind(SceneContext& ctx, WorldId w) {
  ctx.world = w;
  for (BodyId& b : ctx.bodies) b.world = w;
  for (ShapeId& s : ctx.shapes) s.world = w;
  for (JointId& j : ctx.joints) j.world = w;
}

std::string hex(uint64_t v) {
  char buf[24];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
  return buf;
}

bool parse_hex(const std::string& text, uint64_t* out) {
  if (text.empty() || text.size() > 16) return false;
  uint64_t v = 0;
  for (const char ch : text) {
    uint64_t d = 0;
    if (ch >= '0' && ch <= '9') d = static_cast<uint64_t>(ch - '0');
    else if (ch >= 'a' && ch <= 'f') d = static_cast<uint64_t>(ch - 'a' + 10);
    else return false;
    v = (v << 4) | d;
  }
  *out = v;
  return true;
}

std::string golden_path(const std::string& scene) { return golden_dir() + "/" + scene + ".txt"; }

}  // namespace

Chain run_chain(const Scene& scene, const ChainOptions& options) {
  Chain out;
  out.hash_source = k_hash_source;
  WorldDef def = default_world_def();
  def.broad_phase = options.cycle_broad_phase ? BroadPhaseKind::naive : options.broad_phase;
  def.worker_count = options.worker_count;
  def.enqueue_task = options.enqueue_task;
  def.finish_task = options.finish_task;
  def.user_task_context = options.user_task_context;
  const Result<WorldId> w = create_world(def);
  if (!w.ok()) {
    out.error = std::string(scene.name) + ": create_world: " + w.status.message;
    return out;
  }
  SceneContext ctx;
  ctx.world = w.value;
  scene.build(ctx);
  const Q32 dt = Q32::from_ratio(1, 60);
  std::vector<uint64_t> hashes;
  std::vector<uint8_t> scratch;
  hashes.reserve(static_cast<size_t>(options.ticks));

  // Snapshot/restore round trips: distinct seeded ticks, each followed by a
  // detour of 1..40 ticks that is then rolled back.
  std::mt19937_64 rng(options.restore_seed);
  std::vector<int32_t> restore_at;
  for (int32_t i = 0; i < options.restore_count && options.ticks > 1; ++i) {
    restore_at.push_back(1 + static_cast<int32_t>(rng() % static_cast<uint64_t>(options.ticks - 1)));
  }
  std::sort(restore_at.begin(), restore_at.end());
  restore_at.erase(std::unique(restore_at.begin(), restore_at.end()), restore_at.end());
  size_t next_restore = 0;

  auto step = [&](int32_t tick) -> std::string {
    if (options.cycle_broad_phase && tick % 300 == 1) {
      const auto kind = static_cast<BroadPhaseKind>((tick / 300) % 4);
      const Status s = world_set_broad_phase(ctx.world, kind);
      if (!s.ok()) return "world_set_broad_phase: " + s.message;
    }
    if (scene.script != nullptr) scene.script(ctx, tick);
    if (!ctx.error.empty()) return ctx.error;
    const StepResult r = world_step(ctx.world, dt);
    if (!r.ok()) return "world_step: " + r.status.message;
    if ((r.flags & k_step_flag_task_failure) != 0) return r.task_status.message;
    return "";
  };

  for (int32_t tick = 1; tick <= options.ticks && ctx.error.empty(); ++tick) {
    const std::string err = step(tick);
    if (!err.empty()) {
      out.error = std::string(scene.name) + ": tick " + std::to_string(tick) + ": " + err;
      break;
    }
    if (options.observe) options.observe(ctx, tick);
    const uint64_t h = tick_hash(ctx.world, scratch);
    hashes.push_back(h);
    out.ticks = tick;
    if (tick % k_record_interval == 0) out.records.push_back({tick, h});

    if (next_restore < restore_at.size() && restore_at[next_restore] == tick) {
      ++next_restore;
      const std::string where = std::string(scene.name) + ": restore at tick " + std::to_string(tick) + ": ";
      std::vector<uint8_t> image;
      RollbackBuffer compact;
      const Status saved =
          options.compact ? rollback_save(ctx.world, &compact) : encode_world_state(ctx.world, &image);
      if (!saved.ok()) {
        out.error = where + "encode_world_state: " + saved.message;
        break;
      }
      const SceneContext kept = ctx;
      const int32_t detour = 1 + static_cast<int32_t>(rng() % 40);
      for (int32_t t = tick + 1; t <= tick + detour && t <= options.ticks; ++t) {
        const std::string derr = step(t);
        if (!derr.empty()) {
          out.error = where + "detour tick " + std::to_string(t) + ": " + derr;
          break;
        }
      }
      if (!out.error.empty()) break;
      const WorldId old_world = ctx.world;
      ctx = kept;
      if (options.compact) {  // the same world, or every other time a new one
        WorldId target = old_world;
        if (out.restores % 2 == 1) {
          const Result<WorldId> nw = create_world(default_world_def());
          if (!nw.ok()) {
            out.error = where + "create_world: " + nw.status.message;
            break;
          }
          target = nw.value;
        }
        const Status r = rollback_restore(target, compact);
        if (!r.ok()) {
          out.error = where + "rollback_restore: " + r.message;
          break;
        }
        if (target != old_world) {
          (void)destroy_world(old_world);
          rebind(ctx, target);
        }
        RollbackBuffer again;
        (void)rollback_save(ctx.world, &again);
        if (again.image != compact.image) {
          out.error = where + "a save of the restored world differs from the restored image";
          break;
        }
        ++out.restores;
        continue;
      }
      if (out.restores % 2 == 0) {  // back into the same world
        const Status r = world_restore(old_world, image.data(), image.size());
        if (!r.ok()) {
          out.error = where + "world_restore: " + r.message;
          break;
        }
      } else {  // into a new world; the old one goes
        const Result<WorldId> nw = create_world_from_snapshot(image.data(), image.size());
        if (!nw.ok()) {
          out.error = where + "create_world_from_snapshot: " + nw.status.message;
          break;
        }
        (void)destroy_world(old_world);
        rebind(ctx, nw.value);
      }
      ++out.restores;
      const uint64_t again = tick_hash(ctx.world, scratch);
      if (again != h) {
        out.error = where + "the restored world's hash " + hex(again) + " differs from the saved one " + hex(h);
        break;
      }
    }
  }
  if (out.error.empty() && !ctx.error.empty()) out.error = std::string(scene.name) + ": build: " + ctx.error;
  out.chain = chain_hash(hashes);
  (void)destroy_world(ctx.world);
  return out;
}

std::string golden_dir() {
  const char* env = std::getenv("TANDEM_GOLDEN_DIR");
  if (env != nullptr && env[0] != '\0') return env;
  return TANDEM_GOLDEN_SOURCE_DIR;
}

int32_t tick_cap() {
  const char* env = std::getenv("TANDEM_GOLDEN_TICKS");
  if (env == nullptr || env[0] == '\0') return k_scene_ticks;
  const long v = std::strtol(env, nullptr, 10);
  if (v <= 0 || v > k_scene_ticks) return k_scene_ticks;
  return static_cast<int32_t>(v);
}

bool regenerate_mode() {
  const char* env = std::getenv("TANDEM_GOLDEN_REGENERATE");
  return env != nullptr && env[0] != '\0' && std::strcmp(env, "0") != 0;
}

Chain read_golden(const std::string& scene) {
  Chain g;
  const std::string path = golden_path(scene);
  std::ifstream in(path);
  if (!in) {
    g.error = path + ": cannot open (regenerate with TANDEM_GOLDEN_REGENERATE=1, see docs/determinism.md)";
    return g;
  }
  std::string line;
  int line_no = 0;
  bool have_chain = false, have_scene = false;
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#') continue;
    const std::string where = path + ":" + std::to_string(line_no) + ": ";
    std::istringstream fields(line);
    std::string key;
    fields >> key;
    if (key == "scene") {
      std::string name;
      fields >> name;
      if (name != scene) {
        g.error = where + "scene '" + name + "', expected '" + scene + "'";
        return g;
      }
      have_scene = true;
    } else if (key == "hash") {
      std::string rest;
      std::getline(fields, rest);
      const size_t first = rest.find_first_not_of(' ');
      g.hash_source = first == std::string::npos ? "" : rest.substr(first);
    } else if (key == "ticks") {
      long t = 0;
      fields >> t;
      if (!fields || t <= 0 || t > 100000000) {
        g.error = where + "bad tick count";
        return g;
      }
      g.ticks = static_cast<int32_t>(t);
    } else if (key == "tick") {
      long t = 0;
      std::string h;
      fields >> t >> h;
      TickHash rec;
      rec.tick = static_cast<int32_t>(t);
      if (!fields || t <= 0 || t > g.ticks || !parse_hex(h, &rec.hash) ||
          (!g.records.empty() && rec.tick <= g.records.back().tick)) {
        g.error = where + "bad record (expected 'tick <t> <16 hex digits>', ascending, t <= ticks)";
        return g;
      }
      g.records.push_back(rec);
    } else if (key == "chain") {
      std::string h;
      fields >> h;
      if (!parse_hex(h, &g.chain)) {
        g.error = where + "bad chain hash";
        return g;
      }
      have_chain = true;
    } else {
      g.error = where + "unknown record '" + key + "'";
      return g;
    }
  }
  if (!have_scene || !have_chain || g.ticks == 0) {
    g.error = path + ": incomplete (needs scene, ticks, chain records)";
  }
  return g;
}

std::string write_golden(const std::string& scene, const Scene& info, const Chain& chain) {
  const std::string path = golden_path(scene);
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) return path + ": cannot write";
  out << "# Golden hash chain of scene '" << scene << "' (tests/golden/golden_scenes.cpp): " << info.covers << "\n"
      << "# Written by tandem_tests_golden with TANDEM_GOLDEN_REGENERATE=1 (docs/determinism.md); do not edit.\n"
      << "scene " << scene << "\n"
      << "hash " << chain.hash_source << "\n"
      << "ticks " << chain.ticks << "\n";
  for (const TickHash& r : chain.records) out << "tick " << r.tick << " " << hex(r.hash) << "\n";
  out << "chain " << hex(chain.chain) << "\n";
  out.flush();
  if (!out) return path + ": write failed";
  return "";
}

std::string compare(const Chain& golden, const Chain& run) {
  if (golden.hash_source != run.hash_source) {
    return "golden file hash recipe '" + golden.hash_source + "' differs from this build's '" + run.hash_source +
           "': regenerate the golden files (docs/determinism.md)";
  }
  for (const TickHash& g : golden.records) {
    if (g.tick > run.ticks) break;
    const TickHash* r = nullptr;
    for (const TickHash& x : run.records) {
      if (x.tick == g.tick) r = &x;
    }
    if (r == nullptr) return "tick " + std::to_string(g.tick) + " missing from the run";
    if (r->hash != g.hash) {
      return "first differing recorded tick " + std::to_string(g.tick) + ": expected " + hex(g.hash) + ", got " +
             hex(r->hash) + " (chain expected " + hex(golden.chain) + ", got " + hex(run.chain) + ")";
    }
  }
  if (run.ticks == golden.ticks && run.chain != golden.chain) {
    return "every recorded tick matches but the chain differs (an unrecorded tick after the last recorded one "
           "differs): expected " + hex(golden.chain) + ", got " + hex(run.chain);
  }
  if (run.ticks > golden.ticks) {
    return "the run has " + std::to_string(run.ticks) + " ticks, the golden file " + std::to_string(golden.ticks);
  }
  return "";
}

}  // namespace tandem::golden
