#!/usr/bin/env bash
# soak.sh — the soak test (issue 14): one hour of simulated time (216,000
# ticks at 60 Hz) of scenes/tumbler_soak.json while recording a replay, then
# `tandem verify` on that replay. tandem_soak (tests/stress/tools/soak_main.cpp)
# prints live heap bytes (counting allocator) and RSS at ticks 1k, 50k, 100k,
# 150k and the end, the median step time of an early and a late window, and
# fails when the heap grows after warm-up or a body leaves the drum.
# Not part of scripts/test.sh (it takes 10–30 minutes); ctest runs a one-minute
# slice ("stress/soak slice").
#
# Usage: scripts/soak.sh [--preset P] [--ticks N] [--out DIR]
#   --preset P  build to use (default gcc-release; clang-sanitize works, slower)
#   --ticks N   ticks to run (default 216000)
#   --out DIR   where the replay and the log go (default build/soak)
set -euo pipefail
cd "$(dirname "$0")/.."
preset=gcc-release ticks=216000 out=build/soak
while [ $# -gt 0 ]; do
  case "$1" in
    --preset) preset=$2; shift 2 ;;
    --ticks) ticks=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    -h|--help) sed -n '2,16p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "soak.sh: unknown argument $1" >&2; exit 2 ;;
  esac
done
export CMAKE_CXX_COMPILER_LAUNCHER=${CMAKE_CXX_COMPILER_LAUNCHER:-ccache} CMAKE_C_COMPILER_LAUNCHER=${CMAKE_C_COMPILER_LAUNCHER:-ccache}
cmake --preset "$preset" >/dev/null
cmake --build "build/$preset" -j2 --target tandem_soak tandem
mkdir -p "$out"
replay=$out/soak.tandem-replay
log=$out/soak.log
echo "soak.sh: $(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) cores, preset $preset, $ticks ticks" | tee "$log"
status=0
"build/$preset/tests/stress/tandem_soak" --scene scenes/tumbler_soak.json --ticks "$ticks" --out "$replay" 2>&1 | tee -a "$log" || status=1
t0=$(date +%s)
"build/$preset/tandem" verify "$replay" 2>&1 | tee -a "$log" || status=1
echo "soak.sh: tandem verify took $(( $(date +%s) - t0 )) s; replay $(stat -c %s "$replay") bytes" | tee -a "$log"
[ $status -eq 0 ] && echo "soak.sh: ok" | tee -a "$log" || echo "soak.sh: FAILED" | tee -a "$log"
exit $status
