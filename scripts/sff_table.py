#!/usr/bin/python3
"""Markdown table of the SFF results of several runs, one row per test.

usage: sff_table.py RUN.h5|RUN.sff.csv [...]

Reads each run's SFF table (/analysis/sff of a run file, or the <run>.sff.csv that `sffcal sff`
writes) and prints: e0, the peak and last stress ratio with a_c, a_n, m, the last void ratio, the worst SFF stress
error, the worst |eta_SFF - eta| / eta (eta > 0.3) and the worst particle-form-vs-wall stress
difference.
"""
import csv
import os
import sys

import numpy as np


def load(path):
    if path.endswith(".csv"):
        with open(path) as f:
            rows = list(csv.DictReader(f))
        return {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}
    import h5py

    with h5py.File(path, "r") as f:
        if "analysis/sff" not in f:
            sys.exit(f"{path}: no /analysis/sff; run `sffcal sff {path}` first")
        g = f["analysis/sff"]
        return {k: g[k][()] for k in g}


def name_of(path):
    base = os.path.basename(path)
    for suffix in (".sff.csv", ".h5", ".csv"):
        if base.endswith(suffix):
            return base[: -len(suffix)]
    return base


def main(paths):
    print("| test | e0 | peak η (ε_a) | a_c, a_n, m at peak | last η (ε_a) | a_c, a_n, m at last | last e | "
          "max ‖σ_SFF−σ‖/‖σ‖ | max \\|η_SFF−η\\|/η | max \\|σ−σ_walls\\|/p |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for path in paths:
        t = load(path)
        k, last = int(np.argmax(t["eta"])), len(t["eta"]) - 1
        sheared = t["eta"] > 0.3
        eta_error = np.max(np.abs(t["eta_sff"] - t["eta"])[sheared] / t["eta"][sheared]) if sheared.any() else 0.0
        wall = np.max(t["wall_stress_error"]) if "wall_stress_error" in t else float("nan")
        print(f"| {name_of(path)} | {t['void_ratio'][0]:.3f} | {t['eta'][k]:.3f} ({100 * t['axial_strain'][k]:.1f} %) | "
              f"{t['a_c'][k]:.2f}, {t['a_n'][k]:.2f}, {t['m'][k]:.2f} | "
              f"{t['eta'][last]:.3f} ({100 * t['axial_strain'][last]:.1f} %) | "
              f"{t['a_c'][last]:.2f}, {t['a_n'][last]:.2f}, {t['m'][last]:.2f} | {t['void_ratio'][last]:.3f} | "
              f"{100 * np.max(t['sff_error']):.1f} % | {100 * eta_error:.1f} % | {100 * wall:.2f} % |")


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    main(sys.argv[1:])
