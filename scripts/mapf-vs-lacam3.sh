#!/usr/bin/env bash
# Runs lacam3 and `mason crew --resolve lacam` one after the other, each alone on the machine
# with all its cores, on a representative subset of the MovingAI benchmark (or, --wide, on the
# rest of its maps), at time limits of 1, 10 and 30 s, and writes one tab-separated line per
# run and solver. (Until 2026-11-28 the two ran at the same time "so that both saw the same
# load"; but lacam3 runs 15 threads and Mason two, so on two cores lacam3 took 144 % of a core
# and Mason 43 %, measured with /usr/bin/time on random-32-32-20 409 agents at 10 s: not equal
# time. Run the script on a quiet machine.)
#
# usage: scripts/mapf-vs-lacam3.sh LACAM3_BINARY MASON_BINARY DATA_DIR OUT_PREFIX [--wide]
#   DATA_DIR holds maps/NAME.map and scen/NAME-random-1.scen (MovingAI layout).
#   --wide: instead, the other 24 maps of the MovingAI benchmark (every map family) at 1 and
#   10 s, and the 1000-agent points of eight of them at 30 s. A map whose random-1 scenario is
#   not in DATA_DIR gets one from `mason generate scen --map MAP --agents MAX --seed 1` (MAX:
#   the map's largest count; the same pairs on every run; both solvers read the first N pairs
#   of that one file).
#   Writes OUT_PREFIX-lacam3.tsv and OUT_PREFIX-mason.tsv with the columns
#   map agents limit_s seed solved soc soc_lb makespan first_ms
# lacam3 (Kei18/lacam3) is built outside this repository; its `soc` is the same measure as
# Mason's sum of costs (steps until each agent last arrives at its goal).
set -euo pipefail
L=$1; M=$2; D=$3; OUT=$4; MODE=${5:-}
header=$'map\tagents\tlimit_s\tseed\tsolved\tsoc\tsoc_lb\tmakespan\tfirst_ms'
echo "$header" > "$OUT-lacam3.tsv"
echo "$header" > "$OUT-mason.tsv"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
scen_of() { # map max_agents
  local f="$D/scen/$1-random-1.scen"
  if [ ! -f "$f" ]; then
    f="$tmp/$1-mason-1.scen"
    [ -f "$f" ] || "$M" generate scen --map "$D/maps/$1.map" --agents "$2" --seed 1 --out "$f"
  fi
  echo "$f"
}
point() { # map agents limit seed [scenario]
  local map=$1 n=$2 t=$3 s=$4 scen=${5:-$D/scen/$1-random-1.scen}
  # A solver that dies writes nothing: never read the previous point's output instead.
  rm -f "$tmp/l.txt" "$tmp/m.json"
  "$L" -m "$D/maps/$map.map" -i "$scen" -N "$n" -s "$s" -t "$t" \
    -v 0 -l -o "$tmp/l.txt" >/dev/null 2>&1 || true
  "$M" crew "$D/maps/$map.map" --scen "$scen" --agents "$n" \
    --resolve lacam --connectivity 4 --seed "$s" --time-limit "$t" --json --quiet \
    >"$tmp/m.json" 2>/dev/null || true
  python3 - "$tmp/l.txt" "$tmp/m.json" "$map" "$n" "$t" "$s" >>"$OUT-lacam3.tsv" 2>>"$OUT-mason.tsv" <<'PY'
import json, sys
l, m, map_, n, t, s = sys.argv[1:]
try:
    kv = dict(line.strip().split("=", 1) for line in open(l) if "=" in line)
except OSError:
    kv = {}
solved = kv.get("solved") == "1"
print("\t".join([map_, n, t, s, "1" if solved else "0", kv["soc"] if solved else "-",
                 kv.get("soc_lb", "-"), kv["makespan"] if solved else "-",
                 kv["comp_time_initial_solution"] if solved else "-"]))
try:
    d = json.load(open(m))
except Exception:
    d = {}
ok = d.get("status") in ("feasible", "optimal")
st = d.get("stats", {})
print("\t".join([map_, n, t, s, "1" if ok else "0", str(d["sum_of_costs"]) if ok else "-",
                 str(d.get("lower_bound_sum_of_costs", "-")), str(d["makespan"]) if ok else "-",
                 str(round(st["first_solution_ms"])) if ok else "-"]), file=sys.stderr)
PY
  echo "$map $n ${t}s seed $s done" >&2
}
if [ "$MODE" = --wide ]; then
  for t in 1 10; do
    for spec in empty-8-8:8,16,32 empty-16-16:32,64,128 empty-48-48:200,500,1000 \
        random-32-32-10:100,300,461 random-64-64-10:300,1000 maze-32-32-4:50,200,395 \
        maze-128-128-1:300,1000 maze-128-128-2:300,1000 maze-128-128-10:300,1000 \
        room-64-64-16:300,1000 warehouse-10-20-10-2-2:500,1000 \
        warehouse-20-40-10-2-1:500,1000 warehouse-20-40-10-2-2:500,1000 \
        den312d:300,1000 brc202d:300,1000 lak303d:300,1000 orz900d:300,1000 \
        ost003d:300,1000 ht_chantry:300,1000 ht_mansion_n:300,1000 \
        lt_gallowstemplar_n:300,1000 w_woundedcoast:300,1000 Berlin_1_256:500,1000 \
        Paris_1_256:500,1000; do
      map=${spec%%:*}; counts=${spec#*:}; max=${counts##*,}
      scen=$(scen_of "$map" "$max")
      for k in ${counts//,/ }; do point "$map" "$k" "$t" 0 "$scen"; done
    done
  done
  for spec in empty-48-48:1000 random-64-64-10:1000 maze-128-128-10:1000 room-64-64-16:1000 \
      warehouse-20-40-10-2-1:1000 den312d:1000 lak303d:1000 Berlin_1_256:1000; do
    map=${spec%%:*}
    point "$map" "${spec#*:}" 30 0 "$(scen_of "$map" "${spec#*:}")"
  done
  exit 0
fi
for t in 1 10; do
  for spec in empty-32-32:100,300,512 random-32-32-20:100,200,409 maze-32-32-2:50,100,333 \
      room-32-32-4:100,200,341 room-64-64-8:300,1000 random-64-64-20:300,1000 \
      den520d:500,1000 Boston_0_256:500,1000 warehouse-10-20-10-2-1:500,800,1000; do
    map=${spec%%:*}
    for n in ${spec#*:}; do n=${n//,/ }; for k in $n; do point "$map" "$k" "$t" 0; done; done
  done
done
for spec in room-32-32-4:341 warehouse-10-20-10-2-1:800 warehouse-10-20-10-2-1:1000 \
    den520d:1000 random-64-64-20:1000; do
  point "${spec%%:*}" "${spec#*:}" 30 0
done
for s in 1 2 3; do point room-32-32-4 341 10 "$s"; done
for s in 1 2 3; do point random-32-32-20 409 10 "$s"; done
