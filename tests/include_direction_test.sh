#!/bin/bash
# The folder tree is the library graph: each folder may include only the folders listed
# for it below (its own, and those of the libraries its CMake target links). A new folder
# under planner/ fails until it is given a line here.
#
# usage: include_direction_test.sh SOURCE_DIR
set -euo pipefail
cd "$1"

declare -A allowed=(
  [planner/base]="planner/base"
  [planner/robot]="planner/base planner/robot"
  [planner/miqp]="planner/base planner/miqp"
  [planner/qp]="planner/base planner/miqp planner/qp"
  [planner/search]="planner/base planner/miqp planner/qp planner/search"
  [planner/formulation]="planner/base planner/miqp planner/robot planner/formulation terrain"
  [planner/planning]="planner/base planner/miqp planner/qp planner/search planner/robot planner/formulation planner/planning terrain"
  [planner/io]="planner/base planner/miqp planner/qp planner/search planner/robot planner/formulation planner/planning planner/io terrain"
  [terrain]="planner/base terrain"
  [lcmtypes]="planner/base lcmtypes mfp"  # mfp/: the generated message types
)

failures=0
for file in planner/* ; do
  if [ -f "$file" ] && [ "$(basename "$file")" != CMakeLists.txt ]; then
    echo "FAIL: $file: planner/ holds only sub-folders (one per library)"; failures=$((failures + 1))
  fi
done
for dir in planner/*/ terrain/ lcmtypes/; do
  dir=${dir%/}
  if [ -z "${allowed[$dir]+set}" ]; then
    echo "FAIL: $dir has no include rule in $0"; failures=$((failures + 1)); continue
  fi
  while IFS= read -r hit; do
    file=${hit%%:*}
    header=$(sed -E 's/.*#include "([^"]+)".*/\1/' <<<"$hit")
    case $header in
      planner/*/*) folder=$(cut -d/ -f1-2 <<<"$header") ;;
      */*) folder=${header%%/*} ;;
      *) continue ;;  # a header next to the file (none today)
    esac
    if [[ " ${allowed[$dir]} " != *" $folder "* ]]; then
      echo "FAIL: $file includes $header: $dir may include only ${allowed[$dir]}"
      failures=$((failures + 1))
    fi
  done < <(grep -HE '^[[:space:]]*#[[:space:]]*include[[:space:]]+"' $(find "$dir" -maxdepth 1 -name '*.h' -o -maxdepth 1 -name '*.cc') || true)
done
if ((failures)); then
  echo "$failures include(s) against the library graph"; exit 1
fi
echo "every include follows the library graph"
