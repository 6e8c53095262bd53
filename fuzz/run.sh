#!/usr/bin/env bash
# Runs the libFuzzer harnesses built in BUILD/fuzz (make fuzz builds them), each on its own working corpus
# BUILD/corpus/NAME, seeded at run time from the examples, the tests and fuzz/ (so that git keeps one copy of
# every seed). Usage:
#   fuzz/run.sh BUILD SECONDS [NAME...]         SECONDS each, FUZZ_JOBS (nproc) at a time; exits 1 and prints
#                                               the reproducer of any crash, leak, timeout or out-of-memory
#   fuzz/run.sh --long BUILD SECONDS [NAME...]  all at once in the background under nice -n 19, in fork mode
#                                               so that a crash does not end the run; logs in BUILD/long/NAME.log
set -euo pipefail
cd "$(dirname "$0")/.."
long=0
if [ "${1:-}" = "--long" ]; then long=1; shift; fi
build=${1:?usage: fuzz/run.sh [--long] BUILD SECONDS [NAME...]}
seconds=${2:?usage: fuzz/run.sh [--long] BUILD SECONDS [NAME...]}
shift 2
names=("$@")
if [ "${#names[@]}" -eq 0 ]; then names=(gcode cl machine load steps_csv steps_bin measurements); fi

# The seeds of a harness (globs relative to the repository), and the longest input worth trying: a little
# above the largest seed, so that mutations can grow it but time is not spent on megabytes of one format.
seeds_of() {
  case $1 in
    gcode) echo "examples/programs/*.ngc tests/program/conformance/*.ngc tests/program/conformance/*/*.ngc" ;;
    cl) echo "examples/programs/*.cl tests/program/cl_dialects/*" ;;
    machine) echo "examples/machines/*.yaml" ;;
    *) echo "fuzz/seeds/$1/*" ;;
  esac
}
max_len_of() {
  case $1 in
    cl) echo 16384 ;;
    machine) echo 8192 ;;
    load) echo 2048 ;;
    *) echo 4096 ;;
  esac
}

seed_corpus() {
  local name=$1 corpus=$build/corpus/$1
  mkdir -p "$corpus"
  # shellcheck disable=SC2086  # the globs must expand here
  for f in $(seeds_of "$name") fuzz/regressions/"$name"/*; do
    if [ -f "$f" ]; then cp -n "$f" "$corpus/seed-$(basename "$f")"; fi
  done
}

options_of() {
  local name=$1 dict=fuzz/dict/$1.dict
  echo "-max_len=$(max_len_of "$name") -rss_limit_mb=2048 -timeout=10 -max_total_time=$seconds -print_final_stats=1"
  if [ -f "$dict" ]; then echo "-dict=$dict"; fi
}

failed=()
for name in "${names[@]}"; do
  harness=$build/fuzz/fuzz_$name
  [ -x "$harness" ] || { echo "fuzz: $harness is not built (make fuzz builds it)" >&2; exit 2; }
  seed_corpus "$name"
  artifacts=$build/artifacts/$name
  mkdir -p "$artifacts"
  rm -f "$artifacts.failed"
  # shellcheck disable=SC2046  # one word per option
  if [ "$long" -eq 1 ]; then
    mkdir -p "$build/long"
    nice -n 19 "$harness" $(options_of "$name") -fork=1 -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1 \
      -artifact_prefix="$artifacts/" "$build/corpus/$name" > "$build/long/$name.log" 2>&1 &
    echo "fuzz: $name running in the background (pid $!), log $build/long/$name.log"
    continue
  fi
  echo "fuzz: $name for ${seconds} s"
  touch "$artifacts.start"  # reproducers newer than this are this run's
  # FUZZ_JOBS harnesses at once (default: one per core): CI's 2 cores run the six in half the time.
  while [ "$(jobs -rp | wc -l)" -ge "${FUZZ_JOBS:-$(nproc)}" ]; do wait -n || true; done
  (
    if ! "$harness" $(options_of "$name") -artifact_prefix="$artifacts/" "$build/corpus/$name" \
      > "$build/artifacts/$name.log" 2>&1; then
      touch "$build/artifacts/$name.failed"
    fi
  ) &
done
if [ "$long" -eq 1 ]; then exit 0; fi
wait
for name in "${names[@]}"; do
  if [ -f "$build/artifacts/$name.failed" ]; then
    failed+=("$name")
    tail -n 40 "$build/artifacts/$name.log" >&2
  fi
  echo "fuzz: $name: $(grep -E '^#[0-9]+.*(DONE|cov:)' "$build/artifacts/$name.log" | tail -n 1 || true)"
done
if [ "${#failed[@]}" -gt 0 ]; then
  for name in "${failed[@]}"; do
    echo "fuzz: $name failed; reproducer(s), replay with $build/fuzz/fuzz_$name FILE:" >&2
    find "$build/artifacts/$name" -type f -newer "$build/artifacts/$name.start" -printf '  %p\n' >&2 || true
  done
  exit 1
fi
echo "fuzz: no crash, leak or timeout in ${names[*]}"
