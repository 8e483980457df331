"""The specimens of the reference test matrix (issue 7; docs/reference-matrix.md) and the writer
of their TOML configs, used by bench/matrix/make_configs.py and the main job (sffcal.scene).

Isotropic specimens: three densities (compaction friction 0.15 dense, 0.3 medium, 0.5 loose)
x p'0 = 100, 200, 300 kPa. Anisotropic specimens: gravity deposition, dense and loose, loading
angle 0, 30, 45, 60, 90 deg, at 100 kPa. All drained compression; then the other loading paths
(issue 18): undrained compression and drained extension, dense and loose, at 100 and 200 kPa;
true triaxial at b = 0.5, dense, 100 kPa; drained extension of the dense deposit at 45 deg. Every
config starts from the repository's examples/quick_triaxial.toml (TEMPLATE, relative to the
repository's root: the callers are its scripts) and changes only the keys below; the seed is the
same for all (the density, pressure and angle are what differ).
"""
import re

# The template every specimen's config starts from, relative to the repository's root.
TEMPLATE = "examples/quick_triaxial.toml"
# Compaction friction. The loosest stays below the shearing friction (tan 30 deg): with a higher
# one, the contacts beyond the new Coulomb limit slip when shearing starts and the specimen
# collapses (measured with 1.0: q/p dips to -0.3 and 6 % volumetric strain in the first 1 %).
DENSITIES = {"dense": 0.15, "medium": 0.3, "loose": 0.5}


def matrix():
    for density, friction in DENSITIES.items():
        for kpa in (100, 200, 300):
            yield f"iso_{density}_{kpa}kPa", {"method": '"compaction"', "compaction_friction": friction,
                                               "pressure": kpa * 1e3}
    for density in ("dense", "loose"):
        for angle in (0, 30, 45, 60, 90):
            yield f"dep_{density}_a{angle:02d}", {"method": '"deposition"', "loading_angle_deg": float(angle),
                                                 "compaction_friction": DENSITIES[density], "pressure": 1e5}
    for prefix, path in (("und", "undrained_compression"), ("ext", "drained_extension")):
        for density in ("dense", "loose"):
            for kpa in (100, 200):
                keys = {"method": '"compaction"', "compaction_friction": DENSITIES[density],
                        "pressure": kpa * 1e3, "path": f'"{path}"'}
                if prefix == "und":
                    # Undrained, the dense specimens build p past 1 MPa by 10-15 % (E/p near 100:
                    # overlaps reach max_overlap_ratio) and the loose ones liquefy by 3 %.
                    keys["max_axial_strain"] = 0.05
                yield f"{prefix}_{density}_{kpa}kPa", keys
    yield "tt_dense_100kPa_b05", {"method": '"compaction"', "compaction_friction": DENSITIES["dense"],
                                  "pressure": 1e5, "path": '"true_triaxial"', "b": 0.5}
    yield "dep_dense_a45_ext", {"method": '"deposition"', "loading_angle_deg": 45.0,
                                "compaction_friction": DENSITIES["dense"], "pressure": 1e5,
                                "path": '"drained_extension"'}


def loading_path(name):
    """The loading path of a specimen of matrix() (docs/dem.md, "Loading paths")."""
    keys = dict(matrix())[name]
    return keys.get("path", '"drained_compression"').strip('"')


def set_key(text, key, value):
    pattern = re.compile(rf"^({re.escape(key)}\s*=\s*)([^#\n]*?)(\s*#.*)?$", re.M)
    if not pattern.search(text):
        raise KeyError(f"template has no key {key}")
    return pattern.sub(lambda m: f"{m.group(1)}{value}  # set by make_configs.py", text, count=1)




def specimen_config(template, name, keys, bodies=500, seed=1):
    """The config text of one specimen of matrix(): the template with the matrix's common keys
    (one thread, 100 /s to 30 %, a snapshot every 2.5 %) and the specimen's own."""
    text = template
    text = set_key(text, "seed", seed)
    text = set_key(text, "threads", 1)  # one specimen per core: run several at once
    text = set_key(text, "bodies", bodies)
    text = set_key(text, "strain_rate", 100.0)
    text = set_key(text, "max_axial_strain", 0.30)  # unless the entry sets its own
    text = set_key(text, "snapshot_strain_interval", 0.025)
    for key, value in keys.items():
        text = set_key(text, key, value)
    return f"# Reference matrix specimen {name} (bench/matrix/make_configs.py)\n" + text
