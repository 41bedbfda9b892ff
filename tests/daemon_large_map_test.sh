#!/bin/bash
# A map of more than 1 MB over real LCM (udpm://), inside a private network namespace
# this script makes (unshare -n, only lo, with a multicast route; never the host
# network): with the receive buffer the config sets (lcm_recv_buf_bytes), every fragment
# arrives, the daemon accepts the whole map and plans a request on it. LCM's own default
# buffer lost maps of about 0.67 MB or more (with a 200 KB buffer this map is lost: the
# test then fails on "did not arrive whole").
#
# usage: daemon_large_map_test.sh SOURCE_DIR BUILD_DIR
set -euo pipefail

SOURCE_DIR=$(realpath "$1")
BUILD_DIR=$(realpath "$2")
DATA="$SOURCE_DIR/tests/data/daemon_large_map"
BUFFER_BYTES=3145728  # 3 MiB: more than the map, within a common net.core.rmem_max (4 MiB)

# Runs this script again inside a private network namespace (tests/netns_helper.sh).
source "$SOURCE_DIR/tests/netns_helper.sh"
mfp_enter_private_namespace "$@"

mfp_test_workspace mfp_daemon_large_map
LOG="$WORK/daemon.log"

# The map: stones of 0.21 m on a 0.27 m grid around a 1.2 m pad, tops within 3 cm, at
# 1 cm resolution, written as .ot (occupancy values: larger than .bt).
{
  echo "terrain:"
  echo "  resolution: 0.01"
  echo "  boxes:"
  echo "    - {name: pad, center: [0, 0, -0.05], size: [1.2, 1.2, 0.1]}"
  for i in $(seq -9 9); do
    for j in $(seq -9 9); do
      if [ "${i#-}" -le 1 ] && [ "${j#-}" -le 1 ]; then continue; fi
      top=$(( ((i * 7 + j * 13) % 7 + 7) % 7 ))  # 0 .. 6 cm
      printf "    - {name: s%d_%d, center: [%s, %s, %s], size: [0.21, 0.21, 0.1]}\n" "$((i + 9))" "$((j + 9))" \
        "$(awk "BEGIN{print 0.27 * $i}")" "$(awk "BEGIN{print 0.27 * $j}")" "$(awk "BEGIN{print 0.01 * $top - 0.08}")"
    done
  done
} >"$WORK/large_map_terrain.yaml"
"$BUILD_DIR/tools/mfp-terrain" "$WORK/large_map_terrain.yaml" --out "$WORK/large_map.ot" >/dev/null
MAP_BYTES=$(stat -c %s "$WORK/large_map.ot")
[ "$MAP_BYTES" -ge 1000000 ] || fail "the test map is only $MAP_BYTES bytes; it must be 1 MB or more"
echo "map: $MAP_BYTES bytes"
cp "$DATA/large_map.yaml" "$WORK/"

{
  echo "lcm_url: \"$URL\""
  echo "robots:"
  echo "  - $SOURCE_DIR/config/robots/hexapod.yaml"
  echo "default_robot: hexapod"
  echo "lcm_recv_buf_bytes: $BUFFER_BYTES"
  echo "limits:"
  echo "  max_map_bytes: 3000000"
} >"$WORK/daemon.yaml"

"$BUILD_DIR/tools/mfp-make-log" "$WORK/large_map.yaml" --config "$WORK/daemon.yaml" --out "$WORK/large_map.lcmlog"
mfp_start_logger "$WORK/replies.lcmlog"
mfp_start_daemon "$LOG" --config "$WORK/daemon.yaml"
grep -qi "rmem_max" "$LOG" && fail "the kernel capped the receive buffer below $BUFFER_BYTES bytes: raise it with sysctl -w net.core.rmem_max=$BUFFER_BYTES"

lcm-logplayer --lcm-url="$URL" "$WORK/large_map.lcmlog"
for _ in $(seq 1 200); do
  grep -q "request 1 planned" "$LOG" && break
  sleep 0.1
done
grep -q "map accepted (.*): $MAP_BYTES bytes" "$LOG" || fail "the $MAP_BYTES-byte map did not arrive whole"
grep -q "request 1 planned" "$LOG" || fail "the request after the map was not planned within 20 s"
kill -TERM "$DAEMON_PID"; wait "$DAEMON_PID" || fail "mfp-daemon exited with $? on SIGTERM"; DAEMON_PID=""
sleep 0.5
kill -INT "$LOGGER_PID"; wait "$LOGGER_PID" || true; LOGGER_PID=""
"$BUILD_DIR/tools/mfp-check-replies" "$WORK/replies.lcmlog" --scenario "$WORK/large_map.yaml" \
  --config "$WORK/daemon.yaml" || fail "the reply does not check"
grep "map accepted\|request 1 planned" "$LOG"
echo "PASS"
