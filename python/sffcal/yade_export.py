"""A YADE run written for `sffcal import` (docs/import.md): atoms and contacts dumps, a series
table and the import.toml that describes them, from inside a YADE script.

Pure Python and numpy: it imports YADE's modules (yade.wrapper, yade.utils) when an Exporter is
made, never sffcal's compiled part, so that YADE's Python imports it from the package's source:

    PYTHONPATH=/path/to/sffcal/python yade -n -x my_script.py

    from sffcal.yade_export import Exporter
    out = Exporter("runs/triax1",
                   physics=dict(youngs_modulus=1.5e8, stiffness_ratio=0.5, friction=0.5,
                                wall_friction=0.0, grain_density=2650.0, density_scaling=1.0),
                   test=dict(kind="triaxial", path="drained_compression", confining_stress=1e5,
                             strain_rate=0.5, axis_control=["stress-controlled: sigma_3 1e5 Pa",
                                                            "stress-controlled: sigma_3 1e5 Pa",
                                                            "strain-controlled at 0.5 /s"]))
    out.write_frame()           # a snapshot (atoms + contacts) and its series row, at O.iter
    for _ in range(100):
        O.run(100, True)
        out.write_row()         # a series row at O.iter
    out.close()

What is written, all SI (m, N, Pa, s), at YADE's step O.iter:
- atoms.dump (`ITEM: ATOMS id mol x y z radius`): every sphere, `id` its YADE body id, `mol` the id
  of its clump (its own id where it is standalone), x y z its state.pos (unwrapped: YADE keeps a
  body's position across the periodic boundary; the importer joins by the nearest image);
- contacts.dump (`ITEM: ENTRIES atom1 atom2 fx fy fz nx ny nz px py pz overlap`): every real
  interaction, atom1 = id1, atom2 = id2, f = normalForce + shearForce (the force on atom 2),
  n = geom.normal (from atom 1 to atom 2), p = geom.contactPoint, overlap = geom.penetrationDepth;
- series.txt: `step time sxx syy szz syz sxz sxy lx ly lz` and YADE's own figures as extra
  columns (the importer keeps them as source_<name>): `phi_xx .. phi_xy` = utils.fabricTensor()
  (<n n> over the real interactions), `unbalanced` = utils.unbalancedForce(), `porosity` =
  utils.porosity(), which counts every sphere's whole volume (a clump's lens twice),
  `coordination` = utils.avgNumInteractions(considerClumps=True) (2 C / N over the clumps) and
  `mechanical_coordination` = utils.avgNumInteractions(skipFree=True) (Thornton's
  (2C - N1)/(N - N0 - N1), bodies with no contact or one left out). The stress is
  the symmetric part of utils.getStress(), the Love-Weber stress with the branch vector between
  the clumps' centroids, YADE's sign: tension positive (import.toml says so);
- import.toml: [source] yade and its version, [files], [physics] and [test] as given, [series],
  [contacts].

The cell must be periodic and orthogonal: a sheared cell (off-diagonal hSize) is refused.

Or a box between six walls (`walls=` the ids of six axis-aligned Box bodies in the order xlo xhi
ylo yhi zlo zhi, utils.aabbWalls's): import.toml then says `boundary = "walls"`; the atoms dump
adds each wall's force on each sphere (`xlo_fx xlo_fy xlo_fz ... zhi_fz`, the sum of that wall's
interactions with the sphere, zero where none); the series is `step time sxx syy szz lx ly lz
xlo ylo zlo unbalanced coordination`: the walls' stress (YADE's force on each wall, O.forces.f,
the mean of an axis' two walls over the face between the others, tension positive as YADE's),
the gaps between the walls' inner faces and the lower faces' positions [m]. YADE moves bodies and
walls after the forces of a step: the positions written are those after the step whose forces
are written, in both modes.

Each file is flushed after each frame or row, so a run that is killed keeps what it wrote.
"""
import math
import os

__all__ = ["Exporter", "PHYSICS_KEYS", "TEST_KEYS"]

#: [physics] keys of import.toml, all required (docs/import.md), and their units.
PHYSICS_KEYS = {
    "youngs_modulus": "E of the grains [Pa]",
    "stiffness_ratio": "k_t / k_n [-]",
    "friction": "mu between grains while shearing [-]",
    "wall_friction": "mu between grains and walls [-] (0 in a periodic cell)",
    "grain_density": "[kg/m^3]",
    "density_scaling": "mass scaling of the run (>= 1) [-]",
}
#: [test] keys of import.toml, all required: kind and path are strings, axis_control a list of
#: three strings (x, y, z), the others numbers.
TEST_KEYS = {
    "kind": "e.g. triaxial",
    "path": "the loading path, e.g. drained_compression (docs/dem.md)",
    "confining_stress": "[Pa]",
    "strain_rate": "of the axial strain [1/s]",
    "axis_control": "three strings: how x, y and z were controlled",
}
ATOM_COLUMNS = "id mol x y z radius"
CONTACT_COLUMNS = "atom1 atom2 fx fy fz nx ny nz px py pz overlap"
SERIES_COLUMNS = ("step time sxx syy szz syz sxz sxy lx ly lz "
                  "phi_xx phi_yy phi_zz phi_yz phi_xz phi_xy unbalanced porosity "
                  "coordination mechanical_coordination")
STRESS_DEFINITION = ("YADE utils.getStress(): Love-Weber, branch vector between the clumps' "
                     "centroids; symmetric part")
WALL_NAMES = ("xlo", "xhi", "ylo", "yhi", "zlo", "zhi")
WALL_ATOM_COLUMNS = ATOM_COLUMNS + "".join(f" {w}_f{c}" for w in WALL_NAMES for c in "xyz")
WALL_SERIES_COLUMNS = "step time sxx syy szz lx ly lz xlo ylo zlo unbalanced coordination"
WALL_STRESS_DEFINITION = ("the walls' stress: YADE's force on each wall (O.forces.f), the mean of "
                          "an axis' two walls over the face area between the others")
# The six components in the series' order: xx yy zz yz xz xy.
_VOIGT = ((0, 0), (1, 1), (2, 2), (1, 2), (0, 2), (0, 1))


def _toml_value(value, where):
    """One TOML value: a string, a finite number, a bool or a list of them."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return '"' + value.replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n") + '"'
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if not math.isfinite(value):
            raise ValueError(f"yade_export: {where} is {value}: a finite number is needed")
        return repr(value)
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_toml_value(v, where) for v in value) + "]"
    raise TypeError(f"yade_export: {where} is a {type(value).__name__}: "
                    "a string, number, bool or list is needed")


def _numbers(*values):
    """The values as shortest round-trip decimals (Python's repr of a float), space-separated."""
    return " ".join(repr(float(v)) for v in values)


def _checked(table, name, keys):
    """The table with exactly the keys of `keys`: a missing or unknown key is refused by name."""
    missing = [k for k in keys if k not in table]
    unknown = [k for k in table if k not in keys]
    if missing or unknown:
        raise ValueError(f"yade_export: [{name}] " +
                         (f"lacks {', '.join(missing)}" if missing else "") +
                         ("; " if missing and unknown else "") +
                         (f"has unknown {', '.join(unknown)}" if unknown else "") +
                         f" (it takes {', '.join(keys)})")
    return {k: table[k] for k in keys}


class Exporter:
    """Writes a YADE run into `folder` for `sffcal import`.

    folder: a new folder (or an empty one); an existing non-empty folder is refused
        (FileExistsError), never written over.
    physics: the [physics] table, every key of PHYSICS_KEYS (SI units); no defaults.
    test: the [test] table, every key of TEST_KEYS (SI units); no defaults.
    version: the source's version, [source] version (default: yade.config.version).
    stress_definition: [series] stress_definition, the words that say what the stress is
        (default: getStress's in a periodic cell, the walls' between walls).
    walls: None (a periodic cell), or the ids of six Box bodies, the walls xlo xhi ylo yhi zlo
        zhi (the order of utils.aabbWalls).
    """

    def __init__(self, folder, physics, test, version=None, stress_definition=None, walls=None):
        import yade.config
        from yade import utils
        from yade.wrapper import Box, Omega, Sphere
        self._O, self._utils, self._Sphere = Omega(), utils, Sphere
        if walls is not None:
            walls = [int(w) for w in walls]
            if len(walls) != 6 or len(set(walls)) != 6:
                raise ValueError(f"yade_export: walls must be six distinct body ids (xlo xhi ylo "
                                 f"yhi zlo zhi), not {walls}")
            if self._O.periodic:
                raise ValueError("yade_export: walls are given, but the scene is periodic")
            for w in walls:
                if self._O.bodies[w] is None or not isinstance(self._O.bodies[w].shape, Box):
                    raise ValueError(f"yade_export: wall {w} is not a Box body")
        self._walls = walls
        if stress_definition is None:
            stress_definition = STRESS_DEFINITION if walls is None else WALL_STRESS_DEFINITION
        physics = _checked(physics, "physics", PHYSICS_KEYS)
        test = _checked(test, "test", TEST_KEYS)
        for key, value in list(physics.items()) + [(k, test[k]) for k in
                                                   ("confining_stress", "strain_rate")]:
            if isinstance(value, bool) or not isinstance(value, (int, float)):
                raise TypeError(f"yade_export: {key} is {value!r}: a number is needed")
        if not (isinstance(test["axis_control"], (list, tuple)) and len(test["axis_control"]) == 3
                and all(isinstance(a, str) for a in test["axis_control"])):
            raise ValueError("yade_export: [test] axis_control must be three strings (x, y, z)")
        if physics["density_scaling"] < 1:
            raise ValueError("yade_export: [physics] density_scaling must be >= 1")
        tables = {
            "source": {"program": "yade",
                       "version": yade.config.version if version is None else version},
            "files": {"atoms": "atoms.dump", "contacts": "contacts.dump",
                      "series": "series.txt"},
            "physics": physics,
            "test": test if walls is None else {**test, "boundary": "walls"},
            "series": {"stress_sign": "tension_positive", "stress_definition": stress_definition},
            "contacts": {"force_on": "atom2"},
        }
        toml = ["# Written by sffcal.yade_export from inside YADE; "
                "read by `sffcal import` (docs/import.md).\n"]
        for name, table in tables.items():
            toml.append(f"[{name}]\n")
            toml += [f"{key} = {_toml_value(value, f'[{name}] {key}')}\n"
                     for key, value in table.items()]

        if os.path.exists(folder) and (not os.path.isdir(folder) or os.listdir(folder)):
            raise FileExistsError(f"yade_export: {folder} exists and is not an empty folder: "
                                  "give a new one (nothing is written over)")
        os.makedirs(folder, exist_ok=True)
        self.folder = folder
        with open(os.path.join(folder, "import.toml"), "x") as f:
            f.writelines(toml)
        self._atoms = open(os.path.join(folder, "atoms.dump"), "x")
        self._contacts = open(os.path.join(folder, "contacts.dump"), "x")
        self._series = open(os.path.join(folder, "series.txt"), "x")
        self._series.write((SERIES_COLUMNS if walls is None else WALL_SERIES_COLUMNS) + "\n")
        self._series.flush()
        self._last_row = None    # the step of the last series row
        self._last_frame = None  # the step of the last frame

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def close(self):
        """Closes the three files (the Exporter writes nothing more)."""
        for f in (self._atoms, self._contacts, self._series):
            f.close()

    def faces(self):
        """Between walls: the lower walls' inner faces and the gaps to the upper ones' [m], each a
        list x, y, z (refuses a wall turned from the axes)."""
        lower, gaps = [], []
        for axis in range(3):
            faces = []
            for upper in (0, 1):
                body = self._O.bodies[self._walls[2 * axis + upper]]
                if abs(body.state.ori.toAxisAngle()[1]) > 1e-12:
                    raise ValueError(f"yade_export: wall {body.id} is turned: the walls must be "
                                     "aligned with the axes")
                half = body.shape.extents[axis]
                faces.append(body.state.pos[axis] + (-half if upper else half))
            lower.append(faces[0])
            gaps.append(faces[1] - faces[0])
        return lower, gaps

    def wall_stresses(self):
        """Between walls: sigma_x, sigma_y, sigma_z [Pa], compression positive: on each axis the
        mean of its two walls' forces (YADE's O.forces.f of the last step) over the face area."""
        O = self._O
        _, gaps = self.faces()
        stress = []
        for axis in range(3):
            f_lo = O.forces.f(self._walls[2 * axis])[axis]  # along +axis, on the wall
            f_hi = O.forces.f(self._walls[2 * axis + 1])[axis]
            area = gaps[(axis + 1) % 3] * gaps[(axis + 2) % 3]
            stress.append(0.5 * (f_hi - f_lo) / area)
        return stress

    def _box(self):
        """The cell's lengths [m]; refuses an aperiodic scene or a sheared cell."""
        O = self._O
        if not O.periodic:
            raise ValueError("yade_export: the scene is not periodic (O.periodic is False): "
                             "give the Exporter its six walls (walls=...) or make it periodic")
        h = [[float(O.cell.hSize[i][j]) for j in range(3)] for i in range(3)]
        scale = max(abs(h[k][k]) for k in range(3))
        off = max(abs(h[i][j]) for i in range(3) for j in range(3) if i != j)
        if off > 1e-12 * scale:
            raise ValueError(f"yade_export: the cell is sheared (largest off-diagonal hSize term "
                             f"{off:g} m against {scale:g} m): only an orthogonal box is imported")
        return h[0][0], h[1][1], h[2][2]

    def write_row(self):
        """Appends the series row at step O.iter: time [s], the stress [Pa] (tension positive),
        the cell's lengths [m], the fabric, the unbalanced-force ratio, the porosity and the
        coordination numbers. Returns
        False, writing nothing, where the last row is at this step already."""
        O, utils = self._O, self._utils
        step = O.iter
        if self._last_row is not None and step <= self._last_row:
            if step == self._last_row:
                return False
            raise ValueError(f"yade_export: a row at step {step} after one at step "
                             f"{self._last_row}: steps increasing")
        if self._walls is not None:
            lower, gaps = self.faces()
            stress = [-s for s in self.wall_stresses()]  # tension positive, as YADE's
            values = ([O.time] + stress + gaps + lower
                      + [utils.unbalancedForce(), utils.avgNumInteractions(considerClumps=True)])
            self._series.write(f"{step} {_numbers(*values)}\n")
            self._series.flush()
            self._last_row = step
            return True
        lengths = self._box()
        s = utils.getStress()
        phi = utils.fabricTensor()  # 2023.02a: a tuple holding one Matrix3 (two if split)
        if isinstance(phi, tuple):
            phi = phi[0]
        stress = [0.5 * (s[i][j] + s[j][i]) for i, j in _VOIGT]
        fabric = [phi[i][j] for i, j in _VOIGT]
        values = ([O.time] + stress + list(lengths) + fabric
                  + [utils.unbalancedForce(), utils.porosity(),
                     utils.avgNumInteractions(considerClumps=True),
                     utils.avgNumInteractions(skipFree=True)])
        self._series.write(f"{step} {_numbers(*values)}\n")
        self._series.flush()
        self._last_row = step
        return True

    def write_frame(self):
        """Writes the snapshot at step O.iter: one atoms frame, one contacts frame, and the series
        row at this step (unless written already). A second frame at one step is refused, as is
        a body other than one sphere or two spheres of equal radius (docs/import.md)."""
        O = self._O
        step = O.iter
        if self._last_frame is not None and step <= self._last_frame:
            raise ValueError(f"yade_export: a frame at step {step} after one at step "
                             f"{self._last_frame}: one frame per step, steps increasing")
        walls = {} if self._walls is None else {w: k for k, w in enumerate(self._walls)}
        if walls:
            lower, gaps = self.faces()
            box = "ITEM: BOX BOUNDS ff ff ff\n" + "".join(
                f"{lower[a]!r} {lower[a] + gaps[a]!r}\n" for a in range(3))
        else:
            lx, ly, lz = self._box()
            box = f"ITEM: BOX BOUNDS pp pp pp\n0.0 {lx!r}\n0.0 {ly!r}\n0.0 {lz!r}\n"

        # Each wall's force on each sphere, from the wall's interactions.
        wall_force = {}
        for i in O.interactions:
            if not i.isReal or (i.id1 not in walls and i.id2 not in walls):
                continue
            if i.id1 in walls and i.id2 in walls:
                continue  # two walls touching at an edge: no grain in it
            force = i.phys.normalForce + i.phys.shearForce  # on id2
            wall, sphere, sign = ((walls[i.id1], i.id2, 1.0) if i.id1 in walls
                                  else (walls[i.id2], i.id1, -1.0))
            total = wall_force.setdefault(sphere, [0.0] * 18)
            for c in range(3):
                total[3 * wall + c] += sign * force[c]

        atoms, spheres = [], set()
        for b in O.bodies:
            if b is None or b.id in walls:
                continue
            if b.isClump:
                members = list(b.shape.members.keys())
                radii = [O.bodies[m].shape.radius for m in members]
                if len(members) != 2 or radii[0] != radii[1]:
                    raise ValueError(f"yade_export: clump {b.id} has {len(members)} spheres of "
                                     f"radii {radii}: a body is one sphere or two equal ones")
                continue
            if not isinstance(b.shape, self._Sphere):
                raise ValueError(f"yade_export: body {b.id} is a {type(b.shape).__name__}: "
                                 "only spheres (alone or in clumps) are exported")
            mol = b.clumpId if b.isClumpMember else b.id
            extra = wall_force.get(b.id, [0.0] * 18) if walls else []
            atoms.append(f"{b.id} {mol} {_numbers(*b.state.pos, b.shape.radius, *extra)}\n")
            spheres.add(b.id)
        if set(wall_force) - spheres:
            raise ValueError("yade_export: a wall touches a body that is not a sphere")

        contacts = []
        for i in O.interactions:
            if not i.isReal or i.id1 in walls or i.id2 in walls:
                continue
            if i.id1 not in spheres or i.id2 not in spheres:
                raise ValueError(f"yade_export: interaction {i.id1}-{i.id2} is not between two "
                                 "spheres")
            force = i.phys.normalForce + i.phys.shearForce  # on id2
            contacts.append(f"{i.id1} {i.id2} " + _numbers(*force, *i.geom.normal,
                            *i.geom.contactPoint, i.geom.penetrationDepth) + "\n")

        self.write_row()  # every frame's step is a row's step
        self._atoms.write(f"ITEM: TIMESTEP\n{step}\nITEM: NUMBER OF ATOMS\n{len(atoms)}\n{box}"
                          f"ITEM: ATOMS {WALL_ATOM_COLUMNS if walls else ATOM_COLUMNS}\n")
        self._atoms.writelines(atoms)
        self._atoms.flush()
        self._contacts.write(f"ITEM: TIMESTEP\n{step}\nITEM: NUMBER OF ENTRIES\n{len(contacts)}\n"
                             f"{box}ITEM: ENTRIES {CONTACT_COLUMNS}\n")
        self._contacts.writelines(contacts)
        self._contacts.flush()
        self._last_frame = step
