#!/usr/bin/env python3
"""The rough-platen mesh of bench/fe_mesh in CalculiX with sffcal's UMAT (docs/fe.md, "CalculiX"):
one eighth of a 50 x 50 x 100 mm specimen on N x N x N elements (C3D8, or C3D8I with incompatible
modes), symmetry planes x = y = z = 0, sigma_3 on x = L and y = L, the top face moved down in equal
increments and held radially (a rough platen). Prints a row like bench/fe_mesh's: completed
increments, Newton iterations, cuts asked through PNEWDT, q/p at the platen (its force over the
initial area against sigma_3), eps_v from the element volumes, the radial displacement at
mid-height of the edge x = L, y = 0 [mm].

  bench/calculix/mesh.py --ccx build/calculix/ccx_sffcal --sffcal build/sffcal \\
      [--parameters examples/acst_toyoura.json] [--cells 3] [--element C3D8] [--strain 0.05]
      [--steps 50] [--automatic] [--field-tolerance 1e-8] -o out/ccx_mesh
"""
import argparse
import os
import re
import subprocess
import sys
import time


def deck(n, element, strain, steps, automatic, field, cards, material, sigma3, L=0.025, H=0.05):
    node = lambda i, j, k: 1 + i + (n + 1) * (j + (n + 1) * k)
    lines = ["** sffcal: rough-platen mesh, drained triaxial compression", "*NODE, NSET=NALL"]
    for k in range(n + 1):
        for j in range(n + 1):
            for i in range(n + 1):
                lines.append(f"{node(i, j, k)}, {L * i / n!r}, {L * j / n!r}, {H * k / n!r}")
    lines.append(f"*ELEMENT, TYPE={element}, ELSET=EALL")
    faces_x, faces_y, e = [], [], 0
    for k in range(n):
        for j in range(n):
            for i in range(n):
                e += 1
                c = [node(i, j, k), node(i + 1, j, k), node(i + 1, j + 1, k), node(i, j + 1, k)]
                c += [node(i, j, k + 1), node(i + 1, j, k + 1), node(i + 1, j + 1, k + 1),
                      node(i, j + 1, k + 1)]
                lines.append(f"{e}, " + ", ".join(map(str, c)))
                if i == n - 1:
                    faces_x.append(e)
                if j == n - 1:
                    faces_y.append(e)
    nset = lambda name, nodes: [f"*NSET, NSET={name}"] + [
        ", ".join(map(str, nodes[m:m + 8])) for m in range(0, len(nodes), 8)]
    grid = [(i, j, k) for k in range(n + 1) for j in range(n + 1) for i in range(n + 1)]
    lines += nset("XMIN", [node(*g) for g in grid if g[0] == 0])
    lines += nset("YMIN", [node(*g) for g in grid if g[1] == 0])
    lines += nset("ZMIN", [node(*g) for g in grid if g[2] == 0])
    lines += nset("TOP", [node(*g) for g in grid if g[2] == n])
    lines += nset("EDGE", [node(n, 0, k) for k in range(n + 1)])
    lines.append(cards.rstrip("\n"))
    lines += [f"*SOLID SECTION, ELSET=EALL, MATERIAL={material}",
              "*AMPLITUDE, NAME=HELD", "0., 1., 1., 1.",
              "*BOUNDARY", "XMIN, 1, 1", "YMIN, 2, 2", "ZMIN, 3, 3", "TOP, 1, 2",
              "*STEP, INC=100000",
              "*STATIC" + ("" if automatic else ", DIRECT"),
              f"{1.0 / steps!r}, 1." + (f", 1e-6, {1.0 / steps!r}" if automatic else ""),
              "*CONTROLS, PARAMETERS=FIELD", f"{field!r}, {field!r}",
              "*CONTROLS, PARAMETERS=TIME INCREMENTATION", "4, 8, 9, 60, 10, 4, 12, 30",
              "*BOUNDARY", f"TOP, 3, 3, {-strain * H!r}",
              "*DLOAD, AMPLITUDE=HELD"]
    lines += [f"{e}, P4, {sigma3!r}" for e in faces_x] + [f"{e}, P5, {sigma3!r}" for e in faces_y]
    lines += ["*NODE PRINT, NSET=TOP, TOTALS=ONLY", "RF", "*NODE PRINT, NSET=EDGE", "U",
              "*EL PRINT, ELSET=EALL, TOTALS=ONLY", "EVOL", "*END STEP", ""]
    return "\n".join(lines)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--ccx", required=True)
    parser.add_argument("--sffcal", required=True)
    parser.add_argument("--parameters", default=os.path.join(
        os.path.dirname(__file__), "..", "..", "examples", "acst_toyoura.json"))
    parser.add_argument("--dem", help="start from this DEM run (else 100 kPa, e_0 0.8, isotropic)")
    parser.add_argument("--cells", type=int, default=3)
    parser.add_argument("--element", default="C3D8", choices=["C3D8", "C3D8I"])
    parser.add_argument("--strain", type=float, default=0.05)
    parser.add_argument("--steps", type=int, default=50)
    parser.add_argument("--automatic", action="store_true",
                        help="automatic incrementation (cuts allowed), at most 1/steps")
    parser.add_argument("--field-tolerance", type=float, default=1e-8,
                        help="ccx's residual and correction tolerances (*CONTROLS, FIELD)")
    parser.add_argument("-o", "--output", required=True)
    args = parser.parse_args()
    if os.path.exists(args.output):
        sys.exit(f"mesh: {args.output} exists; give a new folder")
    os.makedirs(args.output)
    n = args.cells
    start = ["--dem", args.dem] if args.dem else ["--pressure", "100e3", "--void-ratio", "0.8"]
    cards = subprocess.run([os.path.abspath(args.sffcal), "umat-cards", "--parameters", args.parameters,
                            *start, "--elements", f"1-{n ** 3}"],
                           check=True, capture_output=True, text=True).stdout
    material = re.search(r"\*MATERIAL, NAME=(\S+)", cards).group(1)
    sigma3 = -float(re.search(r"\n1, 1, (\S+),", cards).group(1))
    with open(os.path.join(args.output, "mesh.inp"), "w") as f:
        f.write(deck(n, args.element, args.strain, args.steps, args.automatic, args.field_tolerance,
                     cards, material, sigma3))
    t0 = time.time()
    with open(os.path.join(args.output, "ccx.log"), "w") as log:
        code = subprocess.run([os.path.abspath(args.ccx), "-i", "mesh"], cwd=args.output,
                              stdout=log, stderr=subprocess.STDOUT).returncode
    wall = time.time() - t0
    sta = [line.split() for line in open(os.path.join(args.output, "mesh.sta"))]
    done = [f for f in sta if len(f) >= 7 and f[0] == "1" and f[2].isdigit()]
    iterations = sum(int(f[3]) for f in done)
    reached = float(done[-1][4]) * args.strain if done else 0.0
    cuts = open(os.path.join(args.output, "ccx.log")).read().count("requested by a material user routine")
    # The last printed increment: the platen's reaction, the volume, the edge's u_x.
    text = open(os.path.join(args.output, "mesh.dat")).read()
    rf = re.findall(r"total force \(fx,fy,fz\) for set TOP and time\s+\S+\s+(\S+)\s+(\S+)\s+(\S+)", text)
    vol = re.findall(r"total volume for set EALL and time\s+\S+\s+(\S+)", text)
    L, H = 0.025, 0.05
    row = {}
    if rf and vol:
        axial = -float(rf[-1][2]) / (L * L)  # the platen's force over the initial area, compression +
        p = (axial + 2 * sigma3) / 3
        row["q/p platen"] = (axial - sigma3) / p
        row["eps_v"] = 1.0 - float(vol[-1]) / (L * L * H)
        blocks = re.split(r"displacements \(vx,vy,vz\) for set EDGE", text)
        last = [l.split() for l in blocks[-1].splitlines()[2:2 + n + 1]]
        z0 = [f for f in last if len(f) == 4 and int(f[0]) == 1 + n]  # node (n, 0, 0)
        row["bulge mm"] = 1e3 * float(z0[0][1]) if z0 else float("nan")
    print(f"| {args.element} {n}x{n}x{n} | {'yes' if code == 0 else 'no (exit %d)' % code} | "
          f"{len(done)} incr. to eps_a {reached:.4f} | {iterations} Newton | {cuts} cuts | "
          f"{wall:.1f} s | " + " | ".join(f"{k} {v:.4f}" for k, v in row.items()) + " |")


if __name__ == "__main__":
    main()
