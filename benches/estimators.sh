#!/usr/bin/env bash
# The two estimators of `invlight measure` side by side on the examples' targets and the
# Mitsuba comparison's room: arrivals alone (--arrivals-only, the thesis) against arrivals
# weighted with connections to the target (the default). Efficiency = 1 / (relative
# standard error² × wall seconds of the whole process), higher is better; the last
# column is the ratio connected / arrivals.
# Usage: benches/estimators.sh [photons]   (from the repository root; builds release first)
set -euo pipefail
N=${1:-1000000}
cargo build --release -q
BIN=${CARGO_TARGET_DIR:-target}/release/invlight
run() {
  local scene=$1 surface=$2 a b
  a=$(one "$scene" "$surface" --arrivals-only)
  b=$(one "$scene" "$surface")
  python3 -c "$REPORT" "$scene" "$surface" "$a" "$b"
}
one() {
  local scene=$1 surface=$2 start end json
  shift 2
  start=$(date +%s.%N)
  json=$("$BIN" measure "$scene" --surface "$surface" --photons "$N" --seed 1 --json "$@")
  end=$(date +%s.%N)
  python3 -c 'import json, sys; print(json.dumps([json.loads(sys.argv[1]), float(sys.argv[3]) - float(sys.argv[2])]))' \
    "$json" "$start" "$end"
}
REPORT='
import json, sys
def row(arg):
    r, t = json.loads(arg)
    s = r["surfaces"][0]
    rel = s["std_error"] / s["mean"]
    return s["mean"], s["std_error"], rel, t, 1 / (rel * rel * t)
a, b = row(sys.argv[3]), row(sys.argv[4])
print("%-40s %-10s | arrivals %9.4g ± %-8.3g (%6.3f %%) %5.2f s | connected %9.4g ± %-8.3g (%6.3f %%) %5.2f s | efficiency × %.1f"
      % (sys.argv[1], sys.argv[2], a[0], a[1], 100 * a[2], a[3], b[0], b[1], 100 * b[2], b[3], b[4] / a[4]))
'
grep -m1 'model name' /proc/cpuinfo
run tests/data/gltf/room_area.gltf Floor
run examples/cornell-cone/cornell.dae Cone
run examples/atrium-skylight/scene.gltf Jar
run examples/conference-sun/scene.gltf Blackboard
run examples/atrium-colour/scene.gltf Floor
