#!/usr/bin/env python3
"""The problem files' own strategies against PAIRED_ISOC and RACE_ISOC_ON_END on the bundled examples, one after the other
in one run, with tools/check_examples.py's reduced budgets and its check of the answer.
For each run: evaluations, photons traced (what `solve` reports), photons
the rows ask for (the sum of solutions.csv's photons column: what re-tracing every
evaluation from its first photon would cost), screened rows, seconds of search, the
elapsed seconds at which the final best member first joined the ISOC (time to
solution), the ISOC's size, why it stopped, and whether the answer is in the region.

    python3 benches/strategies.py [--bin PATH] [--only NAME ...] [-j THREADS] [--strategies S ...] [--full]

Python 3 standard library only; the runs' folders go to a temporary folder.
"""

import argparse
import csv
import importlib.util
import json
import os
import re
import subprocess
import tempfile

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
spec = importlib.util.spec_from_file_location("check", os.path.join(REPO, "tools", "check_examples.py"))
check = importlib.util.module_from_spec(spec)
spec.loader.exec_module(check)


def time_to_best(folder, best):
    """Elapsed seconds at the first row that admitted the final best member's cell."""
    with open(os.path.join(folder, "solutions.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    mean = best["estimate"]["mean"]
    for r in rows:
        if r["verdict"] in ("initial", "better", "probable", "final") and abs(float(r["mean"]) - mean) <= 1e-9 * max(1.0, abs(mean)):
            return float(r["elapsed"]), rows
    return float("nan"), rows


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--bin", default=os.path.join(REPO, "target", "release", "invlight"))
    ap.add_argument("--only", nargs="*", choices=sorted(check.EXAMPLES))
    ap.add_argument("-j", default="2")
    ap.add_argument("--strategies", nargs="*", default=[None, "PAIRED_ISOC", "RACE_ISOC_ON_END"],
                    help="the strategies to run, one after the other; 'default' is the problem file's, RACE_ISOC_ON_END where it names none, so name the thesis' REFINE_ISOC_ON_INTERSECTION to compare with it (default: default PAIRED_ISOC RACE_ISOC_ON_END)")
    ap.add_argument("--full", action="store_true",
                    help="the problem files' own budgets instead of check_examples' reduced ones")
    args = ap.parse_args()
    print("| example | strategy | evaluations | screened | photons traced | photons asked | search s | best found at s | ISOC | stopped | in region |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for name, (test, budget) in check.EXAMPLES.items():
            if args.only and name not in args.only:
                continue
            problem = os.path.join("examples", name, "problem.xml")
            for strategy in [None if s in (None, "default") else s for s in args.strategies]:
                out = os.path.join(tmp, "%s-%s" % (name, strategy or "default"))
                cmd = [args.bin, "solve", problem, "--output", out, "--json", "--no-images",
                       "--no-report", "-j", args.j] + ([] if args.full else budget) + (["--strategy", strategy] if strategy else [])
                run = subprocess.run(cmd, cwd=REPO, stdout=subprocess.PIPE, stderr=subprocess.PIPE, check=True)
                result = json.loads(run.stdout)
                best = result["isoc"][0]

                def again(extra):
                    extra = [a.replace("RESULT", os.path.join(out, "result.json")) for a in extra]
                    done = subprocess.run([args.bin, extra[0], problem] + extra[1:], cwd=REPO,
                                          stdout=subprocess.PIPE, check=True)
                    return json.loads(done.stdout)

                # The checks that measure the answer again take a second argument.
                takes_again = test.__code__.co_argcount == 2
                ok, what = test(best, again) if takes_again else test(best)
                found, rows = time_to_best(out, best)
                traced = re.search(r"(\d+) evaluations, (\d+) photons", run.stderr.decode()).group(2)
                asked = sum(int(r["photons"]) for r in rows)
                screened = sum(r["verdict"] == "screened" for r in rows)
                stopped = result.get("stopped", "?").split(":")[0]
                print("| %s | %s | %d | %d | %.2f M | %.2f M | %.1f | %.1f | %d | %s | %s (%s) |" % (
                    name, strategy or "default", result["evaluations"], screened, int(traced) / 1e6,
                    asked / 1e6, result["seconds"], found, len(result["isoc"]), stopped,
                    "yes" if ok else "NO", what), flush=True)


if __name__ == "__main__":
    main()
