#!/bin/bash
# Issue 24, foundation and folders: moves today's tree to base/ geometry/ io/ daemon/
# terrain/<library>/ and internal/ folders, rewrites every include and the CMake lists,
# sorts the include blocks. Replayable and idempotent: run it at the repository root of
# a tree like main (new files in the old folders are placed by folder rules); a second
# run changes nothing. Review with `git status` and `git diff --stat -M`, then commit.
#
# usage: tools/dev/reorganise_tree.sh        (at the repository root)
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
python3 "$here/reorganise_tree.py" "$here/reorganise"
python3 tools/sort_includes.py
echo "reorganise_tree: done; review with: git status --short | head; git diff --cached --stat -M | tail -3"
