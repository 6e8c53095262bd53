"""What the Python examples share: their command line, the pkm import with a hint, and writing the plot and the
key numbers (docs/python.md, "Examples")."""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

REPOSITORY = Path(__file__).resolve().parents[2]


def import_pkm():
    """pkm, or exit 2 with how to build it."""
    try:
        import pkm
    except ImportError as error:
        sys.exit(f"cannot import pkm ({error}): build it with `make python` and run "
                 f"`PYTHONPATH=build/python /usr/bin/python3 {sys.argv[0]}`")
    return pkm


def arguments(description: str, sweep: bool = True, extra=None) -> argparse.Namespace:
    """--out, --quick; with sweep, pkm.sweep's --executor, --workers, --scheduler; extra(parser) adds more."""
    parser = argparse.ArgumentParser(description=description)
    parser.add_argument("--out", default=".", help="folder for the PNG plot and the JSON summary (default: .)")
    parser.add_argument("--quick", action="store_true", help="a coarse run in seconds (the tests use it)")
    if extra:
        extra(parser)
    if not sweep:
        return parser.parse_args()
    parser.add_argument("--executor", default="processes", choices=("serial", "processes", "dask"),
                        help="pkm.sweep's executor (default: local processes)")
    parser.add_argument("--workers", type=int, default=None, help="local worker processes (default: one per core)")
    parser.add_argument("--scheduler", default=None, help="Dask scheduler address, e.g. tcp://host:8786")
    return parser.parse_args()


def sweep_options(args: argparse.Namespace) -> dict:
    options = {"executor": args.executor, "workers": args.workers}
    if args.executor == "dask":
        options["scheduler"] = args.scheduler
    return options


def pyplot():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def write_outputs(out: str, name: str, figure, summary: dict) -> Path:
    """<out>/<name>.png and <out>/<name>.json; returns the PNG's path."""
    folder = Path(out)
    folder.mkdir(parents=True, exist_ok=True)
    png = folder / f"{name}.png"
    figure.savefig(png, dpi=120, bbox_inches="tight")
    (folder / f"{name}.json").write_text(json.dumps(summary, indent=2) + "\n")
    print(f"wrote {png} and {name}.json")
    return png
