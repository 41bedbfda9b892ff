#!/usr/bin/env python3
"""Issue 24, foundation and folders: the tree reorganisation, replayable on main plus
whatever has been merged since (see reorganise_tree.sh, which calls this).

Files are placed by rules, not by a list:
  planner/base/   yaml_fields.* -> io/, everything else -> base/
  planner/io/     -> io/
  terrain/        by the library of terrain/CMakeLists.txt that lists the file's .cc
                  (a header follows its .cc; a header without one goes by HEADER_ONLY or,
                  failing that, with the region extraction pipeline, with a warning):
                  mfp_regions -> geometry/, mfp_region_json and mfp_terrain_yaml -> io/,
                  mfp_terrain -> terrain/extraction/, mfp_octomap_io -> terrain/octomap/,
                  mfp_terrain_quality -> terrain/quality/
  tools/daemon/   -> daemon/, except timestamped_log.* -> io/
  tools/          the sources of libraries tools/CMakeLists.txt defines -> io/ (tools/
                  keeps executables and their own files)
  planner/qp/     the sources of mfp_nlp (the NLopt adapter), their headers and
                  NLP_HEADERS -> planner/nlp/ (one folder, one library)
  internal/       then, in every library folder, each header that no file outside the
                  folder includes (tests excepted) moves to the folder's internal/.
The CMake lists of the new folders come from the templates next to this script, with
@SOURCES@ filled from the source lists of today's CMake lists (so sources added since are
carried along). Every step is idempotent.

usage: reorganise_tree.py TEMPLATE_DIR   (at the repository root)
"""
import os
import re
import subprocess
import sys

TEXT_SUFFIXES = ('.cc', '.h', '.hpp', '.py', '.sh', '.cmake', '.md', '.yaml', '.lcm')
TERRAIN_LIBRARY_FOLDERS = {
    'mfp_regions': 'geometry',
    'mfp_region_json': 'io',
    'mfp_terrain_yaml': 'io',
    'mfp_terrain': 'terrain/extraction',
    'mfp_octomap_io': 'terrain/octomap',
    'mfp_terrain_quality': 'terrain/quality',
    'mfp_height_map_file': 'io',
}
HEADER_ONLY = {'terrain/occupancy_map.h': 'terrain/extraction'}
NLP_HEADERS = {'planner/qp/nonlinear_program.h'}
KNOWN_MOVED_TARGETS = {'mfp_base', 'mfp_io', 'mfp_regions', 'mfp_region_json', 'mfp_terrain_yaml',
                       'mfp_terrain', 'mfp_octomap_io', 'mfp_terrain_quality', 'mfp_daemon',
                       'mfp_tool_log', 'mfp_text_output', 'mfp_replay_scenario', 'mfp_nlp',
                       'mfp_height_map_file'}
# Targets merged into another (old name -> the one that now holds their sources).
TARGET_RENAMES = {
    'mfp::regions': 'mfp::geometry', 'mfp_regions': 'mfp_geometry',
    'mfp::region_json': 'mfp::io', 'mfp_region_json': 'mfp_io',
    'mfp::terrain_yaml': 'mfp::io', 'mfp_terrain_yaml': 'mfp_io',
    'mfp::text_output': 'mfp::io', 'mfp_text_output': 'mfp_io',
    'mfp::tool_log': 'mfp::io', 'mfp_tool_log': 'mfp_io',
    'mfp_replay_scenario': 'mfp::daemon',
    'mfp::height_map_file': 'mfp::io', 'mfp_height_map_file': 'mfp_io',
}
# Folders in docs and comments (after the file paths are rewritten).
FOLDER_RENAMES = {'tools/daemon/': 'daemon/', 'planner/base/': 'base/', 'planner/io/': 'io/'}
NEW_CMAKE_FOLDERS = ['base', 'geometry', 'io', 'daemon', 'terrain', 'terrain/extraction',
                     'terrain/octomap', 'terrain/quality', 'planner/nlp']
TOP_LEVEL_SUBDIRS = ['base', 'geometry', 'lcmtypes', 'terrain', 'planner', 'io', 'daemon',
                     'tools', 'bench']
PLANNER_ORDER = ['robot', 'miqp', 'qp', 'nlp', 'search', 'formulation', 'planning']
LIBRARY_FOLDER_ROOTS = ['base', 'geometry', 'io', 'daemon', 'lcmtypes', 'terrain', 'planner']

warnings = []


def warn(text):
    warnings.append(text)
    print('reorganise_tree: WARNING: ' + text, file=sys.stderr)


def git(*args):
    return subprocess.check_output(['git'] + list(args), text=True)


def tracked():
    return [f for f in git('ls-files', '-z').split('\0') if f and os.path.exists(f)]


def read(path):
    with open(path, encoding='utf-8') as f:
        return f.read()


def write(path, text):
    os.makedirs(os.path.dirname(path) or '.', exist_ok=True)
    with open(path, 'w', encoding='utf-8') as f:
        f.write(text)


def strip_cmake_comments(text):
    return re.sub(r'#[^\n]*', '', text)


def cmake_commands(text, command):
    """(first argument, other arguments) of each call of `command` in a CMake list."""
    calls = []
    for m in re.finditer(r'\b' + command + r'\s*\(([^)]*)\)', strip_cmake_comments(text)):
        args = m.group(1).split()
        if args:
            calls.append((args[0], args[1:]))
    return calls


def library_sources(cmake_file):
    """{target: [source path from the root]} of the add_library calls of a CMake list."""
    folder = os.path.dirname(cmake_file)
    libraries = {}
    for name, args in cmake_commands(read(cmake_file), 'add_library'):
        if 'ALIAS' in args or 'INTERFACE' in args:
            continue
        libraries[name] = [os.path.normpath(os.path.join(folder, a)) for a in args
                           if a.endswith(('.cc', '.cpp'))]
    for name, args in cmake_commands(read(cmake_file), 'mfp_add_library'):
        libraries['mfp_' + name] = [os.path.normpath(os.path.join(folder, a)) for a in args
                                    if a.endswith(('.cc', '.cpp'))]
    return libraries


def link_tokens(cmake_file, target):
    tokens = set()
    for name, args in cmake_commands(read(cmake_file), 'target_link_libraries'):
        if name == target:
            tokens |= {a for a in args if a not in ('PUBLIC', 'PRIVATE', 'INTERFACE')}
    for name, args in cmake_commands(read(cmake_file), 'mfp_add_library'):
        if 'mfp_' + name == target:
            tokens |= {a for a in args if a not in ('SOURCES', 'PUBLIC', 'PRIVATE')
                       and not a.endswith(('.cc', '.cpp'))}
    return tokens


# --- where each file goes ---------------------------------------------------------------

def plan_moves(files):
    moves = {}
    for f in files:
        if f.startswith('planner/base/') and not f.endswith('CMakeLists.txt'):
            name = os.path.basename(f)
            moves[f] = ('io/' if name.startswith('yaml_fields.') else 'base/') + name
        elif f.startswith('planner/io/') and not f.endswith('CMakeLists.txt'):
            moves[f] = 'io/' + f[len('planner/io/'):]
        elif f.startswith('tools/daemon/') and not f.endswith('CMakeLists.txt'):
            name = f[len('tools/daemon/'):]
            moves[f] = ('io/' if name.startswith('timestamped_log.') else 'daemon/') + name
    moves.update(plan_terrain_moves(files))
    moves.update(plan_nlp_moves(files))
    if os.path.exists('tools/CMakeLists.txt'):
        for target, sources in library_sources('tools/CMakeLists.txt').items():
            for source in sources:
                if source.startswith('tools/daemon/'):
                    continue  # daemon/ already
                stem = os.path.splitext(source)[0]
                for f in (source, stem + '.h'):
                    if f in files:
                        moves[f] = 'io/' + os.path.basename(f)
    return moves


def plan_nlp_moves(files):
    if not os.path.exists('planner/qp/CMakeLists.txt'):
        return {}
    sources = library_sources('planner/qp/CMakeLists.txt').get('mfp_nlp', [])
    stems = {os.path.splitext(source)[0] for source in sources}
    return {f: 'planner/nlp/' + os.path.basename(f) for f in files
            if os.path.splitext(f)[0] in stems or f in NLP_HEADERS}


def plan_terrain_moves(files):
    flat = [f for f in files if re.fullmatch(r'terrain/[^/]+\.(h|cc)', f)]
    if not flat:
        return {}
    owner = {}
    for target, sources in library_sources('terrain/CMakeLists.txt').items():
        if target not in TERRAIN_LIBRARY_FOLDERS:
            sys.exit('reorganise_tree: terrain/CMakeLists.txt defines %s, which has no folder '
                     'in TERRAIN_LIBRARY_FOLDERS of %s: add one and run again' % (target, __file__))
        for source in sources:
            owner[os.path.splitext(source)[0]] = TERRAIN_LIBRARY_FOLDERS[target]
    moves = {}
    for f in flat:
        stem = os.path.splitext(f)[0]
        if stem in owner:
            folder = owner[stem]
        elif f in HEADER_ONLY:
            folder = HEADER_ONLY[f]
        else:
            folder = 'terrain/extraction'
            warn('%s has no .cc in any terrain library: placed in %s/; move it if it belongs '
                 'elsewhere' % (f, folder))
        moves[f] = folder + '/' + os.path.basename(f)
    return moves


# --- CMake lists -------------------------------------------------------------------------

def old_library_sources():
    """{source path: target} of every library in today's CMake lists."""
    owners = {}
    for f in tracked():
        if os.path.basename(f) == 'CMakeLists.txt':
            for target, sources in library_sources(f).items():
                for source in sources:
                    owners[source] = target
    return owners


def link_drift(template_dir):
    """Warns when a moved library's links changed upstream since the templates were written."""
    expected = {'mfp_base': ('planner/base/CMakeLists.txt', {'Eigen3::Eigen', 'yaml-cpp'}),
                'mfp_io': ('planner/io/CMakeLists.txt',
                           {'mfp::planning', 'mfp::robot', 'mfp::regions', 'mfp::region_json',
                            'mfp::terrain_yaml', 'mfp::terrain', 'mfp::octomap_io', 'yaml-cpp',
                            'nlohmann_json::nlohmann_json'}),
                'mfp_daemon': ('tools/daemon/CMakeLists.txt',
                               {'mfp::transport', 'mfp::io', 'mfp::terrain', 'mfp::octomap_io',
                                'Threads::Threads'}),
                'mfp_regions': ('terrain/CMakeLists.txt', {'mfp::base', 'Eigen3::Eigen'}),
                'mfp_terrain': ('terrain/CMakeLists.txt', {'mfp::regions', 'Eigen3::Eigen'}),
                'mfp_octomap_io': ('terrain/CMakeLists.txt', {'mfp::terrain', 'mfp_octomap'}),
                'mfp_terrain_quality': ('terrain/CMakeLists.txt',
                                        {'mfp::regions', 'Eigen3::Eigen'}),
                'mfp_nlp': ('planner/qp/CMakeLists.txt',
                            {'mfp::base', 'Eigen3::Eigen', 'PkgConfig::NLOPT'})}
    for target, (cmake_file, links) in expected.items():
        if os.path.exists(cmake_file):
            now = link_tokens(cmake_file, target)
            if now != links:
                warn('%s links changed upstream (%s): carry the change into the new CMake '
                     'list by hand' % (target, ' '.join(sorted(now ^ links))))


def write_new_cmake_lists(template_dir, moves, owners):
    by_folder = {}
    for old, target in owners.items():
        new = moves.get(old)
        if new:
            by_folder.setdefault(os.path.dirname(new), []).append(os.path.basename(new))
            if target not in KNOWN_MOVED_TARGETS:
                warn('%s (of %s, a library added since the script was written) is listed in '
                     '%s/CMakeLists.txt: give it its own target there if it needs one'
                     % (old, target, os.path.dirname(new)))
    written = []
    for folder in NEW_CMAKE_FOLDERS:
        template = read(os.path.join(template_dir, folder.replace('/', '_') + '.cmake.in'))
        sources = ''.join('  %s\n' % s for s in by_folder.get(folder, []))
        if '@SOURCES@' in template and not sources:
            warn('no sources moved to %s/: its CMake list is not written' % folder)
            continue
        written.append(folder + '/CMakeLists.txt')
        write(folder + '/CMakeLists.txt', template.replace('@SOURCES@\n', sources))
    for old_list in ('planner/base/CMakeLists.txt', 'planner/io/CMakeLists.txt',
                     'tools/daemon/CMakeLists.txt'):
        if os.path.exists(old_list):
            git('rm', '-q', '-f', old_list)
    git('add', *written)
    if os.path.exists('planner/nlp/CMakeLists.txt'):
        text = remove_cmake_block(read('planner/qp/CMakeLists.txt'), 'mfp_nlp')
        # The comment of the block removed, now the file's last paragraph without a call.
        text = re.sub(r'\n+(#[^\n]*\n)+$', '\n', text)
        write('planner/qp/CMakeLists.txt', text)


def rewrite_top_level_cmake():
    text = read('CMakeLists.txt')
    block = ''.join('add_subdirectory(%s)\n' % d for d in TOP_LEVEL_SUBDIRS)
    text = re.sub(r'(add_subdirectory\([a-z_]+\)\n)+', block, text, count=1)
    text = text.replace('# Every target includes headers as "planner/x.h", "terrain/x.h", ...',
                        '# Every target includes headers from the root: "base/x.h", '
                        '"planner/qp/x.h", ...')
    if 'MfpLibraryGraph' not in text:
        text = text.replace('if(MFP_BUILD_TESTS)\n  enable_testing()\n  add_subdirectory(tests)\n'
                            'endif()\n',
                            'if(MFP_BUILD_TESTS)\n  enable_testing()\n  add_subdirectory(tests)\n'
                            'endif()\n\n# The library graph the include-direction test reads.\n'
                            'include(cmake/MfpLibraryGraph.cmake)\n'
                            'mfp_write_library_graph(${CMAKE_BINARY_DIR}/mfp_library_graph.txt)\n')
    write('CMakeLists.txt', text)


def rewrite_planner_cmake(template_dir):
    folders = [d for d in PLANNER_ORDER if os.path.exists('planner/%s/CMakeLists.txt' % d)]
    folders += sorted(d for d in os.listdir('planner')
                      if os.path.exists('planner/%s/CMakeLists.txt' % d) and d not in folders)
    text = read(os.path.join(template_dir, 'planner.cmake.in'))
    write('planner/CMakeLists.txt', text + ''.join('add_subdirectory(%s)\n' % d for d in folders))


def remove_cmake_block(text, target):
    """Removes a library's add_library, alias and target_* calls from a CMake list."""
    alias = re.escape(target.replace('mfp_', 'mfp::', 1))
    text = re.sub(r'^add_library\(%s\b[^)]*\)\n' % re.escape(target), '', text, flags=re.M)
    text = re.sub(r'^add_library\(%s ALIAS[^)]*\)\n' % alias, '', text, flags=re.M)
    text = re.sub(r'^target_\w+\(%s\b[^)]*\)\n' % re.escape(target), '', text, flags=re.M)
    text = re.sub(r'^mfp_add_library\(%s\b[^)]*\)\n' % re.escape(target[len('mfp_'):]), '', text,
                  flags=re.M)
    return text


def rewrite_tools_cmake():
    text = read('tools/CMakeLists.txt')
    text = re.sub(r'# Text output \(JSON, SVG\) of the command-line tools\.\n',
                  '# The command-line programs, executables only (their libraries: io/, daemon/).\n\n'
                  '# --- planning ---\n', text)
    for target in library_sources('tools/CMakeLists.txt'):
        text = remove_cmake_block(text, target)
        if target not in TARGET_RENAMES:  # a library added since the script was written
            TARGET_RENAMES[target] = 'mfp_io'
            TARGET_RENAMES[target.replace('mfp_', 'mfp::', 1)] = 'mfp::io'
            warn('tools/CMakeLists.txt library %s merged into mfp_io (io/): carry its include '
                 'directories and links into io/CMakeLists.txt by hand' % target)
    text = re.sub(r'\n*# --- daemon and LCM ---\nadd_subdirectory\(daemon\)\n', '\n', text)
    text = re.sub(r'\n{3,}', '\n\n', text)
    text = re.sub(r'(# [^\n]*\n)\n+(add_)', r'\1\2', text)  # a comment keeps its call
    write('tools/CMakeLists.txt', text.lstrip('\n'))


def rename_targets(files):
    pattern = re.compile(r'(?<![\w:./-])(%s)(?![\w:.-])' % '|'.join(
        re.escape(k) for k in sorted(TARGET_RENAMES, key=len, reverse=True)))
    for f in files:
        if not (os.path.basename(f) == 'CMakeLists.txt' or f.endswith('.cmake')):
            continue
        text = read(f)
        new = pattern.sub(lambda m: TARGET_RENAMES[m.group(1)], text)
        new = '\n'.join(dedupe_tokens(line) for line in new.split('\n'))
        if new != text:
            write(f, new)


def dedupe_tokens(line):
    """mfp::io mfp::io -> mfp::io (targets merged into one)."""
    seen, out = set(), []
    for token in re.split(r'(\s+|[()])', line):
        if token.startswith('mfp::') or token == 'mfp_io':
            if token in seen:
                if out and out[-1].isspace():
                    out.pop()
                continue
            seen.add(token)
        out.append(token)
    return ''.join(out)


# --- paths in text ----------------------------------------------------------------------

def rewrite_paths(files, moves, folder_renames=None):
    if not moves and not folder_renames:
        return
    replacements = dict(moves)
    pattern = re.compile(r'(?<![\w/.-])(%s)(?![\w])' % '|'.join(
        re.escape(k) for k in sorted(replacements, key=len, reverse=True))) if moves else None
    folder_pattern = re.compile(r'(?<![\w/.-])(%s)' % '|'.join(
        re.escape(k) for k in folder_renames)) if folder_renames else None
    me = os.path.relpath(__file__)
    for f in files:
        if not (f.endswith(TEXT_SUFFIXES) or os.path.basename(f) == 'CMakeLists.txt'):
            continue
        if f.startswith('tools/dev/') or f.startswith('docs/course_bench/') or f == me:
            continue
        text = read(f)
        new = pattern.sub(lambda m: replacements[m.group(1)], text) if pattern else text
        if folder_pattern and not f.endswith(('.cc', '.h')):
            new = folder_pattern.sub(lambda m: folder_renames[m.group(1)], new)
        elif folder_pattern:
            # In C++ only comments name folders; includes were rewritten file by file.
            new = '\n'.join(line if line.lstrip().startswith('#include') else
                            folder_pattern.sub(lambda m: folder_renames[m.group(1)], line)
                            for line in new.split('\n'))
        if new != text:
            write(f, new)


def git_mv(moves):
    for old, new in sorted(moves.items()):
        if old == new or not os.path.exists(old):
            continue
        os.makedirs(os.path.dirname(new), exist_ok=True)
        git('mv', old, new)


# --- internal/ ----------------------------------------------------------------------------

INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def library_folder(path):
    folder = os.path.dirname(path)
    if folder.endswith('/internal'):
        folder = folder[:-len('/internal')]
    return folder


def is_library_folder(folder):
    return (folder.split('/')[0] in LIBRARY_FOLDER_ROOTS and folder not in ('planner', 'terrain')
            and os.path.exists(folder + '/CMakeLists.txt'))


def plan_internal_moves(files):
    includers = {}
    for f in files:
        if f.endswith(('.cc', '.h', '.hpp')):
            for header in INCLUDE.findall(read(f)):
                includers.setdefault(header, set()).add(library_folder(f))
    moves = {}
    for f in files:
        folder = os.path.dirname(f)
        if not f.endswith('.h') or not is_library_folder(folder):
            continue
        outside = includers.get(f, set()) - {folder, 'tests'}
        if not outside:
            moves[f] = folder + '/internal/' + os.path.basename(f)
    return moves


# --- hand-written files -------------------------------------------------------------------

def copy_hand_written(template_dir):
    for name, dest in (('include_direction_test.py', 'tests/include_direction_test.py'),
                       ('MfpLibraryGraph.cmake', 'cmake/MfpLibraryGraph.cmake')):
        write(dest, read(os.path.join(template_dir, name)))
        if dest.endswith('.py'):
            os.chmod(dest, 0o755)
        git('add', dest)
    if os.path.exists('tests/include_direction_test.sh'):
        git('rm', '-q', '-f', 'tests/include_direction_test.sh')
    text = read('tests/CMakeLists.txt')
    text = re.sub(r'add_test\(NAME include_direction_test\n\s+COMMAND [^)]*\)',
                  'add_test(NAME include_direction_test\n'
                  '         COMMAND python3 ${CMAKE_CURRENT_SOURCE_DIR}/include_direction_test.py\n'
                  '                 ${MFP_SOURCE_ROOT} ${CMAKE_BINARY_DIR}/mfp_library_graph.txt)',
                  text)
    text = text.replace('# --- planner/io ---', '# --- io ---')
    write('tests/CMakeLists.txt', text)
    readme = read('README.md')
    layout = read(os.path.join(template_dir, 'README_layout.md'))
    readme = re.sub(r'## Layout\n.*?(?=\n## )', lambda m: layout.rstrip('\n') + '\n', readme,
                    count=1, flags=re.S)
    write('README.md', readme)


def main():
    template_dir = sys.argv[1]
    if not os.path.exists('CMakeLists.txt') or 'project(mfp' not in read('CMakeLists.txt'):
        sys.exit('reorganise_tree: run me at the root of the mfp repository')
    needed = [f.replace('/', '_') + '.cmake.in' for f in NEW_CMAKE_FOLDERS] + [
        'planner.cmake.in', 'include_direction_test.py', 'MfpLibraryGraph.cmake',
        'README_layout.md']
    missing = [f for f in needed if not os.path.exists(os.path.join(template_dir, f))]
    if missing:
        sys.exit('reorganise_tree: missing templates in %s: %s' % (template_dir, ' '.join(missing)))
    files = tracked()
    moves = plan_moves(files)
    if moves:
        link_drift(template_dir)
        owners = old_library_sources()
        git_mv(moves)
        write_new_cmake_lists(template_dir, moves, owners)
        rewrite_top_level_cmake()
        rewrite_planner_cmake(template_dir)
        rewrite_tools_cmake()
        files = tracked()
        rename_targets(files)
        rewrite_paths(files, moves, FOLDER_RENAMES)
        copy_hand_written(template_dir)
        print('reorganise_tree: moved %d files' % len(moves))
    else:
        print('reorganise_tree: the folders are already reorganised')
    files = tracked()
    internal = plan_internal_moves(files)
    if internal:
        git_mv(internal)
        rewrite_paths(tracked(), internal)
        print('reorganise_tree: %d private headers moved to internal/' % len(internal))
    for w in warnings:
        print('reorganise_tree: WARNING: ' + w)


if __name__ == '__main__':
    main()
