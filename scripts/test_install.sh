#!/usr/bin/env bash
# Installs the build into a scratch prefix and builds and runs examples/external_fe against it,
# as a user of the installed package would (docs/fe.md, "Install"). Run after scripts/build.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
prefix=build/install-test
example=build/external_fe
rm -rf "$prefix" "$example"
cmake --install build --prefix "$prefix" >/dev/null
# The UMAT library must export the symbol Abaqus calls.
nm -D --defined-only "$prefix/lib/libsffcal_umat.so" | grep -qw umat_ ||
  { echo "test_install: $prefix/lib/libsffcal_umat.so does not export umat_" >&2; exit 1; }
# The model's public headers stand alone with Eigen only (docs/fe.md, "Install"): each compiles
# by itself against the installed tree, so a header the install leaves out is found here.
for header in acst_model.h descriptor.h parameter_field.h parameter_file.h update_status.h umat.h \
  umat_network.h network_model.h network_update.h; do
  echo "#include \"model/$header\"" |
    "${CXX:-c++}" -std=c++17 -fsyntax-only -I"$prefix/include" -I/usr/include/eigen3 -x c++ - ||
    { echo "test_install: the installed model/$header does not compile alone" >&2; exit 1; }
done
generator=()
command -v ninja >/dev/null && generator=(-G Ninja)
cmake -S examples/external_fe -B "$example" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$PWD/$prefix" >/dev/null
cmake --build "$example" --parallel "$(nproc)"
(cd "$example" && ./external_fe ../../examples/acst_toyoura.json 0.03 10)
test -s "$example/external_fe.vtu"
# The Python package as installed: sffcal.models and sffcal.sff from the prefix alone, imported
# from outside the tree.
core=$(find "$PWD/$prefix" -name "_core*.so" -path "*/sffcal/*" | head -1)
[ -n "$core" ] || { echo "test_install: no sffcal/_core*.so under $prefix" >&2; exit 1; }
site=$(dirname "$(dirname "$core")")
(cd /tmp && PYTHONPATH="$site" /usr/bin/python3 -c "
import sffcal, sffcal.models, sffcal.sff
assert sffcal.__file__.startswith('$site'), sffcal.__file__
assert 'acst' in sffcal.models.model_names() and sffcal.sff.CONTACT_DTYPE.itemsize == 136
") || { echo "test_install: the installed Python package does not import from $site" >&2; exit 1; }
# The pure-Python part's pyproject.toml: pip installs it (from a copy: setuptools builds in the
# source folder).
scratch=$(mktemp -d)
cp -r python/pyproject.toml python/sffcal "$scratch/"
/usr/bin/python3 -m pip install -q --no-deps --no-build-isolation --target "$scratch/site" \
  "$scratch" > "$scratch/pip.log" 2>&1 ||
  { cat "$scratch/pip.log" >&2; echo "test_install: pip cannot install python/ (pyproject.toml)" >&2; exit 1; }
(cd /tmp && PYTHONPATH="$scratch/site" /usr/bin/python3 -c "import sffcal.runfile, sffcal.seeds") ||
  { echo "test_install: the pip-installed pure-Python part does not import" >&2; exit 1; }
rm -rf "$scratch"
echo "test_install: the installed package builds and runs examples/external_fe; the Python package imports"
