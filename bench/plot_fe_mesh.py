#!/usr/bin/python3
"""Plots the mesh-level drained triaxial tests of bench/fe_mesh (docs/fe.md, "Rough platens"):
q/p and volumetric strain against axial strain for smooth and rough platens, and the radial
displacement of the outer face against height at the last step (the bulge). Compression positive.

    bench/plot_fe_mesh.py OUT_FOLDER [-o PNG]      (default PNG: OUT_FOLDER/fe_mesh.png)
"""
import argparse
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from sffcal.runfile import read_csv_table  # noqa: E402

CASES = [("smooth", "smooth platens (homogeneous)", dict(color="C0", lw=2.4, alpha=0.7)),
         ("rough", "rough platens", dict(color="C3", lw=1.4))]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("folder", help="output folder of bench/fe_mesh (-o)")
    parser.add_argument("-o", "--output", help="PNG to write")
    args = parser.parse_args()
    output = args.output or os.path.join(args.folder, "fe_mesh.png")
    fig, axes = plt.subplots(1, 3, figsize=(13, 3.8))
    for name, label, style in CASES:
        curve_path = os.path.join(args.folder, name + ".csv")
        if not os.path.exists(curve_path):
            continue
        c = read_csv_table(curve_path)
        # q/p from the platen force, as a laboratory measures it: q = F/A - sigma_3 (the volume
        # average of sigma_zz is F/A), p = sigma_3 + q/3; sigma_3 = the initial radial stress.
        sigma_3 = c["radial_stress"][0]
        q_platen = c["axial_stress"] - sigma_3
        axes[0].plot(100 * c["axial_strain"], q_platen / (sigma_3 + q_platen / 3), label=label,
                     **style)
        if name == "rough":
            axes[0].plot(100 * c["axial_strain"], c["q"] / c["p"], color="C3", lw=1.0, ls=":",
                         label="rough, from volume averages")
        axes[1].plot(100 * c["axial_strain"], 100 * c["volumetric_strain"], label=label, **style)
        b = read_csv_table(os.path.join(args.folder, name + "_bulge.csv"))
        axes[2].plot(1e3 * b["radial_displacement"], 1e3 * b["z"], marker="o", ms=3, label=label,
                     **style)
    axes[0].set(xlabel="axial strain [%]", ylabel="q/p (platen force)")
    axes[1].set(xlabel="axial strain [%]", ylabel="volumetric strain [%] (compression +)")
    axes[2].set(xlabel="radial displacement of the outer face [mm]",
                ylabel="height above mid-height [mm]", title="at the last step")
    for ax in axes:
        ax.grid(alpha=0.3)
    axes[0].legend(loc="lower right")
    fig.tight_layout()
    fig.savefig(output, dpi=130)
    print(output)


if __name__ == "__main__":
    main()
