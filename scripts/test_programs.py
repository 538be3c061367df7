#!/usr/bin/env python3
"""Prints the programs in BUILD/bin that the CTest tests with a label matching LABELS run, one
name per line, read from the build tree's CTestTestfile.cmake files (configured, not built:
`ctest --show-only` names a test's program only once it exists). scripts/sanitize.sh builds
these targets alone.

Usage: test_programs.py BUILD LABELS   (LABELS: a regular expression, e.g. 'unit|small')"""
import os
import re
import sys


def tests(build):
    """(name, words of its command, labels) of every test."""
    commands, labels = {}, {}
    for root, _, files in os.walk(build):
        if "CTestTestfile.cmake" not in files:
            continue
        for line in open(os.path.join(root, "CTestTestfile.cmake"), encoding="utf-8"):
            name = re.match(r"(add_test|set_tests_properties)\(\[=\[(.*?)\]=\]\s*(.*)", line)
            if not name:
                continue
            kind, test, rest = name.groups()
            if kind == "add_test":
                commands[test] = re.findall(r'"([^"]*)"', rest)
            else:
                found = re.search(r'LABELS "([^"]*)"', rest)
                labels[test] = found.group(1).split(";") if found else []
    return [(t, commands[t], labels.get(t, [])) for t in commands]


def main(build, pattern):
    binary = os.path.join(os.path.abspath(build), "bin") + os.sep
    wanted = re.compile(pattern)
    names = {os.path.basename(word) for _, words, labels in tests(build) if any(wanted.fullmatch(l) for l in labels)
             for word in words if word.startswith(binary)}
    if not names:
        sys.exit("test_programs.py: no test with a label matching %r runs a program of %s" % (pattern, binary))
    print("\n".join(sorted(names)))


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
