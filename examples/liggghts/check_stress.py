#!/usr/bin/env python3
"""Compares the contact stress of an imported LIGGGHTS run with LIGGGHTS's own.

    check_stress.py OUTPUT_FOLDER RUN.h5 [ATOMS_DUMP CONTACTS_DUMP]

OUTPUT_FOLDER holds atoms.dump, contacts.dump and series.txt of examples/liggghts/triaxial.in
(or the dumps named); RUN.h5 is their import after `sffcal sff RUN.h5`. At every snapshot it
prints, as fractions of |S|_F (S: the series row's symmetric stress at that step):

  sff    |S_sff - S|_F: the importer's Love-Weber stress (/analysis/sff) against LIGGGHTS's;
  dump   the unsymmetric sum W = (1/V) sum (x_1 - x_2) (x) F_1 recomputed here from the dumps
         with the full-precision cell of the series row, against LIGGGHTS's six components
         (sxx syy szz vxy vxz vyz): checks ids, forces, force sign and completeness;
  sym    sym(W) against S (sxx..sxy): checks the deck's symmetrization by the torques;
  skew   |skew(W)|_F: what LIGGGHTS's own off-diagonal terms (vxy..) hold beyond S;
  box    sym(W) with the dump header's box against sym(W) with the series row's cell (the
         whole of `sff` when the headers carry LIGGGHTS's 6-digit "%g" bounds);
  force  max over contacts of F_1 . u / |F_1|, u the unit vector from atom 1 to atom 2
         (negative everywhere: the dumped force pushes atom 1 away, i.e. acts on atom 1).
"""
import sys

import h5py
import numpy as np


def frames(path):
    with open(path) as f:
        lines = f.read().split("\n")
    i = 0
    while i < len(lines):
        if not lines[i].strip():
            i += 1
            continue
        assert lines[i].startswith("ITEM: TIMESTEP"), lines[i]
        step = int(lines[i + 1])
        rows = int(lines[i + 3])
        box = np.array([[float(v) for v in lines[i + 5 + a].split()] for a in range(3)])
        cols = lines[i + 8].split()[2:]
        data = np.array([[float(v) for v in l.split()] for l in lines[i + 9:i + 9 + rows]])
        data = data.reshape(rows, len(cols))
        yield step, box, cols, data
        i += 9 + rows


def series(path):
    with open(path) as f:
        names = f.readline().split()
        rows = [[float(v) for v in l.split()] for l in f if l.strip() and not l.startswith("#")]
    table = np.array(rows)
    return {n: table[:, k] for k, n in enumerate(names)}


def tensor6(xx, yy, zz, yz, xz, xy):
    return np.array([[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]])


def main():
    folder, run = sys.argv[1], sys.argv[2]
    atoms = sys.argv[3] if len(sys.argv) > 3 else folder + "/atoms.dump"
    contacts = sys.argv[4] if len(sys.argv) > 4 else folder + "/contacts.dump"
    s = series(folder + "/series.txt")
    row = {int(st): k for k, st in enumerate(s["step"])}
    with h5py.File(run, "r") as h:
        a = h["analysis/sff"]
        sff = {int(st): tensor6(*(a["stress_" + c][k] for c in ("xx", "yy", "zz", "yz", "xz", "xy")))
               for k, st in enumerate(a["step"][:])}
    keys = ("sff", "dump", "sym", "skew", "box")
    worst = dict.fromkeys(keys, 0.0)
    print(f"{'step':>8} {'contacts':>8} " + " ".join(f"{k:>9}" for k in keys) + f" {'force':>6}")
    for (step, box, acols, at), (cstep, _, ccols, ct) in zip(frames(atoms), frames(contacts)):
        assert step == cstep
        k = row[step]
        S = tensor6(*(s[c][k] for c in ("sxx", "syy", "szz", "syz", "sxz", "sxy")))
        lig6 = np.array([s[c][k] for c in ("sxx", "syy", "szz", "vxy", "vxz", "vyz")])
        L = np.array([s["xhi"][k] - s["xlo"][k], s["yhi"][k] - s["ylo"][k], s["zhi"][k] - s["zlo"][k]])
        Lh = box[:, 1] - box[:, 0]
        pos = {int(r[acols.index("id")]): r[[acols.index(c) for c in "xyz"]] for r in at}
        i1 = ct[:, ccols.index("c_pgl[1]")].astype(int)
        i2 = ct[:, ccols.index("c_pgl[2]")].astype(int)
        F1 = ct[:, [ccols.index(f"c_pgl[{j}]") for j in (4, 5, 6)]]
        d = np.array([pos[a] - pos[b] for a, b in zip(i1, i2)])  # x_1 - x_2
        dl = d - L * np.round(d / L)
        dh = d - Lh * np.round(d / Lh)
        W = dl.T @ F1 / np.prod(L)          # compression positive
        Wh = dh.T @ F1 / np.prod(Lh)
        sym, symh = 0.5 * (W + W.T), 0.5 * (Wh + Wh.T)
        w6 = np.array([W[0, 0], W[1, 1], W[2, 2], W[0, 1], W[0, 2], W[1, 2]])
        norm = np.linalg.norm(S)
        e = dict(sff=np.linalg.norm(sff[step] - S), dump=np.linalg.norm(w6 - lig6),
                 sym=np.linalg.norm(sym - S), skew=np.linalg.norm(0.5 * (W - W.T)),
                 box=np.linalg.norm(symh - sym))
        u = -dl / np.linalg.norm(dl, axis=1)[:, None]
        cosf = np.max(np.einsum("ij,ij->i", F1, u) / np.linalg.norm(F1, axis=1))
        for key in keys:
            e[key] /= norm
            worst[key] = max(worst[key], e[key])
        print(f"{step:8d} {len(ct):8d} " + " ".join(f"{e[k]:9.2e}" for k in keys) + f" {cosf:6.3f}")
    print("worst: " + ", ".join(f"{k} {v:.2e}" for k, v in worst.items()))


if __name__ == "__main__":
    main()
