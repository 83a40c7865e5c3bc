"""``region(..., chunks=...)``: lazy, one Rust call per block, and bit-identical to the
single-process map on any scheduler -- including a multi-process ``dask.distributed``
cluster."""

from __future__ import annotations

import pickle
from pathlib import Path

import numpy as np
import pytest

import eccjump
from eccjump._base.bridge import jarm_grid
from eccjump.classification.classify import FIELDS, region
from eccjump.classification.fields import JARM
from eccjump.maps.dask import normalize_chunks, records_block
from eccjump.testing import assert_maps_equal

da = pytest.importorskip("dask.array")

GRID = {
    "alpha": np.radians(np.linspace(0.0, 90.0, 13)),
    "chi": np.linspace(0.0, 1.0, 11),
    "km_frac": np.linspace(0.0, 1.0, 7),
}


def assert_bits(reference, fields) -> None:
    """The fields of a labelled map (a dataset's variables) are the reference map's."""
    for f in FIELDS:
        x, y = getattr(reference.result, f), np.asarray(fields[f])
        assert x.dtype == y.dtype and x.shape == y.shape, f
        assert x.tobytes() == y.tobytes(), f  # NaNs compared by bytes


@pytest.fixture(scope="module")
def reference():
    return region(mu_s=0.7, **GRID)


@pytest.mark.parametrize("chunks", [4, (5, 3, -1), {"alpha": 2, "km": 3}, (1, 1, 1), -1])
def test_chunked_region_is_lazy_and_bit_identical(reference, chunks):
    lazy = region(mu_s=0.7, **GRID, chunks=chunks, n_threads=1)
    assert lazy.lazy and isinstance(lazy.result.is_jarm, da.Array)
    done = lazy.compute(scheduler="threads")
    assert not done.lazy
    assert_maps_equal(done, reference)


def test_one_rust_call_per_block(monkeypatch):
    calls = []
    real = eccjump._core.jarm_grid

    def counting(a, c, f, *rest, **options):
        calls.append((a.size, c.size, f.size))
        return real(a, c, f, *rest, **options)

    monkeypatch.setattr(eccjump._core, "jarm_grid", counting)
    lazy = region(mu_s=0.7, **GRID, chunks=(5, 6, -1))
    assert not calls  # nothing computed yet
    lazy.compute(scheduler="sync")
    assert sorted(calls) == sorted((a, c, 7) for a in (5, 5, 3) for c in (6, 5))


def test_lazy_xarray_dataset(reference):
    ds = region(mu_s=0.7, **GRID, chunks=4).to_xarray()
    assert ds.is_jarm.chunks is not None
    assert_bits(reference, {f: ds[f].values for f in FIELDS})


def test_block_function_and_graph_pickle():
    assert pickle.loads(pickle.dumps(records_block)) is records_block
    lazy = region(mu_s=0.7, **GRID, chunks=4)
    graph = dict(lazy.result.theta_J.__dask_graph__())
    assert pickle.loads(pickle.dumps(graph)).keys() == graph.keys()
    axes = (np.empty((0, 1, 1)), np.zeros((1, 2, 1)), np.zeros((1, 1, 3)))
    empty = records_block(*axes, grid=jarm_grid, fixed=(0.7, ()), record=JARM.record())
    assert empty.shape == (0, 2, 3) and empty.dtype == JARM.record()


def test_chunk_validation():
    assert normalize_chunks({"alpha": 2}, (5, 6, 7)) == (2, 6, 7)
    assert normalize_chunks(10, (5, 6, 7)) == (5, 6, 7)
    assert normalize_chunks((np.int64(-1), None, 3), (5, 6, 7)) == (5, 6, 3)
    for bad in (0, (1, 2), {"beta": 1}, 1.5, (True, 1, 1), -2, np.timedelta64(1)):
        with pytest.raises((ValueError, TypeError), match="chunks"):
            normalize_chunks(bad, (5, 6, 7))


def test_distributed_cluster_two_processes_bit_identical(reference, monkeypatch):
    distributed = pytest.importorskip("distributed")
    # Worker processes must import this eccjump (e.g. from a source tree on PYTHONPATH).
    src = str(Path(eccjump.__file__).parents[1])
    monkeypatch.setenv("PYTHONPATH", src)
    with (
        distributed.LocalCluster(
            n_workers=2,
            threads_per_worker=1,
            processes=True,
            dashboard_address=None,
            worker_dashboard_address=None,
        ) as cluster,
        distributed.Client(cluster) as client,
    ):
        lazy = region(mu_s=0.7, **GRID, chunks=(3, 4, -1), n_threads=1)
        done = lazy.compute()  # the client is the default scheduler
        assert_maps_equal(done, reference)
        ds = eccjump.region_dataset(mu_s=[0.7, 0.9], **GRID, chunks=(5, -1, -1), n_threads=1)
        ds = ds.compute()
        assert_bits(reference, {f: ds[f].sel(mu_s=0.7).values for f in FIELDS})
        workers = {w["id"] for w in client.scheduler_info()["workers"].values()}
        assert len(workers) == 2
