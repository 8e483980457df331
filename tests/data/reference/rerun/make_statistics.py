#!/usr/bin/python3
"""Seed statistics of the rerun regression specimens (tests/regression/rerun_statistics_test.cc).

usage: make_statistics.py [--seeds N] [--jobs J] [--sffcal build/sffcal] [--work out/rerun]

Runs `sffcal dem` on dense.toml and loose.toml for seeds 1..N (one thread each, J at a time),
reads each run's series CSV and writes, beside this script, values.csv (one row per case and
seed) and statistics.csv (mean, sample standard deviation, min, max per case and measure). The
measures are defined here and in the test, identically:
  e0       void ratio of the first series row (after compaction to 100 kPa)
  z0       coordination number of the first row
  peak_eta largest q/p (wall stresses) up to 10 % axial strain
  ev_05    volumetric strain at 5 % axial strain (compression positive), linear interpolation
  ev_10    volumetric strain at 10 %
  eta_10   mean q/p over the rows with 8 % <= axial strain <= 10 %
"""
import argparse
import csv
import math
import os
import subprocess
from multiprocessing import Pool

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", "..", "..", ".."))
CASES = ("dense", "loose")
MEASURES = ("e0", "z0", "peak_eta", "ev_05", "ev_10", "eta_10")


def interpolate(x, xs, ys):
    for i in range(1, len(xs)):
        if xs[i] >= x:
            t = (x - xs[i - 1]) / (xs[i] - xs[i - 1])
            return ys[i - 1] + t * (ys[i] - ys[i - 1])
    raise ValueError(f"the series ends at {xs[-1]} < {x}")


def measures(series_csv):
    with open(series_csv) as f:
        rows = list(csv.DictReader(f))
    col = {k: [float(r[k]) for r in rows] for k in ("axial_strain", "void_ratio", "coordination_number", "eta",
                                                    "volumetric_strain")}
    strain = col["axial_strain"]
    window = [e for s, e in zip(strain, col["eta"]) if 0.08 <= s <= 0.10 + 1e-9]
    return {"e0": col["void_ratio"][0], "z0": col["coordination_number"][0], "peak_eta": max(col["eta"]),
            "ev_05": interpolate(0.05, strain, col["volumetric_strain"]),
            "ev_10": interpolate(0.10 - 1e-9, strain, col["volumetric_strain"]),
            "eta_10": sum(window) / len(window)}


def run(task):
    sffcal, work, case, seed = task
    config = os.path.join(work, f"{case}_seed{seed}.toml")
    text = open(os.path.join(HERE, f"{case}.toml")).read().replace("seed = 1\n", f"seed = {seed}\n", 1)
    open(config, "w").write(text)
    out = os.path.join(work, f"{case}_seed{seed}.h5")
    with open(out + ".log", "w") as log:
        subprocess.run([sffcal, "dem", "-c", config, "-o", out, "--force"], stdout=log, stderr=subprocess.STDOUT, check=True)
    return case, seed, measures(out + ".series.csv")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--seeds", type=int, default=12)
    parser.add_argument("--jobs", type=int, default=os.cpu_count())
    parser.add_argument("--sffcal", default=os.path.join(ROOT, "build", "sffcal"))
    parser.add_argument("--work", default=os.path.join(ROOT, "out", "rerun"))
    args = parser.parse_args()
    os.makedirs(args.work, exist_ok=True)
    tasks = [(os.path.abspath(args.sffcal), args.work, c, s) for c in CASES for s in range(1, args.seeds + 1)]
    with Pool(args.jobs) as pool:
        results = sorted(pool.map(run, tasks))
    with open(os.path.join(HERE, "values.csv"), "w") as f:
        f.write("case,seed," + ",".join(MEASURES) + "\n")
        for case, seed, m in results:
            f.write(f"{case},{seed}," + ",".join(f"{m[k]:.6g}" for k in MEASURES) + "\n")
    with open(os.path.join(HERE, "statistics.csv"), "w") as f:
        f.write("case,measure,mean,std,min,max,seeds\n")
        for case in CASES:
            for k in MEASURES:
                values = [m[k] for c, _, m in results if c == case]
                mean = sum(values) / len(values)
                std = math.sqrt(sum((v - mean) ** 2 for v in values) / (len(values) - 1))
                f.write(f"{case},{k},{mean:.6g},{std:.6g},{min(values):.6g},{max(values):.6g},{len(values)}\n")
                print(f"{case:6s} {k:9s} mean {mean:9.5f}  std {std:8.5f}  range [{min(values):.5f}, {max(values):.5f}]")


if __name__ == "__main__":
    main()
