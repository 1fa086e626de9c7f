#!/usr/bin/env bash
# Makes the venv of the aerial-view renderer (PyPI Mitsuba 3, numpy, Pillow) under target/.
# Not a CI step: CI reads the fixtures already rendered in tests/data/aerial/.
#   scripts/render-aerial/install.sh && target/venv-render/bin/python scripts/render-aerial/render.py --help
set -euo pipefail
cd "$(dirname "$0")/../.."
venv=target/venv-render
if [ ! -x "$venv/bin/python" ]; then
    python3 -m venv "$venv"
fi
"$venv/bin/pip" install --quiet mitsuba==3.9.1 drjit==1.5.0 numpy==2.4.6 pillow==13.0.0
