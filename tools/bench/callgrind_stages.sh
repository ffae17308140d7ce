#!/usr/bin/env bash
# callgrind_stages.sh — instructions per step per stage of a benchmark scene,
# counted by Debian's valgrind (callgrind), so a change to the narrow phase or
# the solver is judged on counts, not on a noisy clock.
#
# Usage: tools/bench/callgrind_stages.sh [SCENE] [--ticks N] [--warmup W]
#            [--broadphase NAME] [--sleep on|off|scene] [--build-dir DIR] [--exe FILE]
#            [--keep FILE]
#   SCENE        pyramid-100 (default: 5,050 boxes on a ground box), circles-16k,
#                rain-4000, or any scenes.h name
#   --ticks N    steps collected (default 30)
#   --warmup W   steps run first, not collected (default 0)
#   --broadphase naive|sap|grid|tree (default grid)
#   --sleep      scene (default: as the scene says, on for smash only), on or
#                off (every body awake, sleeping off)
#   --build-dir  a configured build tree (default build/gcc-release; built
#                here: target tandem_profile_stages)
#   --exe FILE   profile this tandem_profile_stages binary as it is (no build;
#                a saved copy of a baseline build, for before/after counts)
#   --keep FILE  also keep the callgrind output file there
#
# Only tandem_profile_timed_steps() is collected (--toggle-collect): the
# scene is built and warmed up outside the count. Stages are callgrind's
# INCLUSIVE counts of these functions (callgrind_annotate --inclusive=yes):
#   narrow phase   update_contacts − broad_phase_update_pairs (pair merge,
#                  manifolds, warm-start matching)
#     of it collide()  the manifold functions alone (tandem::collide)
#   prepare        prepare_contact_constraints (colouring, per-point constants)
#   warm start     warm_start_contacts
#   solve+relax    solve_contacts + relax_contacts
#   integrate      stage_integrate_velocities + stage_integrate_positions
#   broad phase    broad_phase_update_pairs + compute_body_shape_bounds (the shapes' bounds after the step)
#   islands        stage_wake_touched + stage_update_sleep
#   events         events_after_contacts + events_after_step
#   approach       record_contact_approach (per sub-step)
#   other          the rest of world_step (store, continuous, finalize) and
#                  the step loop
# Per contact = per touching pair (a contact with ≥ 1 manifold point), the
# mean over the collected steps as world_broad_phase_stats reports it.
set -euo pipefail

scene=pyramid-100
ticks=30
warmup=0
broadphase=grid
sleep=scene
build_dir=build/gcc-release
keep=""
exe=""
while [[ $# -gt 0 ]]; do
  case "$1" in
    --ticks) ticks=$2; shift 2 ;;
    --warmup) warmup=$2; shift 2 ;;
    --broadphase) broadphase=$2; shift 2 ;;
    --sleep) sleep=$2; shift 2 ;;
    --build-dir) build_dir=$2; shift 2 ;;
    --keep) keep=$2; shift 2 ;;
    --exe) exe=$2; shift 2 ;;
    -h|--help) sed -n '2,39p' "$0"; exit 0 ;;
    -*) echo "callgrind_stages.sh: unknown option $1" >&2; exit 2 ;;
    *) scene=$1; shift ;;
  esac
done
command -v valgrind >/dev/null || { echo "callgrind_stages.sh: valgrind not found (scripts/setup-deps.sh installs it)" >&2; exit 2; }
if [[ -z "$exe" ]]; then
  [[ -f "$build_dir/CMakeCache.txt" ]] || { echo "callgrind_stages.sh: $build_dir is not a configured build tree (cmake --preset gcc-release)" >&2; exit 2; }
  cmake --build "$build_dir" --target tandem_profile_stages >/dev/null
  exe=$(find "$build_dir" -name tandem_profile_stages -type f -perm -u+x | head -n 1)
fi
[[ -n "$exe" ]] || { echo "callgrind_stages.sh: tandem_profile_stages was not built" >&2; exit 2; }

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
out="$tmp/callgrind.out"
valgrind --tool=callgrind --callgrind-out-file="$out" --collect-atstart=no \
  --toggle-collect=tandem_profile_timed_steps "$exe" "$scene" --ticks "$ticks" --warmup "$warmup" \
  --broadphase "$broadphase" --sleep "$sleep" >"$tmp/stdout" 2>"$tmp/stderr" || { cat "$tmp/stderr" >&2; exit 1; }
[[ -n "$keep" ]] && cp "$out" "$keep"
info=$(cat "$tmp/stdout")
touching=$(sed -n 's/.*touching_pairs_per_step \([0-9.]*\).*/\1/p' <<<"$info")
pairs=$(sed -n 's/.* pairs_per_step \([0-9.]*\).*/\1/p' <<<"$info")
callgrind_annotate --inclusive=yes --threshold=100 "$out" >"$tmp/annotate" 2>/dev/null

# inclusive count of the function whose demangled name starts with $1 ("tandem::foo(")
incl() {
  awk -v name="$1" '
    { line = $0; gsub(/,/, "", $1); }
    index(line, name) > 0 && $1 ~ /^[0-9]+$/ { n = $1 + 0; if (n > best) best = n }
    END { printf "%.0f\n", best + 0 }' "$tmp/annotate"
}
total=$(incl 'tandem_profile_timed_steps')
update=$(incl 'tandem::update_contacts(')
collide=$(incl 'tandem::collide(')
bp_pairs=$(incl 'tandem::broad_phase_update_pairs(')
bounds=$(incl 'tandem::compute_body_shape_bounds(')
prepare=$(incl 'tandem::prepare_contact_constraints(')
warm=$(incl 'tandem::warm_start_contacts(')
solve=$(incl 'tandem::solve_contacts(')
relax=$(incl 'tandem::relax_contacts(')
intv=$(incl 'tandem::stage_integrate_velocities(')
intp=$(incl 'tandem::stage_integrate_positions(')
wake=$(incl 'tandem::stage_wake_touched(')
sleepst=$(incl 'tandem::stage_update_sleep(')
ev1=$(incl 'tandem::events_after_contacts(')
ev2=$(incl 'tandem::events_after_step(')
appr=$(incl 'tandem::record_contact_approach(')
sleepinfo=$(sed -n 's/.* sleep \([a-z]*\) .*/\1/p' <<<"$info")

awk -v scene="$scene" -v ticks="$ticks" -v warmup="$warmup" -v bp="$broadphase" -v pairs="$pairs" \
    -v touching="$touching" -v total="$total" -v update="$update" -v bpp="$bp_pairs" -v bounds="$bounds" \
    -v prepare="$prepare" -v warm="$warm" -v solve="$solve" -v relax="$relax" -v intv="$intv" -v intp="$intp" -v collide="$collide" \
    -v islands="$((wake + sleepst))" -v events="$((ev1 + ev2))" -v appr="$appr" -v sleepinfo="$sleepinfo" '
  function row(name, n) {
    printf "| %-16s | %12.2f M | %9.0f | %5.1f %% |\n", name, n / ticks / 1e6, (touching > 0 ? n / ticks / touching : 0), (total > 0 ? 100 * n / total : 0)
  }
  BEGIN {
    narrow = update - bpp; broad = bpp + bounds; sr = solve + relax; integ = intv + intp
    other = total - narrow - prepare - warm - sr - integ - broad - islands - events - appr
    printf "%s, %d ticks after %d warm-up, broad phase %s, sleep %s: %.1f pairs, %.1f touching pairs (contacts) per step\n\n", scene, ticks, warmup, bp, sleepinfo, pairs, touching
    printf "| stage        | instr / step   | / contact | share   |\n|---|--:|--:|--:|\n"
    row("narrow phase", narrow); row(" of it collide()", collide); row("prepare", prepare); row("warm start", warm); row("solve+relax", sr)
    row("integrate", integ); row("broad phase", broad); row("islands", islands); row("events", events)
    row("approach", appr); row("other", other); row("whole step", total)
  }'
