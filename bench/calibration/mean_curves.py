#!/usr/bin/python3
"""The mean curves of several seeds of one specimen, as a reduced run file (issue 19, point 4:
targets against the mean curve of three seeds).

usage: mean_curves.py OUT_FOLDER RUN_SEED_A.h5 RUN_SEED_B.h5 [...]  (runs of one specimen)

Writes OUT_FOLDER/<name>.h5 (python/sffcal/seeds.py, mean_run_file: the first run reduced, its
/series and /analysis/sff replaced by the means over the runs). `sffcal calibrate` reads the file
as it reads a run file. The main job does the same in its `mean` stage (docs/pipeline.md).
"""
import argparse
import os
import sys

from sffcal.seeds import mean_run_file


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
    mean_run_file(args.runs, target, "bench/calibration/mean_curves.py")
    print(target)


if __name__ == "__main__":
    main()
