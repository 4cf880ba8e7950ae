"""The catalog job under faults (issue 22; on Dask since issue 20): a signal stops the
whole job, its cluster included, within seconds with one line; an interrupted or killed run
leaves only complete files (catalog files and finished shards), and a rerun completes them
byte-identically; two runs never write into one folder at once."""

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[1]
COMMAND = [sys.executable, "-m", "baranov.cli", "catalog", "--workers", "2", "--no-crosscheck", "--quiet",
           "--slider-modes", "0"]  # the job's faults, not the slider chains' minutes
INTERRUPTED = "baranov: interrupted; complete catalog files are kept, rerun to resume\n"

pytestmark = pytest.mark.skipif(not Path("/proc").is_dir(), reason="reads child processes from /proc")


def _descendants(pid: int) -> set[int]:
    """Every process below ``pid`` (Linux /proc)."""
    found, pending = set(), [pid]
    while pending:
        parent = pending.pop()
        for task in Path(f"/proc/{parent}/task").glob("*"):
            try:
                children = {int(c) for c in (task / "children").read_text().split()}
            except OSError:
                continue
            pending += list(children - found)
            found |= children
    return found


def _alive(pid: int) -> bool:
    try:
        status = Path(f"/proc/{pid}/status").read_text()
    except OSError:
        return False
    return "\nState:\tZ" not in status


def _started_nine_links(out: Path) -> subprocess.Popen:
    """The catalog job for 3-9 links, once its seven-link file is written and it works on
    nine links with its worker processes."""
    process = subprocess.Popen([*COMMAND, "--links", "3-9", "--out", str(out)], stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 120
    while not ((out / "trusses-7.jsonl").exists() and len(_descendants(process.pid)) >= 2):
        assert process.poll() is None and time.monotonic() < deadline, "the job did not reach nine links"
        time.sleep(0.05)
    time.sleep(1.0)
    return process


def _complete_files_only(out: Path, rewritten: tuple[str, ...] = ()) -> None:
    """Only complete catalog files, and the finished shards of the unfinished link count
    (``.shards/trusses-9/shard-<k>.json``, each a complete JSON file: catalog/tasks.py),
    from which a rerun resumes; ``rewritten``: names not compared with the committed files."""
    for path in out.iterdir():
        if path.name == ".shards":
            assert [p.name for p in path.iterdir()] in ([], ["trusses-9"]), list(path.iterdir())
            for shard in path.glob("*/*"):
                assert shard.name.startswith("shard-") and json.loads(shard.read_text())["results"], shard
            continue
        assert not path.name.startswith("."), f"left behind: {path.name}"
        assert path.name in rewritten or path.read_bytes() == (REPO / "catalog" / path.name).read_bytes(), path.name


@pytest.mark.parametrize("number", [pytest.param(signal.SIGINT, marks=pytest.mark.slow), signal.SIGTERM],
                         ids=["SIGINT", "SIGTERM"])  # each 13 s (2026-11-28); SIGINT in make test-slow
def test_a_signal_stops_the_whole_job(tmp_path, number):
    process = _started_nine_links(tmp_path)
    workers = _descendants(process.pid)
    sent = time.monotonic()
    process.send_signal(number)
    process.wait(timeout=60)
    assert time.monotonic() - sent < 10
    assert process.returncode == 130 and process.stderr.read() == INTERRUPTED
    time.sleep(0.5)
    assert not [pid for pid in workers if _alive(pid)], "workers outlived the job"
    names = sorted(p.name for p in tmp_path.iterdir() if p.name != ".shards")
    assert names == ["trusses-3.jsonl", "trusses-5.jsonl", "trusses-7.jsonl"]
    _complete_files_only(tmp_path)


def test_a_killed_run_leaves_complete_files_and_a_rerun_completes_them(tmp_path):
    process = _started_nine_links(tmp_path)
    workers = _descendants(process.pid)
    (tmp_path / ".trusses-9.jsonl.abc123.tmp").write_text("{\"id\": \"9/N1\"")  # as if killed while writing
    process.kill()
    process.wait(timeout=30)
    for pid in workers:  # SIGKILL leaves no handler to stop them: what a scheduler's kill leaves
        if _alive(pid):
            os.kill(pid, signal.SIGKILL)
    rerun = subprocess.run([*COMMAND, "--links", "3-7", "--out", str(tmp_path)], capture_output=True, text=True)
    assert rerun.returncode == 0, rerun.stderr
    # the Grübler chains counted to 8 links where geng is installed (catalog/build.py)
    names = sorted(p.name for p in tmp_path.iterdir() if p.name not in (".shards", "grubler-chains.json"))
    assert names == ["summary.md", "trusses-3.jsonl", "trusses-5.jsonl", "trusses-7.jsonl"], names
    _complete_files_only(tmp_path, rewritten=("summary.md", "grubler-chains.json"))  # 3-7 links only
    for name in names[1:]:
        assert (tmp_path / name).read_bytes() == (REPO / "catalog" / name).read_bytes(), name


def test_two_runs_into_one_folder_are_refused(tmp_path):
    first = _started_nine_links(tmp_path)
    try:
        second = subprocess.run([*COMMAND, "--links", "3", "--out", str(tmp_path)], capture_output=True, text=True)
        assert second.returncode == 2
        assert second.stderr == (f"baranov: error: {tmp_path}: another baranov catalog is writing into this folder; "
                                 "wait for it to finish or choose another --out\n")
    finally:
        first.send_signal(signal.SIGINT)
        first.wait(timeout=60)
