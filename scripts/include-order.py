#!/usr/bin/python3
"""Checks that no source file of src/ includes a header of a folder above its own.

The order of the folders is the one written in cmake/layers.cmake: the order of its pkm_layer() calls and of
the folders within each (pkm_layer(<target> <alias> <folder>...)). A file of src/F/ (or of a subfolder of F)
may include "G/..." only when G is F or comes before F. A folder of src/ that no pkm_layer() names is an
error too, so that a new folder takes its place in the order before it is used. apps/, python/, linuxcnc/,
tests/ and bench/ stand above the library and may include any of it.

usage: scripts/include-order.py [--matrix]
  --matrix: also print the include matrix (includes per pair of folders, rows including columns), the table of
  docs/ARCHITECTURE.md.
"""
import argparse
import collections
import pathlib
import re
import sys

REPO = pathlib.Path(__file__).resolve().parent.parent
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"/]+)/[^"]+"', re.MULTILINE)
LAYER_CALL = re.compile(r"^pkm_layer\(([^)]*)\)", re.MULTILINE)


def folder_order():
    """The top-level folders of src/ in their order, and the target each belongs to."""
    text = (REPO / "cmake" / "layers.cmake").read_text()
    order, target_of = [], {}
    for call in LAYER_CALL.finditer(text):
        words = call.group(1).split()
        if not words or words[0].startswith("$"):  # the function's own definition
            continue
        target, folders = words[0], words[2:]
        for folder in folders:
            top = folder.split("/")[0]
            if top not in target_of:
                order.append(top)
                target_of[top] = target
    return order, target_of


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--matrix", action="store_true")
    args = parser.parse_args()
    order, target_of = folder_order()
    rank = {folder: i for i, folder in enumerate(order)}
    src = REPO / "src"
    problems = []
    for folder in sorted(p.name for p in src.iterdir() if p.is_dir()):
        if folder not in rank:
            problems.append(f"src/{folder}/: not in any pkm_layer() of cmake/layers.cmake")
    matrix = collections.Counter()
    for path in sorted(src.rglob("*")):
        if path.suffix not in (".hpp", ".cpp", ".h"):
            continue
        own = path.relative_to(src).parts[0]
        if own not in rank:
            continue
        text = path.read_text(errors="replace")
        for match in INCLUDE.finditer(text):
            other = match.group(1)
            if other not in rank:
                continue  # a library's header ("nlohmann/json.hpp" is in <>, but be lenient)
            if other != own:
                matrix[(own, other)] += 1
            if rank[other] > rank[own]:
                line = text.count("\n", 0, match.start()) + 1
                problems.append(f"{path.relative_to(REPO)}:{line}: includes \"{other}/\" "
                                f"({target_of[other]}), above {own}/ ({target_of[own]}) in cmake/layers.cmake")
    if args.matrix:
        used = [f for f in order if any(matrix[(f, g)] or matrix[(g, f)] for g in order)]
        print("| includes → | " + " | ".join(used) + " |")
        print("|---|" + "---|" * len(used))
        for row in used:
            cells = [str(matrix[(row, col)]) if matrix[(row, col)] else ("·" if row != col else "=")
                     for col in used]
            print(f"| {row} | " + " | ".join(cells) + " |")
    for problem in problems:
        print(problem, file=sys.stderr)
    if problems:
        print(f"include-order: {len(problems)} include(s) against the order of cmake/layers.cmake", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
