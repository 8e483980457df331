#!/usr/bin/python3
"""The report of the main job: OUT/report/report.md (and the same page as report.html) with the
plots and tables the main job's stages left in OUT (workflow/Snakefile). A stage that has not
run yet leaves its section saying so.

usage: pipeline_report.py OUT --scene SCENE.toml
"""
import argparse
import datetime
import glob
import json
import os
import re
import shutil
import subprocess
import sys
import tomllib

import h5py
import markdown
import numpy as np

from sffcal import runfile

HERE = os.path.dirname(os.path.abspath(__file__))
STAGES = ["prepare", "triaxial", "sff", "mean", "calibrate", "fe-check"]


class Page:
    def __init__(self, out):
        self.out, self.lines = out, []
        self.folder = os.path.join(out, "report")
        os.makedirs(os.path.join(self.folder, "img"), exist_ok=True)

    def add(self, *lines):
        self.lines.extend(lines)
        self.lines.append("")

    def table(self, header, rows):
        self.add("| " + " | ".join(header) + " |", "|" + "---|" * len(header),
                 *["| " + " | ".join(str(c) for c in row) + " |" for row in rows])

    def image(self, path, caption):
        """Copies the PNG into report/img (the folder stands alone) and embeds it."""
        if not os.path.exists(path):
            self.add(f"*{caption}: not made yet ({os.path.relpath(path, self.out)} missing).*")
            return
        name = os.path.relpath(path, self.out).replace(os.sep, "_")
        shutil.copyfile(path, os.path.join(self.folder, "img", name))
        self.add(f"![{caption}](img/{name})", f"*{caption}*")


def benchmark_times(out):
    """The stages' times from Snakemake's benchmark records (workflow/Snakefile:
    OUT/benchmarks/<stage>_<task>.tsv, column s): per stage the sum over its jobs."""
    rows, total = [], 0.0
    for stage in STAGES:
        jobs = sorted(glob.glob(os.path.join(out, "benchmarks", stage + "_*.tsv")))
        if not jobs:
            rows.append((stage, "-", "not run"))
            continue
        seconds = {}
        for job in jobs:
            with open(job) as f:
                header, values = f.readline().split("\t"), f.readline().split("\t")
            seconds[os.path.basename(job)[len(stage) + 1:-4]] = float(values[header.index("s")])
        total += sum(seconds.values())
        rows.append((stage, f"{sum(seconds.values()):.1f}",
                     "; ".join(f"{name} {s:.0f} s" for name, s in seconds.items())))
    return rows, total


def run_row(path, role):
    with h5py.File(path, "r") as f:
        s = runfile.series(f, ["axial_strain", "eta", "void_ratio", "volumetric_strain", "sigma_3",
                               "inertial_number"])
        config = runfile.config_text(f)
        path_name = runfile.loading_path(f)
        ended, summary = runfile.ended(f), runfile.summary(f)  # the DEM's own record of the test
    eps_a, eta, e = s["axial_strain"], s["eta"], s["void_ratio"]
    eps_v, sigma3, inertial = s["volumetric_strain"], s["sigma_3"], s["inertial_number"]
    bodies = re.search(r"^bodies\s*=\s*(\d+)", config, re.M)
    # extension: eps_a < 0, q/p < 0, its peak the most negative
    last = runfile.end_window(eps_a)  # the last 5 % of axial strain
    k = int(np.argmax(np.abs(eta)))
    return (runfile.name_of(path), role, path_name, bodies.group(1) if bodies else "?",
            f"{sigma3[0] / 1e3:.0f}", f"{e[0]:.3f}",
            f"{eta[k]:.3f} at {100 * eps_a[k]:.1f} %", f"{eta[last].mean():.3f}", f"{e[last].mean():.3f}",
            f"{100 * eps_v[-1]:.1f}", f"{100 * eps_a[-1]:.1f}", ended,
            f"{100 * summary['worst_lateral_error']:.2f}" if "worst_lateral_error" in summary else "?",
            f"{inertial.max():.1e}", f"{eta.min():.2f}")


def run_status(log):
    """The case headers and the driver/element/mesh end lines of a fe-check log."""
    if not os.path.exists(log):
        return []
    with open(log, errors="replace") as f:
        return [line.rstrip() for line in f if re.match(r"^case \S+: ", line)
                or re.match(r"^\s+(driver|element|mesh)\s+(completed|STOPPED)", line)
                or re.match(r"^\s+material-point driver:|^\s+.*failed at", line)]


# Tolerances of the calibrated model against the DEM: those of fe-check (--dem-eta-tol,
# --dem-ev-tol) for q/p and eps_v; for p/p0 of an undrained test ours (issue 19 gives none).
TOLERANCES = {"rms_eta": ("q/p (RMS)", 0.1), "rms_volumetric": ("eps_v (RMS)", 0.01),
              "rms_p_ratio": ("p/p0 (RMS)", 0.1)}
# The quantity of each check label in the noise files of the mean stage (sffcal.mean_of_seeds).
NOISE_OF = {"q/p (RMS)": "eta", "eps_v (RMS)": "volumetric_strain", "p/p0 (RMS)": "p_ratio"}


def specimen_of(stem):
    """The specimen of a run: its file stem without the seed suffix _s<seed> of a scene with
    several seeds (the mean stage)."""
    return re.sub(r"_s\d+$", "", stem)


def read_noise(out):
    """The mean stage's noise records, by specimen: {"seeds", "runs", "noise": {quantity: value}}."""
    records = {}
    for path in sorted(glob.glob(os.path.join(out, "mean", "*.noise.json"))):
        with open(path) as f:
            records[os.path.basename(path)[: -len(".noise.json")]] = json.load(f)
    return records


def with_noise(rows, noise):
    """The check rows with the DEM's noise beside the error: one seed's, and the mean's (the
    checks compare with the mean of the seeds, which scatters by noise/sqrt(K))."""
    out = []
    for test, role, through, quantity, value, tolerance, result in rows:
        record = noise.get(test)
        if record and NOISE_OF.get(quantity) in record["noise"]:
            one = record["noise"][NOISE_OF[quantity]]
            cells = [f"{one:.4f}", f"{one / np.sqrt(len(record['seeds'])):.4f}"]
        else:
            cells = ["-", "-"]
        out.append((test, role, through, quantity, value, *cells, tolerance, result))
    return out


def checks(out, fitted, held):
    """The checks of the model against the DEM, one row per test and quantity: fe-check's FE
    element for the drained compression tests (fe_check/summary.csv), the calibrated model's
    driver for the other paths (calibrate/parameters.json, the same update: fe-check verifies
    element against driver to 1e-8)."""
    rows = []
    fe = os.path.join(out, "fe_check", "summary.csv")
    if os.path.exists(fe):
        for case, check, quantity, value, tolerance, result, *_ in runfile.read_csv_rows(fe)[1:]:
            if check == "FE vs DEM":
                role = "held back" if case in held else "fitted" if case in fitted else "-"
                rows.append((case, role, "FE element", quantity, f"{float(value):.4f}", tolerance, result))
    params = os.path.join(out, "calibrate", "parameters.json")
    if os.path.exists(params):
        with open(params) as f:
            fit = json.load(f)
        for role, key in (("fitted", "errors"), ("held back", "held_out_errors")):
            for e in fit.get(key, []):
                path = e.get("path", "drained_compression")
                if path == "drained_compression" or "rms_eta" not in e:
                    continue  # checked by the FE element above; another model's record: its summary
                undrained = path.startswith("undrained")
                for name in ("rms_eta", "rms_p_ratio" if undrained else "rms_volumetric"):
                    label, tol = TOLERANCES[name]
                    rows.append((e["test"], role, f"model driver ({path})", label, f"{e[name]:.4f}",
                                 f"{tol:g}", "pass" if e[name] <= tol else "fail"))
    return rows


def fitted_model_name(out):
    """The model the calibration stage fitted, as its parameter file names it (the key "model" of
    every model's parameter file, docs/model-interface.md; "acst" in files of the first versions)."""
    params = os.path.join(out, "calibrate", "parameters.json")
    model = "acst"
    if os.path.exists(params):
        with open(params) as f:
            model = json.load(f).get("model", "acst")
    return {"acst": "ACST model", "contact_network": "contact-network model"}.get(model, f"model {model}")


def demote(text):
    """Headings of an embedded page one level down."""
    return re.sub(r"^(#+) ", r"\1## ", text, flags=re.M)


def write_markdown(out, scene_path):
    with open(scene_path, "rb") as f:
        scene = tomllib.load(f)
    fitted, held = scene.get("calibrate_on", []), scene.get("held_back", [])
    runs = sorted(glob.glob(os.path.join(out, "runs", "*.h5")))
    role = {n: "calibration" for n in fitted} | {n: "held back" for n in held}
    page = Page(out)
    page.add("# sffcal main job: report",
             f"Scene `{os.path.relpath(scene_path)}`, output `{out}`, written "
             f"{datetime.datetime.now().isoformat(timespec='seconds')} on {os.cpu_count()} cores. "
             "Made by the workflow `workflow/Snakefile` (docs/pipeline.md); units SI, compression positive.")

    noise = read_noise(out)
    rows = with_noise(checks(out, fitted, held), noise)
    failed = [r for r in rows if r[-1] != "pass"]
    seeds = scene.get("seeds", [scene.get("seed", 1)])
    against = (f"the mean of {len(seeds)} seeds of each specimen (seeds {', '.join(map(str, seeds))}; "
               "`mean/<specimen>.h5`)" if noise else "one run of each specimen")
    page.add("## Checks",
             f"The calibrated model against every DEM test it was fitted to or that was held back from "
             f"the fit (held back: {', '.join(held) or 'none'}; predicted, not fitted). Drained "
             "compression through the deal.II element (`sffcal fe-check`), the other loading paths "
             "through the model's driver on the test's own path (`sffcal calibrate`, docs/calibration.md). "
             "Tolerances: fe-check's for q/p and ε_v; 0.1 for p/p0 of an undrained test (ours). "
             f"The DEM test is {against}. Beside each error the DEM's own noise: how far one run lies "
             "from another of the same specimen (the RMS difference of two seeds / √2), and the scatter "
             "of the mean the check compares with (that / √(seeds)); a model cannot be asked to come "
             "much closer than the latter.")
    if rows:
        page.table(["test", "role", "through", "quantity", "value", "DEM noise (one seed)",
                    "DEM noise (mean)", "tolerance", "result"],
                   [[f"**{c}**" if c == "fail" else c for c in row] for row in rows])
        page.add(f"**{len(failed)} of {len(rows)} checks failed.**" if failed else
                 f"All {len(rows)} checks passed.")
        print(f"checks: {len(rows) - len(failed)} of {len(rows)} passed")
    else:
        page.add("*No checks yet (stages calibrate and fe-check).*")

    if noise:
        page.add("## Seeds and the DEM's noise",
                 "Each specimen was prepared and sheared with every seed of the scene; the fit and the "
                 "checks read the mean of its runs (`sffcal.mean_of_seeds`: the series interpolated "
                 "onto the first seed's rows up to the strain all reached, the SFF tables snapshot by "
                 "snapshot). Noise: the RMS over those rows of the standard deviation across the seeds "
                 "(two seeds: RMS difference / √2).")
        page.table(["specimen", "seeds", "noise q/p", "noise ε_v", "noise p/p0"],
                   [(name, ", ".join(map(str, r["seeds"])), f"{r['noise']['eta']:.4f}",
                     f"{r['noise']['volumetric_strain']:.4f}", f"{r['noise']['p_ratio']:.4f}")
                    for name, r in noise.items()])

    page.add("## Timing of the stages",
             "Snakemake's benchmark records (`benchmarks/`): the wall-clock seconds of each job's "
             "last run, summed over the stage's jobs, which may have run in parallel.")
    rows, total = benchmark_times(out)
    page.table(["stage", "wall-clock [s]", "jobs"], rows)
    page.add(f"Sum over the stages: {total:.0f} s ({total / 60:.1f} min).")

    page.add("## DEM triaxial tests",
             "Drained triaxial compression (σ3 held by the lateral servo walls, platens at a constant "
             "strain rate) unless the path column says otherwise (docs/dem.md, \"Loading paths\": "
             "undrained at constant volume, extension with the platens parting, ε_a and q/p < 0). "
             "Peak (largest |q/p|) and end q/p from the walls; end values are means over the last 5 % of "
             "|ε_a|; ε_v compression positive; how the run ended and the worst lateral-stress error "
             "|σ_lateral − σ3|/σ3 at the output rows are the DEM's own (/summary); I = the largest inertial "
             "number (quasi-static below 1e-3).")
    if runs:
        rows = [run_row(r, role.get(specimen_of(runfile.name_of(r)), "analysed only")) for r in runs]
        page.table(["specimen", "role", "path", "clumps", "σ3 [kPa]", "e0", "peak q/p", "end q/p", "end e",
                    "end ε_v [%]", "end ε_a [%]", "ended", "servo error [%]", "max I", "min q/p"], rows)
        unstable = [row[0] for row in rows if float(row[-1]) < -0.05 and "extension" not in row[2]]
        if unstable:
            page.add(f"**Note:** q/p falls below zero early in the shearing of {', '.join(unstable)} "
                     "(lateral stress above the axial one): most likely the packing is not stable once the "
                     "friction changes from its compaction value to the shearing value; its first strain "
                     "increments are a collapse (see ε_v), not a quasi-static drained path.")
        overview = os.path.join(out, "report", "triaxial_all.png")
        solid = [r for r in runs if specimen_of(runfile.name_of(r)) not in held]
        subprocess.run([sys.executable, os.path.join(HERE, "plot_runs.py"), *solid, "-o", overview,
                        "--held-back", *[r for r in runs if r not in solid]], check=True)
        page.add("![q/p, volumetric strain and void ratio of every specimen](triaxial_all.png)",
                 "*Stress ratio, volumetric strain and void ratio against axial strain (dashed: held back).*")
        for r in runs:
            page.image(r[:-3] + ".png", f"{os.path.basename(r)[:-3]}: q/p from walls and contacts, ε_v, e")
    else:
        page.add("*No run files yet (stage triaxial).*")

    page.add("## SFF analysis",
             "Per specimen (`sffcal sff`, docs/sff.md): stress ratio and the SFF prediction at the "
             "peak and the last snapshot, with the anisotropies of contact normals a_c, normal forces "
             "a_n and the mobilisation m.")
    analysed = [r for r in runs if os.path.exists(os.path.join(out, "sff", os.path.basename(r) + ".sff.csv"))]
    if analysed:
        table = subprocess.run([sys.executable, os.path.join(HERE, "sff_table.py"), *analysed],
                               check=True, capture_output=True, text=True).stdout
        page.add(table.strip())
        page.image(os.path.join(out, "sff", "anisotropy.png"), "a_c, a_n and m against axial strain")
        for r in analysed:
            stem = os.path.basename(r)[:-3]
            page.image(os.path.join(out, "sff", stem + "_eta.png"), f"{stem}: SFF decomposition of q/p")
            page.image(os.path.join(out, "sff", stem + "_rose.png"),
                       f"{stem}: rose diagrams of contact normals and mean normal force (initial, peak, last)")
    else:
        page.add("*Not analysed yet (stage sff).*")

    page.add(f"## Calibration of the {fitted_model_name(out)}",
             f"Fitted (`sffcal calibrate`, docs/calibration.md) on {', '.join(fitted)}; "
             f"options {' '.join(scene.get('calibrate', {}).get('options', [])) or 'none'}. "
             "The summary as written by the fit:")
    summary = os.path.join(out, "calibrate", "summary.md")
    if os.path.exists(summary):
        page.add(demote(open(summary).read().strip()))
        for png in sorted(glob.glob(os.path.join(out, "calibrate", "*_calibration.png"))):
            page.image(png, f"{os.path.basename(png)[:-16]}: model (lines) against DEM (points)")
    else:
        page.add("*Not calibrated yet (stage calibrate).*")

    page.add("## FE element checks against the driver and the DEM",
             "`sffcal fe-check` (docs/fe.md) with the calibrated parameters: one Q1 element against "
             "the material-point driver (must agree to 1e-8), and against every drained-compression DEM specimen, "
             f"including the one(s) held back from the fit ({', '.join(held) or 'none'}): a prediction.")
    fe = os.path.join(out, "fe_check", "summary.csv")
    if os.path.exists(fe):
        rows = runfile.read_csv_rows(fe)
        page.table(rows[0], [[f"**{c}**" if c == "fail" else c for c in row] for row in rows[1:]])
        status = run_status(os.path.join(out, "logs", "fe-check_check.log"))
        if status:
            page.add("How each run ended (from the fe-check log):", "```", *status, "```")
        page.image(os.path.join(out, "fe_check", "fe_check.png"),
                   "q/p, ε_v and F:n_c: DEM, driver, FE element (one row per case)")
    else:
        page.add("*Not checked yet (stage fe-check).*")

    page.add("## Logs", "Every job's output: `logs/<stage>_<task>.log`; the workflow's own: `pipeline.log` "
             "(`scripts/pipeline.py`) and Snakemake's `.snakemake/log/`.")
    return "\n".join(page.lines)


def to_html(text):
    """The page as HTML, by Debian's python3-markdown (tables and fenced code)."""
    body = markdown.markdown(text, extensions=["tables", "fenced_code"])
    style = ("body{font-family:sans-serif;max-width:70em;margin:auto}table{border-collapse:collapse}"
             "td,th{border:1px solid #bbb;padding:2px 6px;font-size:90%}img{max-width:100%}")
    return (f"<!DOCTYPE html><html><head><meta charset='utf-8'><title>sffcal main job</title>"
            f"<style>{style}</style></head><body>\n{body}\n</body></html>\n")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("out", help="output folder of the main job (workflow/Snakefile)")
    parser.add_argument("--scene", required=True)
    args = parser.parse_args()
    page = write_markdown(args.out, args.scene)
    folder = os.path.join(args.out, "report")
    with open(os.path.join(folder, "report.md"), "w") as f:
        f.write(page)
    with open(os.path.join(folder, "report.html"), "w") as f:
        f.write(to_html(page))
    print(f"wrote {folder}/report.md and report.html")


if __name__ == "__main__":
    main()
