#!/usr/bin/env bash
# serve-web.sh — builds the web test page (preset emscripten: tools/web, the
# engine in WebAssembly) when needed and serves it on localhost with
# Python's standard http.server, bound to 127.0.0.1 only; prints the URL.
#
# Usage: scripts/serve-web.sh [PORT]   (default 8080; Ctrl-C stops it)
# Needs Debian's emscripten package (scripts/setup-deps.sh web) and python3.
set -euo pipefail
cd "$(dirname "$0")/.."
port=${1:-8080}
case "$port" in
  ''|*[!0-9]*) echo "serve-web.sh: PORT must be a number, got '$port'" >&2; exit 2 ;;
esac
if [ ! -f build/emscripten/CMakeCache.txt ]; then
  cmake --preset emscripten >/dev/null
fi
cmake --build build/emscripten --target tandem_web
dir=build/emscripten/web
echo "Tandem web test page: http://127.0.0.1:${port}/  (serving ${dir}; Ctrl-C stops)"
exec python3 -m http.server "$port" --bind 127.0.0.1 --directory "$dir"
