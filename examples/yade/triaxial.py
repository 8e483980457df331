"""Drained triaxial compression of two-sphere clumps in YADE, in a periodic cell or (--walls)
between six walls, written for `sffcal import` (docs/import.md) by sffcal.yade_export.

The project's scene: each clump two equal spheres of radius r whose centres are r apart, YADE's
linear contact law with Coulomb friction (FrictMat, Ip2_FrictMat_FrictMat_FrictPhys:
k_n = E r for two equal spheres, k_t = poisson k_n, so poisson = 0.5 is the project's
k_t / k_n = 0.5; the script checks it on YADE's contacts), density 2650 kg/m^3.
  (a) isotropic compaction to --pressure by PeriTriaxController (all axes stress-controlled) with
      the friction --compaction-friction (lower is denser), then the friction set to --friction
      and the cell settled again at the pressure;
  (b) drained compression: x and y stress-controlled at -pressure (YADE: tension positive), z
      strain-controlled, shortened at the constant engineering strain rate --strain-rate (YADE's
      strain is logarithmic: its rate is set to rate / (1 - strain) before each stretch of steps)
      to --final-strain.
With --walls the cloud is made between six frictionless walls (utils.aabbWalls, Box bodies of
the grains' E: k_n = E r at a wall too) and TriaxialStressController moves them: all three
stress-controlled while compacting, then x and y at the pressure and z at the strain rate (YADE's
rate of the walls' gap is logarithmic, set as above). The walls' stress (their forces over the
faces) is the series' stress.
A series row every --row-interval steps, a snapshot (atoms + contacts) every --frame-strain of
axial strain from the start of the compression, and one at the end.

  PYTHONPATH=python yade -n -j1 -x examples/yade/triaxial.py --output runs/yade_triax [--walls]
  sffcal import runs/yade_triax/import.toml -o out/yade_triax.h5
"""
import argparse
import math
import sys
import time

from yade import pack, utils
from yade.wrapper import (ForceResetter, InsertionSortCollider, Bo1_Box_Aabb, Bo1_Sphere_Aabb,
                          InteractionLoop, Ig2_Box_Sphere_ScGeom, Ig2_Sphere_Sphere_ScGeom,
                          Ip2_FrictMat_FrictMat_FrictPhys, Law2_ScGeom_FrictPhys_CundallStrack,
                          PeriTriaxController, TriaxialStressController, NewtonIntegrator,
                          FrictMat, Omega)

from sffcal.yade_export import Exporter

O = Omega()
DENSITY = 2650.0     # the grains' [kg/m^3]
STIFFNESS_RATIO = 0.5  # k_t / k_n: YADE's FrictMat poisson


def arguments():
    parser = argparse.ArgumentParser(prog="triaxial.py", description=__doc__.split("\n\n")[0])
    parser.add_argument("--output", required=True,
                        help="a new folder for import.toml and the dumps (never written over)")
    parser.add_argument("--clumps", type=int, default=400)
    parser.add_argument("--radius", type=float, default=5e-4, help="each sphere's radius [m]")
    parser.add_argument("--pressure", type=float, default=1e5,
                        help="the confining stress sigma_3 [Pa]")
    parser.add_argument("--youngs-modulus", type=float, default=1.5e8, help="E [Pa]")
    parser.add_argument("--friction", type=float, default=0.5, help="mu while compressing")
    parser.add_argument("--compaction-friction", type=float, default=0.1,
                        help="mu while compacting isotropically: lower is denser")
    parser.add_argument("--strain-rate", type=float, default=1.0,
                        help="engineering axial strain rate [1/s]")
    parser.add_argument("--final-strain", type=float, default=0.15, help="axial, engineering")
    parser.add_argument("--frame-strain", type=float, default=0.01,
                        help="a snapshot every this much axial strain")
    parser.add_argument("--row-interval", type=int, default=100,
                        help="a series row every this many steps")
    parser.add_argument("--damping", type=float, default=0.0,
                        help="YADE's local (Cundall) damping while compressing (the project's "
                        "DEM: none)")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--walls", action="store_true",
                        help="between six walls (TriaxialStressController), not a periodic cell")
    args = parser.parse_args(sys.argv[1:])
    for name in ("clumps", "radius", "pressure", "youngs_modulus", "strain_rate", "final_strain",
                 "frame_strain", "row_interval"):
        if not getattr(args, name) > 0:
            parser.error(f"--{name.replace('_', '-')} must be positive")
    if args.final_strain >= 1:
        parser.error("--final-strain must be below 1")
    return args


def set_engines(controller, walls):
    """YADE's loop: the linear law between spheres (and between a wall and a sphere), the
    controller, Newton with damping 0.4 (compaction; compress() sets --damping); dt half YADE's
    P-wave step."""
    O.engines = [
        ForceResetter(),
        InsertionSortCollider([Bo1_Sphere_Aabb()] + ([Bo1_Box_Aabb()] if walls else [])),
        InteractionLoop([Ig2_Sphere_Sphere_ScGeom()] + ([Ig2_Box_Sphere_ScGeom()] if walls else []),
                        [Ip2_FrictMat_FrictMat_FrictPhys()],
                        [Law2_ScGeom_FrictPhys_CundallStrack()]),
        controller,
        NewtonIntegrator(damping=0.4),
    ]
    O.dt = 0.5 * utils.PWaveTimeStep()


def build(args):
    """A loose periodic cloud of clumps compacted to the pressure; returns the controller."""
    r = args.radius
    side = r * (args.clumps * 32.0) ** (1.0 / 3.0)  # about 22 % solid before compaction
    O.periodic = True
    O.cell.setBox(side, side, side)
    O.materials.append(FrictMat(young=args.youngs_modulus, poisson=STIFFNESS_RATIO,
                                density=DENSITY, frictionAngle=math.atan(args.compaction_friction)))
    clump = pack.SpherePack([((0, 0, 0), r), ((r, 0, 0), r)])
    cloud = pack.SpherePack()
    cloud.makeClumpCloud((0, 0, 0), (side, side, side), [clump], periodic=True,
                         num=args.clumps, seed=args.seed)
    cloud.toSimulation()
    clumps = sum(1 for b in O.bodies if b.isClump)
    if clumps != args.clumps:
        sys.exit(f"triaxial.py: YADE placed {clumps} clumps of {args.clumps}")
    controller = PeriTriaxController(
        goal=(-args.pressure,) * 3, stressMask=7, dynCell=True, mass=0.2,
        maxStrainRate=(20.0, 20.0, 20.0), maxUnbalanced=1e-3, relStressTol=1e-4,
        doneHook="O.pause()")
    set_engines(controller, walls=False)

    def settle(what):
        limit = O.iter + 2000000
        O.run(limit - O.iter, True)  # the controller's doneHook pauses at the target
        if O.iter >= limit:
            sys.exit(f"triaxial.py: the {what} did not settle at {args.pressure:g} Pa")
        print(f"triaxial.py: {what} settled at step {O.iter}, porosity (YADE's, spheres "
              f"whole) {utils.porosity():.4f}, unbalanced {utils.unbalancedForce():.2e}",
              flush=True)

    compact(args, O.materials[0], settle)
    return controller


def compact(args, grains, settle):
    """Settles at the compaction friction, then at the test's (grains: their material); checks
    YADE's k_t / k_n on the grains' contacts."""
    settle(f"compaction at friction {args.compaction_friction:g}")
    grains.frictionAngle = math.atan(args.friction)  # new contacts
    for i in O.interactions:  # and the present ones between grains (a wall's keep its 0)
        if i.isReal and i.phys.tangensOfFrictionAngle > 0:
            i.phys.tangensOfFrictionAngle = args.friction
    settle(f"packing at friction {args.friction:g}")
    ratios = {i.phys.ks / i.phys.kn for i in O.interactions if i.isReal}
    if max(abs(k - STIFFNESS_RATIO) for k in ratios) > 1e-12:
        sys.exit(f"triaxial.py: YADE's k_t / k_n are {sorted(ratios)}, not {STIFFNESS_RATIO}")


def make_walls(args):
    """Six frictionless walls around a box for a loose cloud (about 15 % solid: a clump must
    lie wholly inside); returns their ids, xlo xhi ylo yhi zlo zhi (utils.aabbWalls's order)."""
    side = args.radius * (args.clumps * 48.0) ** (1.0 / 3.0)
    O.materials.append(FrictMat(young=args.youngs_modulus, poisson=STIFFNESS_RATIO,
                                density=DENSITY, frictionAngle=0.0, label="walls"))
    return O.bodies.append(utils.aabbWalls([(0, 0, 0), (side, side, side)], thickness=args.radius,
                                           material="walls"))


def build_walls(args, walls, out):
    """A loose cloud of clumps between the walls compacted to the pressure by
    TriaxialStressController; returns it."""
    r, p0 = args.radius, args.pressure
    side = out.faces()[1][0]
    grains = FrictMat(young=args.youngs_modulus, poisson=STIFFNESS_RATIO, density=DENSITY,
                      frictionAngle=math.atan(args.compaction_friction), label="grains")
    O.materials.append(grains)
    clump = pack.SpherePack([((0, 0, 0), r), ((r, 0, 0), r)])
    cloud = pack.SpherePack()
    cloud.makeClumpCloud((0, 0, 0), (side, side, side), [clump], num=args.clumps,
                         seed=args.seed)
    cloud.toSimulation(material="grains")
    clumps = sum(1 for b in O.bodies if b.isClump)
    if clumps != args.clumps:
        sys.exit(f"triaxial.py: YADE placed {clumps} clumps of {args.clumps}")
    controller = TriaxialStressController(
        wall_left_id=walls[0], wall_right_id=walls[1], wall_bottom_id=walls[2],
        wall_top_id=walls[3], wall_back_id=walls[4], wall_front_id=walls[5],
        thickness=r, stressMask=7, internalCompaction=False, goal1=-p0, goal2=-p0, goal3=-p0)
    set_engines(controller, walls=True)

    def settle(what):
        limit = O.iter + 2000000
        while O.iter < limit:
            O.run(1000, True)
            if (max(abs(s / p0 - 1) for s in out.wall_stresses()) < 1e-3
                    and utils.unbalancedForce() < 1e-3):
                break
        else:
            sys.exit(f"triaxial.py: the {what} did not settle at {p0:g} Pa")
        print(f"triaxial.py: {what} settled at step {O.iter}, unbalanced "
              f"{utils.unbalancedForce():.2e}", flush=True)

    compact(args, grains, settle)
    return controller


class PeriodicCell:
    """The periodic cell's drained compression: x and y at the pressure (PeriTriaxController),
    z at a log strain rate; YADE's stress (getStress), compression positive."""

    def __init__(self, args, controller):
        self.controller = controller
        controller.stressMask = 3  # x, y stress; z strain
        controller.goal = (-args.pressure, -args.pressure, -1.0)  # z: a log strain never reached
        controller.doneHook = ""
        # The cell's "mass" [Pa s^2] of the lateral stress control (dynCell): a light cell follows
        # sigma_3 closely; on 400 clumps to 6 % strain the worst lateral error was 1.5 % at 0.2
        # (the compaction's), 0.4-0.5 % at 0.01-0.02, the mean 0.02-0.03 %, with or without
        # damping.
        controller.mass = 0.01

    def height(self):
        return O.cell.hSize[2][2]

    def volume(self):
        return O.cell.volume

    def stresses(self):
        s = utils.getStress()
        return -s[0][0], -s[1][1], -s[2][2]

    def set_rate(self, v):
        self.controller.maxStrainRate = (20.0, 20.0, v)  # the lateral rates capped at 20 /s


class WallBox:
    """The box's drained compression: TriaxialStressController holds the x and y walls at the
    pressure and closes the z walls at a log strain rate; the walls' stress (the Exporter's)."""

    def __init__(self, args, controller, out):
        self.controller, self.out = controller, out
        controller.stressMask = 3  # x, y stress; z strain
        controller.goal1 = controller.goal2 = -args.pressure

    def height(self):
        return self.out.faces()[1][2]

    def volume(self):
        gaps = self.out.faces()[1]
        return gaps[0] * gaps[1] * gaps[2]

    def stresses(self):
        return tuple(self.out.wall_stresses())

    def set_rate(self, v):
        self.controller.goal3 = -v  # a strain rate of the z walls' gap, shortening negative


def compress(args, specimen, out):
    """Drained compression to the final strain, exporting rows and frames; returns figures."""
    p0, rate = args.pressure, args.strain_rate
    h0, v0 = specimen.height(), specimen.volume()
    O.engines[-1].damping = args.damping

    def strain():
        return 1.0 - specimen.height() / h0

    # Steps from strain e to e_target at YADE's log rate v: hSize_zz *= 1 - v dt each step.
    def steps_to(e, target, v):
        return math.ceil(math.log((1 - target) / (1 - e)) / math.log1p(-v * O.dt) - 1e-9)

    frames = [k * args.frame_strain for k in range(1, int(args.final_strain / args.frame_strain
                                                          + 1e-9) + 1)]
    if not frames or frames[-1] < args.final_strain * (1 - 1e-9):
        frames.append(args.final_strain)
    figures = dict(peak_q_p=0.0, peak_strain=0.0, lateral_error=0.0, lateral_sum=0.0, rows=0,
                   frames=1)
    out.write_frame()
    e = 0.0
    while frames:
        v = rate / (1 - e)  # YADE's log strain rate for the engineering rate
        specimen.set_rate(v)
        O.run(max(1, min(args.row_interval, steps_to(e, frames[0], v))), True)
        e = strain()
        sx, sy, sz = specimen.stresses()
        s3 = 0.5 * (sx + sy)
        q, p = sz - s3, (sz + 2 * s3) / 3
        if q / p > figures["peak_q_p"]:
            figures.update(peak_q_p=q / p, peak_strain=e)
        errors = (abs(sx - p0) / p0, abs(sy - p0) / p0)
        figures["lateral_error"] = max(figures["lateral_error"], *errors)
        figures["lateral_sum"] += sum(errors)
        if e >= frames[0] * (1 - 1e-9):
            out.write_frame()
            figures["frames"] += 1
            frames.pop(0)
            print(f"triaxial.py: strain {e:.4f}  q/p {q / p:.3f}  p {p:.4g} Pa  volumetric "
                  f"strain (compression +) {1 - specimen.volume() / v0:+.4f}  sigma_x, sigma_y / "
                  f"sigma_3 - 1 {sx / p0 - 1:+.4f} {sy / p0 - 1:+.4f}  step {O.iter}", flush=True)
        else:
            out.write_row()
        figures["rows"] += 1
    figures.update(final_q_p=q / p, final_strain=e,
                   volumetric_strain=1 - specimen.volume() / v0)
    return figures


args = arguments()
inertial = args.strain_rate * 2 * args.radius * math.sqrt(DENSITY / args.pressure)
walls = make_walls(args) if args.walls else None
exporter = Exporter(  # first: an existing --output is refused before any work
    args.output, walls=walls,
    physics=dict(youngs_modulus=args.youngs_modulus, stiffness_ratio=STIFFNESS_RATIO,
                 friction=args.friction, wall_friction=0.0, grain_density=DENSITY,
                 density_scaling=1.0),
    test=dict(kind="triaxial", path="drained_compression", confining_stress=args.pressure,
              strain_rate=args.strain_rate,
              axis_control=[f"stress-controlled: sigma_3 {args.pressure:g} Pa"] * 2
              + [f"strain-controlled at {args.strain_rate:g} /s"]))
start = time.time()
with exporter:
    if args.walls:
        specimen = WallBox(args, build_walls(args, walls, exporter), exporter)
    else:
        specimen = PeriodicCell(args, build(args))
    print(f"triaxial.py: {args.clumps} clumps, dt {O.dt:.3g} s, compressing at {args.strain_rate:g}"
          f" /s (inertial number {inertial:.2g} with the spheres' diameter) to strain "
          f"{args.final_strain:g}", flush=True)
    figures = compress(args, specimen, exporter)
print(f"triaxial.py: done in {time.time() - start:.1f} s ({O.iter} steps): {figures['rows'] + 1} "
      f"rows, {figures['frames']} frames in {args.output}; peak q/p {figures['peak_q_p']:.3f} at "
      f"strain {figures['peak_strain']:.4f}, final q/p {figures['final_q_p']:.3f}, volumetric "
      f"strain (compression +) {figures['volumetric_strain']:+.4f}; lateral stress error "
      f"|sigma_x,y - sigma_3| / sigma_3: largest {100 * figures['lateral_error']:.2f} %, mean "
      f"{50 * figures['lateral_sum'] / figures['rows']:.3f} %", flush=True)
