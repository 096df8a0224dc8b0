"""Running a sweep's chunks: worker threads in this process or tasks on a Dask cluster."""

from __future__ import annotations

import os
import sys
from collections import OrderedDict


from ..errors import CaseError
from .sweep_grid import _sha
from .sweep_plan import _PARALLEL_MIN_POINTS, _SOLVE_LOCK, SweepPlan




# ---- running the chunks ----------------------------------------------------------------------


def _run_local(plan: SweepPlan, chunks, workers, finished) -> None:
    if not chunks:
        return
    plan.prepare()
    if workers is None:
        workers = os.cpu_count() or 1
    workers = max(1, min(int(workers), len(chunks)))
    if plan.n_points < _PARALLEL_MIN_POINTS or not plan.fast:
        workers = 1          # full solves are serialised anyway
    if workers == 1:
        for chunk in chunks:
            finished(*plan.solve_chunk(chunk))
        return
    from concurrent.futures import FIRST_COMPLETED, ThreadPoolExecutor, wait
    pool = ThreadPoolExecutor(max_workers=workers)
    try:
        pending = {pool.submit(plan.solve_chunk, c) for c in chunks}
        while pending:
            done, pending = wait(pending, return_when=FIRST_COMPLETED)
            for fut in done:
                finished(*fut.result())
    finally:
        pool.shutdown(wait=True, cancel_futures=True)


def _client(scheduler):
    """``(client, created_here)`` for a scheduler address or an existing client."""
    try:
        from distributed import Client
    except ImportError:          # pragma: no cover - a runtime dependency
        raise CaseError("scheduler", "dask.distributed is not installed") from None
    if isinstance(scheduler, Client):
        return scheduler, False
    if not isinstance(scheduler, str) or "://" not in scheduler:
        raise CaseError("scheduler", f"{scheduler!r} must be an address like "
                                     f"tcp://HOST:PORT or a distributed.Client")
    try:
        return Client(scheduler, timeout="10s"), True
    except (OSError, TimeoutError, ValueError) as err:
        raise CaseError("scheduler", f"cannot connect to {scheduler}: {err}") from None


def _run_dask(client, plan: SweepPlan, chunks, finished) -> None:
    if not chunks:
        return
    from distributed import as_completed

    spec = plan.spec()
    key = _sha(spec)
    [spec_future] = client.scatter([spec], broadcast=True, hash=False)
    futures = [client.submit(_remote_chunk, key, spec_future, chunk, pure=False)
               for chunk in chunks]
    try:
        for fut in as_completed(futures):
            finished(*fut.result())
    finally:
        client.cancel(futures)


_REMOTE_PLANS: "OrderedDict[str, SweepPlan]" = OrderedDict()


def _remote_chunk(key: str, spec: dict, points):
    """A Dask task: the plan rebuilt from the case-file data (once per worker process),
    then the same chunk solver as a local run."""
    with _SOLVE_LOCK:
        plan = _REMOTE_PLANS.get(key)
        if plan is None:
            plan = _REMOTE_PLANS[key] = SweepPlan.from_spec(spec)
            while len(_REMOTE_PLANS) > 4:
                _REMOTE_PLANS.popitem(last=False)
    return plan.solve_chunk(points)


def _progress_bar(progress, total: int, initial: int):
    if not progress:
        return _NoBar()
    from tqdm import tqdm
    file = sys.stderr if progress is True else progress
    return tqdm(total=total, initial=initial, unit="pt", desc="sweep", file=file,
                mininterval=0.2, smoothing=0.1)


class _NoBar:
    def update(self, n: int) -> None:
        pass

    def close(self) -> None:
        pass
