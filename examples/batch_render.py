"""Batch renders of a bpy script: every frame x variation (patterns x colourways x cameras...),
on local worker processes by default, or on a Dask cluster given its scheduler's address.

    .venv/bin/python examples/batch_render.py examples/contact_sheet.py --out out/tiles \\
        --vary pattern=seed,garter --vary colourway=nordic,sea
    .venv/bin/python examples/batch_render.py SCRIPT --out DIR --frames 1 120 --workers 2
    .venv/bin/python examples/batch_render.py SCRIPT --out DIR --scheduler tcp://farm:8786

Each job runs the script in a fresh Python process (`bpy` can be imported only once per
process) as `SCRIPT [--frame N] [--NAME VALUE for each variation] --output PATH [extra]`; the
script renders one image to PATH. Scheduling is Dask's (`dask.distributed`): a `LocalCluster`
of worker processes on this machine, or the cluster at `--scheduler`, whose workers need this
repository and its venv at the same path. Nothing here schedules.

- **Resumable.** A job whose output exists is done: run the batch again after a crash, a
  killed worker or Ctrl-C, and only the missing images are rendered.
- **Each output written once.** The script writes a file of its own attempt's name; the worker
  renames it over the output only after the script succeeded (an atomic rename), and a job that
  finds its output already there writes nothing. Dask reruns the jobs of a worker that dies; a
  rerun of a job whose rename had happened finds the output and stops. Each rename is logged,
  a line per output, in `batch-ledger.jsonl` beside the outputs. The attempt files of killed
  renders are removed when the batch ends (and when it starts, after a crash).
- **Deterministic.** The same script and arguments give the same image on any worker (the
  core's output does not depend on the machine or the thread count): a farm's frame equals the
  frame rendered alone.
"""

import argparse
import itertools
import json
import os
import signal
import subprocess
import sys
import time
import uuid
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from pathlib import Path

LEDGER = "batch-ledger.jsonl"


@dataclass(frozen=True)
class Job:
    """One render: `script` run with `args`, writing `output`."""

    script: str
    args: tuple[str, ...]
    output: str


def grid(
    script: Path,
    out: Path,
    *,
    frames: Iterable[int] | None = None,
    variations: dict[str, list[str]] | None = None,
    extra: Iterable[str] = (),
) -> list[Job]:
    """Every frame x every combination of the variations' values, one job each, named
    `<value>_<value>..._f<frame>.png` in `out` (without the frame part when no frames are
    given, without values when no variations are)."""
    variations = variations or {}
    names = list(variations)
    jobs = []
    frame_list: list[int | None] = list(frames) if frames is not None else [None]
    for values in itertools.product(*(variations[n] for n in names)):
        for frame in frame_list:
            args: list[str] = []
            parts = list(values)
            if frame is not None:
                args += ["--frame", str(frame)]
                parts.append(f"f{frame:04d}")
            for name, value in zip(names, values, strict=True):
                args += [f"--{name}", value]
            args += list(extra)
            stem = "_".join(parts) or "render"
            jobs.append(Job(str(script), tuple(args), str(out / f"{stem}.png")))
    return jobs


def _die_with_parent() -> None:
    """In the script's process: be killed when the worker running it dies, so that a killed
    worker leaves no render behind still writing (Linux; elsewhere the attempt's own file
    name keeps it from touching the output)."""
    if sys.platform.startswith("linux"):
        import ctypes

        pr_set_pdeathsig = 1
        ctypes.CDLL(None, use_errno=True).prctl(pr_set_pdeathsig, signal.SIGKILL)


def run_job(job: Job, python: str) -> dict[str, object]:
    """Render `job` (in a Dask worker): skipped where its output exists."""
    output = Path(job.output)
    if output.exists():
        return {"output": job.output, "rendered": False}
    attempt = output.with_name(f".{output.stem}.{uuid.uuid4().hex}.partial{output.suffix}")
    output.parent.mkdir(parents=True, exist_ok=True)
    t0 = time.perf_counter()
    done = subprocess.run(
        [python, job.script, *job.args, "--output", str(attempt)],
        capture_output=True, text=True, check=False, preexec_fn=_die_with_parent,
    )
    if done.returncode != 0 or not attempt.exists():
        attempt.unlink(missing_ok=True)
        raise RuntimeError(
            f"{job.script} {' '.join(job.args)} failed (exit code {done.returncode}):\n"
            f"{done.stdout[-2000:]}{done.stderr[-2000:]}"
        )
    if output.exists():  # a rerun raced an attempt that got there first
        attempt.unlink()
        return {"output": job.output, "rendered": False}
    os.replace(attempt, output)
    seconds = time.perf_counter() - t0
    line = json.dumps({"output": output.name, "pid": os.getpid(), "seconds": round(seconds, 3)})
    with (output.parent / LEDGER).open("a") as ledger:
        ledger.write(line + "\n")
    return {"output": job.output, "rendered": True, "seconds": seconds}


def _attempt_files(jobs: list[Job]) -> list[Path]:
    """The attempt files (`.<stem>.<id>.partial<suffix>`) of `jobs`' outputs on disk."""
    found = []
    for job in jobs:
        output = Path(job.output)
        if output.parent.is_dir():
            found += output.parent.glob(f".{output.stem}.*.partial{output.suffix}")
    return found


def _sweep_attempts(jobs: list[Job]) -> None:
    """Remove the attempt files that killed renders left (a worker killed mid-write leaves
    its attempt's file; its job was rendered again under another name). Called only while no
    job of the batch runs: before it starts and after every job has finished."""
    for path in _attempt_files(jobs):
        path.unlink(missing_ok=True)


def run_batch(
    jobs: list[Job],
    *,
    scheduler: str | None = None,
    workers: int = 2,
    progress: Callable[[str], None] = print,
) -> dict[str, object]:
    """Run `jobs` on a `LocalCluster` of `workers` processes, or on the Dask cluster at
    `scheduler`; return counts and the wall time. Raises the first job's error."""
    import cloudpickle
    from dask.distributed import Client, LocalCluster, as_completed

    # The jobs' code travels with them: a cluster's workers need the venv, not this file.
    if __name__ != "__main__":  # (__main__'s functions travel by value anyway)
        cloudpickle.register_pickle_by_value(sys.modules[__name__])
    todo = [j for j in jobs if not Path(j.output).exists()]
    _sweep_attempts(todo)
    progress(f"batch: {len(jobs)} jobs, {len(jobs) - len(todo)} already done")
    t0 = time.perf_counter()
    cluster = None
    if scheduler is None:
        cluster = LocalCluster(
            n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None
        )
    client = Client(scheduler or cluster)
    try:
        python = sys.executable
        # pure=False: a job is named by its output, not by hashing its arguments.
        futures = [
            client.submit(run_job, j, python, key=f"render-{j.output}", pure=False, retries=2)
            for j in todo
        ]
        rendered = 0
        for k, future in enumerate(as_completed(futures), 1):
            result = future.result()
            rendered += bool(result["rendered"])
            took = f" in {result['seconds']:.1f} s" if result.get("seconds") else ""
            progress(f"batch: [{k}/{len(todo)}] {Path(str(result['output'])).name}{took}")
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
    # Every job has finished (as_completed ran through them all without an error).
    _sweep_attempts(todo)
    wall = time.perf_counter() - t0
    return {"jobs": len(jobs), "rendered": rendered, "skipped": len(jobs) - len(todo),
            "seconds": wall}


def _variation(text: str) -> tuple[str, list[str]]:
    name, _, values = text.partition("=")
    if not name or not values:
        raise argparse.ArgumentTypeError(f"expected NAME=VALUE,VALUE..., got {text!r}")
    return name, values.split(",")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("script", type=Path, help="the bpy script one job runs")
    parser.add_argument("--out", type=Path, required=True, help="folder of the images")
    parser.add_argument("--frames", type=int, nargs=2, metavar=("FIRST", "LAST"))
    parser.add_argument("--vary", type=_variation, action="append", default=[],
                        metavar="NAME=V1,V2", help="a variation: --NAME V for each value V")
    parser.add_argument("--workers", type=int, default=2, help="local worker processes")
    parser.add_argument("--scheduler", help="a Dask scheduler's address (tcp://host:port)")
    args, extra = parser.parse_known_args(argv)
    frames = range(args.frames[0], args.frames[1] + 1) if args.frames else None
    jobs = grid(args.script.resolve(), args.out.resolve(), frames=frames,
                variations=dict(args.vary), extra=extra)
    report = run_batch(jobs, scheduler=args.scheduler, workers=args.workers)
    per_minute = 60.0 * float(report["rendered"]) / max(float(report["seconds"]), 1e-9)
    print(f"batch: {report['rendered']} rendered, {report['skipped']} already there, "
          f"{report['seconds']:.1f} s ({per_minute:.1f} images per minute)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
