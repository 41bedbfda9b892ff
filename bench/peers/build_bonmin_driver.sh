#!/usr/bin/env bash
# Builds bench/peers/bonmin_mps.cc into build-peers/bonmin_mps (outside the main build, which
# must not need Bonmin). Needs the Debian packages in debian-packages.txt. Rebuilds only when
# the source is newer than the binary.
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
REPO="$(cd "$HERE/../.." && pwd)"
OUT_DIR="${MFP_PEERS_BUILD_DIR:-$REPO/build-peers}"
OUT="$OUT_DIR/bonmin_mps"
SRC="$HERE/bonmin_mps.cc"

if [[ -x "$OUT" && "$OUT" -nt "$SRC" ]]; then
  exit 0
fi
if ! pkg-config --exists bonmin; then
  echo "build_bonmin_driver.sh: pkg-config finds no 'bonmin' (install coinor-libbonmin-dev)" >&2
  exit 1
fi
mkdir -p "$OUT_DIR"
# COIN-OR headers as system headers, so that -Wall -Wextra speak about this file only.
cflags="$(pkg-config --cflags bonmin | sed 's/-I/-isystem /g')"
# shellcheck disable=SC2046,SC2086  # pkg-config output is a list of flags
g++ -std=c++17 -O2 -Wall -Wextra -o "$OUT.tmp" "$SRC" $cflags $(pkg-config --libs bonmin)
mv "$OUT.tmp" "$OUT"
echo "build_bonmin_driver.sh: built $OUT (Bonmin $(pkg-config --modversion bonmin))"
