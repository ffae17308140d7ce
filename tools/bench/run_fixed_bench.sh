#!/usr/bin/env bash
# run_fixed_bench.sh — build and run the fixed-point benchmark and accuracy
# program, print Markdown tables and write them to <build>/fixed_bench.md.
#
# Usage: tools/bench/run_fixed_bench.sh [--quick] [--samples N] [--build-dir DIR] [-- CMAKE_ARGS...]
#   --quick        1 repetition, short runs, 1M accuracy inputs (smoke test only)
#   --samples N    accuracy inputs per row (default 10000000)
#   --build-dir    default build/bench (relative to the repository root)
#   CMAKE_ARGS     passed to the configure step, e.g. -DCMAKE_CXX_COMPILER=clang++
# Environment: CMAKE_GENERATOR is honoured (default: Ninja when available).
#
# Speed: median of 5 repetitions (--benchmark_repetitions=5
# --benchmark_report_aggregates_only=true). The machine, compiler, date and
# load average are recorded with the tables: on a shared machine, compare
# runs only when the load was low. Needs cmake, a C++20 compiler, Google
# Benchmark, libfixmath and python3 (to read the benchmark's JSON).
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
build="build/bench"
samples=10000000
repetitions=5
min_time=""
cmake_args=()
while [[ $# -gt 0 ]]; do
  case "$1" in
    --quick) repetitions=1; min_time="0.05"; samples=1000000; shift ;;
    --samples) samples="$2"; shift 2 ;;
    --build-dir) build="$2"; shift 2 ;;
    --) shift; cmake_args=("$@"); break ;;
    -h|--help) sed -n '2,16p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "run_fixed_bench.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
[[ "$build" = /* ]] || build="$root/$build"
command -v python3 >/dev/null || { echo "run_fixed_bench.sh: python3 is needed to read the benchmark JSON" >&2; exit 1; }

generator=()
if [[ -z "${CMAKE_GENERATOR:-}" ]] && command -v ninja >/dev/null; then generator=(-G Ninja); fi
if [[ ! -f "$build/CMakeCache.txt" ]]; then
  cmake -S "$root" -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release -DTANDEM_BUILD_BENCH=ON \
    -DTANDEM_BUILD_TESTS=OFF -DTANDEM_BUILD_TOOLS=OFF "${cmake_args[@]}"
else
  cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DTANDEM_BUILD_BENCH=ON "${cmake_args[@]}"
fi
cmake --build "$build" --target tandem_bench_fixed tandem_fixed_accuracy -j"$(nproc 2>/dev/null || echo 2)"

bench_bin="$build/tools/bench/tandem_bench_fixed"
accuracy_bin="$build/tools/bench/tandem_fixed_accuracy"
json="$build/fixed_bench.json"
md="$build/fixed_bench.md"

load_before="$(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null || echo '?')"
bench_args=(--benchmark_repetitions="$repetitions" --benchmark_report_aggregates_only=true
  --benchmark_out="$json" --benchmark_out_format=json)
[[ -n "$min_time" ]] && bench_args+=(--benchmark_min_time="$min_time")
"$bench_bin" "${bench_args[@]}"
load_after="$(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null || echo '?')"

echo "Running tandem_fixed_accuracy --samples $samples ..." >&2
accuracy_out="$("$accuracy_bin" --samples "$samples")"

cxx="$(sed -n 's/^CMAKE_CXX_COMPILER:[A-Z]*=//p' "$build/CMakeCache.txt")"
export TB_CPU="$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo 2>/dev/null | head -n1)"
export TB_CORES="$(nproc 2>/dev/null || echo '?')"
export TB_CXX="$("${cxx:-c++}" --version | head -n1)"
export TB_DATE="$(date -u '+%Y-%m-%d %H:%M UTC')"
export TB_COMMIT="$(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo '?')$(git -C "$root" diff --quiet HEAD 2>/dev/null || echo ' (modified)')"
export TB_LOAD="$load_before before, $load_after after"
export TB_REPS="$repetitions"
export TB_ACCURACY="$accuracy_out"

python3 - "$json" > "$md" <<'PY'
import json, os, sys

with open(sys.argv[1]) as f:
    data = json.load(f)
reps = int(os.environ["TB_REPS"])
want = "median" if reps > 1 else None
ns = {}
for b in data["benchmarks"]:
    if want is not None and b.get("aggregate_name") != want:
        continue
    if want is None and b.get("run_type") == "aggregate":
        continue
    op, typ = b["run_name"].split("/", 1)
    ns[(op, typ)] = b["s/op"] * 1e9

types = ["q32", "q16", "float", "double", "fix16"]
heads = ["Q32.32", "Q16.16", "float", "double", "fix16"]
ops = [("mul", "mul (throughput)"), ("mul_latency", "mul (latency, dependent chain)"), ("div", "div"),
       ("sqrt", "sqrt"), ("sincos", "sin + cos"), ("atan2", "atan2")]

def cell(op, t):
    v = ns.get((op, t))
    return "—" if v is None else f"{v:.2f}"

def ratio(a, b):
    va, vb = ns.get(a), ns.get(b)
    return "—" if va is None or vb is None or vb == 0 else f"{va / vb:.2f}×"

stat = "median of %d repetitions" % reps if reps > 1 else "1 repetition (quick run, not for reporting)"
e = os.environ
print("# Fixed-point benchmark\n")
print(f"- Machine: {e['TB_CPU']}, {e['TB_CORES']} logical cores; load average (1/5/15 min) {e['TB_LOAD']}")
print(f"- Compiler: {e['TB_CXX']}, CMAKE_BUILD_TYPE=Release")
print(f"- Date: {e['TB_DATE']}; commit {e['TB_COMMIT']}")
ctx = data.get("context", {})
print(f"- Result checksum (Q32.32 + Q16.16 outputs, FNV-1a): {ctx.get('checksum', '?')}")
print("- libfixmath: Debian libfixmath-dev (liblibfixmath.a), built without optimisation (upstream's CMakeLists "
      "overwrites CMAKE_C_FLAGS), with its default options: sin/atan2 result caches on, overflow checks on, "
      "rounding on, Taylor-series sin. Calls into it are not inlined.")
print("- Google Benchmark's \"Library was built as DEBUG\" warning is about Debian's libbenchmark itself, "
      "not about the code under test.\n")
print(f"## Time per operation (ns, {stat})\n")
print("Scalar throughput over pre-generated seeded inputs (every result goes to benchmark::DoNotOptimize), "
      "except the latency row. Inputs: mul ±100, div ±1000 / ±[1, 1000), sqrt [0, 10000), angles ±2π, "
      "atan2 x, y ±1000. fix16 sin + cos is two calls (libfixmath has no sincos).\n")
print("| operation | " + " | ".join(heads) + " |")
print("|---|" + "--:|" * len(heads))
for op, label in ops:
    print(f"| {label} | " + " | ".join(cell(op, t) for t in types) + " |")
print("\n## Ratios (time / time; below 1 means the first is faster)\n")
print("| comparison | ratio |")
print("|---|--:|")
rows = [
    ("Q32.32 mul / double mul (throughput)", ("mul", "q32"), ("mul", "double")),
    ("Q32.32 mul / double mul (latency)", ("mul_latency", "q32"), ("mul_latency", "double")),
    ("Q32.32 div / double div", ("div", "q32"), ("div", "double")),
    ("Q32.32 sqrt / fix16 sqrt", ("sqrt", "q32"), ("sqrt", "fix16")),
    ("Q32.32 sincos / fix16 sin + cos", ("sincos", "q32"), ("sincos", "fix16")),
    ("Q32.32 atan2 / fix16 atan2", ("atan2", "q32"), ("atan2", "fix16")),
    ("Q16.16 sqrt / fix16 sqrt", ("sqrt", "q16"), ("sqrt", "fix16")),
    ("Q16.16 sincos / fix16 sin + cos", ("sincos", "q16"), ("sincos", "fix16")),
    ("Q16.16 atan2 / fix16 atan2", ("atan2", "q16"), ("atan2", "fix16")),
]
for label, a, b in rows:
    print(f"| {label} | {ratio(a, b)} |")
print("\n## Accuracy (tandem_fixed_accuracy)\n")
print(e["TB_ACCURACY"])
PY

cat "$md"
echo >&2
echo "Wrote $md (raw benchmark JSON: $json)" >&2
