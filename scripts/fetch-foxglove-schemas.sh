#!/usr/bin/env bash
# Fetches Foxglove's published JSON schemas (npm `@foxglove/schemas`, MIT, pinned below) with
# npm into target/foxglove-schemas and writes each one as json/foxglove.NAME.json, for the MCAP
# read-back test (tests/python/read_mcap.py --foxglove DIR compares the schemas Mason's logs
# declare with these). Nothing of the package is committed. Idempotent. Prints the json/ folder.
# Needs node and npm (installed from Debian's packages when missing).
set -euo pipefail
cd "$(dirname "$0")/.."
VERSION=2.1.0
DIR="target/foxglove-schemas"
OUT="$DIR/json"
if [ -f "$OUT/.version" ] && [ "$(cat "$OUT/.version")" = "$VERSION" ]; then
    echo "$OUT"
    exit 0
fi
if ! command -v npm >/dev/null || ! command -v node >/dev/null; then
    SUDO=""
    if [ "$(id -u)" != "0" ]; then
        SUDO="sudo"
    fi
    export DEBIAN_FRONTEND=noninteractive
    $SUDO apt-get update -qq >&2
    $SUDO apt-get install -y -qq --no-install-recommends nodejs npm >&2
fi
rm -rf "$DIR"
mkdir -p "$OUT"
(cd "$DIR" && npm pack --silent "@foxglove/schemas@$VERSION" >/dev/null 2>&1 \
    && tar xzf "foxglove-schemas-$VERSION.tgz")
# The package's dist/jsonschema/index.js exports every schema as a plain object.
node -e '
const fs = require("fs");
const schemas = require(process.argv[1]);
let n = 0;
for (const value of Object.values(schemas)) {
    if (value && typeof value.title === "string" && value.title.startsWith("foxglove.")) {
        fs.writeFileSync(`${process.argv[2]}/${value.title}.json`, JSON.stringify(value, null, 2) + "\n");
        n += 1;
    }
}
if (n === 0) { console.error("no foxglove.* schemas in the package"); process.exit(1); }
' "$PWD/$DIR/package/dist/jsonschema/index.js" "$OUT"
echo "$VERSION" > "$OUT/.version"
echo "$OUT"
