#!/usr/bin/env bash
# Builds CalculiX ccx 2.20 from Debian's own source package with sffcal's UMAT linked in place of
# ccx's example umat.f: BUILD/calculix/ccx_sffcal (docs/fe.md, "CalculiX"). Debian's ccx binary
# cannot load a user material at run time, and its material "ABAQUS..." runs that example (linear
# elasticity with E = PROPS(1)) without a word; this ccx calls libsffcal_umat_calculix.so instead
# (the UMAT without DROT: CalculiX gives a user material its stress and strain in the material's
# own axes, model/src/umat_fortran.cc). It also patches ccx (scripts/calculix/) so that Newton uses
# the UMAT's whole tangent, whose unsymmetric part ccx drops, through its unsymmetric solver;
# SFFCAL_CCX_SYMMETRIC_TANGENT=1 at run time turns that off.
#
# Usage: scripts/build_calculix.sh [BUILD]   (BUILD: the project's build folder, default build; its
#        model/libsffcal_umat_calculix.so must exist: scripts/build.sh first)
# Needs the source package, hence a deb-src line for bookworm main; where apt has none, this script
# adds /etc/apt/sources.list.d/sffcal-deb-src.sources (with sudo unless root):
#   Types: deb-src
#   URIs: http://deb.debian.org/debian
#   Suites: bookworm
#   Components: main
# and the build dependencies of calculix-ccx (scripts/install_deps.sh installs them).
set -euo pipefail
cd "$(dirname "$0")/.."
repo=$(pwd)
build=$(cd "${1:-build}" && pwd)
lib_dir=$build/model
[ -f "$lib_dir/libsffcal_umat_calculix.so" ] || {
  echo "build_calculix: $lib_dir/libsffcal_umat_calculix.so not found: run scripts/build.sh first" >&2
  exit 1
}
version=2.20
work=$build/calculix
mkdir -p "$work"
cd "$work"

sudo_cmd=()
[ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
if [ ! -d "calculix-ccx-$version" ]; then
  if ! apt-cache showsrc calculix-ccx 2>/dev/null | grep -q "^Version: $version"; then
    echo "build_calculix: adding a deb-src line for bookworm main"
    printf 'Types: deb-src\nURIs: http://deb.debian.org/debian\nSuites: bookworm\nComponents: main\nSigned-By: /usr/share/keyrings/debian-archive-keyring.gpg\n' |
      "${sudo_cmd[@]}" tee /etc/apt/sources.list.d/sffcal-deb-src.sources > /dev/null
    "${sudo_cmd[@]}" apt-get update -qq
  fi
  apt-get source -qq "calculix-ccx=$version-1" 2>&1 | grep -v "unsandboxed" || true
fi
[ -d "calculix-ccx-$version" ] || { echo "build_calculix: apt-get source calculix-ccx failed" >&2; exit 1; }

src=$work/calculix-ccx-$version/ccx_$version/src
cd "$src"
# sffcal's addition (scripts/calculix): the user material's whole tangent, through ccx's
# unsymmetric solver (docs/fe.md, "CalculiX"). The patch applied is kept beside the source: a
# changed patch replaces it (the old one reversed first), an unchanged one is left.
patches=$repo/scripts/calculix
applied=.sffcal_applied.patch
if ! cmp -s "$patches/unsymmetric_tangent.patch" "$applied"; then
  if [ -f "$applied" ]; then
    patch -s -R -p1 < "$applied" || {
      echo "build_calculix: cannot take the earlier patch out of $src: remove $work and build again" >&2; exit 1; }
  fi
  rm -f "$applied"
  patch -s -N -p1 < "$patches/unsymmetric_tangent.patch" || {
    echo "build_calculix: $patches/unsymmetric_tangent.patch does not apply to the source in $src" \
      "(patched before?): remove $work and build again" >&2; exit 1; }
  cp "$patches/unsymmetric_tangent.patch" "$applied"
fi
# Debian's flags (debian/rules), multithreaded SPOOLES and ARPACK.
cflags="-O2 -w -I/usr/include/spooles -DARCH=\"Linux\" -DSPOOLES -DARPACK -DMATRIXSTORAGE -DUSE_MT=1"
fflags="-O2 -w -fallow-argument-mismatch"
make -s -j"$(nproc)" "ccx_$version.a" CFLAGS="$cflags" FFLAGS="$fflags" > "$work/make.log" 2>&1 || {
  tail -20 "$work/make.log" >&2; echo "build_calculix: the ccx objects did not build ($work/make.log)" >&2; exit 1; }
# ccx's example UMAT out, sffcal's in (the library exports umat_, Abaqus' Fortran name), and the
# assembly of the tangent's unsymmetric part.
gfortran $fflags -I"$src" -c "$patches/sffcal_e_c3d_unsym.f" -o sffcal_e_c3d_unsym.o
cp "ccx_$version.a" ccx_sffcal.a
ar d ccx_sffcal.a umat.o
ar r ccx_sffcal.a sffcal_e_c3d_unsym.o
eval "cc $cflags -c ccx_$version.c -o ccx_main.o"
gfortran -O2 -o "$work/ccx_sffcal" ccx_main.o ccx_sffcal.a -L"$lib_dir" -lsffcal_umat_calculix \
  -Wl,-rpath,"$lib_dir" -lspooles -lpthread -larpack -llapack -lblas -lm -lc -fopenmp
echo "build_calculix: $work/ccx_sffcal (CalculiX $version with $lib_dir/libsffcal_umat_calculix.so)"
