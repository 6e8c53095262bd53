#!/usr/bin/python3
"""Feeds an execution stream into pkm's HAL component pkmexec while LinuxCNC runs (docs/linuxcnc.md).

    pkm linuxcnc stream --machine M.yaml PROGRAM | linuxcnc/pkm_feed.py

Reads the stream that `pkm linuxcnc stream` writes (standard input, or the file given) line by line and
writes each record into pkmexec's HAL stream as room frees there, so a program of any length runs with bounded
memory and a new program can follow without restarting LinuxCNC. pkmexec must be loaded (LinuxCNC running the
configuration of `pkm linuxcnc config --execute`, or any HAL session that loads it).

Exits 0 once the program's `end` has been handed over; 1, naming the line, for a stream it cannot read. A
stream cut short (no `end`) leaves pkmexec to stop, within the drives' limits, after the last period it has.
"""
import os
import sys
import time

import hal

KEY = 0x706B6D78  # pkmexec.c: PKMEXEC_STREAM_KEY
TYPES = "ss" + "f" * 6 + "s" * 6  # kind, line, ideal × 6, position × 6
MAX_DRIVES = 6
START, PERIOD, END = 1, 2, 3


class StreamError(Exception):
    pass


def record(fields, where, drives):
    """The HAL row of one record of the stream."""
    kind = fields[0]
    try:
        if kind == "start" and len(fields) == 1 + drives:
            positions = [int(v) for v in fields[1:]]
            return (START, 0, *([float(p) for p in positions] + [0.0] * (MAX_DRIVES - drives)),
                    *(positions + [0] * (MAX_DRIVES - drives)))
        if kind == "p" and len(fields) == 2 + 2 * drives:
            ideal = [float(v) for v in fields[2:2 + drives]]
            positions = [int(v) for v in fields[2 + drives:]]
            return (PERIOD, int(fields[1]), *(ideal + [0.0] * (MAX_DRIVES - drives)),
                    *(positions + [0] * (MAX_DRIVES - drives)))
        if kind == "end" and len(fields) == 1:
            return (END, 0) + (0.0,) * MAX_DRIVES + (0,) * MAX_DRIVES
    except ValueError as e:
        raise StreamError(f"{where}: {e}") from None
    raise StreamError(f"{where}: not a record of the execution stream: {','.join(fields)[:80]}")


def drives_of(header, where):
    # "# pkm execution stream 1: MACHINE, N drives, period H s, step D"
    if not header.startswith("# pkm execution stream 1:"):
        raise StreamError(f"{where}: not a pkm execution stream (its first line is {header[:60]!r})")
    for part in header.split(","):
        words = part.split()
        if len(words) == 2 and words[1] == "drives":
            return int(words[0])
    raise StreamError(f"{where}: the header does not say how many drives")


def feed(lines, name, stream):
    drives = None
    for number, text in enumerate(lines, start=1):
        where = f"{name}:{number}"
        text = text.strip()
        if number == 1:
            drives = drives_of(text, where)
            continue
        if not text:
            continue
        row = record(text.split(","), where, drives)
        while not stream.writable:
            time.sleep(0.001)
        stream.write(row)
        if row[0] == END:
            return True
    return False


def main():
    name = sys.argv[1] if len(sys.argv) > 1 else "-"
    component = hal.component(f"pkmfeed{os.getpid()}")
    component.ready()
    try:
        stream = hal.stream(component, KEY, TYPES)
    except OSError as e:
        print(f"pkm_feed: pkmexec's stream is not there (is pkmexec loaded?): {e}", file=sys.stderr)
        return 1
    try:
        with (open(name) if name != "-" else sys.stdin) as lines:
            ended = feed(lines, "standard input" if name == "-" else name, stream)
    except StreamError as e:
        print(f"pkm_feed: {e}", file=sys.stderr)
        return 1
    if not ended:
        print("pkm_feed: the stream ended without its end record: pkmexec stops after the last period",
              file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
