"""Plots q/p, the volumetric strain and the void ratio against the axial strain of a triaxial run
file (the main job's triaxial stage, bench/reference/).

usage: python3 -m sffcal.plot_triaxial RUN.h5 OUT.png
Uses Debian's python3-h5py and python3-matplotlib.
"""
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from sffcal import runfile  # noqa: E402


def main(run_path, png_path):
    with h5py.File(run_path, "r") as f:
        s = runfile.series(f, ["axial_strain", "eta", "contact_q", "contact_p", "volumetric_strain",
                               "void_ratio"])
        summary = runfile.summary(f) or runfile.ended(f)  # schema 2 attributes, or schema 1's note
    eps_a, eta, e = s["axial_strain"] * 100.0, s["eta"], s["void_ratio"]
    eta_c = s["contact_q"] / s["contact_p"]
    eps_v = s["volumetric_strain"] * 100.0
    fig, axes = plt.subplots(1, 3, figsize=(13, 4))
    axes[0].plot(eps_a, eta, label="walls")
    axes[0].plot(eps_a, eta_c, "--", label="contacts (Love-Weber)")
    axes[0].set_xlabel("axial strain [%]")
    axes[0].set_ylabel("q/p")
    axes[0].legend()
    axes[1].plot(eps_a, eps_v)
    axes[1].set_xlabel("axial strain [%]")
    axes[1].set_ylabel("volumetric strain [%] (compression +)")
    axes[2].plot(eps_a, e)
    axes[2].set_xlabel("axial strain [%]")
    axes[2].set_ylabel("void ratio")
    for ax in axes:
        ax.grid(alpha=0.3)
    fig.suptitle(run_path, fontsize=9)
    fig.tight_layout()
    fig.savefig(png_path, dpi=110)
    print(f"wrote {png_path}")
    if summary:
        print(summary)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
