"""Python call overhead: hush's Python calls against the same C++ calls without Python.

    PYTHONPATH=<build>/python /usr/bin/python3 backends/python/bench/overhead.py [--repeats 15]

For Perlin, wavelet and Gabor (2D, default parameters), a batch of 2^18 samples: points
(noise(points), float32 (N, 2)) and a 512 x 512 grid (noise.grid), on backend="simd", one
thread. "C++" is the same hush::evaluate call timed inside the module with no Python objects
(Class._cpp_seconds_points / _cpp_seconds_grid: the inputs converted once, a preallocated
output, the GIL released); "Python" is the Python call itself, timed with perf_counter, its
array allocation and argument parsing included. Each figure is the median of --repeats runs
after one warm-up run; the two are interleaved so that a busy machine slows both alike.
Prints a Markdown table: ns/sample for each and the overhead, Python / C++ - 1.
"""
import argparse
import statistics
import time

import numpy as np

import hush

NOISES = {
    "perlin": lambda: hush.perlin(dim=2, seed=1),
    "wavelet": lambda: hush.wavelet(dim=2, seed=1),
    "gabor": lambda: hush.gabor(dim=2, seed=1),
}


def timed(f):
    t0 = time.perf_counter()
    f()
    return time.perf_counter() - t0


def measure(noise, kind, backend, repeats, n):
    if kind == "points":
        pts = (np.random.default_rng(0).random((n, 2), dtype=np.float32) - 0.5) * 64
        py = lambda: noise(pts, backend=backend)  # noqa: E731
        cpp = lambda: noise._cpp_seconds_points(pts, backend=backend)[0]  # noqa: E731
    else:
        side = int(round(n ** 0.5))
        shape, step = (side, side), 1 / 16
        py = lambda: noise.grid(shape, step=step, backend=backend)  # noqa: E731
        cpp = lambda: noise._cpp_seconds_grid(shape, step=step, backend=backend)[0]  # noqa: E731
    py(), cpp()  # warm-up: tiles, tables, pages
    t_py, t_cpp = [], []
    for _ in range(repeats):
        t_cpp.append(cpp())
        t_py.append(timed(py))
    return statistics.median(t_py) * 1e9 / n, statistics.median(t_cpp) * 1e9 / n


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=15)
    ap.add_argument("--log2", type=int, default=18, help="samples per batch: 2^log2")
    ap.add_argument("--backend", default="simd")
    args = ap.parse_args()
    n = 1 << args.log2
    print(f"hush {hush.version}, SIMD target {hush.simd_target()}, backend {args.backend}, "
          f"batches of 2^{args.log2} samples, median of {args.repeats}")
    print()
    print("| noise | batch | C++ ns/sample | Python ns/sample | overhead |")
    print("|---|---|---|---|---|")
    for name, make in NOISES.items():
        noise = make()
        for kind in ("points", "grid"):
            py, cpp = measure(noise, kind, args.backend, args.repeats, n)
            print(f"| {name} | {kind} | {cpp:.2f} | {py:.2f} | {100 * (py / cpp - 1):+.1f} % |",
                  flush=True)


if __name__ == "__main__":
    main()
