#!/usr/bin/python3
"""Plots the curves of `sffcal fe-check`: q/p, volumetric strain and the fabric invariant F:n_c
against axial strain, one row per case, overlaying the FE single element, the FE 2x2x4 mesh, the
material-point driver and (where the case has one) the DEM run. Compression positive.

    scripts/plot_fe_check.py OUT_FOLDER [-o PNG]      (default PNG: OUT_FOLDER/fe_check.png)
"""
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from sffcal.runfile import read_csv_table  # noqa: E402

# label, file, matplotlib style
SOURCES = [
    ("DEM", "dem.csv", dict(color="0.55", lw=1.0)),
    ("driver", "driver.csv", dict(color="C0", lw=2.6, alpha=0.6)),
    ("FE element", "element.csv", dict(color="C3", lw=1.2, ls="--")),
    ("FE mesh 2x2x4", "mesh.csv", dict(color="k", lw=0, marker="o", ms=2.5, markevery=5)),
]


def read_curve(path):
    """Columns of a fe-check CSV (sffcal.runfile.read_csv_table), None where it is absent."""
    if not os.path.exists(path):
        return None
    return read_csv_table(path) or None


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("folder", help="output folder of sffcal fe-check")
    parser.add_argument("-o", "--output", help="PNG to write")
    args = parser.parse_args()

    cases = sorted(
        d for d in os.listdir(args.folder)
        if os.path.isdir(os.path.join(args.folder, d))
        and os.path.exists(os.path.join(args.folder, d, "element.csv")))
    if not cases:
        sys.exit(f"plot_fe_check.py: no case folders with element.csv in {args.folder}")

    fig, axes = plt.subplots(len(cases), 3, figsize=(13, 3.3 * len(cases)), squeeze=False)
    for row, case in enumerate(cases):
        ax_eta, ax_ev, ax_f = axes[row]
        for label, name, style in SOURCES:
            c = read_curve(os.path.join(args.folder, case, name))
            if c is None:
                continue
            ea = c["axial_strain"]
            ax_eta.plot(ea, c["eta"], label=label, **style)
            ax_ev.plot(ea, c["volumetric_strain"], label=label, **style)
            if label != "DEM":
                ax_f.plot(ea, c["fabric_invariant"], label=label, **style)
        fabric = read_curve(os.path.join(args.folder, case, "dem_fabric.csv"))
        if fabric is not None:
            ax_f.plot(fabric["axial_strain"], fabric["fabric_invariant"], "s", color="0.4", ms=4,
                      label="DEM A:n_c / a_cs")
        ax_eta.set_ylabel("q/p")
        ax_ev.set_ylabel("volumetric strain (compression +)")
        ax_f.set_ylabel("fabric F:n_c")
        ax_eta.set_title(case, loc="left", fontsize=10)
        for ax in (ax_eta, ax_ev, ax_f):
            ax.set_xlabel("axial strain")
            ax.grid(alpha=0.3)
        ax_eta.legend(fontsize=8)
        ax_f.legend(fontsize=8)
    fig.suptitle("sffcal fe-check: FE element / mesh, material-point driver, DEM", fontsize=11)
    fig.tight_layout()
    output = args.output or os.path.join(args.folder, "fe_check.png")
    fig.savefig(output, dpi=110)
    print(f"wrote {output}")


if __name__ == "__main__":
    main()
