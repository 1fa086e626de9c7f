"""The Python package's performance targets (#26), measured side by side with the CLI.

    python crates/py/bench/targets.py [--mason target/release/mason] [--shared ../shared/benchmarks]

1. `plan_schedule` on CMCP wall_1024 (reward, T = 2500, the deterministic search), whole call
   from Python, against the search time the CLI reports for the same problem (`stats.elapsed_ms`
   of `mason plan --objective reward --json`): median of 5 runs each.
2. `crew.solve` with 1000 robots on the warehouse map: the time of the call beyond the
   solver's own (`elapsed_s`), i.e. reading the arrays, checking the plan and building the
   (N, T, 2) path array, and the time of the `paths` getter (the copy into numpy).
"""

import argparse
import json
import pathlib
import statistics
import subprocess
import time

import mason

ROOT = pathlib.Path(__file__).resolve().parents[3]


def median_of(n, f):
    return statistics.median(f() for _ in range(n))


def schedule(args):
    wall_path = args.shared / "walls-cmcp" / "config" / "wall_1024_multi.txt"
    wall = mason.Wall.load(wall_path)

    def py():
        t0 = time.perf_counter()
        mason.plan_schedule(wall, objective="reward", budget=2500, model="cmcp", time_limit=None)
        return time.perf_counter() - t0

    def cli():
        out = subprocess.run(
            [args.mason, "plan", str(wall_path), "--objective", "reward", "--budget", "2500",
             "--model", "cmcp", "--json"],
            capture_output=True, text=True, check=True,
        )
        return json.loads(out.stdout)["stats"]["elapsed_ms"] / 1e3

    p, c = median_of(5, py), median_of(5, cli)
    print(f"plan_schedule wall_1024 reward T=2500: python {p:.3f} s, CLI search {c:.3f} s, ratio {p / c:.3f}")


def crew(args):
    grid, starts, goals = mason.crew.load_movingai(
        args.shared / "mapf" / "maps" / "warehouse-10-20-10-2-1.map",
        args.shared / "mapf" / "scen" / "warehouse-10-20-10-2-1-random-1.scen",
        agents=1000,
    )
    overheads, getters = [], []
    for _ in range(3):
        t0 = time.perf_counter()
        sol = mason.crew.solve(grid, starts, goals, resolve="lacam", time_limit=2.0)
        total = time.perf_counter() - t0
        t1 = time.perf_counter()
        paths = sol.paths
        getters.append(time.perf_counter() - t1)
        overheads.append(total - sol.elapsed_s)
    print(
        f"crew.solve 1000 robots: paths {paths.shape}, call beyond the solver {1e3 * statistics.median(overheads):.1f} ms "
        f"(median of 3), paths getter {1e3 * statistics.median(getters):.2f} ms"
    )


if __name__ == "__main__":
    ap = argparse.ArgumentParser()
    ap.add_argument("--mason", default=str(ROOT / "target" / "release" / "mason"))
    ap.add_argument("--shared", type=pathlib.Path, default=ROOT.parent / "shared" / "benchmarks")
    args = ap.parse_args()
    schedule(args)
    crew(args)
