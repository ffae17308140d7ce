#!/usr/bin/env bash
# layering-lint.sh — fails when replay/ reaches into physics' internals.
# replay/ may include the installed public physics headers (the PUBLIC_HEADERS
# of physics in the top-level CMakeLists.txt) and one internal header,
# physics/state_access.h, the interface through which physics lends its
# state; and state_access.h itself may include only public headers (else the
# door would let the internals through). Every other `#include "physics/..."`
# in replay/ is a finding; no file is exempt (the compact rollback image,
# once the last one, now reaches its records through state_access.h too:
# physics/state_compact*.cpp write and read them).
#
# Usage: layering-lint.sh [REPO_ROOT]   lint REPO_ROOT (default: this repo)
#        layering-lint.sh --self-test   check the lint on planted violations
# Prints one line per finding, "file:line: reason: include", then a count;
# exit 1 when anything was found.
set -euo pipefail

readonly k_state_interface="state_access.h"

# public_headers ROOT: the physics PUBLIC_HEADERS of ROOT/CMakeLists.txt, one a line.
public_headers() {
  awk '
    /tandem_add_module\(physics/ { on = 1 }
    on {
      line = $0
      sub(/.*PUBLIC_HEADERS/, "", line)
      if ($0 ~ /PUBLIC_HEADERS/) take = 1
      if (take) {
        gsub(/\)/, " ", line)
        n = split(line, w, /[ \t]+/)
        for (i = 1; i <= n; i++) if (w[i] ~ /\.h$/) print w[i]
      }
      if ($0 ~ /\)/) { on = 0; take = 0 }
    }' "$1/CMakeLists.txt"
}

# lint ROOT: prints findings, returns their count through the exit status.
lint() {
  local root=$1 found=0 file line header rel
  local -A public=()
  while read -r header; do public[$header]=1; done < <(public_headers "$root")
  if [[ ${#public[@]} -eq 0 ]]; then
    echo "$root/CMakeLists.txt: cannot read the physics PUBLIC_HEADERS list"
    return 1
  fi
  shopt -s nullglob
  for file in "$root"/replay/*.h "$root"/replay/*.cpp "$root/physics/$k_state_interface"; do
    rel=${file#"$root"/}
    while IFS=: read -r line header; do
      header=${header#*\"physics/}
      header=${header%%\"*}
      if [[ -n ${public[$header]:-} ]]; then continue; fi
      if [[ $header == "$k_state_interface" && $rel == replay/* ]]; then continue; fi
      echo "$rel:$line: internal physics header: physics/$header"
      found=$((found + 1))
    done < <(grep -n '^[[:space:]]*#[[:space:]]*include[[:space:]]*"physics/' "$file" || true)
  done
  echo "$found finding(s)"
  [[ $found -eq 0 ]]
}

self_test() {
  local dir
  dir=$(mktemp -d)
  trap 'rm -rf "$dir"' RETURN
  mkdir -p "$dir/replay" "$dir/physics"
  printf 'tandem_add_module(physics DEPS fixed\n  PUBLIC_HEADERS tandem.h ids.h)\n' > "$dir/CMakeLists.txt"
  printf '#include "physics/ids.h"\n' > "$dir/physics/$k_state_interface"
  printf '#include "physics/tandem.h"\n#include "physics/state_access.h"\n' > "$dir/replay/good.cpp"
  if ! lint "$dir" > /dev/null; then
    echo "self-test: clean tree refused"
    lint "$dir" || true
    return 1
  fi
  printf '#pragma once\n  #include "physics/world.h"\n' > "$dir/replay/bad.h"
  printf '#include "physics/body.h"\n' >> "$dir/physics/$k_state_interface"
  local out
  out=$(lint "$dir" || true)
  if [[ $out != *"replay/bad.h:2: internal physics header: physics/world.h"* ||
        $out != *"physics/$k_state_interface:2: internal physics header: physics/body.h"* ||
        $out != *"2 finding(s)"* ]]; then
    echo "self-test: planted violations not found as expected:"
    echo "$out"
    return 1
  fi
  rm "$dir/replay/bad.h"
  sed -i '2d' "$dir/physics/$k_state_interface"
  if ! lint "$dir" > /dev/null; then
    echo "self-test: the tree with the violations removed was refused"
    return 1
  fi
  echo "self-test passed"
}

if [[ ${1:-} == --self-test ]]; then
  self_test
else
  lint "${1:-$(cd "$(dirname "$0")/.." && pwd)}"
fi
