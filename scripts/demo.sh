#!/usr/bin/env bash
# The main job: set up everything, then knit a default NURBS surface headless with the
# installed extension and write out/demo.png (render) and out/demo.blend.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"
scripts/bootstrap.sh
.venv/bin/python examples/demo.py --out out
