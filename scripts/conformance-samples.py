#!/usr/bin/python3
"""pkm's G-code interpreter against LinuxCNC's rs274 on every sample program LinuxCNC ships.

Finds every .ngc file the Debian package linuxcnc-uspace installs (dpkg -L) and the project's own
tests/program/conformance/**/*.ngc. Each runs under LinuxCNC's standalone interpreter

    rs274 -g -b -t TOOLS_INCH.tbl -i SAMPLES.ini PROGRAM      (batch, block delete on)

where the INI's [RS274NGC] SUBROUTINE_PATH is the program's folder, the subroutine folders of its sample
configuration (nc_subroutines, remap_subs, macros, ...) and the package's subroutine libraries (ngcgui_lib,
remap-subroutines, ...), and under

    pkm interpret --json --tool-table TOOLS_MM.tbl --subroutine-path THE_SAME_FOLDERS PROGRAM

with the same tool table in mm (rs274 standalone reads its table in inches, its machine units).

A program rs274 runs to its end (exit 0: PROGRAM_END, or a file closed by %) is compared call by call with
pkm's moves: the kind (rapid, line, arc, dwell; rs274's NURBS_FEED, STRAIGHT_PROBE, RIGID_TAP are kinds pkm
has not), the end point in the program's coordinates (pkm's program_end) to 1e-4 mm plus half of rs274's last
printed digit (4 decimals in the program's units: inches after USE_LENGTH_UNITS(CANON_UNITS_INCHES)), the arc
centre, direction, turns and plane, the feed of feed moves, the dwell time, and at every move the G5x and G92
offsets, XY rotation and tool length offset rs274 last announced; then the sequence of tool changes. A program
agrees only if everything matches.

Prints "N programs: rs274 runs R, pkm agrees A". Exits 1 when a program rs274 runs disagrees and is not listed
in tests/program/conformance/known.txt ("path<whitespace>reason" a line, # comments), or when a listed
program now agrees or no longer needs listing (a stale entry). Standard library only; Debian's /usr/bin/python3.

--self-test compares rs274 with its own answer put in the form of pkm's JSON: every program must agree, which
checks this script's bookkeeping (units, planes, offsets, tool lengths) whatever pkm's interpreter does.

Usage: scripts/conformance-samples.py [--pkm build/pkm] [--only SUBSTRING] [--jobs N] [--verbose]
                                      [--list-failures] [--rs274 rs274] [--self-test]
"""
import argparse
import concurrent.futures
import json
import math
import os
import re
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
CONFORMANCE = ROOT / "tests" / "program" / "conformance"
KNOWN = CONFORMANCE / "known.txt"
PACKAGE = "linuxcnc-uspace"
NCFILES = Path("/usr/share/linuxcnc/ncfiles")
# The package's subroutine libraries: what a LinuxCNC configuration puts on its SUBROUTINE_PATH.
LIBRARIES = ["ngcgui_lib", "ngcgui_lib/utilitysubs", "remap-subroutines", "remap_lib/common_nc_subs",
             "gladevcp_lib", "macros/mill"]
# Folders of a sample configuration that hold its subroutines, next to its nc_files.
CONFIG_SUBFOLDERS = ["nc_subroutines", "remap_subs", "macros", "subroutines", "nc_files"]
MAX_SUBROUTINE_DIRS = 10  # LinuxCNC's MAX_SUB_DIRS: later entries would be ignored by rs274
RS274_TIMEOUT_S = 60
PKM_TIMEOUT_S = 120
MOTIONS = {"STRAIGHT_TRAVERSE": "rapid", "STRAIGHT_FEED": "line", "ARC_FEED": "arc", "DWELL": "dwell",
           "NURBS_FEED": "nurbs", "SPLINE_FEED": "spline", "STRAIGHT_PROBE": "probe", "RIGID_TAP": "rigid_tap"}
# rs274's plane -> (first, second, normal) axis indices of its ARC_FEED arguments, and pkm's plane name.
PLANES = {"CANON_PLANE_XY": ((0, 1, 2), "xy"), "CANON_PLANE_XZ": ((2, 0, 1), "zx"),
          "CANON_PLANE_YZ": ((1, 2, 0), "yz")}
ANGLE_TOLERANCE_DEG = 1.5e-4
# The suite's tool table (tests/program/conformance/tools.tbl, inches) and more tools for the samples.
TOOLS = [(1, 1.0, 0.25), (2, 2.5, 0.5), (3, -0.5, 0.125), (4, 0.125, 0.0625)] + \
        [(n, 0.5 + 0.05 * n, 0.125) for n in range(5, 100)]


# --- finding programs ----------------------------------------------------------------------------------

def package_programs():
    try:
        listed = subprocess.run(["dpkg", "-L", PACKAGE], capture_output=True, text=True, check=True).stdout
    except (OSError, subprocess.CalledProcessError):
        print(f"conformance-samples: dpkg -L {PACKAGE} failed: is LinuxCNC installed?", file=sys.stderr)
        return []
    return sorted(Path(p) for p in listed.splitlines() if p.endswith(".ngc") and Path(p).is_file())


def project_programs():
    return sorted(CONFORMANCE.rglob("*.ngc"))


def shown(path):
    """The name a program has in messages and in known.txt: relative to the repository, or absolute."""
    try:
        return str(path.resolve().relative_to(ROOT))
    except ValueError:
        return str(path)


def subroutine_path(program):
    """The program's folder, its configuration's subroutine folders, then the package's libraries."""
    folders = [program.parent]
    for config in (program.parent, program.parent.parent):
        folders += [config / sub for sub in CONFIG_SUBFOLDERS]
    folders += [NCFILES / library for library in LIBRARIES]
    unique = []
    for folder in folders:
        if folder.is_dir() and folder.resolve() not in unique:
            unique.append(folder.resolve())
    return [str(f) for f in unique[:MAX_SUBROUTINE_DIRS]]


# --- running the two interpreters ----------------------------------------------------------------------

def write_tool_tables(folder):
    inch, mm = folder / "tools_inch.tbl", folder / "tools_mm.tbl"
    inch.write_text("".join(f"T{n} P{n} Z{z} D{d}\n" for n, z, d in TOOLS))
    mm.write_text("".join(f"T{n} P{n} Z{z * 25.4:.6f} D{d * 25.4:.6f}\n" for n, z, d in TOOLS))
    return inch, mm


def run_rs274(rs274, program, tools_inch, folders, scratch):
    """rs274's output and whether it ran the program to its end. It runs in a folder of its own: it reads
    (and may write) rs274ngc.var in its working directory, and LinuxCNC 2.9 keeps its tool table in a file
    mapped into memory, $HOME/.tool.mmap, which concurrent runs would share (and unlink under each other:
    SIGBUS, or another run's tools), so HOME is that folder too."""
    work = Path(tempfile.mkdtemp(dir=scratch))
    ini = work / "samples.ini"
    ini.write_text("[RS274NGC]\nSUBROUTINE_PATH = {}\n".format(":".join(folders)))
    try:
        done = subprocess.run([rs274, "-g", "-b", "-t", str(tools_inch), "-i", str(ini), str(program)],
                              stdin=subprocess.DEVNULL, capture_output=True, text=True, errors="replace",
                              cwd=work, env=dict(os.environ, HOME=str(work)), timeout=RS274_TIMEOUT_S)
    except subprocess.TimeoutExpired:
        return "", False, f"rs274 did not finish in {RS274_TIMEOUT_S} s"
    errors = [line for line in done.stderr.splitlines() if line.strip() and line.strip() != "executing"]
    ran = done.returncode == 0
    return done.stdout, ran, "" if ran else (errors[0] if errors else f"rs274 exit {done.returncode}")


def pkm_options(pkm):
    """Which of the program options this pkm knows (an older binary has no --subroutine-path)."""
    try:
        text = subprocess.run([pkm, "interpret", "--help"], capture_output=True, text=True).stdout
    except OSError:
        sys.exit(f"conformance-samples: cannot run {pkm} (build it: make build, or give --pkm)")
    return {"subroutine_path": "--subroutine-path" in text}


def run_pkm(pkm, known_options, program, tools_mm, folders):
    """pkm's program as {moves, events, files}, or an error message."""
    command = [pkm, "interpret", "--json", "--tool-table", str(tools_mm), str(program)]
    if known_options["subroutine_path"]:
        command += ["--subroutine-path", ":".join(folders)]
    try:
        done = subprocess.run(command, stdin=subprocess.DEVNULL, capture_output=True, text=True, errors="replace",
                              timeout=PKM_TIMEOUT_S)
    except subprocess.TimeoutExpired:
        return None, f"pkm did not finish in {PKM_TIMEOUT_S} s"
    if done.returncode != 0:
        return None, (done.stderr.strip().splitlines() or [f"pkm exit {done.returncode}"])[0]
    document = json.loads(done.stdout)
    if isinstance(document, list):  # a pkm before --json printed files and events: its moves alone
        document = {"moves": document, "events": [], "files": [str(program)]}
    return document, ""


# --- rs274's canonical calls ---------------------------------------------------------------------------

CALL = re.compile(r"^\s*\d+\s+N\S*\s+([A-Z_0-9]+)\((.*)\)\s*$")


def numbers(text):
    return [float(v) for v in re.split(r"[,\s]+", text.strip()) if v]


class Rs274State:
    """What rs274 announced before a motion, converted to mm: units, plane, feed, offsets, tool."""

    def __init__(self):
        self.scale = 1.0
        self.plane = "CANON_PLANE_XY"
        self.feed_raw, self.feed_scale, self.feed_pending = 0.0, 1.0, False
        self.g5x_index, self.g5x, self.g92 = 1, [0.0] * 6, [0.0] * 6
        self.rotation_deg, self.tool_length_mm = 0.0, 0.0

    def pose_mm(self, values):
        return [v * self.scale for v in values[:3]] + list(values[3:6])

    def apply(self, name, args):
        """Takes a non-motion call; returns a tool number for a tool change, else None."""
        if name == "USE_LENGTH_UNITS":
            self.scale = 25.4 if args.strip() == "CANON_UNITS_INCHES" else 1.0
        elif name == "SELECT_PLANE":
            self.plane = args.strip()
        elif name == "SET_FEED_RATE":
            self.feed_raw, self.feed_pending = float(args), True
        elif name == "SET_G5X_OFFSET":
            values = numbers(args)
            self.g5x_index, self.g5x = int(values[0]), self.pose_mm(values[1:7])
        elif name == "SET_G92_OFFSET":
            self.g92 = self.pose_mm(numbers(args)[:6])
        elif name == "SET_XY_ROTATION":
            self.rotation_deg = float(args)
        elif name == "USE_TOOL_LENGTH_OFFSET":
            self.tool_length_mm = numbers(args)[2] * self.scale
        elif name in ("CHANGE_TOOL", "CHANGE_TOOL_NUMBER"):
            return int(float(args))
        return None


def parse_rs274(text):
    """The motion calls, each with the state in effect, and the tool changes, in order."""
    state, motions, tools = Rs274State(), [], []
    for line in text.splitlines():
        match = CALL.match(line)
        if not match:
            continue
        name, args = match.groups()
        if name not in MOTIONS:
            tool = state.apply(name, args)
            if tool is not None:
                tools.append(tool)
            continue
        kind = MOTIONS[name]
        if state.feed_pending and kind in ("line", "arc", "probe"):  # the feed's units: those of its first move
            state.feed_scale, state.feed_pending = state.scale, False
        values = numbers(args) if kind in ("rapid", "line", "arc", "dwell", "probe") else []
        motions.append({"kind": kind, "text": line.strip(), "args": values, "scale": state.scale,
                        "plane": state.plane, "feed_mm_min": state.feed_raw * state.feed_scale,
                        "feed_scale": state.feed_scale, "g5x_index": state.g5x_index, "g5x": list(state.g5x),
                        "g92": list(state.g92), "rotation_deg": state.rotation_deg,
                        "tool_length_mm": state.tool_length_mm})
    return motions, tools


# --- comparing -----------------------------------------------------------------------------------------

def tolerance_mm(scale):
    return 1e-4 + 0.5e-4 * scale


def differs(ours, theirs, tolerance):
    return abs(ours - theirs) > tolerance


def program_end(move):
    return move.get("program_end", move["end"])


def arc_length(start, move):
    """XYZ length of pkm's arc (work coordinates), for inverse-time feeds."""
    centre, normal, end = move["center"], move["normal"], move["end"][:3]
    u = [s - c for s, c in zip(start, centre)]
    v = [e - c for e, c in zip(end, centre)]
    along = sum((e - s) * n for e, s, n in zip(end, start, normal))
    v = [vi - along * n for vi, n in zip(v, normal)]
    radius = math.sqrt(sum(x * x for x in u))
    cross = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
    angle = math.atan2(sum(c * n for c, n in zip(cross, normal)), sum(a * b for a, b in zip(u, v)))
    if angle <= 1e-12:
        angle += 2 * math.pi
    angle += 2 * math.pi * (move.get("turns", 1) - 1)
    return math.hypot(radius * angle, along)


def feed_difference(move, start, start_abc, theirs):
    if "feed_per_revolution_mm" in move:  # G95: rs274 prints the feed per revolution
        if differs(move["feed_per_revolution_mm"], theirs["feed_mm_min"], tolerance_mm(theirs["feed_scale"])):
            return f"feed {move['feed_per_revolution_mm']:.4f} mm/rev, rs274 {theirs['feed_mm_min']:.4f}"
        return ""
    if "inverse_time_per_min" not in move:
        if differs(move["feed_mm_min"], theirs["feed_mm_min"], tolerance_mm(theirs["feed_scale"])):
            return f"feed {move['feed_mm_min']:.4f} mm/min, rs274 {theirs['feed_mm_min']:.4f}"
        return ""
    # Inverse time: rs274 prints the equivalent speed, length x F (XYZ length, or the ABC angle without one).
    end = move["end"][:3]
    length = arc_length(start, move) if move["kind"] == "arc" else math.dist(end, start)
    scale = theirs["feed_scale"]
    if length < 1e-9:
        length, scale = math.dist(move["end"][3:6], start_abc), 1.0
    expected = theirs["feed_mm_min"] / theirs["feed_scale"] * scale
    if differs(length * move["inverse_time_per_min"], expected, tolerance_mm(scale)):
        return f"inverse-time feed {length * move['inverse_time_per_min']:.4f}, rs274 {expected:.4f}"
    return ""


def position_difference(move, theirs):
    """End point (and arc centre, direction, turns, plane) in program coordinates."""
    a, scale, tol = theirs["args"], theirs["scale"], tolerance_mm(theirs["scale"])
    end = program_end(move)
    if theirs["kind"] in ("rapid", "line"):
        for i, axis in enumerate("XYZ"):
            if differs(end[i], a[i] * scale, tol):
                return f"{axis} {end[i]:.4f} mm, rs274 {a[i] * scale:.4f}"
        angles = a[3:6]
    else:  # ARC_FEED(first_end, second_end, first_centre, second_centre, rotation, normal_end, a, b, c)
        (first, second, normal), plane = PLANES.get(theirs["plane"], PLANES["CANON_PLANE_XY"])
        centre = move.get("program_center", move.get("center"))
        checks = [("first end", end[first], a[0]), ("second end", end[second], a[1]),
                  ("first centre", centre[first], a[2]), ("second centre", centre[second], a[3]),
                  ("normal-axis end", end[normal], a[5])]
        for what, ours, printed in checks:
            if differs(ours, printed * scale, tol):
                return f"arc {what} {ours:.4f} mm, rs274 {printed * scale:.4f}"
        if move.get("plane", plane) != plane:
            return f"plane {move.get('plane')}, rs274 {plane}"
        rotation = int(round(a[4]))
        expected_normal = [0.0, 0.0, 0.0]
        expected_normal[normal] = 1.0 if rotation > 0 else -1.0
        if move.get("turns") != abs(rotation) or any(differs(x, y, 1e-9) for x, y in
                                                     zip(move["normal"], expected_normal)):
            return f"arc turns {move.get('turns')} normal {move['normal']}, rs274 rotation {rotation}"
        angles = a[6:9]
    for i, axis in enumerate("ABC"):
        if differs(end[3 + i], angles[i], ANGLE_TOLERANCE_DEG):
            return f"{axis} {end[3 + i]:.4f} deg, rs274 {angles[i]:.4f}"
    return ""


def frame_difference(move, theirs):
    """The offsets and tool length in effect, as rs274 last announced them."""
    frame = move.get("frame", {})
    tol = tolerance_mm(theirs["scale"])
    for what, key in (("G5x offset", "g5x"), ("G92 offset", "g92")):
        ours = frame.get(key, [0.0] * 6)
        for i, axis in enumerate("XYZABC"):
            if differs(ours[i], theirs[key][i], tol if i < 3 else ANGLE_TOLERANCE_DEG):
                return f"{what} {axis} {ours[i]:.4f}, rs274 {theirs[key][i]:.4f}"
    if frame.get("system", 1) != theirs["g5x_index"]:
        return f"coordinate system {frame.get('system', 1)}, rs274 {theirs['g5x_index']}"
    if differs(frame.get("xy_rotation_deg", 0.0), theirs["rotation_deg"], ANGLE_TOLERANCE_DEG):
        return f"XY rotation {frame.get('xy_rotation_deg', 0.0)}, rs274 {theirs['rotation_deg']}"
    if differs(move.get("tool_length_mm", 0.0), theirs["tool_length_mm"], tol):
        return f"tool length {move.get('tool_length_mm', 0.0):.4f} mm, rs274 {theirs['tool_length_mm']:.4f}"
    return ""


def move_difference(move, start, start_abc, theirs):
    if move.get("probe") and theirs["kind"] == "probe":  # G38.x: a straight move to the target in pkm
        theirs = dict(theirs, kind="line", args=theirs["args"][:6])
    if move["kind"] != theirs["kind"]:
        return f"kind {move['kind']}, rs274 {theirs['kind']}"
    expected_args = {"rapid": 6, "line": 6, "arc": 9, "dwell": 1}.get(theirs["kind"])
    if expected_args is None:  # NURBS, probe, rigid tap: pkm has no such move, so the kinds differed already
        return ""
    if len(theirs["args"]) < expected_args:
        return f"rs274's call has {len(theirs['args'])} numbers, expected {expected_args}"
    if theirs["kind"] == "dwell":
        if differs(move.get("dwell_s", 0.0), theirs["args"][0], 0.6e-4):
            return f"dwell {move.get('dwell_s', 0.0)} s, rs274 {theirs['args'][0]}"
        return frame_difference(move, theirs)
    difference = position_difference(move, theirs) or frame_difference(move, theirs)
    if not difference and theirs["kind"] in ("line", "arc"):
        difference = feed_difference(move, start, start_abc, theirs)
    return difference


# pkm's tool-change events are exactly "M6 T<n>" and "M61 Q<n>" (messages may mention M6 too).
TOOL_CHANGE = re.compile(r"^(?:M6 T|M61 Q)(\d+)$")


def pkm_tool_changes(events):
    changes = []
    for event in events:
        match = TOOL_CHANGE.search(event.get("what", ""))
        if match:
            changes.append(int(next(g for g in match.groups() if g is not None)))
    return changes


def describe(move, files):
    if move is None:
        return "(none)"
    where = f"line {move['line']}"
    if move.get("file", 0):
        where += f", {Path(files[move['file']]).name}:{move.get('source_line')}"
    end = ", ".join(f"{v:.4f}" for v in program_end(move))
    return f"{move['kind']} to ({end}) [{where}]"


def first_difference(document, motions, tools):
    """(index, rs274's call, pkm's move, what) of the first disagreement, or None."""
    # Moves pkm adds that the program does not make (the operator's retraction after G88) are not rs274's.
    moves = [m for m in document["moves"] if not m.get("inserted")]
    files = document.get("files", [])
    start, start_abc, tool_length = [0.0, 0.0, 0.0], [0.0, 0.0, 0.0], 0.0
    for i, (move, theirs) in enumerate(zip(moves, motions)):
        # A new tool length offset moves the tool tip's Z without a move (work coordinates).
        start[2] -= move.get("tool_length_mm", 0.0) - tool_length
        tool_length = move.get("tool_length_mm", 0.0)
        what = move_difference(move, start, start_abc, theirs)
        if what:
            return i, theirs["text"], describe(move, files), what
        start, start_abc = list(move["end"][:3]), list(move["end"][3:6])
    if len(moves) != len(motions):
        i = min(len(moves), len(motions))
        theirs = motions[i]["text"] if i < len(motions) else "(none)"
        ours = describe(moves[i], files) if i < len(moves) else "(none)"
        return i, theirs, ours, f"pkm has {len(moves)} moves, rs274 {len(motions)}"
    ours_tools = pkm_tool_changes(document.get("events", []))
    if ours_tools != tools:
        return len(moves), f"tool changes {tools}", f"tool changes {ours_tools}", "tool changes differ"
    return None


# --- the run -------------------------------------------------------------------------------------------

def work_point(program_mm, theirs):
    """work = g5x + Rz(rotation)·(program + g92), as pkm's WorkFrame reads."""
    q = [p + g for p, g in zip(program_mm, theirs["g92"])]
    th = math.radians(theirs["rotation_deg"])
    return [theirs["g5x"][0] + math.cos(th) * q[0] - math.sin(th) * q[1],
            theirs["g5x"][1] + math.sin(th) * q[0] + math.cos(th) * q[1], theirs["g5x"][2] + q[2]]


def rs274_as_pkm(motions, tools):
    """rs274's answer in the form of pkm interpret --json (--self-test): what a pkm that agrees prints. Checks
    the harness's own bookkeeping (units, planes, offsets, tool lengths), whatever pkm's interpreter does."""
    moves, previous = [], [0.0] * 6
    for theirs in motions:
        a, scale = theirs["args"], theirs["scale"]
        frame = {"index": 0, "system": theirs["g5x_index"], "g5x": theirs["g5x"], "g92": theirs["g92"],
                 "xy_rotation_deg": theirs["rotation_deg"]}
        move = {"line": 0, "kind": theirs["kind"], "file": 0, "source_line": 0, "frame": frame,
                "tool_length_mm": theirs["tool_length_mm"], "dwell_s": a[0] if theirs["kind"] == "dwell" else 0.0,
                "feed_mm_min": 0.0 if theirs["kind"] == "rapid" else theirs["feed_mm_min"]}
        end = list(previous)
        if theirs["kind"] in ("rapid", "line"):
            end = [v * scale for v in a[:3]] + a[3:6]
        elif theirs["kind"] == "arc":
            (first, second, normal), plane = PLANES.get(theirs["plane"], PLANES["CANON_PLANE_XY"])
            end, centre, axis = [0.0] * 3, [0.0] * 3, [0.0] * 3
            end[first], end[second], end[normal] = a[0] * scale, a[1] * scale, a[5] * scale
            centre[first], centre[second], centre[normal] = a[2] * scale, a[3] * scale, previous[normal]
            axis[normal] = 1.0 if a[4] > 0 else -1.0
            end += a[6:9]
            move.update(program_center=centre, center=work_point(centre, theirs), normal=axis,
                        turns=abs(int(round(a[4]))), plane=plane)
        move["program_end"], move["end"] = end, work_point(end[:3], theirs) + end[3:6]
        previous = end
        moves.append(move)
    return {"moves": moves, "events": [{"what": f"M6 T{tool}"} for tool in tools], "files": []}


def check_program(program, settings):
    try:
        return compare_program(program, settings)
    except Exception as error:  # one program's surprise must not hide the others' results
        return {"path": shown(program), "ran": True, "agrees": False, "why": "",
                "difference": (0, "(not compared)", "(not compared)", f"harness error: {error!r}")}


def compare_program(program, settings):
    folders = subroutine_path(program)
    output, ran, why = run_rs274(settings["rs274"], program, settings["tools_inch"], folders, settings["scratch"])
    result = {"path": shown(program), "ran": ran, "agrees": False, "why": why, "difference": None}
    if not ran:
        return result
    motions, tools = parse_rs274(output)
    if settings["self_test"]:
        document, error = rs274_as_pkm(motions, tools), ""
    else:
        document, error = run_pkm(settings["pkm"], settings["pkm_options"], program, settings["tools_mm"],
                                  folders)
    if document is None:
        result["difference"] = (0, motions[0]["text"] if motions else "(none)", "(none)", "pkm: " + error)
        return result
    result["difference"] = first_difference(document, motions, tools)
    result["agrees"] = result["difference"] is None
    return result


def read_known():
    """known.txt: {path: reason}; '#' starts a comment line."""
    known = {}
    if not KNOWN.exists():
        return known
    for line in KNOWN.read_text().splitlines():
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        parts = line.strip().split(None, 1)
        known[parts[0]] = parts[1] if len(parts) > 1 else ""
    return known


def report(results, known, arguments):
    ran = [r for r in results if r["ran"]]
    agree = [r for r in ran if r["agrees"]]
    print(f"{len(results)} programs: rs274 runs {len(ran)}, pkm agrees {len(agree)}")
    disagree = [r for r in ran if not r["agrees"]]
    unexpected = [r for r in disagree if r["path"] not in known]
    by_path = {r["path"]: r for r in results}
    stale = []
    for path, reason in known.items():
        r = by_path.get(path)
        if r is None and arguments.only is None:
            stale.append(f"{path}: no such program")
        elif r is not None and (not r["ran"] or r["agrees"]):
            stale.append(f"{path}: " + ("pkm now agrees" if r["ran"] else "rs274 does not run it") +
                         f" (listed as: {reason})")
    for r in disagree if arguments.verbose else unexpected:
        index, theirs, ours, what = r["difference"]
        mark = "" if r["path"] not in known else f" (known: {known[r['path']]})"
        print(f"  {r['path']}{mark}: move {index}: {what}")
        if arguments.verbose:
            print(f"      rs274: {theirs}\n      pkm:   {ours}")
    if arguments.verbose:
        for r in results:
            if not r["ran"]:
                print(f"  not run by rs274: {r['path']}: {r['why']}")
        reasons = {}
        for r in results:
            if not r["ran"]:
                reasons[r["why"]] = reasons.get(r["why"], 0) + 1
        for why, count in sorted(reasons.items(), key=lambda item: -item[1])[:10]:
            print(f"  rs274 stopped {count} times with: {why}")
    if arguments.list_failures:
        for r in disagree:
            print(f"{r['path']}\t{r['difference'][3]}")
    for line in stale:
        print(f"  stale known.txt entry: {line}")
    if unexpected:
        print(f"{len(unexpected)} programs disagree that known.txt does not list")
    return 1 if unexpected or stale else 0


def parse_arguments():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--pkm", default=str(ROOT / "build" / "pkm"), help="the pkm binary (default build/pkm)")
    parser.add_argument("--rs274", default="rs274", help="LinuxCNC's standalone interpreter")
    parser.add_argument("--only", help="only programs whose path contains this")
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 1, help="programs run in parallel")
    parser.add_argument("--verbose", action="store_true", help="the first difference of every program")
    parser.add_argument("--list-failures", action="store_true",
                        help="list every disagreeing program with its first difference (known.txt's format)")
    parser.add_argument("--self-test", action="store_true",
                        help="compare rs274 with itself, put in pkm's JSON form: checks this script, not pkm "
                             "(every program rs274 runs must agree)")
    return parser.parse_args()


def main():
    arguments = parse_arguments()
    programs = package_programs() + project_programs()
    if arguments.only:
        programs = [p for p in programs if arguments.only in shown(p)]
    with tempfile.TemporaryDirectory(prefix="pkm-conformance-") as scratch:
        tools_inch, tools_mm = write_tool_tables(Path(scratch))
        settings = {"rs274": arguments.rs274, "pkm": arguments.pkm, "tools_inch": tools_inch,
                    "tools_mm": tools_mm, "scratch": scratch, "self_test": arguments.self_test,
                    "pkm_options": {} if arguments.self_test else pkm_options(arguments.pkm)}
        with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, arguments.jobs)) as pool:
            results = list(pool.map(lambda p: check_program(p, settings), programs))
    return report(results, read_known(), arguments)


if __name__ == "__main__":
    sys.exit(main())
