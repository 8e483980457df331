#!/usr/bin/python3
"""The loading angle's effects on the deposits of bench/angle/run_angles.sh: per specimen (dense
and loose, α = 0-90°) the mean over its seeds, ± the standard error of that mean (the seeds'
standard deviation / √n), of the initial state, the peak and the end, and a figure of the peak
against α.

usage: angle_table.py OUT [--img PNG]

Read from each seed's run file (OUT/seed<S>/<specimen>.h5): e0 and the stress ratio q/p from the
series (the peak is the largest q/p, the end the mean over the last 5 % of axial strain); from the
SFF table the fabric anisotropy a_c (the triaxial scalar of A about z) and the tilt of A's major
axis from z (the loading axis), at the first snapshot (the start of shearing), at the snapshot
nearest the peak and at the last; from the table of checks the non-coaxiality of A, the angle
between the major principal axes of A and σ (docs/sff.md, "coaxiality"), at the peak and at the
end (not at the start, where σ is isotropic and its major axis arbitrary).
"""
import argparse
import glob
import os
import re

import h5py
import numpy as np

from sffcal import runfile

ROWS = [("e0", "e0", "{:.3f}"), ("tilt0", "tilt of A at start [°]", "{:.1f}"),
        ("ac0", "a_c at start", "{:.3f}"),
        ("peak_eta", "peak q/p", "{:.3f}"), ("peak_strain", "ε_a at peak [%]", "{:.1f}"),
        ("peak_ac", "a_c at peak", "{:.3f}"), ("peak_coax", "A vs σ at peak [°]", "{:.1f}"),
        ("end_eta", "q/p at end", "{:.3f}"), ("end_ac", "a_c at end", "{:.3f}"),
        ("end_coax", "A vs σ at end [°]", "{:.1f}")]


def measures(path):
    """The quantities of ROWS of one run."""
    with h5py.File(path, "r") as f:
        s = runfile.series(f, ["axial_strain", "eta", "void_ratio"])
        a = runfile.table(f, "sff", ["axial_strain", "a_c", "fabric_tilt_deg"])
        c = runfile.table(f, "sff_checks", ["coaxiality_fabric_deg"])
    peak = int(np.argmax(s["eta"]))
    near = int(np.argmin(np.abs(a["axial_strain"] - s["axial_strain"][peak])))
    coax = c["coaxiality_fabric_deg"]
    return {"e0": s["void_ratio"][0], "tilt0": a["fabric_tilt_deg"][0], "ac0": a["a_c"][0],
            "peak_eta": s["eta"][peak], "peak_strain": 100 * s["axial_strain"][peak],
            "peak_ac": a["a_c"][near], "peak_coax": coax[near],
            "end_eta": s["eta"][runfile.end_window(s["axial_strain"])].mean(),
            "end_ac": a["a_c"][-1], "end_coax": coax[-1]}


def specimens(out):
    """{(density, angle): [measures of each seed's run]} of OUT's seed folders."""
    found = {}
    for path in sorted(glob.glob(os.path.join(out, "seed*", "dep_*_a[0-9][0-9].h5"))):
        m = re.match(r"dep_(\w+)_a(\d+)$", runfile.name_of(path))
        found.setdefault((m.group(1), int(m.group(2))), []).append(measures(path))
    return found


def mean_and_error(values):
    values = np.asarray(values, float)
    error = values.std(ddof=1) / np.sqrt(len(values)) if len(values) > 1 else float("nan")
    return values.mean(), error


def table(found):
    keys = sorted(found, key=lambda k: (k[0] != "dense", k[1]))
    print("| quantity | " + " | ".join(f"{d} {a}°" for d, a in keys) + " |")
    print("|---|" + "---|" * len(keys))
    print("| seeds | " + " | ".join(str(len(found[k])) for k in keys) + " |")
    for key, label, form in ROWS:
        cells = []
        for k in keys:
            mean, error = mean_and_error([r[key] for r in found[k]])
            cells.append(form.format(mean) + " ± " + form.format(error))
        print(f"| {label} | " + " | ".join(cells) + " |")


def figure(found, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 3, figsize=(13, 3.8))
    for density, marker in (("dense", "o"), ("loose", "s")):
        angles = sorted(a for d, a in found if d == density)
        for ax, key, label in zip(axes, ("peak_eta", "peak_ac", "peak_coax"),
                                  ("peak q/p", "a_c at peak", "A vs σ at peak [°]")):
            stats = [mean_and_error([r[key] for r in found[(density, a)]]) for a in angles]
            ax.errorbar(angles, [m for m, _ in stats], yerr=[e for _, e in stats], marker=marker,
                        capsize=3, label=density)
            ax.set_ylabel(label)
    for ax in axes:
        ax.set_xlabel("loading angle α [°]")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle("500-clump deposits, mean of the seeds ± its standard error", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    print(f"\nwrote {path}")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("out", help="output folder of bench/angle/run_angles.sh")
    parser.add_argument("--img", help="the figure (default OUT/angle.png)")
    args = parser.parse_args()
    found = specimens(args.out)
    if not found:
        raise SystemExit(f"angle_table.py: no deposit runs in {args.out}/seed*/")
    table(found)
    figure(found, args.img or os.path.join(args.out, "angle.png"))


if __name__ == "__main__":
    main()
