#!/usr/bin/python3
"""Side-by-side timing of LAMMPS and sffcal's DEM on the same 10,000-clump specimen.

    /usr/bin/python3 bench/lammps/run.py                 # the README's table (about 20-25 min)
    /usr/bin/python3 bench/lammps/run.py --repeats 1 --nsteps 1000     # a quick look
    /usr/bin/python3 bench/lammps/run.py --tables-only   # results.md again from results.csv

1. Makes the specimen with `sffcal prepare` (10,000 monodisperse clumps, d = 50 um, compacted
   at 100 kPa with friction 0.1; skipped when WORK/specimen.h5 exists) and exports it to LAMMPS
   (export.py: data.lmp, bodies.txt, specimen.in, lateral.in).
2. Runs sffcal's test once, untimed, with a series row every 1/100 of the timed steps: the path
   its servo gives the lateral walls, fitted (degree 5 in time) and written to export/lateral.in,
   which LAMMPS's lateral walls then follow; and sffcal's list builds over the timed steps.
3. Times --nsteps steps of --dt at --rate in both codes: LAMMPS (shear.in) on 1 and 2 MPI ranks,
   `sffcal triaxial` on 1 and 2 OpenMP threads, alternated (LAMMPS, sffcal, LAMMPS, sffcal, then
   sffcal's file-output runs and the variants: LAMMPS with fixed primitive lateral walls, sffcal
   on 2 spinning threads). Each run starts through bench/liggghts/cpuguard.py: it waits until
   the machine is idle and reports the CPU other processes used meanwhile; a run disturbed by
   more than --max-foreign cores is repeated (up to --retries times).
4. Times: LAMMPS's "Loop time" (setup excluded); sffcal's /summary wall_seconds (the test's loop:
   the steps, the lateral servo, two series rows, a snapshot and a checkpoint at the start and a
   snapshot at the end; reading the specimen and building the engine excluded). That file output
   is measured by the same test run for --short-steps steps (alternated as well) and its median
   is subtracted for the "file output excluded" column.
5. Writes OUT/results.md, OUT/results.csv (every run) and OUT/path.json, and copies the LAMMPS
   logs to OUT/logs (the cpuguard lines stay in WORK/*.screen).

Figures: sphere-steps/s per core = spheres x steps / seconds / (ranks or threads).
Everything runs in WORK (default /tmp/sffcal-lammps-bench): LAMMPS writes there, never into the
repository. Needs: build/sffcal, lmp (Debian `lammps`, 29 Sep 2021), mpirun, /usr/bin/python3
with h5py and numpy.
"""
import argparse
import csv
import glob
import json
import os
import re
import shutil
import statistics
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
DECK = os.path.join(ROOT, "examples", "lammps", "walls")  # shear.in, export.py and the servo
CPUGUARD = os.path.join(ROOT, "bench", "liggghts", "cpuguard.py")

# The scene (SI units). Monodisperse, so that LAMMPS's constant hooke k_n = E r equals sffcal's
# K = 2 E r1 r2 / (r1 + r2) for every pair.
SCENE = dict(diameter=5.0e-5, density=2650.0, E=1.5e8, ratio=0.5, mu=0.5, pressure=1.0e5,
             compaction_friction=0.1)

PREPARE_TOML = """# bench/lammps: the specimen (written by run.py)
seed = {seed}
threads = 2
bodies = {bodies}
[grains]
min_diameter = {diameter!r}
max_diameter = {diameter!r}
centre_distance_ratio = 0.5
density = {density!r}
[contact]
youngs_modulus = {E!r}
stiffness_ratio = {ratio!r}
friction = {mu!r}
wall_friction = 0.0
normal_damping_ratio = 0.0
[preparation]
method = "compaction"
pressure = {pressure!r}
compaction_friction = {compaction_friction!r}
"""

# The shearing run: an explicit time step (the one LAMMPS gets), no dashpot or local damping,
# one series row at the start and one at the end, a snapshot only at the start and the end, no
# early stop at a critical state.
SHEAR_TOML = PREPARE_TOML.replace("[preparation]", "[engine]\ntime_step = {dt!r}\n\n[preparation]") + """
[triaxial]
strain_rate = {rate!r}
max_axial_strain = {strain!r}
output_strain_interval = {strain!r}
snapshot_strain_interval = 1.0
checkpoint_strain_interval = 1.0
critical_min_strain = 1.0
"""
SHEAR_TOML = SHEAR_TOML.replace("threads = 2", "threads = {threads}")


def sh(cmd, **kw):
    print("run.py: " + " ".join(cmd), flush=True)
    return subprocess.run(cmd, check=True, **kw)


def guarded(cmd, log_path, args, env=None):
    """Run cmd through cpuguard.py (stdout+stderr to log_path); repeat while foreign load is high."""
    for attempt in range(args.retries + 1):
        with open(log_path, "w") as out:
            rc = subprocess.call([sys.executable, CPUGUARD, "--idle-wait", str(args.idle_wait), "--"] + cmd,
                                 stdout=out, stderr=subprocess.STDOUT, env=env)
        text = open(log_path).read()
        if rc != 0:
            sys.exit("run.py: failed (%d): %s\n%s" % (rc, " ".join(cmd), text[-3000:]))
        m = re.search(r"CPUGUARD wall_s=(\S+) child_cpu_s=(\S+) foreign_cores=(\S+) idle_wait_s=(\S+)", text)
        foreign = float(m.group(3))
        if foreign <= args.max_foreign:
            return text, foreign
        print("run.py:   foreign load %.2f cores during the run, repeating" % foreign, flush=True)
    return text, foreign


def lammps_case(np_, walls, args, work, tag):
    """One timed LAMMPS run: walls 'moving' (all six walls as moving regions, the lateral ones
    along sffcal's path) or 'fixed' (lateral walls fixed primitive planes)."""
    log = os.path.join(work, "lammps_%s.log" % tag)
    cmd = ["lmp", "-in", os.path.join(DECK, "shear.in"), "-log", log, "-var", "deck", DECK,
           "-var", "spec", os.path.join(work, "export"), "-var", "lateral_walls", walls,
           "-var", "nsteps", str(args.nsteps), "-var", "dt", repr(args.dt), "-var", "rate", repr(args.rate),
           "-var", "E", repr(SCENE["E"]), "-var", "ratio", repr(SCENE["ratio"]), "-var", "mu", repr(SCENE["mu"])]
    if np_ > 1:
        cmd = ["mpirun"] + (["--allow-run-as-root"] if os.geteuid() == 0 else []) + ["-np", str(np_)] + cmd
    screen, foreign = guarded(cmd, os.path.join(work, "lammps_%s.screen" % tag), args)
    txt = open(log).read()
    seg = txt.split("\nTIMED_SEGMENT_BEGIN\n", 1)[1].split("\nTIMED_SEGMENT_END\n", 1)[0]
    m = re.search(r"^Loop time of (\S+) on (\d+) procs for (\d+) steps with (\d+) atoms", seg, re.M)
    loop, procs, steps, atoms = float(m.group(1)), int(m.group(2)), int(m.group(3)), int(m.group(4))
    breakdown = {k: float(v) for k, v in re.findall(
        r"^(Pair|Neigh|Comm|Output|Modify|Other)\s*\|.*\|\s*([0-9.]+)\s*$", seg, re.M)}
    builds = int(re.search(r"Neighbor list builds = (\d+)", seg).group(1))
    res = dict(re.findall(r"(\w+) (\S+)", re.search(r"^BENCH_RESULT (.*)$", txt, re.M).group(1)))
    return dict(code="LAMMPS" if walls == "moving" else "LAMMPS-fixed-lateral", workers=procs, steps=steps,
                spheres=atoms, seconds=loop, foreign=foreign, builds=builds, breakdown=breakdown,
                contacts_per_sphere=float(res["contacts_per_sphere"]), strain=float(res["axial_strain"]),
                eta=float(res["eta"]), p=float(res["p"]), sigma_3=0.5 * (float(res["sxx"]) + float(res["syy"])),
                void_ratio=float(res["void_ratio"]))


def sffcal_case(threads, args, work, tag, short=False, active=False):
    """One timed `sffcal triaxial` run; its figures from the run file's /summary and last row.
    active: OMP_WAIT_POLICY=ACTIVE (idle threads spin, as Open MPI's ranks poll; sffcal's default
    is PASSIVE, docs/dem.md "Parallelism and determinism")."""
    import h5py
    cfg = os.path.join(work, "shear_t%d%s.toml" % (threads, "_short" if short else ""))
    run = os.path.join(work, "sffcal_%s.h5" % tag)
    for old in glob.glob(run + "*"):
        os.remove(old)
    env = dict(os.environ, OMP_WAIT_POLICY="ACTIVE") if active else None
    screen, foreign = guarded([args.sffcal, "triaxial", "-c", cfg, "-s", os.path.join(work, "specimen.h5"),
                               "-o", run], os.path.join(work, "sffcal_%s.screen" % tag), args, env=env)
    with h5py.File(run, "r") as f:
        summary = f["summary"].attrs
        last = f["snapshots"][sorted(f["snapshots"].keys())[-1]]
        contacts = last["contacts"][:]
        spheres = len(last["spheres"])
        series = f["series"]
        code = "sffcal-output" if short else ("sffcal-spinning" if active else "sffcal")
        out = dict(code=code, workers=threads, steps=int(summary["steps"]),
                   spheres=spheres, seconds=float(summary["wall_seconds"]), foreign=foreign,
                   contacts_per_sphere=2.0 * int((contacts["body_a"] >= 0).sum()) / spheres,
                   strain=float(summary["axial_strain"]), eta=float(series["eta"][-1]),
                   p=float(series["p"][-1]), sigma_3=float(series["sigma_3"][-1]),
                   void_ratio=float(series["void_ratio"][-1]))
    for old in glob.glob(run + "*"):  # 3 MB each; the figures are kept in results.csv
        os.remove(old)
    return out


def sffcal_path(args, work):
    """Untimed sffcal run over the timed steps and as many again, a series row every 1/100 of
    them and a checkpoint after exactly them. Gives the lateral walls' path (fitted and written
    to export/lateral.in for LAMMPS), the list builds over the timed steps and the state there."""
    import h5py
    import numpy as np
    sys.dont_write_bytecode = True  # no __pycache__ in the repository
    sys.path.insert(0, DECK)
    from export import write_lateral
    strain = args.nsteps * args.rate * args.dt
    cfg = os.path.join(work, "path.toml")
    text = SHEAR_TOML.format(seed=args.seed, bodies=args.bodies, threads=2, dt=args.dt, rate=args.rate,
                             strain=2 * strain, **SCENE)
    text = text.replace("output_strain_interval = %r" % (2 * strain), "output_strain_interval = %r" % (strain / 100))
    text = text.replace("checkpoint_strain_interval = 1.0", "checkpoint_strain_interval = %r" % strain)
    open(cfg, "w").write(text)
    run = os.path.join(work, "path.h5")
    sh([args.sffcal, "triaxial", "-c", cfg, "-s", os.path.join(work, "specimen.h5"), "-o", run, "--force"],
       stdout=subprocess.DEVNULL)
    with h5py.File(os.path.join(work, "specimen.h5"), "r") as f0, h5py.File(run, "r") as f1:
        a0, a1 = f0["checkpoint"].attrs, f1["checkpoint"].attrs
        builds, steps = int(a1["num_builds"] - a0["num_builds"]), int(a1["step_count"] - a0["step_count"])
        t0 = float(a0["time"])
        s = {k: f1["series"][k][:] for k in ("time", "axial_strain", "wall_x_lower", "wall_x_upper",
                                              "wall_y_lower", "wall_y_upper")}
        walls0 = {(int(w["axis"]), int(w["upper"])): float(w["position"]) for w in f0["checkpoint"]["walls"][:]}
    # The lateral walls' displacement against the test's time, over the timed steps (and one row
    # beyond), as a polynomial without constant term: d(tau) = sum_k c_k tau^k, k = 1..5.
    tau = s["time"] - t0
    keep = s["axial_strain"] <= strain * 1.0101
    tau_max = tau[keep].max()
    x = tau[keep] / tau_max
    design = np.stack([x ** k for k in range(1, 6)], 1)
    formulas, worst = [], 0.0
    for name, (axis, upper) in (("wall_x_lower", (0, 0)), ("wall_x_upper", (0, 1)),
                                ("wall_y_lower", (1, 0)), ("wall_y_upper", (1, 1))):
        d = s[name][keep] - walls0[(axis, upper)]
        coef = np.linalg.lstsq(design, d, rcond=None)[0]
        worst = max(worst, np.abs(design @ coef - d).max())
        formulas.append("+".join("(%.17g)*time^%d" % (c / tau_max ** k, k) for k, c in enumerate(coef, 1)))
    write_lateral(os.path.join(work, "export", "lateral.in"), formulas,
                  "sffcal's lateral servo over the timed steps (run.py: degree-5 fit, worst residual %.3g m)" % worst)
    print("run.py: lateral walls follow sffcal's path (fit residual %.3g m; a step moves a platen %.3g m)"
          % (worst, 0.5 * args.rate * args.dt * (walls0[(2, 1)] - walls0[(2, 0)])))
    return builds, steps, worst


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--bodies", type=int, default=10000)
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--nsteps", type=int, default=5000, help="timed steps (default 5000)")
    p.add_argument("--short-steps", type=int, default=20, help="sffcal's file-output run (default 20)")
    p.add_argument("--dt", type=float, default=7.0e-8,
                   help="time step [s] in both codes (default 7e-8: sffcal's automatic choice on this "
                        "specimen, 0.7 x its critical step 1.0e-7 s, rounded)")
    p.add_argument("--rate", type=float, default=100.0, help="axial strain rate [1/s] (sffcal's default)")
    p.add_argument("--repeats", type=int, default=5)
    p.add_argument("--fixed-lateral-repeats", type=int, default=3,
                   help="repeats of the LAMMPS variant with fixed primitive lateral walls (0: none)")
    p.add_argument("--spinning-repeats", type=int, default=3,
                   help="repeats of sffcal on 2 threads with OMP_WAIT_POLICY=ACTIVE (0: none)")
    p.add_argument("--max-foreign", type=float, default=0.10,
                   help="cores of foreign CPU load tolerated during a timed run (default 0.10)")
    p.add_argument("--retries", type=int, default=3)
    p.add_argument("--idle-wait", type=float, default=600)
    p.add_argument("--work", default="/tmp/sffcal-lammps-bench")
    p.add_argument("--out", default=os.path.join(HERE, "results"))
    p.add_argument("--sffcal", default=os.path.join(ROOT, "build", "sffcal"))
    p.add_argument("--tables-only", action="store_true",
                   help="rewrite OUT/results.md from OUT/results.csv and OUT/path.json, run nothing")
    args = p.parse_args()
    if args.tables_only:
        out = os.path.abspath(args.out)
        rows = []
        with open(os.path.join(out, "results.csv")) as f:
            for r in csv.DictReader(f):
                row = dict(code=r["code"], workers=int(r["workers"]), repeat=int(r["repeat"]), steps=int(r["steps"]),
                           spheres=int(r["spheres"]), seconds=float(r["seconds"]), foreign=float(r["foreign_cores"]),
                           contacts_per_sphere=float(r["contacts_per_sphere"]), strain=float(r["axial_strain"]),
                           eta=float(r["eta"]), p=float(r["p_Pa"]), sigma_3=float(r["sigma_3_Pa"]),
                           void_ratio=float(r["void_ratio"]))
                if r["neighbour_builds"]:
                    row["builds"] = int(r["neighbour_builds"])
                    row["breakdown"] = {k: float(r[k.lower() + "_pct"]) for k in ("Pair", "Neigh", "Comm", "Modify", "Other")}
                rows.append(row)
        with open(os.path.join(out, "path.json")) as f:
            path = json.load(f)
        args.dt, args.nsteps, args.rate = path["dt"], path["nsteps"], path["rate"]
        write_tables(rows, args, out, (path["sffcal_builds"], path["sffcal_build_steps"], path["fit_residual_m"]))
        return
    for tool in ("lmp", "mpirun"):
        if not shutil.which(tool):
            sys.exit("run.py: '%s' not found (apt-get install lammps)" % tool)
    work, out = os.path.abspath(args.work), os.path.abspath(args.out)
    if work == ROOT or work.startswith(ROOT + os.sep):
        sys.exit("run.py: --work must lie outside the repository (LAMMPS writes its logs there)")
    os.makedirs(work, exist_ok=True)
    os.makedirs(os.path.join(out, "logs"), exist_ok=True)
    os.chdir(work)

    spec = os.path.join(work, "specimen.h5")
    if not os.path.exists(spec):
        open("prepare.toml", "w").write(PREPARE_TOML.format(seed=args.seed, bodies=args.bodies, **SCENE))
        t0 = time.time()
        sh([args.sffcal, "prepare", "-c", "prepare.toml", "-o", spec])
        print("run.py: prepared in %.0f s" % (time.time() - t0))
    sh(["/usr/bin/python3", os.path.join(DECK, "export.py"), spec, os.path.join(work, "export")])

    strain = args.nsteps * args.rate * args.dt
    short = args.short_steps * args.rate * args.dt
    for threads in (1, 2):
        for suffix, s in (("", strain), ("_short", short)):
            open("shear_t%d%s.toml" % (threads, suffix), "w").write(SHEAR_TOML.format(
                seed=args.seed, bodies=args.bodies, threads=threads, dt=args.dt, rate=args.rate, strain=s,
                **SCENE))
    path = sffcal_path(args, work)
    with open(os.path.join(out, "path.json"), "w") as f:
        json.dump(dict(sffcal_builds=path[0], sffcal_build_steps=path[1], fit_residual_m=path[2], dt=args.dt,
                       nsteps=args.nsteps, rate=args.rate), f, indent=1)

    print("run.py: %s; %s" % (subprocess.run(["lmp", "-h"], capture_output=True, text=True).stdout.splitlines()[1],
                              subprocess.run([args.sffcal, "--help"], capture_output=True, text=True).stdout.splitlines()[0]))
    rows = []
    for r in range(1, args.repeats + 1):
        # Alternated: LAMMPS 1, sffcal 1, LAMMPS 2, sffcal 2, sffcal's file-output runs, then the
        # variants: LAMMPS with fixed lateral walls, sffcal on 2 spinning threads.
        cases = [("lammps", 1), ("sffcal", 1), ("lammps", 2), ("sffcal", 2), ("short", 1), ("short", 2)]
        if r <= args.fixed_lateral_repeats:
            cases += [("fixed", 1), ("fixed", 2)]
        if r <= args.spinning_repeats:
            cases += [("spinning", 2)]
        for kind, workers in cases:
            tag = "%s%d_r%d" % (kind, workers, r)
            if kind in ("lammps", "fixed"):
                row = lammps_case(workers, "moving" if kind == "lammps" else "fixed", args, work, tag)
                shutil.copy(os.path.join(work, "lammps_%s.log" % tag), os.path.join(out, "logs"))
            else:
                row = sffcal_case(workers, args, work, tag, short=(kind == "short"), active=(kind == "spinning"))
            row["repeat"] = r
            rows.append(row)
            print("run.py:   %-20s x%d rep %d: %d steps in %.3f s = %.3g sphere-steps/s per core "
                  "(foreign load %.2f cores)" % (row["code"], workers, r, row["steps"], row["seconds"],
                                                 row["spheres"] * row["steps"] / row["seconds"] / workers,
                                                 row["foreign"]), flush=True)
    write_tables(rows, args, out, path)


def write_tables(rows, args, out, path):
    sffcal_builds, sffcal_build_steps, fit_residual = path
    per_core = lambda r: r["spheres"] * r["steps"] / r["seconds"] / r["workers"]
    with open(os.path.join(out, "results.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["code", "workers", "repeat", "steps", "spheres", "seconds", "sphere_steps_per_s_per_core",
                    "foreign_cores", "neighbour_builds", "contacts_per_sphere", "axial_strain", "eta", "p_Pa",
                    "sigma_3_Pa", "void_ratio", "pair_pct", "neigh_pct", "comm_pct", "modify_pct", "other_pct"])
        for r in rows:
            b = r.get("breakdown", {})
            w.writerow([r["code"], r["workers"], r["repeat"], r["steps"], r["spheres"], "%.4f" % r["seconds"],
                        "%.5g" % per_core(r), "%.3f" % r["foreign"], r.get("builds", ""),
                        "%.4f" % r["contacts_per_sphere"], "%.6f" % r["strain"], "%.5f" % r["eta"],
                        "%.6g" % r["p"], "%.6g" % r["sigma_3"], "%.5f" % r["void_ratio"]]
                       + [b.get(k, "") for k in ("Pair", "Neigh", "Comm", "Modify", "Other")])

    def pick(code, workers):
        return [r for r in rows if r["code"] == code and r["workers"] == workers]

    lammps_med = {n: statistics.median(per_core(r) for r in pick("LAMMPS", n)) for n in (1, 2)}
    overhead = {}
    for n in (1, 2):
        long_runs, short_runs = pick("sffcal", n), pick("sffcal-output", n)
        if long_runs and short_runs:
            per_step = statistics.median(r["seconds"] for r in long_runs) / long_runs[0]["steps"]
            # the short run's seconds less its own steps at the long run's cost per step
            overhead[n] = statistics.median(r["seconds"] - r["steps"] * per_step for r in short_runs)
    lines = ["| code | cores | steps | seconds, median (min) | sphere-steps/s per core, median (best) | "
             "sffcal's file output excluded | ratio to LAMMPS (moving walls), medians: as run (output excluded) | seconds of each run | contacts per sphere "
             "at the end | neighbour-list builds | max foreign load [cores] |",
             "|---|---:|---:|---:|---:|---:|---:|---|---:|---:|---:|"]
    for code in ("LAMMPS", "sffcal", "LAMMPS-fixed-lateral", "sffcal-spinning"):
        for n in (1, 2):
            rs = pick(code, n)
            if not rs:
                continue
            secs = [r["seconds"] for r in rs]
            spheres, steps = rs[0]["spheres"], rs[0]["steps"]
            med = statistics.median(secs)
            thr = spheres * steps / med / n
            net = ratio = ""
            if code.startswith("sffcal") and n in overhead:
                net_thr = spheres * steps / (med - overhead[n]) / n
                net = "%.3g (%.2f s of output)" % (net_thr, overhead[n])
                ratio = "%.2f (%.2f)" % (thr / lammps_med[n], net_thr / lammps_med[n])
            elif code != "LAMMPS":
                ratio = "%.2f" % (thr / lammps_med[n])
            builds = ("%d" % statistics.median(r["builds"] for r in rs)) if code.startswith("LAMMPS") else \
                "%d (over %d steps)" % (sffcal_builds, sffcal_build_steps)
            lines.append("| %s | %d | %d | %.3f (%.3f) | **%.3g** (%.3g) | %s | %s | %s | %.3f | %s | %.2f |" % (
                code, n, steps, med, min(secs), thr, spheres * steps / min(secs) / n, net, ratio,
                ", ".join("%.2f" % x for x in secs), statistics.median(r["contacts_per_sphere"] for r in rs),
                builds, max(r["foreign"] for r in rs)))
    paired = ["", "sffcal / LAMMPS of each alternated pair (LAMMPS's loop time / sffcal's seconds, the runs of one "
              "repeat ran one after the other):", ""]
    for n in (1, 2):
        ratios = []
        for r in sorted({x["repeat"] for x in rows}):
            a = [x for x in pick("LAMMPS", n) if x["repeat"] == r]
            b = [x for x in pick("sffcal", n) if x["repeat"] == r]
            if a and b:
                ratios.append(a[0]["seconds"] / b[0]["seconds"])
        if ratios:
            paired.append("* %d core%s: %s (median %.2f)" % (n, "s" if n > 1 else "", ", ".join("%.2f" % x for x in ratios),
                                                          statistics.median(ratios)))
    state = ["", "The specimen at the end of the timed steps (1-core runs; wall stresses, as sffcal's "
             "series):", "", "| code | axial strain | q/p | p [kPa] | sigma_3 [kPa] | void ratio | contacts per sphere |",
             "|---|---:|---:|---:|---:|---:|---:|"]
    for code in ("LAMMPS", "sffcal", "LAMMPS-fixed-lateral"):
        rs = pick(code, 1)
        if rs:
            r = rs[0]
            state.append("| %s | %.5f | %.4f | %.1f | %.1f | %.4f | %.3f |" % (
                code, r["strain"], r["eta"], r["p"] / 1e3, r["sigma_3"] / 1e3, r["void_ratio"],
                r["contacts_per_sphere"]))
    lam = ["", "LAMMPS timing breakdown (median of the runs, % of the loop time):", "",
           "| walls | ranks | Pair | Neigh | Comm | Output | Modify | Other |", "|---|---:|---:|---:|---:|---:|---:|---:|"]
    for code in ("LAMMPS", "LAMMPS-fixed-lateral"):
        for n in (1, 2):
            rs = pick(code, n)
            if rs:
                lam.append("| %s | %d | %s |" % ("moving (regions)" if code == "LAMMPS" else "lateral fixed (primitive)",
                                                 n, " | ".join("%.1f" % statistics.median(r["breakdown"].get(k, 0.0) for r in rs)
                                                               for k in ("Pair", "Neigh", "Comm", "Output", "Modify", "Other"))))
    notes = ["", "Time step %.3g s, %d steps, strain rate %g /s; the lateral walls in LAMMPS follow sffcal's "
             "path (fit residual %.2g m)." % (args.dt, args.nsteps, args.rate, fit_residual)]
    text = "\n".join(lines + paired + state + lam + notes) + "\n"
    open(os.path.join(out, "results.md"), "w").write(text)
    print(text)


if __name__ == "__main__":
    main()
