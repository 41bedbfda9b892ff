#!/usr/bin/env bash
# Self-test of the peer bench (kept out of the default ctest suite: it needs pip installs).
# Sets up bench/.venv and the Bonmin driver if needed (setup_venv.sh, idempotent), then
# checks that every available peer finds the known optima of the MPS instances in
# instances/ and agrees on a generated one. Exits non-zero on any disagreement.
# Extra arguments go to selftest.py (e.g. --solvers scip,bonmin).
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
REPO="$(cd "$HERE/../.." && pwd)"
"$HERE/setup_venv.sh" ${MFP_PEERS_NO_APT:+--no-apt}
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 MKL_NUM_THREADS=1
exec "$REPO/bench/.venv/bin/python" "$HERE/selftest.py" --python "$REPO/bench/.venv/bin/python" "$@"
