#!/usr/bin/python3
"""The paper-size runs at 20 /s against the recorded reference run (issue 16, point 4).

usage: compare_paper_rate.py RUN.h5|SERIES.csv [...] [--reference SERIES.csv|RUN.h5] [--png OUT.png]

Prints a markdown table of the measures the issue compares (peak q/p and its strain, the mean q/p
over 20-25 % as the critical one, the volumetric strain at 10 and 25 %) for the reference (by
default the recorded bench/reference/dense_100kPa_series.csv, 50 /s, old engine; or the series
CSV or run file given by --reference) and each run, with the run's worst lateral stress error
after 0.5 % of axial strain and its 95th percentile over the rows, its largest inertial number,
steps and shearing wall time; overlays q/p and the volumetric strain in OUT.png. (The reduced
data kept in the repository are the series CSVs `sffcal` writes beside each run,
RUN.h5.series.csv.)
"""
import argparse
import os

import h5py
import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from sffcal import runfile  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
REFERENCE = os.path.join(HERE, "dense_100kPa_series.csv")
CRITICAL_WINDOW = (0.20, 0.25)  # axial strain over which q/p is averaged as the critical one
SETTLING_STRAIN = 0.005          # the servo target applies after this axial strain (issue 16)


def measures(s):
    """The compared measures of one series (a dict of numpy columns)."""
    ea, eta, ev = s["axial_strain"], s["eta"], s["volumetric_strain"]
    k = int(np.argmax(eta))
    window = (ea >= CRITICAL_WINDOW[0]) & (ea <= CRITICAL_WINDOW[1] + 1e-9)
    settled = ea >= SETTLING_STRAIN
    return {
        "peak": eta[k], "peak_strain": ea[k], "critical": eta[window].mean(),
        "ev10": np.interp(0.10, ea, ev), "ev25": np.interp(0.25, ea, ev),
        "lateral": s["lateral_stress_error"][settled].max(),
        "lateral_p95": np.percentile(np.abs(s["lateral_stress_error"][settled]), 95),
        "inertial": s["inertial_number"].max(),
    }


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("runs", nargs="+")
    ap.add_argument("--reference", default=REFERENCE, help="series CSV or run file of the reference")
    ap.add_argument("--png")
    a = ap.parse_args()

    def curve(path, name=None):
        if path.endswith(".csv"):  # a committed series (no summary: steps and time unknown)
            return (name or os.path.basename(path), runfile.read_csv_table(path), {})
        with h5py.File(path, "r") as f:
            return (name or runfile.name_of(path), runfile.series(f), runfile.summary(f) or {})

    curves = [curve(a.reference, f"reference ({os.path.basename(a.reference)})")]
    curves += [curve(path) for path in a.runs]

    print("| run | peak q/p | at ε_a | q/p 20–25 % | ε_v at 10 % | ε_v at 25 % | worst lateral error after 0.5 % | its 95th percentile | max I | steps | shearing wall s |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for name, s, summary in curves:
        m = measures({k: np.asarray(v) for k, v in s.items()})
        steps = summary.get("steps", "")
        wall = summary.get("wall_seconds", "")
        print(f"| {name} | {m['peak']:.3f} | {100 * m['peak_strain']:.1f} % | {m['critical']:.3f} | "
              f"{m['ev10']:.4f} | {m['ev25']:.4f} | {100 * m['lateral']:.2f} % | {100 * m['lateral_p95']:.2f} % | "
              f"{m['inertial']:.1e} | "
              f"{steps} | {wall if wall == '' else f'{wall:.0f}'} |")

    if a.png:
        fig, axes = plt.subplots(1, 2, figsize=(11, 4))
        for name, s, _ in curves:
            ea = 100.0 * np.asarray(s["axial_strain"])
            axes[0].plot(ea, s["eta"], label=name)
            axes[1].plot(ea, 100.0 * np.asarray(s["volumetric_strain"]), label=name)
        axes[0].set_ylabel("q/p (walls)")
        axes[1].set_ylabel("volumetric strain [%] (compression +)")
        for ax in axes:
            ax.set_xlabel("axial strain [%]")
            ax.set_xlim(0, 25)
            ax.grid(alpha=0.3)
        axes[0].legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(a.png, dpi=110)


if __name__ == "__main__":
    main()
