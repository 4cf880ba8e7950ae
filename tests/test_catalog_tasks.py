"""The catalog's tasks (catalog/tasks.py, issue 20): shards saved as they finish, a rerun
resumes from them, a shard of other jobs is recomputed, and on a Dask cluster a worker
killed in the middle of a task loses only that task."""

import importlib
import json
import os
import signal
import threading
import time

import pytest

from baranov.catalog.tasks import SchedulerUnreachable, dask_client, run_in_shards

JOBS = [f"job {n}" for n in range(10)]


class Interrupted(Exception):
    pass


def test_an_interrupted_run_resumes_from_its_shards(tmp_path):
    computed = []

    def failing_after_five(job):
        if len(computed) == 5:
            raise Interrupted
        computed.append(job)
        return job.upper()

    with pytest.raises(Interrupted):
        run_in_shards(failing_after_five, JOBS, tmp_path, shard_size=2)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["shard-0.json", "shard-1.json"]
    computed.clear()
    done = []
    results = run_in_shards(lambda job: computed.append(job) or job.upper(), JOBS, tmp_path, shard_size=2,
                            advance=done.append)
    assert results == [job.upper() for job in JOBS]
    assert computed == JOBS[4:]  # shards 0 and 1 were read back, not computed
    assert sum(done) == len(JOBS)


def test_a_shard_of_other_jobs_is_recomputed(tmp_path):
    (tmp_path / "shard-0.json").write_text(json.dumps({"jobs": ["'other'", "'jobs'"], "results": ["X", "Y"]}))
    (tmp_path / "shard-1.json").write_text('{"jobs": ["job 2"')  # cut short
    assert run_in_shards(str.upper, JOBS[:4], tmp_path, shard_size=2) == [job.upper() for job in JOBS[:4]]


def test_a_killed_worker_loses_only_its_task(tmp_path):
    """Two single-threaded worker processes, eight shards of one second; one worker is
    killed (SIGKILL) while it sleeps in a task: the nanny starts another, the scheduler
    runs the task again, and every result arrives."""
    with dask_client(2) as client:
        pids = list(client.run(os.getpid).values())

        def kill_one():
            time.sleep(1.5)
            os.kill(pids[0], signal.SIGKILL)

        killer = threading.Thread(target=kill_one)
        killer.start()
        results = run_in_shards(time.sleep, [0.5] * 16, tmp_path, client, shard_size=2)
        killer.join()
        assert results == [None] * 16
        assert pids[0] not in client.run(os.getpid).values()  # it did die, and was replaced
    assert len(list(tmp_path.glob("shard-*.json"))) == 8


def test_an_unreachable_scheduler_is_one_error(monkeypatch):
    monkeypatch.setattr("baranov.catalog.tasks.CONNECT_TIMEOUT", 2)
    with pytest.raises(SchedulerUnreachable, match="tcp://127.0.0.1:9: no Dask scheduler answers there"):
        with dask_client(2, "tcp://127.0.0.1:9"):
            pass


def test_a_lost_cluster_is_one_error_and_the_shards_stay(tmp_path, monkeypatch, capsys):
    """A 13-link run whose embedded scheduler starved under load died with a traceback
    (FutureCancelledError, "scheduler-connection-lost"); now the job raises ClusterLost,
    the command prints one line and exits 1, and the shards finished before stay."""
    from distributed.client import FutureCancelledError

    from baranov.catalog.tasks import ClusterLost

    cli = importlib.import_module("baranov.cli.main")

    class Future:
        def __init__(self, value):
            self.value = value

        def result(self):
            if self.value is None:
                raise FutureCancelledError("run_shard-0", "scheduler-connection-lost")
            return self.value

    class Client:  # the first shard finishes, the second is cancelled with the scheduler
        submitted = 0

        def submit(self, task, function, jobs, **options):
            Client.submitted += 1
            return Future(task(function, jobs) if Client.submitted == 1 else None)

    monkeypatch.setattr("distributed.as_completed", lambda futures: iter(futures))
    with pytest.raises(ClusterLost, match="scheduler-connection-lost.*rerun the same command to resume"):
        run_in_shards(str.upper, JOBS[:4], tmp_path, Client(), shard_size=2)
    assert [p.name for p in tmp_path.iterdir()] == ["shard-0.json"]

    def lost(args):
        raise ClusterLost("the Dask cluster was lost during the job (…); rerun the same command to resume")

    monkeypatch.setattr(cli, "run_catalog", lost)
    assert cli.main(["catalog", "--links", "5"]) == 1
    error = capsys.readouterr().err
    assert error.count("\n") == 1 and "rerun the same command" in error and "Traceback" not in error


def test_a_lost_embedded_cluster_is_restarted_and_the_job_resumes(tmp_path, monkeypatch):
    """The catalog job restarts an embedded cluster lost mid-job (up to EMBEDDED_RESTARTS
    times) and writes what an uninterrupted run writes; a cluster named by address is
    not restarted."""
    from contextlib import contextmanager

    from baranov.catalog import build
    from baranov.catalog.tasks import ClusterLost

    clusters = []

    @contextmanager
    def client(workers, scheduler=None):
        clusters.append(scheduler)
        yield None

    real, calls = build.catalog_links, []

    def lost_once(*args, **kwargs):
        calls.append(args[0])
        if len(calls) == 1:
            raise ClusterLost("the Dask cluster was lost during the job (scheduler-connection-lost)")
        return real(*args, **kwargs)

    monkeypatch.setattr(build, "dask_client", client)
    monkeypatch.setattr(build, "catalog_links", lost_once)
    messages = []
    build.build_catalog([3, 5], tmp_path / "resumed", crosscheck=False, slider_modes=0, log=messages.append)
    assert clusters == [None, None] and calls == [3, 3, 5]
    assert any("restarting the embedded cluster (1 of 3)" in m for m in messages)
    monkeypatch.setattr(build, "catalog_links", real)
    build.build_catalog([3, 5], tmp_path / "plain", crosscheck=False, slider_modes=0)
    for name in ("trusses-3.jsonl", "trusses-5.jsonl", "summary.md"):
        assert (tmp_path / "resumed" / name).read_bytes() == (tmp_path / "plain" / name).read_bytes()

    calls.clear()
    monkeypatch.setattr(build, "catalog_links", lost_once)
    with pytest.raises(ClusterLost):
        build.build_catalog([3], tmp_path / "named", crosscheck=False, slider_modes=0, scheduler="tcp://host:8786")
    assert clusters[-1] == "tcp://host:8786" and calls == [3]


def test_archived_shards_restore_and_a_job_resumes_from_them(tmp_path):
    """catalog/shard_archive.py: shards archived from one working folder and restored into
    a fresh one are reused by the rerun (nothing recomputed), byte-identical archives."""
    from baranov.catalog.shard_archive import archive_shards, restore_shards

    first, archive, second = tmp_path / "first", tmp_path / "archive", tmp_path / "second"
    with pytest.raises(Interrupted):
        run_in_shards(lambda job: (_ for _ in ()).throw(Interrupted) if job == "job 6" else job.upper(), JOBS,
                      first, shard_size=2)
    assert archive_shards(first, archive) == 3
    packed = {path.name: path.read_bytes() for path in archive.iterdir()}
    assert archive_shards(first, archive) == 0 and packed == {p.name: p.read_bytes() for p in archive.iterdir()}
    assert restore_shards(archive, second) == 3 and restore_shards(archive, second) == 0
    computed = []
    results = run_in_shards(lambda job: computed.append(job) or job.upper(), JOBS, second, shard_size=2)
    assert results == [job.upper() for job in JOBS] and computed == JOBS[6:]
