#!/usr/bin/env bash
# Installs the Debian packages mfp needs (tools/debian-packages.txt) that are missing,
# then configures and builds mfp in build/ (Release). Used by tools/demo.sh and
# tools/test.sh; safe to run again (nothing is reinstalled or rebuilt needlessly).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${MFP_BUILD_DIR:-$root/build}"

say() { printf '[mfp setup] %s\n' "$*"; }

mapfile -t wanted < <(grep -v '^\s*#' "$root/tools/debian-packages.txt" | sed '/^\s*$/d')
missing=()
for pkg in "${wanted[@]}"; do
  dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q 'install ok installed' || missing+=("$pkg")
done
if ((${#missing[@]})); then
  say "installing ${#missing[@]} Debian packages: ${missing[*]}"
  sudo=""
  if [ "$(id -u)" -ne 0 ]; then
    command -v sudo >/dev/null || { echo "mfp setup: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
    sudo="sudo"
  fi
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
else
  say "all ${#wanted[@]} Debian packages present"
fi

jobs="$(nproc 2>/dev/null || echo 2)"
say "configuring and building in $build ($jobs jobs)"
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null
# The whole build log stays in build/build.log; errors, warnings and linker failures
# (a missing library shows as 'cannot find -lNAME') are shown here.
built=0
cmake --build "$build" -j"$jobs" >"$build/build.log" 2>&1 && built=1
grep -E "error|warning:|Error|cannot find|undefined reference" "$build/build.log" || true
((built)) && test -x "$build/tools/mfp-plan" || { echo "mfp setup: build failed (full log: $build/build.log)" >&2; exit 1; }
say "built"
