#!/usr/bin/env python3
"""Sorts each contiguous block of #include lines in mfp's C++ files.

A block is a run of consecutive lines that start with #include; blank lines, comments
and preprocessor conditionals end it, so the groups a file separates (its own header,
system headers, project headers) stay apart and guarded includes stay under their
guard. Within a block: <...> before "...", then by path; a file's own header
(foo.cc -> foo.h, foo_test.cc -> foo.h) stays first; a line included twice is kept once.
Trailing comments stay on their line.

usage: tools/sort_includes.py [--check] [FILE ...]
  Without FILEs: every C++ file git tracks in the repository holding this script.
  --check: change nothing; list the files that are not sorted and exit 1 if any.
"""
import os
import re
import subprocess
import sys

INCLUDE = re.compile(r'^#include\s*([<"])([^>"]+)[>"]')
SUFFIXES = ('.h', '.hh', '.hpp', '.cc', '.cpp', '.cxx')


def own_header_stem(path):
    stem = os.path.splitext(os.path.basename(path))[0]
    return stem[:-len('_test')] if stem.endswith('_test') else stem


def sort_block(block, path):
    seen, unique = set(), []
    for line in block:
        if line not in seen:
            seen.add(line)
            unique.append(line)
    first = []
    m = INCLUDE.match(unique[0])
    if path.endswith(('.cc', '.cpp', '.cxx')) and m and \
            os.path.splitext(os.path.basename(m.group(2)))[0] == own_header_stem(path):
        first, unique = unique[:1], unique[1:]

    def key(line):
        m = INCLUDE.match(line)
        return (0 if m.group(1) == '<' else 1, m.group(2))

    return first + sorted(unique, key=key)


def sorted_text(text, path):
    lines = text.split('\n')
    out, block = [], []
    for line in lines:
        if INCLUDE.match(line):
            block.append(line)
            continue
        if block:
            out.extend(sort_block(block, path))
            block = []
        out.append(line)
    if block:
        out.extend(sort_block(block, path))
    return '\n'.join(out)


def tracked_files(root):
    names = subprocess.run(['git', '-C', root, 'ls-files'], check=True, capture_output=True,
                           text=True).stdout.split('\n')
    return [os.path.join(root, n) for n in names if n.endswith(SUFFIXES)]


def main(argv):
    check = '--check' in argv
    files = [a for a in argv if a != '--check']
    if not files:
        root = subprocess.run(['git', '-C', os.path.dirname(os.path.abspath(__file__)), 'rev-parse',
                               '--show-toplevel'], check=True, capture_output=True, text=True).stdout.strip()
        files = tracked_files(root)
    unsorted = []
    for path in files:
        with open(path, encoding='utf-8') as f:
            text = f.read()
        new = sorted_text(text, path)
        if new != text:
            unsorted.append(path)
            if not check:
                with open(path, 'w', encoding='utf-8') as f:
                    f.write(new)
    for path in unsorted:
        print(('not sorted: ' if check else 'sorted: ') + os.path.relpath(path))
    return 1 if check and unsorted else 0


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
