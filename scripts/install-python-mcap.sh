#!/usr/bin/env bash
# Installs PyPI's `mcap` 1.6.0 (the MCAP reader Mason's tests check its logs with) into a venv,
# ${MASON_PYENV:-target/pyenv} from the repository root. Idempotent: quick when it is there.
# Prints the venv's python.
set -euo pipefail
cd "$(dirname "$0")/.."
VERSION=1.6.0
ENV="${MASON_PYENV:-target/pyenv}"
PY="$ENV/bin/python"
if [ -x "$PY" ] && "$PY" -c "import importlib.metadata as m, sys; sys.exit(m.version('mcap') != '$VERSION')" 2>/dev/null; then
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
python3 -m venv "$ENV"
"$PY" -m pip install --quiet --disable-pip-version-check "mcap==$VERSION"
echo "$PY"
