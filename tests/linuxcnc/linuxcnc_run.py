"""Runs LinuxCNC headless on a configuration written by `pkm linuxcnc config` (docs/linuxcnc.md).

Each run gets its own world-readable folder in /tmp: rtapi_app, started as root, drops to RTAPI_UID (nobody)
and must then still read the machine file that pkmkins loads and create its socket, RTAPI_FIFO_PATH. The run is
bounded in time and always torn down: when LinuxCNC does not end by itself, its process group is killed and
`halrun -U` unloads whatever is left in the real-time layer.
"""
import json
import os
import shutil
import signal
import subprocess
import tempfile
from dataclasses import dataclass, field

import numpy as np

SOURCE_DIR = os.environ["PKM_SOURCE_DIR"]
PKM = os.environ["PKM_BINARY"]
BUILT_MODULE = os.environ["PKM_KINS_MODULE"]
MODULES_DIR = "/usr/lib/linuxcnc/modules"
DRIVER = os.path.join(SOURCE_DIR, "linuxcnc", "headless_run.py")
NOBODY_UID = "65534"


def machine_path(name):
    return os.path.join(SOURCE_DIR, "examples", "machines", name)


def program_path(name):
    return os.path.join(SOURCE_DIR, "examples", "programs", name)


def ensure_installed(built_module, name):
    """rtapi_app loads modules only from LinuxCNC's module folder (no paths in module names): the module built
    in `built_module` must be the one installed there as `name` (`make linuxcnc`; make test does it)."""
    installed = os.path.join(MODULES_DIR, name)
    with open(built_module, "rb") as f:
        built = f.read()
    if os.path.exists(installed):
        with open(installed, "rb") as f:
            if f.read() == built:
                return
    if os.geteuid() != 0:
        raise RuntimeError(f"{installed} is not the module built in {built_module}: run `sudo make linuxcnc`")
    shutil.copyfile(built_module, installed)


def ensure_module_installed():
    ensure_installed(BUILT_MODULE, "pkmkins.so")


@dataclass
class Run:
    returncode: int
    log: str
    config_dir: str
    summary: dict = field(default_factory=dict)
    columns: list = field(default_factory=list)
    samples: np.ndarray = None

    def column(self, name):
        return self.samples[:, self.columns.index(name)]

    def axes(self):
        """Commanded Cartesian positions (x, y, z mm; a, b, c deg) per servo period."""
        return np.column_stack([self.column(f"axis_{a}_mm_or_deg") for a in "xyzabc"])

    def joints(self, kind="kinematics"):
        n = self.summary["joints"]
        return np.column_stack([self.column(f"joint_{j}_{kind}") for j in range(n)])


def write_config(machine, out_dir, kinematics="pkmkins", extra_args=()):
    subprocess.run([PKM, "linuxcnc", "config", "--machine", machine, "--out", out_dir, "--kinematics", kinematics,
                    "--display", DRIVER, *extra_args], check=True, capture_output=True, text=True)


def _environment(work_dir, program, record, timeout_s, operator=""):
    env = dict(os.environ)
    if os.geteuid() == 0:
        env["RTAPI_UID"] = NOBODY_UID  # rtapi_app refuses to run as root without a fallback uid
    env["RTAPI_FIFO_PATH"] = os.path.join(work_dir, ".rtapi_fifo")  # the socket itself, not a folder
    env["PKM_LINUXCNC_PROGRAM"] = program
    env["PKM_LINUXCNC_RECORD"] = record
    env["PKM_LINUXCNC_TIMEOUT_S"] = str(timeout_s)
    env["PKM_LINUXCNC_OPERATOR"] = operator
    env.pop("DISPLAY", None)
    return env


def _tear_down(env):
    subprocess.run(["halrun", "-U"], env=env, capture_output=True, timeout=60)
    lock = "/tmp/linuxcnc.lock"
    if os.path.exists(lock):
        os.remove(lock)


def run_linuxcnc(machine, program, kinematics="pkmkins", edit_config=None, timeout_s=120, config_args=(),
                 operator=""):
    """Writes the configuration, runs `program` on it (or several, ':'-separated: G-code, and pkm execution
    streams with `--execute`) and returns the recorded run. `edit_config(dir)` may change the written files
    first (the tests of bad machines); `operator` is headless_run.py's PKM_LINUXCNC_OPERATOR."""
    ensure_module_installed()
    if "--execute" in config_args:
        ensure_installed(os.environ["PKM_EXEC_MODULE"], "pkmexec.so")
    work_dir = tempfile.mkdtemp(prefix="pkm-linuxcnc-", dir="/tmp")
    os.chmod(work_dir, 0o777)
    config_dir = os.path.join(work_dir, "config")
    write_config(machine, config_dir, kinematics, config_args)
    if edit_config:
        edit_config(config_dir)
    os.chmod(config_dir, 0o777)
    for name in os.listdir(config_dir):
        os.chmod(os.path.join(config_dir, name), 0o644)
    record = os.path.join(work_dir, "record.csv")
    env = _environment(work_dir, program, record, timeout_s, operator)
    _tear_down(env)  # a run killed earlier must not block this one
    process = subprocess.Popen(["linuxcnc", "-r", os.path.join(config_dir, "machine.ini")], env=env, cwd=config_dir,
                               stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, start_new_session=True)
    try:
        log, _ = process.communicate(timeout=timeout_s + 60)
    except subprocess.TimeoutExpired:
        os.killpg(process.pid, signal.SIGKILL)
        log, _ = process.communicate()
        log += "\n(killed: LinuxCNC did not end in time)"
    finally:
        _tear_down(env)
    run = Run(process.returncode, log, config_dir)
    if os.path.exists(record + ".json"):
        with open(record + ".json") as f:
            run.summary = json.load(f)
        with open(record) as f:
            run.columns = f.readline().strip().split(",")
        run.samples = np.loadtxt(record, delimiter=",", skiprows=1, ndmin=2)
    return run


def rtapi_processes():
    """Live rtapi_app processes (zombies, already ended, are not left behind)."""
    listing = subprocess.run(["ps", "-eo", "pid=,stat=,comm="], capture_output=True, text=True).stdout
    return [line.split()[0] for line in listing.splitlines()
            if line.split()[2:] == ["rtapi_app"] and not line.split()[1].startswith("Z")]
