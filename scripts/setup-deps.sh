#!/usr/bin/env bash
# setup-deps.sh — installs the Debian 12 packages Tandem needs, and only the
# missing ones. A fresh machine is assumed to have build-essential, cmake,
# clang and git; everything else comes from here.
#
# Usage: scripts/setup-deps.sh [all|demo|ci-cross|matrix]
#   all      (default) everything scripts/test.sh needs: the libraries,
#            Catch2, Python 3 and Mono (binding tests), the i686 and s390x
#            cross compilers, qemu-user, pkg-config, plus the ci-cross group
#   demo     only what building and running `tandem demo` needs
#   ci-cross the extra cross rows scripts/test.sh runs (aarch64 under qemu,
#            wasm32-wasi under node), plus the web group
#   web      the web test page (tools/web): Emscripten, Chromium, and
#            playwright-core from npm (tools/web/package-lock.json; no browser
#            download: the tests drive Debian's /usr/bin/chromium)
#   matrix   everything tools/matrix.sh needs: all of the above plus the
#            armhf, riscv64 and ppc64le cross compilers and mingw-w64 +
#            wine for Windows (not in `all`)
#
# Checks each package with dpkg-query; runs `apt-get update` and one
# non-interactive `apt-get install` only when something is missing. Works as
# root, or through sudo when not root. Exit status non-zero if an install fails.
set -euo pipefail

group=${1:-all}

# Toolchain basics (on a fresh machine already; checked so a bare one also works).
base=(build-essential cmake clang git ninja-build pkg-config)
# Libraries the library, the command line and its demo use.
libs=(catch2 libcli11-dev nlohmann-json3-dev libxxhash-dev libcairo2-dev libenet-dev)
# The C API's binding tests (capi/tests): Python runs bindings/python (ctypes,
# standard library only), mcs + mono compile and run bindings/csharp.
bindings=(python3 mono-mcs mono-runtime)
# Only for scripts/test.sh: cross builds and tools/bench.
extra=(g++-i686-linux-gnu g++-s390x-linux-gnu qemu-user valgrind libbenchmark-dev libfixmath-dev libbox2d-dev
  libchipmunk-dev libclang-rt-14-dev)  # libclang-rt-14-dev: libFuzzer and the sanitizer runtimes (scripts/fuzz.sh)
# Cross rows of scripts/test.sh beyond i686/s390x (golden chains only).
ci_cross=(g++-aarch64-linux-gnu wasi-libc libc++-14-dev-wasm32 libc++abi-14-dev-wasm32
  libclang-rt-14-dev-wasm32 lld-14 llvm-14 nodejs)
# The web row of scripts/test.sh (tools/web): Debian's emscripten (3.1.6, with
# its prebuilt system libraries) and chromium, and npm for playwright-core
# when node came without it (Debian's nodejs 18 does; nodesource's bundles npm).
web=(emscripten chromium)
command -v npm >/dev/null 2>&1 || web+=(npm)
# The rest of tools/matrix.sh's targets (big; not installed by `all`).
# (Windows under wine is here rather than in CI: its build is the slowest row.)
matrix=(g++-arm-linux-gnueabihf g++-riscv64-linux-gnu g++-powerpc64le-linux-gnu g++-mingw-w64-x86-64 wine64)

case "$group" in
  all) wanted=("${base[@]}" "${libs[@]}" "${bindings[@]}" "${extra[@]}" "${ci_cross[@]}" "${web[@]}") ;;
  demo) wanted=("${base[@]}" "${libs[@]}") ;;
  ci-cross) wanted=("${ci_cross[@]}" "${web[@]}") ;;
  web) wanted=("${web[@]}") ;;
  matrix) wanted=("${base[@]}" "${libs[@]}" "${bindings[@]}" "${extra[@]}" "${ci_cross[@]}" "${web[@]}" "${matrix[@]}") ;;
  *) echo "usage: $0 [all|demo|ci-cross|web|matrix]" >&2; exit 2 ;;
esac

# playwright-core (the web tests' browser driver) from npm, exactly as
# tools/web/package-lock.json pins it; never a browser download.
web_node_modules() {
  case "$group" in demo) return 0 ;; esac
  local dir
  dir="$(cd "$(dirname "$0")/.." && pwd)/tools/web"
  [ -f "$dir/package-lock.json" ] || return 0
  local want have
  want=$(node -e 'console.log(require(process.argv[1]).packages["node_modules/playwright-core"].version)' \
    "$dir/package-lock.json" 2>/dev/null || true)
  have=$(node -e 'console.log(require(process.argv[1]).version)' \
    "$dir/node_modules/playwright-core/package.json" 2>/dev/null || true)
  if [ -n "$want" ] && [ "$want" = "$have" ]; then
    return 0
  fi
  echo "setup-deps: npm ci in tools/web (playwright-core)"
  if ! (cd "$dir" && PLAYWRIGHT_SKIP_BROWSER_DOWNLOAD=1 npm ci --no-audit --no-fund --ignore-scripts); then
    # Everything else is installed; only the web page's browser tests need
    # this, and scripts/test.sh says loudly that it skipped them.
    echo "setup-deps: WARNING: npm could not install playwright-core (is npm's registry reachable?);" \
      "the web page's browser tests will be skipped" >&2
  fi
}

missing=()
for pkg in "${wanted[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null || true)
  [ "$status" = "install ok installed" ] || missing+=("$pkg")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup-deps: all ${#wanted[@]} packages present ($group)"
  web_node_modules
  exit 0
fi

if [ "$(id -u)" -eq 0 ]; then
  as_root=()
elif command -v sudo >/dev/null 2>&1; then
  as_root=(sudo -n)
  sudo -n true 2>/dev/null || as_root=(sudo)  # may ask for a password on a terminal
else
  echo "setup-deps: missing ${missing[*]}, and not root with no sudo; install them as root:" >&2
  echo "  apt-get install -y ${missing[*]}" >&2
  exit 1
fi

echo "setup-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${as_root[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update -q
"${as_root[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends \
  -o Dpkg::Options::=--force-confdef -o Dpkg::Options::=--force-confold "${missing[@]}"
web_node_modules
echo "setup-deps: done"
