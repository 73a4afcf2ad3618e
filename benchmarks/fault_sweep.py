"""A larger fault sweep of the core's Python API (issue 18, item 6): the generators of
`tests/python/core/test_faults.py`, `--scale` times as many examples, each case in a child
process (6 GiB address space, `--timeout` seconds), and prints the counts: crashes, hangs,
exceptions that are not a `knitwear.KnitError`, NaN/inf outputs (and wrong outputs), and the
clear errors; then a table of every failing case.

    PYTHONPATH=build/site .venv/bin/python benchmarks/fault_sweep.py --scale 6
    PYTHONPATH=build/site .venv/bin/python benchmarks/fault_sweep.py --knit-patterns --timeout 60

`--failing FILE` writes the failing cases as JSON lines; replay them with
``tests/python/core/fault_case.py @FILE``. Exit status 1 when any fault was found.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from collections import Counter, defaultdict
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests" / "python" / "core"))
import fault_suite as fs  # noqa: E402


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--scale", type=float, default=6.0, help="examples per family x this")
    ap.add_argument("--timeout", type=float, default=60.0, help="seconds a case may take")
    ap.add_argument("--workers", type=int, default=2, help="child processes at a time")
    ap.add_argument("--batch", type=int, default=25, help="safe cases per child")
    ap.add_argument("--memory-gib", type=float, default=6.0, help="address space per child")
    ap.add_argument("--families", default=",".join(fs.FAMILIES), help="comma-separated")
    ap.add_argument("--no-scripted", action="store_true", help="leave out issue 18's list")
    ap.add_argument(
        "--knit-patterns", action="store_true", help="also knit every pattern that parses"
    )
    ap.add_argument("--failing", type=Path, help="write the failing cases here (JSON lines)")
    ap.add_argument("--all", type=Path, help="write every outcome here (JSON lines)")
    ap.add_argument("-v", "--verbose", action="store_true", help="print each case as it ends")
    args = ap.parse_args()

    families = [f for f in args.families.split(",") if f]
    counts = {f: max(1, round(fs.COUNTS.get(f, 20) * args.scale)) for f in families}
    t0 = time.monotonic()
    cases = fs.build_cases(counts, scripted=not args.no_scripted, knit_patterns=args.knit_patterns)
    print(f"{len(cases)} cases generated in {time.monotonic() - t0:.1f} s", flush=True)

    def progress(o: fs.Outcome) -> None:
        if args.verbose or o.kind in fs.FAULTS:
            print(f"  {o.kind:<16}{o.id:<14}{o.seconds:6.1f} s  {o.detail[:100]}", flush=True)

    t1 = time.monotonic()
    outcomes = fs.run_cases(
        cases,
        timeout=args.timeout,
        workers=args.workers,
        batch=args.batch,
        memory=int(args.memory_gib * (1 << 30)),
        progress=progress,
    )
    seconds = time.monotonic() - t1

    per_family: dict[str, Counter[str]] = defaultdict(Counter)
    for o in outcomes:
        per_family[o.id.rsplit("-", 1)[0]][o.kind] += 1
    kinds = [*fs.FAULTS, *fs.ACCEPTED]
    print()
    print(f"{'family':<10}" + "".join(f"{k:>16}" for k in kinds))
    for fam in sorted(per_family):
        print(f"{fam:<10}" + "".join(f"{per_family[fam][k]:>16}" for k in kinds))
    slow = sorted(outcomes, key=lambda o: -o.seconds)[:5]
    print("\nslowest: " + ", ".join(f"{o.id} {o.seconds:.1f} s ({o.kind})" for o in slow))
    c = fs.counts(outcomes)
    print()
    print(fs.table(outcomes, (*fs.FAULTS, "internal")))
    print()
    print(f"crashes:                  {c['crash']}")
    print(f"hangs:                    {c['hang']}")
    print(f"non-KnitError exceptions: {c['other_exception']}")
    print(f"NaN/inf outputs:          {c['nonfinite']}")
    print(f"wrong outputs:            {c['wrong']}")
    print(f"clear errors (KnitError): {c['knit_error']}  (of which internal: {c['internal']})")
    print(f"ok:                       {c['ok']}")
    print(f"{len(outcomes)} cases in {seconds:.0f} s")
    if args.failing:
        n = fs.write_cases(outcomes, args.failing)
        print(f"{n} failing cases written to {args.failing}")
    if args.all:
        with args.all.open("w", encoding="utf-8") as f:
            for o in outcomes:
                f.write(
                    json.dumps(
                        {
                            "id": o.id,
                            "kind": o.kind,
                            "detail": o.detail,
                            "seconds": round(o.seconds, 3),
                            "case": o.case,
                        }
                    )
                    + "\n"
                )
    return 1 if any(c[k] for k in fs.FAULTS) else 0


if __name__ == "__main__":
    sys.exit(main())
