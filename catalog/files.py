"""Atomic file output: a reader never sees a half-written file; and reading back a
complete one."""

from __future__ import annotations

import gzip
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


def dump_objects(objects: list[dict]) -> str:
    """JSON lines: one compact object per line (deterministic, diff-friendly, readable in
    a stream by :func:`iter_objects`).

    >>> print(dump_objects([{"id": "3/N1"}, {"id": "5/N1"}]), end="")
    {"id":"3/N1"}
    {"id":"5/N1"}
    """
    return "".join(json.dumps(o, separators=(",", ":"), ensure_ascii=False) + "\n" for o in objects)


def gzipped(text: str) -> bytes:
    """``text`` (UTF-8) gzip-compressed, byte-identical from run to run (no file name or
    time stamp in the header)."""
    return gzip.compress(text.encode("utf-8"), compresslevel=9, mtime=0)


def iter_objects(path: Path) -> Iterator[dict]:
    """The objects of a JSON-lines file one at a time (gzip-compressed if its name ends
    in ``.gz``), without reading the whole file. Raises ``OSError`` or ``ValueError``
    (with the line number) on a missing file or a line that is not a JSON object."""
    opener = gzip.open if path.name.endswith(".gz") else open
    with opener(path, "rt", encoding="utf-8") as stream:
        for number, line in enumerate(stream, 1):
            try:
                value = json.loads(line)
            except ValueError as error:
                raise ValueError(f"{path}, line {number}: not JSON ({error})") from None
            if not isinstance(value, dict):
                raise ValueError(f"{path}, line {number}: not a JSON object")
            yield value


def legacy_path(path: Path) -> Path:
    """The name a catalog file had before the catalog moved to JSON lines: ``.json``
    for ``.jsonl`` (a JSON list, one object per line)."""
    return path.with_suffix(".json")


def load_complete_objects(path: Path, fields: tuple[str, ...]) -> list[dict] | None:
    """The objects of a catalog file (JSON lines), or None if it is absent, unreadable,
    empty, or some object lacks one of ``fields`` (then the job recomputes it). Where
    ``path`` is absent, its :func:`legacy_path` (a JSON list) is read instead, so that a
    catalog folder written before the change is reused, not recomputed. A file written
    by :func:`write_atomically` is complete or absent; a file cut short elsewhere ends
    in a broken line, almost always, and is recomputed."""
    try:
        if path.exists() or not legacy_path(path).exists():
            objects = list(iter_objects(path))
        else:
            objects = json.loads(legacy_path(path).read_text(encoding="utf-8"))
    except (OSError, ValueError, EOFError):
        return None
    if not isinstance(objects, list) or not objects:
        return None
    if not all(isinstance(o, dict) and all(field in o for field in fields) for o in objects):
        return None
    return objects
