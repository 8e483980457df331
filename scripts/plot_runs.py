#!/usr/bin/python3
"""Overview of several triaxial run files in one figure: q/p (walls), volumetric strain and void
ratio against axial strain, one line per run; the runs listed after --held-back (not fitted by the
calibration) dashed.

usage: plot_runs.py RUN.h5 [...] -o OUT.png [--held-back RUN.h5 ...]
"""
import argparse

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from sffcal import runfile  # noqa: E402


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("runs", nargs="+")
    parser.add_argument("-o", "--output", required=True)
    parser.add_argument("--held-back", nargs="*", default=[])
    args = parser.parse_args()
    fig, axes = plt.subplots(1, 3, figsize=(14, 4.2))
    for k, path in enumerate(args.runs + args.held_back):
        with h5py.File(path, "r") as f:
            s = runfile.series(f, ["axial_strain", "eta", "volumetric_strain", "void_ratio"])
        eps_a, eta = 100 * s["axial_strain"], s["eta"]
        eps_v, e = 100 * s["volumetric_strain"], s["void_ratio"]
        style = dict(color=f"C{k}", ls="--" if path in args.held_back else "-", lw=1.2)
        label = runfile.name_of(path) + (" (held back)" if path in args.held_back else "")
        axes[0].plot(eps_a, eta, label=label, **style)
        axes[1].plot(eps_a, eps_v, **style)
        axes[2].plot(eps_a, e, **style)
    for ax, label in zip(axes, ["q/p (walls)", "volumetric strain [%] (compression +)", "void ratio"]):
        ax.set_xlabel("axial strain [%]")
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(args.output, dpi=110)


if __name__ == "__main__":
    main()
