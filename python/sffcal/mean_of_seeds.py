"""The mean of several seeds of one specimen, and the DEM's noise between them: the command line of
sffcal.seeds (the main job's `mean` stage, docs/pipeline.md; bench/calibration/).

usage: python3 -m sffcal.mean_of_seeds -o MEAN.h5 RUN_SEED_A.h5 RUN_SEED_B.h5 [...] [--force]

The runs must be of one specimen: their stored configs equal but for the seed and the thread
count (else an error names the keys that differ). Writes MEAN.h5, a reduced run file whose
/series and /analysis/sff are the means over the runs (`sffcal calibrate` and `sffcal fe-check`
read it as a run file), and MEAN.noise.json: the seeds, the runs and the noise per quantity
(q/p, volumetric strain, p/p0: the RMS over the rows of the standard deviation across the seeds;
for two, RMS(a - b)/sqrt(2); a_c: the same over the sheared snapshots).
"""
import argparse
import json
import os
import sys

import h5py

from sffcal import seeds


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("runs", nargs="+")
    parser.add_argument("-o", "--output", required=True)
    parser.add_argument("--force", action="store_true", help="overwrite MEAN.h5 and its noise file")
    args = parser.parse_args()
    if len(args.runs) < 2:
        sys.exit("sffcal.mean_of_seeds: give at least two runs of the same specimen")
    noise_file = args.output[:-3] + ".noise.json" if args.output.endswith(".h5") else args.output + ".noise.json"
    for path in (args.output, noise_file):
        if os.path.exists(path) and not args.force:
            sys.exit(f"sffcal.mean_of_seeds: {path} exists (--force to overwrite)")
    run_seeds = []
    for path in args.runs:
        with h5py.File(path, "r") as f:
            run_seeds.append(int(f.attrs.get("seed", -1)))
            if "analysis/sff" not in f:
                sys.exit(f"sffcal.mean_of_seeds: {path} has no /analysis/sff (run `sffcal sff` on it)")
    if len(set(run_seeds)) < len(run_seeds):
        sys.exit(f"sffcal.mean_of_seeds: the runs' seeds repeat ({run_seeds}): the noise needs distinct seeds")
    try:
        seeds.check_same_specimen(args.runs)  # before anything is written
        os.makedirs(os.path.dirname(os.path.abspath(args.output)), exist_ok=True)
        seeds.mean_run_file(args.runs, args.output, "python3 -m sffcal.mean_of_seeds")
        noise = seeds.noise(args.runs)
    except ValueError as e:
        sys.exit(f"sffcal.mean_of_seeds: {e}")
    record = {"seeds": run_seeds, "runs": [os.path.basename(r) for r in args.runs],
              "noise": noise,
              "definition": "RMS over the common rows (a_c: the common sheared snapshots) of the "
                            "standard deviation across the seeds (two seeds: RMS(a - b)/sqrt(2)); "
                            "the mean of K seeds scatters by noise/sqrt(K)"}
    with open(noise_file, "w") as f:
        json.dump(record, f, indent=1)
    print(f"{args.output}: mean of seeds {', '.join(map(str, run_seeds))}; noise "
          + ", ".join(f"{k} {v:.4g}" if v is not None else f"{k} none"
                      for k, v in record["noise"].items()))


if __name__ == "__main__":
    main()
