#!/usr/bin/python3
"""Runs every command of the documentation as a reader would, after installing pkm.

The commands are the lines of the ```sh blocks of README.md and docs/*.md (synopses with [options] and
placeholders, and printed output, are in ```text blocks). The blocks of one document run in order in a
scratch folder of their own, which holds the project's examples/ and linuxcnc/ as the reader's clone does,
with the installed pkm first on PATH and the installed Python module importable. Every command must exit 0.

The few commands that cannot run here are left out by ALLOWED below, each with the reason; any other
command that fails fails the test, naming the document, its line and the command's output.

usage: scripts/doc-commands.py --bin DIR --python-site DIR [--only DOC] [--list]
"""
import argparse
import os
import pathlib
import re
import subprocess
import sys
import tempfile
import time

REPO = pathlib.Path(__file__).resolve().parent.parent

# Commands (by how they start) that this test does not run, and why.
ALLOWED = [
    (re.compile(r"^make( |$)"), "the set-up and build commands: CI runs them (make test, make package)"),
    (re.compile(r"^sudo "), "installs into the system: the package test installs the package in a root of its own"),
    (re.compile(r"^cmake "), "builds and installs from source: the package test and make consumer do"),
    (re.compile(r"(^|\s)linuxcnc \S+\.ini"),
     "starts LinuxCNC: its real-time modules as root or a display (make test runs the README's headless run)"),
    (re.compile(r"^(\S+=\S+ )*dask "), "starts a Dask cluster's worker: needs the cluster"),
    (re.compile(r"^man "), "opens the pager: the package test checks that the man page is installed"),
    (re.compile(r"^(grep |python3 scripts/include-order\.py)"), "checks of the source tree's layering, not of an installed pkm"),
    (re.compile(r"^python3 -m venv |^~/pkm-env/bin/"),
     "pip install . from the source tree into a virtual environment: the package test does it"),
]


def blocks_of(path):
    """(first line number, [(line number, command)]) of each ```sh block, continuation lines joined."""
    lines = path.read_text(encoding="utf-8").split("\n")
    blocks, inside, commands, pending, start = [], False, [], None, 0
    for number, line in enumerate(lines, start=1):
        if line.strip().startswith("```"):
            if inside:
                if commands:
                    blocks.append((start, commands))
                inside, commands, pending = False, [], None
            elif line.strip() == "```sh":
                inside, start = True, number + 1
            continue
        if not inside or (pending is None and (not line.strip() or line.strip().startswith("#"))):
            continue
        text = line.rstrip()
        if pending is not None:
            pending = (pending[0], pending[1] + " " + text.strip())
        else:
            pending = (number, text.strip())
        if pending[1].endswith("\\"):
            pending = (pending[0], pending[1][:-1].rstrip())
            continue
        commands.append(pending)
        pending = None
    return blocks


def allowed_reason(command):
    for pattern, reason in ALLOWED:
        if pattern.search(command):
            return reason
    return None


def documents(only):
    paths = [REPO / "README.md"] + sorted((REPO / "docs").glob("*.md"))
    return [p for p in paths if not only or p.name == only]


def scratch_folder(parent, bin_dir, site):
    """A reader's clone: examples/ and linuxcnc/, and build/pkm and build/python as `make run` and
    `make python` leave them, here the installed ones."""
    folder = pathlib.Path(tempfile.mkdtemp(prefix="doc-", dir=parent))
    for name in ("examples", "linuxcnc"):
        (folder / name).symlink_to(REPO / name)
    (folder / "build").mkdir()
    (folder / "build" / "pkm").symlink_to(pathlib.Path(bin_dir).resolve() / "pkm")
    (folder / "build" / "python").symlink_to(pathlib.Path(site).resolve())
    (folder / "home").mkdir()
    return folder


def run_document(path, env, parent, args):
    """Runs the document's commands; returns (ran, skipped, failures)."""
    folder = scratch_folder(parent, args.bin, args.python_site)
    timeout_s = args.timeout
    doc_env = dict(env, HOME=str(folder / "home"))
    ran, skipped, failures = 0, 0, []
    for _, commands in blocks_of(path):
        for number, command in commands:
            if allowed_reason(command):
                skipped += 1
                continue
            started = time.monotonic()
            try:
                done = subprocess.run(["bash", "-o", "pipefail", "-c", command], cwd=folder, env=doc_env,
                                      capture_output=True, text=True, timeout=timeout_s)
                code, output = done.returncode, (done.stdout + done.stderr)
            except subprocess.TimeoutExpired:
                code, output = "timeout", f"still running after {timeout_s} s"
            ran += 1
            took = time.monotonic() - started
            where = f"{path.relative_to(REPO)}:{number}"
            if code != 0:
                tail = "\n".join(output.strip().split("\n")[-12:])
                failures.append(f"{where}: exit {code}: {command}\n{tail}")
            elif took > 30:
                print(f"doc-commands: note: {where} took {took:.0f} s: {command}")
    return ran, skipped, failures


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--bin", help="the folder of the installed pkm")
    parser.add_argument("--python-site", help="the folder the Python module pkm is installed in")
    parser.add_argument("--only", help="one document, by its file name")
    parser.add_argument("--list", action="store_true", help="print the commands, run nothing")
    parser.add_argument("--timeout", type=float, default=600.0, help="seconds per command")
    args = parser.parse_args()
    if args.list:
        for path in documents(args.only):
            for _, commands in blocks_of(path):
                for number, command in commands:
                    reason = allowed_reason(command)
                    print(f"{path.relative_to(REPO)}:{number}: {'SKIP ' if reason else ''}{command}")
        return 0
    if not args.bin or not args.python_site:
        parser.error("--bin and --python-site are needed to run the commands")
    env = dict(os.environ)
    # Debian's python3 and tools, as on a reader's machine (not a virtual environment's).
    env["PATH"] = f"{os.path.abspath(args.bin)}:/usr/bin:/bin"
    env["PYTHONPATH"] = os.path.abspath(args.python_site)
    total_ran, total_skipped, failures = 0, 0, []
    with tempfile.TemporaryDirectory(prefix="pkm-doc-commands-") as parent:
        for path in documents(args.only):
            ran, skipped, failed = run_document(path, env, parent, args)
            total_ran, total_skipped = total_ran + ran, total_skipped + skipped
            failures += failed
    for failure in failures:
        print(f"doc-commands: FAILED {failure}\n", file=sys.stderr)
    print(f"doc-commands: {total_ran - len(failures)} of {total_ran} documented commands ran as written "
          f"({total_skipped} left out: set-up, system installs, LinuxCNC's display, a Dask cluster)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
