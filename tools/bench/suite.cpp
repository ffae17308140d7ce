// suite.cpp — runs the benchmark suite and writes its table, CSV, JSON and
// SVG (see suite.h). Doubles here are timings and probes: display only.
#include "suite.h"

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <thread>

namespace tandem::bench {
namespace {

constexpr int32_t k_large_scene = 4000;

/// One scene × engine: the runs' times and the first run's probes.
struct Row {
  std::string scene, family;
  int32_t size = 0, bodies = 0;
  Engine engine;
  int32_t runs = 0, warmup = 0, steps = 0;
  std::vector<double> ms;
  double median = 0, min = 0, max = 0;
  Quality quality;
  ProfileSeries profile;  ///< Tandem: every timed step of every run
  std::string error;    ///< the engine refused the scene
  std::string skipped;  ///< not run, and why
  std::string note;     ///< e.g. fewer runs than asked, and why
  std::map<std::string, double> ratio;  ///< peer engine → this median / peer median
};

double nan() { return std::numeric_limits<double>::quiet_NaN(); }

double ke_change_percent(const Quality& q) {
  return q.ke_start > 0 ? 100.0 * (q.ke_end - q.ke_start) / q.ke_start : nan();
}

/// Pyramid verdicts: stands when no box ended more than 0.25 m sideways from
/// its start and none fell off the ground (the top box's sag is reported
/// beside it: soft contacts compress a tall stack without toppling it); at
/// rest when no body moves faster than 0.1 m/s.
bool pyramid_stands(const Row& r) { return r.quality.moved == 0 && r.quality.escaped == 0; }
bool at_rest(const Row& r) { return r.quality.max_speed < 0.1; }

std::string fmt(const char* f, double v) {
  if (std::isnan(v)) return "-";
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

std::string hex64(uint64_t v) {
  char buf[24];
  std::snprintf(buf, sizeof buf, "%016" PRIx64, v);
  return buf;
}

std::string read_first_line_with(const char* path, const char* key) {
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind(key, 0) == 0) {
      const size_t colon = line.find(':');
      if (colon != std::string::npos) {
        size_t start = colon + 1;
        while (start < line.size() && line[start] == ' ') ++start;
        return line.substr(start);
      }
    }
  }
  return "?";
}

struct Machine {
  std::string cpu, compiler, build, date, load_before, load_after;
  unsigned cores = 0;
};

std::string load_average() {
  std::ifstream in("/proc/loadavg");
  std::string a, b, c;
  if (!(in >> a >> b >> c)) return "?";
  return a + " " + b + " " + c;
}

Machine machine_now() {
  Machine m;
  m.cpu = read_first_line_with("/proc/cpuinfo", "model name");
  m.cores = std::thread::hardware_concurrency();
#if defined(__clang__)
  m.compiler = std::string("clang ") + __clang_version__;
#elif defined(__GNUC__)
  m.compiler = std::string("g++ ") + __VERSION__;
#else
  m.compiler = "?";
#endif
#ifdef NDEBUG
  m.build = "optimised (NDEBUG)";
#else
  m.build = "DEBUG (assertions on: timings not meaningful)";
#endif
  char buf[64];
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  std::strftime(buf, sizeof buf, "%Y-%m-%d %H:%M UTC", &tm);
  m.date = buf;
  return m;
}

double median_of(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  if (n == 0) return nan();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// --- output ------------------------------------------------------------------

std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (const char ch : s) {
    const auto u = static_cast<unsigned char>(ch);
    if (ch == '"' || ch == '\\') {
      out += '\\';
      out += ch;
    } else if (u < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", u);
      out += buf;
    } else {
      out += ch;
    }
  }
  return out + "\"";
}

std::string json_number(double v) {
  if (!std::isfinite(v)) return "null";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string out = "\"";
  for (const char ch : s) {
    if (ch == '"') out += '"';
    out += ch;
  }
  return out + "\"";
}

const std::vector<std::string>& peer_names(const std::vector<Row>& rows) {
  static std::vector<std::string> names;
  names.clear();
  for (const Row& r : rows) {
    if (r.engine.is_peer && std::find(names.begin(), names.end(), r.engine.engine) == names.end()) {
      names.push_back(r.engine.engine);
    }
  }
  return names;
}

std::string label(const Row& r) {
  return r.engine.is_peer ? r.engine.engine : r.engine.engine + "/" + r.engine.broad_phase;
}

void print_table(const std::vector<Row>& rows, const Machine& m, const BenchOptions& o) {
  const std::vector<std::string> peers = peer_names(rows);
  std::printf("\nTandem physics benchmark — %s, %u logical cores; %s; %s\n", m.cpu.c_str(), m.cores,
              m.compiler.c_str(), m.build.c_str());
  std::printf("%s; load average %s before, %s after. Median ms/step over the runs (min-max), %s;\n", m.date.c_str(),
              m.load_before.c_str(), m.load_after.c_str(),
              o.cpu_clock ? "process CPU time for 1-worker rows, wall clock for the others (--clock cpu)"
                          : "wall clock");
  std::printf("ratios are Tandem / peer (above 1: Tandem slower). Quality columns: first run.\n\n");
  std::printf("%-14s %-16s %5s %9s %-19s", "scene", "engine", "runs", "median", "min-max");
  for (const std::string& p : peers) std::printf(" %10s", ("/" + p).substr(0, 10).c_str());
  std::printf(" %9s %10s %9s %9s %8s %4s  %s\n", "KE chg %", "KE end J", "top y", "top sag", "max v", "esc", "notes");
  for (const Row& r : rows) {
    std::printf("%-14s %-16s", r.scene.c_str(), label(r).c_str());
    if (!r.skipped.empty() || !r.error.empty()) {
      std::printf(" %s\n", (r.skipped.empty() ? "error: " + r.error : "skipped: " + r.skipped).c_str());
      continue;
    }
    const std::string mm = fmt("%.3f", r.min) + "-" + fmt("%.3f", r.max);
    std::printf(" %5d %9.3f %-19s", r.runs, r.median, mm.c_str());
    for (const std::string& p : peers) {
      const auto it = r.ratio.find(p);
      std::printf(" %10s", it == r.ratio.end() ? "" : fmt("%.2fx", it->second).c_str());
    }
    const bool tracked = r.family == "pyramid";
    std::printf(" %9s %10s %9s %9s %8s %4d ", fmt("%+.3f", ke_change_percent(r.quality)).c_str(),
                fmt("%.4g", r.quality.ke_end).c_str(),
                tracked ? fmt("%.3f", r.quality.track_y_end).c_str() : "",
                tracked ? fmt("%.3f", r.quality.track_y_start - r.quality.track_y_end).c_str() : "",
                fmt("%.3f", r.quality.max_speed).c_str(), r.quality.escaped);
    std::string notes;
    if (tracked) {
      notes += std::string(pyramid_stands(r) ? "stands" : "FELL (" + std::to_string(r.quality.moved) + " moved)") +
               (at_rest(r) ? ", at rest; " : ", moving; ");
    }
    if (r.quality.has_fingerprint) notes += "state " + hex64(r.quality.fingerprint).substr(0, 8);
    if (!r.note.empty()) notes += "; " + r.note;
    std::printf(" %s\n", notes.c_str());
  }
  bool any_note = false;
  for (const Row& r : rows) {
    if (!r.engine.is_peer || r.engine.note.empty()) continue;
    bool seen = false;
    for (const Row& q : rows) {
      if (&q == &r) break;
      if (q.engine.engine == r.engine.engine) seen = true;
    }
    if (seen) continue;
    if (!any_note) std::printf("\n");
    any_note = true;
    std::printf("%s: %s\n", r.engine.engine.c_str(), r.engine.note.c_str());
  }
  std::fflush(stdout);
}

bool write_csv(const std::string& path, const std::vector<Row>& rows) {
  std::ofstream out(path);
  if (!out) return false;
  const std::vector<std::string> peers = peer_names(rows);
  out << "scene,family,size,bodies,engine,broad_phase,runs,warmup_steps,timed_steps,median_ms,min_ms,max_ms";
  for (const std::string& p : peers) out << ",ratio_to_" << p;
  out << ",ke_start,ke_end,ke_change_percent,top_y_start,top_y_end,top_sag,max_speed,escaped,moved_sideways,stands,at_rest,"
         "state_fingerprint,status,run_ms,note\n";
  for (const Row& r : rows) {
    out << csv_field(r.scene) << ',' << r.family << ',' << r.size << ',' << r.bodies << ',' << r.engine.engine << ','
        << r.engine.broad_phase << ',' << r.runs << ',' << r.warmup << ',' << r.steps << ',';
    const bool ok = r.skipped.empty() && r.error.empty();
    const auto num = [&](double v) { return ok ? fmt("%.6g", v) : std::string(); };
    out << num(r.median) << ',' << num(r.min) << ',' << num(r.max);
    for (const std::string& p : peers) {
      const auto it = r.ratio.find(p);
      out << ',' << (it == r.ratio.end() ? std::string() : fmt("%.4f", it->second));
    }
    const bool tracked = r.family == "pyramid";
    const Quality& q = r.quality;
    out << ',' << num(q.ke_start) << ',' << num(q.ke_end) << ',' << (ok ? fmt("%.4f", ke_change_percent(q)) : "")
        << ',' << (tracked ? num(q.track_y_start) : "") << ',' << (tracked ? num(q.track_y_end) : "") << ','
        << (tracked ? num(q.track_y_start - q.track_y_end) : "") << ',' << num(q.max_speed) << ','
        << (ok ? std::to_string(q.escaped) : "") << ',' << (ok ? std::to_string(q.moved) : "") << ','
        << (ok && tracked ? (pyramid_stands(r) ? "yes" : "no") : "")
        << ',' << (ok && tracked ? (at_rest(r) ? "yes" : "no") : "") << ','
        << (ok && q.has_fingerprint ? hex64(q.fingerprint) : "") << ','
        << csv_field(!r.skipped.empty() ? "skipped: " + r.skipped : !r.error.empty() ? "error: " + r.error : "ok")
        << ',';
    for (size_t i = 0; i < r.ms.size(); ++i) out << (i ? " " : "") << fmt("%.6g", r.ms[i]);
    out << ',' << csv_field(r.note.empty() ? r.engine.note : r.engine.note.empty() ? r.note : r.note + "; " + r.engine.note)
        << '\n';
  }
  return static_cast<bool>(out);
}

bool write_json(const std::string& path, const std::vector<Row>& rows, const Machine& m, const BenchOptions& o,
                const std::vector<std::string>& warnings) {
  std::ofstream out(path);
  if (!out) return false;
  out << "{\n  \"machine\": {\"cpu\": " << json_string(m.cpu) << ", \"logical_cores\": " << m.cores
      << ", \"compiler\": " << json_string(m.compiler) << ", \"build\": " << json_string(m.build)
      << ", \"date\": " << json_string(m.date) << ", \"load_average_before\": " << json_string(m.load_before)
      << ", \"load_average_after\": " << json_string(m.load_after) << "},\n";
  out << "  \"options\": {\"runs\": " << o.runs << ", \"runs_large\": " << (o.runs_large ? o.runs_large : o.runs)
      << ", \"steps\": " << o.steps << ", \"warmup\": " << o.warmup << ", \"workers\": " << o.workers << ", \"clock\": " << json_string(o.cpu_clock ? "cpu" : "wall") << ", \"naive_max\": " << o.naive_max << ", \"max_run_seconds\": " << o.max_run_seconds
      << ", \"time_step\": \"1/60 s\"},\n";
  out << "  \"warnings\": [";
  for (size_t i = 0; i < warnings.size(); ++i) out << (i ? ", " : "") << json_string(warnings[i]);
  out << "],\n";
  out << "  \"ratio_meaning\": \"Tandem median / peer median; above 1 means Tandem is slower\",\n";
  out << "  \"results\": [";
  for (size_t i = 0; i < rows.size(); ++i) {
    const Row& r = rows[i];
    const Quality& q = r.quality;
    out << (i ? ",\n" : "\n") << "    {\"scene\": " << json_string(r.scene) << ", \"family\": " << json_string(r.family)
        << ", \"size\": " << r.size << ", \"bodies\": " << r.bodies << ", \"engine\": " << json_string(r.engine.engine)
        << ", \"broad_phase\": " << json_string(r.engine.broad_phase) << ", \"workers\": " << r.engine.workers
        << ", \"clock\": " << json_string(o.cpu_clock && r.engine.workers <= 1 ? "cpu" : "wall");
    if (!r.engine.note.empty()) out << ", \"note\": " << json_string(r.engine.note);
    if (!r.skipped.empty()) {
      out << ", \"skipped\": " << json_string(r.skipped) << "}";
      continue;
    }
    if (!r.error.empty()) {
      out << ", \"error\": " << json_string(r.error) << "}";
      continue;
    }
    out << ", \"runs\": " << r.runs << ", \"warmup_steps\": " << r.warmup << ", \"timed_steps\": " << r.steps
        << ", \"median_ms\": " << json_number(r.median) << ", \"min_ms\": " << json_number(r.min)
        << ", \"max_ms\": " << json_number(r.max) << ", \"run_ms\": [";
    for (size_t k = 0; k < r.ms.size(); ++k) out << (k ? ", " : "") << json_number(r.ms[k]);
    out << "], \"ratio_to\": {";
    bool first = true;
    for (const auto& [peer, ratio] : r.ratio) {
      out << (first ? "" : ", ") << json_string(peer) << ": " << json_number(ratio);
      first = false;
    }
    out << "}, \"ke_start\": " << json_number(q.ke_start) << ", \"ke_end\": " << json_number(q.ke_end)
        << ", \"ke_change_percent\": " << json_number(ke_change_percent(q))
        << ", \"max_speed\": " << json_number(q.max_speed) << ", \"escaped\": " << q.escaped
        << ", \"moved_sideways\": " << q.moved;
    if (r.family == "pyramid") {
      out << ", \"top_y_start\": " << json_number(q.track_y_start) << ", \"top_y_end\": " << json_number(q.track_y_end)
          << ", \"stands\": " << (pyramid_stands(r) ? "true" : "false")
          << ", \"at_rest\": " << (at_rest(r) ? "true" : "false");
    }
    if (q.has_fingerprint) out << ", \"state_fingerprint\": " << json_string(hex64(q.fingerprint));
    if (!r.profile.empty()) out << ", \"profile\": " << profile_json(r.profile.stats());
    if (!r.note.empty()) out << ", \"run_note\": " << json_string(r.note);
    out << "}";
  }
  out << "\n  ]\n}\n";
  return static_cast<bool>(out);
}

/// Step time of circles-N against N, log-log, one line per Tandem broad
/// phase and per peer, with min–max bars.
bool write_svg(const std::string& path, const std::vector<Row>& rows, const Machine& m) {
  std::ofstream out(path);
  if (!out) return false;
  std::vector<std::string> series;
  double x_lo = 1e300, x_hi = 0, y_lo = 1e300, y_hi = 0;
  for (const Row& r : rows) {
    if (r.family != "circles" || !r.skipped.empty() || !r.error.empty() || !(r.median > 0)) continue;
    if (std::find(series.begin(), series.end(), label(r)) == series.end()) series.push_back(label(r));
    x_lo = std::min(x_lo, double(r.size));
    x_hi = std::max(x_hi, double(r.size));
    y_lo = std::min(y_lo, r.min);
    y_hi = std::max(y_hi, r.max);
  }
  constexpr double W = 760, H = 500, left = 70, right = 200, top = 50, bottom = 60;
  out << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << W << "\" height=\"" << H << "\" viewBox=\"0 0 " << W
      << ' ' << H << "\" font-family=\"sans-serif\" font-size=\"12\">\n";
  out << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  out << "<text x=\"" << left << "\" y=\"22\" font-size=\"15\">circles-N: step time against N (median, min-max bars)</text>\n";
  out << "<text x=\"" << left << "\" y=\"40\" font-size=\"10\" fill=\"#555\">" << m.cpu << ", " << m.cores
      << " cores, " << m.date << "</text>\n";
  if (series.empty()) {
    out << "<text x=\"" << left << "\" y=\"" << H / 2 << "\">no circles-N results</text>\n</svg>\n";
    return static_cast<bool>(out);
  }
  // Whole decades around the data on y; powers of two around it on x.
  const double ly0 = std::floor(std::log10(y_lo)), ly1 = std::max(ly0 + 1, std::ceil(std::log10(y_hi)));
  const double lx0 = std::log2(x_lo) - 0.25, lx1 = std::log2(x_hi) + 0.25;
  const double pw = W - left - right, ph = H - top - bottom;
  const auto px = [&](double x) { return left + (std::log2(x) - lx0) / (lx1 - lx0) * pw; };
  const auto py = [&](double y) { return top + ph - (std::log10(y) - ly0) / (ly1 - ly0) * ph; };
  out << "<rect x=\"" << left << "\" y=\"" << top << "\" width=\"" << pw << "\" height=\"" << ph
      << "\" fill=\"none\" stroke=\"#333\"/>\n";
  for (double d = ly0; d <= ly1 + 1e-9; d += 1) {
    for (int k = 1; k < 10; ++k) {
      const double v = std::pow(10.0, d) * k;
      if (d == ly1 && k > 1) break;
      const double y = py(v);
      out << "<line x1=\"" << left << "\" x2=\"" << left + pw << "\" y1=\"" << y << "\" y2=\"" << y
          << "\" stroke=\"" << (k == 1 ? "#bbb" : "#eee") << "\"/>\n";
      if (k == 1) {
        out << "<text x=\"" << left - 6 << "\" y=\"" << y + 4 << "\" text-anchor=\"end\">" << fmt("%g", v)
            << "</text>\n";
      }
    }
  }
  // x ticks and grid lines at the scene sizes (N = 1000, 2000, ...).
  std::vector<int32_t> sizes;
  for (const Row& r : rows) {
    if (r.family == "circles" && std::find(sizes.begin(), sizes.end(), r.size) == sizes.end()) sizes.push_back(r.size);
  }
  for (const int32_t n : sizes) {
    const double x = px(n);
    out << "<line x1=\"" << x << "\" x2=\"" << x << "\" y1=\"" << top << "\" y2=\"" << top + ph
        << "\" stroke=\"#ddd\"/>\n";
    const std::string text = n >= 1000 && n % 1000 == 0 ? std::to_string(n / 1000) + "k" : std::to_string(n);
    out << "<text x=\"" << x << "\" y=\"" << top + ph + 18 << "\" text-anchor=\"middle\">" << text << "</text>\n";
  }
  out << "<text x=\"" << left + pw / 2 << "\" y=\"" << H - 12 << "\" text-anchor=\"middle\">N (circles)</text>\n";
  out << "<text transform=\"translate(18," << top + ph / 2 << ") rotate(-90)\" text-anchor=\"middle\">ms per step</text>\n";
  const char* colours[] = {"#1f77b4", "#2ca02c", "#9467bd", "#17becf", "#d62728", "#ff7f0e", "#8c564b", "#e377c2"};
  for (size_t s = 0; s < series.size(); ++s) {
    const char* colour = colours[s % 8];
    std::vector<const Row*> pts;
    for (const Row& r : rows) {
      if (r.family == "circles" && label(r) == series[s] && r.skipped.empty() && r.error.empty() && r.median > 0) {
        pts.push_back(&r);
      }
    }
    std::sort(pts.begin(), pts.end(), [](const Row* a, const Row* b) { return a->size < b->size; });
    const bool peer = pts.front()->engine.is_peer;
    out << "<polyline fill=\"none\" stroke=\"" << colour << "\" stroke-width=\"2\""
        << (peer ? " stroke-dasharray=\"6,4\"" : "") << " points=\"";
    for (const Row* r : pts) out << px(r->size) << ',' << py(r->median) << ' ';
    out << "\"/>\n";
    for (const Row* r : pts) {
      out << "<line x1=\"" << px(r->size) << "\" x2=\"" << px(r->size) << "\" y1=\"" << py(r->min) << "\" y2=\""
          << py(r->max) << "\" stroke=\"" << colour << "\"/>\n";
      out << "<circle cx=\"" << px(r->size) << "\" cy=\"" << py(r->median) << "\" r=\"3\" fill=\"" << colour
          << "\"/>\n";
    }
    const double ly = top + 10 + 20 * static_cast<double>(s);
    out << "<line x1=\"" << left + pw + 15 << "\" x2=\"" << left + pw + 45 << "\" y1=\"" << ly << "\" y2=\"" << ly
        << "\" stroke=\"" << colour << "\" stroke-width=\"2\"" << (peer ? " stroke-dasharray=\"6,4\"" : "") << "/>\n";
    out << "<text x=\"" << left + pw + 50 << "\" y=\"" << ly + 4 << "\">" << series[s] << "</text>\n";
  }
  out << "</svg>\n";
  return static_cast<bool>(out);
}

/// Tandem's per-stage profile, one Markdown row per Tandem row: the median
/// ms/step of each stage over every timed step of every run.
void print_profile_markdown(const std::vector<Row>& rows) {
  bool header = false;
  for (const Row& r : rows) {
    if (r.profile.empty()) continue;
    const std::vector<StageStat> stats = r.profile.stats();
    if (!header) {
      std::printf("\nPer-stage profile (world_profile()): median ms per step over every timed step of every run\n\n");
      std::printf("| scene | engine |");
      for (const StageStat& s : stats) std::printf(" %s |", s.name);
      std::printf("\n|---|---|");
      for (size_t i = 0; i < stats.size(); ++i) std::printf("--:|");
      std::printf("\n");
      header = true;
    }
    std::printf("| %s | %s |", r.scene.c_str(), label(r).c_str());
    for (const StageStat& s : stats) std::printf(" %.3f |", s.median_ms);
    std::printf("\n");
  }
  std::fflush(stdout);
}

}  // namespace

int run_bench_suite(const BenchOptions& o) {
  if (o.runs < 1) {
    std::fprintf(stderr, "bench: --runs must be at least 1\n");
    return 2;
  }
  // Scenes first, so a typo fails before any time is spent.
  std::vector<SceneSpec> scenes;
  const std::vector<std::string> default_names =
      o.rays > 0 ? std::vector<std::string>{"rain-4000"} : default_scene_names();
  for (const std::string& name : o.scenes.empty() ? default_names : o.scenes) {
    SceneSpec s;
    std::string error;
    if (!make_scene(name, &s, &error)) {
      std::fprintf(stderr, "bench: %s\n", error.c_str());
      return 2;
    }
    scenes.push_back(std::move(s));
  }
  std::vector<Engine> engines;
  std::vector<std::string> bps = o.broad_phases;
  if (bps.empty() || std::find(bps.begin(), bps.end(), "all") != bps.end()) bps = tandem_broad_phase_names();
  for (const std::string& bp : bps) {
    Engine e;
    if (!tandem_engine(bp, o.workers, &e)) {
      std::fprintf(stderr, "bench: unknown broad phase '%s' (naive, sap, grid, tree, all)\n", bp.c_str());
      return 2;
    }
    if (bp == "naive") e.max_bodies = o.naive_max;
    engines.push_back(std::move(e));
  }
  if (o.peers) {
    std::vector<Engine> peers = peer_engines();
    if (peers.empty()) std::fprintf(stderr, "bench: no peers: %s\n", peers_unavailable_reason());
    for (Engine& e : peers) engines.push_back(std::move(e));
  }
  if (!o.engines.empty()) {
    for (const std::string& name : o.engines) {
      const bool known = std::any_of(engines.begin(), engines.end(), [&](const Engine& e) {
        return (e.is_peer ? e.engine : e.engine + "/" + e.broad_phase) == name;
      });
      if (!known) {
        std::fprintf(stderr, "bench: --engines: '%s' is not among the engines selected (Tandem broad phases%s)\n",
                     name.c_str(), o.peers ? " and the linked peers" : "; peers need --peers");
        return 2;
      }
    }
    std::vector<Engine> kept;
    for (Engine& e : engines) {
      const std::string name = e.is_peer ? e.engine : e.engine + "/" + e.broad_phase;
      if (std::find(o.engines.begin(), o.engines.end(), name) != o.engines.end()) kept.push_back(std::move(e));
    }
    engines = std::move(kept);
  }
  Machine machine = machine_now();
  machine.load_before = load_average();
#ifndef NDEBUG
  std::fprintf(stderr, "bench: WARNING: this is not an optimised build; timings are not meaningful\n");
#endif
  if (o.rays > 0) {
    return run_ray_bench(o, scenes, engines,
                         machine.cpu + ", " + std::to_string(machine.cores) + " logical cores; " + machine.compiler +
                             "; " + machine.build + "; " + machine.date + "; load average " + machine.load_before);
  }

  std::vector<Row> rows;
  std::vector<std::string> warnings;
  std::map<std::string, int32_t> too_slow;  // engine/family → the size whose run exceeded --max-run-seconds
  for (const SceneSpec& scene : scenes) {
    const size_t first_row = rows.size();
    const int32_t runs = scene.dynamic_count > k_large_scene && o.runs_large > 0 ? o.runs_large : o.runs;
    const int32_t warmup = o.warmup >= 0 ? o.warmup : scene.warmup_steps;
    const int32_t steps = o.steps > 0 ? o.steps : scene.timed_steps;
    for (const Engine& engine : engines) {
      const std::string guard_key = engine.engine + "/" + engine.broad_phase + "/" + scene.family;
      Row row;
      row.scene = scene.name;
      row.family = scene.family;
      row.size = scene.size;
      row.bodies = scene.dynamic_count;
      row.engine = engine;
      row.warmup = warmup;
      row.steps = steps;
      if (engine.max_bodies > 0 && scene.dynamic_count > engine.max_bodies) {
        row.skipped = "O(n^2) above " + std::to_string(engine.max_bodies) + " bodies (--naive-max)";
        rows.push_back(std::move(row));
        continue;
      }
      const auto slow = too_slow.find(guard_key);
      if (slow != too_slow.end() && scene.size > slow->second) {
        row.skipped = "a run at " + scene.family + "-" + std::to_string(slow->second) + " took over " +
                      std::to_string(o.max_run_seconds) + " s (--max-run-seconds)";
        rows.push_back(std::move(row));
        continue;
      }
      for (int32_t run = 0; run < runs; ++run) {
        RunResult r = engine.run(scene, warmup, steps);
        if (!r.error.empty()) {
          row.error = r.error;
          break;
        }
        if (run == 0) row.quality = r.quality;
        row.profile.append(r.profile);
        const bool cpu = o.cpu_clock && engine.workers <= 1;  // CPU time sums threads: wall for the others
        const double ms = cpu ? r.cpu_ms_per_step : r.ms_per_step;
        row.ms.push_back(ms);
        if (!o.quiet) {
          std::fprintf(stderr, "  %-14s %-18s run %d/%d: %.3f ms/step (%s; wall %.3f, CPU %.3f)\n", scene.name.c_str(),
                       label(row).c_str(), run + 1, runs, ms, cpu ? "CPU" : "wall", r.ms_per_step, r.cpu_ms_per_step);
        }
        if (o.max_run_seconds > 0 && r.ms_per_step * steps > 1000.0 * o.max_run_seconds) {
          // Too slow to repeat: keep this run, skip the rest and the larger scenes of this family.
          too_slow[guard_key] = scene.size;
          if (run + 1 < runs) row.note = "1 run only: it took over " + std::to_string(o.max_run_seconds) + " s";
          break;
        }
      }
      if (!o.quiet && !row.error.empty()) {
        std::fprintf(stderr, "  %-14s %-18s error: %s\n", scene.name.c_str(), label(row).c_str(), row.error.c_str());
      }
      row.runs = static_cast<int32_t>(row.ms.size());
      if (!row.ms.empty()) {
        row.median = median_of(row.ms);
        row.min = *std::min_element(row.ms.begin(), row.ms.end());
        row.max = *std::max_element(row.ms.begin(), row.ms.end());
      }
      rows.push_back(std::move(row));
    }
    // Ratios of each Tandem row to each peer of this scene; fingerprints agree?
    const auto ok = [](const Row& r) { return r.skipped.empty() && r.error.empty() && r.median > 0; };
    std::string fingerprint_owner;
    uint64_t fingerprint = 0;
    for (size_t i = first_row; i < rows.size(); ++i) {
      Row& r = rows[i];
      if (r.engine.is_peer || !ok(r)) continue;
      for (size_t k = first_row; k < rows.size(); ++k) {
        if (rows[k].engine.is_peer && ok(rows[k])) r.ratio[rows[k].engine.engine] = r.median / rows[k].median;
      }
      if (!r.quality.has_fingerprint) continue;
      if (fingerprint_owner.empty()) {
        fingerprint_owner = label(r);
        fingerprint = r.quality.fingerprint;
      } else if (r.quality.fingerprint != fingerprint) {
        warnings.push_back(scene.name + ": " + label(r) + " ends in a different state than " + fingerprint_owner +
                           " (every broad phase must give the same pairs, so the same state)");
        std::fprintf(stderr, "bench: WARNING: %s\n", warnings.back().c_str());
      }
    }
  }
  machine.load_after = load_average();
  print_table(rows, machine, o);
  if (o.profile) print_profile_markdown(rows);
  for (const std::string& w : warnings) std::printf("WARNING: %s\n", w.c_str());
  int status = warnings.empty() ? 0 : 1;
  if (!o.csv.empty() && !write_csv(o.csv, rows)) {
    std::fprintf(stderr, "bench: cannot write CSV file '%s'\n", o.csv.c_str());
    status = 2;
  }
  if (!o.json.empty() && !write_json(o.json, rows, machine, o, warnings)) {
    std::fprintf(stderr, "bench: cannot write JSON file '%s'\n", o.json.c_str());
    status = 2;
  }
  if (!o.svg.empty() && !write_svg(o.svg, rows, machine)) {
    std::fprintf(stderr, "bench: cannot write SVG file '%s'\n", o.svg.c_str());
    status = 2;
  }
  return status;
}

}  // namespace tandem::bench
