#!/usr/bin/env bash
# Repeated real fault runs of `mason launch` (issue #14): N launches of the MBZIRC wall with
# three agent processes over Zenoh at --speed 100, cycling through a kill -9 of one agent, a
# 60 s network cut under `auto`, and message loss + duplication + reordering, each with its own
# seed and fault time. Prints one line per run and a tally:
#   violations = merged traces that fail check_trace (launch exit 3): must be 0;
#   unfinished = safe runs that left bricks (launch exit 1);
#   crashed = agents that died by a signal or a panic (launch counts each as a failed UAV).
# Usage: [MASON=path/to/mason] scripts/fault-batch.sh [N=50] [OUT=target/fault-batch]
# Needs `cargo build --release --features zenoh` first (or MASON=target/debug/mason).
# Extra `mason launch` options go in LAUNCH_ARGS, e.g. LAUNCH_ARGS="--link tls".
set -uo pipefail
cd "$(dirname "$0")/.."
n="${1:-50}"
out="${2:-target/fault-batch}"
mason="${MASON:-target/release/mason}"
read -r -a extra <<<"${LAUNCH_ARGS:-}"
if [ ! -x "$mason" ]; then
  echo "build it first: cargo build --release --features zenoh" >&2
  exit 2
fi
mkdir -p "$out"
ok=0 unfinished=0 violations=0 other=0 crashed=0
for i in $(seq 1 "$n"); do
  seed=$((i + 100))
  case $((i % 3)) in
    0) t=$((200 + (i * 37) % 700)); fault=(--kill "$((i % 3))@$t"); what="kill $((i % 3))@$t" ;;
    1) a=$((300 + (i * 53) % 600)); fault=(--cut "$a-$((a + 60))"); what="cut $a-$((a + 60))" ;;
    2) fault=(--drop 0.3 --duplicate 0.2 --delay-jitter 0.5); what="loss 30% dup 20% jitter 0.5" ;;
  esac
  dir="$out/run-$i"
  rm -rf "$dir"
  start=$(date +%s.%N)
  "$mason" launch builtin:mbzirc --uavs 3 --speed 100 --coord auto --seed "$seed" \
    --out "$dir" "${fault[@]}" "${extra[@]}" >"$dir.txt" 2>&1
  code=$?
  wall=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { print b - a }')
  placed=$(grep -o "bricks placed: [0-9]*/[0-9]*" "$dir.txt" | head -1)
  crashes=$(grep -c "crashed:" "$dir.txt")
  crashed=$((crashed + crashes))
  [ "$crashes" -gt 0 ] && placed="$placed  CRASHED: $crashes"
  case $code in
    0) ok=$((ok + 1)) ;;
    1) unfinished=$((unfinished + 1)) ;;
    3) violations=$((violations + 1)) ;;
    *) other=$((other + 1)) ;;
  esac
  printf 'run %2d  seed %3d  %-30s exit %d  %s  %.1f s\n' "$i" "$seed" "$what" "$code" "$placed" "$wall"
done
echo "runs $n: finished $ok, unfinished $unfinished, check_trace violations $violations, other $other; agents crashed $crashed"
[ "$violations" -eq 0 ] && [ "$other" -eq 0 ]
