#!/usr/bin/python3
"""Feeds an execution stream into pkm's HAL component pkmexec while LinuxCNC runs (docs/linuxcnc.md).

    pkm linuxcnc stream --machine M.yaml PROGRAM | linuxcnc/pkm_feed.py [--machine-on] [STREAM]

Reads the stream that `pkm linuxcnc stream` writes (standard input, or the file given) line by line and
writes each record into pkmexec's HAL stream as room frees there, so a program of any length runs with bounded
memory and a new program can follow without restarting LinuxCNC. pkmexec must be loaded (LinuxCNC running the
configuration of `pkm linuxcnc config --execute`, or any HAL session that loads it).

Before the first record it checks that the drives are handed over (pkmexec.enable: with the --execute
configuration, LinuxCNC on, homed, idle and at rest); then it waits until pkmexec has executed the program
and says how it ended. With --machine-on it then turns LinuxCNC's machine on again (LinuxCNC's motion is off
while pkmexec moves the drives, and takes them back where pkmexec left them).

Exits 0 when the program was executed to its end; 1, naming the line, for a stream it cannot read or drives
not handed over; 2 when pkmexec refused the program, stopped it at a software stop (naming the program line)
or it was aborted. A stream cut short (no `end`) leaves pkmexec to stop, within the drives' limits, after the
last period it has.
"""
import os
import sys
import time

import hal

KEY = 0x706B6D78  # pkmexec.c: PKMEXEC_STREAM_KEY
TYPES = "ss" + "f" * 6 + "s" * 6  # kind, line, ideal × 6, position × 6
MAX_DRIVES = 6
START, PERIOD, END = 1, 2, 3
# pkmexec.state (pkmexec_bridge.h)
RUNNING, STARVED, FINISHED, ABORTED, STOPPED_AT_LIMIT, REFUSED, NOT_HANDED_OVER = 1, 2, 3, 4, 5, 6, 7
OUTCOMES = {
    FINISHED: "executed to its end",
    ABORTED: "aborted: the drives stopped along the path within their limits",
    STOPPED_AT_LIMIT: "stopped before a software stop (the drives' range) at program line {line}",
    REFUSED: "refused: it does not start where the drives are",
    NOT_HANDED_OVER: "refused: the drives were not handed over (pkmexec.enable false)",
}


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


def feed(lines, name, stream, before_start):
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
        if row[0] == START:
            before_start()
        while not stream.writable:
            time.sleep(0.001)
        stream.write(row)
        if row[0] == END:
            return True
    return False


def handed_over():
    """pkmexec.enable, or True where nothing drives it (a HAL session of pkmexec alone)."""
    return bool(hal.get_value("pkmexec.enable"))


def outcome(programs_before, timeout_s=None):
    """Waits until pkmexec has taken the program and no longer moves the drives; its final state."""
    deadline = None if timeout_s is None else time.monotonic() + timeout_s
    while deadline is None or time.monotonic() < deadline:
        state = hal.get_value("pkmexec.state")
        # pkmexec stays active after a program until the drives reach its last command.
        if (hal.get_value("pkmexec.programs") > programs_before and state not in (RUNNING, STARVED)
                and not hal.get_value("pkmexec.active")):
            return state
        time.sleep(0.01)
    return None


def machine_on():
    """LinuxCNC's machine on again, through its own command channel."""
    import linuxcnc
    command, stat = linuxcnc.command(), linuxcnc.stat()
    stat.poll()
    if stat.task_state == linuxcnc.STATE_ESTOP:
        return "LinuxCNC is in E-stop: its machine stays off"
    command.state(linuxcnc.STATE_ON)
    command.wait_complete()
    stat.poll()
    return None if stat.task_state == linuxcnc.STATE_ON else "LinuxCNC did not turn its machine on"


def check_handed_over():
    if not handed_over():
        raise StreamError("the drives are not handed over to pkmexec (pkmexec.enable is false): turn LinuxCNC's "
                          "machine on, home it, and let it be idle")


def main():
    args = sys.argv[1:]
    turn_on = "--machine-on" in args
    args = [a for a in args if a != "--machine-on"]
    name = args[0] if args else "-"
    component = hal.component(f"pkmfeed{os.getpid()}")
    component.ready()
    try:
        stream = hal.stream(component, KEY, TYPES)
    except OSError as e:
        print(f"pkm_feed: pkmexec's stream is not there (is pkmexec loaded?): {e}", file=sys.stderr)
        return 1
    programs_before = hal.get_value("pkmexec.programs")
    try:
        with (open(name) if name != "-" else sys.stdin) as lines:
            ended = feed(lines, "standard input" if name == "-" else name, stream, check_handed_over)
    except StreamError as e:
        print(f"pkm_feed: {e}", file=sys.stderr)
        return 1
    if not ended:
        print("pkm_feed: the stream ended without its end record: pkmexec stops after the last period",
              file=sys.stderr)
        return 1
    state = outcome(programs_before)
    said = OUTCOMES.get(state, f"ended in state {state}").format(line=hal.get_value("pkmexec.fault-line"))
    print(f"pkm_feed: the program was {said}", file=sys.stdout if state == FINISHED else sys.stderr)
    if turn_on and state != NOT_HANDED_OVER:
        problem = machine_on()
        if problem:
            print(f"pkm_feed: {problem}", file=sys.stderr)
            return 2
    return 0 if state == FINISHED else 2


if __name__ == "__main__":
    sys.exit(main())
