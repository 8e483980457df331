"""sffcal's Python side: the package of the scripts of scripts/ and bench/, and the Python API.

- runfile: reading a run file (the series, /summary, /physics, /loading and the analysis tables),
  with the names of the C++ runfile library, and the CSV tables the commands write;
- matrix: the specimens of the reference test matrix and the config writer behind
  bench/matrix/make_configs.py and the main job;
- reduce: a reduced copy of a run file (no snapshots, no checkpoint);
- seeds: the mean of several seeds of one specimen as a reduced run file, and the DEM's noise
  between them; mean_of_seeds its command line (`python3 -m sffcal.mean_of_seeds`, the main job's
  mean stage; bench/calibration/);
- plot_triaxial: a triaxial run's curves as a PNG (`python3 -m sffcal.plot_triaxial`);
- scene: the main job's scene files (scripts/pipeline.py, workflow/Snakefile);
- sff_table: the Markdown table of SFF results of several runs;
- sff_plots: drawings shared by several scripts (the SFF decomposition of q/p);
- models, sff (compiled, sffcal._core): the constitutive models and the SFF analysis from numpy;
- calibration (compiled, sffcal._fit): the fit of a model to run files, as `sffcal calibrate`.

The scripts import the package as built (build/python: these modules and sffcal._core; their
shell scripts source scripts/python_env.sh, which puts it on PYTHONPATH) or as installed
(`cmake --install`); docs/python.md.
"""


def __getattr__(name):
    """sffcal.calibrate: sffcal.calibration.calibrate, imported when first asked for (it loads
    the compiled sffcal._fit and Ceres, which the scripts' modules do not need)."""
    if name == "calibrate":
        from sffcal.calibration import calibrate
        return calibrate
    raise AttributeError(f"module 'sffcal' has no attribute '{name}'")
