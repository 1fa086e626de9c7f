"""A parameter sweep over a Dask cluster: team size × fault rate × wall × seeds.

Each (setting, chunk of seeds) is one Dask task that calls ``mason.monte_carlo(...,
per_run=True)`` on a worker; the per-run rows of a setting are joined in seed order and
summarised with ``mason.summarise``, which gives exactly the summary of one
``monte_carlo`` call over all the seeds (and of ``mason simulate --runs N --json``).

    python examples/sweep_dask.py                      # a LocalCluster on this machine
    python examples/sweep_dask.py tcp://scheduler:8786 # an existing cluster
"""

import itertools
import json
import sys

import numpy as np


def fly_chunk(wall_name, uavs, grasp_fail, first_seed, runs):
    """One task: the per-run rows of seeds first_seed .. first_seed + runs - 1."""
    import mason

    wall = mason.Wall.builtin(wall_name)
    out = mason.monte_carlo(
        wall,
        uavs=uavs,
        faults={"grasp_fail": grasp_fail},
        seed=first_seed,
        runs=runs,
        per_run=True,
    )
    return out["runs"]


def sweep(client, walls, teams, grasp_fails, seed=0, runs=200, chunk=50):
    """The summary of every setting, keyed by (wall, uavs, grasp_fail)."""
    import mason

    futures = {}
    for setting in itertools.product(walls, teams, grasp_fails):
        futures[setting] = [
            client.submit(fly_chunk, *setting, first, min(chunk, seed + runs - first), pure=True)
            for first in range(seed, seed + runs, chunk)
        ]
    results = {}
    for setting, parts in futures.items():
        rows = np.concatenate(client.gather(parts))
        results[setting] = mason.summarise(rows)
    return results


def main(argv):
    from dask.distributed import Client, LocalCluster

    if len(argv) > 1:
        client = Client(argv[1])
    else:
        client = Client(LocalCluster(n_workers=2, threads_per_worker=1, host="127.0.0.1"))
    with client:
        results = sweep(client, ["mbzirc", "levels5-width5"], [2, 3], [0.0, 0.2])
    for (wall, uavs, p), summary in results.items():
        print(wall, uavs, p, json.dumps(summary["makespan_s"]))


if __name__ == "__main__":
    main(sys.argv)
