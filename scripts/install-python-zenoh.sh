#!/usr/bin/env bash
# Installs PyPI's `eclipse-zenoh` 1.10.2 (the Zenoh Python package tests/python/ground_station.py
# listens to a running team with; the same version as the Rust crate, so that the wire protocol
# matches) into the venv ${MASON_PYENV:-target/pyenv} from the repository root (the venv the
# MCAP reader uses too). Idempotent: quick when it is there. Prints the venv's python.
set -euo pipefail
cd "$(dirname "$0")/.."
VERSION=1.10.2
ENV="${MASON_PYENV:-target/pyenv}"
PY="$ENV/bin/python"
if [ -x "$PY" ] && "$PY" -c "import importlib.metadata as m, sys; sys.exit(m.version('eclipse-zenoh') != '$VERSION')" 2>/dev/null; then
    echo "$PY"
    exit 0
fi
if ! python3 -c "import venv, ensurepip" 2>/dev/null; then
    SUDO=""
    if [ "$(id -u)" != "0" ]; then
        SUDO="sudo"
    fi
    export DEBIAN_FRONTEND=noninteractive
    $SUDO apt-get update -qq
    $SUDO apt-get install -y -qq --no-install-recommends python3-venv >/dev/null
fi
if [ ! -x "$PY" ]; then
    python3 -m venv "$ENV"
fi
"$PY" -m pip install --quiet --disable-pip-version-check "eclipse-zenoh==$VERSION"
echo "$PY"
