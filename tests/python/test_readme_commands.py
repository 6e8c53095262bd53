"""The README's command-line block, run in order as a user would type it (README.md, "Command line").

Each line runs with its optional [bracketed] arguments left out, in a fresh folder that sees the repository's
examples/, with this build's pkm for `build/pkm`; every command must succeed, and the folders the commands
write must each hold one complete output set (a manifest that lists every file of the folder). A line with a
placeholder (`...`) is the README's sketch of a variant, not a command.
"""
import json
import os
import re
import shlex
import subprocess
from pathlib import Path

SOURCE = Path(os.environ.get("PKM_SOURCE_DIR", Path(__file__).resolve().parents[2]))
PKM = os.environ.get("PKM_BINARY", "pkm")
TIMEOUT_S = 600


def readme_commands():
    """The command lines of the README's "Command line" sh block, optional arguments and comments removed."""
    text = (SOURCE / "README.md").read_text()
    section = re.search(r"^## Command line\n(.*?)^## ", text, re.S | re.M).group(1)
    block = re.search(r"```sh\n(.*?)```", section, re.S).group(1)
    commands = []
    for line in block.splitlines():
        line = line.split(" # ")[0].strip()
        if not line or " ... " in line:
            continue
        commands.append(re.sub(r"\s\[[^\]]*\]", "", line))
    return commands


def test_the_readme_command_line_block_runs_in_order(tmp_path):
    (tmp_path / "examples").symlink_to(SOURCE / "examples")
    commands = readme_commands()
    assert len(commands) >= 15, commands
    for command in commands:
        assert command.startswith("build/pkm "), command
        args = shlex.split(command)[1:]
        run = subprocess.run([PKM, *args], cwd=tmp_path, capture_output=True, text=True, timeout=TIMEOUT_S)
        assert run.returncode == 0, f"{command}\n{run.stdout[-2000:]}\n{run.stderr[-2000:]}"
    # Every folder a command wrote holds one complete set: its manifest names every file in it.
    folders = [p for p in tmp_path.iterdir() if p.is_dir() and not p.is_symlink()]
    assert {p.name for p in folders} >= {"run", "steps", "stiffness", "ws"}
    for folder in folders:
        manifest = json.loads((folder / "manifest.json").read_text())
        listed = {entry["name"] if isinstance(entry, dict) else entry for entry in manifest["files"]}
        present = {str(p.relative_to(folder)) for p in folder.rglob("*")
                   if p.is_file() and p.name not in ("manifest.json", ".pkm-lock")}
        assert present <= listed | {"manifest.json"}, (folder.name, sorted(present - listed))
