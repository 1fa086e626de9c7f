"""examples/sweep_dask.py on a LocalCluster of 2 workers on 127.0.0.1 gives exactly the
single-process summaries of the same seeds."""

import importlib.util

import pytest

import mason
from conftest import ROOT

distributed = pytest.importorskip("dask.distributed")


def load_example():
    spec = importlib.util.spec_from_file_location("sweep_dask", ROOT / "examples" / "sweep_dask.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_a_dask_sweep_equals_the_single_process_run():
    sweep = load_example()
    cluster = distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, host="127.0.0.1", dashboard_address=None
    )
    with cluster, distributed.Client(cluster) as client:
        results = sweep.sweep(client, ["mbzirc"], [2, 3], [0.0, 0.3], seed=5, runs=60, chunk=25)
    assert len(results) == 4
    for (wall, uavs, p), summary in results.items():
        alone = mason.monte_carlo(
            mason.Wall.builtin(wall), uavs=uavs, faults={"grasp_fail": p}, seed=5, runs=60
        )
        assert summary == alone["summary"], (wall, uavs, p)
        assert summary["runs"] == 60
