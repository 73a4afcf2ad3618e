#!/usr/bin/env bash
# Every test: lint (rustfmt, clippy, ruff), the Rust core (cargo test), the Python API of the
# core without Blender, and the installed extension in headless Blender (bpy from PyPI).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"
# CI builds once: incremental-compilation state would only take disk (about 1 GB).
export CARGO_INCREMENTAL=0
# A CI disk has run out of room mid-suite (a .blend save failed); say what each stage had.
room() { echo "== disk: $(df -h --output=avail . | tail -1 | tr -d ' ') free before $1"; }
room "bootstrap"
scripts/bootstrap.sh

echo "== lint"
cargo fmt --check
cargo clippy --quiet --all-targets -- -D warnings
.venv/bin/ruff check python blender_addon tests examples benchmarks scripts
.venv/bin/python scripts/check_layers.py
# The .pyi stub against the built module: names, signatures, defaults.
PYTHONPATH="$root/build/site" .venv/bin/python -m mypy.stubtest knitwear._core

room "cargo test"
echo "== cargo test"
cargo test --quiet

echo "== pytest: core API without Blender"
PYTHONPATH="$root/build/site" .venv/bin/python -m pytest -q tests/python/core

# Each Blender run that passes is recorded for the README's table of versions tested.
.venv/bin/python scripts/blender_matrix.py reset

room "the Blender suite"
echo "== pytest: extension in headless Blender 5.2 (the newest)"
.venv-blender52/bin/python -m pytest -q tests/python/blender --junitxml=build/blender-suite.xml
.venv/bin/python scripts/blender_matrix.py suite .venv-blender52/bin/python build/blender-suite.xml

# The other Blender versions (a crash at exit fails here too): 4.2 and 4.5 LTS, and 5.0 (the
# bpy of .venv).
for python in .venv-blender42/bin/python .venv-blender45/bin/python .venv/bin/python; do
  echo "== smoke: the extension in the bpy of $python"
  "$python" scripts/smoke_blender.py | tee build/smoke.log
  .venv/bin/python scripts/blender_matrix.py smoke "$python" build/smoke.log
done

echo "== the README's table of Blender versions, from these runs"
.venv/bin/python scripts/blender_matrix.py write
