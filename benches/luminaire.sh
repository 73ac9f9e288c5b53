#!/usr/bin/env bash
# Photon throughput of `invlight measure` with a photometric light against a point light
# on the same scene: tests/data/ilp/lamp-room.gltf (a 6 × 4 × 2.5 m room with a desk and
# one point lamp), and the same room with the lamp node turned into the batwing office
# luminaire of tests/data/photometry/batwing.ies (glTF EXT_lights_ies, aimed down). Runs
# each `rounds` times, alternating, on one thread, arrivals only (the photon loop) and
# with connections to the desk (which evaluate the table's density toward every point
# they draw), and prints photons/s and rays/s of the trace alone (BVH build excluded).
# Usage: benches/luminaire.sh [photons] [rounds]   (from the repository root)
set -euo pipefail
N=${1:-2000000}
ROUNDS=${2:-3}
cargo build --release -q
BIN=${CARGO_TARGET_DIR:-target}/release/invlight
DIR=$(mktemp -d)
trap 'rm -rf "$DIR"' EXIT
cp tests/data/photometry/batwing.ies "$DIR/"
python3 - "$DIR" <<'PY'
import json, math, sys
d = json.load(open("tests/data/ilp/lamp-room.gltf"))
d["extensionsUsed"] = ["EXT_lights_ies"]
del d["extensions"]["KHR_lights_punctual"]
d["extensions"]["EXT_lights_ies"] = {"lights": [{"uri": "batwing.ies"}]}
for n in d["nodes"]:
    if n.get("name") == "Lamp":
        s = math.sin(math.radians(-45.0))
        n["rotation"] = [s, 0.0, 0.0, math.cos(math.radians(-45.0))]
        n["extensions"] = {"EXT_lights_ies": {"light": 0}}
json.dump(d, open(sys.argv[1] + "/luminaire-room.gltf", "w"))
PY
REPORT='
import json, sys
r = json.load(sys.stdin)
t = r["seconds"] - r["build_seconds"]
p, n = r["photons"], r["rays"] + r.get("connection_rays", 0)
print("%-12s %-10s %6.3f M photons/s, %6.3f M rays/s (connections included), %.2f rays/photon, %.2f s"
      % (sys.argv[1], sys.argv[2], p / t / 1e6, n / t / 1e6, n / p, t))
'
grep -m1 'model name' /proc/cpuinfo
for round in $(seq "$ROUNDS"); do
  for mode in --arrivals-only ""; do
    for light in point luminaire; do
      scene=tests/data/ilp/lamp-room.gltf
      [ "$light" = luminaire ] && scene="$DIR/luminaire-room.gltf"
      json=$("$BIN" measure "$scene" --surface Desk --photons "$N" --seed 1 --threads 1 $mode --json)
      python3 -c "$REPORT" "$light" "${mode:---connect}" <<<"$json"
    done
  done
done
