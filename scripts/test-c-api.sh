#!/usr/bin/env bash
# The C API end to end, as a user meets it (run by scripts/test.sh after cargo test):
#  1. scripts/install.sh into a fresh prefix, then the prefix moved elsewhere: everything
#     below uses the moved copy, which proves the packages relocatable;
#  2. the libraries: SONAME, symlinks, exported symbols = the header's functions;
#  3. c-examples/ configured with only find_package(mtcut), built, run by ctest: the C99
#     example, the NULL-argument test, the C++17 wrapper, the live scalpel, the VTK round
#     trip, and each under valgrind memcheck;
#  4. minimal consumers: CMake with mtcut::mtcut, CMake with mtcut::mtcut_static,
#     pkg-config, the README's C snippet; and a CMake version request the package must
#     refuse;
#  5. ParaView (pvbatch under xvfb-run) opens what the examples wrote - a plain mesh, cut
#     meshes, extractions - and `mtcut demo`'s outputs (and any FILE.pvd given), checks
#     counts and arrays, and saves screenshots (scripts/pvbatch-check.py).
# Needs cargo, cmake, pkg-config, cc, readelf and nm (binutils), valgrind; for step 5
# pvbatch (paraview), xvfb-run and apt-get (ParaView's Python package is fetched with
# `apt-get download`, DESIGN.md section 8, when pvbatch cannot import it).
#
# Usage: scripts/test-c-api.sh [--screenshots DIR] [FILE.pvd ...]
set -euo pipefail
cd "$(dirname "$0")/.."
screenshots=""
extra_files=()
while [ $# -gt 0 ]; do
  case "$1" in
    --screenshots) screenshots=$2; shift 2 ;;
    *) extra_files+=("$(cd "$(dirname "$1")" && pwd)/$(basename "$1")"); shift ;;
  esac
done

for tool in cmake pkg-config cc readelf nm valgrind; do
  command -v "$tool" >/dev/null || { echo "$0: $tool is needed" >&2; exit 1; }
done
work=$(mktemp -d "${TMPDIR:-/tmp}/mtcut-c-api.XXXXXX")
trap 'rm -rf "$work"' EXIT
step() { printf '\n--> %s\n' "$*"; }
fail() { echo "FAILED: $*" >&2; exit 1; }
version=$(sed -n 's/^version = "\(.*\)"$/\1/p' Cargo.toml | head -n 1)
major=${version%%.*}

step "install into a fresh prefix, then move it"
scripts/install.sh --prefix "$work/staged"
mv "$work/staged" "$work/prefix"
prefix=$work/prefix
if grep -rl "$work/staged" "$prefix"; then
  fail "the files above contain the absolute path they were installed to"
fi

step "libraries: SONAME, links, exported symbols"
lib=$prefix/lib
soname=$(readelf -d "$lib/libmtcut.so.$version" | sed -n 's/.*Library soname: \[\(.*\)\]/\1/p')
[ "$soname" = "libmtcut.so.$major" ] || fail "SONAME is '$soname', expected libmtcut.so.$major"
[ "$(readlink "$lib/libmtcut.so")" = "libmtcut.so.$major" ] || fail "libmtcut.so link"
[ "$(readlink "$lib/libmtcut.so.$major")" = "libmtcut.so.$version" ] || fail "libmtcut.so.$major link"
exported=$(nm -D --defined-only "$lib/libmtcut.so.$version" | awk '{print $3}' | sort)
declared=$(sed -n 's/^[a-z].*[ *]\(mtcut_[a-z0-9_]*\)(.*/\1/p' include/mtcut.h | sort)
diff <(echo "$exported") <(echo "$declared") ||
  fail "the shared library's symbols (<) differ from the header's functions (>)"
echo "SONAME $soname; $(echo "$exported" | wc -l) symbols, all declared in mtcut.h"

step "c-examples: configure with find_package(mtcut), build, ctest (valgrind memcheck)"
cmake -S c-examples -B "$work/examples" -DCMAKE_PREFIX_PATH="$prefix" \
      -DCMAKE_BUILD_TYPE=Debug >/dev/null
cmake --build "$work/examples" -j 2 >/dev/null
ctest --test-dir "$work/examples" --output-on-failure
# Listings are captured before grep reads them: under pipefail, `producer | grep -q` fails
# whenever grep exits at the first match before the producer has written everything.
examples=$(ctest --test-dir "$work/examples" -N)
if ! grep -q vtk_roundtrip <<<"$examples"; then
  # CI installs libvtk9-dev: there the VTK example must have been built and run.
  [ -z "${CI:-}" ] || fail "VTK 9 was not found: the VTK example did not run"
  echo "note: VTK 9 not found, the VTK example was skipped (apt-get install libvtk9-dev)"
fi

consumer() { # NAME CMAKE-ARGS...: configure, build and run c-examples/consumer
  local dir=$work/$1; shift
  cmake -S c-examples/consumer -B "$dir" -DCMAKE_PREFIX_PATH="$prefix" "$@" >/dev/null
  cmake --build "$dir" >/dev/null
  "$dir/app"
}
step "consumer: find_package(mtcut CONFIG REQUIRED) + mtcut::mtcut"
consumer shared
needed=$(readelf -d "$work/shared/app")
grep -q "NEEDED.*\[libmtcut.so.$major\]" <<<"$needed" ||
  fail "the program does not record libmtcut.so.$major"

step "consumer: find_package(mtcut CONFIG REQUIRED) + mtcut::mtcut_static"
consumer static -DMTCUT_STATIC=ON
needed=$(readelf -d "$work/static/app")
if grep -q "NEEDED.*libmtcut" <<<"$needed"; then
  fail "the statically linked program still needs libmtcut.so"
fi

step "consumer: pkg-config --cflags --libs mtcut"
export PKG_CONFIG_PATH=$lib/pkgconfig
[ "$(pkg-config --modversion mtcut)" = "$version" ] || fail "pkg-config version"
# shellcheck disable=SC2046 # the flags are words
cc -std=c99 -o "$work/pc-app" c-examples/consumer/app.c $(pkg-config --cflags --libs mtcut) \
   -Wl,-rpath,"$(pkg-config --variable=libdir mtcut)"
"$work/pc-app"

step "README: the C snippet compiles (C99, every warning an error) and runs"
awk '/compiles and runs this very snippet/ {found = 1} found && /^```c$/ {inside = 1; next}
     inside && /^```$/ {exit} inside {print}' README.md > "$work/readme.c"
[ -s "$work/readme.c" ] || fail "no C snippet found in README.md"
# shellcheck disable=SC2046 # the flags are words
cc -std=c99 -pedantic -Wall -Wextra -Werror -o "$work/readme" "$work/readme.c" \
   $(pkg-config --cflags --libs mtcut) -Wl,-rpath,"$(pkg-config --variable=libdir mtcut)"
(cd "$work" && ./readme "$OLDPWD/tests/data/pinion-coarse.node" && [ -s cut.vtu ]) ||
  fail "the README's C snippet"

step "CMake package version: SameMajorVersion"
next=$((major + 1)).0
if cmake -S c-examples/consumer -B "$work/too-new" -DCMAKE_PREFIX_PATH="$prefix" \
         -DMTCUT_VERSION_REQUEST="$next" >"$work/too-new.log" 2>&1; then
  fail "find_package(mtcut $next) accepted version $version"
fi
grep -q "version: $version" "$work/too-new.log" ||
  fail "find_package(mtcut $next) failed for another reason: $(cat "$work/too-new.log")"
echo "find_package(mtcut $next) refuses $version, as it must"

step "ParaView: pvbatch opens the outputs, checks them, saves screenshots"
out=$work/examples/out
pv_files=("$out/cube.vtu=$work/cube.json" "$out/cut-through.vtu" "$out/cut-part0.vtu"
          "$out/live-scalpel.vtu")
if grep -q "tetgen_mt" <<<"$examples"; then
  pv_files+=("$out/tetgen-coarse.vtu" "$out/tetgen-focus.vtu" "$out/tetgen-cut.vtu"
            "$out/tetgen-mt-cut-coarse.vtu")
fi
if grep -q "vtk_cut" <<<"$examples"; then
  pv_files+=("$out/box-cut.vtu")
fi
# mesh_basics wrote the cube (8 points, 6 tets) with these columns.
cat > "$work/cube.json" <<'JSON'
{"points": 8, "cells": 6, "point_arrays": ["temperature", "displacement"], "cell_arrays": ["material"]}
JSON
# The demo's outputs (a .pvd when the demo writes one), without expectations beyond
# "opens, has tets, same arrays in every step".
cargo run --release --locked --quiet --bin mtcut -- demo -o "$work/demo" >/dev/null
for f in "$work"/demo/*.pvd "$work"/demo/*.vtu "${extra_files[@]}"; do
  [ -e "$f" ] && pv_files+=("$f")
done
pv_run() { xvfb-run -a pvbatch scripts/pvbatch-check.py --screenshots "${screenshots:-$work/screenshots}" "${pv_files[@]}"; }
# Once more on failure: xvfb-run's server start is racy (seen: "bad X server connection"
# and SIGABRT before any file was read, on a busy machine). A real failure fails twice.
pv_check() { pv_run || { echo "pvbatch failed; once more (xvfb-run's X server start is racy)"; pv_run; }; }
if ! command -v pvbatch >/dev/null || ! command -v xvfb-run >/dev/null; then
  [ -z "${CI:-}" ] || fail "pvbatch and xvfb-run are needed (apt-get install --no-install-recommends paraview xvfb xauth)"
  echo "note: pvbatch or xvfb-run not found: the ParaView check was skipped"
else
  echo 'import paraview.simple' > "$work/probe.py"
  if ! xvfb-run -a pvbatch "$work/probe.py" >/dev/null 2>&1; then
    # Debian's pvbatch without its Python package (which conflicts with python3-vtk9):
    # unpack the package beside the system, as DESIGN.md section 8 says.
    target_dir=$(cargo metadata --format-version 1 --no-deps --locked |
      sed -n 's/.*"target_directory":"\([^"]*\)".*/\1/p')
    pvpy=$target_dir/python3-paraview
    if [ ! -d "$pvpy/root/usr/lib/python3/dist-packages/paraview" ]; then
      mkdir -p "$pvpy"
      (cd "$pvpy" && apt-get download python3-paraview >/dev/null && dpkg -x python3-paraview_*.deb root)
    fi
    export PYTHONPATH=$pvpy/root/usr/lib/python3/dist-packages${PYTHONPATH:+:$PYTHONPATH}
  fi
  pv_check
fi

step "C API checks passed"
