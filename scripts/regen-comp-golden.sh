#!/usr/bin/env bash
# Regenerates the golden files of the cutter radius compensation suite (tests/program/conformance/comp):
#  - kNN_name.ngc are written by hand (concave and convex corners, arcs, entry and exit moves, G41.1/G42.1,
#    G18, LinuxCNC's errors);
#  - rNN_random.ngc are generated here from fixed seeds: closed contours (random star-shaped polygons, some
#    edges arcs bulging either way) cut on the left or right with several tool radii, in G17 (r01-r40), G18
#    (r41-r50), millimetres with dwells, plunges and rapids (r51-r60), polygons with tangent fillets (r61-r70)
#    and open paths with sharp turns and near-reversals (r71-r80); some of them rs274 refuses (gouging, arcs
#    too small for the tool), which the test expects pkm to refuse too;
# and for each the output of LinuxCNC's standalone interpreter is kept as NAME.rs274: its canonical calls
# (stdout), then its error message and the offending block if it stopped (stderr, without "executing").
# tests/program/ngc_cutter_compensation_test.cpp drives pkm's CutterCompensation with the same programs and
# compares. rs274 reads the tool table (tools.tbl here) in inches: programs in G21 use G41.1/G42.1 only.
# With --check, writes nothing: regenerates into a temporary directory and fails if anything differs.
set -euo pipefail
dir="$(cd "$(dirname "$0")/../tests/program/conformance/comp" && pwd)"
check=0
if [ "${1:-}" = "--check" ]; then check=1; fi
out_dir="$dir"
if [ $check -eq 1 ]; then
  out_dir=$(mktemp -d)
  trap 'rm -rf "$out_dir"' EXIT
  cp "$dir"/k*.ngc "$dir"/tools.tbl "$out_dir"/
fi
RS274=${RS274:-rs274}
command -v "$RS274" > /dev/null || { echo "regen-comp-golden: $RS274 not found (apt-get install linuxcnc-uspace)" >&2; exit 1; }

python3 - "$out_dir" <<'PY'
import math, random, sys
out = sys.argv[1]

def fmt(v):
    s = f"{v:.4f}"
    return "0.0000" if s == "-0.0000" else s

def contour(rng, seed, n, plane="G17", mm=False, extras=False):
    """A closed contour around the origin; edges lines or arcs; plane G17 (X Y, I J) or G18 (Z X, K I)."""
    k = 25.4 if mm else 1.0
    a1, a2, c1, c2 = ("X", "Y", "I", "J") if plane == "G17" else ("Z", "X", "K", "I")
    vertices = rng.randint(3, 7)
    angles = sorted(rng.uniform(0, 2 * math.pi) for _ in range(vertices))
    # keep vertices apart so that edges are not degenerate
    angles = [a + i * 0.15 for i, a in enumerate(angles)]
    angles = [a * 2 * math.pi / (angles[-1] + 0.6) for a in angles]
    pts = [(round(k * rng.uniform(0.6, 2.0) * math.cos(a), 4), round(k * rng.uniform(0.6, 2.0) * math.sin(a), 4))
           for a in angles]
    if rng.random() < 0.5:
        pts.reverse()
    side = rng.choice(["G41", "G42"])
    if rng.random() < 0.3 or mm:
        comp = f"{side}.1 D{fmt(k * rng.choice([0.05, 0.1, 0.2, 0.3]))}"
    else:
        comp = f"{side} D{rng.randint(1, 4)}"
    far = fmt(3 * k)
    depth = "Z" if plane == "G17" else "Y"
    lines = ["(random closed contour, seed %d, number %d)" % (seed, n), f"{'G21' if mm else 'G20'} {plane} G90 G40",
             f"F{20 * k:g}", f"G0 {a1}{far} {a2}{far} {depth}{fmt(0.1 * k)}", f"G1 {depth}{fmt(-0.1 * k)}", comp]
    lines.append(f"G1 {a1}{fmt(pts[0][0])} {a2}{fmt(pts[0][1])}")
    for i in range(1, len(pts) + 1):
        a = pts[i - 1]
        b = pts[i % len(pts)]
        if extras and rng.random() < 0.2:
            lines.append(rng.choice(["G4 P0.5", f"G1 {depth}{fmt(-0.2 * k)}", f"G0 {depth}{fmt(0.1 * k)}"]))
        if rng.random() < 0.45:
            mx, my = (a[0] + b[0]) / 2, (a[1] + b[1]) / 2
            dx, dy = b[0] - a[0], b[1] - a[1]
            h = rng.choice([-1, 1]) * rng.uniform(0.15, 1.5)
            cx, cy = mx - dy * h, my + dx * h
            g = rng.choice(["G2", "G3"])
            lines.append(f"{g} {a1}{fmt(b[0])} {a2}{fmt(b[1])} {c1}{fmt(cx - a[0])} {c2}{fmt(cy - a[1])}")
        else:
            kind = "G0" if extras and rng.random() < 0.15 else "G1"
            lines.append(f"{kind} {a1}{fmt(b[0])} {a2}{fmt(b[1])}")
    lines += ["G40", f"G0 {a1}{far} {a2}-{far}", "M2"]
    with open(f"{out}/r{n:02d}_random.ngc", "w") as f:
        f.write("\n".join(lines) + "\n")

def header(rng, n, kind, lines):
    side = rng.choice(["G41", "G42"])
    comp = f"{side}.1 D{fmt(rng.choice([0.05, 0.1, 0.2, 0.3, 0.5]))}" if rng.random() < 0.5 else f"{side} D{rng.randint(1, 4)}"
    return ["(random %s, seed 20261208, number %d)" % (kind, n), "G20 G17 G90 G40", "F20", "G0 X3.0000 Y3.0000", comp] + lines + ["G40", "G0 X3.0000 Y-3.0000", "M2"]

def filleted(rng, n):
    vertices = rng.randint(3, 7)
    angles = sorted(rng.uniform(0, 2 * math.pi) for _ in range(vertices))
    angles = [a + i * 0.15 for i, a in enumerate(angles)]
    angles = [a * 2 * math.pi / (angles[-1] + 0.6) for a in angles]
    pts = [(rng.uniform(0.6, 2.0) * math.cos(a), rng.uniform(0.6, 2.0) * math.sin(a)) for a in angles]
    if rng.random() < 0.5: pts.reverse()
    m = len(pts)
    mid = ((pts[0][0] + pts[1][0]) / 2, (pts[0][1] + pts[1][1]) / 2)
    lines = [f"G1 X{fmt(mid[0])} Y{fmt(mid[1])}"]
    for k in range(1, m + 1):
        a, v, b = pts[k - 1], pts[k % m], pts[(k + 1) % m]
        d1 = (v[0] - a[0], v[1] - a[1]); l1 = math.hypot(*d1); d1 = (d1[0] / l1, d1[1] / l1)
        d2 = (b[0] - v[0], b[1] - v[1]); l2 = math.hypot(*d2); d2 = (d2[0] / l2, d2[1] / l2)
        phi = math.atan2(d1[0] * d2[1] - d1[1] * d2[0], d1[0] * d2[0] + d1[1] * d2[1])
        f = rng.uniform(0.02, 0.5)
        t = f * math.tan(abs(phi) / 2)
        tmax = 0.45 * min(l1, l2)
        if t > tmax:
            t = tmax; f = t / math.tan(abs(phi) / 2)
        p1 = (v[0] - d1[0] * t, v[1] - d1[1] * t); p2 = (v[0] + d2[0] * t, v[1] + d2[1] * t)
        nrm = (-d1[1], d1[0]) if phi > 0 else (d1[1], -d1[0])
        c = (p1[0] + nrm[0] * f, p1[1] + nrm[1] * f)
        lines.append(f"G1 X{fmt(p1[0])} Y{fmt(p1[1])}")
        if rng.random() < 0.85:
            lines.append(f"{'G3' if phi > 0 else 'G2'} X{fmt(p2[0])} Y{fmt(p2[1])} I{fmt(c[0] - p1[0])} J{fmt(c[1] - p1[1])}")
        else:
            lines.append(f"G1 X{fmt(v[0])} Y{fmt(v[1])}")
            lines.append(f"G1 X{fmt(p2[0])} Y{fmt(p2[1])}")
    lines.append(f"G1 X{fmt(mid[0])} Y{fmt(mid[1])}")
    return header(rng, n, "filleted contour", lines)

def walk(rng, n):
    x, y, h = 0.0, 0.0, rng.uniform(0, 2 * math.pi)
    lines = [f"G1 X{fmt(x)} Y{fmt(y)}"]
    for _ in range(rng.randint(3, 9)):
        h += rng.choice([rng.uniform(-3.1, 3.1), rng.uniform(-0.1, 0.1), math.pi * rng.choice([-1, 1]) * rng.uniform(0.97, 1.0)])
        L = rng.uniform(0.1, 1.5)
        nx, ny = x + L * math.cos(h), y + L * math.sin(h)
        if rng.random() < 0.4:
            mx, my = (x + nx) / 2, (y + ny) / 2
            dx, dy = nx - x, ny - y
            hh = rng.choice([-1, 1]) * rng.uniform(0.0, 1.5)
            cx, cy = mx - dy * hh, my + dx * hh
            lines.append(f"{rng.choice(['G2', 'G3'])} X{fmt(nx)} Y{fmt(ny)} I{fmt(cx - x)} J{fmt(cy - y)}")
        else:
            lines.append(f"G1 X{fmt(nx)} Y{fmt(ny)}")
        x, y = float(fmt(nx)), float(fmt(ny))
    return header(rng, n, "open path", lines)

# r01-r40: XY, inches, in the tool table's radii or G41.1/G42.1 (seed kept: their goldens are reviewed)
rng = random.Random(20261206)
for n in range(1, 41):
    contour(rng, 20261206, n)
# r41-r50: XZ (G18); r51-r60: millimetres with dwells, plunges and rapids inside the contour
rng = random.Random(20261207)
for n in range(41, 51):
    contour(rng, 20261207, n, plane="G18")
for n in range(51, 61):
    contour(rng, 20261207, n, mm=True, extras=True)
# r61-r70: polygons with tangent fillets (some corners left sharp), the shape CAM output has; r71-r80: open
# random paths with sharp turns, near-reversals and near-tangents, lines and arcs
rng = random.Random(20261208)
for n in range(61, 81):
    lines = filleted(rng, n) if n <= 70 else walk(rng, n)
    with open(f"{out}/r{n:02d}_random.ngc", "w") as f:
        f.write("\n".join(lines) + "\n")
PY

# rs274 keeps its tool table in a file mapped into memory, $HOME/.tool.mmap, shared by every rs274 running
# under the same HOME: runs in parallel (another worktree's regeneration) overwrite each other's tools. Each
# run of this script gets a HOME of its own.
rs274_home=$(mktemp -d)
trap 'rm -rf "$rs274_home"; if [ $check -eq 1 ]; then rm -rf "$out_dir"; fi' EXIT
status=0
count=0
cd "$out_dir"
for program in k[0-9][0-9]_*.ngc r[0-9][0-9]_*.ngc; do
  golden="${program%.ngc}.rs274"
  HOME="$rs274_home" "$RS274" -g -b -t tools.tbl "$program" < /dev/null > "$golden.out" 2> "$golden.err" || true
  { cat "$golden.out"; grep -v '^executing$' "$golden.err" || true; } > "$golden"
  rm -f "$golden.out" "$golden.err"
  if [ $check -eq 1 ]; then
    for f in "$program" "$golden"; do
      if ! diff -q "$f" "$dir/$f" > /dev/null 2>&1; then
        echo "regen-comp-golden: $f differs from the committed file:" >&2
        diff "$dir/$f" "$f" | head -n 10 >&2 || true
        status=1
      fi
    done
  fi
  count=$((count + 1))
done
echo "regen-comp-golden: $count programs"
exit $status
