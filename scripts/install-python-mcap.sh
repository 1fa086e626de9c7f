#!/usr/bin/env bash
# Installs PyPI's `mcap` 1.6.0 (the MCAP reader Mason's tests check its logs with) and
# `jsonschema` 4.26.0 (which validates every message against the schema its channel declares)
# into the project's venv. Prints the venv's python.
"$(dirname "$0")/install-python.sh" jsonschema 4.26.0 >/dev/null
exec "$(dirname "$0")/install-python.sh" mcap 1.6.0
