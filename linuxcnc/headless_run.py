#!/usr/bin/python3
"""LinuxCNC without a GUI: run one G-code program and record every servo period (docs/linuxcnc.md).

Give this file as LinuxCNC's user interface (`pkm linuxcnc config --display /path/to/headless_run.py`, or
[DISPLAY] DISPLAY in the INI) and start `linuxcnc -r DIR/machine.ini` with these variables set:

  PKM_LINUXCNC_PROGRAM   the G-code program to run
  PKM_LINUXCNC_RECORD    the CSV file to write (and beside it RECORD.json, the run's summary)
  PKM_LINUXCNC_TIMEOUT_S give up after this many seconds (default 300)

It loads LinuxCNC's `sampler` into the servo thread, after the motion controller, with the commanded Cartesian
position (axis.L.pos-cmd), each joint's position from the kinematics in that period (joint.N.coarse-pos-cmd),
the joint command after LinuxCNC's interpolation (joint.N.pos-cmd) and the motion controller's time in CPU
clocks; reads the samples through the HAL stream in full double precision (halsampler prints six decimals); then
resets E-stop, turns the machine on, homes all joints, runs the program and writes the CSV and the summary. It
exits when the program ends, fails or times out, and LinuxCNC then shuts down.
"""
import json
import os
import subprocess
import sys
import time

import hal
import linuxcnc

AXES = "xyzabc"


def ini_path():
    args = sys.argv[1:]
    return args[args.index("-ini") + 1]


def halcmd(*words):
    subprocess.run(["halcmd", *words], check=True)


class Recorder:
    def __init__(self, joints):
        self.columns = [f"axis_{a}_mm_or_deg" for a in AXES]
        self.columns += [f"joint_{j}_kinematics" for j in range(joints)]
        self.columns += [f"joint_{j}_command" for j in range(joints)]
        self.columns += ["coordinated", "motion_controller_clocks"]
        types = "f" * (len(self.columns) - 2) + "bs"
        halcmd("loadrt", "sampler", "depth=60000", f"cfg={types}")
        halcmd("addf", "sampler.0", "servo-thread")
        pins = [f"axis.{a}.pos-cmd" for a in AXES]
        pins += [f"joint.{j}.coarse-pos-cmd" for j in range(joints)]
        pins += [f"joint.{j}.pos-cmd" for j in range(joints)]
        pins += ["motion.coord-mode", "motion-controller.time"]
        for i, pin in enumerate(pins):
            halcmd("net", f"pkm-record-{i}", pin, "=>", f"sampler.0.pin.{i}")
        self.component = hal.component("pkmrecord")
        self.component.ready()
        self.stream = hal.stream(self.component, hal.sampler_base + 0, types)
        self.rows = []
        self.recording = False

    def drain(self):
        while True:
            row = self.stream.read()
            if row is None:
                return
            if self.recording:
                self.rows.append(row)

    def overruns(self):
        return self.stream.num_overruns


def wait_for(condition, stat, recorder, timeout_s, what):
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        stat.poll()
        recorder.drain()
        if condition(stat):
            return
        time.sleep(0.01)
    raise TimeoutError(f"timed out waiting for {what}")


def write_atomically(path, text):
    temporary = path + ".part"
    with open(temporary, "w") as f:
        f.write(text)
    os.replace(temporary, path)


def main():
    program = os.environ["PKM_LINUXCNC_PROGRAM"]
    record = os.environ["PKM_LINUXCNC_RECORD"]
    timeout_s = float(os.environ.get("PKM_LINUXCNC_TIMEOUT_S", "300"))
    ini = linuxcnc.ini(ini_path())
    joints = int(ini.find("KINS", "JOINTS"))
    summary = {"program": program, "errors": [], "homed": False, "finished": False, "joints": joints,
               "kinematics": ini.find("KINS", "KINEMATICS").split()[0]}
    stat, command, errors = linuxcnc.stat(), linuxcnc.command(), linuxcnc.error_channel()
    recorder = Recorder(joints)
    started = time.monotonic()

    def collect_errors():
        while True:
            e = errors.poll()
            if not e:
                return
            summary["errors"].append(e[1].strip())

    try:
        command.state(linuxcnc.STATE_ESTOP_RESET)
        command.state(linuxcnc.STATE_ON)
        command.wait_complete()
        command.home(-1)
        wait_for(lambda s: all(s.homed[:joints]), stat, recorder, 90, "homing")
        summary["homed"] = True
        summary["homed_joints"] = list(stat.joint_actual_position[:joints])
        # joint = motor position − motor offset: what homing made of the motors' positions.
        summary["motor_offsets"] = [float(subprocess.run(["halcmd", "getp", f"joint.{j}.motor-offset"],
                                                         capture_output=True, text=True).stdout.strip() or "nan")
                                    for j in range(joints)]
        summary["homed_position"] = list(stat.position[:6])
        command.mode(linuxcnc.MODE_AUTO)
        command.wait_complete()
        command.program_open(program)
        command.wait_complete()
        recorder.recording = True
        command.auto(linuxcnc.AUTO_RUN, 0)
        # Running until the interpreter is idle again and motion has stopped, or an error stops the machine.
        wait_for(lambda s: s.interp_state != linuxcnc.INTERP_IDLE or s.task_state != linuxcnc.STATE_ON,
                 stat, recorder, 10, "the program to start")
        remaining = timeout_s - (time.monotonic() - started)
        wait_for(lambda s: (s.interp_state == linuxcnc.INTERP_IDLE and s.inpos) or s.task_state != linuxcnc.STATE_ON,
                 stat, recorder, remaining, "the program to end")
        time.sleep(0.05)
        recorder.drain()
        collect_errors()
        stat.poll()
        summary["final_joints"] = list(stat.joint_actual_position[:joints])
        summary["final_position"] = list(stat.position[:6])
        summary["finished"] = stat.task_state == linuxcnc.STATE_ON and not summary["errors"]
    except Exception as exc:  # recorded, never raised: LinuxCNC must shut down either way
        collect_errors()
        summary["errors"].append(f"driver: {exc}")
    if summary["kinematics"] == "pkmkins":
        # The module's counters: forward solves and failures over the whole run (homing included).
        for pin in ("fk-solves", "fk-failures"):
            got = subprocess.run(["halcmd", "getp", f"pkmkins.{pin}"], capture_output=True, text=True)
            summary[f"pkmkins_{pin.replace('-', '_')}"] = int(got.stdout.strip() or "-1", 0)
    summary["samples"] = len(recorder.rows)
    summary["overruns"] = recorder.overruns()
    lines = [",".join(recorder.columns)]
    lines += [",".join(repr(int(v)) if isinstance(v, bool) else repr(v) for v in row) for row in recorder.rows]
    write_atomically(record, "\n".join(lines) + "\n")
    write_atomically(record + ".json", json.dumps(summary, indent=2) + "\n")
    command.state(linuxcnc.STATE_OFF)


if __name__ == "__main__":
    main()
