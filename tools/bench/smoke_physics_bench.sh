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
