#!/usr/bin/env bash
# Installs PyPI's `mcap` 1.6.0 (the MCAP reader Mason's tests check its logs with) into the
# project's venv. Prints the venv's python.
exec "$(dirname "$0")/install-python.sh" mcap 1.6.0
