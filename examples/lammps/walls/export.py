#!/usr/bin/python3
"""Export an sffcal specimen (the /checkpoint of a `sffcal prepare` file) to LAMMPS.

usage: export.py SPECIMEN.h5 OUT_FOLDER

Writes, in OUT_FOLDER:
  data.lmp      read_data file: one atom per sphere (atom_style sphere: id type diameter density
                x y z), the clump as its molecule id (read with `fix property/atom mol` and
                `read_data ... fix ID NULL Molecules`); the box is the walls' box plus a margin.
  bodies.txt    `fix rigid/small molecule infile` file: per clump its mass, centroid, the world
                inertia tensor of the *union* of its two spheres (sffcal's, lens counted once;
                LAMMPS would otherwise take two whole spheres), its velocity and angular momentum.
  specimen.in   LAMMPS variables: the six wall positions (xlo..zhi), the sphere radius, counts.
  lateral.in    the lateral walls' displacements dxlo dxhi dylo dyhi as formulas of `time`: 0
                here (fixed walls); bench/lammps/run.py and results.py replace it with the path they need.

Exactly what sffcal's engine holds: sphere centres and radii, clump mass/inertia/velocity/angular
momentum and wall positions come from /checkpoint bit for bit (printed with %.17g). Not exported:
the contacts' tangential history (LAMMPS starts with none) and the wall servo's memory.
Units: SI (m, kg, s), as both programs use.
"""
import os
import sys

import h5py
import numpy as np


def rotation_matrices(q_xyzw):
    """World-from-body rotation of each unit quaternion, given as (x, y, z, w) rows."""
    x, y, z, w = q_xyzw.T
    r = np.empty((len(q_xyzw), 3, 3))
    r[:, 0, 0] = 1 - 2 * (y * y + z * z)
    r[:, 0, 1] = 2 * (x * y - w * z)
    r[:, 0, 2] = 2 * (x * z + w * y)
    r[:, 1, 0] = 2 * (x * y + w * z)
    r[:, 1, 1] = 1 - 2 * (x * x + z * z)
    r[:, 1, 2] = 2 * (y * z - w * x)
    r[:, 2, 0] = 2 * (x * z - w * y)
    r[:, 2, 1] = 2 * (y * z + w * x)
    r[:, 2, 2] = 1 - 2 * (x * x + y * y)
    return r


def write_lateral(path, formulas, note):
    """lateral.in: dxlo dxhi dylo dyhi [m] as equal-style formulas of LAMMPS's `time` [s]."""
    with open(path, "w") as s:
        s.write("# lateral wall displacements [m] against time [s]: %s\n" % note)
        for name, formula in zip(("dxlo", "dxhi", "dylo", "dyhi"), formulas):
            s.write("variable %s equal %s\n" % (name, formula))


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    path, out = sys.argv[1], sys.argv[2]
    os.makedirs(out, exist_ok=True)
    f = h5py.File(path, "r")
    c = f["checkpoint"]
    pos = c["position"][:]                 # clump centroids [m]
    mass = c["mass"][:]                    # union mass [kg]
    ia = c["inertia_axial"][:]             # about the clump axis (body x) [kg m^2]
    it = c["inertia_transverse"][:]        # across it
    vel = c["velocity"][:]                 # [m/s] (leapfrog: half a step behind the positions)
    angmom = c["angular_momentum"][:]      # world frame [kg m^2/s]
    q = c["orientation_xyzw"][:]
    nsph = c["num_body_spheres"][:]
    sph_pos = c["sphere_position"][:]
    sph_r = c["sphere_radius"][:]
    sph_body = c["sphere_body"][:]
    offset = c["sphere_offset"][:]
    walls = c["walls"][:]
    nb, ns = len(pos), len(sph_pos)
    if not np.all(nsph == 2):
        sys.exit("export.py: only two-sphere clumps are exported")

    # Check the geometry: each sphere sits at centroid + offset * (clump axis = R e_x).
    rot = rotation_matrices(q)
    axis = rot[:, :, 0]
    err = np.abs(pos[sph_body] + offset[:, None] * axis[sph_body] - sph_pos).max()
    if err > 1e-12 * np.abs(sph_pos).max():
        sys.exit("export.py: sphere positions do not follow the clumps' (%.3g m)" % err)
    # World inertia tensors I = R diag(Ia, It, It) R^T.
    inertia = np.einsum("bij,bj,bkj->bik", rot, np.stack([ia, it, it], 1), rot)

    # Wall positions: axis 0/1/2, upper 0/1.
    w = {}
    for row in walls:
        w[(int(row["axis"]), int(row["upper"]))] = float(row["position"])
    lo = np.array([w[(a, 0)] for a in range(3)])
    hi = np.array([w[(a, 1)] for a in range(3)])
    # The box must hold every sphere at every step (boundary f: an atom outside is lost); the walls,
    # not the box, confine them. The lateral walls move out as the specimen dilates (10 % of the
    # width each by 25 % axial strain on the dense specimen): a margin of 0.3 x the largest edge.
    margin = 0.3 * (hi - lo).max()

    # Each atom carries half its clump's mass (rigid/small takes the body mass from bodies.txt;
    # the atom masses matter only to the (zero) dashpots): density = (m/2) / (4/3 pi r^3).
    dens = 0.5 * mass[sph_body] / (4.0 / 3.0 * np.pi * sph_r ** 3)

    with open(os.path.join(out, "data.lmp"), "w") as d:
        d.write("sffcal specimen %s: %d clumps, %d spheres (examples/lammps/walls/export.py)\n\n" %
                (os.path.basename(path), nb, ns))
        d.write("%d atoms\n1 atom types\n\n" % ns)
        for a, name in enumerate("xyz"):
            d.write("%.17g %.17g %slo %shi\n" % (lo[a] - margin, hi[a] + margin, name, name))
        d.write("\nAtoms # sphere\n\n")
        for i in range(ns):
            d.write("%d 1 %.17g %.17g %.17g %.17g %.17g\n" % (
                i + 1, 2.0 * sph_r[i], dens[i], sph_pos[i, 0], sph_pos[i, 1], sph_pos[i, 2]))
        d.write("\nMolecules\n\n")
        for i in range(ns):
            d.write("%d %d\n" % (i + 1, sph_body[i] + 1))

    # fix rigid/small infile: ID masstotal xcm ycm zcm ixx iyy izz ixy ixz iyz vxcm vycm vzcm
    # lx ly lz ixcm iycm izcm (angular momentum l, image flags 0).
    with open(os.path.join(out, "bodies.txt"), "w") as b:
        b.write("# clumps of %s: the union's mass and inertia (sffcal's), velocity, angular momentum\n"
                % os.path.basename(path))
        b.write("%d\n" % nb)
        for k in range(nb):
            I = inertia[k]
            b.write(" ".join(["%d" % (k + 1)] + ["%.17g" % v for v in (
                mass[k], pos[k, 0], pos[k, 1], pos[k, 2],
                I[0, 0], I[1, 1], I[2, 2], I[0, 1], I[0, 2], I[1, 2],
                vel[k, 0], vel[k, 1], vel[k, 2], angmom[k, 0], angmom[k, 1], angmom[k, 2])])
                    + " 0 0 0\n")

    radii = np.unique(sph_r)
    with open(os.path.join(out, "specimen.in"), "w") as s:
        s.write("# %s: wall positions [m], sphere radius [m] (examples/lammps/walls/export.py)\n" % path)
        for a, name in enumerate("xyz"):
            s.write("variable %slo string %.17g\n" % (name, lo[a]))
            s.write("variable %shi string %.17g\n" % (name, hi[a]))
        s.write("variable radius string %.17g\n" % radii[0])
        s.write("variable nclumps string %d\n" % nb)
        s.write("variable nspheres string %d\n" % ns)
    write_lateral(os.path.join(out, "lateral.in"), ["0.0"] * 4, "fixed lateral walls")
    if len(radii) != 1:
        print("export.py: warning: %d sphere radii; specimen.in gives the smallest, and a constant "
              "hooke k_n = E r matches sffcal only for equal radii" % len(radii))
    print("export.py: %d clumps, %d spheres, walls x [%.6g, %.6g] y [%.6g, %.6g] z [%.6g, %.6g] m -> %s"
          % (nb, ns, lo[0], hi[0], lo[1], hi[1], lo[2], hi[2], out))


if __name__ == "__main__":
    main()
