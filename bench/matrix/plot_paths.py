#!/usr/bin/python3
"""The loading paths of the reference matrix (issue 18): stress paths, q/p and volumetric strain
against axial strain, and a Markdown table with the extension-to-compression ratio M_e/M_c; with
--sff-png, the SFF decomposition of q/p of every path (one panel per run) and its table at the
peak and at the end.

usage: plot_paths.py PATHS_FOLDER DRAINED_FOLDER OUT_PNG [--sff-png SFF_PNG]

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

from sffcal import runfile  # noqa: E402
from sffcal.sff_plots import decomposition_terms, draw_decomposition  # noqa: E402


def read(path):
    with h5py.File(path, "r") as f:
        run = runfile.series(f, ["axial_strain", "volumetric_strain", "p", "q", "eta", "void_ratio"])
        run["path"] = runfile.loading_path(f)
        run["ended"] = runfile.summary(f).get("ended", "?")
        run["e0"] = run["void_ratio"][0]
        run["mu"] = runfile.friction(f) if "physics" in f else None
        if "analysis/sff" in f:
            run["sff"] = runfile.table(f, "sff")
    run["name"] = runfile.name_of(path)
    last = runfile.end_window(run["axial_strain"])
    run["final_eta"] = float(np.mean(run["eta"][last]))
    k = int(np.argmax(np.abs(run["eta"]) * (run["p"] > 0.01 * run["p"][0])))
    run["peak"] = (float(run["eta"][k]), float(run["axial_strain"][k]))
    return run


def plot_decompositions(runs, png):
    """One panel per run: q/p and its SFF terms against axial strain; and the Markdown table of
    the terms at the peak of |q/p| and at the last snapshot."""
    runs = [run for run in runs if "sff" in run and run["mu"] is not None]
    columns = 5
    rows = (len(runs) + columns - 1) // columns
    fig, axes = plt.subplots(rows, columns, figsize=(4 * columns, 3.4 * rows), squeeze=False)
    for ax, run in zip(axes.flat, runs):
        sff = run["sff"]
        held = sff["p"] >= 0.01 * run["p"][0]  # a liquefied specimen's terms are noise
        ax.set_title(f"{run['name']}\n({run['path']})", fontsize=9)
        if np.count_nonzero(held) < 2:
            ax.text(0.5, 0.5, "liquefied before its\nfirst sheared snapshot", ha="center",
                    va="center", transform=ax.transAxes)
            ax.axis("off")
            continue
        draw_decomposition(ax, {k: v[held] for k, v in sff.items()}, run["mu"], legend=False)
    for ax in list(axes.flat)[len(runs):]:
        ax.axis("off")
    handles, labels = axes[0, 0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=6, fontsize=8)
    fig.tight_layout(rect=(0, 0.04, 1, 1))
    fig.savefig(png, dpi=100)

    print("| test | snapshot | ε_a | q/p | (2/5) a_c | (2/5) a_n | (3/5) μ m | η decoupled | η_SFF |")
    print("|---|---|---|---|---|---|---|---|---|")
    for run in runs:
        sff = run["sff"]
        held = np.flatnonzero(sff["p"] >= 0.01 * run["p"][0])
        if len(held) < 2:
            print(f"| {run['name']} | — | | | | | | | liquefied before its first sheared snapshot |")
            continue
        peak = held[np.argmax(np.abs(sff["eta"][held]))]
        fabric, force, mobilisation = decomposition_terms(sff, run["mu"])
        for label, k in (("peak", peak), ("last", held[-1])):
            print(f"| {run['name']} | {label} | {100 * sff['axial_strain'][k]:.1f} % | {sff['eta'][k]:.3f} | "
                  f"{fabric[k]:.3f} | {force[k]:.3f} | {mobilisation[k]:.3f} | "
                  f"{sff['eta_decoupled'][k]:.3f} | {sff['eta_sff'][k]:.3f} |")
    print()


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("paths")
    parser.add_argument("drained")
    parser.add_argument("png")
    parser.add_argument("--sff-png", help="also the SFF decomposition of each path, as this PNG and a table")
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
    if args.sff_png:
        plot_decompositions(runs, args.sff_png)

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
