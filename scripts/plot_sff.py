#!/usr/bin/python3
"""Plots of the SFF analysis written by `sffcal sff` into run files.

usage: plot_sff.py RUN.h5 [RUN.h5 ...] [-o FOLDER] [--mu MU]

For each run: <stem>_eta.png (the stress ratio against axial strain with its SFF decomposition:
fabric (2/5)a_c, normal force (2/5)a_n, mobilisation (3/5)mu m) and <stem>_rose.png (rose
diagrams of the contact-normal density and the mean normal force in the Y-Z plane at the initial,
peak and last snapshots). For all runs together: anisotropy.png (a_c, a_n and m against axial
strain; with tables written since issue 18, a second row in the Guo & Zhao (2013) convention:
a_n of the raw normal force, the branch-length anisotropy a_l and a_t). Needs python3-h5py and
python3-matplotlib (Debian).
"""
import argparse
import os
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from sffcal.runfile import RunFileError, friction, table  # noqa: E402
from sffcal.sff_plots import draw_decomposition  # noqa: E402


def plot_eta(run, sff, mu, path):
    fig, ax = plt.subplots(figsize=(7, 4.5))
    ax.plot(100 * sff["axial_strain"], sff["wall_eta"], "k:", label="eta, walls")
    if "eta_gz" in sff:
        ax.plot(100 * sff["axial_strain"], sff["eta_gz"], "g:", label="eta, Guo & Zhao first order")
    draw_decomposition(ax, sff, mu)
    ax.set_title(f"{run}: SFF decomposition of the stress ratio")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def plot_rose(run, sff, rose, path):
    snapshots = rose["snapshot"].astype(int)
    peak = int(sff["snapshot"][np.argmax(np.abs(sff["eta"]))])  # extension: the most negative
    chosen = [("initial", int(sff["snapshot"][0])), ("peak", peak), ("last", int(sff["snapshot"][-1]))]
    fig, axes = plt.subplots(2, 3, subplot_kw={"projection": "polar"}, figsize=(10, 6.5))
    for column, (label, k) in enumerate(chosen):
        rows = snapshots == k
        low, high = np.radians(rose["psi_low_deg"][rows]), np.radians(rose["psi_high_deg"][rows])
        width = high - low
        strain = 100 * rose["axial_strain"][rows][0]
        for row, (key, name) in enumerate([("fraction", "contact normals"), ("normal_force", "mean f_n")]):
            ax = axes[row, column]
            value = rose[key][rows]
            if key == "fraction":
                value = value / width / 2  # density per radian over the full circle (psi and psi + pi)
            for shift in (0.0, np.pi):  # n and -n: the rose is symmetric
                ax.bar(low + shift, value, width=width, align="edge", color="C0" if row == 0 else "C3",
                       edgecolor="k", linewidth=0.3)
            ax.set_title(f"{name}, {label} ({strain:.1f} %)", fontsize=9)
            ax.set_xticks(np.radians([0, 90, 180, 270]))
            ax.set_xticklabels(["+y", "+z (load)", "-y", "-z"], fontsize=7)
            ax.set_yticklabels([])
    fig.suptitle(f"{run}: rose diagrams in the Y-Z plane")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


ANISOTROPY_PANELS = [("a_c", "fabric a_c"), ("a_n", "normal force a_n (f l)"), ("m", "mobilisation m")]
GUO_ZHAO_PANELS = [("a_n_gz", "normal force a_n, Guo & Zhao"), ("a_l", "branch length a_l"),
                   ("a_t_gz", "tangential force a_t, Guo & Zhao")]


def plot_anisotropy(curves, path):
    rows = [ANISOTROPY_PANELS]
    if all("a_n_gz" in sff for _, sff in curves):
        rows.append(GUO_ZHAO_PANELS)
    fig, axes = plt.subplots(len(rows), 3, figsize=(12, 3.8 * len(rows)), sharex=True, squeeze=False)
    for run, sff in curves:
        eps = 100 * sff["axial_strain"]
        for panels, row in zip(rows, axes):
            for ax, (key, _) in zip(row, panels):
                ax.plot(eps, sff[key], "-o", ms=3, label=run)
    for panels, row in zip(rows, axes):
        for ax, (_, title) in zip(row, panels):
            ax.set_xlabel("axial strain [%]")
            ax.set_title(title)
            ax.grid(alpha=0.3)
    axes[0, 0].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("runs", nargs="+")
    parser.add_argument("-o", "--output", default=None, help="folder for the PNGs (default: beside the first run)")
    args = parser.parse_args()
    folder = args.output or os.path.dirname(os.path.abspath(args.runs[0]))
    os.makedirs(folder, exist_ok=True)
    curves = []
    for path in args.runs:
        run = os.path.splitext(os.path.basename(path))[0]
        with h5py.File(path, "r") as f:
            try:
                sff, rose, mu = table(f, "sff"), table(f, "sff_rose"), friction(f)
            except RunFileError as e:
                sys.exit(str(e))
        if len(sff["eta"]) == 0:
            sys.exit(f"{path}: the SFF table is empty")
        plot_eta(run, sff, mu, os.path.join(folder, f"{run}_eta.png"))
        plot_rose(run, sff, rose, os.path.join(folder, f"{run}_rose.png"))
        curves.append((run, sff))
        print(f"{run}: {run}_eta.png, {run}_rose.png")
    plot_anisotropy(curves, os.path.join(folder, "anisotropy.png"))
    print(f"plots in {folder}")


if __name__ == "__main__":
    main()
