"""The README's LinuxCNC commands, run in order as a user would type them (README.md, "LinuxCNC").

The first block is for a desktop user: as root and without an X display LinuxCNC cannot run it, and
`pkm linuxcnc config` says so with what to do instead. The second block is that: it must run here, as root
and headless, and run the five-axis example program to its end through pkmkins.
"""
import json
import os
import re
import shutil
import subprocess
import tempfile

from linuxcnc_run import PKM, SOURCE_DIR, ensure_module_installed, rtapi_processes

TIMEOUT_S = 300


def readme_blocks():
    """The sh code blocks of the README's LinuxCNC section, each a list of command lines."""
    with open(os.path.join(SOURCE_DIR, "README.md")) as f:
        text = f.read()
    section = re.search(r"^## LinuxCNC\n(.*?)^## ", text, re.S | re.M).group(1)
    blocks = re.findall(r"```sh\n(.*?)```", section, re.S)
    return [[line.split("  #")[0].strip() for line in b.splitlines() if line.strip()] for b in blocks]


def as_typed(command):
    """The command as the README has it, with this build's pkm for `build/pkm`."""
    return command.replace("build/pkm ", PKM + " ", 1) if command.startswith("build/pkm ") else command


def shell(command, env, timeout_s=TIMEOUT_S):
    return subprocess.run(["bash", "-c", command], cwd=SOURCE_DIR, env=env, capture_output=True, text=True,
                          timeout=timeout_s, start_new_session=True)


def tear_down(env):
    """Whatever LinuxCNC left in the real-time layer goes (as linuxcnc_run.py does after every run)."""
    subprocess.run(["halrun", "-U"], env=env, capture_output=True, timeout=60)
    if os.path.exists("/tmp/linuxcnc.lock"):
        os.remove("/tmp/linuxcnc.lock")


def test_the_readme_linuxcnc_commands_run_in_order():
    ensure_module_installed()
    blocks = readme_blocks()
    assert len(blocks) == 2, blocks
    desktop, headless = blocks
    home = tempfile.mkdtemp(prefix="pkm-readme-home-")
    env = dict(os.environ, HOME=home)
    env.pop("DISPLAY", None)
    for name in ("RTAPI_UID", "RTAPI_FIFO_PATH", "PKM_LINUXCNC_PROGRAM", "PKM_LINUXCNC_RECORD"):
        env.pop(name, None)
    try:
        # The desktop block's configuration is written; here (no X display, and as root in CI) pkm warns with
        # what to do instead, which is the README's second block.
        config, start = desktop
        done = shell(as_typed(config), env)
        assert done.returncode == 0, done.stderr
        assert os.path.exists(os.path.join(home, "linuxcnc/configs/ch5-hexapod/machine.ini"))
        assert "warning: the display axis needs an X display" in done.stderr, done.stderr
        if os.geteuid() == 0:
            assert "RTAPI_UID=$(id -u nobody) RTAPI_FIFO_PATH=" in done.stdout, done.stdout
        assert start.startswith("linuxcnc ")

        # The headless block, as written, to the end of the example program.
        out_dir = None
        for command in headless:
            typed = as_typed(command)
            if typed.startswith(PKM):
                out_dir = re.search(r"--out (\S+)", typed).group(1)
                if os.path.isdir(out_dir):
                    shutil.rmtree(out_dir)
            done = shell(typed, env)
            tear_down(dict(env, RTAPI_UID="65534", RTAPI_FIFO_PATH="/tmp/linuxcnc-rtapi.fifo"))
            assert done.returncode == 0, (command, done.stdout[-3000:], done.stderr[-3000:])
        record = re.search(r"PKM_LINUXCNC_RECORD=(\S+)", " ".join(headless)).group(1)
        with open(record + ".json") as f:
            summary = json.load(f)
        assert summary["kinematics"] == "pkmkins"
        assert summary["homed"] and summary["finished"] and summary["errors"] == [], summary
        assert rtapi_processes() == []
        shutil.rmtree(out_dir, ignore_errors=True)
    finally:
        shutil.rmtree(home, ignore_errors=True)
