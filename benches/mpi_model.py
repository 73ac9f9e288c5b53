#!/usr/bin/env python3
"""The cluster model of BENCHMARKS.md ("The same solve on K processes").

    python3 benches/mpi_model.py RUN_DIR... [--words 138] [--fold-us F] [--rate R]

Each RUN_DIR is a solve's output folder from one node (this machine); its solutions.csv
gives every evaluation's photons n and seconds t, its result.json the search's seconds.
An evaluation on K nodes is predicted to take

    t·⌈c/K⌉/c + c·fold + blocks·α·⌈log₂K⌉ + 8·words·c·(K−1)/K / β

with c = ⌈n/4096⌉ chunks (the unit of work: the rank with the most sets the pace), blocks = ⌈c/(256K)⌉ exchanges, `words` per chunk (138 for one
surface of one component with its groups: docs/cluster.md), `fold` the time every rank
spends unpacking and adding one chunk (it is not divided by K), α the latency of one
step of the all-gather and β the bandwidth. The search's own time (result.json's seconds
less the evaluations') is not divided either. Efficiency is the one-node time over K
times the K-node time; "last K ≥ 50 %" is the largest power of two still at half
efficiency or more, "fastest K" the one of least time (more ranks are slower). A last line does the same for one evaluation of 10⁹ photons
traced at R photons/s on one node.
"""

import argparse
import csv
import json
import math
import os

NETWORKS = {"InfiniBand (α 2 µs, β 10 GB/s)": (2e-6, 10e9), "10 GbE (α 30 µs, β 1 GB/s)": (30e-6, 1e9)}


def predict(evals, serial, k, words, fold, alpha, beta):
    total = serial
    for n, t in evals:
        c = math.ceil(n / 4096)
        blocks = math.ceil(c / (256 * k))
        steps = math.ceil(math.log2(k)) if k > 1 else 0
        # Chunks are the unit of work: the rank with the most of them sets the pace.
        total += t * math.ceil(c / k) / c + (c * fold if k > 1 else 0) + blocks * alpha * steps
        total += 8 * words * c * (k - 1) / k / beta
    return total


def main():
    p = argparse.ArgumentParser()
    p.add_argument("runs", nargs="+")
    p.add_argument("--words", type=float, default=138)
    p.add_argument("--fold-us", type=float, default=1.0)
    p.add_argument("--rate", type=float, default=1.1e6)
    a = p.parse_args()
    fold = a.fold_us * 1e-6
    print("| run | evaluations | photons | one node s (search alone) | network | K = 16: s, efficiency | K = 256: s, efficiency | last K ≥ 50 % | fastest K |")
    print("|---|---|---|---|---|---|---|---|---|")
    cases = []
    for run in a.runs:
        rows = list(csv.DictReader(open(os.path.join(run, "solutions.csv"), newline="")))
        evals = [(int(r["photons"]), float(r["seconds"])) for r in rows]
        search = json.load(open(os.path.join(run, "result.json")))["seconds"]
        serial = max(search - sum(t for _, t in evals), 0.0)
        cases.append((os.path.basename(run.rstrip("/")), evals, serial))
    cases.append(("one evaluation of 10⁹ photons", [(10**9, 10**9 / a.rate)], 0.0))
    for name, evals, serial in cases:
        one = predict(evals, serial, 1, a.words, fold, 0, 1)
        for net, (alpha, beta) in NETWORKS.items():
            cells = []
            for k in (16, 256):
                t = predict(evals, serial, k, a.words, fold, alpha, beta)
                cells.append("%.3g s, %.0f %%" % (t, 100 * one / (k * t)))
            ks = [2**i for i in range(15)]
            best = min(ks, key=lambda k: predict(evals, serial, k, a.words, fold, alpha, beta))
            half = max(k for k in ks if one / (k * predict(evals, serial, k, a.words, fold, alpha, beta)) >= 0.5)
            photons = sum(n for n, _ in evals)
            print("| %s | %d | %.3g | %.3g (%.2g) | %s | %s | %s | %d | %d |" % (
                name, len(evals), photons, one, serial, net, cells[0], cells[1], half, best))


main()
