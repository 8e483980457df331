#!/usr/bin/python3
"""The mean curves of several seeds of one specimen, as a reduced run file (issue 19, point 4:
targets against the mean curve of three seeds).

usage: mean_curves.py OUT_FOLDER RUN_SEED_A.h5 RUN_SEED_B.h5 [...]  (runs of one specimen)

Writes OUT_FOLDER/<name>.h5: the first run reduced as bench/matrix/reduce_matrix.py does (root
attributes, /physics, /loading, /summary, /series, /analysis), then /series replaced by the mean
over the runs, each interpolated linearly in axial strain onto the first run's rows up to the
smallest final strain of all runs, and /analysis/sff by the mean over the runs snapshot by snapshot
(the snapshots are at the same nominal strains; as many as the run with the fewest). Integer
columns (steps, snapshot numbers) are the first run's. The root note `note:mean_of` names the
runs and their seeds. `sffcal calibrate` reads the file as it reads a run file.
"""
import argparse
import os
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "matrix"))
from reduce_matrix import reduce  # noqa: E402


def mean_file(runs, target):
    reduce(runs[0], target)
    files = [h5py.File(r, "r") for r in runs]
    try:
        strains = [f["series/axial_strain"][()] for f in files]
        top = min(abs(s[-1]) for s in strains)
        rows = np.abs(strains[0]) <= top + 1e-12
        n_snapshots = min(len(f["analysis/sff/axial_strain"]) for f in files)
        with h5py.File(target, "r+") as out:
            for name, column in out["series"].items():
                first = files[0]["series"][name][()]
                if np.issubdtype(first.dtype, np.floating):
                    values = [np.interp(np.abs(strains[0][rows]), np.abs(s), f["series"][name][()])
                              for s, f in zip(strains, files)]
                    column.resize((int(rows.sum()),))
                    column[...] = np.mean(values, axis=0)
                else:
                    column.resize((int(rows.sum()),))
                    column[...] = first[rows]
            sff = out["analysis/sff"]
            for name in list(sff.keys()):
                first = files[0]["analysis/sff"][name][()]
                if first.ndim != 1:
                    del sff[name]  # a table of other shape (none today) is not averaged
                    continue
                if np.issubdtype(first.dtype, np.floating):
                    data = np.mean([f["analysis/sff"][name][()][:n_snapshots] for f in files], axis=0)
                else:
                    data = first[:n_snapshots]
                attrs = dict(sff[name].attrs)
                del sff[name]
                sff.create_dataset(name, data=data)
                for key, value in attrs.items():
                    sff[name].attrs[key] = value
            seeds = [int(f.attrs.get("seed", 0)) for f in files]
            out.attrs["note:mean_of"] = (f"mean of {len(runs)} runs (seeds {', '.join(map(str, seeds))}) "
                                         f"by bench/calibration/mean_curves.py: "
                                         + ", ".join(os.path.relpath(r) for r in runs))
    finally:
        for f in files:
            f.close()


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("out")
    parser.add_argument("runs", nargs="+")
    args = parser.parse_args()
    if len(args.runs) < 2:
        sys.exit("mean_curves.py: give at least two runs of the same specimen")
    os.makedirs(args.out, exist_ok=True)
    target = os.path.join(args.out, os.path.basename(args.runs[0]))
    if os.path.exists(target):
        sys.exit(f"mean_curves.py: {target} exists (remove it first)")
    mean_file(args.runs, target)
    print(target)


if __name__ == "__main__":
    main()
