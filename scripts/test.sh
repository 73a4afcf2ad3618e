#!/usr/bin/env bash
# Every test: lint (rustfmt, clippy, ruff), the Rust core (cargo test), the Python API of the
# core without Blender, and the installed extension in headless Blender (bpy from PyPI).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"
scripts/bootstrap.sh

echo "== lint"
cargo fmt --check
cargo clippy --quiet --all-targets -- -D warnings
.venv/bin/ruff check python blender_addon tests examples benchmarks scripts
.venv/bin/python scripts/check_layers.py
# The .pyi stub against the built module: names, signatures, defaults.
PYTHONPATH="$root/build/site" .venv/bin/python -m mypy.stubtest knitwear._core

echo "== cargo test"
cargo test --quiet

echo "== pytest: core API without Blender"
PYTHONPATH="$root/build/site" .venv/bin/python -m pytest -q tests/python/core

echo "== pytest: extension in headless Blender"
.venv/bin/python -m pytest -q tests/python/blender

# The other Blender versions bootstrap installs (a crash at exit fails here too).
for version in 42 45 52; do
  echo "== smoke: the extension in the bpy of .venv-blender$version"
  ".venv-blender$version/bin/python" scripts/smoke_blender.py
done
