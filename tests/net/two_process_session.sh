#!/usr/bin/env bash
# Two `tandem session` processes on 127.0.0.1 play 200 ticks in rollback mode
# with added latency and loss; both must exit 0 with the same final hash.
# Usage: two_process_session.sh TANDEM_EXECUTABLE
set -euo pipefail
tandem=$1
base=$((20000 + ($$ % 20000) * 2))
peers="127.0.0.1:$base,127.0.0.1:$((base + 1))"
common=(--peers "$peers" --ticks 200 --frame-us 8000 --latency 30 --jitter 10 --loss 5 --timeout 60 --connect-timeout 10000 --json)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
"$tandem" session --endpoint 1 "${common[@]}" >"$out/1.json" 2>"$out/1.err" &
pid=$!
rc0=0
"$tandem" session --endpoint 0 "${common[@]}" >"$out/0.json" 2>"$out/0.err" || rc0=$?
rc1=0
wait "$pid" || rc1=$?
cat "$out/0.err" "$out/1.err" >&2
[ "$rc0" -eq 0 ] && [ "$rc1" -eq 0 ] || { echo "exit codes $rc0 $rc1" >&2; cat "$out/0.json" "$out/1.json"; exit 1; }
h0=$(grep -o '"final_hash": "[^"]*"' "$out/0.json")
h1=$(grep -o '"final_hash": "[^"]*"' "$out/1.json")
echo "endpoint 0 $h0"
echo "endpoint 1 $h1"
[ -n "$h0" ] && [ "$h0" = "$h1" ] || { echo "final hashes differ" >&2; exit 1; }
echo "two processes in sync"
