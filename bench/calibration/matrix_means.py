#!/usr/bin/python3
"""The errors of the fits of bench/calibration/matrix_means.sh against issue 19's 500-clump targets
(fitted: RMS q/p <= 0.06, eps_v <= 0.005; held back: <= 0.09, <= 0.007; RMS a_c <= 0.1) with
the DEM's noise of each mean beside them.

usage: bench/calibration/matrix_means.py MEANS FIT [FIT...] [--markdown FILE]

MEANS is the folder of the means and their noise files, MEANS/<specimen>.noise.json
(sffcal.mean_of_seeds: OUT/mean of matrix_means.sh, or tests/data/reference/matrix_means);
each FIT a folder of `sffcal calibrate -o FIT` (ACST, or --model network) on those means. The
noise of the mean of K seeds is the noise of one run (the RMS over the rows, for a_c over the
sheared snapshots, of the standard deviation across the seeds) divided by sqrt(K). Undrained tests
have eps_v = 0 and are judged in p/p0, for which the issue gives no target.
"""
import argparse
import glob
import json
import math
import os
import sys

TARGETS = {"fitted": {"eta": 0.06, "volumetric": 0.005}, "held back": {"eta": 0.09, "volumetric": 0.007}}
A_C_TARGET = 0.1


def errors_of(fit):
    """{test: (role, {quantity: RMS})} of one parameter file, ACST's or the network model's
    (the latter's errors on the test's own predicted loading path)."""
    out = {}
    if fit.get("model") == "contact_network":
        for e in fit["errors"]:
            p = e["predicted"]
            out[e["test"]] = (e["role"],
                              {"eta": p.get("rms_eta"), "volumetric": p.get("rms_volumetric"),
                               "p_ratio": p.get("rms_p_ratio"), "a_c": p.get("rms_a_c"),
                               "complete": p.get("complete", True)})
        return out
    for role, key in (("fitted", "errors"), ("held back", "held_out_errors")):
        for e in fit.get(key, []):
            out[e["test"]] = (role, {"eta": e.get("rms_eta"), "volumetric": e.get("rms_volumetric"),
                                     "p_ratio": e.get("rms_p_ratio"), "a_c": e.get("rms_a_c"),
                                     "complete": e.get("status", "ok") == "ok"})
    return out


def cell(value, target=None):
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "–"
    text = f"{value:.4f}" if value < 0.01 else f"{value:.3f}"
    return f"**{text}**" if target is not None and value > target else text


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("means")
    parser.add_argument("fits", nargs="+")
    parser.add_argument("--markdown", help="also write the tables to this file")
    args = parser.parse_args()
    noise = {}
    for path in sorted(glob.glob(os.path.join(args.means, "*.noise.json"))):
        with open(path) as f:
            record = json.load(f)
        k = len(record["seeds"])
        noise[os.path.basename(path)[: -len(".noise.json")]] = (
            k, {q: v / math.sqrt(k) for q, v in record["noise"].items() if v is not None})
    if not noise:
        sys.exit(f"matrix_means.py: no noise file in {args.means} (python3 -m sffcal.mean_of_seeds writes them)")
    lines = []
    for folder in args.fits:
        path = os.path.join(folder, "parameters.json")
        if not os.path.exists(path):
            sys.exit(f"matrix_means.py: {path} does not exist (a folder of `sffcal calibrate -o`)")
        with open(path) as f:
            fit = json.load(f)
        errors = errors_of(fit)
        lines += [f"### {folder} ({fit.get('model', 'acst')})", "",
                  "| test | role | RMS q/p | noise of the mean | RMS ε_v | noise of the mean | "
                  "RMS p/p0 | noise of the mean | RMS a_c | noise of the mean |",
                  "|---|---|---|---|---|---|---|---|---|---|"]
        missed = []
        for test, (role, e) in sorted(errors.items(), key=lambda t: (t[1][0] != "fitted", t[0])):
            k, n = noise.get(test, (0, {}))
            target = TARGETS[role]
            undrained = test.startswith("und_")
            row = [test, role + ("" if e["complete"] else " (incomplete)"),
                   cell(e["eta"], target["eta"]), cell(n.get("eta")),
                   "0 (undrained)" if undrained else cell(e["volumetric"], target["volumetric"]),
                   "" if undrained else cell(n.get("volumetric_strain")),
                   cell(e["p_ratio"]), cell(n.get("p_ratio")), cell(e["a_c"], A_C_TARGET),
                   cell(n.get("a_c"))]
            lines.append("| " + " | ".join(row) + " |")
            for name, value, limit in (("q/p", e["eta"], target["eta"]),
                                       ("ε_v", None if undrained else e["volumetric"], target["volumetric"]),
                                       ("a_c", e["a_c"], A_C_TARGET)):
                if value is not None and value > limit:
                    missed.append(f"{test} {name} {value:.4g} > {limit}")
        lines += ["", "Targets missed: " + ("; ".join(missed) if missed else "none") + ".", ""]
    text = "\n".join(lines)
    print(text)
    if args.markdown:
        with open(args.markdown, "w") as f:
            f.write(text + "\n")


if __name__ == "__main__":
    main()
