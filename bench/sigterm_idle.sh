#!/bin/bash
# SIGTERM latency of an idle mfp-daemon (started, no map, no request), RUNS times, inside
# a private network namespace (tests/netns_helper.sh; never the host network). The other
# daemon states (extracting a map, planning, reloading a 16-leg robot) are measured by
# tests/daemon_signals_test.sh, which prints "SIGTERM to exit: N ms" for each.
#
# usage: bench/sigterm_idle.sh SOURCE_DIR BUILD_DIR [RUNS]
set -euo pipefail

SOURCE_DIR=$(realpath "$1")
BUILD_DIR=$(realpath "$2")
RUNS=${3:-5}
URL="udpm://239.255.76.67:7667?ttl=0"

source "$SOURCE_DIR/tests/netns_helper.sh"
mfp_enter_private_namespace "$@"
mfp_test_workspace mfp_sigterm_idle

{
  echo "lcm_url: \"$URL\""
  echo "robots:"
  echo "  - $SOURCE_DIR/config/robots/hexapod.yaml"
  echo "default_robot: hexapod"
} >"$WORK/daemon.yaml"

for run in $(seq 1 "$RUNS"); do
  mfp_start_daemon "$WORK/daemon_$run.log" --config "$WORK/daemon.yaml"
  sleep 1
  t0=$(date +%s%N)
  kill -TERM "$DAEMON_PID"
  status=0
  wait "$DAEMON_PID" || status=$?
  t1=$(date +%s%N)
  DAEMON_PID=""
  echo "idle run $run: SIGTERM to exit $(( (t1 - t0) / 1000000 )) ms, exit status $status"
done
