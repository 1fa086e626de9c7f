#!/usr/bin/env bash
# Hostile inputs against the whole process (#32): each case is run with /usr/bin/time and
# judged on its exit code (0, 1 or 2: never a crash), its wall time (at most --time-limit + 1 s
# where it gives one, else 30 s) and its peak memory (at most 2 GB). Prints one row per case
# and exits 1 if any case breaks a rule. A benchmark, not a test: run it on a quiet machine.
#
#   scripts/hostile-limits.sh [MASON_BINARY]     (default: target/release/mason, built first)
set -euo pipefail
cd "$(dirname "$0")/.."
M="${1:-}"
if [[ -z "$M" ]]; then
    cargo build --release -q -p mason-cli
    M=target/release/mason
fi
M="$(realpath "$M")"
W="$(mktemp -d)"
trap 'rm -rf "$W"' EXIT
cd "$W"

python3 - <<'EOF'
# A million-brick layer-text wall, a 100-level one, 3 000 CMCP bricks in one spot, a dense
# 10 000-brick CMCP grid, an open 4096 x 4096 map with 5 robots, and mission and model files
# with zero, tiny and huge values.
row = " ".join(["R"] * 1000)
open("million.txt", "w").write("\n".join([row] * 1000) + "\n")
open("levels100.txt", "w").write("\n".join(["R G B R G B R G B R"] * 100) + "\n")
with open("overlap3000.txt", "w") as f:
    for i in range(3000):
        f.write(f"{i} 1 0.0 0.0 0.1 0\n")
with open("grid10k.txt", "w") as f:
    i = 0
    for z in range(10):
        for y in range(10):
            for x in range(100):
                f.write(f"{i} 1 {x * 0.3:.3f} {y * 0.3:.3f} {0.1 + z * 0.2:.3f} 0\n")
                i += 1
with open("open4096.map", "w") as f:
    f.write("type octile\nheight 4096\nwidth 4096\nmap\n")
    f.write(("." * 4096 + "\n") * 4096)
with open("open4096.scen", "w") as f:
    f.write("version 1\n")
    for k in range(5):
        f.write(f"0\topen4096.map\t4096\t4096\t{k}\t{k}\t{4095 - k}\t{4095 - k}\t1\n")
open("zero.toml", "w").write(
    "max_time_s = 1000000.0\n[uav]\nspeed = 1e9\ncheck_s = 0.0\ntakeoff_s = 0.0\n"
    "land_s = 0.0\ndetect_s = 0.0\nabove_s = 0.0\nzone_transit_s = 0.0\n"
    "[faults]\ngrasp_fail = 0.999\ndetect_fail = 0.999\n")
piles = ", ".join(f"{{ x = {i % 50}.0, y = {i // 50 % 40}.0 }}" for i in range(20000))
open("piles.toml", "w").write(f"[arena]\npiles = [{piles}]\n")
open("d1.toml", "w").write('base = "cmcp"\ndistance_m = 1.0\n')
open("tiny.toml", "w").write('base = "cmcp"\n[red]\nplace_s = 1e-10\n')
open("bigbase.toml", "w").write('base = "' + "x" * 5000 + '"\n')
EOF

fail=0
printf '%-78s %5s %8s %9s  %s\n' "case" "exit" "wall s" "peak MB" "verdict"
# Time each case with bash's own clock (whole process, reading and writing included).
timed() {
    local limit="$1"
    shift
    local start end
    start=$(date +%s.%N)
    set +e
    /usr/bin/time -f "%M" -o rss.txt timeout 120 "$M" "$@" >out.txt 2>err.txt
    local code=$?
    set -e
    end=$(date +%s.%N)
    WALL=$(awk -v a="$start" -v b="$end" 'BEGIN{printf "%.2f", b - a}')
    local rss=$(($(tail -1 rss.txt) / 1024))
    local verdict=ok
    if [[ $code -gt 2 ]] || grep -q "panicked" err.txt; then verdict="CRASH ($code)"; fi
    if ((rss > 2048)); then verdict="MEMORY"; fi
    if awk -v w="$WALL" -v l="$limit" 'BEGIN{exit !(w > l)}'; then verdict="TIME (> $limit s)"; fi
    printf '%-78s %5s %8s %9s  %s\n' "$(echo "$*" | cut -c1-78)" "$code" "$WALL" "$rss" "$verdict"
    [[ $verdict == ok ]] || fail=1
}

timed 6 plan million.txt --objective makespan --time-limit 5 --json
timed 6 plan million.txt --objective expected --uav-hazard 0.1 --uavs 64 --budget 100000 --time-limit 5
timed 6 plan million.txt --objective reward --budget 100000 --time-limit 5
timed 6 plan million.txt --planner exact --time-limit 5
timed 30 wall show million.txt --json
timed 30 plan overlap3000.txt --objective makespan
timed 30 wall show overlap3000.txt --json
timed 6 plan grid10k.txt --objective makespan --model d1.toml --time-limit 5
timed 6 plan grid10k.txt --objective makespan --model d1.toml --uavs 64 --time-limit 5
timed 6 plan grid10k.txt --objective expected --uav-hazard 1 --budget 20000 --model d1.toml --time-limit 5
timed 30 plan levels100.txt --objective makespan
timed 30 plan builtin:mbzirc --objective expected --uav-hazard 1 --uavs 64 --budget 600
timed 30 plan builtin:thesis-2x5 --objective makespan --model tiny.toml
timed 30 plan builtin:thesis-2x5 --objective makespan --model bigbase.toml
timed 6 crew open4096.map --scen open4096.scen --resolve lacam --time-limit 5
timed 6 crew open4096.map --scen open4096.scen --assign joint --time-limit 5
timed 30 simulate builtin:mbzirc --mission zero.toml --json
timed 30 simulate builtin:mbzirc --mission zero.toml --runs 4
timed 30 simulate builtin:mbzirc --mission piles.toml
timed 30 simulate builtin:mbzirc --coord windows --slot 5e-324
timed 30 simulate builtin:mbzirc --uav-hazard 1e-300 --runs 1000
exit $fail
