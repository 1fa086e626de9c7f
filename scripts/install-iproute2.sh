#!/usr/bin/env bash
# Installs iproute2 (`ip netns`, for the real network cut of crates/cli/tests/agents_zenoh.rs) from
# Debian's packages when `ip` is missing. Idempotent. Namespaces also need root.
set -euo pipefail
if command -v ip >/dev/null 2>&1; then
    exit 0
fi
SUDO=""
if [ "$(id -u)" != "0" ]; then
    SUDO="sudo"
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends iproute2 >/dev/null
