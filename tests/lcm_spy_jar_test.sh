#!/bin/bash
# tools/mfp-spy.sh --build-only: the jar holds a class for every .lcm file, compiled
# against LCM's lcm.jar, so lcm.spy.Spy can decode mfp's channels.
# usage: lcm_spy_jar_test.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
SOURCE_DIR=$(realpath "$1")
BUILD_DIR=$(realpath "$2")
JAR=$("$SOURCE_DIR/tools/mfp-spy.sh" --build-only --jar-dir "$BUILD_DIR/mfp-spy")
entries=$(jar tf "$JAR")
for lcm in "$SOURCE_DIR"/lcmtypes/*.lcm; do
  class="mfp/$(basename "$lcm" .lcm).class"
  grep -qx "$class" <<<"$entries" || { echo "FAIL: $class missing from $JAR"; exit 1; }
done
# Each class is an LCM type the spy can find: it implements lcm.lcm.LCMEncodable.
javap -cp "/usr/share/java/lcm.jar:$JAR" mfp.plan_t | grep -q "implements lcm.lcm.LCMEncodable" \
  || { echo "FAIL: mfp.plan_t is not an LCMEncodable"; exit 1; }
echo "PASS: $JAR"
