#!/usr/bin/env bash
# Set-up from a fresh clone, idempotent: a virtual environment with the pinned tools
# (requirements-dev.txt, bpy included), the core's abi3 wheel built by maturin, that wheel
# unpacked for the Blender-free tests (build/site), and the Blender extension zip (dist/).
# Everything comes from the project's own files plus crates.io and PyPI.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"

PY=${PYTHON:-python3}
if [ ! -x .venv/bin/python ]; then
  echo "bootstrap: creating .venv"
  "$PY" -m venv .venv
fi
.venv/bin/python -m pip install -q --disable-pip-version-check -r requirements-dev.txt

# Blender 5.2, the newest, for a smoke run beside the suite's 5.0 (its bpy needs Python 3.13:
# PYTHON313, or python3.13 on PATH, or pyenv's). Missing is an error, not a skip.
# A pyenv shim on PATH may exist and fail to run: each candidate must run as 3.13.
PY313=""
for candidate in ${PYTHON313:-} "${PYENV_ROOT:-$HOME/.pyenv}"/versions/3.13*/bin/python3.13 python3.13; do
  if "$candidate" -c 'import sys; assert sys.version_info[:2] == (3, 13)' 2>/dev/null; then
    PY313=$candidate
    break
  fi
done
if [ -z "$PY313" ]; then
  echo "bootstrap: Python 3.13 not found (for Blender 5.2's bpy): install it (pyenv install 3.13) or set PYTHON313" >&2
  exit 1
fi
if [ ! -x .venv-blender52/bin/python ]; then
  echo "bootstrap: creating .venv-blender52 with $PY313"
  "$PY313" -m venv .venv-blender52
fi
.venv-blender52/bin/python -m pip install -q --disable-pip-version-check -r requirements-blender52.txt

echo "bootstrap: building the core wheel (release)"
rm -rf build/wheels
.venv/bin/maturin build --release --quiet -o build/wheels
wheel=$(ls build/wheels/knitwear-*.whl)

# The core without Blender: unpacked into build/site, kept out of .venv so that the Blender
# tests import the copy that the extension bundles, as a user's Blender does.
rm -rf build/site
.venv/bin/python -m pip install -q --disable-pip-version-check --no-deps --target build/site "$wheel"

# The extension: the wheel is bundled under the exact name blender_manifest.toml lists.
rm -rf blender_addon/wheels && mkdir -p blender_addon/wheels dist
cp "$wheel" blender_addon/wheels/
ext_cli=$(.venv/bin/python - <<'PY'
import pathlib, sysconfig
site = pathlib.Path(sysconfig.get_paths()["purelib"])
print(next(site.glob("bpy/*/scripts/addons_core/bl_pkg/cli/blender_ext.py")))
PY
)
rm -f dist/knitwear-*.zip
.venv/bin/python "$ext_cli" build --source-dir blender_addon --output-dir dist >/dev/null
echo "bootstrap: built $(ls dist/knitwear-*.zip)"
