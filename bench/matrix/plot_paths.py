#!/usr/bin/python3
"""The loading paths of the reference matrix (issue 18): stress paths, q/p and volumetric strain
against axial strain, and a Markdown table with the extension-to-compression ratio M_e/M_c.

usage: plot_paths.py PATHS_FOLDER DRAINED_FOLDER OUT_PNG

PATHS_FOLDER holds the reduced runs of the other paths (und_*, ext_*, tt_*, dep_*_ext),
DRAINED_FOLDER the drained compression runs of the same specimens (iso_dense_100kPa, ...).
M is taken as the mean q/p over the last 5 % of |axial strain| of each run: a final-window value,
the critical state where the run reached it (the table says which).
"""
import argparse
import glob
import os

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def read(path):
    with h5py.File(path, "r") as f:
        s = f["series"]
        run = {k: s[k][()] for k in ("axial_strain", "volumetric_strain", "p", "q", "eta")}
        run["path"] = f["loading"].attrs["path"] if "loading" in f else "drained_compression"
        run["ended"] = f["summary"].attrs["ended"] if "summary" in f else "?"
        run["e0"] = s["void_ratio"][0]
    run["name"] = os.path.basename(path)[:-3]
    strain = np.abs(run["axial_strain"])
    last = strain >= strain[-1] - 0.05
    run["final_eta"] = float(np.mean(run["eta"][last]))
    k = int(np.argmax(np.abs(run["eta"]) * (run["p"] > 0.01 * run["p"][0])))
    run["peak"] = (float(run["eta"][k]), float(run["axial_strain"][k]))
    return run


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("paths")
    parser.add_argument("drained")
    parser.add_argument("png")
    args = parser.parse_args()
    runs = [read(p) for p in sorted(glob.glob(os.path.join(args.paths, "*.h5")))]
    drained = {os.path.basename(p)[:-3]: read(p)
               for p in sorted(glob.glob(os.path.join(args.drained, "iso_*_[12]00kPa.h5")))
               if "medium" not in p}

    fig, axes = plt.subplots(1, 3, figsize=(15, 4.6))
    for run in list(drained.values()) + runs:
        style = "--" if run["path"] == "drained_compression" else "-"
        label = f"{run['name']} ({run['path']})"
        axes[0].plot(run["p"] / 1e3, run["q"] / 1e3, style, lw=1, label=label)
        held = run["p"] >= 0.01 * run["p"][0]  # a liquefied specimen's q/p is noise
        axes[1].plot(run["axial_strain"][held], run["eta"][held], style, lw=1)
        axes[2].plot(run["axial_strain"], run["volumetric_strain"], style, lw=1)
    axes[0].set(xlabel="p [kPa]", ylabel="q = σz − (σx + σy)/2 [kPa]", title="stress paths")
    axes[1].set(xlabel="axial strain ε_a (< 0: extension)", ylabel="q/p", title="stress ratio (where p ≥ 0.01 p0)")
    axes[2].set(xlabel="axial strain ε_a", ylabel="volumetric strain ε_v (compression > 0)",
                title="volume")
    axes[0].set_xscale("log")
    for ax in axes:
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=6, loc="lower left")
    fig.tight_layout()
    fig.savefig(args.png, dpi=110)

    print("| test | path | e0 | peak q/p (ε_a) | final q/p | final p/p0 | final ε_v | ended |")
    print("|---|---|---|---|---|---|---|---|")
    for run in runs:
        print(f"| {run['name']} | {run['path']} | {run['e0']:.3f} | {run['peak'][0]:.3f} "
              f"({100 * run['peak'][1]:.1f} %) | {run['final_eta']:.3f} | "
              f"{run['p'][-1] / run['p'][0]:.3f} | {run['volumetric_strain'][-1]:.4f} | {run['ended']} |")
    print()
    print("| specimen | M_c (drained compression) | M_e (drained extension) | M_e/M_c |")
    print("|---|---|---|---|")
    for run in runs:
        if not run["name"].startswith("ext_"):
            continue
        compression = drained.get("iso_" + run["name"][4:])
        if compression is None:
            continue
        m_c, m_e = compression["final_eta"], -run["final_eta"]
        print(f"| {run['name'][4:]} | {m_c:.3f} | {m_e:.3f} | {m_e / m_c:.3f} |")


if __name__ == "__main__":
    main()
