#!/usr/bin/env bash
# Installs the second aerial-view renderer: Debian's blender (3.4.1 on bookworm, Cycles on the
# CPU) and the numpy and Pillow that its Python 3.11 imports (Debian's python3-numpy and
# python3-pil; Blender's Python reads /usr/lib/python3/dist-packages). Needs root.
# Not a CI step: CI reads the fixtures already rendered in tests/data/aerial/.
#   scripts/render-aerial/install-blender.sh
#   blender -b --factory-startup -noaudio -P scripts/render-aerial/render_blender.py -- OUT --seeds 0-9
set -euo pipefail
if ! command -v blender >/dev/null || ! /usr/bin/python3 -c 'import numpy, PIL' 2>/dev/null; then
    apt-get update
    DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends blender python3-numpy python3-pil
fi
blender -b --factory-startup -noaudio --python-expr 'import bpy, numpy, PIL; print("blender", bpy.app.version_string, "numpy", numpy.__version__)' 2>/dev/null | grep '^blender'
