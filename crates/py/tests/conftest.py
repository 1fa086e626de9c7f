"""Shared fixtures: the repository's paths, the `mason` CLI to cross-check against, and the
shared benchmark data when it is present."""

import json
import os
import pathlib
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[3]
DATA = ROOT / "tests" / "data"
SHARED = ROOT.parent / "shared" / "benchmarks"


def _cli() -> pathlib.Path:
    explicit = os.environ.get("MASON_BIN")
    if explicit:
        return pathlib.Path(explicit)
    for profile in ("debug", "release"):
        p = ROOT / "target" / profile / "mason"
        if p.exists():
            return p
    pytest.skip("no mason binary: build it with `cargo build -p mason-cli` or set MASON_BIN")


@pytest.fixture(scope="session")
def cli():
    """Runs the CLI and returns its parsed JSON (it must exit 0)."""
    binary = _cli()

    def run(*args):
        out = subprocess.run(
            [str(binary), *map(str, args)], capture_output=True, text=True, cwd=ROOT
        )
        assert out.returncode == 0, out.stderr
        return json.loads(out.stdout)

    return run


@pytest.fixture(scope="session")
def data():
    return DATA


def shared(*parts):
    """A file of the shared benchmark data; skipped when absent, unless MASON_REQUIRE_SHARED=1."""
    p = SHARED.joinpath(*parts)
    if not p.exists():
        if os.environ.get("MASON_REQUIRE_SHARED") == "1":
            raise AssertionError(f"{p} is missing and MASON_REQUIRE_SHARED=1")
        pytest.skip(f"{p} is not here")
    return p


def without_stats(d):
    """A JSON document without its timing figures (which differ run to run)."""
    d = dict(d)
    d.pop("stats", None)
    return d
