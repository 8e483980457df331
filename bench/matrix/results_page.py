#!/usr/bin/python3
"""Tables and figures of the reference matrix for docs/reference-matrix.md (issue 7).

usage: results_page.py [FOLDER=tests/data/reference/matrix] [--img docs/img/matrix]

Reads the reduced run files (reduce_matrix.py) and prints Markdown: the per-test table of
the table of sffcal.sff_table (snapshots: e0, peak and last q/p, a_c, a_n, m, last e, SFF errors), then the
influence of the initial void ratio, the confining pressure and the loading angle on the
stress ratio and the anisotropies, as least-squares slopes with their standard errors. Here the
peak is the largest wall q/p of the series (every 0.2 % of axial strain), with a_c, a_n, m from
the snapshot nearest to it (snapshots every 2.5 %); the end values are q/p averaged over the
last 5 % of axial strain and the anisotropies of the last snapshot.
"""
import argparse
import glob
import os

import h5py
import numpy as np

from sffcal import runfile, sff_table


def load(path):
    with h5py.File(path, "r") as f:
        s = runfile.series(f, ["axial_strain", "eta", "void_ratio", "volumetric_strain"])
        a = runfile.table(f, "sff", ["axial_strain", "a_c", "a_n", "a_t", "m", "eta"])
        ended = runfile.ended(f)
    name = runfile.name_of(path)
    peak = int(np.argmax(s["eta"]))
    near = int(np.argmin(np.abs(a["axial_strain"] - s["axial_strain"][peak])))
    end = runfile.end_window(s["axial_strain"])
    kind, density = name.split("_")[:2]
    pressure = float(name.split("_")[2][:-3]) if kind == "iso" else 100.0
    angle = float(name.split("_a")[-1]) if kind == "dep" else None
    return {"name": name, "kind": kind, "density": density, "pressure": pressure, "angle": angle,
            "e0": s["void_ratio"][0], "peak_eta": s["eta"][peak], "peak_strain": s["axial_strain"][peak],
            "peak_snapshot_strain": a["axial_strain"][near],
            "end_strain": s["axial_strain"][-1], "end_eta": s["eta"][end].mean(), "end_e": s["void_ratio"][end].mean(),
            "peak_ac": a["a_c"][near], "peak_an": a["a_n"][near], "peak_m": a["m"][near],
            "end_ac": a["a_c"][-1], "end_an": a["a_n"][-1], "end_m": a["m"][-1],
            "ac0": a["a_c"][0], "series": s, "sff": a,
            "ended": ended}


def series_table(runs):
    """The stress ratio and void ratio from the series (finer than the snapshots)."""
    print("\n| test | e0 | peak q/p (walls) | at ε_a | q/p at end (last 5 %) | e at end | how the run ended |")
    print("|---|---|---|---|---|---|---|")
    for r in runs:
        print(f"| {r['name']} | {r['e0']:.3f} | {r['peak_eta']:.3f} | {100 * r['peak_strain']:.1f} % | "
              f"{r['end_eta']:.3f} | {r['end_e']:.3f} | {r['ended']} |")


def slope(x, y):
    """Least-squares slope and its standard error."""
    x, y = np.asarray(x, float), np.asarray(y, float)
    A = np.vstack([x, np.ones_like(x)]).T
    coef, res, *_ = np.linalg.lstsq(A, y, rcond=None)
    dof = len(x) - 2
    sigma2 = (res[0] / dof) if dof > 0 and len(res) else float("nan")
    se = np.sqrt(sigma2 / np.sum((x - x.mean()) ** 2)) if dof > 0 else float("nan")
    return coef[0], se


def influences(runs):
    iso = [r for r in runs if r["kind"] == "iso"]
    dep = [r for r in runs if r["kind"] == "dep"]
    print("\n| influence | of | on | slope ± s.e. | data |")
    print("|---|---|---|---|---|")
    for key, label in (("peak_eta", "peak q/p"), ("peak_ac", "a_c at peak"), ("peak_an", "a_n at peak"),
                       ("peak_m", "m at peak"), ("end_ac", "a_c at end"), ("end_eta", "q/p at end")):
        b, se = slope([r["e0"] for r in iso], [r[key] for r in iso])
        print(f"| initial void ratio | e0 | {label} | {b:+.3f} ± {se:.3f} per unit e0 | {len(iso)} isotropic tests |")
    for key, label in (("peak_eta", "peak q/p"), ("peak_ac", "a_c at peak"), ("peak_an", "a_n at peak"),
                       ("peak_m", "m at peak")):
        for density in ("dense", "medium", "loose"):
            group = [r for r in iso if r["density"] == density]
            b, se = slope([r["pressure"] for r in group], [r[key] for r in group])
            print(f"| confining pressure | p'0 [100 kPa] | {label} | {100 * b:+.3f} ± {100 * se:.3f} per 100 kPa | "
                  f"{density}, 100-300 kPa |")
    for key, label in (("ac0", "a_c at start"), ("peak_eta", "peak q/p"), ("peak_ac", "a_c at peak"),
                       ("peak_an", "a_n at peak"), ("peak_m", "m at peak")):
        for density in ("dense", "loose"):
            group = sorted((r for r in dep if r["density"] == density), key=lambda r: r["angle"])
            b, se = slope([r["angle"] for r in group], [r[key] for r in group])
            values = ", ".join(f"{r[key]:.3f}" for r in group)
            print(f"| loading angle | α [90°] | {label} | {90 * b:+.3f} ± {90 * se:.3f} per 90° | {density}: {values} "
                  f"at α = {', '.join(str(int(r['angle'])) for r in group)}° |")


def figures(runs, folder):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    os.makedirs(folder, exist_ok=True)
    groups = {"iso": [r for r in runs if r["kind"] == "iso"], "dep": [r for r in runs if r["kind"] == "dep"]}
    for kind, group in groups.items():
        fig, axes = plt.subplots(1, 3, figsize=(13, 3.8))
        for r in group:
            s, a = r["series"], r["sff"]
            line, = axes[0].plot(100 * s["axial_strain"], s["eta"], lw=0.8, label=r["name"])
            axes[1].plot(100 * s["axial_strain"], 100 * s["volumetric_strain"], lw=0.8, color=line.get_color())
            axes[2].plot(100 * a["axial_strain"], a["a_c"], "o-", ms=2.5, lw=0.8, color=line.get_color())
        axes[0].set_ylabel("q/p (walls)")
        axes[1].set_ylabel("ε_v [%] (compression +)")
        axes[2].set_ylabel("a_c")
        for ax in axes:
            ax.set_xlabel("ε_a [%]")
        axes[0].legend(fontsize=6, ncol=2)
        fig.tight_layout()
        path = os.path.join(folder, f"matrix_{kind}.png")
        fig.savefig(path, dpi=110)
        plt.close(fig)
        print(f"\nwrote {path}")
    fig, axes = plt.subplots(1, 2, figsize=(10, 3.8))
    for density, marker in (("dense", "o"), ("loose", "s")):
        group = sorted((r for r in groups["dep"] if r["density"] == density), key=lambda r: r["angle"])
        angles = [r["angle"] for r in group]
        axes[0].plot(angles, [r["peak_eta"] for r in group], marker + "-", label=f"{density}: peak q/p")
        for key, color in (("peak_ac", "tab:blue"), ("peak_an", "tab:orange"), ("peak_m", "tab:green")):
            axes[1].plot(angles, [r[key] for r in group], marker + "-", color=color,
                         label=f"{density}: {key[5:]}", alpha=1.0 if density == "dense" else 0.55)
    for ax in axes:
        ax.set_xlabel("loading angle α [°]")
        ax.legend(fontsize=7)
    axes[1].set_ylabel("anisotropy at peak")
    fig.tight_layout()
    path = os.path.join(folder, "matrix_angle.png")
    fig.savefig(path, dpi=110)
    print(f"wrote {path}")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("folder", nargs="?", default="tests/data/reference/matrix")
    parser.add_argument("--img", default="")
    args = parser.parse_args()
    runs = [load(p) for p in sorted(glob.glob(os.path.join(args.folder, "*.h5")))]
    order = {"iso": 0, "dep": 1}
    runs.sort(key=lambda r: (order[r["kind"]], ["dense", "medium", "loose"].index(r["density"]), r["pressure"],
                             r["angle"] or 0))
    sff_table.print_table([os.path.join(args.folder, r["name"] + ".h5") for r in runs])
    series_table(runs)
    influences(runs)
    if args.img:
        figures(runs, args.img)


if __name__ == "__main__":
    main()
