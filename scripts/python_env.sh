# Sourced by the shell scripts that run the project's Python scripts: puts the package sffcal as
# the build made it (build/python: the pure-Python modules and the compiled sffcal._core) first on
# PYTHONPATH, so that the scripts import it (docs/python.md). Run from the repository's root, after
# scripts/build.sh; a build folder other than build/: SFFCAL_BUILD=folder.
if [ ! -f "${SFFCAL_BUILD:-build}/python/sffcal/__init__.py" ]; then
  echo "the Python package is not built: run scripts/build.sh first (no ${SFFCAL_BUILD:-build}/python/sffcal)" >&2
  return 1 2>/dev/null || exit 1
fi
export PYTHONPATH="$PWD/${SFFCAL_BUILD:-build}/python${PYTHONPATH:+:$PYTHONPATH}"
