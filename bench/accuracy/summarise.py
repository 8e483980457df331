#!/usr/bin/python3
"""Tables and the Pareto plot of the run-time-against-error sweep (run_sweep.py).

usage: summarise.py OUT [--png bench/accuracy/pareto.png]

Measures of each run: peak eta (largest wall q/p), critical eta (mean wall q/p over 20-30 %
axial strain), volumetric strain at 10 % axial strain (compression positive), and a_c at the
peak (the snapshots' a_c interpolated at the peak's axial strain). Error of a case in one
measure: the root mean square over the seeds of (case - reference) on the same specimen (seeds
1-3, and any extra seed run for both). Scatter: the standard deviation between seeds, pooled
over the reference and base runs. A case is "within scatter" when every error is at most
the scatter of its measure; its score is the largest error / scatter ratio.
"""
import argparse
import math
import os
import re
import sys

from run_sweep import CASES, SEEDS, case_keys  # a sibling: this script's folder is on the path
from sffcal.runfile import read_csv_table

MAX_SEED = 20  # seeds looked for beyond SEEDS
MEASURES = (("peak_eta", "peak η"), ("critical_eta", "critical η"), ("ev_10", "ε_v at 10 %"),
            ("ac_peak", "a_c at peak"))


def interpolate(x, xs, ys):
    for i in range(1, len(xs)):
        if xs[i] >= x:
            t = (x - xs[i - 1]) / (xs[i] - xs[i - 1]) if xs[i] > xs[i - 1] else 0.0
            return ys[i - 1] + t * (ys[i] - ys[i - 1])
    return ys[-1]


def measures(stem):
    """None when the run failed or is not finished."""
    try:
        seconds, code = open(stem + ".time").read().split()
    except OSError:
        return None
    if int(code) != 0:
        return {"seconds": float(seconds), "failed": True}
    summary = re.search(r"(\d+) steps in ([0-9.]+) s", open(stem + ".log").read())
    series = read_csv_table(stem + ".h5.series.csv")
    sff = read_csv_table(stem + ".h5.sff.csv")
    strain, eta = series["axial_strain"], series["eta"]
    peak = max(range(len(eta)), key=lambda i: eta[i])
    window = [e for s, e in zip(strain, eta) if 0.2 <= s <= 0.3]
    return {"seconds": float(summary.group(2)), "steps": int(summary.group(1)), "failed": False,
            "peak_eta": eta[peak],
            "critical_eta": sum(window) / len(window),
            "ev_10": interpolate(0.10, strain, series["volumetric_strain"]),
            "ac_peak": interpolate(strain[peak], sff["axial_strain"], sff["a_c"])}


def stdev(values):
    mean = sum(values) / len(values)
    return math.sqrt(sum((v - mean) ** 2 for v in values) / (len(values) - 1))


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("out")
    parser.add_argument("--png", default="")
    args = parser.parse_args()
    runs = {(name, seed): measures(os.path.join(args.out, "runs", f"{name}_seed{seed}"))
            for name in CASES for seed in range(1, MAX_SEED + 1)}
    if any(runs[c, s] is None or runs[c, s]["failed"] for c in ("reference", "base") for s in SEEDS):
        sys.exit(f"the reference and base runs must be finished for seeds {SEEDS}")
    # Extra seeds (run_sweep.py --seeds) count where the reference has them too.
    ref_seeds = [s for s in range(1, MAX_SEED + 1) if runs["reference", s] is not None]
    reference = [runs["reference", s] for s in ref_seeds]
    base = [runs["base", s] for s in ref_seeds if runs["base", s] is not None]
    scatter = {}
    for key, _ in MEASURES:
        pooled = (stdev([r[key] for r in reference]) ** 2 + stdev([r[key] for r in base]) ** 2) / 2
        scatter[key] = math.sqrt(pooled)
    base_seconds = sum(r["seconds"] for r in base) / len(base)

    header = ["case", "setting", "seeds", "steps", "wall s", "speed-up"] + [f"{label} (error)" for _, label in MEASURES] + ["score"]
    print("| " + " | ".join(header) + " |")
    print("|" + "---|" * len(header))
    print(f"| seed scatter | reference and base | {len(reference)} + {len(base)} | | | | " + " | ".join(f"{scatter[k]:.3g}" for k, _ in MEASURES) + " | 1 |")
    points = []
    for name in CASES:
        seeds = [s for s in ref_seeds if runs[name, s] is not None]
        done = [runs[name, s] for s in seeds]
        setting = ", ".join(f"{k.split('.')[-1]} {v}" for k, v in CASES[name].items()) or "rate 50 /s, safety 0.2 (the base of issue 8)"
        if not set(SEEDS) <= set(seeds):
            print(f"| {name} | {setting} | seeds {seeds} of {list(SEEDS)} done |")
            continue
        seconds = sum(r["seconds"] for r in done) / len(done)
        if any(r["failed"] for r in done):
            print(f"| {name} | {setting} | {len(seeds)} | | {seconds:.0f} | {base_seconds / seconds:.2f} | failed (see the run log) |")
            continue
        cells, score = [], 0.0
        for key, _ in MEASURES:
            mean = sum(r[key] for r in done) / len(done)
            error = math.sqrt(sum((runs[name, s][key] - runs["reference", s][key]) ** 2 for s in seeds) / len(seeds))
            score = max(score, error / scatter[key])
            cells.append(f"{mean:.3f} ({error:.3f})")
        if name != "reference":  # the yardstick: score 0 by construction
            points.append((name, seconds, score))
        steps = sum(r["steps"] for r in done) / len(done)
        print(f"| {name} | {setting} | {len(seeds)} | {steps:.3g} | {seconds:.0f} | {base_seconds / seconds:.2f} | " + " | ".join(cells)
              + f" | {score:.2f} |")

    front, best = [], math.inf
    for name, seconds, score in sorted(points, key=lambda p: (p[1], p[2])):
        if score < best:
            front.append((name, seconds, score))
            best = score
    print("\nPareto front (faster and not worse than any other case): "
          + ", ".join(f"{n} ({s:.0f} s, score {e:.2f})" for n, s, e in front))
    within = [p for p in points if p[2] <= 1.0]
    if within:
        fastest = min(within, key=lambda p: p[1])
        print(f"fastest case within the seed scatter: {fastest[0]} ({fastest[1]:.0f} s, score {fastest[2]:.2f})")
    if args.png:
        plot(points, front, args.png)


def plot(points, front, png):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for name, seconds, score in points:
        ax.plot(seconds, score, "o", color="tab:blue" if score <= 1 else "tab:red", ms=5)
        ax.annotate(name, (seconds, score), fontsize=7, xytext=(3, 3), textcoords="offset points")
    ax.plot([p[1] for p in front], [p[2] for p in front], "-", color="gray", lw=1, label="Pareto front")
    ax.axhline(1.0, color="k", ls=":", lw=1, label="seed scatter")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("wall-clock time of the shearing per run [s] (one thread)")
    ax.set_ylabel("largest error / seed scatter")
    ax.set_title(f"{case_keys('base')['bodies']} clumps, dense, 100 kPa, to 30 % axial strain")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(png, dpi=120)
    print(f"wrote {png}")


if __name__ == "__main__":
    main()
