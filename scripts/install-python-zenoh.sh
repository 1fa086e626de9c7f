#!/usr/bin/env bash
# Installs PyPI's `eclipse-zenoh` 1.10.2 (the Zenoh Python package tests/python/ground_station.py
# listens to a running team with; the same version as the Rust crate, so that the wire protocol
# matches) into the project's venv, beside the MCAP reader. Prints the venv's python.
exec "$(dirname "$0")/install-python.sh" eclipse-zenoh 1.10.2
