#!/usr/bin/env python3
"""The folder tree is the library graph: every #include "x/y.h" follows the CMake links.

The rules come from the library graph CMake writes at configure time
(cmake/MfpLibraryGraph.cmake), never from a table kept by hand:
- a folder belongs to the targets that list sources in it (its internal/ sub-folder too);
- a file may include headers of its own folder and of the folders of the libraries its
  targets link, directly or through their public (interface) links;
- a header in an internal/ folder is private: only its own folder (and tests/) includes it;
- base/ includes the standard library, POSIX's C headers and Eigen only;
- every C++ file lies in a folder some target lists sources in.

usage: include_direction_test.py SOURCE_DIR LIBRARY_GRAPH
"""
import os
import re
import sys

# Headers generated at build time: their include prefix and the target that provides them.
GENERATED = {'mfp': 'mfp_lcmtypes'}
# Folders of C++ built outside the CMake build, and by what.
OUTSIDE_THE_BUILD = {'bench/peers': 'bench/peers/build_bonmin_driver.sh, against Bonmin only'}
# The platform's own C interface, which base/bounded_file.cc needs to refuse a FIFO or a
# device before opening it (no library beside the standard one).
POSIX_HEADERS = {'fcntl.h', 'sys/stat.h', 'unistd.h'}
INCLUDE = re.compile(r'^\s*#\s*include\s+([<"])([^>"]+)[>"]', re.M)
CXX = ('.h', '.hpp', '.cc', '.cpp')


def read_graph(path):
    targets = {}
    with open(path, encoding='utf-8') as f:
        for line in f:
            name, kind, folder, sources, links, interface = line.rstrip('\n').split('\t')
            split = lambda s: [x for x in s.split(';') if x and x != 'NOTFOUND']
            targets[name] = dict(kind=kind, folder=folder, sources=split(sources),
                                 links=split(links), interface=split(interface))
    return targets


def owned_folders(name, target, root):
    folders = set()
    for source in target['sources']:
        path = os.path.normpath(os.path.join(root, target['folder'], source))
        rel = os.path.relpath(path, root)
        if not rel.startswith('..') and rel.endswith(CXX):
            folders.add(os.path.dirname(rel))
    folders |= {prefix for prefix, owner in GENERATED.items() if owner == name}
    return folders


def public_closure(name, targets, memo):
    """The folders a consumer of `name` may include: its own and its interface links'."""
    if name not in memo:
        memo[name] = set()  # cycles end here
        result = set(targets[name]['owned'])
        for dep in targets[name]['interface']:
            if dep in targets:
                result |= public_closure(dep, targets, memo)
        memo[name] = result
    return memo[name]


def library_folder(path):
    folder = os.path.dirname(path)
    return folder[:-len('/internal')] if folder.endswith('/internal') else folder


def cxx_files(root):
    for dirpath, dirnames, filenames in os.walk(root):
        dirnames[:] = [d for d in dirnames if not d.startswith('.')
                       and not os.path.exists(os.path.join(dirpath, d, 'CMakeCache.txt'))]
        for name in filenames:
            if name.endswith(CXX):
                yield os.path.relpath(os.path.join(dirpath, name), root)


def main():
    root, graph = sys.argv[1], sys.argv[2]
    targets = read_graph(graph)
    for name, target in targets.items():
        target['owned'] = owned_folders(name, target, root)
    memo, allowed = {}, {}
    for name, target in targets.items():
        reach = set(target['owned'])
        for dep in target['links'] + target['interface']:
            if dep in targets:
                reach |= public_closure(dep, targets, memo)
        for folder in target['owned']:
            allowed.setdefault(folder, set()).update(reach)

    failures = []
    for path in sorted(cxx_files(root)):
        folder = library_folder(path)
        if folder in OUTSIDE_THE_BUILD:
            continue
        if folder not in allowed:
            failures.append('%s: no CMake target lists sources in %s/ (one folder, one '
                            'library: add the file to a target of its folder)' % (path, folder))
            continue
        with open(os.path.join(root, path), encoding='utf-8') as f:
            text = f.read()
        for kind, header in INCLUDE.findall(text):
            if kind == '<':
                if folder == 'base' and not (header.startswith('Eigen/') or
                                             re.fullmatch(r'[a-z_]+', header) or
                                             header in POSIX_HEADERS):
                    failures.append('%s includes <%s>: base/ sees only the standard library '
                                    'and Eigen' % (path, header))
                continue
            if '/' not in header:
                continue  # a header next to the file
            included = library_folder(header)
            if included.split('/')[0] in GENERATED and included not in allowed:
                included = included.split('/')[0]
            if included != folder and included not in allowed[folder]:
                failures.append('%s includes "%s": %s/ links no library of %s/ (may include %s)'
                                % (path, header, folder, included,
                                   ' '.join(sorted(allowed[folder]))))
            elif ('/internal/' in header and included != folder and folder != 'tests'):
                failures.append('%s includes "%s": a private header of %s/ (move it out of '
                                'internal/ to make it part of the library\'s interface)'
                                % (path, header, included))
    for failure in failures:
        print('FAIL: ' + failure)
    if failures:
        print('%d include(s) against the library graph' % len(failures))
        return 1
    print('every include follows the library graph (%d folders)' % len(allowed))
    return 0


if __name__ == '__main__':
    sys.exit(main())
