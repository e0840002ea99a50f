"""backend="glsl": hush::exec::glsl on the process's headless GL device. Grids equal the C++
call (the hush program's --backend glsl output) bit for bit, and every batch lies within the
GLSL backend's stated tolerance of the CPU (backends/glsl/include/hush/glsl/device.hpp)."""
import threading

import numpy as np
import pytest

import hush

pytestmark = pytest.mark.skipif(not hush.glsl_available(),
                                reason="the module was built without the GL backend")


@pytest.fixture(scope="module")
def gl():
    try:
        return hush.glsl_renderer()
    except RuntimeError as e:  # built with OSMesa or EGL, but no context on this machine
        pytest.skip(str(e))


# ---- Bit for bit the C++ exec::glsl call: the program's .npy of the same grid.
@pytest.mark.parametrize("noise, dim, size, options, make", [
    ("perlin", 2, (32, 48), [], lambda: hush.perlin(dim=2, seed=11)),
    ("perlin", 3, (6, 10, 12), [], lambda: hush.perlin(dim=3, seed=11)),
    ("perlin", 3, (6, 10, 12), ["--octaves", "5", "--fractal", "fbm"],
     lambda: hush.fractal(dim=3, seed=11, octaves=5)),
    ("wavelet", 2, (24, 40), ["--tile-size", "32"], lambda: hush.wavelet(dim=2, seed=11, tile_size=32)),
    ("gabor", 2, (24, 40), [], lambda: hush.gabor(dim=2, seed=11)),
])
def test_glsl_grid_equals_the_program(gl, hush_program, noise, dim, size, options, make):
    want = hush_program("sample", noise, "--dim", str(dim), "--size", "x".join(map(str, size[::-1])),
                        "--origin", ",".join(["3.25", "-7.5", "0.5"][:dim]), "--step", "0.0625",
                        "--seed", "11", "--backend", "glsl", *options)
    got = make().grid(size, origin=(3.25, -7.5, 0.5)[:dim], step=0.0625, backend="glsl")
    assert got.dtype == np.float32 and got.shape == want.shape
    assert np.array_equal(got, want)


# ---- Within the stated tolerance of the CPU float path (backends/glsl: device.hpp and each
# <noise>/program.hpp): Perlin 2^-15; fBm 2 K sum|w_i| (2^-16 + (nb + 4) 2^-24) (2e-4 at 6
# octaves); wavelet and Gabor twice the noise's float budget, anisotropic its program's
# tolerance, here as bounds for these parameters (the C++ kits' tests check the exact ones).
@pytest.mark.parametrize("make, tol", [
    (lambda: hush.perlin(dim=2, seed=3), 2.0 ** -15),
    (lambda: hush.perlin(dim=3, seed=3), 2.0 ** -15),
    (lambda: hush.fractal(dim=2, seed=3, octaves=6), 2e-4),
    (lambda: hush.wavelet(dim=3, seed=3, tile_size=32, weights=[1, 0.5]), 1e-4),
    (lambda: hush.gabor(dim=2, seed=3), 5e-4),
    (lambda: hush.anisotropic(seed=3, tile_size=64), 1e-3),
])
def test_glsl_points_and_grids_are_within_tolerance_of_the_cpu(gl, make, tol):
    n = make()
    d = n.dimension
    pts = (np.random.default_rng(5).random((5000, d), dtype=np.float32) - 0.5) * 40
    assert np.max(np.abs(n(pts, backend="glsl") - n(pts, backend="scalar"))) <= tol
    shape = (7, 9, 11)[-d:]
    assert np.max(np.abs(n.grid(shape, origin=0.3, step=0.37, backend="glsl") -
                         n.grid(shape, origin=0.3, step=0.37, backend="scalar"))) <= tol


def test_glsl_gradients_and_samples(gl):
    n = hush.perlin(dim=3, seed=2)
    pts = np.random.default_rng(1).random((1000, 3), dtype=np.float32) * 9
    v, g = n.gradient(pts, backend="glsl")
    vc, gc = n.gradient(pts, backend="scalar")
    assert np.max(np.abs(v - vc)) <= 2.0 ** -15 and np.max(np.abs(g - gc)) <= 2.0 ** -15 * 11
    w = hush.wavelet(dim=2, seed=2, tile_size=32)
    p2 = pts[:, :2].copy()
    widths = np.full(1000, 0.7)
    assert np.max(np.abs(w.sample(p2, footprints=widths, backend="glsl") -
                         w.sample(p2, footprints=widths, backend="scalar"))) <= 1e-4


def test_glsl_block_equals_the_whole_grid_and_repeats(gl):
    n = hush.gabor(dim=2, seed=9)
    whole = n.grid((40, 64), origin=(1e4 + 0.1, -7.25), step=1 / 3, backend="glsl")
    block = n.grid((40, 64), origin=(1e4 + 0.1, -7.25), step=1 / 3, backend="glsl",
                   block=((5, 17), (20, 30)))
    assert np.array_equal(block, whole[5:25, 17:47])
    assert np.array_equal(n.grid((40, 64), origin=(1e4 + 0.1, -7.25), step=1 / 3, backend="glsl"),
                          whole)


def test_glsl_from_many_threads_runs_on_the_one_device(gl):
    n = hush.perlin(dim=2, seed=4)
    want = n.grid((64, 64), step=0.1, backend="glsl")
    results = [None] * 6

    def work(i):
        results[i] = n.grid((64, 64), step=0.1, backend="glsl")

    threads = [threading.Thread(target=work, args=(i,)) for i in range(6)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert all(np.array_equal(r, want) for r in results)


def test_glsl_errors_name_the_problem(gl):
    n = hush.perlin(dim=2)
    with pytest.raises(ValueError, match="threads.*glsl"):
        n(np.zeros((4, 2), np.float32), backend="glsl", threads=0)
    with pytest.raises(ValueError, match="backend 'vulkan' is invalid; valid: 'simd', 'scalar', 'glsl'"):
        hush.coherent().advance(np.ones((8, 8), np.float32), np.zeros((8, 8, 3), np.float32),
                                backend="vulkan")


def test_coherent_stream_advances_on_glsl_within_tolerance_of_the_cpu(gl):
    # A scene panning 1.5 pixels a frame, with an occluder's disocclusions: the GL stream's frames
    # against the scalar stream's, within tests/coherent/glsl_coherent_test.cpp's bound for white
    # input, 2 (12 / (1 - alpha) + 1) 2^-24 M with M = 8 (the value bound); then one stream that
    # changes backend mid-sequence (its history comes back from the device) against both.
    alpha = 0.9
    tol = 2 * (12 / (1 - alpha) + 1) * 2.0 ** -24 * 8
    h, w = 24, 32
    gpu, cpu, mixed = (hush.coherent(seed=5, alpha=alpha, channels=2) for _ in range(3))
    for i in range(6):
        depth = np.full((h, w), 10.0, np.float32)
        depth[6:14, 4 + 2 * i:12 + 2 * i] = 3.0  # the occluder moves 2 pixels a frame
        velocity = np.zeros((h, w, 3), np.float32)
        velocity[..., 0] = 1.5
        velocity[6:14, 4 + 2 * i:12 + 2 * i, 0] = 2.0
        g = gpu.advance(depth, velocity, backend="glsl")
        c = cpu.advance(depth, velocity, backend="scalar")
        m = mixed.advance(depth, velocity, backend="glsl" if i % 2 == 0 else "simd")
        assert g.shape == c.shape == (2, h, w) and g.dtype == np.float32
        assert np.std(c) > 0.3
        assert np.max(np.abs(g - c)) <= tol
        assert np.max(np.abs(m - c)) <= tol
    del gpu, mixed  # their GL buffers are deleted on the GL thread
    import gc
    gc.collect()
    assert hush.glsl_renderer()  # the device still answers


def test_npr_gabor_renders_on_glsl(gl):
    n = hush.npr_gabor(seed=1)
    h, w = 64, 64
    depth = np.full((h, w), 5.0, np.float32)
    ids = np.zeros((h, w), np.uint32)
    args = (depth, np.array([[0, 2, 1]]), np.array([[4, 4], [60, 4], [4, 60]], np.float32),
            np.full(3, 5.0, np.float32), np.array([0], np.uint32))
    kw = dict(frame_object_id=ids, frame_triangle_id=ids)
    cpu = n.render(*args, backend="scalar", **kw)
    gpu = n.render(*args, backend="glsl", **kw)
    assert np.count_nonzero(cpu) > 100
    assert np.max(np.abs(gpu - cpu)) <= 1e-3 * max(1.0, np.max(np.abs(cpu)))


def test_glsl_in_a_forked_child_raises_instead_of_hanging(gl):
    import os
    n = hush.perlin(dim=2)
    n.grid((4, 4), backend="glsl")  # the device exists in this process
    pid = os.fork()
    if pid == 0:
        try:
            n.grid((4, 4), backend="glsl")
        except RuntimeError as e:
            os._exit(5 if "forked" in str(e) else 6)
        os._exit(0)
    assert os.waitpid(pid, 0)[1] >> 8 == 5
