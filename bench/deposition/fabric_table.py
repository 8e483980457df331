#!/usr/bin/python3
"""Fabric of prepared specimens against their loading angle (issue 3), as a Markdown table.

usage: fabric_table.py specimen.h5 [...]

For each specimen file (`sffcal prepare`): the loading angle alpha from the stored config, the
bedding normal n_b = (0, -sin a, cos a), and from the last snapshot the body-body contact-normal
fabric phi = <n n>: its major principal direction and the angle between it and n_b, the
deviatoric components a_c(d) = (15/2) d.(phi - I/3).d along n_b, X and the in-plane direction
t = X x n_b (their sum is 0), and the clump-axis fabric's minor direction's angle to n_b.
"""
import re
import sys

import h5py
import numpy as np


def angle_deg(u, v):
    return float(np.degrees(np.arccos(min(1.0, abs(float(u @ v))))))


def row(path):
    with h5py.File(path, "r") as f:
        text = f.attrs["config"]
        text = text.decode() if isinstance(text, bytes) else str(text)
        alpha = float(re.search(r"^loading_angle_deg\s*=\s*([-0-9.eE+]+)", text, re.M).group(1))
        snap = f["snapshots"][sorted(f["snapshots"].keys())[-1]]
        contacts = snap["contacts"][:]
        particles = snap["particles"][:]
    a = np.radians(alpha)
    n_b = np.array([0.0, -np.sin(a), np.cos(a)])
    t = np.array([0.0, np.cos(a), np.sin(a)])
    normals = np.asarray(contacts[contacts["wall"] < 0]["normal"], float)
    phi = normals.T @ normals / len(normals)
    major = np.linalg.eigh(phi)[1][:, 2]
    dev = 7.5 * (phi - np.eye(3) / 3.0)
    w, x, y, z = np.asarray(particles["orientation"], float).T  # unit quaternions (w, x, y, z)
    axes = np.stack([1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y)], 1)  # q e_x
    minor_axis = np.linalg.eigh(axes.T @ axes / len(axes))[1][:, 0]
    return (f"| {alpha:.0f} | {len(particles)} | {len(normals)} | "
            f"({major[0]:+.2f}, {major[1]:+.2f}, {major[2]:+.2f}) | {angle_deg(major, n_b):.0f} | "
            f"{n_b @ dev @ n_b:+.3f} | {dev[0, 0]:+.3f} | {t @ dev @ t:+.3f} | "
            f"{angle_deg(minor_axis, n_b):.0f} |")


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    print("| α [°] | bodies | contacts | contact-fabric major direction | its angle to n_b [°] | "
          "a_c(n_b) | a_c(X) | a_c(t) | clump-axis minor to n_b [°] |")
    print("|---|---|---|---|---|---|---|---|---|")
    for path in sys.argv[1:]:
        print(row(path))


if __name__ == "__main__":
    main()
