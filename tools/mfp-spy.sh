#!/bin/bash
# mfp-spy.sh: watch mfp's LCM channels with lcm-spy.
# Debian's lcm-spy wrapper does not start on Java 17 (it passes -Xincgc) and ships no
# jar of our types. This script builds one (lcm-gen --java, javac, jar) from
# lcmtypes/*.lcm and starts lcm.spy.Spy with LCM's jars and ours on the class path.
# It installs liblcm-java (lcm.jar, the spy) and libjchart2d-java (the spy's charts)
# with apt-get when they are missing.
#
# usage: tools/mfp-spy.sh [--build-only] [--jar-dir DIR] [--lcm-url URL]
#   --build-only   build the jar, print its path, do not start the spy
#   --jar-dir DIR  where the jar goes (default: ${XDG_CACHE_HOME:-~/.cache}/mfp-spy)
#   --lcm-url URL  LCM URL to watch (default: the daemon's, udpm://239.255.76.67:7667?ttl=0)
set -euo pipefail

SOURCE_DIR=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
JAR_DIR="${XDG_CACHE_HOME:-$HOME/.cache}/mfp-spy"
LCM_URL="udpm://239.255.76.67:7667?ttl=0"
BUILD_ONLY=0
while [ $# -gt 0 ]; do
  case "$1" in
    --build-only) BUILD_ONLY=1; shift ;;
    --jar-dir) JAR_DIR="$2"; shift 2 ;;
    --lcm-url) LCM_URL="$2"; shift 2 ;;
    -h|--help) sed -n '2,14p' "$0"; exit 0 ;;
    *) echo "mfp-spy.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done

LCM_JAR=/usr/share/java/lcm.jar
# The spy's charts and message viewer need jchart2d, which liblcm-java does not pull in.
CHART_JAR=/usr/share/java/jchart2d.jar
missing=()
[ -f "$LCM_JAR" ] || missing+=(liblcm-java)
[ -f "$CHART_JAR" ] || [ "$BUILD_ONLY" -eq 1 ] || missing+=(libjchart2d-java)
if [ ${#missing[@]} -gt 0 ]; then
  if [ "$(id -u)" -ne 0 ]; then
    echo "mfp-spy.sh: missing; install with: sudo apt-get install ${missing[*]}" >&2
    exit 1
  fi
  echo "mfp-spy.sh: installing ${missing[*]}" >&2
  apt-get install -y --no-install-recommends "${missing[@]}" >&2
fi
for tool in lcm-gen javac jar java; do
  command -v "$tool" >/dev/null || { echo "mfp-spy.sh: $tool not found (a JDK: default-jdk-headless)" >&2; exit 1; }
done

# Rebuild the jar when a .lcm file is newer than it.
LCM_FILES=("$SOURCE_DIR"/lcmtypes/*.lcm)
JAR="$JAR_DIR/mfp_lcmtypes.jar"
stale=0
[ -f "$JAR" ] || stale=1
for f in "${LCM_FILES[@]}"; do [ "$f" -nt "$JAR" ] && stale=1; done
if [ "$stale" -eq 1 ]; then
  mkdir -p "$JAR_DIR"
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
  lcm-gen --java --jpath "$work/java" "${LCM_FILES[@]}"
  mkdir -p "$work/classes"
  javac -nowarn -cp "$LCM_JAR" -d "$work/classes" $(find "$work/java" -name '*.java')
  jar cf "$JAR.tmp" -C "$work/classes" .
  mv "$JAR.tmp" "$JAR"
fi

if [ "$BUILD_ONLY" -eq 1 ]; then
  echo "$JAR"
  exit 0
fi

# The spy finds message types by scanning the jars on its class path.
CLASSPATH="$LCM_JAR:$CHART_JAR:$JAR"
exec java -Djava.net.preferIPv4Stack=true -Xmx256m -cp "$CLASSPATH" lcm.spy.Spy --lcm-url="$LCM_URL"
