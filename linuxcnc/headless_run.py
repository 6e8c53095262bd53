#!/usr/bin/python3
"""LinuxCNC without a GUI: run programs and record every servo period (docs/linuxcnc.md).

Give this file as LinuxCNC's user interface (`pkm linuxcnc config --display /path/to/headless_run.py`, or
[DISPLAY] DISPLAY in the INI) and start `linuxcnc -r DIR/machine.ini` with these variables set:

  PKM_LINUXCNC_PROGRAM   the G-code program to run; or several, separated by ':', run one after the other:
                         G-code programs by LinuxCNC, pkm execution streams (`pkm linuxcnc stream --to F.stream`)
                         by pkm's executor with linuxcnc/pkm_feed.py --machine-on (with `config --execute`),
                         and the words machine-off and machine-on (LinuxCNC's machine)
  PKM_LINUXCNC_RECORD    the CSV file to write (and beside it RECORD.json, the run's summary)
  PKM_LINUXCNC_TIMEOUT_S give up after this many seconds (default 300)
  PKM_LINUXCNC_OPERATOR  during the first stream, the operator's actions at seconds after it starts:
                         "T:hold=1,T:hold=0,T:override=0.3,T:abort=1" (feed hold, LinuxCNC's feed override, abort)

It loads LinuxCNC's `sampler` into the servo thread, after the motion controller, with the commanded Cartesian
position (axis.L.pos-cmd), each joint's position from the kinematics in that period (joint.N.coarse-pos-cmd),
the joint command after LinuxCNC's interpolation (joint.N.pos-cmd) and the motion controller's time in CPU
clocks; with pkm's executor loaded instead the joint commands, the drives' positions (joint.N.motor-pos-fb),
the executor's counts, whether LinuxCNC's motion is enabled and the executor's state and line; reads the samples through the HAL stream in full double precision (halsampler prints six decimals); then
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

FEEDER = os.path.join(os.path.dirname(os.path.abspath(__file__)), "pkm_feed.py")

AXES = "xyzabc"


def ini_path():
    args = sys.argv[1:]
    return args[args.index("-ini") + 1]


def halcmd(*words):
    subprocess.run(["halcmd", *words], check=True)


def linked_signal(pin):
    """The signal a pin is already linked to (a pin has one), or None."""
    shown = subprocess.run(["halcmd", "-s", "show", "pin", pin], capture_output=True, text=True).stdout.split()
    for arrow in ("<==", "==>", "<=>"):
        if arrow in shown:
            return shown[shown.index(arrow) + 1]
    return None


class Recorder:
    """The sampler's columns: LinuxCNC's motion (its Cartesian command, the kinematics' joints, the interpolated
    joint commands, coordinated mode, its time); with pkm's executor, the joint commands, the drives' positions,
    the executor's counts, motion enabled, the executor's state and line (a HAL stream holds 21 at most)."""

    def __init__(self, joints, executor):
        if executor:
            self.columns = [f"joint_{j}_command" for j in range(joints)]
            self.columns += [f"drive_{j}_position" for j in range(joints)]
            self.columns += [f"pkmexec_{j}_counts" for j in range(joints)]
            self.columns += ["motion_enabled", "pkmexec_state", "pkmexec_line"]
            types = "f" * (2 * joints) + "s" * joints + "bss"
            pins = [f"joint.{j}.pos-cmd" for j in range(joints)]
            pins += [f"joint.{j}.motor-pos-fb" for j in range(joints)]
            pins += [f"pkmexec.{j}.counts" for j in range(joints)]
            pins += ["motion.motion-enabled", "pkmexec.state", "pkmexec.line"]
        else:
            self.columns = [f"axis_{a}_mm_or_deg" for a in AXES]
            self.columns += [f"joint_{j}_kinematics" for j in range(joints)]
            self.columns += [f"joint_{j}_command" for j in range(joints)]
            self.columns += ["coordinated", "motion_controller_clocks"]
            types = "f" * (len(self.columns) - 2) + "bs"
            pins = [f"axis.{a}.pos-cmd" for a in AXES]
            pins += [f"joint.{j}.coarse-pos-cmd" for j in range(joints)]
            pins += [f"joint.{j}.pos-cmd" for j in range(joints)]
            pins += ["motion.coord-mode", "motion-controller.time"]
        halcmd("loadrt", "sampler", "depth=60000", f"cfg={types}")
        halcmd("addf", "sampler.0", "servo-thread")
        for i, pin in enumerate(pins):
            halcmd("net", linked_signal(pin) or f"pkm-record-{i}", pin, "=>", f"sampler.0.pin.{i}")
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


def operator_actions(text):
    """[(seconds, what, value)] from "T:hold=1,T:override=0.3"."""
    actions = []
    for item in filter(None, text.split(",")):
        at, action = item.split(":", 1)
        what, value = action.split("=")
        actions.append((float(at), what, float(value)))
    return sorted(actions)


def act(command, what, value):
    if what == "override":
        command.feedrate(value)  # LinuxCNC's own feed override, which execute.hal gives pkmexec
    else:
        halcmd("sets", {"hold": "pkm-feed-hold", "abort": "pkm-abort"}[what], str(int(value)))


def run_stream(path, stat, command, recorder, timeout_s, actions):
    """Feeds a pkm execution stream to pkmexec and waits for its end; pkm_feed.py's exit status and words."""
    stat.poll()
    if stat.task_state == linuxcnc.STATE_ON:
        # As an operator would, the stream starts once LinuxCNC has settled after what ran before (halui's idle
        # pin and motion's in-position follow the task's own state a few of their periods later, longer on a
        # loaded machine). A hand-over that never comes is pkm_feed's to report.
        try:
            wait_for(lambda s: hal.get_value("pkmexec.enable"), stat, recorder, 5, "the hand-over to pkmexec")
        except TimeoutError:
            pass
    feeder = subprocess.Popen(["/usr/bin/python3", FEEDER, "--machine-on", path], stdout=subprocess.PIPE,
                              stderr=subprocess.STDOUT, text=True)
    started = time.monotonic()
    pending = list(actions)
    while feeder.poll() is None:
        if time.monotonic() - started > timeout_s:
            feeder.kill()
            raise TimeoutError(f"timed out executing {path}")
        while pending and time.monotonic() - started >= pending[0][0]:
            act(command, *pending.pop(0)[1:])
        stat.poll()
        recorder.drain()
        time.sleep(0.01)
    return {"stream": path, "exit": feeder.returncode, "said": feeder.stdout.read().strip()}


def run_gcode(program, stat, command, recorder, timeout_s):
    command.mode(linuxcnc.MODE_AUTO)
    command.wait_complete()
    command.program_open(program)
    command.wait_complete()
    command.auto(linuxcnc.AUTO_RUN, 0)
    # Running until the interpreter is idle again and motion has stopped, or an error stops the machine.
    wait_for(lambda s: s.interp_state != linuxcnc.INTERP_IDLE or s.task_state != linuxcnc.STATE_ON,
             stat, recorder, 10, "the program to start")
    wait_for(lambda s: (s.interp_state == linuxcnc.INTERP_IDLE and s.inpos) or s.task_state != linuxcnc.STATE_ON,
             stat, recorder, timeout_s, "the program to end")
    stat.poll()
    return {"program": program, "state_on": stat.task_state == linuxcnc.STATE_ON}


def fk_failures(kinematics):
    """pkmkins' forward solves that failed so far (before homing the joints are not a pose at all)."""
    if kinematics != "pkmkins":
        return None
    got = subprocess.run(["halcmd", "getp", "pkmkins.fk-failures"], capture_output=True, text=True)
    return int(got.stdout.strip() or "-1", 0)


def home_all(stat, command, recorder, joints, summary):
    command.state(linuxcnc.STATE_ESTOP_RESET)
    command.state(linuxcnc.STATE_ON)
    command.wait_complete()
    command.home(-1)
    wait_for(lambda s: all(s.homed[:joints]), stat, recorder, 90, "homing")
    summary["homed"] = True
    summary["homed_joints"] = list(stat.joint_actual_position[:joints])
    # joint = motor position − motor offset: what homing made of the motors' positions.
    summary["motor_offsets"] = [hal.get_value(f"joint.{j}.motor-offset") for j in range(joints)]
    summary["homed_position"] = list(stat.position[:6])


def main():
    programs = [p for p in os.environ["PKM_LINUXCNC_PROGRAM"].split(":") if p]
    record = os.environ["PKM_LINUXCNC_RECORD"]
    timeout_s = float(os.environ.get("PKM_LINUXCNC_TIMEOUT_S", "300"))
    actions = operator_actions(os.environ.get("PKM_LINUXCNC_OPERATOR", ""))
    ini = linuxcnc.ini(ini_path())
    joints = int(ini.find("KINS", "JOINTS"))
    summary = {"program": programs[0], "programs": [], "errors": [], "homed": False, "finished": False,
               "joints": joints, "kinematics": ini.find("KINS", "KINEMATICS").split()[0]}
    stat, command, errors = linuxcnc.stat(), linuxcnc.command(), linuxcnc.error_channel()
    components = subprocess.run(["halcmd", "list", "comp"], capture_output=True, text=True).stdout.split()
    recorder = Recorder(joints, "pkmexec" in components)
    started = time.monotonic()

    def collect_errors():
        while True:
            e = errors.poll()
            if not e:
                return
            summary["errors"].append(e[1].strip())

    try:
        home_all(stat, command, recorder, joints, summary)
        recorder.recording = True
        summary["pkmkins_fk_failures_homed"] = fk_failures(summary["kinematics"])
        for program in programs:
            remaining = timeout_s - (time.monotonic() - started)
            if program in ("machine-off", "machine-on"):
                command.state(linuxcnc.STATE_OFF if program == "machine-off" else linuxcnc.STATE_ON)
                command.wait_complete()
                summary["programs"].append({"program": program})
            elif program.endswith(".stream"):
                summary["programs"].append(run_stream(program, stat, command, recorder, remaining, actions))
                actions = []
            else:
                summary["programs"].append(run_gcode(program, stat, command, recorder, remaining))
            collect_errors()
        time.sleep(0.05)
        recorder.drain()
        collect_errors()
        stat.poll()
        summary["final_joints"] = list(stat.joint_actual_position[:joints])
        summary["final_position"] = list(stat.position[:6])
        # LinuxCNC reports its motion disabled each time pkm's executor takes the drives: not an error of the run.
        handovers = [e for e in summary["errors"] if "motion stopped by enable input" in e]
        summary["handovers"] = len(handovers)
        summary["errors"] = [e for e in summary["errors"] if e not in handovers]
        summary["finished"] = (stat.task_state == linuxcnc.STATE_ON and not summary["errors"]
                               and all(p.get("exit", 0) == 0 and p.get("state_on", True) for p in summary["programs"]))
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
