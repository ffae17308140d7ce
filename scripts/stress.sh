#!/usr/bin/env bash
# stress.sh — the long random-world stress (issue 14): seeded worlds with every
# shape kind, filters, sensors, chains, kinematic bodies, sizes, masses and
# speeds across physics/limits.h, bodies created and destroyed and inputs every
# tick, inside a closed container (tests/stress/stress_world.h). Each world runs
# with all four broad phases and once through a snapshot/restore; the hash
# chains must agree, no fixed-point fault may be reported, no sanitizer error,
# and no body may leave the container in a slow world. Escapes of the two known
# engine issues (fast worlds; bodies with chain segments) are counted and
# listed with their seeds, not failed (see tests/stress/test_stress_worlds.cpp);
# so is known issue 8, a failure a world has only with joint inputs (random
# joints of every kind, created, destroyed and changed; --no-joints: none).
#
# Usage: scripts/stress.sh [--worlds N] [--ticks T] [--first-seed S] [--jobs J]
#                          [--preset P] [--out DIR] [--no-joints]
#   --worlds N      worlds to run (default 10000)
#   --ticks T       ticks per world (default 600)
#   --first-seed S  first seed (default 1); seeds S … S+N−1
#   --jobs J        processes in parallel, each a contiguous seed range (default 2)
#   --preset P      build (default clang-sanitize: ASan + UBSan, fault checks on)
#   --out DIR       logs (default build/stress); DIR/job-K.log names the seed
#                   each world started, so a crash names its seed
#   --no-joints     no joint inputs: the worlds of runs before 2026-11-29
#                   (joint inputs create, destroy and change random joints)
# Reproduce one world: build/<preset>/tests/stress/tandem_stress --first-seed S
# --worlds 1 --ticks T; TANDEM_STRESS_TRACE=<body index> prints one body's path.
set -uo pipefail
cd "$(dirname "$0")/.." || exit 1
worlds=10000 ticks=600 first=1 jobs=2 preset=clang-sanitize out=build/stress
joint_args=()
while [ $# -gt 0 ]; do
  case "$1" in
    --worlds) worlds=$2; shift 2 ;;
    --ticks) ticks=$2; shift 2 ;;
    --first-seed) first=$2; shift 2 ;;
    --jobs) jobs=$2; shift 2 ;;
    --preset) preset=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --no-joints) joint_args=(--no-joints); shift ;;
    -h|--help) sed -n '2,26p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "stress.sh: unknown argument $1" >&2; exit 2 ;;
  esac
done
export CMAKE_CXX_COMPILER_LAUNCHER=${CMAKE_CXX_COMPILER_LAUNCHER:-ccache} CMAKE_C_COMPILER_LAUNCHER=${CMAKE_C_COMPILER_LAUNCHER:-ccache}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
export ASAN_OPTIONS=${ASAN_OPTIONS:-abort_on_error=0:detect_leaks=1}
cmake --preset "$preset" >/dev/null || exit 1
cmake --build "build/$preset" -j2 --target tandem_stress || exit 1
bin=build/$preset/tests/stress/tandem_stress
mkdir -p "$out"
echo "stress.sh: $(date -u '+%Y-%m-%d %H:%M UTC'), preset $preset, $worlds worlds x $ticks ticks from seed $first, $jobs jobs${joint_args:+, joint inputs off}"
t0=$(date +%s)
per=$(( (worlds + jobs - 1) / jobs ))
pids=()
for (( k = 0; k < jobs; k++ )); do
  s=$(( first + k * per ))
  n=$(( worlds - k * per )); [ $n -gt $per ] && n=$per
  [ $n -gt 0 ] || continue
  "$bin" --worlds "$n" --ticks "$ticks" --first-seed "$s" "${joint_args[@]}" --quiet --log "$out/job-$k.log" \
    > "$out/job-$k.out" 2> "$out/job-$k.err" &
  pids+=($!)
done
status=0
for k in "${!pids[@]}"; do
  if ! wait "${pids[$k]}"; then
    status=1
    echo "stress.sh: job $k failed; last seed started: $(grep '^start seed' "$out/job-$k.log" | tail -1)"
    tail -20 "$out/job-$k.err"
  fi
done
cat "$out"/job-*.out | grep -E '^FAIL' || true
known=$(cat "$out"/job-*.out | grep -c '^KNOWN' || true)
done_worlds=$(cat "$out"/job-*.log | grep -c '^seed ' || true)
echo "stress.sh: $done_worlds of $worlds worlds finished, $(cat "$out"/job-*.out | grep -c '^FAIL' || true) failed," \
  "$known with known issues ($(cat "$out"/job-*.out | grep '^KNOWN' | grep -c 'fast world:' || true) fast-world escapes," \
  "$(cat "$out"/job-*.out | grep '^KNOWN' | grep -c 'chain segments:' || true) chain-body escapes," \
  "$(cat "$out"/job-*.out | grep '^KNOWN' | grep -c 'known issue 8' || true) known issue 8 with joints); $(( $(date +%s) - t0 )) s"
grep -h '^summary' "$out"/job-*.out
exit $status
