#!/usr/bin/env python3
"""Checks the engine's layout rules (docs/design.md, "Layout of the engine"): which folder of
engine/src may include which (each folder's README.md says it, in its "May include:" line, and
docs/design.md's table must say the same), that the public headers include no internal one, and
that every test that includes an internal header is registered as a test of internals
(dtlab_internal_test).

Usage: tools/check_engine_layout.py [REPO-ROOT]   (exit 0: every rule holds; 1: a list of breaks)
"""
import os
import re
import sys

INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def includes(path):
    with open(path, encoding="utf-8") as f:
        return INCLUDE.findall(f.read())


def may_include(text):
    """The folder names of a "May include: a, b." statement (nothing: none)."""
    match = re.search(r"May include: ([^\n]*)", text)
    if match is None:
        return None
    return set(re.findall(r"\b(support|mesh|location|insertion|validate|repair|methods|output|driver)\b",
                          match.group(1).split("nothing of the engine")[0]))


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..")
    src = os.path.join(root, "engine", "src")
    broken = []
    folders = sorted(d for d in os.listdir(src) if os.path.isdir(os.path.join(src, d)))
    ALLOWED = {}
    for folder in folders:
        readme = os.path.join(src, folder, "README.md")
        rule = may_include(open(readme, encoding="utf-8").read()) if os.path.exists(readme) else None
        if rule is None:
            broken.append(f"engine/src/{folder}/README.md: no \"May include:\" line")
            continue
        ALLOWED[folder] = rule
    # docs/design.md's layout table: `src/FOLDER/` | contract | may include
    with open(os.path.join(root, "docs", "design.md"), encoding="utf-8") as f:
        for line in f:
            row = re.match(r"\| `src/(\w+)/` \|.*\| ([^|]*) \|\s*$", line)
            if row and row.group(1) in ALLOWED:
                cell = row.group(2)
                said = set() if "nothing" in cell else set(
                    re.findall(r"\b(support|mesh|location|insertion|validate|repair|methods|output)\b", cell))
                if cell.strip() == "everything":
                    said = set(ALLOWED) - {row.group(1)}
                if said != ALLOWED[row.group(1)]:
                    broken.append(f"docs/design.md: src/{row.group(1)}/ may include {sorted(said)}, "
                                  f"its README says {sorted(ALLOWED[row.group(1)])}")
    for folder in folders:
        if folder not in ALLOWED:
            broken.append(f"engine/src/{folder}/: a folder without a rule in ALLOWED")
            continue
        for name in sorted(os.listdir(os.path.join(src, folder))):
            if not name.endswith((".cpp", ".hpp")):
                continue
            for inc in includes(os.path.join(src, folder, name)):
                top = inc.split("/")[0]
                if top == "dtlab" or top == folder:
                    continue
                if top not in ALLOWED[folder]:
                    broken.append(f"engine/src/{folder}/{name} includes {inc}")
    loose = [n for n in os.listdir(src) if os.path.isfile(os.path.join(src, n))]
    broken += [f"engine/src/{n}: a file outside the folders" for n in loose]
    public = os.path.join(root, "engine", "include", "dtlab", "engine")
    for name in sorted(os.listdir(public)):
        for inc in includes(os.path.join(public, name)):
            if not inc.startswith("dtlab/"):
                broken.append(f"public header {name} includes internal {inc}")
    # Tests that include engine/src headers must be tests of internals.
    with open(os.path.join(root, "tests", "CMakeLists.txt"), encoding="utf-8") as f:
        cmake = f.read()
    internal_tests = set(re.findall(r"dtlab_internal_test\((\w+)", cmake))
    for tests_dir in ("tests", "property_tests", "fuzz"):
        for name in sorted(os.listdir(os.path.join(root, tests_dir))):
            if not name.endswith(".cpp"):
                continue
            internal = [i for i in includes(os.path.join(root, tests_dir, name))
                        if i.split("/")[0] in folders]
            if internal and (tests_dir != "tests" or name[:-4] not in internal_tests):
                broken.append(f"{tests_dir}/{name} includes {internal[0]} but is no "
                              "dtlab_internal_test")
    for line in broken:
        print(line)
    print(f"engine layout: {len(broken)} rule(s) broken")
    return 1 if broken else 0


if __name__ == "__main__":
    sys.exit(main())
