"""pkm.sweep's executors: the chunks run serially, on a local process pool or on a Dask cluster."""

from __future__ import annotations

import concurrent.futures
import multiprocessing
import os
import pickle
import sys
from typing import Any, List, Tuple

from ._sweep_chunks import _ChunkResults, _run_chunk, _Task


def _chunks(count: int, size: int) -> List[Tuple[int, int]]:
    return [(start, min(start + size, count)) for start in range(0, count, size)]


def _run_serial(task: _Task, points: List[tuple], spans: List[Tuple[int, int]]) -> List[_ChunkResults]:
    return [_run_chunk(task, start, points[start:stop]) for start, stop in spans]


def _process_context() -> multiprocessing.context.BaseContext:
    # Not fork: the compiled module's TBB threads do not survive a fork of a process that has started them.
    if "forkserver" not in multiprocessing.get_all_start_methods():
        return multiprocessing.get_context("spawn")
    context = multiprocessing.get_context("forkserver")
    # The server imports pkm (and numpy) once, so that every worker forked from it starts with them loaded; it
    # runs nothing, so no TBB thread exists in it. Effective when this sweep starts the server (the default list
    # is ["__main__"]).
    context.set_forkserver_preload(["__main__", __package__ or "pkm"])
    return context


def _defined_interactively(function: Any) -> bool:
    """True for a function of a __main__ that worker processes cannot import (python -c, a REPL, a notebook)."""
    function = getattr(function, "func", function)  # functools.partial
    main = sys.modules.get("__main__")
    return getattr(function, "__module__", None) == "__main__" and not getattr(main, "__file__", None)


def _run_processes(task: _Task, points: List[tuple], spans: List[Tuple[int, int]], workers: int) -> List[_ChunkResults]:
    for label, function in (("evaluate", task.evaluate), ("base", task.variants.base_callable)):
        if function is not None and _defined_interactively(function):
            raise TypeError(f"pkm.sweep: {label} is defined interactively (in __main__ without a file), where worker "
                            f"processes cannot import it; put it in a module, or use executor='serial' or 'dask'")
    try:
        pickle.dumps(task)
    except Exception as error:  # noqa: BLE001 (pickle raises several types)
        raise TypeError(f"pkm.sweep: with executor='processes', evaluate and base must be picklable: define them "
                        f"at module level (not a lambda or a nested function) and import them from a module, or use "
                        f"executor='serial' ({type(error).__name__}: {error})") from None
    with concurrent.futures.ProcessPoolExecutor(max_workers=workers, mp_context=_process_context()) as pool:
        futures = [pool.submit(_run_chunk, task, start, points[start:stop]) for start, stop in spans]
        try:
            return [future.result() for future in futures]
        except BaseException:
            for future in futures:
                future.cancel()
            raise


def _dask_client(scheduler: Any) -> Tuple[Any, bool]:
    try:
        import distributed
    except ImportError:  # pragma: no cover (Debian's python3-distributed is a build dependency)
        raise ImportError("pkm.sweep: executor='dask' needs dask.distributed (Debian: python3-distributed)") from None
    if isinstance(scheduler, distributed.Client):
        return scheduler, False
    if isinstance(scheduler, str):
        return distributed.Client(scheduler), True
    if scheduler is not None:
        raise TypeError(f"pkm.sweep: scheduler must be an address such as 'tcp://host:8786' or a "
                        f"dask.distributed.Client, got {type(scheduler).__name__}")
    try:
        return distributed.default_client(), False
    except ValueError:
        raise ValueError("pkm.sweep: executor='dask' needs scheduler='tcp://host:8786' (or a Client) when no "
                         "dask.distributed.Client is active") from None


def _run_packed_chunk(task_bytes: bytes, first_index: int, points_bytes: bytes) -> bytes:
    """_run_chunk on pickled arguments and result: Dask walks lists and tuples in a task's arguments looking for
    its own keys, which for thousands of points costs more than evaluating them; bytes it passes through."""
    chunk = _run_chunk(pickle.loads(task_bytes), first_index, pickle.loads(points_bytes))
    return pickle.dumps(chunk, protocol=pickle.HIGHEST_PROTOCOL)


def _run_dask(task: _Task, points: List[tuple], spans: List[Tuple[int, int]], client: Any) -> List[_ChunkResults]:
    import cloudpickle  # a dependency of dask.distributed: sends evaluate by value where it must (a lambda)

    task_bytes = cloudpickle.dumps(task, protocol=pickle.HIGHEST_PROTOCOL)
    futures = [client.submit(_run_packed_chunk, task_bytes, start,
                             pickle.dumps(points[start:stop], protocol=pickle.HIGHEST_PROTOCOL), pure=False)
               for start, stop in spans]
    try:
        return [pickle.loads(future.result()) for future in futures]
    except BaseException:
        client.cancel(futures)
        raise


def _local_workers() -> int:
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # pragma: no cover (not Linux)
        return max(1, os.cpu_count() or 1)
