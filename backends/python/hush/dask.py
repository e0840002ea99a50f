"""hush noise as dask arrays: grids of any size, in chunks computed anywhere.

A hush noise is a pure function of position and parameters, so a grid splits into chunks that
can be computed on any worker: each chunk is ``noise.grid(shape, origin, step, block=...)``,
the block of the whole grid, bit-identical to the same samples of one call over the whole grid
(positions are formed from the whole grid's origin and step, never from a shifted origin).
Noises pickle their parameters, so a ``dask.distributed`` worker rebuilds the same noise::

    import hush, hush.dask
    n = hush.fractal(dim=2, octaves=10, seed=7)
    h = hush.dask.grid(n, (65536, 65536), step=1 / 1024, chunks=4096)   # lazy, 16 GiB
    h.to_zarr("terrain.zarr")                                              # computed chunk by chunk

Memory per task is one chunk (4 bytes a sample), whatever the array's size.
"""

import numpy as np


def grid(noise, shape, origin=0.0, step=1.0, chunks="auto", backend="simd", threads=1):
    """A dask.array (float32) of ``noise`` on the grid ``shape`` (numpy order: (ny, nx) or
    (nz, ny, nx)); sample (i, j[, k]) at origin + step * (i, j[, k]) as in ``noise.grid``.

    chunks: anything ``dask.array`` accepts ("auto", an int, a tuple per axis). backend and
    threads: as for ``noise.grid``, per chunk (threads=1 leaves parallelism to dask).
    """
    import dask.array as da
    from dask.base import tokenize

    shape = tuple(int(s) for s in shape)
    if len(shape) != noise.dimension:
        raise ValueError(f"shape: {len(shape)} axes given; valid: {noise.dimension}")
    chunks = da.core.normalize_chunks(chunks, shape, dtype=np.float32)

    def block(block_info=None):
        location = block_info[None]["array-location"]
        start = tuple(int(a) for a, _ in location)
        size = tuple(int(b - a) for a, b in location)
        return noise.grid(shape, origin, step, backend=backend, threads=threads,
                          block=(start, size))

    name = "hush-grid-" + tokenize(type(noise).__name__, noise.params, shape, origin, step,
                                   chunks, backend)
    return da.map_blocks(block, chunks=chunks, dtype=np.float32, name=name,
                         meta=np.empty((0,) * len(shape), np.float32))
