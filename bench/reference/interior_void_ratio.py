#!/usr/bin/python3
"""The void ratio of a box specimen's interior, snapshot by snapshot (issue 19: is the dense
specimens' late dilation a wall-layer effect?).

usage: interior_void_ratio.py RUN.h5 [RUN.h5 ...] [--margins 1,2,3]

For each snapshot: the void ratio of the whole box (as the run reports it) and of the bodies whose
centroid lies farther than m x d_max from every wall, over the inner box that leaves that margin
(a body straddling the inner box's faces counts by its centroid, so the estimate is unbiased but
noisy). Body volumes: a sphere 4/3 pi r^3; a two-sphere clump of centre distance r (the
configs' centre_distance_ratio 0.5) two spheres less their lens, 2.25 pi r^3.
"""
import argparse

import h5py
import numpy as np


def body_volumes(particles):
    r = 0.5 * particles["sphere_diameter"]
    return np.where(particles["num_spheres"] == 2, 2.25 * np.pi * r**3, 4.0 / 3.0 * np.pi * r**3)


def box_bounds(walls):
    lower, upper = np.zeros(3), np.zeros(3)
    for w in walls:
        (upper if w["upper"] else lower)[w["axis"]] = w["position"]
    return lower, upper


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("runs", nargs="+")
    ap.add_argument("--margins", default="1,2,3", help="margins in largest sphere diameters")
    a = ap.parse_args()
    margins = [float(m) for m in a.margins.split(",")]
    for path in a.runs:
        with h5py.File(path, "r") as f:
            print(f"{path}\n| ε_a | e (box) | " + " | ".join(f"e inside {m:g} d_max" for m in margins) + " |")
            print("|---|---|" + "---|" * len(margins))
            for name in sorted(f["snapshots"]):
                g = f["snapshots"][name]
                particles = g["particles"][()]
                volume, position = body_volumes(particles), particles["position"]
                lower, upper = box_bounds(g["walls"][()])
                d_max = 2.0 * g["spheres"][:, 3].max()
                cells = [f"{g.attrs['axial_strain']:.3f}", f"{np.prod(upper - lower) / volume.sum() - 1:.4f}"]
                for m in margins:
                    lo, hi = lower + m * d_max, upper - m * d_max
                    inside = np.all((position > lo) & (position < hi), axis=1)
                    cells.append(f"{np.prod(hi - lo) / volume[inside].sum() - 1:.4f}")
                print("| " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
