#!/usr/bin/env bash
# The Python package (#26): builds Mason's abi3 wheel with maturin, installs it into a venv
# under target/ (${MASON_PYPKG_ENV:-target/pymason}; with PyPI's maturin, pytest, numpy and
# dask at pinned versions, installed by this script), and runs crates/py/tests against it and
# against the `mason` CLI (${MASON_BIN:-target/debug/mason}, built here if missing).
# Run from anywhere; extra arguments go to pytest.
set -euo pipefail
cd "$(dirname "$0")/.."
ENV="${MASON_PYPKG_ENV:-target/pymason}"
# The venv (made, with python3-venv from Debian's packages if missing) and maturin.
PY="$(MASON_PYENV="$ENV" scripts/install-python.sh maturin 1.16.0 | tail -n 1)"
"$PY" -m pip install --quiet --disable-pip-version-check \
    pytest==9.2.0 numpy==2.4.6 dask==2026.8.0 distributed==2026.8.0
rm -rf target/wheels
"$ENV/bin/maturin" build --release --quiet -m crates/py/Cargo.toml -i "$PY" -o target/wheels
"$PY" -m pip install --quiet --disable-pip-version-check --force-reinstall --no-deps target/wheels/mason-*.whl
export MASON_BIN="${MASON_BIN:-target/debug/mason}"
if [ ! -x "$MASON_BIN" ]; then
    cargo build -p mason-cli
fi
MASON_BIN="$(realpath "$MASON_BIN")"
export MASON_BIN
PY="$(realpath -s "$PY")"
# The installed wheel, not the sources: run from a folder where `mason` is not a directory.
cd crates/py/tests
exec "$PY" -m pytest -q -p no:cacheprovider "$@" .
