#!/usr/bin/env python3
"""One CalculiX C3D8 element with sffcal's UMAT, turned as a rigid body under NLGEOM and then
compressed along its own z axis: its Cauchy stress must be that of the element compressed without
the turn, turned, sigma_B = R sigma_A R^T (objectivity; docs/fe.md, "CalculiX").

The element starts from a model state of the UMAT's cards (`sffcal umat-cards`; a DEM run's
anisotropic fabric with --dem) and is held for one increment; run B then turns every node by
R(theta) about the x axis to --angle degrees in --increments increments, and both runs compress
the element by --strain along its own z axis (uniaxial strain, in --increments increments):
F = R diag(1, 1, 1 - strain t), every node prescribed, exactly at the end of each increment
(tabulated amplitudes). Run A is the same with theta = 0. ccx (umat_abaqusnl.f) gives the UMAT
the stress and the logarithmic strain in the material's own axes, R^T sigma R: a UMAT that turns
its tensor state by DROT as well turns it twice, and run B's stress leaves R sigma_A R^T. Prints
the largest difference, relative to |sigma_A|, and exits 1 where it exceeds --tolerance.

  examples/calculix/rotated_element.py --ccx build/calculix/ccx_sffcal --sffcal build/sffcal \\
      --parameters bench/reference/network_paper_params.json \\
      --dem tests/data/reference/matrix/dep_dense_a45.h5 -o out/ccx_rotated
"""
import argparse
import math
import os
import re
import subprocess
import sys

import ccx_case

NODES = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]


def rotation(theta):
    """R(theta) about the x axis."""
    c, s = math.cos(theta), math.sin(theta)
    return [[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]]


def rotated(r, sigma):
    """R sigma R^T of 3x3 lists."""
    return [[sum(r[i][k] * sigma[k][l] * r[j][l] for k in range(3) for l in range(3))
             for j in range(3)] for i in range(3)]


def amplitudes(name, displacement, increments):
    """*AMPLITUDE cards N<node>D<dof><name>: each node's y and z displacement at the end of each
    increment of a step, from displacement(node coordinates, t), t in [0, 1]."""
    lines = []
    for n, x in enumerate(NODES):
        for dof in (2, 3):
            lines.append(f"*AMPLITUDE, NAME=N{n + 1}D{dof}{name}")
            lines += [f"{k / increments!r}, {displacement(x, k / increments)[dof - 1]!r}"
                      for k in range(increments + 1)]
    return lines


def step(name, increments):
    lines = ["*STEP, NLGEOM, INC=100000", "*STATIC, DIRECT", f"{1.0 / increments!r}, 1.",
             "*BOUNDARY, OP=NEW", "NALL, 1, 1, 0."]
    for n in range(len(NODES)):
        for dof in (2, 3):
            lines += [f"*BOUNDARY, AMPLITUDE=N{n + 1}D{dof}{name}", f"{n + 1}, {dof}, {dof}, 1."]
    return lines + ["*EL PRINT, ELSET=EALL", "S", "*END STEP"]


def deck(cards, material, angle, strain, increments):
    """Held, turned by `angle` about x, then compressed by `strain` along the turned z axis."""
    def turn(x, t):
        r = rotation(angle * t)
        return [sum(r[i][j] * x[j] for j in range(3)) - x[i] for i in range(3)]

    def compress(x, t):
        r = rotation(angle)
        stretched = (x[0], x[1], x[2] * (1.0 - strain * t))
        return [sum(r[i][j] * stretched[j] for j in range(3)) - x[i] for i in range(3)]

    lines = ["** sffcal: one C3D8 element turned as a rigid body about x, then compressed along its "
             "own z, under NLGEOM", "*NODE, NSET=NALL"]
    lines += [f"{n + 1}, {x}, {y}, {z}" for n, (x, y, z) in enumerate(NODES)]
    lines += ["*ELEMENT, TYPE=C3D8, ELSET=EALL", "1, 1, 2, 3, 4, 5, 6, 7, 8", cards.rstrip(),
              f"*SOLID SECTION, ELSET=EALL, MATERIAL={material}"]
    lines += amplitudes("T", turn, increments) + amplitudes("C", compress, increments)
    lines += ["*STEP, NLGEOM", "*STATIC, DIRECT", "1., 1.", "*BOUNDARY", "NALL, 1, 3, 0.",
              "*EL PRINT, ELSET=EALL", "S", "*END STEP"]
    lines += step("T", increments) + step("C", increments) + [""]
    return "\n".join(lines)


def run(args, cards, material, angle, name):
    """The stress blocks of one run (held, turned, compressed), or exits naming the failure."""
    out = os.path.join(os.path.abspath(args.output), name)
    os.makedirs(out)
    with open(os.path.join(out, "rotated.inp"), "w") as f:
        f.write(deck(cards, material, angle, args.strain, args.increments))
    with open(os.path.join(out, "ccx.log"), "w") as log:
        code = subprocess.run([os.path.abspath(args.ccx), "-i", "rotated"], cwd=out, stdout=log,
                              stderr=subprocess.STDOUT).returncode
    dat = os.path.join(out, "rotated.dat")
    stresses = read_stresses(dat) if os.path.exists(dat) else []
    if code != 0 or len(stresses) != 2 * args.increments + 1:
        sys.exit(f"rotated_element: ccx (exit {code}) wrote {len(stresses)} of "
                 f"{2 * args.increments + 1} stress blocks; see {out}/ccx.log")
    return stresses


def read_stresses(path):
    """The mean over the integration points of the Cauchy stress (tension positive), as 3x3 lists,
    in the order of the .dat file's blocks."""
    blocks, current = [], None
    with open(path) as f:
        for line in f:
            if re.match(r"\s*stresses ", line):
                current = []
                blocks.append(current)
                continue
            fields = line.split()
            if current is not None and len(fields) == 8 and re.match(r"^-?\d", fields[0]):
                current.append([float(x) for x in fields[2:8]])
    means = []
    for block in blocks:
        m = [sum(p[i] for p in block) / len(block) for i in range(6)]  # xx yy zz xy xz yz
        means.append([[m[0], m[3], m[4]], [m[3], m[1], m[5]], [m[4], m[5], m[2]]])
    return means


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ccx_case.add_common_arguments(parser)
    parser.add_argument("--angle", type=float, default=45.0, help="end rotation about x [degrees]")
    parser.add_argument("--strain", type=float, default=0.02,
                        help="compression along the element's own z axis after the turn")
    parser.add_argument("--increments", type=int, default=45, help="of the turn and of the compression")
    parser.add_argument("--tolerance", type=float, default=1e-5,
                        help="largest |sigma_B - R sigma_A R^T| / |sigma_A| accepted")
    parser.add_argument("--nl", action="store_true",
                        help="name the material ABAQUSNL...: ccx's umat_abaqusnl interface")
    args = parser.parse_args()
    ccx_case.new_folder(args.output, "rotated_element")
    cards, material = ccx_case.umat_cards(os.path.abspath(args.sffcal), args.parameters,
                                          ["--dem", args.dem] if args.dem else [])
    if args.nl:  # ccx's umat_abaqusnl: Cauchy stress and logarithmic strain, and a real DROT
        cards = cards.replace(f"NAME={material}", f"NAME=ABAQUSNL{material[len('ABAQUS'):]}")
        material = f"ABAQUSNL{material[len('ABAQUS'):]}"
    angle = math.radians(args.angle)
    plain = run(args, cards, material, 0.0, "plain")
    turned = run(args, cards, material, angle, "turned")
    compressed = slice(args.increments + 1, None)
    r = rotation(angle)
    scale = math.sqrt(sum(x * x for row in plain[-1] for x in row))
    worst = 0.0
    print(f"{'strain':>8} {'|sigma_B - R sigma_A R^T| / |sigma_A|':>40}")
    for k, (a, b) in enumerate(zip(plain[compressed], turned[compressed]), start=1):
        expected = rotated(r, a)
        error = max(abs(b[i][j] - expected[i][j]) for i in range(3) for j in range(3)) / scale
        worst = max(worst, error)
        if k % max(args.increments // 5, 1) == 0 or k == args.increments:
            print(f"{args.strain * k / args.increments:8.4f} {error:40.3e}")
    change = max(abs(plain[-1][i][j] - plain[0][i][j]) for i in range(3) for j in range(3))
    print(f"sigma_A at the end: |sigma_A| {scale:.6g} Pa, changed by up to {change:.6g} Pa in the "
          f"compression; largest difference {worst:.3e} (tolerance {args.tolerance:g})")
    sys.exit(0 if worst <= args.tolerance else 1)


if __name__ == "__main__":
    main()
