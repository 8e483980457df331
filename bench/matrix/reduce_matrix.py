#!/usr/bin/python3
"""Reduces the run files of the reference matrix to what the tests and the results page read.

usage: reduce_matrix.py MATRIX_FOLDER OUT_FOLDER

For every MATRIX_FOLDER/<name>.h5 with an /analysis/sff table (`sffcal sff` done): copies the
root attributes (config, seed, program version, notes), /physics, /loading and /summary, the
whole /series (compressed) and every /analysis table into OUT_FOLDER/<name>.h5, without snapshots or checkpoint, and records the source in the
root note `note:reduction`. `sffcal calibrate` and `sffcal fe-check` read these files as they
read full run files; `sffcal sff` cannot re-analyse them (no snapshots).
"""
import argparse
import glob
import os
import sys

import h5py

from sffcal.reduce import reduce


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("matrix")
    parser.add_argument("out")
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    runs = sorted(p for p in glob.glob(os.path.join(args.matrix, "*.h5")) if not p.endswith(".specimen.h5"))
    done = 0
    for path in runs:
        with h5py.File(path, "r") as f:
            if "analysis/sff" not in f:
                print(f"skipped {path}: no /analysis/sff (run `sffcal sff` on it)", file=sys.stderr)
                continue
        target = os.path.join(args.out, os.path.basename(path))
        reduce(path, target, "bench/matrix/reduce_matrix.py")
        done += 1
        print(f"{target}: {os.path.getsize(target) / 1024:.0f} KiB")
    print(f"{done} of {len(runs)} runs reduced")


if __name__ == "__main__":
    main()
