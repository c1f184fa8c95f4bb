"""The same study on the local process pool and on a local Dask cluster: same numbers."""

from __future__ import annotations

import numpy as np
import pytest

from mrsuspension.studies import Study, run_study

distributed = pytest.importorskip("dask.distributed")


def test_local_pool_and_dask_cluster_agree() -> None:
    study = Study.from_dict(
        {
            "excitation": {"kind": "swept", "amplitude": 0.025, "frequencies": "log:4:1:8"},
            "simulation": {"dt": 5e-4},
            "cases": {
                "policy": {
                    "I": {"controller": {"law": "skyhook-hilo", "gain": 3.0}},
                    "IV": {"controller": {"law": "policy-iv", "gain": 300.0}},
                }
            },
            "study": {"measures": ["T_as", "DLC", "mean_current"]},
        }
    )
    local = run_study(study, workers=2, progress=False, cache_dir=False)
    with (
        distributed.LocalCluster(
            n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
        ) as cluster,
        distributed.Client(cluster) as client,
    ):
        by_address = run_study(
            study, executor=cluster.scheduler_address, progress=False, cache_dir=False
        )
        by_client = run_study(study, executor=client, progress=False, cache_dir=False)
    # the local pool reduces in the kernels (lane batches), Dask post-processes each run:
    # equal to round-off (the engine's contract: 1e-9 relative)
    for m in study.measures:
        np.testing.assert_allclose(local[m].values, by_address[m].values, rtol=1e-9, atol=0)
        np.testing.assert_allclose(local[m].values, by_client[m].values, rtol=1e-9, atol=0)
    assert local.content_hash == by_address.content_hash
