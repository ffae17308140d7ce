#!/usr/bin/env bash
# demo.sh — the README's first command: installs what the demo needs (only
# the missing packages), builds the release preset's `tandem` command line in
# build/release, and runs `tandem demo`. Extra arguments go to the demo.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/setup-deps.sh demo
cmake --preset release
cmake --build build/release -j 2 --target tandem
exec build/release/tandem demo --out build/demo "$@"
