#!/usr/bin/env bash
# Regenerates include/mtcut.h from src/ffi with the pinned cbindgen (scripts/cbindgen-version),
# or writes it to the path given as argument (tests/ffi_header.rs compares that with the
# checked-in header).
#   scripts/gen-header.sh [OUTPUT]
#   scripts/gen-header.sh --install-cbindgen   # installs the pinned cbindgen if missing, only
set -euo pipefail
cd "$(dirname "$0")/.."

pin=$(cat scripts/cbindgen-version)
found=$(cbindgen --version 2>/dev/null || echo "no cbindgen")
if [ "${1:-}" = "--install-cbindgen" ]; then
  if [ "$found" != "cbindgen $pin" ]; then
    # Debian's cbindgen (0.24) cannot parse #[unsafe(no_mangle)], which edition 2024 needs.
    cargo install cbindgen --version "$pin" --locked
  fi
  exit 0
fi
if [ "$found" != "cbindgen $pin" ]; then
  echo "scripts/gen-header.sh: needs cbindgen $pin, found: $found" >&2
  echo "  install it with: scripts/gen-header.sh --install-cbindgen" >&2
  echo "  (that is: cargo install cbindgen --version $pin --locked)" >&2
  exit 1
fi
cbindgen --quiet --config cbindgen.toml --output "${1:-include/mtcut.h}" src/ffi/mod.rs
