#!/usr/bin/env python3
"""The layout rules of libvoronoimesh (docs/layout.md), checked on the source tree.

Usage: check_layout.py SOURCE_DIR

1. Stages, from the bottom up (STAGES): a file of a stage includes only files of
   its own stage or of a stage on a lower level. Stages on one level (check and
   io) do not include each other. The umbrella header voronoimesh/voronoimesh.hpp
   is for programs, never included inside the library.
2. Public headers (include/voronoimesh/<stage>/) include only public headers;
   the command-line tool and the plugins include only public headers too.
3. Every source file of the library lies in a stage's folder, and every include
   of the library's own files names a file that exists.
4. No source file (library, tool, plugins, tests, benchmarks, fuzzers,
   examples) is longer than MAX_LINES.

Before looking at the tree it checks itself on a small planted tree with one
breach of each rule: a checker that finds nothing there is broken, and fails.
Exit status 0 when every rule holds, 1 otherwise (each breach on one line).
"""
import os
import re
import sys
import tempfile

# Level of each stage: a stage may include the stages of lower levels.
STAGES = {
    "core": 0,     # errors, text, parallel loops, exact arithmetic, fixed-point sums, JSON, atomic writes, memory
    "mesh": 1,     # NodeMesh, the patch-split InterfaceMesh, topology tables, junctions, queries
    "check": 2,    # validation, self-intersections, statistics, quality histories
    "io": 2,       # mesh readers and writers, volume readers
    "fields": 3,   # phase functions: scenes, inputs, labels, point clouds, sampled and top-K fields
    "create": 4,   # the initial mesh (paper Algorithm 2)
    "improve": 5,  # passes, registry, pipeline, crossing guard (paper Algorithms 1, 3-5)
    "plugin": 6,   # pass plugins behind the C ABI
    "run": 7,      # the one run path: input, field, create, improve, with an observer
    "mpi": 8,      # distributed create and improvement (voronoimesh_mpi)
}
MAX_LINES = 600
SOURCE_SUFFIXES = (".cpp", ".hpp", ".h", ".c", ".cxx", ".in")
GENERATED = {"voronoimesh/core/version.hpp"}
INCLUDE = re.compile(r'^\s*#\s*include\s*"([^"]+)"', re.M)


def source_files(root, folder):
    for base, dirs, files in os.walk(os.path.join(root, folder)):
        dirs.sort()
        for name in sorted(files):
            if name.endswith(SOURCE_SUFFIXES):
                yield os.path.relpath(os.path.join(base, name), root)


def check(root):
    """The breaches of the rules in the tree at `root`, one line each."""
    lib = "libvoronoimesh"
    public_root, private_root = f"{lib}/include/voronoimesh", f"{lib}/src"
    problems = []

    def stage_of_include(target):
        """(stage, public?) of an include of the library's own, or None if it is not one."""
        if target.startswith("voronoimesh/"):
            parts = target.split("/")
            return (parts[1] if len(parts) > 2 else "<umbrella>", True)
        first = target.split("/")[0]
        return (first, False) if first in STAGES and "/" in target else None

    def exists(target, public):
        if public:
            return target in GENERATED or os.path.isfile(os.path.join(root, lib, "include", target)) or \
                os.path.isfile(os.path.join(root, lib, "include", target + ".in"))
        return os.path.isfile(os.path.join(root, private_root, target))

    for folder, public in ((public_root, True), (private_root, False)):
        for path in source_files(root, folder):
            rel = os.path.relpath(path, folder)
            stage = rel.split(os.sep)[0] if os.sep in rel else None
            if stage not in STAGES:
                if not (public and rel == "voronoimesh.hpp"):
                    problems.append(f"{path}: not in a stage's folder ({', '.join(STAGES)})")
                continue
            for target in INCLUDE.findall(open(os.path.join(root, path), encoding="utf-8").read()):
                found = stage_of_include(target)
                if found is None:
                    continue  # a header of a dependency or beside the file
                to, to_public = found
                if public and not to_public:
                    problems.append(f'{path}: public header includes the private "{target}"')
                if to == "<umbrella>":
                    problems.append(f'{path}: includes the umbrella header "{target}", which is for programs')
                    continue
                if to not in STAGES:
                    problems.append(f'{path}: includes "{target}" of no stage')
                    continue
                if not exists(target, to_public):
                    problems.append(f'{path}: includes "{target}", which does not exist')
                if to != stage and STAGES[to] >= STAGES[stage]:
                    problems.append(f'{path}: stage {stage} (level {STAGES[stage]}) includes "{target}" of stage '
                                    f'{to} (level {STAGES[to]}): includes run down the levels only')

    for folder in ("tools", "plugins", "python", "paraview"):
        for path in source_files(root, folder):
            for target in INCLUDE.findall(open(os.path.join(root, path), encoding="utf-8").read()):
                found = stage_of_include(target)
                if found and not found[1]:
                    problems.append(f'{path}: includes the library\'s private "{target}"')

    for folder in (lib, "tools", "plugins", "python", "paraview", "tests", "bench", "fuzz", "examples"):
        for path in source_files(root, folder):
            with open(os.path.join(root, path), encoding="utf-8", errors="replace") as f:
                lines = sum(1 for _ in f)
            if lines > MAX_LINES:
                problems.append(f"{path}: {lines} lines, more than {MAX_LINES}: split it by what its parts do")
    return problems


def self_test():
    """The checker must find each planted breach in a small tree."""
    planted = {
        "libvoronoimesh/include/voronoimesh/core/types.hpp": "",
        "libvoronoimesh/include/voronoimesh/mesh/node_mesh.hpp": '#include "voronoimesh/improve/pass.hpp"\n',
        "libvoronoimesh/include/voronoimesh/improve/pass.hpp": '#include "improve/hidden.hpp"\n',
        "libvoronoimesh/src/improve/hidden.hpp": "",
        "libvoronoimesh/src/check/stats.cpp": '#include "io/writers.hpp"\n#include "core/missing.hpp"\n',
        "libvoronoimesh/src/io/writers.hpp": "",
        "libvoronoimesh/src/detail/catch_all.cpp": "",
        "tools/cli/main.cpp": '#include "core/text.hpp"\n',
        "tests/unit/long.cpp": "x\n" * (MAX_LINES + 1),
    }
    expected = ["node_mesh.hpp: stage mesh", "pass.hpp: public header includes the private",
                "stats.cpp: stage check (level 2) includes \"io/writers.hpp\" of stage io (level 2)",
                "core/missing.hpp\", which does not exist", "catch_all.cpp: not in a stage's folder",
                "main.cpp: includes the library's private", "long.cpp: 601 lines"]
    with tempfile.TemporaryDirectory() as tree:
        for path, text in planted.items():
            os.makedirs(os.path.dirname(os.path.join(tree, path)), exist_ok=True)
            with open(os.path.join(tree, path), "w") as f:
                f.write(text)
        found = check(tree)
    missed = [e for e in expected if not any(e in p for p in found)]
    if missed or len(found) != len(expected):
        print("check_layout.py is broken: on its planted tree it found", found, "but missed", missed)
        return False
    return True


def main():
    if len(sys.argv) != 2:
        print(__doc__.split("\n\n")[1])
        return 2
    if not self_test():
        return 1
    problems = check(sys.argv[1])
    for p in problems:
        print(p)
    if problems:
        print(f"{len(problems)} breach(es) of the layout rules (tests/layout/check_layout.py says what they are)")
        return 1
    print(f"layout: {len(STAGES)} stages, includes run down the levels, public headers include public ones, "
          f"no source file over {MAX_LINES} lines")
    return 0


if __name__ == "__main__":
    sys.exit(main())
