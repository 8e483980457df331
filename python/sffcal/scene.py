"""A scene of the main job (docs/pipeline.md): which specimens of the reference matrix are sheared,
with which seeds, what is fitted, held back and checked, and each run's DEM config. Read by the
Snakemake workflow (workflow/Snakefile) and by its command line (scripts/pipeline.py).
"""
import os
import tomllib

from sffcal import matrix as specimen_matrix


class SceneError(Exception):
    """A scene file that cannot be read or names what does not exist (the message says which)."""


def read_scene(path):
    """The scene as a dict, with `seeds` (a list) and `specimens` (every specimen sheared) added."""
    try:
        with open(path, "rb") as f:
            scene = tomllib.load(f)
    except (OSError, tomllib.TOMLDecodeError) as e:
        raise SceneError(f"scene {path}: {e}")
    known = [name for name, _ in specimen_matrix.matrix()]
    for key in ("calibrate_on", "held_back", "other_paths"):
        for name in scene.get(key, []):
            if name not in known:
                raise SceneError(f"scene {path}: {key} names '{name}', not a specimen of the matrix "
                                 f"(python/sffcal/matrix.py): {', '.join(known)}")
    if not scene.get("calibrate_on"):
        raise SceneError(f"scene {path}: 'calibrate_on' must name at least one specimen")
    if "seed" in scene and "seeds" in scene:
        raise SceneError(f"scene {path}: give 'seed' (one) or 'seeds' (a list), not both")
    scene["seeds"] = scene.get("seeds", [scene.get("seed", 1)])
    seeds = scene["seeds"]
    if not (isinstance(seeds, list) and seeds and all(isinstance(s, int) and s >= 0 for s in seeds)
            and len(set(seeds)) == len(seeds)):
        raise SceneError(f"scene {path}: 'seeds' must be a list of distinct non-negative integers, "
                         f"not {seeds!r}")
    scene["specimens"] = known if scene.get("matrix") else (
        scene["calibrate_on"] + scene.get("held_back", []) + scene.get("other_paths", []))
    scene["path"] = path
    return scene


def stems(scene, name):
    """The file stems of a specimen's runs: its name with one seed, <name>_s<seed> with several."""
    seeds = scene["seeds"]
    return [name] if len(seeds) == 1 else [f"{name}_s{seed}" for seed in seeds]


def instances(scene):
    """(specimen, seed, stem) of every run of the scene."""
    return [(n, seed, stem) for n in scene["specimens"]
            for seed, stem in zip(scene["seeds"], stems(scene, n))]


def test_stem(scene, name):
    """Where the test of a specimen that the fit and the checks read lies, under the output
    folder: runs/<name>.h5 with one seed, the mean of its seeds' runs mean/<name>.h5 with several."""
    return os.path.join("runs" if len(scene["seeds"]) == 1 else "mean", name + ".h5")


def checked(scene):
    """The tests fe-check runs through the element: the fitted and held-back drained compressions
    (the element's path; the calibration predicts the others)."""
    return [n for n in scene["calibrate_on"] + scene.get("held_back", [])
            if specimen_matrix.loading_path(n) == "drained_compression"]


def run_configs(scene, root):
    """{stem: the DEM config text} of every run: the matrix's config of the specimen, then the
    scene's [dem] keys (first key of that name), then those of its [dem.<specimen>] table."""
    with open(os.path.join(root, specimen_matrix.TEMPLATE)) as f:
        template = f.read()
    specimens = dict(specimen_matrix.matrix())
    dem = scene.get("dem", {})
    configs = {}
    for name, seed, stem in instances(scene):
        text = specimen_matrix.specimen_config(template, name, specimens[name],
                                               bodies=scene.get("bodies", 400), seed=seed)
        keys = [(k, v) for k, v in dem.items() if not isinstance(v, dict)] + \
            list(dem.get(name, {}).items())
        for key, value in keys:
            try:
                text = specimen_matrix.set_key(text, key, value)
            except KeyError as e:  # the template has no such key
                raise SceneError(f"scene {scene['path']}: [dem] {e.args[0]}")
        configs[stem] = text
    return configs
