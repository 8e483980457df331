#!/usr/bin/python3
"""Covariance standard errors against the spread of refits, and the DEM's own noise (issue 19).

usage: bench/calibration/seed_spread.py OUT [--fit NAME] [--markdown FILE]

OUT is the folder of bench/calibration/seed_spread.sh or matrix_means.sh: OUT/seed<S>/<specimen>.h5
(the runs) and OUT/seed<S>/NAME/parameters.json (one calibration per seed; NAME `fit` by default:
ACST, or the contact-network model of `sffcal calibrate --model network`; matrix_means.sh writes
the network model's refits to `fit_network`). Prints, as Markdown:
- per fitted parameter: the mean over the seeds' fits, the standard deviation of the refits, the
  root-mean-square of the standard errors the fits reported (robust to correlated residuals, and
  as if the residuals were independent), and the ratios;
- per specimen: the DEM's noise, the RMS difference of q/p and of eps_v between two seeds of the
  same specimen divided by sqrt(2) (python/sffcal/seeds.py, noise: over all pairs, on the common
  strain range), beside the fits' RMS errors of that specimen.
"""
import argparse
import glob
import json
import math
import os
import sys

import numpy as np

from sffcal.seeds import noise as seeds_noise


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("folder")
    parser.add_argument("--fit", default="fit", help="the fits' folder in each OUT/seed<S> (fit)")
    parser.add_argument("--markdown", help="also write the tables to this file")
    args = parser.parse_args()
    seeds = sorted(glob.glob(os.path.join(args.folder, "seed*", args.fit, "parameters.json")))
    if len(seeds) < 2:
        sys.exit(f"seed_spread.py: fewer than 2 fits in {args.folder}/seed*/{args.fit} "
                 "(run seed_spread.sh or matrix_means.sh)")
    fits = [json.load(open(p)) for p in seeds]
    names = [os.path.basename(os.path.dirname(os.path.dirname(p))) for p in seeds]
    out = [f"Fits: {', '.join(names)} ({len(fits)} seeds).", "",
           "| parameter | mean of the fits | SD of the refits | RMS SE (robust) | SD / SE | "
           "RMS SE (if independent) | SD / SE |", "|---|---|---|---|---|---|---|"]
    network = fits[0].get("model") == "contact_network"

    def estimate(fit, name):
        """(value, robust SE, independent SE, at a bound) of a parameter in one fit; SEs None if
        not estimated."""
        if network:  # standard errors in the fit's record, null at a bound
            robust = fit["fit"]["standard_errors"].get(name)
            return (fit["parameters"][name]["value"], robust,
                    fit["fit"]["standard_errors_independent"].get(name), robust is None)
        e = fit["fabric_normalisation"]["a_cs"] if name == "a_cs" else fit["parameters"][name]
        return (e["value"], e.get("standard_error"),
                fit["fit"].get("standard_errors_independent", {}).get(name), bool(e.get("at_bound")))

    names_in_fit = list(fits[0]["parameters"]) + ([] if network else ["a_cs"])
    for name in names_in_fit:
        if not network and any(
                (fits[0]["fabric_normalisation"]["a_cs"] if name == "a_cs" else f["parameters"][name])
                .get("fixed", False) for f in fits):
            continue
        rows = [estimate(f, name) for f in fits]
        values = np.array([r[0] for r in rows])
        errors = [r[1] for r in rows]
        independent = [r[2] for r in rows]
        at_bound = sum(r[3] for r in rows)
        sd = float(np.std(values, ddof=1))

        def rms(errors):
            known = [e for e in errors if e is not None]
            return math.sqrt(sum(e * e for e in known) / len(known)) if known else float("nan")

        se, se_independent = rms(errors), rms(independent)
        note = f" ({at_bound} at a bound)" if at_bound else ""
        out.append(f"| {name}{note} | {np.mean(values):.4g} | {sd:.3g} | {se:.3g} | "
                   f"{sd / se if se > 0 else float('nan'):.2f} | {se_independent:.3g} | "
                   f"{sd / se_independent if se_independent > 0 else float('nan'):.2f} |")
    # The DEM noise per specimen, beside the fits' errors.
    specimens = sorted({os.path.basename(p)[:-3] for p in glob.glob(os.path.join(args.folder, "seed*", "*.h5"))
                        if not p.endswith(".specimen.h5")})
    out += ["", "| specimen | DEM noise q/p | fits' RMS q/p (mean) | DEM noise eps_v | "
            "fits' RMS eps_v (mean) |", "|---|---|---|---|---|"]
    for spec in specimens:
        runs = [os.path.join(os.path.dirname(os.path.dirname(p)), spec + ".h5") for p in seeds]
        runs = [r for r in runs if os.path.exists(r + ".done")]
        if len(runs) < 2:
            continue
        noise = seeds_noise(runs)
        errors = [e.get("predicted", e) for f in fits for e in f.get("errors", [])
                  if e["test"] == spec]
        eta = np.mean([e["rms_eta"] for e in errors]) if errors else float("nan")
        ev = np.mean([e["rms_volumetric"] for e in errors]) if errors else float("nan")
        out.append(f"| {spec} | {noise['eta']:.3f} | {eta:.3f} | {noise['volumetric_strain']:.4f} | "
                   f"{ev:.4f} |")
    text = "\n".join(out)
    print(text)
    if args.markdown:
        with open(args.markdown, "w") as f:
            f.write(text + "\n")


if __name__ == "__main__":
    main()
