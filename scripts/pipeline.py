#!/usr/bin/python3
"""The main job, end to end: prepare specimens (one or several packing seeds each), shear them on
their loading paths, analyse them with SFF, average the seeds, calibrate the ACST model, run the
deal.II element checks, write a report. The command line of the Snakemake workflow
workflow/Snakefile, which does the work.

usage: scripts/pipeline.py [--scene FILE | --matrix] [-o OUT] [--only STAGE[,STAGE] | --from STAGE]
                           [--force] [--sffcal PATH] [--jobs N] [-n] [-- SNAKEMAKE OPTIONS]

Stages, in order: prepare, triaxial, sff, mean, calibrate, fe-check, report. A job whose inputs,
parameters and commands are unchanged since it ran is not run again (Snakemake's records, in
OUT/.snakemake/). The scene (default examples/main_scene.toml; --matrix:
examples/matrix_scene.toml, the paper-size matrix) names the specimens. Outputs under OUT
(default out/main): configs/, specimens/, runs/, vtk/, sff/, mean/ (several seeds), calibrate/,
fe_check/, logs/, benchmarks/ and report/report.md (+ report.html); the console's lines are
appended to OUT/pipeline.log. Options after `--` go to Snakemake as they are, e.g.
`-- --profile workflow/profiles/slurm` (a Slurm cluster). See docs/pipeline.md.
"""
import argparse
import glob
import os
import re
import shlex
import subprocess
import sys
import threading
import time

from sffcal import scene as scenes

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
SNAKEFILE = os.path.join(ROOT, "workflow", "Snakefile")
# Each stage: the target that makes all of its outputs, and its rules (workflow/Snakefile).
STAGES = {
    "prepare": ("all_prepare", ["prepare", "prepare_deposit"]),
    "triaxial": ("all_triaxial", ["triaxial"]),
    "sff": ("sff", ["sff"]),
    "mean": ("all_mean", ["mean"]),
    "calibrate": ("calibrate", ["calibrate"]),
    "fe-check": ("fe_check", ["fe_check"]),
    "report": ("report", ["report"]),
}
ALWAYS_ALLOWED = ["all_prepare", "all_triaxial", "all_mean"]  # the stages' targets
HEARTBEAT_S = 30.0  # how often the last line of a job's log is shown while Snakemake is silent


class UsageError(Exception):
    pass


def selected_stages(only, start):
    """The stages --only or --from names, in the order of the job; None for all of them."""
    names = list(STAGES)
    if only:
        chosen = only.split(",")
        unknown = [s for s in chosen if s not in STAGES]
        if unknown:
            raise UsageError(f"--only: unknown stage '{unknown[0]}' (stages: {', '.join(names)})")
        return [s for s in names if s in chosen]
    if start:
        if start not in STAGES:
            raise UsageError(f"--from: unknown stage '{start}' (stages: {', '.join(names)})")
        return names[names.index(start):]
    return None


def snakemake_command(args, jobs):
    """The Snakemake command line of the options: --only STAGES makes those stages' targets with
    only their rules allowed (an output of an earlier stage that is missing is an error naming
    it); --from STAGE makes the report with the rules of STAGE and later ones; --force forces the
    selected stages' jobs (--forcerun: and those after them that are selected), or every job."""
    stages = selected_stages(args.only, args.start)
    # the targets first: options take several values, and a profile (-- --profile) adds its own last
    targets = [STAGES[s][0] for s in stages] if args.only else ["report"]
    # The greedy scheduler: the ILP one solves an integer program with CBC whenever a job ends, and
    # was no faster on the main job (bench/RESULTS.md, "The main job on Snakemake alone").
    # --rerun-incomplete: a job killed with its outputs half-written runs again.
    command = ["snakemake", *targets, "-s", SNAKEFILE, "--directory", args.output, "--cores", str(jobs),
               "--scheduler", "greedy", "--rerun-incomplete",
               "--config", f"scene={os.path.abspath(args.scene)}", f"sffcal={os.path.abspath(args.sffcal)}"]
    if stages is None:
        command += ["--forceall"] if args.force else []
    else:
        rules = [r for s in stages for r in STAGES[s][1]]
        command += ["--allowed-rules", *ALWAYS_ALLOWED, *rules]
        command += ["--forcerun", *rules] if args.force else []
    if args.dry_run:
        command += ["--dry-run"]
    return command + args.snakemake


class Console:
    """Snakemake's output on the console and appended to OUT/pipeline.log, each line with the
    minutes since the start; while Snakemake is silent, every HEARTBEAT_S the last line of each
    job log under OUT/logs that changed since the last look."""

    def __init__(self, out):
        self.out, self.start, self.lock = out, time.monotonic(), threading.Lock()
        self.file = open(os.path.join(out, "pipeline.log"), "a")
        self.last_output = self.last_look = time.time()

    def line(self, text):
        elapsed = time.monotonic() - self.start
        with self.lock:
            line = f"{int(elapsed // 60):3d}:{int(elapsed % 60):02d} {text}"
            print(line, flush=True)
            self.file.write(line + "\n")
            self.file.flush()
            self.last_output = time.time()

    def heartbeat(self, done):
        while not done.wait(HEARTBEAT_S):
            if time.time() - self.last_output >= HEARTBEAT_S:
                for log in sorted(glob.glob(os.path.join(self.out, "logs", "*.log"))):
                    if os.path.getmtime(log) > self.last_look:
                        self.line(f"  running: {os.path.relpath(log, self.out)}: {tail(log, 1)[0]}")
            self.last_look = time.time()  # each look covers the logs that changed since the last


def tail(path, count):
    """The last `count` non-empty lines of a log (at most 160 characters each)."""
    if not os.path.exists(path):
        return ["(no log)"]
    with open(path, "rb") as f:
        f.seek(max(0, os.path.getsize(path) - 8192))
        lines = [l for l in f.read().decode(errors="replace").replace("\r", "\n").splitlines() if l.strip()]
    return [l[:160] for l in lines[-count:]] or ["(empty)"]


def main():
    title, _, *rest = __doc__.split("\n\n")  # the usage paragraph is argparse's own
    parser = argparse.ArgumentParser(description="\n\n".join([title] + rest),
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--scene", help="scene file (default examples/main_scene.toml)")
    parser.add_argument("--matrix", action="store_true",
                        help="the paper-size matrix: --scene examples/matrix_scene.toml, -o out/main-matrix")
    parser.add_argument("-o", "--output", help="output folder (default out/main)")
    parser.add_argument("--only", help="run only these stages (comma separated), on the files in OUT")
    parser.add_argument("--from", dest="start", help="run this stage and the later ones")
    parser.add_argument("--force", action="store_true", help="rerun the selected stages even if up to date")
    parser.add_argument("--sffcal", default=os.environ.get("SFFCAL", os.path.join(ROOT, "build", "sffcal")),
                        help="the sffcal binary (default $SFFCAL, else build/sffcal)")
    parser.add_argument("--jobs", type=int, help="cores: jobs at once, one core each, where the SFF "
                        "analysis and the fit take them all (default: the scene's jobs)")
    parser.add_argument("-n", "--dry-run", action="store_true", help="say what would run, and why; run nothing")
    argv = sys.argv[1:]
    split = argv.index("--") if "--" in argv else len(argv)
    args = parser.parse_args(argv[:split])
    args.snakemake = argv[split + 1:]
    args.scene = args.scene or os.path.join(ROOT, "examples", "matrix_scene.toml" if args.matrix else "main_scene.toml")
    args.output = args.output or os.path.relpath(os.path.join(ROOT, "out", "main-matrix" if args.matrix else "main"))
    try:
        if args.only and args.start:
            raise UsageError("give --only or --from, not both")
        scene = scenes.read_scene(args.scene)
        jobs = args.jobs or scene.get("jobs", 1)
        if jobs < 1:
            raise UsageError(f"--jobs {jobs}: give at least 1")
        command = snakemake_command(args, jobs)
        if not os.access(args.sffcal, os.X_OK) and (args.only or "") != "report":
            raise UsageError(f"sffcal binary {args.sffcal} not found: build it (scripts/build.sh) "
                             "or pass --sffcal PATH / set SFFCAL")
    except (UsageError, scenes.SceneError) as e:
        sys.exit(f"pipeline.py: {e}")
    os.makedirs(args.output, exist_ok=True)
    console = Console(args.output)
    console.line(f"scene {args.scene}: {len(scene['specimens'])} specimens x {len(scene['seeds'])} "
                 f"seeds, output {args.output}")
    console.line("$ " + shlex.join(command))
    done = threading.Event()
    threading.Thread(target=console.heartbeat, args=(done,), daemon=True).start()
    # Snakemake and its jobs work in OUT: the package sffcal is found there by absolute paths
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(
        os.path.abspath(p) for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p))
    snakemake = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                                 errors="replace", env=env)
    failed_logs = []  # the logs of failed jobs, which Snakemake names but does not show
    try:
        for line in snakemake.stdout:
            console.line(line.rstrip("\n"))
            failed = re.match(r"\s+log: (\S+) \(check log file", line)
            if failed:
                failed_logs.append(os.path.join(args.output, failed.group(1)))
        code = snakemake.wait()
    except KeyboardInterrupt:  # Snakemake got it too: it removes the outputs of the jobs it stops
        code = snakemake.wait()
        console.line("interrupted; the jobs that were running rerun next time")
        return 130
    finally:
        done.set()
    if code == 0 and args.dry_run:
        console.line("a dry run: nothing was run")
    elif code == 0:
        report_log = os.path.join(args.output, "logs", "report_report.log")
        for line in tail(report_log, 20) if os.path.exists(report_log) else []:
            if line.startswith("checks:"):  # the report's count of passed checks
                console.line(line)
        console.line(f"finished in {time.monotonic() - console.start:.0f} s; report: "
                     f"{os.path.join(args.output, 'report', 'report.md')}")
    else:
        for log in failed_logs:
            console.line(f"the end of {log}:")
            for line in tail(log, 6):
                console.line("    " + line)
        console.line(f"stopped: Snakemake exited with {code} (the error is above; each job's log is "
                     f"{os.path.join(args.output, 'logs')}/<stage>_<task>.log)")
    return 1 if code else 0


if __name__ == "__main__":
    sys.exit(main())
