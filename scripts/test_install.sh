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
echo "test_install: the installed package builds and runs examples/external_fe"
