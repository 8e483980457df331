"""sffcal's SFF analysis inside YADE: a real client of sffcal.sff (docs/python.md, "Inside YADE").

Builds a periodic cell of two-sphere clumps in YADE, compacts it isotropically with YADE's own
PeriTriaxController, hands YADE's interactions to sffcal.sff.analyse, and checks the result
against YADE's own numbers:
  - the fabric: sffcal's A = (15/2) dev phi against YADE's utils.fabricTensor() (phi = <n n>);
  - the stress: sffcal's contact stress (compression positive, symmetric) against the symmetric
    part of YADE's utils.getStress() (Love-Weber, tension positive, sum of f_i l_j with the branch
    vector l between the bodies' centres: the clumps' centroids); the antisymmetric part YADE
    keeps, which the clumps' unbalanced moments leave, is printed;
  - the void ratio against YADE's porosity (utils.porosity()).
Exits 1 where the fabric or the stress differ by more than --tolerance.

  PYTHONPATH=build/python yade -n -x examples/yade/sff_in_yade.py --clumps 300 --seed 1
"""
import argparse
import json
import math
import sys

import numpy as np
import yade.config
from yade import pack, utils  # noqa: F401 (yade's names: O, FrictMat, the engines)
from yade.wrapper import (ForceResetter, InsertionSortCollider, Bo1_Sphere_Aabb, InteractionLoop,
                          Ig2_Sphere_Sphere_ScGeom, Ip2_FrictMat_FrictMat_FrictPhys,
                          Law2_ScGeom_FrictPhys_CundallStrack, PeriTriaxController,
                          NewtonIntegrator, FrictMat, Omega)

from sffcal import sff

O = Omega()
DENSITY = 2650.0  # the grains' [kg/m^3]: the clumps' volumes are their masses over it


def arguments():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--clumps", type=int, default=300)
    parser.add_argument("--radius", type=float, default=5e-4, help="each sphere's radius [m]")
    parser.add_argument("--pressure", type=float, default=1e5, help="isotropic target [Pa]")
    parser.add_argument("--youngs-modulus", type=float, default=1.5e8, help="[Pa]")
    parser.add_argument("--friction", type=float, default=0.5, help="the grains' mu")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--tolerance", type=float, default=1e-10,
                        help="largest relative difference accepted in the fabric and the stress")
    parser.add_argument("--json", help="write the figures here (a new file)")
    return parser.parse_args(sys.argv[1:])


def build(args):
    """A loose periodic cloud of two-sphere clumps (centres one radius apart), YADE's linear
    contact law with Coulomb friction, compacted to the isotropic target."""
    r = args.radius
    side = r * (args.clumps * 32.0) ** (1.0 / 3.0)  # about 22 % solid before compaction
    O.periodic = True
    O.cell.setBox(side, side, side)
    O.materials.append(FrictMat(young=args.youngs_modulus, poisson=0.5, density=DENSITY,
                                frictionAngle=math.atan(args.friction)))
    clump = pack.SpherePack([((0, 0, 0), r), ((r, 0, 0), r)])
    cloud = pack.SpherePack()
    cloud.makeClumpCloud((0, 0, 0), (side, side, side), [clump], periodic=True,
                         num=args.clumps, seed=args.seed)
    cloud.toSimulation()
    O.engines = [
        ForceResetter(),
        InsertionSortCollider([Bo1_Sphere_Aabb()]),
        InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                        [Law2_ScGeom_FrictPhys_CundallStrack()]),
        PeriTriaxController(label="compaction", goal=(-args.pressure,) * 3, stressMask=7,
                            dynCell=True, maxStrainRate=(20.0, 20.0, 20.0), maxUnbalanced=1e-3,
                            relStressTol=1e-4, mass=0.2, doneHook="O.pause()"),
        NewtonIntegrator(damping=0.4),
    ]
    O.dt = 0.5 * utils.PWaveTimeStep()
    limit = 1000000
    O.run(limit, True)  # the controller's doneHook pauses at the target
    if O.iter >= limit:
        sys.exit(f"sff_in_yade: the compaction did not reach {args.pressure:g} Pa in {limit} steps")


def contact_records(friction):
    """YADE's real interactions between clumps as sffcal contact records: A = id1's clump, B =
    id2's; YADE's normal points from 1 to 2 and its normalForce + shearForce is the force on 2;
    the branch vector from clump centroid to clump centroid, B's shifted by the cell's hSize *
    cellDist across the periodic boundary."""
    clumps = {b.id: k for k, b in enumerate(b for b in O.bodies if b.isClump)}
    interactions = [i for i in O.interactions if i.isReal]
    records = np.zeros(len(interactions), dtype=sff.CONTACT_DTYPE)
    h = O.cell.hSize
    for k, i in enumerate(interactions):
        a, b = O.bodies[i.id1], O.bodies[i.id2]
        n = np.array(i.geom.normal)
        branch = O.bodies[b.clumpId].state.pos + h * i.cellDist - O.bodies[a.clumpId].state.pos
        fn = np.array(i.phys.normalForce)
        records[k] = (clumps[a.clumpId], clumps[b.clumpId], -1,
                      int(np.linalg.norm(i.phys.shearForce) >= friction * np.linalg.norm(fn)
                          * (1 - 1e-9)),
                      tuple(i.geom.contactPoint), tuple(n), tuple(branch),
                      i.geom.penetrationDepth, float(fn.dot(n)), tuple(i.phys.shearForce))
    return records, len(clumps)


def relative(a, b):
    return float(np.linalg.norm(np.asarray(a) - np.asarray(b)) / np.linalg.norm(b))


args = arguments()
build(args)
volume = O.cell.volume
solid = sum(b.state.mass for b in O.bodies if b.isClump) / DENSITY  # the clumps' own volumes
common = dict(volume=volume, solid_volume=solid, youngs_modulus=args.youngs_modulus,
              friction=args.friction)

records, bodies = contact_records(args.friction)
result = sff.analyse(records, num_bodies=bodies, **common)

phi_yade = np.array(utils.fabricTensor()[0] if isinstance(utils.fabricTensor(), tuple)
                    else utils.fabricTensor())
phi_sffcal = np.eye(3) / 3 + (2.0 / 15.0) * result["fabric_tensor"]
stress_yade = -np.array(utils.getStress())  # YADE: tension positive
figures = {
    "yade_version": yade.config.version,
    "clumps": bodies, "contacts": len(records), "iterations": O.iter,
    "unbalanced_force": utils.unbalancedForce(),
    "p_sffcal": result["p"], "q_sffcal": result["q"], "coordination": result["coordination"],
    "a_c": result["a_c"], "a_n": result["a_n"], "a_t": result["a_t"], "eta_sff": result["eta_sff"],
    "fabric_difference": relative(phi_sffcal, phi_yade),
    "stress_difference": relative(result["stress_tensor"], 0.5 * (stress_yade + stress_yade.T)),
    "yade_stress_antisymmetric_part": float(np.linalg.norm(0.5 * (stress_yade - stress_yade.T))
                                            / np.linalg.norm(stress_yade)),
    "void_ratio_sffcal": result["void_ratio"],
    "void_ratio_yade": utils.porosity() / (1 - utils.porosity()),
}
for name, value in figures.items():
    print(f"{name:34} {value}")
if args.json:
    with open(args.json, "x") as f:  # never over an existing file
        json.dump(figures, f, indent=1)
ok = (figures["fabric_difference"] <= args.tolerance
      and figures["stress_difference"] <= args.tolerance)
print("sff_in_yade:", "agrees with YADE" if ok else "DIFFERS from YADE", f"(tolerance {args.tolerance:g})")
sys.exit(0 if ok else 1)
