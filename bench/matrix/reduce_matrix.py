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


def reduce(source, target):
    with h5py.File(source, "r") as src, h5py.File(target, "w") as dst:
        for key, value in src.attrs.items():
            dst.attrs[key] = value
        for group in ("physics", "loading", "summary", "analysis"):
            if group in src:  # schema 1 has none of /physics, /loading, /summary
                src.copy(src[group], dst, group)
        # The series compressed: a run file's series chunks are not (they are appended to while
        # the run may be killed, docs/run-file.md); a reduced file is written once.
        series = dst.create_group("series")
        for key, value in src["series"].attrs.items():
            series.attrs[key] = value
        for name, column in src["series"].items():
            series.create_dataset(name, data=column[()], maxshape=(None,), chunks=True,
                                  shuffle=True, compression="gzip", compression_opts=4)
        dst.attrs["note:reduction"] = (f"reduced by bench/matrix/reduce_matrix.py from {os.path.basename(source)}: "
                                       f"/series and /analysis kept; {len(src['snapshots'])} snapshots and "
                                       "the checkpoint left out")


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
        reduce(path, target)
        done += 1
        print(f"{target}: {os.path.getsize(target) / 1024:.0f} KiB")
    print(f"{done} of {len(runs)} runs reduced")


if __name__ == "__main__":
    main()
