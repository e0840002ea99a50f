"""Python call overhead: hush's Python calls against the same C++ calls without Python.

    PYTHONPATH=<build>/python /usr/bin/python3 backends/python/bench/overhead.py [--repeats 15]

For Perlin, wavelet and Gabor (2D, default parameters), a batch of 2^18 samples: points
(noise(points), float32 (N, 2)) and a 512 x 512 grid (noise.grid), on backend="simd", one
thread. "C++" is the same hush::evaluate call timed inside the module with no Python objects
(Class._cpp_seconds_points / _cpp_seconds_grid: the inputs converted once, the GIL released)
into a preallocated array. "Python, out=" is the Python call writing into that same array (so
both find it equally warm in the caches); "Python, new array" lets each call allocate its
result (numpy's fresh pages: a first touch per call). Each figure is the median (or, --stat
min, the fastest) of --repeats runs after one warm-up run, the three interleaved so that a busy machine slows them alike.
Prints a Markdown table: ns/sample and the overhead, Python / C++ - 1, then the fixed cost of
one call (a batch of one sample), in microseconds.
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


def calls(noise, kind, backend, n):
    """(Python with out=, Python allocating, C++ seconds) callables for a batch of n."""
    if kind == "points":
        pts = (np.random.default_rng(0).random((n, 2), dtype=np.float32) - 0.5) * 64
        out = np.empty(n, np.float32)
        return (lambda: noise(pts, backend=backend, out=out),
                lambda: noise(pts, backend=backend),
                lambda: noise._cpp_seconds_points(pts, backend=backend, out=out)[0])
    side = int(round(n ** 0.5))
    shape, step = (side, n // side), 1 / 16
    out = np.empty(shape, np.float32)
    return (lambda: noise.grid(shape, step=step, backend=backend, out=out),
            lambda: noise.grid(shape, step=step, backend=backend),
            lambda: noise._cpp_seconds_grid(shape, step=step, backend=backend, out=out)[0])


STAT = statistics.median


def measure(noise, kind, backend, repeats, n):
    """STAT of the seconds of (Python with out=, Python allocating, C++)."""
    py_out, py_new, cpp = calls(noise, kind, backend, n)
    py_out(), py_new(), cpp()  # warm-up: tiles, tables, pages
    t = [[], [], []]
    for _ in range(repeats):
        t[2].append(cpp())
        t[0].append(timed(py_out))
        t[1].append(timed(py_new))
    return [STAT(x) for x in t]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=15)
    ap.add_argument("--log2", type=int, default=18, help="samples per batch: 2^log2")
    ap.add_argument("--backend", default="simd")
    ap.add_argument("--stat", choices=["median", "min"], default="median",
                    help="per figure: the median of the runs, or the fastest (steadier on a "
                         "shared machine)")
    args = ap.parse_args()
    n = 1 << args.log2
    global STAT
    STAT = statistics.median if args.stat == "median" else min
    print(f"hush {hush.version}, SIMD target {hush.simd_target()}, backend {args.backend}, "
          f"batches of 2^{args.log2} samples, {args.stat} of {args.repeats} runs")
    print()
    print("| noise | batch | C++ ns/sample | Python, out= | overhead | Python, new array | overhead |")
    print("|---|---|---|---|---|---|---|")
    for name, make in NOISES.items():
        noise = make()
        for kind in ("points", "grid"):
            py_out, py_new, cpp = (t * 1e9 / n for t in
                                   measure(noise, kind, args.backend, args.repeats, n))
            print(f"| {name} | {kind} | {cpp:.2f} | {py_out:.2f} | {100 * (py_out / cpp - 1):+.1f} % "
                  f"| {py_new:.2f} | {100 * (py_new / cpp - 1):+.1f} % |", flush=True)
    print()
    print("| one call (1 sample) | C++ us | Python, out= us | Python, new array us |")
    print("|---|---|---|---|")
    noise = NOISES["perlin"]()
    for kind in ("points", "grid"):
        py_out, py_new, cpp = (t * 1e6 for t in
                               measure(noise, kind, args.backend, 20 * args.repeats, 1))
        print(f"| perlin {kind} | {cpp:.2f} | {py_out:.2f} | {py_new:.2f} |")


if __name__ == "__main__":
    main()
