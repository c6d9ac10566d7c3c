#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Checks that the C++ sources follow the repository's .clang-format (clang-format --dry-run
-Werror): a file that drifts is one line naming it, with clang-format's first complaint.

Usage: check_format.py CLANG_FORMAT [ROOT]    (ROOT: the checkout, default: this file's ../..)
Exits 1 if any file drifts."""
import os
import subprocess
import sys

FOLDERS = ["Core", "Common", "Readers", "Filters", "Parallel", "Views", "Apps", "Testing",
           "paraview_plugin"]
SUFFIXES = (".h", ".cxx", ".cpp", ".hpp")


def sources(root):
    for folder in FOLDERS:
        for parent, _, names in os.walk(os.path.join(root, folder)):
            for name in sorted(names):
                if name.endswith(SUFFIXES):
                    yield os.path.join(parent, name)


def main(argv):
    clang_format = argv[1]
    root = os.path.abspath(argv[2] if len(argv) > 2 else
                           os.path.join(os.path.dirname(__file__), "..", ".."))
    files = sorted(sources(root))
    drifting = []
    for path in files:
        result = subprocess.run([clang_format, "--dry-run", "-Werror", path],
                                capture_output=True, text=True, cwd=root)
        if result.returncode != 0:
            first = next((line for line in result.stderr.splitlines() if "error" in line), "")
            drifting.append(f"{os.path.relpath(path, root)}: not formatted ({first.strip()})")
    for line in drifting:
        print(line)
    if drifting:
        print(f"{len(drifting)} of {len(files)} files drift from .clang-format: run "
              "clang-format -i on them")
        return 1
    print(f"all {len(files)} C++ files follow .clang-format")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
