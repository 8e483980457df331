#!/usr/bin/python3
"""DEM results of LAMMPS and sffcal side by side: triaxial compression of the same specimen.

    /usr/bin/python3 bench/lammps/results.py [--strain 0.45] [--work /tmp/sffcal-lammps-bench]

Uses the specimen and its export that run.py left in WORK (specimen.h5, export/); runs, one after
the other on 2 cores (2 threads, 2 MPI ranks; not timed against each other):

  drained     sffcal's drained compression (platens at +-rate H0/2, lateral walls servo-controlled
              to sigma_3 = 100 kPa), and the same test in LAMMPS: the platens as in sffcal, the
              lateral walls moved by sffcal's servo law (servo.py, called by LAMMPS every step
              through python-style variables: this LAMMPS has no wall servo or fix controller).
  replay      (--replay) LAMMPS with the lateral walls along sffcal's recorded positions (piecewise
              linear between its series rows): its sigma_3 shows whether its grains hold 100 kPa
              on sffcal's path, its q/p whether they carry the same deviator.
  undrained   (--undrained) constant-volume compression in both codes, kinematic in both (each
              lateral width w0 sqrt(h0/h)). On this dense specimen p rises past 1 MPa by 10 %
              strain and sffcal stops the run (an overlap past 0.25 r: E / stress ~ 110), so it is
              off by default.

Both codes: the same time step, strain rate, contact law, walls (docs and shear.in); a series row
every --row-strain of axial strain; q/p = (sigma_z - sigma_3) / p from the wall stresses.
Peak = the largest q/p of the rows; "end" = the mean q/p over the last 0.1 of axial strain
(sffcal's critical_window; sffcal's summary calls it critical_eta). Writes OUT/dem_results.md and
OUT/dem_results.csv (every row of every run) and keeps the LAMMPS logs in WORK/dem_*.
"""
import argparse
import csv
import math
import os
import shutil
import subprocess
import sys
import time

import h5py
import numpy as np

sys.dont_write_bytecode = True  # no __pycache__ in the repository
HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from run import DECK, ROOT, SCENE, SHEAR_TOML  # noqa: E402
sys.path.insert(0, DECK)
from export import write_lateral  # noqa: E402

WINDOW = 0.1  # sffcal's triaxial.critical_window


def sffcal_run(args, work, path, name):
    strain = args.strain
    text = SHEAR_TOML.format(seed=args.seed, bodies=args.bodies, threads=2, dt=args.dt, rate=args.rate,
                             strain=strain, **SCENE)
    text = text.replace("output_strain_interval = %r" % strain, "output_strain_interval = %r" % args.row_strain)
    text = text.replace("[triaxial]\n", '[triaxial]\npath = "%s"\n' % path)
    cfg = os.path.join(work, "dem_%s.toml" % name)
    open(cfg, "w").write(text)
    run = os.path.join(work, "dem_%s.h5" % name)
    t0 = time.time()
    subprocess.run([args.sffcal, "triaxial", "-c", cfg, "-s", os.path.join(work, "specimen.h5"), "-o", run,
                    "--force"], check=True, stdout=subprocess.DEVNULL)
    seconds = time.time() - t0
    with h5py.File(run, "r") as f:
        s = {k: f["series"][k][:] for k in ("step", "time", "axial_strain", "eta", "p", "q", "sigma_3",
                                            "void_ratio", "coordination_number", "wall_x_lower",
                                            "wall_x_upper", "wall_y_lower", "wall_y_upper")}
        summary = dict(f["summary"].attrs)
        snap = f["snapshots"][sorted(f["snapshots"].keys())[-1]]
        contacts = snap["contacts"][:]
        s["contacts_per_sphere_end"] = 2.0 * int((contacts["body_a"] >= 0).sum()) / len(snap["spheres"])
    print("results.py: sffcal %s: %d steps in %.0f s (peak q/p %.4f, critical_eta %.4f)" % (
        name, summary["steps"], seconds, summary["peak_eta"], summary["critical_eta"]))
    return s, summary, seconds


def lammps_run(args, work, name, nsteps, every, lateral_formulas=None, note="", walls="moving"):
    """LAMMPS on 2 ranks, a row of series.txt every `every` steps; walls "moving" along the given
    lateral formulas of time, or "servo"."""
    folder = os.path.join(work, "dem_lammps_%s" % name)
    shutil.rmtree(folder, ignore_errors=True)
    os.makedirs(folder)
    lateral = os.path.join(folder, "lateral.in")
    if lateral_formulas:
        write_lateral(lateral, lateral_formulas, note)
    cmd = ["mpirun"] + (["--allow-run-as-root"] if os.geteuid() == 0 else []) + ["-np", "2",
           "lmp", "-in", os.path.join(DECK, "shear.in"), "-log", "log.lammps", "-var", "deck", DECK,
           "-var", "spec", os.path.join(work, "export"), "-var", "lateral", lateral,
           "-var", "lateral_walls", walls, "-var", "p0", repr(SCENE["pressure"]),
           "-var", "nsteps", str(nsteps), "-var", "sample_every", str(every), "-var", "thermo_every", str(20 * every),
           "-var", "dt", repr(args.dt), "-var", "rate", repr(args.rate),
           "-var", "E", repr(SCENE["E"]), "-var", "ratio", repr(SCENE["ratio"]), "-var", "mu", repr(SCENE["mu"])]
    t0 = time.time()
    with open(os.path.join(folder, "screen.txt"), "w") as out:
        subprocess.run(cmd, check=True, cwd=folder, stdout=out, stderr=subprocess.STDOUT)
    seconds = time.time() - t0
    data = np.genfromtxt(os.path.join(folder, "series.txt"), names=True, comments="#")
    print("results.py: LAMMPS %s: %d steps in %.0f s" % (name, nsteps, seconds))
    return data, seconds


def figures(strain, eta, p, sigma_3, void_ratio):
    """Peak q/p; over the last WINDOW of strain: mean q/p, p, sigma_3, and the changes of q/p and
    of the void ratio along straight lines fitted there (sffcal's critical-state test asks
    |change of q/p| < 0.05 and |change of volumetric strain| < 0.005 over the window)."""
    k = int(np.argmax(eta))
    window = strain >= strain[-1] - WINDOW
    eta_change = np.polyfit(strain[window], eta[window], 1)[0] * WINDOW
    void_change = np.polyfit(strain[window], void_ratio[window], 1)[0] * WINDOW
    return dict(peak=eta[k], peak_strain=strain[k], end=eta[window].mean(), end_strain=strain[-1],
                p_end=p[window].mean(), sigma_3_end=sigma_3[window].mean(), void_end=void_ratio[-1],
                eta_change=eta_change, void_change=void_change,
                sigma_3_max_dev=np.abs(sigma_3 / SCENE["pressure"] - 1.0).max())


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--work", default="/tmp/sffcal-lammps-bench")
    ap.add_argument("--out", default=os.path.join(HERE, "results"))
    ap.add_argument("--strain", type=float, default=0.45,
                    help="final axial strain (default 0.45, sffcal's triaxial.max_axial_strain)")
    ap.add_argument("--row-strain", type=float, default=0.002, help="a series row every this much strain")
    ap.add_argument("--dt", type=float, default=7.0e-8)
    ap.add_argument("--rate", type=float, default=100.0)
    ap.add_argument("--bodies", type=int, default=10000)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--sffcal", default=os.path.join(ROOT, "build", "sffcal"))
    ap.add_argument("--undrained", action="store_true", help="also the constant-volume test (see above)")
    ap.add_argument("--replay", action="store_true", help="also LAMMPS on sffcal's drained wall path")
    args = ap.parse_args()
    work = os.path.abspath(args.work)
    for need in ("specimen.h5", "export/data.lmp"):
        if not os.path.exists(os.path.join(work, need)):
            sys.exit("results.py: %s/%s missing: run run.py first (same --work)" % (work, need))
    os.makedirs(args.out, exist_ok=True)

    strain_per_step = args.rate * args.dt
    every = int(round(args.row_strain / strain_per_step))
    # LAMMPS's fix print writes every `every` steps: its last row at the last step needs a multiple
    # (sffcal stops at --strain itself; 0.45 gives 64,286 steps there and 64,350 in LAMMPS)
    nsteps = every * int(math.ceil(args.strain / strain_per_step / every - 1e-9))
    with h5py.File(os.path.join(work, "specimen.h5"), "r") as f:
        walls = {(int(w["axis"]), int(w["upper"])): float(w["position"]) for w in f["checkpoint"]["walls"][:]}
        t_spec = float(f["checkpoint"].attrs["time"])
    h0 = walls[(2, 1)] - walls[(2, 0)]
    vp = 0.5 * args.rate * h0
    rows, table = [], []

    tests = []
    # ---- undrained: kinematic in both codes -----------------------------------------------
    if args.undrained:
        s_u, sum_u, sec_su = sffcal_run(args, work, "undrained_compression", "undrained")
        formulas = []
        for axis in (0, 1):
            w0 = walls[(axis, 1)] - walls[(axis, 0)]
            half_growth = "0.5*(%.17g*sqrt(%.17g/(%.17g-%.17g*time))-%.17g)" % (w0, h0, h0, 2.0 * vp, w0)
            formulas += ["-" + half_growth, half_growth]
        l_u, sec_lu = lammps_run(args, work, "undrained", nsteps, every, formulas,
                                 "constant volume: each width w0 sqrt(h0 / h), h = h0 - 2 vp time")
        tests.append(("undrained", "LAMMPS", s_u, sum_u, sec_su, l_u, sec_lu))

    # ---- drained: sffcal's servo in both; LAMMPS also on sffcal's wall path ------------------
    s_d, sum_d, sec_sd = sffcal_run(args, work, "drained_compression", "drained")
    l_s, sec_ls = lammps_run(args, work, "drained_servo", nsteps, every, walls="servo")
    tests.insert(0, ("drained", "LAMMPS (sffcal's servo law)", s_d, sum_d, sec_sd, l_s, sec_ls))
    if args.replay:
        tau = s_d["time"] - t_spec
        formulas = []
        for name, key in (("wall_x_lower", (0, 0)), ("wall_x_upper", (0, 1)),
                          ("wall_y_lower", (1, 0)), ("wall_y_upper", (1, 1))):
            # piecewise linear through (0, 0) and every row: sum over the rows of the slope change
            # times max(time - t_k, 0), written 0.5 (x + abs(x)) (this LAMMPS has no max(x, y))
            t = np.concatenate([[0.0], tau])
            d = np.concatenate([[0.0], s_d[name] - walls[key]])
            changes = np.diff(np.concatenate([[0.0], np.diff(d) / np.diff(t)]))
            formulas.append("+".join("(%.12g)*0.5*(time-%.12g+abs(time-%.12g))" % (c, tk, tk)
                                     for c, tk in zip(changes, t[:-1])))
        l_d, sec_ld = lammps_run(args, work, "drained_path", nsteps, every, formulas,
                                 "sffcal's drained lateral wall path, piecewise linear between its rows")
        tests.insert(1, ("drained", "LAMMPS on sffcal's wall path", s_d, sum_d, sec_sd, l_d, sec_ld))

    for test, lammps_label, s, summ, sec_s, l, sec_l in tests:
        fs = figures(s["axial_strain"], s["eta"], s["p"], s["sigma_3"], s["void_ratio"])
        fl = figures(l["axial_strain"], l["eta"], l["p"], 0.5 * (l["sxx"] + l["syy"]), l["void_ratio"])
        fs.update(code="sffcal", test=test, seconds=sec_s, contacts_end=s["contacts_per_sphere_end"], steps=int(summ["steps"]),
                  summary="peak_eta %.4f, critical_eta %.4f" % (summ["peak_eta"], summ["critical_eta"]))
        fl.update(code=lammps_label, test=test,
                  seconds=sec_l, contacts_end=l["contacts_per_sphere"][-1], summary="")
        first = not any(r["code"] == "sffcal" and r["test"] == test for r in table)
        table += [fs, fl] if first else [fl]
        for code, x in ((("sffcal", s),) if first else ()) + ((lammps_label, l),):
            n = len(x["axial_strain"])
            s3 = x["sigma_3"] if code == "sffcal" else 0.5 * (x["sxx"] + x["syy"])
            for i in range(n):
                rows.append([test, code, "%.6f" % x["axial_strain"][i], "%.6f" % x["eta"][i],
                             "%.6g" % x["p"][i], "%.6g" % s3[i], "%.6f" % x["void_ratio"][i]])

    with open(os.path.join(args.out, "dem_results.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["test", "code", "axial_strain", "eta", "p_Pa", "sigma_3_Pa", "void_ratio"])
        w.writerows(rows)
    lines = ["| test | code | peak q/p (at axial strain) | q/p over the last %.2g of strain | its fitted change "
             "there | void ratio's fitted change there | p there [kPa] | sigma_3 there [kPa] | "
             "max abs(sigma_3/p0 - 1) | void ratio at %.3g | contacts per sphere at the end | "
             "wall seconds (2 cores) | sffcal's summary |" % (WINDOW, args.strain),
             "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|"]
    for r in table:
        lines.append("| %s | %s | %.4f (%.4f) | %.4f | %+.3f | %+.4f | %.1f | %.1f | %.3f | %.4f | %.3f | %.0f | %s |" % (
            r["test"], r["code"], r["peak"], r["peak_strain"], r["end"], r["eta_change"], r["void_change"],
            r["p_end"] / 1e3, r["sigma_3_end"] / 1e3, r["sigma_3_max_dev"], r["void_end"], r["contacts_end"],
            r["seconds"], r["summary"]))
    text = "\n".join(lines) + ("\n\nTime step %.3g s, %g /s. sffcal: %d steps to axial strain %.4g. LAMMPS: %d steps "
                               "(a multiple of its row interval, %d steps), to %.4g. Wall stresses; a row every %.3g "
                               "of axial strain.\n" % (args.dt, args.rate, table[0]["steps"], args.strain, nsteps, every,
                                                     nsteps * strain_per_step, args.row_strain))
    open(os.path.join(args.out, "dem_results.md"), "w").write(text)
    print(text)


if __name__ == "__main__":
    main()
