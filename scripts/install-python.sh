#!/usr/bin/env bash
# Installs one PyPI package at an exact version into the project's venv,
# ${MASON_PYENV:-target/pyenv} from the repository root (created, with python3-venv from
# Debian's packages if venv is missing). Idempotent: quick when that version is there.
# Prints the venv's python.  Usage: scripts/install-python.sh PACKAGE VERSION
set -euo pipefail
cd "$(dirname "$0")/.."
PACKAGE="$1"
VERSION="$2"
ENV="${MASON_PYENV:-target/pyenv}"
PY="$ENV/bin/python"
if [ -x "$PY" ] && "$PY" -c "import importlib.metadata as m, sys; sys.exit(m.version('$PACKAGE') != '$VERSION')" 2>/dev/null; then
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
"$PY" -m pip install --quiet --disable-pip-version-check "$PACKAGE==$VERSION"
echo "$PY"
