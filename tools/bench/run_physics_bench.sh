#!/usr/bin/env bash
# run_physics_bench.sh — configure a Release build with the benchmarks on,
# build tandem_bench_physics, run the physics suite (Tandem's broad phases
# against Box2D 2.4 and Chipmunk2D) and write the results to a folder.
#
# Usage: tools/bench/run_physics_bench.sh [--quick] [--build-dir DIR] [--out DIR] [--box2d-v3 DIR] [-- BENCH_ARGS...]
#   --quick        circles-1k, circles-2k, pyramid-20 only, 2 runs (smoke test, not for reporting)
#   --box2d-v3     also run Box2D v3 (1 and 2 workers) from a checkout built
#                  outside the repository (docs/benchmarks.md); sets the CMake
#                  cache variable TANDEM_BOX2D_V3_DIR (it stays set in that
#                  build folder until changed; "" turns it off)
#   --build-dir    default build/bench (shared with run_fixed_bench.sh)
#   --out          default build/bench-results (relative to the repository root)
#   BENCH_ARGS     replace the default suite arguments, e.g.
#                  -- circles-1k pyramid-100 --runs 9 --broadphase sap,grid
# Default suite: circles-1k…32k, pyramid-20, pyramid-100, rain-4000, 5 runs
# (3 above 4000 bodies), every broad phase (naive only up to 4000 bodies;
# an engine whose run takes over 60 s is not repeated and skips larger
# scenes of that family), with the peers.
# Writes OUT/table.txt (stdout of the run), OUT/results.csv,
# OUT/results.json, OUT/circles.svg and OUT/progress.log.
# Exit status: the driver's (1: Tandem's broad phases ended a scene in
# different states, a determinism bug; the results are still written).
# Environment: CMAKE_GENERATOR is honoured (default: Ninja when available);
# CMAKE_ARGS (space-separated) go to the configure step.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
build="build/bench"
out="build/bench-results"
quick=0
box2d_v3=unset
bench_args=()
while [[ $# -gt 0 ]]; do
  case "$1" in
    --quick) quick=1; shift ;;
    --build-dir) build="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    --box2d-v3) box2d_v3="$2"; shift 2 ;;
    --) shift; bench_args=("$@"); break ;;
    -h|--help) sed -n '2,24p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "run_physics_bench.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
[[ "$build" = /* ]] || build="$root/$build"
[[ "$out" = /* ]] || out="$root/$out"
if [[ ${#bench_args[@]} -eq 0 ]]; then
  if [[ $quick -eq 1 ]]; then
    bench_args=(circles-1k circles-2k pyramid-20 --runs 2)
  else
    bench_args=(--runs 5 --runs-large 3)
  fi
fi

generator=()
if [[ -z "${CMAKE_GENERATOR:-}" ]] && command -v ninja >/dev/null; then generator=(-G Ninja); fi
read -r -a extra_cmake <<<"${CMAKE_ARGS:-}"
if [[ "$box2d_v3" != unset ]]; then extra_cmake+=("-DTANDEM_BOX2D_V3_DIR=$box2d_v3"); fi
if [[ ! -f "$build/CMakeCache.txt" ]]; then
  cmake -S "$root" -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release -DTANDEM_BUILD_BENCH=ON \
    -DTANDEM_BUILD_TESTS=OFF -DTANDEM_BUILD_TOOLS=OFF "${extra_cmake[@]}"
else
  cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DTANDEM_BUILD_BENCH=ON "${extra_cmake[@]}"
fi
cmake --build "$build" --target tandem_bench_physics -j"$(nproc 2>/dev/null || echo 2)"

mkdir -p "$out"
bin="$build/tools/bench/tandem_bench_physics"
echo "Running: tandem_bench_physics ${bench_args[*]}" >&2
status=0
"$bin" "${bench_args[@]}" --csv "$out/results.csv" --json "$out/results.json" --svg "$out/circles.svg" \
  2> >(tee "$out/progress.log" >&2) | tee "$out/table.txt" || status=$?
commit="$(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo '?')$(git -C "$root" diff --quiet HEAD 2>/dev/null || echo ' (modified)')"
echo "commit $commit; command: tandem_bench_physics ${bench_args[*]}" >>"$out/table.txt"
echo >&2
echo "Results in $out: table.txt results.csv results.json circles.svg progress.log" >&2
if [[ $status -eq 1 ]]; then
  echo "run_physics_bench.sh: WARNING: Tandem's broad phases disagreed on a scene's final state (see table.txt)" >&2
fi
exit "$status"
