#!/usr/bin/env bash
# benches/photons.sh's runs for two builds of invlight, alternately, ROUNDS times: on a
# shared machine the load drifts within minutes, and alternating spreads the drift over
# both. Prints the raw CSV, then the mean ± sd of each build, scene and thread count.
# Usage: benches/photons_ab.sh BEFORE AFTER [photons] [rounds]
#   BEFORE, AFTER: paths of two `invlight` binaries (from the repository root).
set -euo pipefail
[ $# -ge 2 ] || { sed -n 2,6p "$0"; exit 2; }
BEFORE=$1 AFTER=$2 N=${3:-2000000} ROUNDS=${4:-5}
CSV=$(mktemp)
ROW='
import json, sys
r = json.load(sys.stdin)
t = r["seconds"] - r["build_seconds"]
cpu = sum(map(float, sys.argv[5].split()))
print("%s,%s,%s,%s,%.4f,%.4f,%.4f,%.4f" % (*sys.argv[1:5], r["photons"] / t / 1e6,
      r["rays"] / t / 1e6, r["rays"] / cpu / 1e6, t))
'
echo "build,scene,threads,round,Mphotons_per_s_wall,Mrays_per_s_wall,Mrays_per_cpu_s,trace_s" >"$CSV"
for round in $(seq 1 "$ROUNDS"); do
  for scene in "tests/data/collada/cornell.dae Cone" "examples/atrium-skylight/scene.gltf Jar"; do
    set -- $scene
    for threads in 1 2; do
      for build in before after; do
        bin=$BEFORE; [ $build = after ] && bin=$AFTER
        json=$(/usr/bin/time -f "%U %S" -o /tmp/invlight-ab-cpu "$bin" measure "$1" --surface "$2" \
            --photons "$N" --seed 1 --threads "$threads" --arrivals-only --json)
        python3 -c "$ROW" $build "$1" "$threads" "$round" "$(cat /tmp/invlight-ab-cpu)" <<<"$json" >>"$CSV"
      done
    done
  done
done
cat "$CSV"
python3 - "$CSV" <<'EOF'
import csv, sys, statistics as st
rows = list(csv.DictReader(open(sys.argv[1])))
keys = sorted({(r["scene"], r["threads"], r["build"]) for r in rows}, key=lambda k: (k[0], k[1], k[2] != "before"))
print("\n%-36s %s %-6s  %-22s %s" % ("scene", "threads", "build", "M photons/s (wall)", "M rays per CPU-s"))
for k in keys:
    g = [r for r in rows if (r["scene"], r["threads"], r["build"]) == k]
    f = lambda c: "%.3f ± %.3f" % (st.mean(float(r[c]) for r in g), st.stdev(float(r[c]) for r in g))
    print("%-36s %-7s %-6s  %-22s %s" % (*k, f("Mphotons_per_s_wall"), f("Mrays_per_cpu_s")))
EOF
rm -f "$CSV"
