"""pkm.sweep: evaluate a function of a machine variant over a design space (docs/python.md, "Sweeps").

    table = pkm.sweep(evaluate, {"platform_separation_deg": [0, 10, 20, 30], "limits.actuator_max": [800, 900]},
                      base=functools.partial(pkm.layouts.hexapod, 500, 300))

Every point of the space is one variant of the base machine; `evaluate(machine, params)` runs once per point and
returns a dict of scalars (or one scalar, stored as `value`). The table has one row per point, in the points'
order, whichever executor ran them: serial, local processes (the default) or a Dask cluster.
"""


from __future__ import annotations

import math
from collections.abc import Mapping
from numbers import Integral
from typing import Any, Callable, Dict, Optional

from ._sweep_chunks import _Task
from ._sweep_executors import _chunks, _dask_client, _local_workers, _run_dask, _run_processes, _run_serial
from ._sweep_space import _EXECUTORS, MACHINE_KEYS, TASK_POINTS, _Variants, design_points
from ._sweep_table import _table

__all__ = ["sweep", "design_points", "MACHINE_KEYS", "TASK_POINTS"]

# ---- the sweep ----------------------------------------------------------------------------------------------------

def sweep(evaluate: Callable[[Any, Dict[str, Any]], Any], space: Mapping[str, Any], *, base: Any = None,
          method: str = "grid", samples: Optional[int] = None, seed: Any = 0, executor: str = "processes",
          workers: Optional[int] = None, scheduler: Any = None, chunk_size: Optional[int] = None,
          on_error: str = "raise", table: str = "auto") -> Any:
    """Evaluates `evaluate(machine, params)` at every point of a design space; returns the table of results.

    space      dict parameter name -> values. method='grid': a list of values per name, every combination, the
               last name varying fastest. method='random': (low, high) per name, `samples` points drawn uniformly
               with numpy.random.default_rng(seed) (the same seed, the same points).
    base       the machine the variants start from: a machine file path (read once here, so workers need not see
               the file), a machine dict (pkm.read_machine_dict, pkm.layouts), or a callable returning one, such as
               a pkm.layouts function or a functools.partial of one. None: evaluate gets machine=None.
    Parameters act on the machine by their names:
      - names of the callable base's arguments are passed to it (`platform_separation_deg` for layouts.hexapod);
      - paths replace entries of the machine dict: keys joined by dots, list indices in brackets
        (`motion.max_feed_mm_min`, `limits.actuator_max`, `base_joints[2][0]`); a machine file's top-level key
        (`tool`, `home`, `limits`, ...: MACHINE_KEYS) or any top-level key of a dict base replaces it whole;
        missing mappings on the way are created;
      - other names (a law, a feed, a pose) only reach evaluate.
    evaluate   evaluate(machine: pkm.Machine, params: dict) -> dict of scalars (numbers, bools, strings), or one
               scalar (the column `value`). params holds every parameter of the point. With executor='processes'
               it must be picklable: a function defined at module level of an importable module (in a script:
               under `if __name__ == "__main__":` guard the call, as for multiprocessing).
    executor   'serial' (in this process), 'processes' (a concurrent.futures.ProcessPoolExecutor of `workers`
               processes, default one per usable core, started by forkserver or spawn, never fork), or 'dask'
               (dask.distributed: `scheduler` is an address 'tcp://host:8786' or a Client; None: the active one).
    chunk_size points per task; default min(TASK_POINTS, ceil(points / (4 * workers))), so that every worker
               gets several tasks and each task's start-up is small beside its work.
    on_error   'raise': the first failing point (in point order) raises its exception, with a note naming the
               point. 'nan': that row's results are NaN (empty for text) and the `error` column has
               "ExceptionType: message" ('' where the point succeeded). A variant that does not load (e.g. home
               unreachable) counts as a failing point.
    table      'auto': a pandas.DataFrame if pandas imports, else a numpy structured array; 'numpy'; 'pandas'.

    The rows are in the points' order and hold the parameters, then the results (the union of evaluate's keys in
    the order first returned; missing entries NaN). The values do not depend on the executor, workers or chunks.
    """
    if not callable(evaluate):
        raise TypeError(f"pkm.sweep: evaluate must be a function evaluate(machine, params), got "
                        f"{type(evaluate).__name__}")
    if executor not in _EXECUTORS:
        raise ValueError(f"pkm.sweep: executor must be one of {', '.join(_EXECUTORS)}, got {executor!r}")
    if on_error not in ("raise", "nan"):
        raise ValueError(f"pkm.sweep: on_error must be 'raise' or 'nan', got {on_error!r}")
    if table not in ("auto", "numpy", "pandas"):
        raise ValueError(f"pkm.sweep: table must be 'auto', 'numpy' or 'pandas', got {table!r}")
    for label, value in (("workers", workers), ("chunk_size", chunk_size)):
        if value is not None and (isinstance(value, bool) or not isinstance(value, Integral) or value < 1):
            raise ValueError(f"pkm.sweep: {label} must be a positive whole number, got {value!r}")
    if scheduler is not None and executor != "dask":
        raise ValueError("pkm.sweep: scheduler is for executor='dask'")
    names, points = design_points(space, method, samples, seed)
    task = _Task(evaluate, _Variants(base, names), names, on_error)

    client, own_client = (None, False)
    if executor == "dask":
        client, own_client = _dask_client(scheduler)
    try:
        if executor == "serial":
            parallel = 1
        elif executor == "processes":
            parallel = int(workers) if workers else _local_workers()
        else:
            parallel = int(workers) if workers else max(1, sum(client.nthreads().values()))
        size = int(chunk_size) if chunk_size else max(1, min(TASK_POINTS, math.ceil(len(points) / (4 * parallel))))
        spans = _chunks(len(points), size)
        if executor == "serial":
            chunks = _run_serial(task, points, spans)
        elif executor == "processes":
            chunks = _run_processes(task, points, spans, min(parallel, len(spans)))
        else:
            chunks = _run_dask(task, points, spans, client)
    finally:
        if own_client:
            client.close()
    return _table(names, points, chunks, on_error, table)
