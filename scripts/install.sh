#!/usr/bin/env bash
# Builds mtcut's C library (release) and installs it into a prefix:
#
#   PREFIX/include/mtcut.h
#   PREFIX/lib/libmtcut.so.X.Y.Z, libmtcut.so.X -> it, libmtcut.so -> libmtcut.so.X
#   PREFIX/lib/libmtcut.a
#   PREFIX/lib/cmake/mtcut/mtcutConfig.cmake, mtcutConfigVersion.cmake
#   PREFIX/lib/pkgconfig/mtcut.pc
#
# Usage: scripts/install.sh --prefix DIR
#
# Needs cargo and cmake (for the package's version file). The installed tree holds no
# absolute path: it can be moved as a whole.
set -euo pipefail

usage() { echo "usage: $0 --prefix DIR" >&2; exit 2; }
prefix=""
while [ $# -gt 0 ]; do
  case "$1" in
    --prefix) [ $# -ge 2 ] || usage; prefix=$2; shift 2 ;;
    --prefix=*) prefix=${1#--prefix=}; shift ;;
    *) usage ;;
  esac
done
[ -n "$prefix" ] || usage
command -v cmake >/dev/null || { echo "$0: cmake is needed (apt-get install cmake)" >&2; exit 1; }
mkdir -p "$prefix"
prefix=$(cd "$prefix" && pwd)

cd "$(dirname "$0")/.."
version=$(sed -n 's/^version = "\(.*\)"$/\1/p' Cargo.toml | head -n 1)
major=${version%%.*}
# Where cargo builds (CARGO_TARGET_DIR, a config file, or ./target), as an absolute path.
target_dir=$(cargo metadata --format-version 1 --no-deps --locked |
  sed -n 's/.*"target_directory":"\([^"]*\)".*/\1/p')
[ -n "$target_dir" ] || { echo "$0: cargo metadata gave no target directory" >&2; exit 1; }
target=$target_dir/release
native="$target/mtcut-native-static-libs.txt"

# One build gives the shared and the static library, and rustc's list of the system
# libraries the static one needs (written when the library is compiled).
build() { cargo rustc --release --locked --lib -- --print "native-static-libs=$native"; }
build
if [ ! -s "$native" ]; then
  # Up to date from a build that did not ask for the list: rebuild this crate once.
  cargo clean --release -p mtcut
  build
fi
native_libs=$(tr -s ' \n' '  ' < "$native" | sed 's/ *$//')
# The same libraries as a CMake list: -lfoo becomes foo.
native_cmake=$(for l in $native_libs; do printf '%s;' "${l#-l}"; done | sed 's/;$//')

lib="$prefix/lib"
mkdir -p "$prefix/include" "$lib/cmake/mtcut" "$lib/pkgconfig"
install -m 644 include/mtcut.h "$prefix/include/mtcut.h"
install -m 755 "$target/libmtcut.so" "$lib/libmtcut.so.$version"
ln -sfn "libmtcut.so.$version" "$lib/libmtcut.so.$major"
ln -sfn "libmtcut.so.$major" "$lib/libmtcut.so"
install -m 644 "$target/libmtcut.a" "$lib/libmtcut.a"

fill() {
  sed -e "s|@MTCUT_VERSION@|$version|g" -e "s|@MTCUT_VERSION_MAJOR@|$major|g" \
      -e "s|@MTCUT_NATIVE_LIBS@|$native_libs|g" -e "s|@MTCUT_NATIVE_LIBS_CMAKE@|$native_cmake|g" \
      "$1" > "$2"
}
fill cmake/mtcutConfig.cmake.in "$lib/cmake/mtcut/mtcutConfig.cmake"
fill cmake/mtcut.pc.in "$lib/pkgconfig/mtcut.pc"
pointer_bytes=$(( $(getconf LONG_BIT) / 8 ))
cmake -DOUT="$lib/cmake/mtcut/mtcutConfigVersion.cmake" -DVERSION="$version" \
      -DSIZEOF_VOID_P="$pointer_bytes" -P cmake/write-version-file.cmake

echo "installed mtcut $version into $prefix"
