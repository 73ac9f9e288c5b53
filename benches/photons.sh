#!/usr/bin/env bash
# Photon-tracing throughput of `invlight measure` on the thesis' Cornell box (8 212
# triangles) and on the Sponza atrium of examples/atrium-skylight (66 k triangles, two
# point lights and a sun), on 1 and 2 threads. Prints one line per run: photons/s and
# rays/s of the trace alone (`seconds` − `build_seconds` of the JSON: scene loading and
# the BVH build are not counted). It measures the photon loop itself, so it counts
# arrivals only (`--arrivals-only`: no shadow rays toward the target); what connections
# cost and gain is benches/estimators.sh's part.
# Usage: benches/photons.sh [photons]   (from the repository root; builds release first)
set -euo pipefail
N=${1:-2000000}
cargo build --release -q
BIN=${CARGO_TARGET_DIR:-target}/release/invlight
run() {
  local scene=$1 surface=$2 threads=$3
  local json
  json=$(/usr/bin/time -f "%U %S" -o /tmp/invlight-bench-cpu "$BIN" measure "$scene" \
      --surface "$surface" --photons "$N" --seed 1 --threads "$threads" --arrivals-only --json)
  python3 -c "$REPORT" "$scene" "$threads" "$(cat /tmp/invlight-bench-cpu)" <<<"$json"
}
# Wall rates of the trace alone, and rays per CPU-second of the whole process (user +
# system time, loading and BVH build included): on a shared machine the second is the
# steadier figure of the code's speed.
REPORT='
import json, sys
r = json.load(sys.stdin)
t = r["seconds"] - r["build_seconds"]
p, n = r["photons"], r["rays"]
cpu = sum(map(float, sys.argv[3].split())) if sys.argv[3].strip() else float("nan")
print("%-36s %s thread(s): %6.3f M photons/s, %6.3f M rays/s wall; %6.3f M rays per CPU-s; %.2f rays/photon, %.2f s"
      % (sys.argv[1], sys.argv[2], p / t / 1e6, n / t / 1e6, n / cpu / 1e6, n / p, t))
'
grep -m1 'model name' /proc/cpuinfo
for scene in "tests/data/collada/cornell.dae Cone" "examples/atrium-skylight/scene.gltf Jar"; do
  set -- $scene
  for t in 1 2; do run "$1" "$2" "$t"; done
done
