"""hush.dask: chunked arrays equal one call bit for bit, on one machine and on a cluster that
loses a worker mid-bake."""
import os
import signal

import numpy as np
import pytest

import hush

dask = pytest.importorskip("dask")
distributed = pytest.importorskip("distributed")
import hush.dask  # noqa: E402


@pytest.mark.parametrize("make, shape, chunks", [
    (lambda: hush.fractal(dim=2, octaves=6, seed=3), (300, 500), (128, 96)),
    (lambda: hush.wavelet(dim=2, seed=5, tile_size=64, weights=[1, 0.5, 0.25]), (257, 131), 64),
    (lambda: hush.gabor(dim=3, seed=2), (20, 33, 17), (7, 11, 5)),
])
def test_chunks_assemble_into_the_one_call_grid(make, shape, chunks):
    n = make()
    origin, step = (1e5 + 0.1,) * len(shape), 1 / 3
    lazy = hush.dask.grid(n, shape, origin=origin, step=step, chunks=chunks)
    assert lazy.numblocks != (1,) * len(shape)
    assert np.array_equal(lazy.compute(scheduler="threads"), n.grid(shape, origin=origin, step=step))


def test_a_block_equals_the_same_samples_of_the_whole_grid():
    n = hush.perlin(dim=2, seed=9)
    whole = n.grid((40, 64), origin=(3e9 + 0.1, -7.25), step=1 / 3)
    block = n.grid((40, 64), origin=(3e9 + 0.1, -7.25), step=1 / 3, block=((5, 17), (20, 30)))
    assert np.array_equal(block, whole[5:25, 17:47])
    with pytest.raises(ValueError, match="size"):
        n.grid((40, 64), block=((30, 0), (20, 10)))


def test_a_cluster_that_loses_a_worker_still_bakes_the_one_call_result(tmp_path):
    zarr = pytest.importorskip("zarr")
    n = hush.fractal(dim=2, octaves=8, seed=7)
    shape, step = (2048, 2048), 1 / 256
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None, silence_logs=50) as cluster, \
            distributed.Client(cluster) as client:
        lazy = hush.dask.grid(n, shape, step=step, chunks=256, backend="scalar")
        blocks = lazy.to_delayed().ravel()
        futures = client.compute(list(blocks))
        done = distributed.as_completed(futures)
        first = next(done)  # a chunk finished: kill the worker that holds it
        holder = next(iter(next(iter(client.who_has([first]).values()))))
        pid = client.run(os.getpid, workers=[holder])[holder]
        os.kill(pid, signal.SIGKILL)
        parts = client.gather(futures)  # lost chunks are recomputed elsewhere
        assert len(parts) == 64
        baked = dask.array.block([[parts[i * 8 + j] for j in range(8)] for i in range(8)])
        assert np.array_equal(np.asarray(baked), n.grid(shape, step=step, backend="scalar"))
        # And through a chunked store, the README's bake on this cluster.
        store = str(tmp_path / "bake.zarr")
        lazy.to_zarr(store)
        assert np.array_equal(zarr.open(store, mode="r")[:], n.grid(shape, step=step, backend="scalar"))


def test_noises_pickle_their_parameters():
    import pickle
    n = hush.wavelet(dim=3, seed=4, tile_size=32, weights=[1, 0.5])
    m = pickle.loads(pickle.dumps(n))
    assert m.params == n.params
    pts = np.random.default_rng(0).random((100, 3)).astype(np.float32) * 10
    assert np.array_equal(m(pts), n(pts))
