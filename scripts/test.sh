#!/usr/bin/env bash
# test.sh — everything CI checks: installs missing packages, then configures,
# builds and runs ctest in each build below (presets from CMakePresets.json,
# build directories build/<preset>):
#
#   gcc-release      g++ 12, -O3; full accuracy samples; + install/consumer test
#   clang-release    clang 14, -O3; fixed/ golden/ stress/ tests
#   gcc-sanitize     g++, ASan + UBSan, no recovery, fault checks on;
#                    fixed/ physics/ replay/ golden/ stress/ tests
#   clang-sanitize   clang, ASan + UBSan, no recovery, fault checks on
#                    (the golden chains' variants are split between the two)
#   clang-tsan       clang, ThreadSanitizer, -O1, NDEBUG (the release code
#                    paths); the tests that step worlds on the worker pool or
#                    through a task system: golden chains with 2-16 workers,
#                    shuffled and reversed task orders, worker counts changed
#                    between steps, and the physics worker tests
#   portable-int128  g++ release on wide.h's portable 128-bit path; the same
#                    tests as clang-release
#   i686             32-bit x86, no __int128, static; fixed/ tests + golden chains
#   s390x            big-endian, under qemu-user; fixed/ tests + golden chains
#   aarch64          under qemu-user; golden chains + fixed-point golden hash
#   mingw64          Windows x86-64 under wine64; golden chains + fixed golden hash
#                    (not in the default list: its build is the slowest; run it by
#                    name after `scripts/setup-deps.sh matrix`, or use tools/matrix.sh)
#   wasm32           wasm32-wasi under node; golden chains + fixed golden hash
#   web              Emscripten (preset emscripten): the web test page's
#                    module, tested in Debian's Chromium (playwright-core,
#                    tools/web/tests): every bundled scene's hash chain equals
#                    the native `tandem run` (build/gcc-release's tandem, built
#                    here if missing), sliders, replays, error texts
#   fuzz             clang 14 libFuzzer targets (preset clang-fuzz, tests/fuzz/):
#                    each runs for a short slice (TANDEM_FUZZ_SLICE seconds,
#                    default 15) through scripts/fuzz.sh; each target counts
#                    as one test, passed when it found nothing
# (golden chains: tests/golden, the 13 scenes' hash chains; the native builds
# also run their broad-phase and snapshot/restore variants. The full
# cross-platform matrix is tools/matrix.sh, not run here: docs/determinism.md.)
#
# Usage: scripts/test.sh [--clean] [BUILD...]   (default: all builds above but mingw64)
#   --clean  delete each build directory first
# Prints the time of every stage, a per-build summary, and as its very last
# line "N passed, N failed": ctest tests summed over all builds, where a build
# whose configure or compile fails counts as one failed test (so a broken
# build never reads as "0 failed"). Exit status 0 only if everything passed.
set -uo pipefail
cd "$(dirname "$0")/.." || exit 1

all_builds=(gcc-release clang-release gcc-sanitize clang-sanitize clang-tsan portable-int128 i686 s390x aarch64 wasm32 web fuzz)
clean=0
builds=()
for arg in "$@"; do
  case "$arg" in
    --clean) clean=1 ;;
    -h|--help) sed -n '2,44p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    -*) echo "test.sh: unknown option $arg" >&2; exit 2 ;;
    *) builds+=("$arg") ;;
  esac
done
[ ${#builds[@]} -gt 0 ] || builds=("${all_builds[@]}")

jobs=2
t_start=$(date +%s)
now() { date +%s; }
clock() { date +%H:%M:%S; }
banner() { printf '\n[test.sh] ==== %s  (%s, %d s elapsed)\n' "$1" "$(clock)" "$(( $(now) - t_start ))"; }

# Sanitizer reports: stack traces, stop at the first error.
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
export ASAN_OPTIONS=${ASAN_OPTIONS:-abort_on_error=0:detect_leaks=1}

banner "setup: scripts/setup-deps.sh"
t0=$(now)
if ! bash scripts/setup-deps.sh all; then
  echo "test.sh: installing dependencies failed"
  echo "0 passed, 1 failed"
  exit 1
fi
t_setup=$(( $(now) - t0 ))
echo "[test.sh] setup: ${t_setup} s"

total_passed=0
total_failed=0
summary=()

# run_build NAME: configure, build and test one preset; appends to summary.
run_build() {
  local name=$1 preset=$1 dir=build/$1 result=ok passed=0 failed=0
  local t_cfg=0 t_bld=0 t_tst=0 t0 b0 log
  local build_args=() ctest_args=() runner=()
  case "$name" in
    # Cross builds check the fixed-point core and the golden hash chains (the
    # other physics tests would take too long under emulation).
    i686|s390x)
      build_args=(--target tandem_tests_fixed tandem_tests_golden)
      ctest_args=(-R '^fixed/|^golden/golden chain: [a-z_0-9]+$') ;;
    aarch64|mingw64|wasm32)
      build_args=(--target tandem_tests_fixed tandem_tests_golden)
      ctest_args=(-R '^golden/golden chain: [a-z_0-9]+$|^fixed/fixed_math gives the same bits') ;;
    gcc-release) ;;  # the one build that also runs the determinism lint
    # A second compiler at -O3 and the portable 128-bit path matter where
    # bits are computed: the fixed-point tests, the golden chains (with their
    # broad-phase, restore, worker and solver-path variants) and the stress
    # worlds' asserted hashes. The behaviour tests (physics/, replay/, the
    # command line, C API, network) run in gcc-release and both sanitizer
    # builds, clang's included.
    clang-release|portable-int128)
      build_args=(--target tandem_tests_fixed tandem_tests_golden tandem_tests_stress)
      ctest_args=(-R '^(fixed|golden|stress)/' -E '^stress/soak slice') ;;
    # The web page: its browser tests compare with the native CLI.
    web)
      preset=emscripten dir=build/emscripten
      ctest_args=(-R '^web/') ;;
    # The fuzzers: built from preset clang-fuzz, "tested" by short runs.
    fuzz)
      preset=clang-fuzz dir=build/clang-fuzz
      build_args=(--target tandem_fuzzers) ;;
    # The two sanitizer builds share out the work (the release builds run all
    # of it): gcc-sanitize runs the engine's tests (as clang-release) with
    # the golden chains' broad-phase variants; clang-sanitize runs every
    # test but those variants, so the command line, C API and network code
    # run under clang's ASan + UBSan, and the worker, task-system and
    # solver-path variants of the chains too. Each sanitizer still runs
    # every scene's chain, its restore and its compact rollback.
    gcc-sanitize)
      build_args=(--target tandem_tests_fixed tandem_tests_physics tandem_tests_replay
                  tandem_tests_golden tandem_tests_stress tandem_stress tandem_soak)
      ctest_args=(-R '^(fixed|physics|replay|golden|stress)/' -E '^golden/golden chain (with|through|on the) ') ;;
    clang-sanitize)
      ctest_args=(-E '^determinism lint|^golden/golden chain: [a-z_0-9]+, every broad phase$') ;;
    # Data races between the pool's threads are undefined behaviour even
    # where every order gives the same bits: ThreadSanitizer watches the
    # tests that run steps on more than one thread.
    clang-tsan)
      build_args=(--target tandem_tests_golden tandem_tests_physics)
      ctest_args=(-R '^golden/.*(worker|task system)|^physics/.*(worker|task)')
      # clang 14's TSan cannot map its shadow memory under kernels that
      # randomise mmap with more than 28 bits ("unexpected memory mapping"):
      # run the tests without address randomisation where setarch allows it.
      if setarch "$(uname -m)" -R true 2>/dev/null; then runner=(setarch "$(uname -m)" -R); fi ;;
    *) ctest_args=(-E '^determinism lint') ;;
  esac

  banner "$name"
  b0=$(now)
  if [ $clean -eq 1 ]; then rm -rf "$dir"; fi
  # A build directory made by another generator cannot be reused.
  if [ -f "$dir/CMakeCache.txt" ] && ! grep -q '^CMAKE_GENERATOR:INTERNAL=Ninja$' "$dir/CMakeCache.txt"; then
    echo "test.sh: $dir was configured with another generator; starting it afresh"
    rm -rf "$dir"
  fi

  t0=$(now)
  echo "[test.sh] $name: configure (cmake --preset $preset)"
  if ! cmake --preset "$preset"; then
    result="configure FAILED"
  fi
  t_cfg=$(( $(now) - t0 ))
  echo "[test.sh] $name: configure: ${t_cfg} s"

  if [ "$result" = ok ]; then
    t0=$(now)
    echo "[test.sh] $name: build (-j$jobs)"
    if ! cmake --build "$dir" -j "$jobs" "${build_args[@]}"; then
      result="build FAILED"
    fi
    # web: the native `tandem` the browser tests compare with.
    if [ "$result" = ok ] && [ "$name" = web ]; then
      echo "[test.sh] $name: native tandem (build/gcc-release)"
      if ! { [ -f build/gcc-release/CMakeCache.txt ] || cmake --preset gcc-release >/dev/null; } ||
         ! cmake --build build/gcc-release -j "$jobs" --target tandem; then
        result="build FAILED (native tandem)"
      fi
    fi
    t_bld=$(( $(now) - t0 ))
    echo "[test.sh] $name: build: ${t_bld} s"
  fi

  if [ "$result" = ok ] && [ "$name" = web ] && [ ! -f tools/web/node_modules/playwright-core/package.json ]; then
    # setup-deps could not install playwright-core (npm's registry not
    # reachable): the module and page were built, the browser tests cannot run.
    result="ok, browser SKIPPED"
    echo "[test.sh] web: WARNING: tools/web/node_modules/playwright-core is missing (npm could not reach its" \
      "registry when scripts/setup-deps.sh ran): the page was built, its browser tests were NOT run"
  elif [ "$result" = ok ] && [ "$name" = fuzz ]; then
    t0=$(now)
    log=$dir/fuzz-slice-output.txt
    echo "[test.sh] $name: scripts/fuzz.sh --seconds ${TANDEM_FUZZ_SLICE:-15} (each target)"
    bash scripts/fuzz.sh --no-build --seconds "${TANDEM_FUZZ_SLICE:-15}" --out "$dir/fuzz-slice" 2>&1 | tee "$log"
    t_tst=$(( $(now) - t0 ))
    echo "[test.sh] $name: fuzz slice: ${t_tst} s"
    # pass/XPASS: passed; FAIL: failed; stopped (interrupted by a signal,
    # nothing found): failed, as the slice did not run; xfail (a crash listed
    # in tests/fuzz/known-crashes.txt, owned by another change): neither.
    passed=$(grep -cE '^\[fuzz.sh\] result [a-z_]+ (pass|XPASS)$' "$log")
    failed=$(grep -cE '^\[fuzz.sh\] result [a-z_]+ FAIL$' "$log")
    local xfail stopped
    xfail=$(grep -cE '^\[fuzz.sh\] result [a-z_]+ xfail$' "$log")
    stopped=$(grep -cE '^\[fuzz.sh\] result [a-z_]+ stopped$' "$log")
    if [ $(( passed + failed + xfail + stopped )) -eq 0 ]; then
      failed=1
      result="fuzz FAILED (no result)"
    elif [ "$failed" -gt 0 ]; then
      failed=$(( failed + stopped ))
      result="fuzz FOUND CRASHES"
    elif [ "$stopped" -gt 0 ]; then
      failed=$stopped
      result="fuzz INTERRUPTED ($stopped target(s) stopped by a signal)"
    elif [ "$xfail" -gt 0 ]; then
      result="ok, $xfail xfail"
    fi
  elif [ "$result" = ok ]; then
    t0=$(now)
    log=$dir/ctest-output.txt
    echo "[test.sh] $name: ctest"
    "${runner[@]}" ctest --test-dir "$dir" -j "$jobs" --output-on-failure --no-tests=error "${ctest_args[@]}" 2>&1 |
      tee "$log"
    local rc=${PIPESTATUS[0]}
    t_tst=$(( $(now) - t0 ))
    echo "[test.sh] $name: ctest: ${t_tst} s"
    # "100% tests passed, 0 tests failed out of 21"
    local line
    line=$(grep -E '^[0-9]+% tests passed, [0-9]+ tests? failed out of [0-9]+' "$log" | tail -1)
    if [ -n "$line" ]; then
      local total
      failed=$(sed -E 's/.* ([0-9]+) tests? failed out of.*/\1/' <<<"$line")
      total=$(sed -E 's/.* out of ([0-9]+).*/\1/' <<<"$line")
      passed=$(( total - failed ))
      if [ "$rc" -ne 0 ] && [ "$failed" -eq 0 ]; then failed=1; fi
      [ "$failed" -eq 0 ] || result="tests FAILED"
    else
      failed=1
      result="ctest FAILED (exit $rc)"
    fi
  else
    failed=1
  fi

  local t_all=$(( $(now) - b0 ))
  total_passed=$(( total_passed + passed ))
  total_failed=$(( total_failed + failed ))
  summary+=("$(printf '%-16s %-22s %6d %6d %9d %7d %6d %7d' "$name" "$result" "$passed" "$failed" \
    "$t_cfg" "$t_bld" "$t_tst" "$t_all")")
  echo "[test.sh] $name: $result, $passed passed, $failed failed, ${t_all} s"
}

for b in "${builds[@]}"; do
  case " ${all_builds[*]} " in
    *" $b "*) run_build "$b" ;;
    *) echo "test.sh: unknown build $b (builds: ${all_builds[*]})"
       summary+=("$(printf '%-16s %-22s' "$b" "unknown build")")
       total_failed=$(( total_failed + 1 )) ;;
  esac
done

t_total=$(( $(now) - t_start ))
echo
echo "[test.sh] summary (seconds; setup ${t_setup} s, total ${t_total} s on $(nproc) cores)"
printf '%-16s %-22s %6s %6s %9s %7s %6s %7s\n' build result passed failed configure build test total
for line in "${summary[@]}"; do echo "$line"; done
echo
echo "${total_passed} passed, ${total_failed} failed"
[ "$total_failed" -eq 0 ]
