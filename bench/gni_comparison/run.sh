#!/bin/sh
# GNI Fortran codes against geomint (issue 25): bench/gni_comparison/run.sh [GNI_DIR]
# GNI_DIR (or $GM_GNI_DIR) holds Hairer's gni_irk2.f and gni_comp.f (version of 4 Sep 2002; not
# part of geomint, e.g. the gnicodes/ folder of a public copy). They are compiled with
# gfortran -O2 into a temporary directory and linked with driver.c (our force routines) and the
# shared libgeomint of $GM_BUILD_DIR (default: build). Not in CI. Skips, exit 0, without them.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
gni=${1:-${GM_GNI_DIR:-}}
build=${GM_BUILD_DIR:-$root/build}
if [ -z "$gni" ] || [ ! -f "$gni/gni_irk2.f" ] || [ ! -f "$gni/gni_comp.f" ]; then
  echo "gni_comparison: skipped: no gni_irk2.f and gni_comp.f in '${gni}' (pass their directory or set GM_GNI_DIR)"
  exit 0
fi
if ! command -v gfortran >/dev/null 2>&1; then
  echo "gni_comparison: skipped: gfortran not found (apt-get install gfortran)"
  exit 0
fi
if [ ! -f "$build/libgeomint.so" ]; then
  echo "gni_comparison: no $build/libgeomint.so: build geomint first (make build)" >&2
  exit 2
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
gfortran -O2 -std=legacy -c "$gni/gni_irk2.f" -o "$tmp/gni_irk2.o"
gfortran -O2 -std=legacy -c "$gni/gni_comp.f" -o "$tmp/gni_comp.o"
cc -O2 -std=c11 -D_POSIX_C_SOURCE=200809L -I"$root/include" -I"$root/src" -I"$root/bench" \
  -I"$build/include" -c "$here/driver.c" -o "$tmp/driver.o"
gfortran "$tmp/driver.o" "$tmp/gni_irk2.o" "$tmp/gni_comp.o" -L"$build" -lgeomint \
  -Wl,-rpath,"$build" -lm -o "$tmp/gni_comparison"
echo "load: $(cut -d' ' -f1-3 /proc/loadavg); $(date -u '+%Y-%m-%d %H:%M UTC'); GNI from $gni"
"$tmp/gni_comparison"
