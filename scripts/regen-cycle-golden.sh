#!/usr/bin/env bash
# Regenerates the golden files of the canned-cycle conformance suite (tests/program/ngc_canned_cycle_test.cpp):
#   - cNN_name.ngc: hand-written programs (each cycle, each plane, G98/G99, L, G91, inch), committed as is;
#   - eNN_name.ngc: hand-written programs ending in one error, committed as is;
#   - rNN.ngc: NUM_RANDOM (60) random cycle programs, written here by a seeded generator (same seed, same files);
# and, for every program, NAME.rs274: what LinuxCNC's standalone interpreter `rs274` (Debian package
# linuxcnc-uspace) prints for it, its canonical calls or its error message. Same options as
# scripts/regen-rs274-golden.sh: -g (batch) -b (block delete on).
# Fails if rs274 is missing, if a cNN or rNN program does not run to its end, or if an eNN program does.
# With --check, writes nothing: generates and runs rs274 into a temporary directory and fails if any file differs
# from the committed one (so the golden files are always LinuxCNC's current answers to the current generator).
set -euo pipefail
cd "$(dirname "$0")/../tests/program/conformance/cycles"
check=0
if [ "${1:-}" = "--check" ]; then check=1; fi
out_dir=.
if [ $check -eq 1 ]; then out_dir=$(mktemp -d); trap 'rm -rf "$out_dir"' EXIT; fi
RS274=${RS274:-rs274}
command -v "$RS274" > /dev/null || { echo "regen-cycle-golden: $RS274 not found (apt-get install linuxcnc-uspace)" >&2; exit 1; }
command -v python3 > /dev/null || { echo "regen-cycle-golden: python3 not found" >&2; exit 1; }

# The random programs: one to three series of one to three cycle blocks each, in a random plane and unit
# system, from a random start (sometimes below R); the blocks after the first of a series either repeat the
# cycle (leaving out sticky words at random) or switch to another one (with all its words).
python3 - "$out_dir" <<'PYTHON'
import random, sys
out_dir = sys.argv[1]
NUM_RANDOM = 60
PLANES = {17: ('X', 'Y', 'Z'), 18: ('Z', 'X', 'Y'), 19: ('Y', 'Z', 'X')}  # in-plane a, b; normal

def num(v, inch):
    v = round(v / 25.0, 3) if inch else round(v, 1)
    text = ('%.3f' % v).rstrip('0').rstrip('.')
    return '0' if text in ('-0', '') else text

def cycle_words(rng, code, plane, inch, incremental, full, prev, initial):
    a, b, c = PLANES[plane]
    words = []
    for axis in (a, b):
        if rng.random() < 0.7:
            words.append(axis + num(rng.uniform(-10, 10) if incremental else rng.uniform(-20, 20), inch))
    if not words and not full:  # a block without axis words does not run the cycle (nor may hold R P Q)
        words.append(a + num(rng.uniform(-10, 10), inch))
    new_depth = full or rng.random() < 0.3
    if full or rng.random() < 0.3:
        r = rng.uniform(-10, 5) if incremental else rng.uniform(-2, 8)
        if not incremental and not new_depth:  # keeps the remembered depth below R
            r = max(r, prev['depth'] + rng.uniform(0.5, 5))
        prev['r'] = r
        words.append('R' + num(r, inch))
    if new_depth:
        depth = -rng.uniform(1, 15)
        if not incremental:
            depth += prev['r']
        prev['depth'] = depth
        words.append(c + num(depth, inch))
    if code in (82, 86, 88, 89) and (full or rng.random() < 0.4):
        words.append('P' + num(rng.choice([0, 0.2, 0.5, 1, 1.5]) * (25.0 if inch else 1.0), inch))
    if code == 84 and rng.random() < 0.5:
        words.append('P' + num(rng.choice([0, 0.3, 1]) * (25.0 if inch else 1.0), inch))
    if code in (73, 83) and (full or rng.random() < 0.4):
        words.append('Q' + num(rng.uniform(0.7, 5), inch))
    if code == 87 and (full or rng.random() < 0.4):
        offsets = {'X': 'I', 'Y': 'J', 'Z': 'K'}
        for axis in (a, b):
            words.append(offsets[axis] + num(rng.choice([-1, 1]) * rng.uniform(0.5, 3), inch))
        # the top of the counterbore: above the bottom (relative to it in G91)
        words.append(offsets[c] + num(rng.uniform(1, 4) if incremental else rng.uniform(-12, -1), inch))
    if rng.random() < (0.4 if incremental else 0.1):
        words.append('L' + str(rng.randint(2, 3)))
    return words

def program(seed):
    rng = random.Random(seed)
    inch = rng.random() < 0.3
    plane = rng.choice([17, 18, 19])
    ccw = rng.random() < 0.15
    lines = ['%s G%d G90 F%d S%d %s' % ('G20' if inch else 'G21', plane, rng.randint(2, 20) * 10,
                                       rng.randint(2, 20) * 100, 'M4' if ccw else 'M3')]
    codes = [73, 81, 82, 83, 85, 86, 87, 88, 89] + ([] if ccw else [84])
    for series in range(rng.randint(1, 3)):
        start = [rng.uniform(-20, 20), rng.uniform(-20, 20), rng.uniform(-20, 20)]
        normal = 'XYZ'.index(PLANES[plane][2])
        start[normal] = rng.uniform(-4, 25)
        lines.append('G0 X%s Y%s Z%s' % tuple(num(v, inch) for v in start))
        incremental = rng.random() < 0.4
        code = None
        prev = {'r': 0.0, 'depth': 0.0}
        for block in range(rng.randint(1, 3)):
            words = []
            full = code is None or rng.random() < 0.4
            if block == 0:
                words += ['G99' if rng.random() < 0.5 else 'G98', 'G91' if incremental else 'G90']
            elif rng.random() < 0.2:
                words.append('G99' if rng.random() < 0.5 else 'G98')
            if full:
                new_code = rng.choice(codes)
                words.append('G%d' % new_code)
                code = new_code
            words += cycle_words(rng, code, plane, inch, incremental, full, prev, start[normal])
            lines.append(' '.join(words))
        lines.append('G90 G80')
    lines.append('M2')
    return '\n'.join(lines) + '\n'

for n in range(1, NUM_RANDOM + 1):
    with open('%s/r%02d.ngc' % (out_dir, n), 'w') as f:
        f.write(program(20261206 + n))
PYTHON

status=0
count=0
for program in c[0-9][0-9]_*.ngc e[0-9][0-9]_*.ngc "$out_dir"/r[0-9][0-9].ngc; do
  name=$(basename "${program%.ngc}")
  golden="$out_dir/$name.rs274"
  (cd "$(dirname "$program")" && "$RS274" -g -b "$(basename "$program")" < /dev/null 2>&1) > "$golden" || true
  if [[ $name == e* ]]; then
    if grep -q 'PROGRAM_END()' "$golden"; then
      echo "regen-cycle-golden: $name.ngc ran to its end under rs274, it should end in an error" >&2
      status=1
    fi
  elif ! grep -q 'PROGRAM_END()' "$golden"; then
    echo "regen-cycle-golden: $name.ngc did not run to its end under rs274:" >&2
    tail -n 3 "$golden" >&2
    status=1
  fi
  if [ $check -eq 1 ]; then
    for file in "$golden" "$out_dir/$name.ngc"; do
      [ -f "$file" ] || continue
      if ! diff -q "$file" "$(basename "$file")" > /dev/null 2>&1; then
        echo "regen-cycle-golden: $(basename "$file") differs from the committed file:" >&2
        diff "$(basename "$file")" "$file" | head -n 10 >&2 || true
        status=1
      fi
    done
  fi
  count=$((count + 1))
done
echo "regen-cycle-golden: $count programs"
exit $status
