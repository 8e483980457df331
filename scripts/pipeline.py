#!/usr/bin/python3
"""The main job, end to end: prepare specimens (one or several packing seeds each), shear them on
their loading paths, analyse them with SFF, average the seeds, calibrate the ACST model, run the
deal.II element checks, write a report.

usage: scripts/pipeline.py [--scene FILE | --matrix] [-o OUT] [--only STAGE[,STAGE] | --from STAGE]
                           [--force] [--sffcal PATH] [--jobs N]

Stages, in order: prepare, triaxial, sff, mean, calibrate, fe-check, report. Each declares the files it
reads and writes; one whose inputs are unchanged since its last run (and whose outputs exist) is
skipped and says so. The scene (default examples/main_scene.toml; --matrix:
examples/matrix_scene.toml, the paper-size matrix) names the specimens. Outputs under OUT
(default out/main): configs/, specimens/, runs/, vtk/, sff/, mean/ (several seeds), calibrate/,
fe_check/, logs/ and report/report.md (+ report.html). See docs/pipeline.md.
"""
import argparse
import os
import sys
import time

from pipeline_tasks import Runner, StageFailed, Task
from sffcal import matrix as specimen_matrix
from sffcal import scene as scenes

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
STAGES = ["prepare", "triaxial", "sff", "mean", "calibrate", "fe-check", "report"]
PY = sys.executable


class Pipeline:
    def __init__(self, args, scene, runner):
        self.args, self.scene, self.runner = args, scene, runner
        self.out = args.output
        self.sffcal = args.sffcal

    def path(self, *parts):
        return os.path.join(self.out, *parts)

    def stems(self, name):
        return scenes.stems(self.scene, name)

    def instances(self):
        return scenes.instances(self.scene)

    def run_file(self, stem):
        return self.path("runs", stem + ".h5")

    def test_file(self, name):
        return self.path(scenes.test_stem(self.scene, name))

    def write_configs(self):
        """The scene's specimen configs (sffcal.scene; cheap, every start: the records compare
        contents, so rewriting an unchanged config reruns nothing)."""
        folder = self.path("configs")
        os.makedirs(folder, exist_ok=True)
        try:
            configs = scenes.run_configs(self.scene, ROOT)
        except scenes.SceneError as e:
            raise StageFailed(str(e))
        for stem, text in configs.items():
            with open(os.path.join(folder, stem + ".toml"), "w") as f:
                f.write(text)

    def tasks(self, stage):
        """The tasks of one stage: inputs, outputs and commands."""
        names = self.scene["specimens"]
        stems = [stem for _, _, stem in self.instances()]
        runs = [self.run_file(stem) for stem in stems]
        several = len(self.scene["seeds"]) > 1
        fitted = [self.test_file(n) for n in self.scene["calibrate_on"]]
        held = [self.test_file(n) for n in self.scene.get("held_back", [])]
        # fe-check's element runs drained compression only; the calibration predicts the others
        checked = [self.test_file(n) for n in scenes.checked(self.scene)]
        made_by_triaxial = {r: "triaxial" for r in runs}
        # the tests the fit and the checks read: the runs or the means of their seeds
        made_by_test = {self.test_file(n): "mean" if several else "triaxial" for n in names}
        if stage == "prepare":
            if self.scene.get("matrix"):
                return []  # run_matrix.sh prepares and shears in one `sffcal dem`
            self.write_configs()
            return [Task(stage, n, [self.path("configs", n + ".toml")], [self.path("specimens", n + ".h5")],
                         [[self.sffcal, "prepare", "-c", self.path("configs", n + ".toml"),
                           "-o", self.path("specimens", n + ".h5"), "--force"]]) for n in stems]
        if stage == "triaxial":
            if self.scene.get("matrix"):
                script = os.path.join(ROOT, "bench", "matrix", "run_matrix.sh")
                return [Task(stage, "matrix", [script, os.path.join(ROOT, specimen_matrix.TEMPLATE)], runs,
                             # absolute: run_matrix.sh works from the repository root
                             [[script, os.path.abspath(self.path("runs")), str(self.runner.jobs),
                               str(self.scene["bodies"])]],
                             options=str(self.scene["bodies"]))]
            self.write_configs()
            tasks = []
            for n in stems:
                config, specimen, run = self.path("configs", n + ".toml"), self.path("specimens", n + ".h5"), self.run_file(n)
                vtk = self.path("vtk", n)
                tasks.append(Task(stage, n, [config, specimen],
                                  [run, self.path("runs", n + ".png"), os.path.join(vtk, "spheres.pvd")],
                                  [[self.sffcal, "triaxial", "-c", config, "-s", specimen, "-o", run, "--force"],
                                   [PY, os.path.join(ROOT, "bench", "reference", "plot_triaxial.py"),
                                    run, self.path("runs", n + ".png")],
                                   [self.sffcal, "vtk", run, "-o", vtk]],  # snapshots for ParaView
                                  made_by={specimen: "prepare"}))
            return tasks
        if stage == "sff":
            sff = self.path("sff")
            return [Task(stage, "all", runs,
                         [os.path.join(sff, n + ".h5.sff.csv") for n in stems] + [os.path.join(sff, "anisotropy.png")],
                         [[self.sffcal, "sff", *runs, "-o", sff],
                          [PY, os.path.join(ROOT, "scripts", "plot_sff.py"), *runs, "-o", sff]],
                         made_by=made_by_triaxial)]
        if stage == "mean":
            if not several:
                return []  # one seed: the fit and the checks read the runs themselves
            tasks = []
            for n in names:
                seed_runs = [self.run_file(stem) for stem in self.stems(n)]
                mean = self.test_file(n)
                tasks.append(Task(stage, n, seed_runs, [mean, mean[:-3] + ".noise.json"],
                                  [[PY, os.path.join(ROOT, "scripts", "mean_of_seeds.py"), *seed_runs,
                                    "-o", mean, "--force"]],
                                  made_by={r: "triaxial" for r in seed_runs}))
            return tasks
        if stage == "calibrate":
            fit = self.path("calibrate")
            hold_out = ["--hold-out", *held] if held else []
            return [Task(stage, "fit", fitted + held,
                         [os.path.join(fit, "parameters.json"), os.path.join(fit, "summary.md")],
                         [[self.sffcal, "calibrate", *fitted, *hold_out, "-o", fit,
                           *self.scene.get("calibrate", {}).get("options", [])],
                          [PY, os.path.join(ROOT, "scripts", "plot_calibration.py"), fit]],
                         made_by=made_by_test)]
        if stage == "fe-check":
            params, check = self.path("calibrate", "parameters.json"), self.path("fe_check")
            dem = [a for r in checked for a in ("--dem", r)]
            return [Task(stage, "check", [params] + checked,
                         [os.path.join(check, "summary.csv"), os.path.join(check, "fe_check.png")],
                         [[self.sffcal, "fe-check", "--parameters", params, *dem, "-o", check,
                           *self.scene.get("fe_check", {}).get("options", [])],
                          [PY, os.path.join(ROOT, "scripts", "plot_fe_check.py"), check]],
                         check_codes=(1, 2),  # 2: FE vs DEM off; 1: also a verification check or a run
                         made_by={params: "calibrate", **made_by_test})]
        if stage == "report":
            # whatever the earlier stages left: the report covers what exists
            noise = [self.test_file(n)[:-3] + ".noise.json" for n in names] if several else []
            inputs = [p for p in [self.args.scene] + runs + noise
                      + [self.path("calibrate", "summary.md"), self.path("fe_check", "summary.csv")]
                      + [self.path(".records", s, "_stage.json") for s in STAGES[:-1]] if os.path.exists(p)]
            return [Task(stage, "report", inputs,
                         [self.path("report", "report.md"), self.path("report", "report.html")],
                         [[PY, os.path.join(ROOT, "scripts", "pipeline_report.py"), self.out,
                           "--scene", self.args.scene]])]
        raise ValueError(stage)


def selected_stages(args):
    if args.only:
        chosen = args.only.split(",")
        for stage in chosen:
            if stage not in STAGES:
                raise StageFailed(f"--only: unknown stage '{stage}' (stages: {', '.join(STAGES)})")
        return [s for s in STAGES if s in chosen]
    if args.start:
        if args.start not in STAGES:
            raise StageFailed(f"--from: unknown stage '{args.start}' (stages: {', '.join(STAGES)})")
        return STAGES[STAGES.index(args.start):]
    return STAGES


def main():
    title, _, *rest = __doc__.split("\n\n")  # the usage paragraph is argparse's own
    parser = argparse.ArgumentParser(description="\n\n".join([title] + rest),
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--scene", help="scene file (default examples/main_scene.toml)")
    parser.add_argument("--matrix", action="store_true",
                        help="the paper-size matrix: --scene examples/matrix_scene.toml, -o out/main-matrix")
    parser.add_argument("-o", "--output", help="output folder (default out/main)")
    parser.add_argument("--only", help="run only these stages (comma separated)")
    parser.add_argument("--from", dest="start", help="run this stage and the later ones")
    parser.add_argument("--force", action="store_true", help="rerun the selected stages even if up to date")
    parser.add_argument("--sffcal", default=os.environ.get("SFFCAL", os.path.join(ROOT, "build", "sffcal")),
                        help="the sffcal binary (default $SFFCAL, else build/sffcal)")
    parser.add_argument("--jobs", type=int, help="tasks at once (default: the scene's jobs)")
    args = parser.parse_args()
    args.scene = args.scene or os.path.join(ROOT, "examples", "matrix_scene.toml" if args.matrix else "main_scene.toml")
    args.output = args.output or os.path.relpath(os.path.join(ROOT, "out", "main-matrix" if args.matrix else "main"))
    os.makedirs(args.output, exist_ok=True)

    start = time.monotonic()
    log_file = open(os.path.join(args.output, "pipeline.log"), "a")

    def log(text):
        elapsed = time.monotonic() - start
        line = f"{int(elapsed // 60):3d}:{int(elapsed % 60):02d} {text}"
        print(line, flush=True)
        log_file.write(line + "\n")
        log_file.flush()

    try:
        try:
            scene = scenes.read_scene(args.scene)
        except scenes.SceneError as e:
            raise StageFailed(str(e))
        stages = selected_stages(args)
        if not os.access(args.sffcal, os.X_OK) and any(s != "report" for s in stages):
            raise StageFailed(f"sffcal binary {args.sffcal} not found: build it (scripts/build.sh) "
                              "or pass --sffcal PATH / set SFFCAL")
        runner = Runner(args.output, args.jobs or scene.get("jobs", 1), args.force, log)
        pipeline = Pipeline(args, scene, runner)
        log(f"scene {args.scene}: {len(scene['specimens'])} specimens, output {args.output}, "
            f"stages {', '.join(stages)}")
        for stage in stages:
            log(f"== {stage} ==")
            runner.run_stage(stage, pipeline.tasks(stage))
    except StageFailed as e:
        log(str(e))
        log("pipeline stopped; the later stages did not run")
        return 1
    except KeyboardInterrupt:
        log("interrupted; the task that was running reruns next time")
        return 130
    for warning in runner.warnings:
        log("WARNING " + warning)
    log(f"pipeline finished in {time.monotonic() - start:.0f} s; report: "
        f"{os.path.join(args.output, 'report', 'report.md')}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
