"""Worker processes that stop when their parent does.

A ``concurrent.futures`` pool drains its queue when the parent is interrupted: the catalog
job kept computing 11-link entries in its two workers for more than ten minutes after
SIGINT (issue 22). :func:`worker_pool` is a :class:`multiprocessing.pool.Pool` whose
workers ignore SIGINT (a Ctrl-C reaches the whole process group; the parent decides) and
which is terminated, not drained, when the ``with`` block ends by an exception.
"""

from __future__ import annotations

import multiprocessing
import multiprocessing.pool
import signal
from collections.abc import Iterator
from contextlib import contextmanager


def _ignore_interrupts() -> None:
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)  # a forked worker must not inherit the CLI's handler


@contextmanager
def worker_pool(workers: int, spawn: bool = False) -> Iterator[multiprocessing.pool.Pool]:
    """A pool of ``workers`` processes (started by ``spawn`` if asked, else the platform's
    default), closed and joined when the block ends normally, terminated at once when it
    ends by an exception (KeyboardInterrupt included)."""
    context = multiprocessing.get_context("spawn" if spawn else None)
    pool = context.Pool(workers, initializer=_ignore_interrupts)
    try:
        yield pool
        pool.close()
    except BaseException:
        pool.terminate()
        raise
    finally:
        pool.join()
