"""Runs fault cases of the core's Python API in this process and reports each one's outcome.

The child side of the fault suite (`test_faults.py`, `benchmarks/fault_sweep.py`): its parent
runs it in a subprocess with an address-space limit and a wall-clock limit per case, so a
crash or a hang cannot take the runner down. Cases are JSON objects, one per line on stdin,
or one given as the first argument (a path to a JSON file with ``@path``)::

    PYTHONPATH=build/site .venv/bin/python tests/python/core/fault_case.py '{"id": "x", ...}'

For each case it prints ``S <index>`` before it starts and ``R <json>`` when it is done,
flushed, so the parent can tell which case was running when the process died or stalled. An
outcome is ``ok`` (every float it returned is finite), ``knit_error`` (a `knitwear.KnitError`:
a clear refusal), ``internal`` (`knitwear.InternalError`, a caught panic: a KnitError, so
accepted, but listed), ``other_exception`` (any other exception), ``nonfinite`` (NaN or inf
in a returned float buffer) or ``wrong`` (a broken promise: an index out of range, a chart that
does not read back).

A case: ``{"id": str, "call": "knit" | "Knit" | "Pattern.from_text" | ..., "args": [...],
"kwargs": {...}, "then": [{"call": ..., "args": [...], "kwargs": {...}, "value_at": 0}]}``:
each ``then`` call gets the first call's value inserted into its args at ``value_at``. Values
are JSON, with tagged objects for what JSON lacks (see `decode`).
"""

from __future__ import annotations

import json
import math
import os
import resource
import sys
import tempfile
import traceback
from typing import Any


def limit_memory() -> None:
    """The parent's address-space limit (``KNITWEAR_FAULT_AS_BYTES``), set here before numpy
    and the core load rather than in a ``preexec_fn``, which is unsafe in a parent that starts
    children from several threads. No core dumps."""
    limit = int(os.environ.get("KNITWEAR_FAULT_AS_BYTES", "0"))
    if limit > 0:
        resource.setrlimit(resource.RLIMIT_AS, (limit, limit))
    resource.setrlimit(resource.RLIMIT_CORE, (0, 0))


limit_memory()

import knitwear  # noqa: E402
import numpy as np  # noqa: E402

# --- Decoding the tagged values ---------------------------------------------------------------


def sheet(sx: float = 0.05, sy: float = 0.05, n: int = 12, z0: float = 0.0) -> Any:
    """A flat rectangular GridSurface sx x sy (scene units), n x n samples, at height z0."""
    u, v = np.meshgrid(np.linspace(0, 1, n), np.linspace(0, 1, n))
    pos = np.stack([u * sx, v * sy, np.full_like(u, z0)], axis=-1).astype(np.float32)
    nrm = np.zeros_like(pos)
    nrm[..., 2] = 1.0
    return knitwear.GridSurface(pos, nrm)


def perspective(fov_y: float, aspect: float, near: float, far: float) -> np.ndarray:
    f = 1.0 / math.tan(fov_y / 2)
    return np.array(
        [
            [f / aspect, 0, 0, 0],
            [0, f, 0, 0],
            [0, 0, (far + near) / (near - far), 2 * far * near / (near - far)],
            [0, 0, -1, 0],
        ]
    )


def look_at(eye: np.ndarray, target: np.ndarray) -> np.ndarray:
    f = (target - eye) / np.linalg.norm(target - eye)
    up = np.array([0.0, 0.0, 1.0]) if abs(f[2]) < 0.99 else np.array([0.0, 1.0, 0.0])
    s = np.cross(f, up)
    s /= np.linalg.norm(s)
    u = np.cross(s, f)
    m = np.eye(4)
    m[0, :3], m[1, :3], m[2, :3] = s, u, -f
    m[:3, 3] = -m[:3, :3] @ eye
    return m


def camera_matrix(eye: list[float], resolution: Any) -> np.ndarray:
    """A perspective camera at `eye` looking at the centre of the default 5 cm sheet."""
    ok = len(resolution) == 2 and all(isinstance(x, int) and 0 < x < 2**31 for x in resolution)
    aspect = resolution[0] / resolution[1] if ok else 4 / 3
    e = np.array(eye, float)
    return perspective(math.radians(50), aspect, 0.01, 100) @ look_at(
        e, np.array([0.025, 0.025, 0.0])
    )


def nd(spec: dict[str, Any]) -> np.ndarray:
    """An array: ``data`` (nested lists, NaN/inf allowed) or ``fill`` (one value) in ``shape``."""
    dtype = np.dtype(spec.get("dtype", "float32"))
    if "fill" in spec:
        return np.full(spec["shape"], spec["fill"], dtype=dtype)
    a = np.array(spec["data"], dtype=np.float64 if dtype.kind == "f" else None)
    with np.errstate(all="ignore"):
        a = a.astype(dtype)
    if "shape" in spec:
        a = a.reshape(spec["shape"])
    if spec.get("fortran"):
        a = np.asfortranarray(a)
    if spec.get("readonly"):
        a.flags.writeable = False
    return a


def path_value(spec: dict[str, Any]) -> Any:
    """A path for `Pattern.from_file`: kind ``raw`` (str), ``bytes``, ``pathlike``, or a new
    temporary file (``file`` with ``text`` or ``hex`` content), a FIFO or a folder."""
    kind = spec["kind"]
    if kind == "raw":
        return spec["path"]
    if kind == "bytes":
        return bytes.fromhex(spec["hex"])
    if kind == "pathlike":
        import pathlib

        return pathlib.Path(spec["path"])
    d = tempfile.mkdtemp(prefix="knitwear-fault-")
    if kind == "folder":
        return d
    p = os.path.join(d, spec.get("name", "pattern.txt"))
    if kind == "fifo":
        os.mkfifo(p)
        return p
    data = bytes.fromhex(spec["hex"]) if "hex" in spec else spec["text"].encode("utf-8", "replace")
    with open(p, "wb") as f:
        f.write(data * int(spec.get("repeat", 1)))
    if spec.get("as_bytes"):
        return os.fsencode(p)
    return p


def decode(v: Any) -> Any:
    """JSON value -> Python value. Tags: ``$t`` tuple, ``$b`` bytes (hex), ``$nd`` array,
    ``$grid`` a sheet (`sheet`'s keywords), ``$pattern`` a preset, ``$colors`` a ColorPattern,
    ``$camera`` a Camera looking at the sheet, ``$path`` a path (`path_value`), ``$call``
    a nested call (its errors are the case's), ``$f`` a float spelled "nan" / "inf" / "-inf"."""
    if isinstance(v, list):
        return [decode(x) for x in v]
    if not isinstance(v, dict):
        return v
    if "$t" in v:
        return tuple(decode(x) for x in v["$t"])
    if "$b" in v:
        return bytes.fromhex(v["$b"])
    if "$f" in v:
        return float(v["$f"])
    if "$nd" in v:
        return nd(v["$nd"])
    if "$grid" in v:
        return sheet(**v["$grid"])
    if "$pattern" in v:
        return knitwear.Pattern.preset(v["$pattern"])
    if "$colors" in v:
        c = v["$colors"]
        return knitwear.ColorPattern(decode(c["palette"]), c.get("chart", "0"))
    if "$camera" in v:
        c = v["$camera"]
        res = decode(c["resolution"])
        m = nd(c["matrices"]) if "matrices" in c else camera_matrix(c["eye"], res)
        eyes = decode(c["eyes"]) if "eyes" in c else [*c["eye"], 1.0]
        return knitwear.Camera(m, eyes, res)
    if "$path" in v:
        return path_value(v["$path"])
    if "$call" in v:
        return call(v["$call"], decode(v.get("args", [])), decode(v.get("kwargs", {})))
    return {k: decode(x) for k, x in v.items()}


def call(name: str, args: list[Any], kwargs: dict[str, Any]) -> Any:
    target: Any = knitwear
    for part in name.split("."):
        target = getattr(target, part)
    return target(*args, **kwargs)


# --- Exercising and checking what comes back --------------------------------------------------


def nonfinite(value: Any, where: str = "result", depth: int = 0) -> str | None:
    """Where `value` holds a NaN or an infinity (float arrays, floats, nested containers and
    the attributes of knitwear's result types), or None."""
    if depth > 6:
        return None
    if isinstance(value, np.ndarray):
        if value.dtype.kind in "fc" and value.size and not np.isfinite(value).all():
            bad = int((~np.isfinite(value)).sum())
            return f"{where}: {bad} of {value.size} not finite"
        return None
    if isinstance(value, float):
        return None if math.isfinite(value) else f"{where} = {value}"
    if isinstance(value, dict):
        for k, x in value.items():
            if (r := nonfinite(x, f"{where}[{k!r}]", depth + 1)) is not None:
                return r
        return None
    if isinstance(value, list | tuple):
        for i, x in enumerate(value):
            if (r := nonfinite(x, f"{where}[{i}]", depth + 1)) is not None:
                return r
        return None
    names = ATTRIBUTES.get(type(value).__name__, ())
    for n in names:
        if (r := nonfinite(getattr(value, n), f"{where}.{n}", depth + 1)) is not None:
            return r
    return None


ATTRIBUTES: dict[str, tuple[str, ...]] = {
    "KnitResult": ("vertices", "colors", "centerline_points", "yarn_radius", "normals", "stats"),
    "Knit": ("yarn_radius", "stitch_size", "counts", "vertex_count", "stitch_levels"),
    "PlushResult": ("vertices", "colors", "uvs", "mask", "stats", "field"),
    "PlushField": (
        "roots",
        "directions",
        "normals",
        "root_uvs",
        "noise",
        "noise_rgb",
        "pile_length",
        "pile_radius",
        "stats",
    ),
    "PlushView": ("vertices", "mask", "stats"),
    "GridSurface": ("extent",),
    "MeshSurface": ("extent", "domain"),
    "Camera": ("views", "resolution"),
    "Pattern": ("name", "width", "height"),
}


def exercise(value: Any, args: list[Any], kwargs: dict[str, Any]) -> list[Any]:
    """What a user does next with `value`; the values to check for NaN. Every call here is
    part of the case (its exceptions are the case's)."""
    out: list[Any] = [value]
    kind = type(value).__name__
    if kind == "Knit":
        surface = args[0]
        r = value.build(surface)
        out += [r, value.positions(surface), value.crossing_order(surface)]
        out.append(value.clearance(surface))
        out += [value.seen_triangles, value.topology_key]
        if kwargs.get("cull_hidden"):
            out.append(value.normals(surface))
        check_indices(r)
    elif kind == "KnitResult":
        check_indices(value)
        if len(value.vertices):
            out.append(knitwear.measure_clearance(value))
    elif kind == "Pattern":
        chart = value.chart()
        out += [chart, value.stitch_counts()]
        again = knitwear.Pattern.from_chart(chart)
        if again.stitch_counts() != value.stitch_counts():
            raise WrongOutput("Pattern.from_chart(p.chart()) changed the stitches")
    elif kind == "PlushResult":
        out.append(value.field.view(eye=[0.02, 0.02, 0.3]))
        out.append(value.field.view(view_dir=[0.0, 0.3, -1.0]))
    return out


class WrongOutput(Exception):
    """A result that breaks a documented promise (an index out of range, a chart that does
    not read back): counted apart from the exceptions."""


def check_indices(r: Any) -> None:
    """Triangles and edges index existing vertices (a wrong index would crash Blender)."""
    n = len(r.vertices)
    for name in ("triangles", "edges"):
        a = getattr(r, name)
        if a.size and (a.min() < 0 or a.max() >= n):
            raise WrongOutput(f"{name} index outside 0..{n}")


def run_case(case: dict[str, Any]) -> dict[str, Any]:
    knit_error = knitwear.KnitError
    try:
        args = decode(case.get("args", []))
        kwargs = decode(case.get("kwargs", {}))
        value = call(case["call"], args, kwargs)
        checked = exercise(value, args, kwargs)
        for then in case.get("then", []):
            more = decode(then.get("args", []))
            more.insert(then.get("value_at", 0), value)
            checked.append(call(then["call"], more, decode(then.get("kwargs", {}))))
    except knit_error as e:
        kind = "internal" if isinstance(e, knitwear.InternalError) else "knit_error"
        return {"outcome": kind, "detail": f"{type(e).__name__}: {str(e)[:300]}"}
    except WrongOutput as e:
        return {"outcome": "wrong", "detail": str(e)}
    except BaseException as e:  # noqa: BLE001 - every other exception is what we count
        tb = [f for f in traceback.extract_tb(e.__traceback__) if f.filename != __file__]
        at = f" at {os.path.basename(tb[-1].filename)}:{tb[-1].lineno}" if tb else ""
        return {"outcome": "other_exception", "detail": f"{type(e).__name__}: {e!s:.300}{at}"}
    where = nonfinite(checked)
    if where is not None:
        return {"outcome": "nonfinite", "detail": where}
    return {"outcome": "ok", "detail": ""}


def main() -> None:
    if len(sys.argv) > 1:
        arg = sys.argv[1]
        text = open(arg[1:], encoding="utf-8").read() if arg.startswith("@") else arg
        lines = [ln for ln in text.splitlines() if ln.strip()]
    else:
        lines = [ln for ln in sys.stdin.read().splitlines() if ln.strip()]
    for i, line in enumerate(lines):
        case = json.loads(line)
        print(f"S {i}", flush=True)
        result = run_case(case)
        result["id"] = case.get("id", str(i))
        print("R " + json.dumps(result), flush=True)


if __name__ == "__main__":
    main()
