#!/usr/bin/env bash
# fuzz.sh — builds the libFuzzer targets (preset clang-fuzz: clang 14,
# -fsanitize=fuzzer,address,undefined; tests/fuzz/) and runs each for a set
# time, then prints a summary table (target, executions, exec/s, coverage as
# libFuzzer's cov: and ft:, crashes) and writes it to OUT/summary.txt.
#
#   replay_file  read_replay, then a world at tick ≤ 30 from the replay
#   snapshot     create_world_from_snapshot, then 30 steps
#   commands     decode_commands, round trip, applied to a world, 3 steps
#   scene        load_scene_text (≤ 300 bodies), build_world, 5 steps
#   decimal      parse_q32 / parse_q16, exact round trip through to_string
#   session_packet  decode_session_packet, round trip, then a live session receives it
#
# Usage: scripts/fuzz.sh [--seconds N] [--out DIR] [--no-build] [--make-seeds] [TARGET...]
#   --seconds N   time per target (default 60); hours: --seconds 3600 or more
#   --out DIR     where corpora, logs, crashes and summary.txt go
#                 (default build/clang-fuzz/fuzz-out; the corpus there grows
#                 across runs, so a second run starts where the first stopped)
#   --no-build    use the fuzzers already built in build/clang-fuzz
#   --make-seeds  rewrite the committed seed corpora (tests/fuzz/corpus/) from
#                 the bundled scenes, a replay recorded by the command line and
#                 fuzz_make_seeds, then exit (TANDEM_BIN=path/to/tandem
#                 uses that command line instead of building one here)
# Every run appends a line to OUT/ledger.tsv (UTC start, target, seconds,
# executions, exec/s, cov, ft, new crash files, result, the checkout's
# commit); the summary's "in all" column adds up the executions of every run
# of that target recorded there, i.e. of every run on the corpus kept under
# OUT (issue 14's goal counts executions on one corpus).
# Each target is seeded from tests/fuzz/corpus/<target>/ (scene also gets
# tests/fuzz/scene.dict). A crash, leak, sanitizer report, timeout (> 10 s
# per input) or out-of-memory (> 2 GB) stops that target and is kept as
# OUT/crashes/<target>/<kind>-<sha1>; to make it a regression test copy it to
# tests/fuzz/regressions/<target>/ (tests/tools/test_fuzz_regressions.cpp
# replays that folder in every build). Reproduce one with
#   build/clang-fuzz/tests/fuzz/fuzz_<target> FILE
# A target listed in tests/fuzz/known-crashes.txt (a crash in code another
# change owns, saved as a .pending regression) reports a finding as "xfail"
# instead of FAIL, and "XPASS" when it found nothing (remove its line then).
# A run stopped by SIGINT or SIGTERM (Ctrl-C, kill, pkill fuzz_<target>)
# before its time is up, with no new file under OUT/crashes/<target>/, is
# reported as "stopped": not a finding (libFuzzer exits 72 after printing
# "run interrupted" and its final statistics, which the row shows), but not
# a full run either.
# Exit status: 0 when no target found anything unexpected, 1 otherwise, 2 on
# bad usage or a failed build. Prints "[fuzz.sh] result <target>
# pass|FAIL|xfail|XPASS|stopped" per target (scripts/test.sh counts pass/XPASS
# as passed, FAIL and stopped as failed, xfail as neither).
set -uo pipefail
cd "$(dirname "$0")/.." || exit 2

all_targets=(replay_file snapshot commands scene decimal session_packet)
seconds=60
out=build/clang-fuzz/fuzz-out
build=1
make_seeds=0
targets=()
while [ $# -gt 0 ]; do
  case "$1" in
    --seconds) seconds=${2:-}; shift 2 ;;
    --out) out=${2:-}; shift 2 ;;
    --no-build) build=0; shift ;;
    --make-seeds) make_seeds=1; shift ;;
    -h|--help) sed -n '2,47p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    -*) echo "fuzz.sh: unknown option $1" >&2; exit 2 ;;
    *) targets+=("$1"); shift ;;
  esac
done
[[ "$seconds" =~ ^[0-9]+$ ]] && [ "$seconds" -ge 1 ] || { echo "fuzz.sh: --seconds wants a whole number ≥ 1" >&2; exit 2; }
[ ${#targets[@]} -gt 0 ] || targets=("${all_targets[@]}")
for t in "${targets[@]}"; do
  case " ${all_targets[*]} " in
    *" $t "*) ;;
    *) echo "fuzz.sh: unknown target $t (targets: ${all_targets[*]})" >&2; exit 2 ;;
  esac
done

dir=build/clang-fuzz
if [ $build -eq 1 ] || [ $make_seeds -eq 1 ]; then
  echo "[fuzz.sh] build: cmake --preset clang-fuzz; tandem_fuzzers"
  cmake --preset clang-fuzz >/dev/null || { echo "fuzz.sh: configure failed" >&2; exit 2; }
  extra=()
  [ $make_seeds -eq 1 ] && extra=(fuzz_make_seeds)
  [ $make_seeds -eq 1 ] && [ -z "${TANDEM_BIN:-}" ] && extra+=(tandem)
  cmake --build "$dir" -j 2 --target tandem_fuzzers "${extra[@]}" || { echo "fuzz.sh: build failed" >&2; exit 2; }
fi

if [ $make_seeds -eq 1 ]; then
  corpus=tests/fuzz/corpus
  rm -rf "$corpus"
  mkdir -p "$corpus"/{replay_file,snapshot,commands,scene,decimal,session_packet}
  "$dir"/tests/fuzz/fuzz_make_seeds "$corpus" || exit 2
  cp scenes/*.json "$corpus"/scene/
  cp tests/tools/data/*.json "$corpus"/scene/
  tandem=${TANDEM_BIN:-$dir/tandem}  # any build's command line records the same bytes
  export ASAN_OPTIONS=detect_leaks=0
  for s in stack dominoes; do
    "$tandem" -q record "scenes/$s.json" --ticks 12 --keyframe-every 6 -o "$corpus/replay_file/$s.tdr" || exit 2
    "$tandem" -q replay "$corpus/replay_file/$s.tdr" --save-state "$corpus/snapshot/$s.state" >/dev/null || exit 2
  done
  "$tandem" -q record scenes/impulses.json --ticks 40 --keyframe-every 0 -o "$corpus/replay_file/impulses.tdr" || exit 2
  du -sh "$corpus"
  exit 0
fi

mkdir -p "$out"
summary=$out/summary.txt
ledger=$out/ledger.tsv
[ -f "$ledger" ] || printf 'start_utc\ttarget\tseconds\texecutions\texec_per_s\tcov\tft\tcrashes\tresult\tcommit\n' >"$ledger"
commit=$(git rev-parse --short HEAD 2>/dev/null || echo unknown)
t_all=$(date +%s)
rows=()
found=0
for t in "${targets[@]}"; do
  exe=$dir/tests/fuzz/fuzz_$t
  if [ ! -x "$exe" ]; then
    echo "fuzz.sh: $exe is missing (build first, without --no-build)" >&2
    exit 2
  fi
  work=$out/corpus/$t
  crashes=$out/crashes/$t
  log=$out/$t.log
  mkdir -p "$work" "$crashes"
  args=(-max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1
        -artifact_prefix="$crashes/" -close_fd_mask=1 -interrupted_exitcode=72)
  [ "$t" = scene ] && args+=(-dict=tests/fuzz/scene.dict)
  echo "[fuzz.sh] $t: ${seconds} s ($(date +%H:%M:%S))"
  started=$(date -u '+%Y-%m-%dT%H:%M:%SZ')
  before=$(ls "$crashes" | wc -l)
  # Leaks are findings too; the first directory receives new inputs.
  ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1} UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1} \
    "$exe" "${args[@]}" "$work" "tests/fuzz/corpus/$t" >"$log" 2>&1
  rc=$?
  after=$(ls "$crashes" | wc -l)
  new=$(( after - before ))
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
  last=$(grep -E '^#[0-9]+' "$log" | tail -1)
  cov=$(sed -nE 's/.* cov: ([0-9]+).*/\1/p' <<<"$last")
  ft=$(sed -nE 's/.* ft: ([0-9]+).*/\1/p' <<<"$last")
  corpus_n=$(ls "$work" | wc -l)
  known=0
  grep -qE "^$t[[:space:]]" tests/fuzz/known-crashes.txt 2>/dev/null && known=1
  if [ "$rc" -eq 72 ] && [ "$new" -eq 0 ] && grep -q 'libFuzzer: run interrupted' "$log"; then
    # libFuzzer's exit status after SIGINT/SIGTERM (-interrupted_exitcode,
    # 72 unless set): stopped from outside, nothing found in the part that ran.
    result=stopped
    echo "[fuzz.sh] $t: stopped by a signal after ${execs:-?} executions, no finding; log $log"
  elif [ "$rc" -ne 0 ] || [ "$new" -gt 0 ]; then
    [ "$new" -gt 0 ] || new=1
    grep -E 'ERROR: |SUMMARY: |runtime error|fuzz invariant broken|deadly signal|Test unit written' "$log" | head -8
    echo "[fuzz.sh] $t: found something (exit $rc); log $log, inputs in $crashes/"
    if [ $known -eq 1 ]; then
      result=xfail
      echo "[fuzz.sh] $t: expected (tests/fuzz/known-crashes.txt): $(sed -nE "s/^$t[[:space:]]+//p" tests/fuzz/known-crashes.txt)"
    else
      result=FAIL
      found=1
    fi
  elif [ $known -eq 1 ]; then
    result=XPASS
    echo "[fuzz.sh] $t: found nothing this time, though tests/fuzz/known-crashes.txt lists a crash (its .pending regression reproduces it; remove the line once the fix has landed)"
  else
    result=pass
  fi
  printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$started" "$t" "$seconds" "${execs:-0}" "${rate:-?}" \
    "${cov:-?}" "${ft:-?}" "$new" "$result" "$commit" >>"$ledger"
  in_all=$(awk -F'\t' -v t="$t" 'NR > 1 && $2 == t && $4 ~ /^[0-9]+$/ { n += $4 } END { printf "%d", n }' "$ledger")
  rows+=("$(printf '%-12s %14s %10s %8s %8s %8s %8s %14s  %s' "$t" "${execs:-?}" "${rate:-?}" "${cov:-?}" "${ft:-?}" \
    "$corpus_n" "$new" "$in_all" "$result")")
  echo "[fuzz.sh] result $t $result"
done

{
  echo "fuzz.sh summary: $(date -u '+%Y-%m-%d %H:%M UTC'), ${seconds} s per target, $(nproc) cores ($(sed -n 's/^model name[^:]*: //p' /proc/cpuinfo | head -1))"
  printf '%-12s %14s %10s %8s %8s %8s %8s %14s  %s\n' target execs exec/s cov ft corpus crashes "in all" result
  for r in "${rows[@]}"; do echo "$r"; done
  echo "total $(( $(date +%s) - t_all )) s; logs and crashes under $out"
} | tee "$summary"
exit $found
