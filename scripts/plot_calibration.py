#!/usr/bin/python3
"""Plots of the calibration: model against DEM for every test.

Usage: scripts/plot_calibration.py OUT_FOLDER [-o PNG_FOLDER]

Reads OUT_FOLDER/<test>_curves.csv and <test>_fabric.csv (written by `sffcal calibrate`) and
writes <test>_calibration.png (q/p, volumetric strain, void ratio, p/p0 and a_c against axial
strain, and the effective stress path q/p0 against p/p0; DEM as points, model as lines) into
PNG_FOLDER (default OUT_FOLDER). DEM q/p is left out where p < 0.05 p0 (a liquefied specimen: the
fit does not use it either, docs/calibration.md).
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
        fig, axes = plt.subplots(2, 3, figsize=(14, 7.5))
        ea = [100 * x for x in c["axial_strain"]]
        has_p = "dem_p_Pa" in c  # written since the undrained paths (issue 19)
        p0 = c["dem_p_Pa"][0] if has_p else 1.0
        liquefied = [has_p and p < 0.05 * p0 for p in (c["dem_p_Pa"] if has_p else ea)]
        dem_eta = [float("nan") if gone else v for v, gone in zip(c["dem_eta"], liquefied)]
        panels = [
            (axes[0, 0], dem_eta, c["model_eta"], "q/p"),
            (axes[0, 1], [100 * v for v in c["dem_volumetric_strain"]],
             [100 * v for v in c["model_volumetric_strain"]], "volumetric strain [%] (compression +)"),
            (axes[1, 0], c["dem_void_ratio"], c["model_void_ratio"], "void ratio"),
        ]
        if has_p:
            panels.append((axes[0, 2], [v / p0 for v in c["dem_p_Pa"]],
                           [v / p0 for v in c["model_p_Pa"]], "p / p0"))
        for ax, dem, model, label in panels:
            ax.plot(ea, dem, "o", ms=3, color="0.45", label="DEM")
            ax.plot(ea, model, "-", color="C0", label="model")
            ax.set_ylabel(label)
            ax.set_xlabel("axial strain [%]")
            ax.grid(alpha=0.3)
        if max(abs(v) for v in c["dem_volumetric_strain"]) < 1e-9:  # undrained: 0 to rounding
            axes[0, 1].set_ylim(-1.0, 1.0)
        ax = axes[1, 2]
        if has_p:  # the effective stress path, q = (q/p) p
            for key, style, color, label in (("dem", "o", "0.45", "DEM"), ("model", "-", "C0", "model")):
                pp = [v / p0 for v in c[key + "_p_Pa"]]
                ax.plot(pp, [e * v for e, v in zip(c[key + "_eta"], pp)], style, ms=3, color=color,
                        label=label)
            ax.set_xlabel("p / p0")
            ax.set_ylabel("q / p0")
            ax.grid(alpha=0.3)
        else:
            ax.axis("off")
        ax = axes[1, 1]
        if f:
            fa = [100 * x for x in f["axial_strain"]]
            ax.plot(fa, f["dem_a_c"], "s", ms=5, color="0.45", label="DEM")
            ax.plot(fa, f["model_a_c"], "-o", ms=3, color="C3", label="model a_cs (F_zz - F_xx)")
        ax.set_ylabel("fabric anisotropy a_c")
        ax.set_xlabel("axial strain [%]")
        ax.grid(alpha=0.3)
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
