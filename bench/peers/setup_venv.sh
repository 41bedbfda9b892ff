#!/usr/bin/env bash
# Sets up everything the peer bench needs, idempotently and quietly when already done:
#   - the Debian packages in bench/peers/debian-packages.txt (apt-get; sudo when not root),
#   - bench/.venv with the peer solvers' Python packages (pinned versions below),
#   - the Bonmin driver (build_bonmin_driver.sh).
# A Python package that cannot be installed is reported and skipped: solve_mps.py then
# reports that solver as "unavailable: <reason>" instead of failing.
# Options: --no-apt (skip the Debian packages), --no-bonmin (skip the driver build).
set -euo pipefail

HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
REPO="$(cd "$HERE/../.." && pwd)"
VENV="$REPO/bench/.venv"
PYTHON="${PYTHON:-python3}"

# Versions checked to install and run on Python 3.11 (Debian 12).
PIP_PACKAGES=(
  "pyscipopt==6.3.0"
  "coptpy==8.0.7"
  "cplex==22.2.0.1"
  "gurobipy==13.0.3"
)

do_apt=1
do_bonmin=1
for arg in "$@"; do
  case "$arg" in
    --no-apt) do_apt=0 ;;
    --no-bonmin) do_bonmin=0 ;;
    *) echo "setup_venv.sh: unknown option $arg (allowed: --no-apt --no-bonmin)" >&2; exit 2 ;;
  esac
done

if [[ $do_apt == 1 ]]; then
  mapfile -t wanted < <(grep -v '^\s*#' "$HERE/debian-packages.txt" | grep -v '^\s*$')
  missing=()
  for pkg in "${wanted[@]}"; do
    dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed" || missing+=("$pkg")
  done
  if (( ${#missing[@]} )); then
    SUDO=""
    [[ $(id -u) == 0 ]] || SUDO="sudo"
    echo "setup_venv.sh: installing Debian packages: ${missing[*]}"
    $SUDO apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${missing[@]}" >/dev/null
  fi
fi

if [[ ! -x "$VENV/bin/python" ]]; then
  echo "setup_venv.sh: creating $VENV"
  "$PYTHON" -m venv "$VENV"
  "$VENV/bin/python" -m pip install -q --upgrade pip
fi

failed=()
for spec in "${PIP_PACKAGES[@]}"; do
  name="${spec%%==*}"
  want="${spec##*==}"
  have="$("$VENV/bin/python" -m pip show "$name" 2>/dev/null | sed -n 's/^Version: //p' || true)"
  [[ "$have" == "$want" ]] && continue
  echo "setup_venv.sh: pip install $spec"
  if ! "$VENV/bin/python" -m pip install -q "$spec"; then
    failed+=("$spec")
  fi
done
if (( ${#failed[@]} )); then
  echo "setup_venv.sh: could not install: ${failed[*]} (those solvers will be reported unavailable)" >&2
fi

if [[ $do_bonmin == 1 ]]; then
  "$HERE/build_bonmin_driver.sh"
fi
