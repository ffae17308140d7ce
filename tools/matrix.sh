#!/usr/bin/env bash
# matrix.sh — the cross-platform determinism matrix: builds the golden-chain
# test (tandem_tests_golden) and the fixed-point tests (tandem_tests_fixed)
# on every configuration below and runs, on each, every golden chain (13
# scenes × 3600 ticks, tests/golden/*.txt) and the fixed-point golden hash.
# Native rows also run the broad-phase and snapshot/restore variants of the
# chains. Every row must reproduce the same bits.
#
# Usage: tools/matrix.sh [--list] [--only NAME...] [--jobs N] [--no-install]
#                        [--regenerate]
#   --list        print the configurations and exit
#   --only NAME   run only these rows (repeatable; several names may follow)
#   --jobs N      parallel compile and test jobs (default 2)
#   --no-install  do not run scripts/setup-deps.sh matrix
#   --regenerate  first rewrite the snapshot's golden files with the gcc-O3
#                 row (the working tree's files are left alone), so the rows
#                 check agreement with x86-64 g++ -O3 even while the golden
#                 files in the tree are stale
# The sources are copied once, at the start, to build/matrix/src (tracked
# and untracked files git does not ignore), so every row builds the same
# code even while the working tree changes. Build directories:
# build/matrix/<name>. Prints a table (target, compiler, flags, result, build
# and test seconds) and writes it, as Markdown, to
# build/matrix/matrix-table.md. Exit status 0 only if every row passed.
#
# Cross rows run under qemu-user (Linux targets), wine64 (Windows) or node's
# WASI (wasm32); the toolchain files are cmake/toolchains/*.cmake. Warnings
# are not errors here (TANDEM_WERROR=OFF: odd compilers and flags such as
# -ffast-math may warn; the CI builds keep -Werror); tools and bench are off.
set -uo pipefail
cd "$(dirname "$0")/.." || exit 1
root=$(pwd)

# name | target | compiler | flags (shown) | cmake arguments | scope
#   scope: full = every golden test; chains = the plain chains only.
rows=(
  "gcc-O3|x86-64|g++ 12|-O3|-DCMAKE_CXX_COMPILER=g++ -DCMAKE_BUILD_TYPE=Release|full"
  "s390x|s390x big-endian (qemu)|g++-s390x-linux-gnu 12|-O3|--toolchain cmake/toolchains/s390x-linux-gnu.cmake -DCMAKE_BUILD_TYPE=Release|chains"
  "i686|i686 (32-bit, static)|g++-i686-linux-gnu 12|-O3 -static|--toolchain cmake/toolchains/i686-linux-gnu.cmake -DCMAKE_BUILD_TYPE=Release|chains"
  "aarch64|aarch64 (qemu)|g++-aarch64-linux-gnu 12|-O3|--toolchain cmake/toolchains/aarch64-linux-gnu.cmake -DCMAKE_BUILD_TYPE=Release|chains"
  "mingw64|Windows x86-64 (wine64)|x86_64-w64-mingw32-g++ 12|-O3 -static|--toolchain cmake/toolchains/x86_64-w64-mingw32.cmake -DCMAKE_BUILD_TYPE=Release|chains"
  "wasm32|wasm32-wasi (node)|clang 14|-O3 -fno-exceptions|--toolchain cmake/toolchains/wasm32-wasi.cmake -DCMAKE_BUILD_TYPE=Release|chains"
  "armhf|armv7 hard-float (qemu)|g++-arm-linux-gnueabihf 12|-O3|--toolchain cmake/toolchains/arm-linux-gnueabihf.cmake -DCMAKE_BUILD_TYPE=Release|chains"
  "riscv64|riscv64 (qemu)|g++-riscv64-linux-gnu 12|-O3|--toolchain cmake/toolchains/riscv64-linux-gnu.cmake -DCMAKE_BUILD_TYPE=Release|chains"
  "ppc64le|ppc64le (qemu)|g++-powerpc64le-linux-gnu 12|-O3|--toolchain cmake/toolchains/powerpc64le-linux-gnu.cmake -DCMAKE_BUILD_TYPE=Release|chains"
  "clang-O3|x86-64|clang 14|-O3|-DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Release|full"
  "aarch64-clang|aarch64 (qemu)|clang 14|-O3|--toolchain cmake/toolchains/clang-cross-linux-gnu.cmake -DTANDEM_CROSS_TRIPLE=aarch64-linux-gnu -DCMAKE_BUILD_TYPE=Release|chains"
  "s390x-clang|s390x big-endian (qemu)|clang 14|-O3|--toolchain cmake/toolchains/clang-cross-linux-gnu.cmake -DTANDEM_CROSS_TRIPLE=s390x-linux-gnu -DCMAKE_BUILD_TYPE=Release|chains"
  "gcc-fast-math|x86-64|g++ 12|-O3 -ffast-math|-DCMAKE_CXX_COMPILER=g++ -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS=-ffast-math|chains"
  "clang-fast-math|x86-64|clang 14|-O3 -ffast-math|-DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS=-ffast-math|chains"
  "portable-int128|x86-64|g++ 12|-O3, no __int128|-DCMAKE_CXX_COMPILER=g++ -DCMAKE_BUILD_TYPE=Release -DTANDEM_FORCE_PORTABLE_INT128=ON|chains"
  "gcc-O3-native|x86-64|g++ 12|-O3 -march=native|-DCMAKE_CXX_COMPILER=g++ -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS=-march=native|chains"
  "clang-O3-native|x86-64|clang 14|-O3 -march=native|-DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS=-march=native|chains"
  "gcc-O0|x86-64|g++ 12|-O0|-DCMAKE_CXX_COMPILER=g++ -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG=-O0|chains"
  "clang-O0|x86-64|clang 14|-O0|-DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG=-O0|chains"
)

field() { cut -d'|' -f"$2" <<<"$1"; }

jobs=2
install=1
regenerate=0
only=()
list=0
while [ $# -gt 0 ]; do
  case "$1" in
    --list) list=1 ;;
    --jobs) shift; jobs=${1:?--jobs needs a number} ;;
    --jobs=*) jobs=${1#--jobs=} ;;
    --no-install) install=0 ;;
    --regenerate) regenerate=1 ;;
    --only) shift
      while [ $# -gt 0 ] && [ "${1#-}" = "$1" ]; do only+=("$1"); shift; done
      continue ;;
    -h|--help) sed -n '2,29p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "matrix.sh: unknown argument $1 (see --help)" >&2; exit 2 ;;
  esac
  shift
done

if [ $list -eq 1 ]; then
  printf '%-16s %-28s %-28s %s\n' NAME TARGET COMPILER FLAGS
  for r in "${rows[@]}"; do
    printf '%-16s %-28s %-28s %s\n' "$(field "$r" 1)" "$(field "$r" 2)" "$(field "$r" 3)" "$(field "$r" 4)"
  done
  exit 0
fi

selected=()
for r in "${rows[@]}"; do
  name=$(field "$r" 1)
  if [ ${#only[@]} -eq 0 ]; then selected+=("$r"); continue; fi
  for o in "${only[@]}"; do [ "$o" = "$name" ] && selected+=("$r"); done
done
for o in "${only[@]}"; do
  found=0
  for r in "${rows[@]}"; do [ "$(field "$r" 1)" = "$o" ] && found=1; done
  [ $found -eq 1 ] || { echo "matrix.sh: unknown row $o (see --list)" >&2; exit 2; }
done

if [ $install -eq 1 ]; then
  bash scripts/setup-deps.sh matrix || { echo "matrix.sh: installing packages failed" >&2; exit 1; }
fi

# One snapshot of the sources for every row.
src=build/matrix/src
rm -rf "$src"
mkdir -p "$src"
if ! git ls-files -z -co --exclude-standard | tar --null -T - -cf - | tar -xf - -C "$src"; then
  echo "matrix.sh: copying the sources to $src failed" >&2
  exit 1
fi
snapshot_id=$(cd "$src" && find . -type f -print0 | sort -z | xargs -0 sha256sum | sha256sum | cut -c1-12)
echo "[matrix] sources copied to $src (content id $snapshot_id)"

launcher=()
command -v ccache >/dev/null 2>&1 && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
export WINEDEBUG=-all
mkdir -p build/matrix
results=()
failed=0
now() { date +%s; }

if [ $regenerate -eq 1 ]; then
  dir=build/matrix/gcc-O3  # the gcc-O3 row's configuration: that row reuses the build
  echo "[matrix] ==== regenerating $src/tests/golden with g++ -O3"
  if ! { cmake -S "$src" -B "$dir" -G Ninja -DCMAKE_CXX_COMPILER=g++ -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" \
           -DTANDEM_WERROR=OFF -DTANDEM_BUILD_TOOLS=OFF -DTANDEM_BUILD_BENCH=OFF &&
         cmake --build "$dir" -j "$jobs" --target tandem_tests_golden tandem_tests_fixed &&
         TANDEM_GOLDEN_REGENERATE=1 TANDEM_GOLDEN_DIR="$root/$src/tests/golden" \
           "$dir/tests/tandem_tests_golden" 'golden chain: *'; } >build/matrix/regenerate.log 2>&1; then
    echo "matrix.sh: regenerating the golden files failed; see build/matrix/regenerate.log" >&2
    tail -30 build/matrix/regenerate.log >&2
    exit 1
  fi
fi

for r in "${selected[@]}"; do
  name=$(field "$r" 1)
  scope=$(field "$r" 6)
  dir=build/matrix/$name
  log=$dir.log
  result=pass
  t_build=0 t_test=0
  echo "[matrix] ==== $name: $(field "$r" 2), $(field "$r" 3), $(field "$r" 4)  ($(date +%H:%M:%S))"
  t0=$(now)
  read -r -a args <<<"$(field "$r" 5)"
  if ! cmake -S "$src" -B "$dir" -G Ninja "${args[@]}" "${launcher[@]}" -DTANDEM_WERROR=OFF \
      -DTANDEM_BUILD_TOOLS=OFF -DTANDEM_BUILD_BENCH=OFF >"$log" 2>&1; then
    result="configure FAILED"
  elif ! cmake --build "$dir" -j "$jobs" --target tandem_tests_golden tandem_tests_fixed >>"$log" 2>&1; then
    result="build FAILED"
  fi
  t_build=$(( $(now) - t0 ))
  if [ "$result" = pass ]; then
    t0=$(now)
    if [ "$scope" = full ]; then
      regex='^golden/|^fixed/fixed_math gives the same bits'
    else
      regex='^golden/golden chain: [a-z_0-9]+$|^golden/golden: |^fixed/fixed_math gives the same bits'
    fi
    if ! ctest --test-dir "$dir" -j "$jobs" --output-on-failure --no-tests=error -R "$regex" >>"$log" 2>&1; then
      result="tests FAILED"
    fi
    t_test=$(( $(now) - t0 ))
    counts=$(grep -E '^[0-9]+% tests passed' "$log" | tail -1 | sed -E 's/.* ([0-9]+) tests? failed out of ([0-9]+)/\1 of \2 failed/')
    [ -n "$counts" ] && result="$result ($counts)"
  fi
  [ "${result#pass}" = "$result" ] && { failed=$(( failed + 1 )); echo "[matrix] $name: $result; log $log"; tail -30 "$log"; }
  echo "[matrix] $name: $result, build ${t_build} s, test ${t_test} s"
  results+=("$name|$(field "$r" 2)|$(field "$r" 3)|$(field "$r" 4)|$result|$t_build|$t_test")
done

table=build/matrix/matrix-table.md
{
  echo "| row | target | compiler | flags | result | build s | test s |"
  echo "| --- | --- | --- | --- | --- | ---: | ---: |"
  for x in "${results[@]}"; do
    IFS='|' read -r a b c d e f g <<<"$x"
    echo "| $a | $b | $c | \`$d\` | $e | $f | $g |"
  done
  echo
  echo "$(date -u '+%Y-%m-%d %H:%M') UTC on $(nproc) cores ($(uname -m)), --jobs $jobs; sources: commit $(git rev-parse --short HEAD 2>/dev/null || echo '?') plus working-tree changes, snapshot content id $snapshot_id$([ $regenerate -eq 1 ] && echo '; golden files regenerated by g++ -O3 first (--regenerate)')."
} >"$table"
echo
printf '%-16s %-28s %-28s %-20s %-22s %7s %6s\n' row target compiler flags result build test
for x in "${results[@]}"; do
  IFS='|' read -r a b c d e f g <<<"$x"
  printf '%-16s %-28s %-28s %-20s %-22s %7s %6s\n' "$a" "$b" "$c" "$d" "$e" "$f" "$g"
done
echo
echo "[matrix] table written to $root/$table"
echo "$(( ${#results[@]} - failed )) passed, $failed failed"
[ $failed -eq 0 ]
