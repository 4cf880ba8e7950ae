"""The catalog's work as Dask tasks (issue 20): jobs grouped in shards, each shard a task,
submitted costliest first, each finished shard written to disk atomically, so that a rerun
resumes from the shards there and a killed worker loses only its task (Dask retries it).

By default the cluster is embedded (a ``distributed.LocalCluster`` of one single-threaded
process per worker: flint and the solvers are not thread-safe to share, and processes
are spawned, never forked — a forked worker deadlocked once flint had run in the parent);
``scheduler`` names a running Dask scheduler instead (``tcp://host:8786``), whose workers
must have this package installed. With one worker and no scheduler the shards run in this
process, in the same order and to the same files: the output does not depend on where
the work ran.
"""

from __future__ import annotations

import json
import logging
import multiprocessing
import shutil
import tempfile
from collections.abc import Callable, Iterator, Sequence
from concurrent.futures import CancelledError
from contextlib import contextmanager, suppress
from pathlib import Path
from typing import Any

from .files import write_atomically

#: Jobs per shard: a shard is one Dask task and one file on disk.
SHARD_SIZE = 8
#: A task that fails (its worker killed, say) is retried this many times before the job fails.
RETRIES = 3
#: Seconds to wait for a scheduler named by address.
CONNECT_TIMEOUT = 20


class SchedulerUnreachable(ValueError):
    """No Dask scheduler answers at the address given."""


class ClusterLost(RuntimeError):
    """The Dask scheduler went away during the job (its tasks cancelled); the shards
    finished before are on disk."""


@contextmanager
def dask_client(workers: int, scheduler: str | None = None) -> Iterator[Any]:
    """A ``distributed.Client`` for the block: connected to ``scheduler`` if given, else
    to an embedded LocalCluster of ``workers`` processes; None (work in this process) for
    one worker and no scheduler. The cluster is closed when the block ends, also by an
    exception (Ctrl-C)."""
    if scheduler is None and workers <= 1:
        yield None
        return
    from distributed import Client, LocalCluster  # only where a cluster is wanted: ~0.5 s to import

    if scheduler is not None:
        try:
            client = Client(scheduler, timeout=f"{CONNECT_TIMEOUT}s")
        except OSError as error:  # the address answers nothing, or no scheduler there
            raise SchedulerUnreachable(f"--scheduler {scheduler}: no Dask scheduler answers there ({error})") from None
        with client:
            yield client
        return
    # ":0": any free port for its HTTP server, which starts even without a dashboard (on
    # 8787 a second job beside the first printed a warning on stderr). Logs below CRITICAL
    # are silenced: a task's failure reaches us as its exception, and on Ctrl-C a worker
    # still heartbeating to the closed scheduler logged an ERROR with a traceback onto the
    # one-line message (test_catalog_faults, SIGTERM: seen once, in the suite run of 2026-11-25)
    with (LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=":0",
                       silence_logs=logging.CRITICAL) as cluster, Client(cluster) as client):
        try:
            yield client
        except BaseException:
            kill_worker_processes()
            raise


def kill_worker_processes() -> None:
    """Kill the worker processes of an embedded cluster (every child process this one
    started through multiprocessing, as Dask's nannies start them), before the cluster
    closes on an exception (Ctrl-C, SIGTERM; the command line's signal handler calls it
    too, so that workers still starting are covered). A worker busy in a task holds its
    GIL in flint or numba and cannot answer a graceful close: its nanny waits 4 s, then
    kills it, and under load the close took 22 s (test_catalog_faults, a suite run of
    2026-11-29; again in a fresh clone with the workers killed in the block above only,
    cause not isolated: a signal while the cluster starts escapes that block). Their work
    is lost either way, and only this process writes files."""
    for child in multiprocessing.active_children():
        with suppress(OSError, AttributeError, ValueError):  # already gone, or closed
            child.kill()


def run_in_shards(function: Callable[[Any], Any], jobs: Sequence, folder: Path, client: Any = None,
                  costs: Sequence[float] | None = None, advance: Callable[[int], None] = lambda done: None,
                  shard_size: int = SHARD_SIZE) -> list:
    """``[function(job) for job in jobs]``, computed in shards of ``shard_size``
    consecutive jobs. Shard k is saved as ``folder/shard-<k>.json`` (the jobs' reprs and
    their results, JSON) once it is done; a shard file whose jobs are the same is reused
    instead of computed. Shards run on ``client`` (Dask) if given, costliest first by the
    sum of ``costs`` (Dask priorities), else here in that order; ``advance(n)`` is called
    as n more jobs are done. Results must be JSON values (as catalog entries are).
    Cost: one task per shard; the jobs' own cost otherwise."""
    folder.mkdir(parents=True, exist_ok=True)
    shards = [list(range(start, min(start + shard_size, len(jobs)))) for start in range(0, len(jobs), shard_size)]
    results: list = [None] * len(jobs)
    pending = []
    for number, indices in enumerate(shards):
        saved = _saved_shard(folder / f"shard-{number}.json", [jobs[i] for i in indices])
        if saved is None:
            pending.append(number)
            continue
        for index, result in zip(indices, saved, strict=True):
            results[index] = result
        advance(len(indices))
    weight = [sum(costs[i] for i in shards[n]) if costs is not None else 0.0 for n in pending]
    order = [pending[k] for k in sorted(range(len(pending)), key=lambda k: -weight[k])]
    for number, shard_results in _computed(function, jobs, shards, order, client, weight, pending):
        indices = shards[number]
        write_atomically(folder / f"shard-{number}.json", json.dumps(
            {"jobs": [repr(jobs[i]) for i in indices], "results": shard_results}) + "\n")
        for index, result in zip(indices, shard_results, strict=True):
            results[index] = result
        advance(len(indices))
    return results


def _computed(function, jobs, shards, order, client, weight, pending) -> Iterator[tuple[int, list]]:
    """(shard number, results) for the shards ``order``, as they finish."""
    if client is None:
        for number in order:
            yield number, run_shard(function, [jobs[i] for i in shards[number]])
        return
    from distributed import as_completed

    priority = dict(zip(pending, weight, strict=True))
    futures = {client.submit(run_shard, function, [jobs[i] for i in shards[number]], pure=False,
                             retries=RETRIES, priority=priority[number]):
               number for number in order}
    try:
        for future in as_completed(futures):
            yield futures[future], future.result()
    except CancelledError as error:  # e.g. "scheduler-connection-lost" (a 13-link run under load)
        raise ClusterLost(f"the Dask cluster was lost during the job ({error}); the finished shards are "
                          "kept: rerun the same command to resume") from None


def run_shard(function: Callable[[Any], Any], jobs: list) -> list:
    """One task: ``function`` on each job of a shard, results as JSON values (a round
    trip through JSON, so that a reused shard and a computed one are the same values)."""
    return json.loads(json.dumps([function(job) for job in jobs]))


def _saved_shard(path: Path, jobs: list) -> list | None:
    """The results saved at ``path`` if it holds exactly these jobs, else None."""
    try:
        saved = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    if not isinstance(saved, dict) or saved.get("jobs") != [repr(job) for job in jobs]:
        return None
    results = saved.get("results")
    return results if isinstance(results, list) and len(results) == len(jobs) else None


@contextmanager
def shard_folder(folder: Path | None) -> Iterator[Path]:
    """``folder``, removed when the block ends normally (every result is in memory then;
    the caller writes the final file next, so a kill in between costs a recomputation, not
    a wrong file); kept after an interruption, for the rerun to resume from. A temporary
    folder if None."""
    if folder is None:
        with tempfile.TemporaryDirectory(prefix="baranov-shards-") as temporary:
            yield Path(temporary)
        return
    yield folder
    shutil.rmtree(folder, ignore_errors=True)
    with suppress(OSError):  # out/.shards/ once its last shard folder is gone
        folder.parent.rmdir()
