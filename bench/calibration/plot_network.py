#!/usr/bin/python3
"""Plots the contact-network model's predictions (`sffcal calibrate --model network -o DIR`, or
bench/calibration/network_fit --out DIR) against the DEM:
q/p, volumetric strain, Z, Lambda, a_c, a_n, a_t and p/p0 against axial strain (p/p0: each mean
stress over its own start, as the fit compares them; the model's is the contacts' SFF stress, the
DEM's the walls'; a_n: the DEM's that the fit followed as dots, closing the SFF equation on the
contacts' q/p, and sff's measured one as rings). A test is a committed
paper-size CSV pair by name (bench/reference/NAME_series.csv, NAME_sff.csv) or a run file (.h5).

usage: plot_network.py DIR TEST... -o OUT.png
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


def read_dem(test):
    """The DEM's series and SFF table of a test, each as {column: values}."""
    if test.endswith(".h5"):
        import h5py
        with h5py.File(test, "r") as f:
            return {"series": {k: f["series"][k][()] for k in f["series"]},
                    "sff": {k: f["analysis/sff"][k][()] for k in f["analysis/sff"]}}
    return {"series": read(os.path.join(REFERENCE, test + "_series.csv")),
            "sff": read(os.path.join(REFERENCE, test + "_sff.csv"))}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("folder")
    ap.add_argument("tests", nargs="+")
    ap.add_argument("-o", "--output", required=True)
    args = ap.parse_args()
    panels = [("eta", "q/p", "eta", "series"), ("volumetric_strain", "volumetric strain",
              "volumetric_strain", "series"), ("coordination", "Z", "coordination", "sff"),
              ("lambda", "Lambda", "lambda", "sff"), ("a_c", "a_c", "a_c", "sff"),
              ("a_n", "a_n", "a_n", "sff"), ("a_t", "a_t", "a_t", "sff")]
    fig, axes = plt.subplots(2, 4, figsize=(16, 7.5))
    for i, test in enumerate(args.tests):
        colour = "C%d" % i
        name = os.path.basename(test).split(".")[0]  # the run file's stem, as network_fit names it
        model = read(os.path.join(args.folder, name + "_network.csv"))
        dem = read_dem(test)
        for ax, (column, label, dem_column, table) in zip(axes.flat, panels):
            ax.plot(model["axial_strain"], model[column], "-", color=colour, label=name)
            d = dem[table]
            if column == "a_n" and "dem_a_n" in model:
                # The a_n the fit followed (closing the SFF equation on the contacts' q/p), and
                # sff's measured one hollow.
                ax.plot(d["axial_strain"], d[dem_column], "o", mfc="none", color=colour, ms=3)
                at = [(x, y) for x, y in zip(model["axial_strain"], model["dem_a_n"]) if y == y]
                ax.plot([x for x, _ in at], [y for _, y in at], ".", color=colour, ms=5)
            else:
                ax.plot(d["axial_strain"], d[dem_column], ".", color=colour, ms=3)
            ax.set_xlabel("axial strain")
            ax.set_ylabel(label)
        ax = axes.flat[-1]
        ax.plot(model["axial_strain"], [p / model["p"][0] for p in model["p"]], "-", color=colour)
        s = dem["series"]
        ax.plot(s["axial_strain"], [p / s["p"][0] for p in s["p"]], ".", color=colour, ms=3)
        ax.set_xlabel("axial strain")
        ax.set_ylabel("p/p0")
    axes.flat[0].legend(fontsize=8)
    fig.suptitle("contact-network model (lines) against the DEM (points)")
    fig.tight_layout()
    if os.path.exists(args.output):
        raise SystemExit("%s exists (not overwritten)" % args.output)
    fig.savefig(args.output, dpi=80)


if __name__ == "__main__":
    main()
