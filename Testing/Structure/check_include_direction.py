#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Checks that the code's includes point one way (README "Layout").

Core/ has one folder per stage of the method, in the method's order (STAGES). A Core file may
include headers of its own stage and of earlier ones only, always written from Core's root
("cover/RBuffer.h"), and no VTK header. Of the VTK modules, Common/ is the bridge that Readers/
and Filters/ share: Common includes neither of them, and Readers and Filters include nothing of
each other (they meet only through the pipeline's datasets). Parallel/ (the distributed filters)
and Views/ stand above Filters/ and include nothing of Readers/; no module includes Apps/ or
Parallel/ from below.

Usage: check_include_direction.py [ROOT]    (ROOT: the checkout, default: this file's ../..)
       check_include_direction.py --self-test
Prints one line per violation (file:line: problem) and exits 1 if there is any.
"""
import os
import re
import sys
import tempfile

# distributed/ comes last: the method's stages run serially, and what shares their work among
# processes (ranks) builds on all of them; none of them includes it.
STAGES = ["math", "geometry", "scene", "subdivision", "cover", "reflectance", "propagation",
          "render", "distributed"]
# Which of the VTK modules' folders each may include headers of.
# Parallel/ stands above Filters/ (its classes are the serial filters plus ranks); Views/
# (the plug-in's render-view classes) above Filters/; Apps/ (the command line) above them all.
MODULES = {"Common": {"Common"}, "Readers": {"Common", "Readers"},
           "Filters": {"Common", "Filters"},
           "Parallel": {"Common", "Filters", "Parallel"},
           "Views": {"Common", "Filters", "Views"},
           "Apps": {"Common", "Readers", "Filters", "Parallel", "Apps"}}
INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^">]+)[">]')
SOURCE_SUFFIXES = (".h", ".cxx", ".cpp", ".hpp")


def sources(folder):
    for parent, _, names in os.walk(folder):
        for name in sorted(names):
            if name.endswith(SOURCE_SUFFIXES):
                yield os.path.join(parent, name)


def includes(path):
    with open(path, encoding="utf-8") as text:
        for number, line in enumerate(text, 1):
            match = INCLUDE.match(line)
            if match:
                yield number, match.group(1), match.group(2)


def check_core(root):
    core = os.path.join(root, "Core")
    problems = []
    for path in sources(core):
        relative = os.path.relpath(path, core)
        stage = relative.split(os.sep)[0]
        where = os.path.relpath(path, root)
        if stage not in STAGES:
            problems.append(f"{where}:1: not in a stage folder of Core ({', '.join(STAGES)})")
            continue
        for number, bracket, name in includes(path):
            if bracket == "<":
                if re.match(r"vtk[A-Z]", name):
                    problems.append(f"{where}:{number}: Core includes VTK <{name}>")
                continue
            target = name.split("/")[0]
            if "/" not in name or target not in STAGES:
                problems.append(f'{where}:{number}: "{name}" is not written from Core\'s root '
                                f'(stage/Name.h)')
            elif not os.path.isfile(os.path.join(core, name)):
                problems.append(f'{where}:{number}: "{name}" names no file of Core')
            elif STAGES.index(target) > STAGES.index(stage):
                problems.append(f'{where}:{number}: {stage}/ includes the later stage '
                                f'"{name}"')
    return problems


def check_modules(root):
    headers = {}
    for module in MODULES:
        for path in sources(os.path.join(root, module)):
            if path.endswith(".h"):
                headers[os.path.basename(path)] = module
    problems = []
    for module, allowed in MODULES.items():
        for path in sources(os.path.join(root, module)):
            for number, _, name in includes(path):
                owner = headers.get(os.path.basename(name))
                if owner and owner not in allowed:
                    problems.append(f"{os.path.relpath(path, root)}:{number}: {module}/ "
                                    f"includes {owner}/{os.path.basename(name)}")
    return problems


def check(root):
    return check_core(root) + check_modules(root)


def self_test():
    """The checker finds each kind of violation in a small tree made for it."""
    files = {
        "Core/geometry/A.h": '#include "math/M.h"\n',
        "Core/math/M.h": "",
        "Core/scene/S.h": '#include "cover/C.h"\n',          # later stage
        "Core/cover/C.h": '#include "M.h"\n#include <vtkObject.h>\n',  # not rooted; VTK
        "Core/cover/D.h": '#include "cover/Missing.h"\n',    # no such file
        "Core/distributed/P.h": '#include "render/R.h"\n',   # allowed: the last stage
        "Core/render/R.h": '#include "distributed/P.h"\n',   # a stage includes distributed/
        "Common/vtkBridge.h": '#include "vtkReader.h"\n',     # Common -> Readers
        "Readers/vtkReader.h": '#include "vtkBridge.h"\n',    # allowed
        "Filters/vtkFilter.cxx": '#include "vtkReader.h"\n',  # Filters -> Readers
        "Filters/vtkFilter2.cxx": '#include "vtkPFilter.h"\n',  # Filters -> Parallel
        "Parallel/vtkPFilter.h": '#include "vtkFilter.h"\n',  # allowed (no such header here)
        "Views/vtkView.cxx": '#include "vtkPFilter.h"\n',     # Views -> Parallel
    }
    with tempfile.TemporaryDirectory() as root:
        for name, text in files.items():
            os.makedirs(os.path.dirname(os.path.join(root, name)), exist_ok=True)
            with open(os.path.join(root, name), "w", encoding="utf-8") as out:
                out.write(text)
        found = check(root)
    expected = ["Core/scene/S.h:1", "Core/cover/C.h:1", "Core/cover/C.h:2", "Core/cover/D.h:1",
                "Core/render/R.h:1", "Common/vtkBridge.h:1", "Filters/vtkFilter.cxx:1",
                "Filters/vtkFilter2.cxx:1", "Views/vtkView.cxx:1"]
    missing = [e for e in expected if not any(p.startswith(e + ":") for p in found)]
    if missing or len(found) != len(expected):
        print("self-test failed: expected violations at", expected, "found", found)
        return 1
    print(f"self-test: all {len(expected)} planted violations found")
    return 0


def main(argv):
    if argv[1:] == ["--self-test"]:
        return self_test()
    root = argv[1] if len(argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "..")
    problems = check(os.path.abspath(root))
    for problem in problems:
        print(problem)
    if not problems:
        print("includes point one way: Core's stages in order "
              f"({' < '.join(STAGES)}); Common < Readers, Filters < Parallel, Views < Apps")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
