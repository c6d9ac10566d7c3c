#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Checks that every header opens with its contract in at most MAX_LINES lines (issue 40).

A header's opening comment (the block comment or the run of // lines after the licence line)
says what the unit is for, the paper section it implements and what it promises: a reader
decides from it whether to read on. Measurements, alternatives tried and their history belong in
Documentation/notes/ (dated notes), which the comment may point to; a contract that does not fit
is a unit doing too much.

Usage: check_header_contract.py [ROOT]    (ROOT: the checkout, default: this file's ../..)
       check_header_contract.py --self-test
Exits 1 if any header's opening comment is longer, or if a header has none."""
import os
import sys

MAX_LINES = 60
FOLDERS = ["Core", "Common", "Readers", "Filters", "Parallel", "Views", "Apps"]


def opening_comment_lines(text):
    """The number of lines of the first comment of a header, the licence line not counted;
    None if the header does not open with a comment."""
    lines = text.splitlines()
    i = 0
    if i < len(lines) and lines[i].startswith("// SPDX-License-Identifier"):
        i += 1
    while i < len(lines) and not lines[i].strip():
        i += 1
    if i >= len(lines):
        return None
    first = lines[i].lstrip()
    if first.startswith("/*"):
        for j in range(i, len(lines)):
            if "*/" in lines[j]:
                return j - i + 1
        return len(lines) - i
    if first.startswith("//"):
        j = i
        while j < len(lines) and lines[j].lstrip().startswith("//"):
            j += 1
        return j - i
    return None


def headers(root):
    for folder in FOLDERS:
        for parent, _, names in os.walk(os.path.join(root, folder)):
            for name in sorted(names):
                if name.endswith(".h"):
                    yield os.path.join(parent, name)


def problems(root):
    found = []
    for path in sorted(headers(root)):
        with open(path, encoding="utf-8") as stream:
            count = opening_comment_lines(stream.read())
        name = os.path.relpath(path, root)
        if count is None:
            found.append(f"{name}: opens with no comment stating its contract")
        elif count > MAX_LINES:
            found.append(f"{name}: opening comment of {count} lines (at most {MAX_LINES}: move "
                         "measurements and variants to a dated note in Documentation/notes/)")
    return found


def self_test():
    """The check finds what it is there to find: a long block, a long run of // lines, a header
    without a comment; and passes a contract of exactly MAX_LINES lines."""
    licence = "// SPDX-License-Identifier: BSD-3-Clause\n"
    block = lambda n: "/**\n" + " * line\n" * (n - 2) + " */\n"  # noqa: E731
    slashes = lambda n: "// line\n" * n  # noqa: E731
    cases = [
        (licence + block(MAX_LINES) + "#pragma once\n", MAX_LINES),
        (licence + block(MAX_LINES + 1) + "#pragma once\n", MAX_LINES + 1),
        (licence + "\n" + slashes(MAX_LINES + 3) + "#pragma once\n", MAX_LINES + 3),
        ("/** one */\n#pragma once\n", 1),
        (licence + "#pragma once\n", None),
    ]
    failed = 0
    for text, expected in cases:
        got = opening_comment_lines(text)
        if got != expected:
            print(f"self-test: expected {expected}, got {got} for {text[:60]!r}")
            failed += 1
    print("self-test passed" if not failed else f"self-test: {failed} case(s) failed")
    return 1 if failed else 0


def main(argv):
    if len(argv) > 1 and argv[1] == "--self-test":
        return self_test()
    root = os.path.abspath(argv[1] if len(argv) > 1 else
                           os.path.join(os.path.dirname(__file__), "..", ".."))
    found = problems(root)
    for line in found:
        print(line)
    if found:
        print(f"{len(found)} header(s) do not open with a contract of at most {MAX_LINES} lines")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
