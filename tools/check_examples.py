#!/usr/bin/env python3
"""Runs every bundled example with a reduced budget and checks that its answer lands in
the region its README expects (CI runs it).

    python3 tools/check_examples.py [--bin PATH] [--only NAME] [--full] [--strategy S]

Python 3 standard library only. `--bin` is the invlight binary (default: `cargo run
--release --` from the repository); `--full` uses each problem file's own budget. The
run's files go to a temporary folder. `--strategy` solves with that strategy instead
of the problem file's (BENCHMARKS.md compares them this way). Exit status 0 when every
check passes.

The regions are the geometric arguments of the READMEs, with margins of about one cell:
the check is on the ISOC's best member, which the search returns first. office-target's
check also measures that member again with other photons (`invlight measure --config`)
and checks its constraints hold. Each example's report.html must be written and
reference nothing outside itself.
"""

import argparse
import json
import math
import os
import re
import subprocess
import sys
import tempfile
import time

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def cornell_cone(r):
    # The cone's centre (its anchor: result.json gives it beside the placement point P,
    # which is P + (authored centre − A) = P + (−0.752, +0.850)); the panel covers
    # x ∈ [−0.39, 0.86], y ∈ [0.93, 2.17]: under it, within 0.5 m.
    cx, cy, _ = r["variables"]["Cone"]["anchor"]
    return -0.89 <= cx <= 1.36 and 0.43 <= cy <= 2.67, "cone centre (%.2f, %.2f)" % (cx, cy)


def cornell_light(r):
    # The panel's centre, its anchor (= P + (2.741, −3.607)). The optimum is not over the cone's axis
    # (2.26, −7.01) but 0.19 m toward the box's middle: the sweep of the README's
    # "Independent check" (crates/ilp/examples/sweep.rs, 49 cells of 2 M photons) fits
    # its maximum at (2.11, −6.89) ± 0.013 m; directly above the cone with direct light
    # only. Within 0.75 m of it (a cell is 0.28 m × 0.66 m), and the 1.24 m panel whole
    # inside the walls x = 3.15, y = −7.97: a panel through a wall loses the light it
    # sends outside (the sweep's `*` cells).
    cx, cy, _ = r["variables"]["Light"]["anchor"]
    d = math.hypot(cx - 2.11, cy + 6.89)
    whole = cx <= 3.15 - 0.62 and cy >= -7.97 + 0.62
    return d <= 0.75 and whole, "panel centre (%.2f, %.2f), %.2f m from the sweep's optimum%s" % (
        cx, cy, d, "" if whole else ", through a wall")


def atrium_skylight(r):
    # The sun reaches the jar's centre through a hole centred at x = −4.07, z = 0; the
    # whole jar stays lit within ±0.7 m; one cell (0.99 m in x) of margin.
    x, _, z = r["variables"]["Hole"]["anchor"]
    return abs(x + 4.07) <= 1.0 and abs(z) <= 1.0, "hole centre (%.2f, %.2f)" % (x, z)


def atrium_colour(r):
    # The floor crosses the 35 lx cap at V ≈ 0.735 (README's table); one cell each side.
    v = r["variables"]["InnerWalls"]["value"]
    return 0.70 <= v <= 0.76, "V = %.3f" % v


def conference_sun(r):
    # A low sun through the window: travelling toward +x and +z, below 15°, azimuth from
    # +z toward +x within 10°–60° (the geometric 34° ± about one cell of 18°).
    d = r["variables"]["Sun"]["direction"]
    elevation = math.degrees(math.asin(max(-1.0, min(1.0, -d[1]))))
    azimuth = math.degrees(math.atan2(d[0], d[2]))
    ok = 0.0 < elevation <= 15.0 and 10.0 <= azimuth <= 60.0
    return ok, "sun elevation %.1f°, azimuth %.1f° from +z toward +x" % (elevation, azimuth)


def office_target(r, again):
    # Both lamps over the desk (x in [1.7, 3.3], z in [1.6, 2.4]; a cell of 0.15 m of
    # margin), the least power 1.19 x 3217 lm = 3828 lm found with the full budget (the
    # README), within 15 % with the reduced one; and measured again with 1 M other
    # photons, 500 lx on the desk (within its noise) and at most 300 lx on the screen.
    lamps = [r["variables"][k]["anchor"] for k in ("Lamp1", "Lamp2")]
    over = all(1.55 <= x <= 3.45 and 1.45 <= z <= 2.55 for x, _, z in lamps)
    power = r["estimate"]["mean"]
    m = again(["measure", "--config", "RESULT#1", "--side", "front", "-s", "Desk", "-s",
               "Screen", "--photons", "1000000", "--seed", "7", "--json"])
    desk, screen = m["surfaces"]
    ok = over and power <= 1.15 * 3828 and desk["high"] >= 500 and screen["low"] <= 300
    return ok, "lamps at %s, %.0f lm; measured again: desk %.1f lx [%.1f, %.1f], screen %.1f lx" % (
        ", ".join("(%.2f, %.2f)" % (x, z) for x, _, z in lamps), power, desk["mean"],
        desk["low"], desk["high"], screen["mean"])


def office_ies(r, again):
    # The lamps from downlight.ldt at multiplier 2 (37 W each): the least electrical
    # power (watts, since every lamp's file gives them) within 15 % of the README's
    # 39.03 W from 600 draws; measured again with 1 M other photons (the problem file's
    # <luminaire>s applied by measure too), 500 lx on the desk within its noise and at
    # most 300 lx on the screen.
    power = r["estimate"]["mean"]
    m = again(["measure", "--config", "RESULT#1", "--side", "front", "-s", "Desk", "-s",
               "Screen", "--photons", "1000000", "--seed", "7", "--json"])
    desk, screen = m["surfaces"]
    ok = power <= 1.15 * 39.03 and desk["high"] >= 500 and screen["low"] <= 300
    return ok, "%.2f W; measured again: desk %.1f lx [%.1f, %.1f], screen %.1f lx" % (
        power, desk["mean"], desk["low"], desk["high"], screen["mean"])


def overcast_sky_component(cx, cz, side=1.0, h=2.8 - 0.75, n=16, m=24):
    # office-daylight's sky component, % : the daylight factor the desk's top (x in
    # [1.7, 3.3], z in [1.6, 2.4], 2.05 m under the ceiling) gets straight from the CIE
    # overcast sky L = Lz (1 + 2 cos Z)/3 (E_h = 7 pi/9 Lz) through a horizontal square
    # opening of `side` centred at (cx, cz): 100/E_h x the integral of L cos Z dw,
    # dw = cos Z dA / r^2, by the midpoint rule (n x n desk points, m x m opening cells).
    total = 0.0
    cell = side / m
    for i in range(n):
        for k in range(n):
            x = 1.7 + 1.6 * (i + 0.5) / n
            z = 1.6 + 0.8 * (k + 0.5) / n
            for a in range(m):
                for b in range(m):
                    dx = cx - side / 2 + (a + 0.5) * cell - x
                    dz = cz - side / 2 + (b + 0.5) * cell - z
                    r2 = dx * dx + dz * dz + h * h
                    c = h / math.sqrt(r2)
                    total += (1 + 2 * c) / 3 * c * c / r2 * cell * cell
    return 100 * 9 / (7 * math.pi) * total / (n * n)


def office_daylight(r, again):
    # The room, desk and zone are symmetric about the desk's centre (2.5, 2.0), so the
    # most daylight factor is with the skylight right over it: within one cell (0.44 m
    # in x, 0.43 m in z). Measured again with 1 M other photons, the desk's DF is at
    # least its sky component, computed here (the rest is light reflected by the room),
    # and the floor keeps its 1 %.
    cx, _, cz = r["variables"]["Skylight"]["anchor"]
    over = abs(cx - 2.5) <= 0.45 and abs(cz - 2.0) <= 0.44
    m = again(["measure", "--config", "RESULT#1", "--daylight-factor", "--side", "front",
               "-s", "Desk", "-s", "Floor", "--photons", "1000000", "--seed", "7", "--json"])
    desk, floor = (s["daylight_factor"] for s in m["surfaces"])
    sky = overcast_sky_component(cx, cz)
    ok = over and desk["high"] >= sky and floor["high"] >= 1.0
    return ok, "skylight centre (%.2f, %.2f); measured again: desk DF %.2f %% [%.2f, %.2f], sky component %.2f %%, floor %.2f %%" % (
        cx, cz, desk["mean"], desk["low"], desk["high"], sky, floor["mean"])


def open_office(r, again):
    # Six downlights free on the ceiling: no more power than the regular 3 x 2 array
    # with its lamps dimmed one by one at their least (grid.xml, solved here from one
    # trace), and measured again with 1 M other photons, 500 lx on the task area
    # within its noise.
    grid = again(["solve", "--output", "GRID", "--json", "--no-images", "--no-report"],
                 os.path.join("examples", "open-office", "grid.xml"))
    regular = grid["isoc"][0]["estimate"]["mean"]
    power = r["estimate"]["mean"]
    m = again(["measure", "--config", "RESULT#1", "--side", "front", "-s", "TaskArea",
               "--photons", "1000000", "--seed", "7", "--json"])
    task = m["surfaces"][0]
    # The same six lamps as one <lightArray> at one level (array.xml): an array it
    # reads back as one, no more power than grid.xml's, and 500 lx measured again.
    array = again(["solve", "--output", "ARRAY", "--json", "--no-images", "--no-report"],
                  os.path.join("examples", "open-office", "array.xml"))
    member = array["isoc"][0]
    shape = member["layouts"][0].get("array")
    m = again(["measure", "--config", "ARRAY/result.json#1", "--side", "front", "-s", "TaskArea",
               "--photons", "1000000", "--seed", "7", "--json"],
              os.path.join("examples", "open-office", "array.xml"))
    array_task = m["surfaces"][0]
    ok = (power <= regular and task["high"] >= 500 and shape is not None
          and member["estimate"]["mean"] <= regular and array_task["high"] >= 500)
    return ok, ("%.1f W against the regular array's %.1f W; measured again: task area %.1f lx [%.1f, %.1f]; "
                "as one <lightArray>: %.1f W, %s; measured again %.1f lx") % (
        power, regular, task["mean"], task["low"], task["high"], member["estimate"]["mean"],
        member["layouts"][0]["description"], array_task["mean"])


def classroom(r, again):
    # The least power for everything EN 12464-1 asks of a classroom and a pupil's UGR at
    # most 19: every constraint of the answer holds (the UGR decided at 95 %), and its
    # UGR rated again with 1 M other photons reads within the limit (the answer's level
    # is set by the task area's Em, which leaves its UGR a few hundredths under 19, so
    # the mean, not the interval, is what a second trace can confirm); with the
    # luminaires turned across the
    # pupil's view (turned.xml) no layout tried meets it, and the UGR limit is what fails.
    ugr = next(c for c in r["constraints"] if c["label"] == "pupil.maxUGR")
    g = again(["glare", "--config", "RESULT#1", "--observer", "4.5,1.2,6.2", "--view", "0,0,-1",
               "--photons", "1000000", "--seed", "7", "--json"])
    turned = again(["solve", "--output", "TURNED", "--json", "--no-images", "--no-report"],
                   os.path.join("examples", "classroom", "turned.xml"))
    closest = turned["closest"][0] if turned["closest"] else {"constraints": []}
    binds = any(c["label"] == "pupil.maxUGR" and c["verdict"] == "infeasible"
                for c in closest["constraints"])
    ok = (all(c["verdict"] == "feasible" for c in r["constraints"])
          and g["ugr"] <= 19.0 and not turned["isoc"] and binds)
    return ok, ("%s; UGR %.2f, rated again %.2f [%.2f, %.2f]; turned across the view: %s, "
                "the closest UGR %s") % (
        r["layouts"][0]["description"] if r.get("layouts") else "?", ugr["mean"], g["ugr"],
        g["ugr_interval"][0], g["ugr_interval"][1],
        "no layout meets it" if not turned["isoc"] else "met",
        next(("%.1f" % c["mean"] for c in closest["constraints"] if c["label"] == "pupil.maxUGR"), "?"))


# name: (check, reduced-budget arguments)
EXAMPLES = {
    "cornell-cone": (cornell_cone, ["--iterations", "300"]),
    "cornell-light": (cornell_light, ["--iterations", "300"]),
    "atrium-skylight": (atrium_skylight, ["--iterations", "400", "--photons", "400000"]),
    "atrium-colour": (atrium_colour, ["--photons", "400000"]),
    "conference-sun": (conference_sun, ["--iterations", "300", "--photons", "400000"]),
    "office-target": (office_target, ["--iterations", "600"]),
    "office-ies": (office_ies, ["--iterations", "600"]),
    "office-daylight": (office_daylight, ["--iterations", "100", "--photons", "100000"]),
    "open-office": (open_office, []),
    "classroom": (classroom, []),
}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--bin", help="the invlight binary (default: cargo run --release --)")
    ap.add_argument("--only", choices=sorted(EXAMPLES))
    ap.add_argument("--full", action="store_true", help="the problem files' own budgets")
    ap.add_argument("--strategy", help="solve --strategy (default: the problem file's)")
    args = ap.parse_args()
    command = [args.bin] if args.bin else ["cargo", "run", "--quiet", "--release", "--"]
    failed = 0
    with tempfile.TemporaryDirectory() as tmp:
        for name, (check, budget) in EXAMPLES.items():
            if args.only not in (None, name):
                continue
            out = os.path.join(tmp, name)
            cmd = command + ["solve", os.path.join("examples", name, "problem.xml"),
                             "--output", out, "--json", "--no-images",
                             "--report-photons", "200000"] + ([] if args.full else budget)
            cmd += ["--strategy", args.strategy] if args.strategy else []
            start = time.monotonic()
            run = subprocess.run(cmd, cwd=REPO, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
            seconds = time.monotonic() - start
            if run.returncode != 0:
                print("FAIL %s: exit %d\n%s" % (name, run.returncode, run.stderr.decode()[-2000:]))
                failed += 1
                continue
            result = json.loads(run.stdout)
            # Every example's report.html is built, self-contained.
            report = os.path.join(out, "report.html")
            page = open(report, encoding="utf-8").read() if os.path.exists(report) else ""
            outside = re.findall(r"""(?:src|href)=["'](?!data:|#)[^"']*|url\((?!data:)|@import""", page)
            if not page or outside:
                print("FAIL %s: report.html %s" % (name, "missing" if not page else "references %s" % outside[:3]))
                failed += 1
                continue
            if not result["isoc"]:
                print("FAIL %s: no feasible configuration" % name)
                failed += 1
                continue
            best = result["isoc"][0]
            problem = os.path.join("examples", name, "problem.xml")

            def again(extra, on=None):
                # A member's configuration measured by another command (on this problem
                # or on the file `on`): RESULT stands for this run's result.json, GRID
                # for a folder beside this run's.
                extra = [a.replace("RESULT", os.path.join(out, "result.json")) for a in extra]
                extra = [a.replace("GRID", out + "-grid").replace("ARRAY", out + "-array")
                         .replace("TURNED", out + "-turned") for a in extra]
                cmd = command + [extra[0], on or problem] + extra[1:]
                done = subprocess.run(cmd, cwd=REPO, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                      check=True)
                return json.loads(done.stdout)

            ok, what = check(best, again) if check in (office_target, office_ies, office_daylight, open_office, classroom) else check(best)
            unit = result["objective"]["unit"]
            traced = re.search(r"(\d+) evaluations, (\d+) photons", run.stderr.decode())
            print("%s %s: %s; %.4g %s [%.4g, %.4g]; %d evaluations, %s photons traced, N = %d, "
                  "ISOC of %d, search %.1f s, %.0f s in all; stopped: %s" % (
                "ok  " if ok else "FAIL", name, what, best["estimate"]["mean"], unit,
                best["estimate"]["low"], best["estimate"]["high"], result["evaluations"],
                traced.group(2) if traced else "?", result["photons"], len(result["isoc"]),
                result["seconds"], seconds, result.get("stopped", "?")))
            ratio = re.search(r"var\(X−Y\)/\(var X \+ var Y\) = (\S+)", run.stderr.decode())
            if ratio:
                print("     paired variance ratio %s" % ratio.group(1))
            failed += not ok
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
