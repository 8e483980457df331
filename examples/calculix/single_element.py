#!/usr/bin/env python3
"""One CalculiX C3D8 element in triaxial compression or extension, drained or undrained, with
sffcal's UMAT, against sffcal's material-point driver on the same path (docs/fe.md, "CalculiX").

The deck is written from `sffcal umat-cards` (PROPS, *DEPVAR, the initial stress) and run by the
ccx that scripts/build_calculix.sh builds; `sffcal point` runs the driver of the model (through
the same update as the UMAT) from the same start. The unit cube has symmetry planes x = 0, y = 0,
z = 0, and its top face z = 1 is moved to the end axial strain in equal increments (ccx's
*STATIC, DIRECT; small strain; a negative --max-strain lifts it: extension). The faces x = 1 and
y = 1 carry
  drained:   the confining pressure sigma_3, held from the start, the faces kept plane (*EQUATION)
             so that the element deforms homogeneously, as the material point does;
  undrained: no load but the lateral displacement eps_a / 2 that keeps the volume (small strain),
             so every degree of freedom is prescribed (ccx warns that none is left: expected).
Prints one row per increment and the largest differences; exits 1 where one exceeds --tolerance
(absolute, in q/p and in eps_v).

  examples/calculix/single_element.py --ccx build/calculix/ccx_sffcal --sffcal build/sffcal \\
      --parameters examples/acst_toyoura.json --pressure 150e3 --max-strain 0.05 --steps 25 -o out/ccx1
"""
import argparse
import csv
import os
import re
import subprocess
import sys

import ccx_case

# No *HEADING: CalculiX 2.20 reads it with an uninitialised count (headings.f) and may crash.
DECK = """** sffcal: one C3D8 element, {drainage} triaxial {kind}
*NODE, NSET=NALL
1, 0, 0, 0
2, 1, 0, 0
3, 1, 1, 0
4, 0, 1, 0
5, 0, 0, 1
6, 1, 0, 1
7, 1, 1, 1
8, 0, 1, 1
*ELEMENT, TYPE=C3D8, ELSET=EALL
1, 1, 2, 3, 4, 5, 6, 7, 8
*NSET, NSET=XMIN
1, 4, 5, 8
*NSET, NSET=YMIN
1, 2, 5, 6
*NSET, NSET=ZMIN
1, 2, 3, 4
*NSET, NSET=ZMAX
5, 6, 7, 8
*NSET, NSET=XMAX
2, 3, 6, 7
*NSET, NSET=YMAX
3, 4, 7, 8
*NSET, NSET=CORNER
7
{cards}*SOLID SECTION, ELSET=EALL, MATERIAL={material}
*AMPLITUDE, NAME=HELD
0., 1., 1., 1.
*BOUNDARY
XMIN, 1, 1
YMIN, 2, 2
ZMIN, 3, 3
{plane_faces}*STEP, INC=100000
*STATIC{direct}
{dt}, 1.{limits}
*CONTROLS, PARAMETERS=FIELD
{field_tolerance}, {field_tolerance}
*CONTROLS, PARAMETERS=TIME INCREMENTATION
4, 8, 9, 60, 10, 4, 12, 30
*BOUNDARY
ZMAX, 3, 3, {top}
{lateral}*NODE PRINT, NSET=CORNER
U
*EL PRINT, ELSET=EALL
S
*END STEP
"""

# Drained: the faces x = 1 and y = 1 kept plane, so that the element deforms homogeneously, as the
# material point (a fully integrated C3D8 can leave the homogeneous path where the model's tangent
# allows an hourglass-like mode: the contact-network model's does at the first increment).
PLANE_FACES = """*EQUATION
2
3, 1, 1., 2, 1, -1.
2
6, 1, 1., 2, 1, -1.
2
7, 1, 1., 2, 1, -1.
2
4, 2, 1., 3, 2, -1.
2
7, 2, 1., 3, 2, -1.
2
8, 2, 1., 3, 2, -1.
"""
DRAINED = """*DLOAD, AMPLITUDE=HELD
1, P4, {sigma3}
1, P5, {sigma3}
"""
UNDRAINED = """XMAX, 1, 1, {lateral}
YMAX, 2, 2, {lateral}
"""


def read_dat(path):
    """Per increment time: the corner's displacement and the mean stress over the points."""
    blocks, kind, time = {}, None, None
    with open(path) as f:
        for line in f:
            head = re.match(r"\s*(displacements|stresses) .* and time\s+(\S+)", line)
            if head:
                kind, time = head.group(1), float(head.group(2))
                blocks.setdefault(time, {"u": None, "s": []})
                continue
            fields = line.split()
            if kind and fields and re.match(r"^-?\d", fields[0]):
                values = [float(x) for x in fields]
                if kind == "displacements":
                    blocks[time]["u"] = values[1:4]
                else:
                    blocks[time]["s"].append(values[2:8])
    rows = []
    for time in sorted(blocks):
        u, s = blocks[time]["u"], blocks[time]["s"]
        if u is None or not s:
            continue
        mean = [sum(x[i] for x in s) / len(s) for i in range(6)]  # tension positive
        p = -(mean[0] + mean[1] + mean[2]) / 3.0
        q = 0.5 * (mean[0] + mean[1]) - mean[2]
        rows.append({"axial_strain": -u[2], "volumetric_strain": -(u[0] + u[1] + u[2]),
                     "p": p, "q": q, "eta": q / p})
    return rows


def read_curve(path):
    """A curve CSV of `sffcal point` (its first line a comment): the numbers compared, and each
    update's status as written."""
    with open(path) as f:
        lines = [line for line in f if not line.startswith("#")]
    return [{k: (v if k == "status" else float(v)) for k, v in row.items() if k in
             ("axial_strain", "volumetric_strain", "p", "q", "eta", "status")}
            for row in csv.DictReader(lines)]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ccx_case.add_common_arguments(parser)
    parser.add_argument("--pressure", type=float, default=100e3, help="plain specimen sigma_3 [Pa]")
    parser.add_argument("--void-ratio", type=float, default=0.8, help="plain specimen e_0")
    parser.add_argument("--max-strain", type=float, default=0.05,
                        help="end axial strain (negative: extension)")
    parser.add_argument("--drainage", choices=("drained", "undrained"), default="drained")
    parser.add_argument("--steps", type=int, default=25)
    parser.add_argument("--field-tolerance", type=float, default=1e-9,
                        help="ccx's residual and correction tolerances (*CONTROLS, FIELD)")
    parser.add_argument("--tolerance", type=float, default=1e-6,
                        help="largest |difference| in q/p and in eps_v accepted")
    parser.add_argument("--one-increment", action="store_true",
                        help="ccx's automatic incrementation from one increment to the end strain "
                             "(the UMAT asks for smaller ones through PNEWDT): the end point is "
                             "compared, with --tolerance, and the cuts counted")
    args = parser.parse_args()
    args.ccx, args.sffcal = os.path.abspath(args.ccx), os.path.abspath(args.sffcal)
    if not args.max_strain != 0:
        sys.exit("single_element: --max-strain must not be 0")
    out = ccx_case.new_folder(args.output, "single_element")

    start = ["--dem", args.dem] if args.dem else ["--pressure", repr(args.pressure),
                                                   "--void-ratio", repr(args.void_ratio)]
    cards, material = ccx_case.umat_cards(args.sffcal, args.parameters, start)
    sigma3 = -float(re.search(r"\n1, 1, (\S+),", cards).group(1))
    drained = args.drainage == "drained"
    with open(os.path.join(out, "element.inp"), "w") as f:
        f.write(DECK.format(drainage=args.drainage,
                            kind="compression" if args.max_strain > 0 else "extension",
                            cards=cards, material=material,
                            plane_faces=PLANE_FACES if drained else "",
                            lateral=(DRAINED.format(sigma3=sigma3) if drained
                                     else UNDRAINED.format(lateral=args.max_strain / 2)),
                            direct="" if args.one_increment else ", DIRECT",
                            dt=1.0 if args.one_increment else 1.0 / args.steps,
                            limits=", 1e-6, 1." if args.one_increment else "",
                            field_tolerance=args.field_tolerance, top=-args.max_strain))
    with open(os.path.join(out, "ccx.log"), "w") as log:
        code = subprocess.run([args.ccx, "-i", "element"], cwd=out, stdout=log,
                              stderr=subprocess.STDOUT).returncode
    ccx = read_dat(os.path.join(out, "element.dat")) if os.path.exists(os.path.join(out, "element.dat")) else []
    log = open(os.path.join(out, "ccx.log")).read()
    cuts = log.count("increment size decrease requested by a material user routine")
    # ITRS of each converged increment (element.sta: STEP INC ATT ITRS ...; "U": not converged).
    iterations = [int(f[3]) for f in (line.split() for line in open(os.path.join(out, "element.sta")))
                  if len(f) >= 7 and f[0] == "1" and f[2].isdigit()]
    if args.one_increment:
        if code != 0 or not ccx or abs(ccx[-1]["axial_strain"] - args.max_strain) > 1e-12:
            sys.exit(f"single_element: ccx did not reach the end strain (exit {code}); see {out}/ccx.log")
    elif code != 0 or len(ccx) != args.steps:
        sys.exit(f"single_element: ccx stopped (exit {code}) after {len(ccx)} of {args.steps} "
                 f"increments; see {out}/ccx.log")

    reference = os.path.join(out, "driver.csv")
    with open(os.path.join(out, "driver.log"), "w") as log:
        code = subprocess.run([args.sffcal, "point", "--parameters", args.parameters, *start,
                               "--drainage", args.drainage, "--max-strain", repr(args.max_strain),
                               "--steps", str(args.steps), "-o", reference], stdout=log,
                              stderr=subprocess.STDOUT).returncode
    if code != 0 or not os.path.exists(reference):
        sys.exit(f"single_element: the driver (sffcal point, exit {code}) did not complete; see "
                 f"{out}/driver.log")
    driver = read_curve(reference)[1:]
    unreliable = sum(row["status"] != "ok" for row in driver)
    print(f"ccx: {len(ccx)} increments, {cuts} cut(s) asked by the UMAT through PNEWDT, Newton "
          f"iterations per increment: mean {sum(iterations) / max(len(iterations), 1):.2f}, "
          f"max {max(iterations, default=0)}; driver: {unreliable} update(s) not ok")
    if args.one_increment:
        c, d = ccx[-1], driver[-1]
        difference = max(abs(c["eta"] - d["eta"]), abs(c["volumetric_strain"] - d["volumetric_strain"]))
        print(f"end point: q/p ccx {c['eta']:.6f} driver {d['eta']:.6f}, eps_v ccx "
              f"{c['volumetric_strain']:.6f} driver {d['volumetric_strain']:.6f}; largest "
              f"|difference| {difference:.2e} (tolerance {args.tolerance:g})")
        sys.exit(0 if cuts > 0 and difference <= args.tolerance else 1)

    worst = {"eta": 0.0, "eps_v": 0.0}
    print(f"{'eps_a':>9} {'q/p ccx':>12} {'q/p driver':>12} {'eps_v ccx':>12} {'eps_v driver':>12}")
    for c, d in zip(ccx, driver):
        if abs(c["axial_strain"] - d["axial_strain"]) > 1e-12:
            sys.exit(f"single_element: axial strains differ: {c['axial_strain']} {d['axial_strain']}")
        worst["eta"] = max(worst["eta"], abs(c["eta"] - d["eta"]))
        worst["eps_v"] = max(worst["eps_v"], abs(c["volumetric_strain"] - d["volumetric_strain"]))
        print(f"{c['axial_strain']:9.5f} {c['eta']:12.8f} {d['eta']:12.8f} "
              f"{c['volumetric_strain']:12.8f} {d['volumetric_strain']:12.8f}")
    print("largest |difference| of ccx against the driver: " +
          ", ".join(f"{k} {v:.2e}" for k, v in worst.items()) + f" (tolerance {args.tolerance:g})")
    sys.exit(0 if max(worst.values()) <= args.tolerance else 1)


if __name__ == "__main__":
    main()
