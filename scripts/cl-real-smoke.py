#!/usr/bin/python3
"""Reads real CL files written by CAM systems with `pkm interpret` and checks what tests/program/cl_real_sources.tsv
says of each: recognised as its dialect, read without an arc-direction warning (or refused, where the file is
refused for a stated reason). The files come from public repositories whose licences do not let pkm ship them;
fetch them (repository, commit and path are in the table) into a folder under the names of its first column.

    scripts/cl-real-smoke.py FOLDER [--pkm build/pkm]

Prints one line per file that does not do what is expected and a summary; exits 1 if any does not.
"""
import argparse
import csv
import pathlib
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
NAMES = {"nx": "NX CLSF", "creo": "Pro/CLfile (Creo)", "solidworks": "SolidWorks CAM / CAMWorks APT",
         "catia": "CATIA APT", "apt": "APT CL data"}


def sources():
    with open(ROOT / "tests/program/cl_real_sources.tsv", newline="") as table:
        lines = (line for line in table if not line.startswith("#"))
        yield from csv.DictReader(lines, delimiter="\t")


def check(pkm, folder, row):
    """None when the file does what the table expects, else what went wrong."""
    path = folder / row["file"]
    if not path.is_file():
        return f"missing: fetch {row['repository']}@{row['commit'][:10]}:{row['path']}"
    run = subprocess.run([pkm, "interpret", "--count", str(path)], capture_output=True, text=True)
    if row["expect"].startswith("refused"):
        reason = row["expect"].split(":", 1)[1].strip()
        if run.returncode == 0 or reason not in run.stderr:
            return f"expected a refusal ({reason}), got: {(run.stdout + run.stderr).strip()[:200]}"
        return None
    if run.returncode != 0:
        return f"refused: {run.stderr.strip()[:300]}"
    if f"({NAMES[row['dialect']]})" not in run.stdout:
        return f"not recognised as {NAMES[row['dialect']]}: {run.stdout.strip()}"
    if "start against" in run.stderr:
        return f"arc warning: {run.stderr.strip()[:300]}"
    return None


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("folder", type=pathlib.Path)
    parser.add_argument("--pkm", default=str(ROOT / "build/pkm"))
    args = parser.parse_args()
    rows = list(sources())
    failures = 0
    for row in rows:
        problem = check(args.pkm, args.folder, row)
        if problem:
            failures += 1
            print(f"{row['file']}: {problem}")
    by_dialect = {}
    for row in rows:
        by_dialect[row["dialect"]] = by_dialect.get(row["dialect"], 0) + 1
    counts = ", ".join(f"{n} {NAMES[d]}" for d, n in sorted(by_dialect.items()))
    print(f"{len(rows)} real CL files ({counts}): {len(rows) - failures} as expected")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
