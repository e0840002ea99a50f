"""Bake a hush heightfield of any size to a chunked zarr store on a dask cluster.

    python3 examples/python/bake.py --size 65536 --chunk 4096 --workers 2 --out terrain.zarr

runs a LocalCluster on this machine (PYTHONPATH must reach the built module: see
docs/python.md). --scheduler tcp://HOST:8786 uses a running cluster instead (`dask scheduler`
on one machine, `dask worker tcp://HOST:8786` on each of the others; every worker needs
`import hush`). The store equals one noise.grid call over the whole grid, bit for bit, whichever
worker computes a chunk. Prints the throughput and each worker's peak memory.
"""
import argparse
import resource
import time

import hush
import hush.dask


def peak_rss_mib():
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--noise", choices=["fbm", "wavelet"], default="fbm")
    ap.add_argument("--size", type=int, default=65536, help="samples per side")
    ap.add_argument("--chunk", type=int, default=4096, help="samples per chunk side")
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--scheduler", help="address of a running dask scheduler")
    ap.add_argument("--out", required=True, help="the zarr store to write")
    args = ap.parse_args()

    import distributed

    if args.noise == "fbm":
        noise = hush.fractal(dim=2, octaves=10, seed=7)
    else:  # multiband wavelet noise, 8 bands with a 1/f falloff
        noise = hush.wavelet(dim=2, seed=7, tile_size=256, weights=[2.0 ** -i for i in range(8)])
    step = 4.0 / args.size
    cluster = None
    if args.scheduler:
        client = distributed.Client(args.scheduler)
    else:
        cluster = distributed.LocalCluster(n_workers=args.workers, threads_per_worker=1,
                                           dashboard_address=None)
        client = distributed.Client(cluster)
    try:
        array = hush.dask.grid(noise, (args.size, args.size), step=step, chunks=args.chunk)
        start = time.perf_counter()
        array.to_zarr(args.out, overwrite=True)
        seconds = time.perf_counter() - start
        samples = args.size * args.size
        print(f"{noise!r}: {args.size} x {args.size} = {samples:.3g} samples in {seconds:.1f} s, "
              f"{samples / seconds / 1e6:.1f} M samples/s, {len(client.scheduler_info()['workers'])} "
              f"workers, chunks {args.chunk} x {args.chunk} ({args.chunk ** 2 * 4 / 2 ** 20:.0f} MiB)")
        for worker, mib in sorted(client.run(peak_rss_mib).items()):
            print(f"  {worker}: peak memory {mib:.0f} MiB")
    finally:
        client.close()
        if cluster:
            cluster.close()


if __name__ == "__main__":
    main()
