#!/usr/bin/env python3
"""The rough-platen mesh of bench/fe_mesh in CalculiX with sffcal's UMAT, against the deal.II mesh
(docs/fe.md, "CalculiX"): one eighth of a 50 x 50 x 100 mm specimen on N x N x N elements (C3D8,
C3D8I with incompatible modes, or the 20-node C3D20R), symmetry planes x = y = z = 0, sigma_3 on x = L and y = L, the
top face moved down and held radially (a rough platen), automatic incrementation at most 1/steps
of the step. Prints a row: completed increments, Newton iterations, cuts asked through PNEWDT,
q/p at the platen (its force over the initial area against sigma_3), eps_v (the mean of the
points' small strains, compression positive), the radial displacement at mid-height of the edge
x = L, y = 0 [mm]; --csv writes it to a file too.

With --fe-mesh (bench/fe_mesh; ACST, a plain start), deal.II runs the same mesh, steps and strain:
Q1 with full integration against C3D8 (the same element), Q1 with B-bar against C3D8I and C3D20R
(the nearest), and the script prints deal.II's row and the differences. The exit status is 1 where ccx
does not reach the end, where --tolerance is given and q/p, eps_v or the bulge differ by more (q/p
and the bulge relative, eps_v absolute), or where --max-newton-ratio is given and ccx takes more
times deal.II's Newton iterations. In equal increments too small for the UMAT to ask for a cut
(3.5 % in 70), C3D8 and deal.II's Q1 take the same path and agree to the printed digits.

  examples/calculix/rough_platen_mesh.py --ccx build/calculix/ccx_sffcal --sffcal build/sffcal \\
      --parameters examples/acst_toyoura.json [--cells 3] [--element C3D8I] [--strain 0.05]
      [--steps 50] [--field-tolerance 1e-8] [--symmetric-tangent]
      [--nlgeom [--abaqusnl]] [--csv ROW.csv]
      [--fe-mesh build/bench/fe_mesh [--tolerance 1e-3] [--max-newton-ratio 2]] -o out/ccx_mesh
"""
import argparse
import csv
import os
import re
import subprocess
import sys
import time

import ccx_case

L, H = 0.025, 0.05  # the eighth's width and height [m]


# C3D20R's nodes after its corners: the midpoints of the edges 1-2, 2-3, 3-4, 4-1, 5-6, 6-7, 7-8,
# 8-5, 1-5, 2-6, 3-7, 4-8 (CalculiX's element library).
MIDSIDE = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4), (0, 4), (1, 5), (2, 6),
           (3, 7)]


def deck(n, element, strain, steps, field, cards, material, sigma3, nlgeom):
    # Nodes on a grid of s = 1 (linear) or 2 (quadratic) points a cell, numbered as on that grid.
    s = 2 if element.startswith("C3D20") else 1
    m = s * n
    node = lambda i, j, k: 1 + i + (m + 1) * (j + (m + 1) * k)
    elements, used, faces_x, faces_y = [], set(), [], []
    for k in range(n):
        for j in range(n):
            for i in range(n):
                corners = [(i, j, k), (i + 1, j, k), (i + 1, j + 1, k), (i, j + 1, k),
                           (i, j, k + 1), (i + 1, j, k + 1), (i + 1, j + 1, k + 1), (i, j + 1, k + 1)]
                points = [tuple(s * x for x in c) for c in corners]
                if s == 2:
                    points += [tuple((a + b) // 2 for a, b in zip(points[p], points[q]))
                               for p, q in MIDSIDE]
                used.update(points)
                elements.append([node(*p) for p in points])
                if i == n - 1:
                    faces_x.append(len(elements))
                if j == n - 1:
                    faces_y.append(len(elements))
    grid = sorted(used, key=lambda g: node(*g))
    lines = ["** sffcal: rough-platen mesh, drained triaxial compression", "*NODE, NSET=NALL"]
    lines += [f"{node(*g)}, {L * g[0] / m!r}, {L * g[1] / m!r}, {H * g[2] / m!r}" for g in grid]
    lines.append(f"*ELEMENT, TYPE={element}, ELSET=EALL")
    for e, c in enumerate(elements, start=1):  # at most 15 entries on the first line
        lines.append(f"{e}, " + ", ".join(map(str, c[:15])) + ("," if len(c) > 15 else ""))
        if len(c) > 15:
            lines.append(", ".join(map(str, c[15:])))
    nset = lambda name, nodes: [f"*NSET, NSET={name}"] + [
        ", ".join(map(str, nodes[q:q + 8])) for q in range(0, len(nodes), 8)]
    lines += nset("XMIN", [node(*g) for g in grid if g[0] == 0])
    lines += nset("YMIN", [node(*g) for g in grid if g[1] == 0])
    lines += nset("ZMIN", [node(*g) for g in grid if g[2] == 0])
    lines += nset("TOP", [node(*g) for g in grid if g[2] == m])
    lines += nset("EDGE", [node(*g) for g in grid if g[0] == m and g[1] == 0])
    lines.append(cards.rstrip("\n"))
    lines += [f"*SOLID SECTION, ELSET=EALL, MATERIAL={material}",
              "*AMPLITUDE, NAME=HELD", "0., 1., 1., 1.",
              "*BOUNDARY", "XMIN, 1, 1", "YMIN, 2, 2", "ZMIN, 3, 3", "TOP, 1, 2",
              "*STEP, INC=100000" + (", NLGEOM" if nlgeom else ""),
              "*STATIC", f"{1.0 / steps!r}, 1., 1e-6, {1.0 / steps!r}",
              "*CONTROLS, PARAMETERS=FIELD", f"{field!r}, {field!r}",
              "*CONTROLS, PARAMETERS=TIME INCREMENTATION", "4, 8, 9, 60, 10, 4, 12, 30",
              "*BOUNDARY", f"TOP, 3, 3, {-strain * H!r}",
              "*DLOAD, AMPLITUDE=HELD"]
    lines += [f"{e}, P4, {sigma3!r}" for e in faces_x] + [f"{e}, P5, {sigma3!r}" for e in faces_y]
    lines += ["*NODE PRINT, NSET=TOP, TOTALS=ONLY", "RF", "*NODE PRINT, NSET=EDGE", "U",
              "*EL PRINT, ELSET=EALL", "E", "*END STEP", ""]
    return "\n".join(lines)


def run_ccx(args):
    """Writes and runs the deck; returns the row."""
    n = args.cells
    start = ["--dem", args.dem] if args.dem else ["--pressure", "100e3", "--void-ratio", "0.8"]
    cards, material = ccx_case.umat_cards(args.sffcal, args.parameters, start, f"1-{n ** 3}")
    if args.abaqusnl:  # ccx's umat_abaqusnl.f: the corotated Cauchy stress and logarithmic strain
        nl_name = f"ABAQUSNL{material[len('ABAQUS'):]}"
        cards, material = cards.replace(f"NAME={material}", f"NAME={nl_name}"), nl_name
    sigma3 = -float(re.search(r"\n1, 1, (\S+),", cards).group(1))
    with open(os.path.join(args.output, "mesh.inp"), "w") as f:
        f.write(deck(n, args.element, args.strain, args.steps, args.field_tolerance, cards,
                     material, sigma3, args.nlgeom))
    env = dict(os.environ, SFFCAL_CCX_SYMMETRIC_TANGENT="1" if args.symmetric_tangent else "0")
    t0 = time.time()
    with open(os.path.join(args.output, "ccx.log"), "w") as log:
        code = subprocess.run([args.ccx, "-i", "mesh"], cwd=args.output, stdout=log,
                              stderr=subprocess.STDOUT, env=env).returncode
    wall = time.time() - t0
    for name in ("mesh.sta", "mesh.dat"):
        if not os.path.exists(os.path.join(args.output, name)):
            sys.exit(f"rough_platen_mesh: ccx (exit {code}) wrote no {name}: see "
                     f"{os.path.join(args.output, 'ccx.log')}")
    sta = [line.split() for line in open(os.path.join(args.output, "mesh.sta"))]
    done = [f for f in sta if len(f) >= 7 and f[0] == "1" and f[2].isdigit()]
    row = {"code": f"ccx {args.element}", "tangent": "symmetric" if args.symmetric_tangent else "whole",
           "completed": int(code == 0), "increments": len(done),
           "axial_strain": float(done[-1][4]) * args.strain if done else 0.0,
           "newton": sum(int(f[3]) for f in done), "wall_s": wall,
           "cuts": open(os.path.join(args.output, "ccx.log")).read().count(
               "requested by a material user routine")}
    # The last printed increment: the platen's reaction, the points' strains, the edge's u_x.
    text = open(os.path.join(args.output, "mesh.dat")).read()
    rf = re.findall(r"total force \(fx,fy,fz\) for set TOP and time\s+\S+\s+(\S+)\s+(\S+)\s+(\S+)", text)
    strains = re.split(r"strains \(elem, integ\.pnt\.,exx,eyy,ezz,exy,exz,eyz\) for set EALL", text)
    if rf and len(strains) > 1:
        axial = -float(rf[-1][2]) / (L * L)  # the platen's force over the initial area, compression +
        row["q_p_platen"] = (axial - sigma3) / ((axial + 2 * sigma3) / 3)
        # Equal cells and equal point weights: eps_v is the plain mean of the points' traces.
        points = [[float(v) for v in line.split()[2:5]] for line in strains[-1].splitlines()
                  if len(line.split()) == 8 and line.split()[0].isdigit()]
        row["eps_v"] = -sum(sum(point) for point in points) / len(points)
        blocks = re.split(r"displacements \(vx,vy,vz\) for set EDGE", text)
        last = [line.split() for line in blocks[-1].splitlines()[2:]]
        corner = 1 + args.cells * (2 if args.element.startswith("C3D20") else 1)  # node (L, 0, 0)
        z0 = [f for f in last if len(f) == 4 and f[0].isdigit() and int(f[0]) == corner]
        row["bulge_mm"] = 1e3 * float(z0[0][1]) if z0 else float("nan")
    return row


def run_dealii(args):
    """bench/fe_mesh on the same mesh, steps and strain (ACST, 100 kPa, e_0 0.8); returns the row."""
    out = os.path.join(args.output, "dealii")
    command = [args.fe_mesh, "--cells", str(args.cells), "--steps", str(args.steps), "--strain",
               repr(args.strain), "--only", "rough", "--threads", "1", "-o", out, args.parameters]
    if args.element == "C3D8":
        command.append("--full-integration")
    t0 = time.time()
    with open(os.path.join(args.output, "fe_mesh.log"), "w") as log:
        code = subprocess.run(command, stdout=log, stderr=subprocess.STDOUT).returncode
    wall = time.time() - t0
    with open(os.path.join(out, "rough.csv")) as f:
        steps = list(csv.DictReader(line for line in f if not line.startswith("#")))
    with open(os.path.join(out, "rough_bulge.csv")) as f:
        bulge = list(csv.DictReader(line for line in f if not line.startswith("#")))
    end, sigma3 = steps[-1], 100e3
    q = float(end["axial_stress"]) - sigma3
    return {"code": "deal.II Q1" + (" full integration" if args.element == "C3D8" else " B-bar"),
            "tangent": "whole", "completed": int(code == 0 and end["status"] != "failed"
                                                and float(end["axial_strain"]) >= args.strain * (1 - 1e-9)),
            "increments": len(steps) - 1, "axial_strain": float(end["axial_strain"]),
            "newton": sum(int(s["newton_iterations"]) for s in steps), "wall_s": wall,
            "cuts": sum(int(s["cuts"]) for s in steps), "q_p_platen": q / (sigma3 + q / 3),
            "eps_v": float(end["volumetric_strain"]),
            "bulge_mm": 1e3 * float(bulge[0]["radial_displacement"])}


def print_row(row, n):
    print(f"| {row['code']} {n}x{n}x{n} | {row['tangent']} tangent | "
          f"{'yes' if row['completed'] else 'NO'} | {row['increments']} incr. to eps_a "
          f"{row['axial_strain']:.4f} | {row['newton']} Newton | {row['cuts']} cuts | "
          f"{row['wall_s']:.1f} s | " + " | ".join(
              f"{k} {row[k]:.5f}" for k in ("q_p_platen", "eps_v", "bulge_mm") if k in row) + " |")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ccx_case.add_common_arguments(parser)
    parser.add_argument("--cells", type=int, default=3)
    parser.add_argument("--element", default="C3D8I", choices=["C3D8", "C3D8I", "C3D20R"])
    parser.add_argument("--strain", type=float, default=0.05)
    parser.add_argument("--steps", type=int, default=50)
    parser.add_argument("--field-tolerance", type=float, default=1e-8,
                        help="ccx's residual and correction tolerances (*CONTROLS, FIELD)")
    parser.add_argument("--symmetric-tangent", action="store_true",
                        help="the symmetric part of the tangent alone, as an unpatched ccx "
                             "(SFFCAL_CCX_SYMMETRIC_TANGENT=1)")
    parser.add_argument("--nlgeom", action="store_true",
                        help="geometrically nonlinear step (*STEP, NLGEOM): the UMAT gets the "
                             "Green-Lagrange strain; no comparison with deal.II (small strain)")
    parser.add_argument("--abaqusnl", action="store_true",
                        help="with --nlgeom: the material named ABAQUSNL..., ccx's interface with "
                             "the corotated Cauchy stress and the logarithmic strain")
    parser.add_argument("--csv", help="also write ccx's row to this CSV file")
    parser.add_argument("--fe-mesh", help="bench/fe_mesh: run deal.II on the same mesh and compare")
    parser.add_argument("--tolerance", type=float, help="largest difference from deal.II allowed")
    parser.add_argument("--max-newton-ratio", type=float,
                        help="most Newton iterations allowed, in deal.II's")
    args = parser.parse_args()
    if args.fe_mesh and args.dem:
        sys.exit("rough_platen_mesh: --fe-mesh runs a plain start (100 kPa, e_0 0.8): no --dem")
    if args.abaqusnl and not args.nlgeom:
        sys.exit("rough_platen_mesh: --abaqusnl needs --nlgeom")
    if args.fe_mesh and args.nlgeom:
        sys.exit("rough_platen_mesh: deal.II's mesh is in small strain: no --fe-mesh with --nlgeom")
    if (args.tolerance is not None or args.max_newton_ratio is not None) and not args.fe_mesh:
        sys.exit("rough_platen_mesh: --tolerance and --max-newton-ratio need --fe-mesh")
    args.output = ccx_case.new_folder(args.output, "rough_platen_mesh")
    args.ccx, args.sffcal = os.path.abspath(args.ccx), os.path.abspath(args.sffcal)
    row = run_ccx(args)
    print_row(row, args.cells)
    if args.csv:
        with open(args.csv, "w") as f:
            writer = csv.DictWriter(f, fieldnames=list(row))
            writer.writeheader()
            writer.writerow(row)
    failures = [] if row["completed"] else ["ccx did not reach the end"]
    if args.fe_mesh:
        reference = run_dealii(args)
        print_row(reference, args.cells)
        if not reference["completed"]:
            failures.append("deal.II did not reach the end")
        if "q_p_platen" in row:
            differences = {
                "q/p": abs(row["q_p_platen"] / reference["q_p_platen"] - 1),
                "eps_v": abs(row["eps_v"] - reference["eps_v"]),
                "bulge": abs(row["bulge_mm"] / reference["bulge_mm"] - 1)}
            ratio = row["newton"] / reference["newton"]
            print("ccx against deal.II: " + ", ".join(f"{k} {v:.2e}" for k, v in differences.items())
                  + " (q/p and the bulge relative, eps_v absolute); "
                  f"Newton iterations {ratio:.2f} times deal.II's")
            if args.tolerance is not None:
                failures += [f"{k} differs by {v:.2e} > {args.tolerance:g}"
                             for k, v in differences.items() if v > args.tolerance]
            if args.max_newton_ratio is not None and ratio > args.max_newton_ratio:
                failures.append(f"{ratio:.2f} times deal.II's Newton iterations > "
                                f"{args.max_newton_ratio:g}")
    if failures:
        sys.exit("rough_platen_mesh: " + "; ".join(failures))


if __name__ == "__main__":
    main()
