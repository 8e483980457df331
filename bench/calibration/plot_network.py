#!/usr/bin/python3
"""Plots the contact-network model's predictions (network_paper_fit --out DIR) against the DEM's
committed reduced runs: q/p, volumetric strain, Z, Lambda, a_c, a_n, a_t against axial strain.

usage: plot_network.py DIR NAME... -o OUT.png
"""
import argparse
import csv
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

REFERENCE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "reference")


def read(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return {k: [float(r[k]) for r in rows] for k in rows[0]}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("folder")
    ap.add_argument("names", nargs="+")
    ap.add_argument("-o", "--output", required=True)
    args = ap.parse_args()
    panels = [("eta", "q/p", "eta", "series"), ("volumetric_strain", "volumetric strain",
              "volumetric_strain", "series"), ("coordination", "Z", "coordination", "sff"),
              ("lambda", "Lambda", "lambda", "sff"), ("a_c", "a_c", "a_c", "sff"),
              ("a_n", "a_n", "a_n", "sff"), ("a_t", "a_t", "a_t", "sff")]
    fig, axes = plt.subplots(2, 4, figsize=(16, 7.5))
    for i, name in enumerate(args.names):
        colour = "C%d" % i
        model = read(os.path.join(args.folder, name + "_network.csv"))
        dem = {"series": read(os.path.join(REFERENCE, name + "_series.csv")),
               "sff": read(os.path.join(REFERENCE, name + "_sff.csv"))}
        for ax, (column, label, dem_column, table) in zip(axes.flat, panels):
            ax.plot(model["axial_strain"], model[column], "-", color=colour, label=name)
            d = dem[table]
            ax.plot(d["axial_strain"], d[dem_column], ".", color=colour, ms=3)
            ax.set_xlabel("axial strain")
            ax.set_ylabel(label)
    axes.flat[-1].axis("off")
    axes.flat[0].legend(fontsize=8)
    fig.suptitle("contact-network model (lines) against the DEM (points)")
    fig.tight_layout()
    if os.path.exists(args.output):
        raise SystemExit("%s exists (not overwritten)" % args.output)
    fig.savefig(args.output, dpi=80)


if __name__ == "__main__":
    main()
