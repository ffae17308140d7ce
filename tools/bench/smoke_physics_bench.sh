#!/usr/bin/env bash
# smoke_physics_bench.sh — ctest smoke test of tandem_bench_physics (no
# timings are checked): runs tiny scenes for a few steps with every broad
# phase and the peers, then checks that the driver succeeded (so every broad
# phase ended each scene in the same state), that the CSV has one row per
# scene × engine, that the JSON parses with the same rows, and that the SVG
# is well-formed XML with one polyline per engine.
#
# Usage: smoke_physics_bench.sh PATH/TO/tandem_bench_physics [OUT_DIR]
set -euo pipefail
bin="$1"
out="${2:-$(mktemp -d)}"
mkdir -p "$out"
"$bin" circles-200 circles-400 pyramid-6 rain-90 --runs 2 --steps 10 --warmup 2 -q \
  --csv "$out/smoke.csv" --json "$out/smoke.json" --svg "$out/smoke.svg" >"$out/smoke.txt"
python3 - "$out" <<'PY'
import csv, json, sys, xml.dom.minidom
out = sys.argv[1]
scenes = ["circles-200", "circles-400", "pyramid-6", "rain-90"]
rows = list(csv.DictReader(open(f"{out}/smoke.csv")))
engines = sorted({(r["engine"], r["broad_phase"]) for r in rows})
assert len(engines) >= 3, f"expected Tandem broad phases and peers, got {engines}"
assert len(rows) == len(scenes) * len(engines), f"{len(rows)} CSV rows for {len(scenes)} scenes x {len(engines)} engines"
for r in rows:
    assert r["status"] == "ok", f"{r['scene']} {r['engine']}/{r['broad_phase']}: {r['status']}"
    assert float(r["median_ms"]) > 0 and len(r["run_ms"].split()) == 2, r
    assert int(r["escaped"]) == 0, f"{r['scene']} {r['engine']}: {r['escaped']} bodies escaped"
data = json.load(open(f"{out}/smoke.json"))
assert len(data["results"]) == len(rows) and data["warnings"] == [], data["warnings"]
for r in data["results"]:  # Tandem rows carry the per-stage profile (world_profile), peers none
    if r["engine"] == "tandem":
        p = r["profile"]
        assert p["total"]["median_ms"] > 0 and all(v["median_ms"] >= 0 for v in p.values()), p
        assert sum(v["mean_ms"] for k, v in p.items() if k != "total") <= p["total"]["mean_ms"] * 1.000001, p
    else:
        assert "profile" not in r, r
svg = xml.dom.minidom.parse(f"{out}/smoke.svg")
lines = svg.getElementsByTagName("polyline")
assert len(lines) == len(engines), f"{len(lines)} polylines for {len(engines)} engines"
print(f"smoke ok: {len(rows)} rows, {len(engines)} engines")
PY

# The ray-cast benchmark: every Tandem broad phase and Box2D 2.4 report rays/s,
# and the Tandem broad phases agree on every hit (the driver exits 1 if not).
"$bin" rain-90 --rays 300 --runs 2 --warmup 30 -q --csv "$out/rays.csv" >"$out/rays.txt"
python3 - "$out" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(f"{sys.argv[1]}/rays.csv")))
engines = sorted((r["engine"], r["broad_phase"]) for r in rows)
assert ("box2d24", "") in engines and len([e for e in engines if e[0] == "tandem"]) == 4, engines
for r in rows:
    assert float(r["median_rays_per_s"]) > 0 and int(r["batches"]) == 2 and int(r["rays"]) == 300, r
tandem_hits = {r["hits"] for r in rows if r["engine"] == "tandem"}
assert len(tandem_hits) == 1 and int(tandem_hits.pop()) > 0, rows
print(f"ray smoke ok: {len(rows)} engines")
PY
