#!/usr/bin/env bash
# Fuzzes every reader (#15): installs cargo-fuzz if missing, then runs each target of fuzz/
# for N executions (default 10 000 000) or, with FUZZ_SECONDS=S, for S seconds each.
# Stable Rust is enough (RUSTC_BOOTSTRAP=1; the sanitizer runtimes ship with stable).
# Mason has no `unsafe` code, so the targets are built without a sanitizer (`-s none`,
# several times as many executions per second): what they look for is a panic, an overflow
# (overflow checks stay on), a hang or a blow-up in memory. FUZZ_SANITIZER=address brings
# AddressSanitizer back. FUZZ_FLAGS adds cargo-fuzz flags, e.g. FUZZ_FLAGS=--no-trace-compares
# (3.4 times the executions per second on wall_png, whose comparisons libFuzzer otherwise traces).
# Crashes land in fuzz/artifacts/TARGET/; turn each into a regression test.
#   scripts/fuzz.sh                 # every target, 10 million executions each
#   scripts/fuzz.sh 100000 cmcp     # one target, 100 000 executions
set -euo pipefail
cd "$(dirname "$0")/.."
runs="${1:-10000000}"
shift || true
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
    targets=(layer_text cmcp wall_png movingai birdseye_png aerial_view toml_files trace_file fault_layer agent_sample)
fi
if ! cargo fuzz --version >/dev/null 2>&1; then
    cargo install cargo-fuzz --locked
fi
export RUSTC_BOOTSTRAP=1
for t in "${targets[@]}"; do
    mkdir -p "fuzz/corpus/$t"
    limit=(-runs="$runs")
    if [ -n "${FUZZ_SECONDS:-}" ]; then
        limit=(-max_total_time="$FUZZ_SECONDS")
    fi
    echo "== $t"
    # shellcheck disable=SC2086 # FUZZ_FLAGS is a list of flags
    cargo +stable fuzz run -s "${FUZZ_SANITIZER:-none}" ${FUZZ_FLAGS:-} "$t" "fuzz/corpus/$t" -- "${limit[@]}" -rss_limit_mb=2048 \
        -max_len=65536 -print_final_stats=1
done
