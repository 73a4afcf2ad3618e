#!/usr/bin/env bash
# Set-up from a fresh clone, idempotent: a virtual environment with the pinned tools
# (requirements-dev.txt, bpy included), the core's abi3 wheel built by maturin, that wheel
# unpacked for the Blender-free tests (build/site), and the Blender extension zip (dist/).
# Everything comes from the project's own files plus crates.io and PyPI.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"

# `--zip-only`: just the release zip and wheel (dist/, build/wheels), skipping the other
# Blender versions' venvs that only the tests need (and the Python 3.13 they need).
ZIP_ONLY=0
if [ "${1:-}" = "--zip-only" ]; then
  ZIP_ONLY=1
elif [ $# -gt 0 ]; then
  echo "usage: scripts/bootstrap.sh [--zip-only]" >&2
  exit 2
fi

PY=${PYTHON:-python3}
# Four bpy builds (about 1 GB each unpacked) are installed below: pip's cache would keep a
# second copy of every wheel, and a CI disk has run out of room here once.
export PIP_NO_CACHE_DIR=1
# Blender versions smoke-tested beside the suite's (see below and scripts/test.sh).
SMOKE_BLENDERS="42:3.11 45:3.11 52:3.13"
if [ "$ZIP_ONLY" = 1 ]; then
  SMOKE_BLENDERS=""
fi
if [ ! -x .venv/bin/python ]; then
  echo "bootstrap: creating .venv"
  "$PY" -m venv .venv
fi
.venv/bin/python -m pip install -q --disable-pip-version-check -r requirements-dev.txt

# Other Blender versions for a smoke run each (scripts/smoke_blender.py), beside the suite's
# 5.0: <version>:<the Python its bpy needs>, pinned in requirements-blender<version>.txt. The
# Python is taken from PYTHON<major><minor> (PYTHON313), pyenv or PATH; a missing one is an
# error, not a skip.
find_python() {
  local want=$1 override="PYTHON${1//./}" candidate
  for candidate in ${!override:-} "${PYENV_ROOT:-$HOME/.pyenv}"/versions/"$want".*/bin/python"$want" python"$want"; do
    # A pyenv shim on PATH may exist and still fail to run: each candidate must run as $want.
    if "$candidate" -c "import sys; assert '%d.%d' % sys.version_info[:2] == '$want'" 2>/dev/null; then
      echo "$candidate"
      return 0
    fi
  done
  return 1
}
for spec in $SMOKE_BLENDERS; do
  version=${spec%%:*} python=${spec#*:}
  venv=.venv-blender$version
  if [ ! -x "$venv/bin/python" ]; then
    interpreter=$(find_python "$python") || {
      echo "bootstrap: Python $python not found (for the bpy of Blender $version): install it (pyenv install $python) or set PYTHON${python//./}" >&2
      exit 1
    }
    echo "bootstrap: creating $venv with $interpreter"
    "$interpreter" -m venv "$venv"
  fi
  "$venv/bin/python" -m pip install -q --disable-pip-version-check -r "requirements-blender$version.txt"
done

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
