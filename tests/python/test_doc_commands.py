"""scripts/doc-commands.py reads the documentation's commands as a reader types them."""
import importlib.util
import pathlib

SCRIPT = pathlib.Path(__file__).resolve().parents[2] / "scripts" / "doc-commands.py"
spec = importlib.util.spec_from_file_location("doc_commands", SCRIPT)
doc_commands = importlib.util.module_from_spec(spec)
spec.loader.exec_module(doc_commands)

DOC = """# A document

```sh
pkm plan a.ngc --machine m.yaml \\
    --out run/          # a comment stays with its command
# a comment line alone is not a command

pkm report run/
```

```text
pkm plan PROGRAM [--json]
```

1. In a list:
   ```sh
   make linuxcnc
   ```
```yaml
key: value
```
"""


def test_sh_blocks_give_commands_with_their_lines_and_continuations_joined(tmp_path):
    doc = tmp_path / "doc.md"
    doc.write_text(DOC, encoding="utf-8")
    blocks = doc_commands.blocks_of(doc)
    assert [commands for _, commands in blocks] == [
        [(4, "pkm plan a.ngc --machine m.yaml --out run/          # a comment stays with its command"),
         (8, "pkm report run/")],
        [(17, "make linuxcnc")],
    ]


def test_only_the_listed_commands_are_left_out():
    assert doc_commands.allowed_reason("make test")
    assert doc_commands.allowed_reason("sudo apt install ./build/pkm_0.1.0_amd64.deb")
    assert doc_commands.allowed_reason("RTAPI_UID=$(id -u nobody) RTAPI_FIFO_PATH=/tmp/f linuxcnc /tmp/c/machine.ini")
    assert doc_commands.allowed_reason("linuxcnc ~/linuxcnc/configs/ch5-hexapod/machine.ini")
    assert doc_commands.allowed_reason("pkm plan a.ngc --machine m.yaml --out run/") is None
    assert doc_commands.allowed_reason("build/pkm linuxcnc config --machine m.yaml --out c") is None
    assert doc_commands.allowed_reason("python3 -c 'import pkm'") is None


def test_every_shipped_document_has_runnable_commands_and_no_synopsis_in_them():
    commands = [c for p in doc_commands.documents(None) for _, block in doc_commands.blocks_of(p) for _, c in block]
    assert len(commands) > 40
    # Synopses ([--option], placeholders) belong in text blocks: a reader cannot type them.
    assert not [c for c in commands if "[--" in c or " DIR" in c or "M.yaml" in c]
