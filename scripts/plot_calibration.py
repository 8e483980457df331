#!/usr/bin/python3
"""Plots of the calibration: model against DEM for every test.

Usage: scripts/plot_calibration.py OUT_FOLDER [-o PNG_FOLDER]

Reads OUT_FOLDER/<test>_curves.csv and <test>_fabric.csv (written by `sffcal calibrate`) and
writes <test>_calibration.png (q/p, volumetric strain, void ratio and a_c against axial strain,
DEM as points, model as lines) into PNG_FOLDER (default OUT_FOLDER).
"""
import argparse
import glob
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from sffcal.runfile import read_csv_table  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("folder", help="output folder of sffcal calibrate")
    parser.add_argument("-o", "--output", help="folder for the PNG files (default: folder)")
    args = parser.parse_args()
    out = args.output or args.folder
    os.makedirs(out, exist_ok=True)
    curves = sorted(glob.glob(os.path.join(args.folder, "*_curves.csv")))
    if not curves:
        raise SystemExit(f"no *_curves.csv in {args.folder}")
    for path in curves:
        name = os.path.basename(path)[: -len("_curves.csv")]
        c = read_csv_table(path)
        fabric_path = os.path.join(args.folder, name + "_fabric.csv")
        f = read_csv_table(fabric_path) if os.path.exists(fabric_path) else {}
        fig, axes = plt.subplots(2, 2, figsize=(10, 7.5), sharex=True)
        ea = [100 * x for x in c["axial_strain"]]
        panels = [
            (axes[0, 0], "eta", "q/p", 1.0),
            (axes[0, 1], "volumetric_strain", "volumetric strain [%] (compression +)", 100.0),
            (axes[1, 0], "void_ratio", "void ratio", 1.0),
        ]
        for ax, key, label, scale in panels:
            ax.plot(ea, [scale * v for v in c["dem_" + key]], "o", ms=3, color="0.45", label="DEM")
            ax.plot(ea, [scale * v for v in c["model_" + key]], "-", color="C0", label="model")
            ax.set_ylabel(label)
            ax.grid(alpha=0.3)
        ax = axes[1, 1]
        if f:
            fa = [100 * x for x in f["axial_strain"]]
            ax.plot(fa, f["dem_a_c"], "s", ms=5, color="0.45", label="DEM")
            ax.plot(fa, f["model_a_c"], "-o", ms=3, color="C3", label="model a_cs (F_zz - F_xx)")
        ax.set_ylabel("fabric anisotropy a_c")
        ax.grid(alpha=0.3)
        for ax in axes[1]:
            ax.set_xlabel("axial strain [%]")
        axes[0, 0].legend()
        axes[1, 1].legend()
        fig.suptitle(f"{name}: ACST model against DEM")
        fig.tight_layout()
        png = os.path.join(out, name + "_calibration.png")
        fig.savefig(png, dpi=120)
        plt.close(fig)
        print(png)


if __name__ == "__main__":
    main()
