"""The batch runner (`examples/batch_render.py`, issue 21) on a real Dask cluster: a scheduler
and two worker processes started on this machine over loopback, one of them killed while it
renders. Every image must be written once, the killed worker's jobs rerun, and the images equal
those of a single worker process, bit for bit."""

import json
import os
import signal
import socket
import subprocess
import sys
import time
from pathlib import Path

import psutil
import pytest
from conftest import ROOT, _extension_zip

BIN = Path(sys.executable).parent
PATTERNS = ("seed", "garter", "rib_1x1")
COLOURWAYS = ("nordic", "sea")


def _batch(out: Path, *options: str) -> subprocess.Popen[str]:
    env = dict(os.environ, BLENDER_USER_RESOURCES="")  # each job installs the zip afresh
    return subprocess.Popen(
        [sys.executable, str(ROOT / "examples" / "batch_render.py"),
         str(ROOT / "examples" / "contact_sheet.py"), "--out", str(out),
         "--vary", "pattern=" + ",".join(PATTERNS), "--vary", "colourway=" + ",".join(COLOURWAYS),
         *options, "--tile", "64", "48", "--zip", str(_extension_zip())],
        stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=env,
    )


def _finish(proc: subprocess.Popen[str]) -> str:
    out, _ = proc.communicate(timeout=600)
    assert proc.returncode == 0, out[-4000:]
    return out


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _rendering(worker: subprocess.Popen[str]) -> list[psutil.Process]:
    """The tile renders running under a worker (its nanny's process tree)."""
    try:
        tree = psutil.Process(worker.pid).children(recursive=True)
    except psutil.NoSuchProcess:
        return []
    found = []
    for p in tree:
        try:  # a process may end (or be a zombie) between the listing and this look
            if "contact_sheet.py" in " ".join(p.cmdline()):
                found.append(p)
        except psutil.Error:
            continue
    return found


def _ledger(out: Path) -> list[str]:
    lines = (out / "batch-ledger.jsonl").read_text().splitlines()
    return [json.loads(line)["output"] for line in lines]


@pytest.fixture
def cluster() -> tuple[str, list[subprocess.Popen[str]]]:
    port = _free_port()
    address = f"tcp://127.0.0.1:{port}"
    procs = [subprocess.Popen(
        [str(BIN / "dask"), "scheduler", "--host", "127.0.0.1", "--port", str(port),
         "--no-dashboard"],
        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True,
    )]
    for _ in range(2):
        procs.append(subprocess.Popen(
            [str(BIN / "dask"), "worker", address, "--nthreads", "1", "--no-dashboard"],
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True,
        ))
    yield address, procs[1:]
    for p in reversed(procs):
        try:
            os.killpg(p.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        p.wait()


def test_a_killed_worker_reruns_and_every_image_matches_one_process(
    tmp_path: Path, cluster: tuple[str, list[subprocess.Popen[str]]]
) -> None:
    names = {f"{p}_{c}.png" for p in PATTERNS for c in COLOURWAYS}
    alone = tmp_path / "alone"
    t0 = time.perf_counter()
    _finish(_batch(alone, "--workers", "1"))
    one_worker = time.perf_counter() - t0

    address, workers = cluster
    farm = tmp_path / "farm"
    t0 = time.perf_counter()
    batch = _batch(farm, "--scheduler", address)
    # Kill the first worker while it renders a tile (its whole process group: nanny, worker
    # and the render), once the other has rendered one too: its job is lost with it.
    victim = workers[0]
    deadline = time.monotonic() + 300
    while not (_rendering(victim) and (farm / "batch-ledger.jsonl").exists()):
        assert batch.poll() is None and time.monotonic() < deadline, "no worker got a job"
        time.sleep(0.05)
    lost = [p.pid for p in _rendering(victim)]
    os.killpg(victim.pid, signal.SIGKILL)
    victim.wait()
    out = _finish(batch)
    two_workers = time.perf_counter() - t0
    print(out[-1500:])
    print(f"batch: 6 tiles, 1 worker {one_worker:.1f} s ({360 / one_worker:.1f} per minute); "
          f"2 workers with one killed {two_workers:.1f} s")

    assert lost, "the killed worker was rendering nothing"
    written = _ledger(farm)
    assert sorted(written) == sorted(names), f"each image written once: {written}"
    assert {p.name for p in farm.glob("*.png")} == names
    assert not list(farm.glob(".*.partial.png")), "a killed attempt's file is left"
    for name in names:
        assert (farm / name).read_bytes() == (alone / name).read_bytes(), name

    # Resumable: the batch again renders nothing; an image removed is rendered again, alone,
    # and the half-written attempt a crash left for it is cleared away.
    (farm / "garter_sea.png").unlink()
    (farm / ".garter_sea.0123abcd.partial.png").write_bytes(b"\x89PNG half")
    again = _finish(_batch(farm, "--workers", "1"))
    assert "1 rendered, 5 already there" in again
    assert (farm / "garter_sea.png").read_bytes() == (alone / "garter_sea.png").read_bytes()
    assert sorted(_ledger(farm)) == sorted([*names, "garter_sea.png"])
    assert not list(farm.glob(".*.partial.png")), "a crashed attempt's file is left"
