"""Atomic file output: a reader never sees a half-written file; and reading back a
complete one."""

from __future__ import annotations

import json
import os
import tempfile
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

try:
    import fcntl
except ImportError:  # not POSIX: no lock
    fcntl = None


class FolderBusyError(ValueError):
    """Another process is writing a catalog into the same folder."""


@contextmanager
def folder_lock(folder: Path) -> Iterator[None]:
    """Hold an exclusive advisory lock (flock) on ``folder`` itself for the block, so that
    two catalog jobs never write into one folder at once; raise :class:`FolderBusyError`
    at once if another process holds it. Nothing is created in the folder, and the lock
    goes with the process however it ends."""
    if fcntl is None:
        yield
        return
    handle = os.open(folder, os.O_RDONLY)
    try:
        try:
            fcntl.flock(handle, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            raise FolderBusyError(f"{folder}: another baranov catalog is writing into this folder; wait for it "
                                  "to finish or choose another --out") from None
        yield
    finally:
        os.close(handle)


def write_atomically(path: Path, content: str | bytes) -> None:
    """Write ``content`` to ``path`` through a temporary file in the same folder and a rename."""
    handle, temporary = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    try:
        binary = isinstance(content, bytes)
        with os.fdopen(handle, "wb" if binary else "w", **({} if binary else {"encoding": "utf-8", "newline": "\n"})) as stream:
            stream.write(content)
            stream.flush()
            os.fsync(stream.fileno())
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(temporary, 0o666 & ~umask)  # mkstemp creates 0600; give the usual mode
        os.replace(temporary, path)
    except BaseException:
        Path(temporary).unlink(missing_ok=True)
        raise


def remove_stale_temporaries(folder: Path) -> list[Path]:
    """Delete the temporary files that a killed run of :func:`write_atomically` left in
    ``folder`` and its shard folders (``.<name>.<random>.tmp``; SIGKILL gives no chance to
    clean up), and return them. Call it under :func:`folder_lock`: a live run's
    temporaries look the same."""
    stale = [path for pattern in (".*.tmp", ".shards/*/.*.tmp") for path in folder.glob(pattern) if path.is_file()]
    for path in stale:
        path.unlink(missing_ok=True)
    return stale


def check_writable_folder(path: Path) -> None:
    """Create ``path`` if needed and prove that files can be created in it.

    Raises ``OSError`` (with the reason) before any catalog work starts.
    """
    path.mkdir(parents=True, exist_ok=True)
    handle, probe = tempfile.mkstemp(dir=path, prefix=".write-probe.", suffix=".tmp")
    os.close(handle)
    os.unlink(probe)


def load_complete_objects(path: Path, fields: tuple[str, ...]) -> list[dict] | None:
    """The objects of a catalog file (a JSON list), or None if it is absent, unreadable,
    empty, or some object lacks one of ``fields`` (then the job recomputes it)."""
    try:
        objects = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    if not isinstance(objects, list) or not objects:
        return None
    if not all(isinstance(o, dict) and all(field in o for field in fields) for o in objects):
        return None
    return objects
