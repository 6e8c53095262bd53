"""pkm's executor pkmexec in LinuxCNC's real-time layer, without the rest of LinuxCNC (docs/linuxcnc.md).

A HalSession starts LinuxCNC's realtime environment (rtapi_app, as `halrun` does), a 1 ms servo thread with
pkmexec and LinuxCNC's `sampler` after it, recording pkmexec's pins every period; `pkm linuxcnc stream` feeds it
through linuxcnc/pkm_feed.py. Each session has its own world-readable folder in /tmp (rtapi_app drops to
RTAPI_UID and must still read the machine file), is bounded in time, and is always torn down (`halrun -U`).
"""
import os
import shutil
import subprocess
import tempfile
import time

import hal
import numpy as np

from linuxcnc_run import NOBODY_UID, PKM, SOURCE_DIR, ensure_installed, rtapi_processes

BUILT_EXEC_MODULE = os.environ["PKM_EXEC_MODULE"]
FEEDER = os.path.join(SOURCE_DIR, "linuxcnc", "pkm_feed.py")
REALTIME = "/usr/lib/linuxcnc/realtime"
DRIVES = 6
COLUMNS = ([f"counts_{j}" for j in range(DRIVES)] + [f"set_point_{j}" for j in range(DRIVES)] +
           ["state", "tau", "exec_time_ns", "line", "factor"])
PINS = ([f"pkmexec.{j}.counts" for j in range(DRIVES)] + [f"pkmexec.{j}.set-point" for j in range(DRIVES)] +
        ["pkmexec.state", "pkmexec.tau", "pkmexec.exec-time-ns", "pkmexec.line", "pkmexec.factor"])
TYPES = "s" * DRIVES + "f" * DRIVES + "sfssf"
IDLE, RUNNING, STARVED, FINISHED, ABORTED, STOPPED_AT_LIMIT, REFUSED = range(7)


def write_stream(machine, program, stream_path, out_dir=None):
    """`pkm linuxcnc stream` of a program into a file; returns the completed process."""
    command = [PKM, "linuxcnc", "stream", "--machine", machine, program, "--to", stream_path]
    if out_dir:
        command += ["--out", out_dir]
    return subprocess.run(command, capture_output=True, text=True, timeout=600)


def stream_periods(stream_path):
    """The whole-step positions and ideal values of every period of a stream, and its start."""
    start, positions, ideal, lines = None, [], [], []
    with open(stream_path) as f:
        for text in f:
            fields = text.strip().split(",")
            if fields[0] == "start":
                start = [int(v) for v in fields[1:]]
            elif fields[0] == "p":
                lines.append(int(fields[1]))
                ideal.append([float(v) for v in fields[2:2 + DRIVES]])
                positions.append([int(v) for v in fields[2 + DRIVES:]])
    return np.array(start), np.array(positions), np.array(ideal), np.array(lines)


class HalSession:
    def __init__(self, machine_file, period_ns=1_000_000):
        ensure_installed(BUILT_EXEC_MODULE, "pkmexec.so")
        self.work_dir = tempfile.mkdtemp(prefix="pkm-hal-", dir="/tmp")
        os.chmod(self.work_dir, 0o777)
        self.machine = os.path.join(self.work_dir, os.path.basename(machine_file))
        shutil.copyfile(machine_file, self.machine)
        os.chmod(self.machine, 0o644)
        self.period_ns = period_ns
        self.env = dict(os.environ)
        if os.geteuid() == 0:
            self.env["RTAPI_UID"] = NOBODY_UID
        self.env["RTAPI_FIFO_PATH"] = os.path.join(self.work_dir, ".rtapi_fifo")
        os.environ.update({k: self.env[k] for k in ("RTAPI_FIFO_PATH", "RTAPI_UID") if k in self.env})
        self.rows = []
        self.stream = None

    def hal_file(self):
        lines = [f"loadrt threads name1=servo-thread period1={self.period_ns}",
                 f"loadrt pkmexec machine={self.machine} period_ns={self.period_ns}",
                 f"loadrt sampler depth=100000 cfg={TYPES}",
                 "addf pkmexec.update servo-thread", "addf sampler.0 servo-thread"]
        lines += [f"net pkm-record-{i} {pin} => sampler.0.pin.{i}" for i, pin in enumerate(PINS)]
        # Simulated drives: each is where pkmexec commands it, and pkmexec follows it between programs.
        lines += [f"net pkm-drive-{j} pkmexec.{j}.pos-cmd => pkmexec.{j}.pos-fb" for j in range(DRIVES)]
        return "\n".join(lines + ["start"]) + "\n"

    def __enter__(self):
        self.tear_down()  # a session killed earlier must not block this one
        path = os.path.join(self.work_dir, "pkmexec.hal")
        with open(path, "w") as f:
            f.write(self.hal_file())
        # rtapi_app stays running and keeps whatever output it was started with: a file, not a pipe (a pipe
        # would never reach its end while the session runs).
        self.log = os.path.join(self.work_dir, "hal.log")
        with open(self.log, "w") as log:
            subprocess.run([REALTIME, "start"], env=self.env, check=True, stdout=log, stderr=log, timeout=60)
            loaded = subprocess.run(["halcmd", "-f", path], env=self.env, stdout=log, stderr=log, timeout=60)
        if loaded.returncode != 0:
            with open(self.log) as log:
                raise RuntimeError(f"halcmd -f {path} failed:\n{log.read()[-3000:]}")
        self.component = hal.component(f"pkmrecord{os.getpid()}")
        self.component.ready()
        self.stream = hal.stream(self.component, hal.sampler_base + 0, TYPES)
        return self

    def __exit__(self, *exc):
        # The recorder leaves HAL first: `halrun -U` interrupts the processes of the components still there.
        self.stream = None
        self.component.exit()
        self.tear_down()
        shutil.rmtree(self.work_dir, ignore_errors=True)
        return False

    def tear_down(self):
        subprocess.run(["halrun", "-U"], env=self.env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                       timeout=60)

    def setp(self, pin, value):
        subprocess.run(["halcmd", "setp", pin, str(value)], env=self.env, check=True, stdout=subprocess.DEVNULL,
                       stderr=subprocess.DEVNULL, timeout=30)

    def feed(self, stream_path):
        """Starts the feeder on a stream file; returns its process."""
        return subprocess.Popen(["/usr/bin/python3", FEEDER, stream_path], env=self.env,
                                stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)

    def drain(self):
        while True:
            row = self.stream.read()
            if row is None:
                return
            self.rows.append(row)

    def record_until(self, done, timeout_s, every=None):
        """Records the sampled periods until done(rows) holds; `every(session)` is called between drains."""
        deadline = time.monotonic() + timeout_s
        while time.monotonic() < deadline:
            self.drain()
            if self.rows and done(self.rows):
                return self.table()
            if every:
                every(self)
            time.sleep(0.005)
        raise TimeoutError(f"pkmexec did not get there in {timeout_s} s (state {self.rows[-1][12] if self.rows else None})")

    def table(self):
        return {name: np.array([row[i] for row in self.rows]) for i, name in enumerate(COLUMNS)}


def ended(rows, states=(FINISHED, ABORTED, STOPPED_AT_LIMIT, REFUSED), after=0):
    return len(rows) > after and rows[-1][12] in states


__all__ = ["HalSession", "write_stream", "stream_periods", "ended", "rtapi_processes"]
