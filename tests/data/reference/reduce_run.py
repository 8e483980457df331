#!/usr/bin/python3
"""Reduce a triaxial run file to a few snapshots and re-run the SFF analysis on them.

    tests/data/reference/reduce_run.py SOURCE.h5 OUTPUT.h5 --sffcal build/sffcal [--snapshots 0,1,11]

Copies the root attributes and the whole /series unchanged, and the chosen snapshots renumbered
from 000000 (default: the first, the one nearest the peak of the wall q/p, the last). /checkpoint
(internal, and meaningless for the kept snapshots) and /analysis are left out; then
`sffcal sff OUTPUT.h5 --resamples 200 --seed 1` writes /analysis/{sff,sff_checks,sff_rose} for
exactly these snapshots (its CSV copies go to a temporary folder). The root note
`note:reduction` records the source and the kept snapshots. Finally the new /analysis/sff rows are
compared with the source's rows of the same snapshots, if the source has that table.
"""
import argparse
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np


def default_snapshots(src):
    names = sorted(src["snapshots"])
    strains = np.array([src["snapshots"][n].attrs["axial_strain"] for n in names])
    s = src["series"]
    peak_strain = s["axial_strain"][int(np.argmax(s["eta"][:]))]
    nearest = int(np.argmin(np.abs(strains - peak_strain)))
    return sorted({0, nearest, len(names) - 1})


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("source")
    parser.add_argument("output")
    parser.add_argument("--sffcal", required=True, help="the sffcal executable")
    parser.add_argument("--snapshots", help="comma-separated snapshot indices of the source")
    args = parser.parse_args()

    with h5py.File(args.source, "r") as src, h5py.File(args.output, "w") as dst:
        kept = ([int(k) for k in args.snapshots.split(",")] if args.snapshots
                else default_snapshots(src))
        for name in src.attrs:  # keep each attribute's stored type (int64, UTF-8 strings)
            dst.attrs.create(name, src.attrs[name], dtype=src.attrs.get_id(name).dtype)
        dst.attrs.create("note:reduction",
                         "reduced from %s by tests/data/reference/reduce_run.py: snapshots %s of "
                         "its %d kept (renumbered from 000000); /series complete; /checkpoint "
                         "dropped" % (os.path.basename(args.source), kept, len(src["snapshots"])),
                         dtype=h5py.string_dtype("utf-8"))
        src.copy("series", dst)  # keeps chunking, filters, maxshape and the columns attribute
        for group in ("physics", "loading", "summary"):  # where present (schema 2)
            if group in src:
                src.copy(group, dst)
        snapshots = dst.create_group("snapshots")
        for new, old in enumerate(kept):
            src.copy("snapshots/%06d" % old, snapshots, name="%06d" % new)
        stored = ({c: src["analysis/sff"][c][:] for c in src["analysis/sff"]}
                  if "analysis/sff" in src else None)
    print("kept snapshots %s of %s" % (kept, args.source))

    with tempfile.TemporaryDirectory() as csv:
        subprocess.run([args.sffcal, "sff", args.output, "-o", csv, "--resamples", "200",
                        "--seed", "1"], check=True)

    if stored is None:
        return 0
    with h5py.File(args.output, "r") as f:
        new = f["analysis/sff"]
        rows = [int(np.flatnonzero(stored["snapshot"] == k)[0]) for k in kept]
        differ = [c for c in new if c != "snapshot" and not np.array_equal(new[c][:], stored[c][rows])]
    if differ:
        print("note: the source's /analysis/sff differs in %s (made by another sffcal version?)"
              % ", ".join(differ))
    else:
        print("the new /analysis/sff equals the source's rows %s bit for bit" % rows)
    return 0


if __name__ == "__main__":
    sys.exit(main())
