#!/usr/bin/python3
"""The void ratio of a box specimen's interior, snapshot by snapshot (issue 19: is the dense
specimens' late dilation a wall-layer effect?).

usage: interior_void_ratio.py RUN.h5 [RUN.h5 ...] [--margins 1,2,3]

For each snapshot: the void ratio of the whole box (as the run reports it) and of the bodies whose
centroid lies farther than m x d_max from every wall, over the inner box that leaves that margin.
A body straddling the inner box's faces counts by its centroid: unbiased where the packing is
uniform across those faces, biased within a few diameters of a wall, where the grains form layers
(so the margins give different values, and only their trend over strain is compared). Body
volumes from the snapshot's spheres: a body of two spheres of radius r whose centres are s apart
is their union, 8 pi r^3 / 3 - pi (4r + s)(2r - s)^2 / 12 (the closed form of
common/include/sffcal/clump_geometry.h, two_sphere_union_volume); a single sphere 4/3 pi r^3.
"""
import argparse

import h5py
import numpy as np


def body_volumes(snapshot):
    """Each body's solid volume [m^3], in the order of the snapshot's particles."""
    spheres, ids = snapshot["spheres"][()], snapshot["particles"]["id"]
    n = len(ids)
    # sphere_body holds body ids (docs/run-file.md): their rows in the particles table.
    by_id = np.argsort(ids)
    body = by_id[np.searchsorted(ids[by_id], snapshot["sphere_body"][()])]
    count = np.bincount(body, minlength=n)
    radius = np.zeros(n)
    radius[body] = spheres[:, 3]  # the spheres of one body share its radius
    centre_sum = np.zeros((n, 3))
    np.add.at(centre_sum, body, spheres[:, :3])
    # A body's two centres lie half their separation s from their mean, either one of them.
    member = np.zeros(n, dtype=int)
    member[body] = np.arange(len(body))
    s = 2.0 * np.linalg.norm(spheres[member, :3] - centre_sum / count[:, None], axis=1)
    r = radius
    pair = 8.0 * np.pi * r**3 / 3.0 - np.pi * (4.0 * r + s) * (2.0 * r - s) ** 2 / 12.0
    return np.where(count == 2, pair, 4.0 / 3.0 * np.pi * r**3)


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
                volume, position = body_volumes(g), g["particles"]["position"]
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
