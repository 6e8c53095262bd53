#!/usr/bin/env bash
# Regenerates the golden files of the G-code conformance suite: runs LinuxCNC's standalone interpreter
# `rs274` (Debian package linuxcnc-uspace) on every tests/program/conformance/NN_name.ngc and keeps its raw
# output as NN_name.rs274 next to it. tests/program/gcode_conformance_test.cpp compares pkm's interpreter
# with these files (docs/part-programs.md).
#
# Options passed to rs274, to match pkm's defaults:
#   -g          batch mode (run the whole file)
#   -b          block delete ON (rs274's default is OFF; pkm's InterpretOptions::block_delete is true)
#   -t tools.tbl  the suite's tool table (rs274 reads it in inches; the test gives pkm the same table in mm)
#   -v NN_name.var  the program's parameter file, when it has one (inches too; the test converts it likewise)
# Fails if rs274 is missing or if any program does not run to its end (an rs274 error).
# With --check, writes nothing: runs rs274 into a temporary directory and fails if any output differs from the
# committed golden file (CI runs this, so the golden files are always LinuxCNC's current answers).
set -euo pipefail
cd "$(dirname "$0")/../tests/program/conformance"
check=0
if [ "${1:-}" = "--check" ]; then check=1; fi
out_dir=.
if [ $check -eq 1 ]; then out_dir=$(mktemp -d); fi
RS274=${RS274:-rs274}
command -v "$RS274" > /dev/null || { echo "regen-rs274-golden: $RS274 not found (apt-get install linuxcnc-uspace)" >&2; exit 1; }
# rs274 keeps its tool table in $HOME/.tool.mmap, shared by every rs274 of one user: a private HOME keeps
# other runs (another checkout, a parallel job) from changing this one's tools.
rs274_home=$(mktemp -d)
cleanup() {
  rm -rf "$rs274_home"
  if [ $check -eq 1 ]; then rm -rf "$out_dir"; fi
}
trap cleanup EXIT
export HOME=$rs274_home
status=0
count=0
for program in [0-9][0-9]_*.ngc; do
  golden="$out_dir/${program%.ngc}.rs274"
  # A program with a parameter file NN_name.var gets a copy of it (rs274 writes its parameters back at the end).
  var_options=()
  if [ -f "${program%.ngc}.var" ]; then
    cp "${program%.ngc}.var" "$rs274_home/params.var"
    var_options=(-v "$rs274_home/params.var")
  fi
  "$RS274" -g -b -t tools.tbl "${var_options[@]}" "$program" < /dev/null > "$golden" 2>&1 || true
  if ! grep -qE 'PROGRAM_END\(\)|FINISH\(\)' "$golden"; then
    echo "regen-rs274-golden: $program did not run to its end under rs274:" >&2
    tail -n 3 "$golden" >&2
    status=1
  fi
  if [ $check -eq 1 ] && ! diff -q "$golden" "${program%.ngc}.rs274" > /dev/null; then
    echo "regen-rs274-golden: rs274's output for $program differs from the golden file:" >&2
    diff "${program%.ngc}.rs274" "$golden" | head -n 10 >&2
    status=1
  fi
  count=$((count + 1))
done
echo "regen-rs274-golden: $count programs"
exit $status
