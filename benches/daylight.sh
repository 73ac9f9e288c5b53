#!/usr/bin/env bash
# A daylight-factor measurement against a direct-sun one on the same scene with the same
# photons: examples/office-daylight/scene.gltf (the office with its 1 m skylight as
# authored, centred at (0.5, 2.8, 0.5)), the desk and the floor, `measure
# --daylight-factor` under the CIE overcast sky of 10 000 lx (photons from the whole
# dome, most of them stopped by the roof) against `--site/--sun` (Montevideo's December
# solstice noon: one parallel beam). Runs each `rounds` times, alternating, on one
# thread, and prints photons/s and rays/s of the trace alone (BVH build excluded).
# Usage: benches/daylight.sh [photons] [rounds]   (from the repository root)
set -euo pipefail
N=${1:-2000000}
ROUNDS=${2:-3}
cargo build --release -q
BIN=${CARGO_TARGET_DIR:-target}/release/invlight
SCENE=examples/office-daylight/scene.gltf
REPORT='
import json, sys
r = json.load(sys.stdin)
t = r["seconds"] - r["build_seconds"]
p, n = r["photons"], r["rays"] + r.get("connection_rays", 0)
desk = r["surfaces"][0]
print("%-15s %6.3f M photons/s, %6.3f M rays/s (connections included), %.2f rays/photon, %.2f s; desk %.4g ± %.2g lx"
      % (sys.argv[1], p / t / 1e6, n / t / 1e6, n / p, t, desk["mean"], desk["std_error"]))
'
grep -m1 'model name' /proc/cpuinfo
for round in $(seq "$ROUNDS"); do
  for light in daylight-factor sun; do
    if [ "$light" = sun ]; then
      flags=(--site=-34.9,-56.2,-3 --sun 2025-12-21,12:00)
    else
      flags=(--sky cie-overcast:10000 --daylight-factor)
    fi
    json=$("$BIN" measure "$SCENE" -s Desk -s Floor --side front --photons "$N" --seed 1 \
      --threads 1 "${flags[@]}" --json)
    python3 -c "$REPORT" "$light" <<<"$json"
  done
done
