#!/usr/bin/env bash
# The whole test suite: the same set-up as tools/demo.sh, then every ctest test.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/tools/setup.sh"
build="${MFP_BUILD_DIR:-$root/build}"
cd "$build"
ctest --output-on-failure -j2 --timeout 600 "$@"
