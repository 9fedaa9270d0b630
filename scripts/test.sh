#!/usr/bin/env bash
# Every check of mtcut, on a fresh Debian 12 machine: installs what is missing (system
# packages as root; see DEVELOPERS.md), then formatting, lints, and the whole test suite,
# including the cross-checks against VTK.
set -euo pipefail
cd "$(dirname "$0")/.."

step() { printf '\n==> %s (%s)\n' "$*" "$(date +%T)"; }

# System packages the tests use: VTK (C++ and Python) and TetGen for cross-checks and the
# C/C++ examples, CMake for those examples, ParaView (pvbatch) under Xvfb for what a user
# opens; valgrind and binutils (readelf, nm) for the C API checks. `--no-install-recommends`
# matters: paraview's recommends would remove libvtk9-dev.
APT_PACKAGES=(cmake pkg-config g++ binutils valgrind libvtk9-dev libtet1.5-dev tetgen python3-vtk9 python3-numpy paraview xvfb xauth)
missing=()
for p in "${APT_PACKAGES[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [[ $status == *"ok installed"* ]] || missing+=("$p")
done
if ((${#missing[@]})); then
  if [ "$(id -u)" -ne 0 ]; then
    echo "scripts/test.sh: missing Debian packages: ${missing[*]}" >&2
    echo "Run this script as root, or install them first:" >&2
    echo "  sudo apt-get install -y --no-install-recommends ${missing[*]}" >&2
    exit 1
  fi
  step "installing ${missing[*]}"
  apt-get update -q
  DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

# Rust components for the checks (present in a rustup toolchain unless removed).
for c in rustfmt clippy; do
  installed=$(rustup component list --installed 2>/dev/null || true)
  if ! grep -q "^$c" <<<"$installed"; then
    step "installing rust component $c"
    rustup component add "$c"
  fi
done

# The pinned cbindgen: tests/ffi_header.rs regenerates the C header with it and fails when
# the checked-in include/mtcut.h is stale (cargo install, about a minute, when missing).
step "cbindgen $(cat scripts/cbindgen-version)"
scripts/gen-header.sh --install-cbindgen

step "cargo fmt --check"
cargo fmt --all -- --check

step "cargo clippy --all-targets -- -D warnings"
cargo clippy --locked --all-targets -- -D warnings

step "cargo test (unit, integration, CLI, VTK cross-checks)"
cargo test --locked

# One release build of the library, installed into a temporary prefix that the C/C++
# examples (under ctest and valgrind) and the CMake and pkg-config consumers use.
step "C API: install, examples, consumers, valgrind (scripts/test-c-api.sh)"
scripts/test-c-api.sh

# Sequences of 50 MT cuts per shared mesh, the model validated after every cut: a few
# minutes, so apart from `cargo test`'s run. In the test profile, built above: as fast here
# as in release (validation dominates and is parallel), and a release test build would
# compile the library and the dev-dependencies again (2-3 minutes; the dev-dependencies
# change features of shared dependencies).
step "MT cut: sequences of 50 cuts on each shared mesh"
cargo test --locked --test mtcut_cut -- --ignored sequence_of_50_cuts

step "all checks passed"
