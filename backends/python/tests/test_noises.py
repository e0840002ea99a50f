"""hush's Python module: the same values as the C++ library, numpy in and out, clear errors."""
import threading

import numpy as np
import pytest

import hush


# ---- Bit for bit the C++ API: the program's .npy output of the same grid.
@pytest.mark.parametrize("backend", ["scalar", "simd"])
def test_perlin_grid_equals_the_program(hush_program, backend):
    want = hush_program("sample", "perlin", "--dim", "2", "--size", "48x32", "--origin", "3.25,-7.5",
                        "--step", "0.0625", "--seed", "11", "--backend", backend)
    got = hush.perlin(dim=2, seed=11).grid((32, 48), origin=(3.25, -7.5), step=0.0625, backend=backend)
    assert got.dtype == np.float32 and got.shape == want.shape
    assert np.array_equal(got, want)


def test_fractal_3d_grid_equals_the_program(hush_program):
    want = hush_program("sample", "perlin", "--dim", "3", "--size", "16x12x8", "--step", "0.1",
                        "--seed", "5", "--octaves", "6", "--fractal", "turbulence", "--backend", "simd")
    got = hush.fractal(dim=3, seed=5, octaves=6, kind="turbulence",
                       normalization="unit_range").grid((8, 12, 16), step=0.1)
    assert np.array_equal(got, want)


def test_wavelet_grid_equals_the_program(hush_program):
    want = hush_program("sample", "wavelet", "--dim", "2", "--size", "40x24", "--step", "0.3",
                        "--seed", "9", "--tile-size", "32", "--backend", "simd")
    got = hush.wavelet(dim=2, seed=9, tile_size=32).grid((24, 40), step=0.3)
    assert np.array_equal(got, want)


# ---- Backends and threads: one field whatever the call.
@pytest.mark.parametrize("make", [lambda: hush.perlin(dim=3, seed=2),
                                  lambda: hush.wavelet(dim=3, seed=2, tile_size=32),
                                  lambda: hush.gabor(dim=2, seed=2),
                                  lambda: hush.anisotropic(seed=2, tile_size=64)])
def test_threads_give_the_values_of_one_thread(make):
    n = make()
    rng = np.random.default_rng(1)
    pts = (rng.random((20000, n.dimension), dtype=np.float32) - 0.5) * 200
    one = n(pts)
    assert np.array_equal(n(pts, threads=0), one)
    assert np.array_equal(n(pts, threads=3), one)
    # The scalar backend agrees within float rounding (bit for bit only under HUSH_STRICT_FP).
    assert np.max(np.abs(n(pts, backend="scalar") - one)) < 1e-4


def test_points_equal_the_grid_at_the_same_float_positions():
    n = hush.perlin(dim=2, seed=4)
    g = n.grid((3, 5), origin=(0.5, 0.25), step=0.5)
    ys, xs = np.mgrid[0:3, 0:5]
    pts = np.stack([0.5 + 0.5 * xs, 0.25 + 0.5 * ys], axis=-1).reshape(-1, 2).astype(np.float32)
    assert np.array_equal(n(pts, backend="scalar"), n.grid((3, 5), origin=(0.5, 0.25), step=0.5,
                                                             backend="scalar").ravel())
    assert g.shape == (3, 5)


def test_float64_points_are_rounded_to_float32():
    n = hush.gabor(dim=3, seed=3)
    pts = np.random.default_rng(0).random((100, 3)) * 10
    assert np.array_equal(n(pts), n(pts.astype(np.float32)))


def test_gradients_match_finite_differences():
    n = hush.perlin(dim=2, seed=8)
    pts = np.random.default_rng(3).random((50, 2)).astype(np.float32) * 20
    values, grads = n.gradient(pts)
    assert grads.shape == (50, 2) and np.array_equal(values, n(pts))
    h = 1e-3
    for a in range(2):
        d = np.zeros(2, np.float64)
        d[a] = h
        fd = (n(pts.astype(np.float64) + d) - n(pts.astype(np.float64) - d)) / (2 * h)
        assert np.max(np.abs(fd - grads[:, a])) < 0.05


def test_footprints_filter_wavelet_noise_towards_zero():
    n = hush.wavelet(dim=2, seed=1, tile_size=64)
    pts = np.random.default_rng(2).random((4000, 2)).astype(np.float32) * 50
    sharp = n.sample(pts, footprints=np.full(4000, 0.01))
    blurred = n.sample(pts, footprints=np.full(4000, 64.0))
    assert np.std(blurred) < 0.1 * np.std(sharp)
    derivs = np.zeros((4000, 2, 2))
    derivs[:, 0, 0] = derivs[:, 1, 1] = 0.01
    assert np.max(np.abs(n.sample(pts, footprints=derivs) - sharp)) < 0.05


# ---- Errors name the parameter.
def test_bad_parameter_values_raise_value_error_naming_them():
    with pytest.raises(ValueError, match="tile_size"):
        hush.wavelet(tile_size=10)
    with pytest.raises(ValueError, match="octaves"):
        hush.fractal(octaves=0)
    with pytest.raises(ValueError, match="kind"):
        hush.fractal(kind="pink")
    with pytest.raises(ValueError, match="dim"):
        hush.perlin(dim=4)
    with pytest.raises(TypeError, match="octave"):
        hush.fractal(octave=3)


def test_bad_arrays_raise_value_error_naming_them():
    n = hush.perlin(dim=3)
    with pytest.raises(ValueError, match="points.*\\(N, 3\\)"):
        n(np.zeros((4, 2), np.float32))
    with pytest.raises(ValueError, match="points.*dtype"):
        n(np.zeros((4, 3), np.complex64))
    with pytest.raises(ValueError, match="backend"):
        n(np.zeros((4, 3), np.float32), backend="cuda")
    with pytest.raises(ValueError, match="threads"):
        n(np.zeros((4, 3), np.float32), threads=-1)
    with pytest.raises(ValueError, match="shape"):
        n.grid((4, 4))
    w = hush.wavelet(dim=2)
    with pytest.raises(ValueError, match="footprints"):
        w.sample(np.zeros((4, 2), np.float32), footprints=np.ones(3))
    with pytest.raises(ValueError, match="normal"):
        w.sample(np.zeros((4, 2), np.float32), normals=np.ones((4, 3), np.float32))


# ---- The GIL is released while hush computes: another Python thread runs meanwhile.
def test_evaluation_releases_the_gil():
    n = hush.fractal(dim=2, octaves=8)
    done = threading.Event()
    started = threading.Event()

    def work():
        started.set()
        n.grid((1024, 1024), step=0.01, backend="scalar")
        done.set()

    t = threading.Thread(target=work)
    t.start()
    started.wait()
    ticks = 0
    while not done.is_set():
        ticks += 1
    t.join()
    # Holding the GIL, the worker would have let this loop run only between its calls.
    assert ticks > 1000


# ---- Scene-driven noises over G-buffer arrays.
def test_coherent_stream_is_unit_variance_and_coherent_for_a_still_frame():
    s = hush.coherent(seed=3, alpha=0.9)
    depth = np.ones((64, 64), np.float32)
    velocity = np.zeros((64, 64, 3), np.float32)
    first = s.advance(depth, velocity)[0]
    second = s.advance(depth, velocity)[0]
    assert first.shape == (64, 64)
    assert 0.7 < np.std(second) < 1.3  # 4096 samples of unit variance
    assert np.corrcoef(first.ravel(), second.ravel())[0, 1] > 0.8  # alpha = 0.9
    with pytest.raises(ValueError, match="velocity"):
        s.advance(depth, np.zeros((64, 64), np.float32))


def test_npr_gabor_renders_a_visible_triangle():
    n = hush.npr_gabor(seed=1)
    h, w = 64, 64
    depth = np.full((h, w), 5.0, np.float32)
    ids = np.zeros((h, w), np.uint32)
    screen = np.array([[4, 4], [60, 4], [4, 60]], np.float32)  # clockwise on the y-down screen
    out = n.render(depth, np.array([[0, 1, 2]]), screen, np.full(3, 5.0, np.float32),
                   np.array([0], np.uint32), frame_object_id=ids, frame_triangle_id=ids)
    flipped = n.render(depth, np.array([[0, 2, 1]]), screen, np.full(3, 5.0, np.float32),
                       np.array([0], np.uint32), frame_object_id=ids, frame_triangle_id=ids)
    assert out.shape == (h, w)
    # One winding is culled as a back face, the other draws.
    assert (np.count_nonzero(out) > 100) != (np.count_nonzero(flipped) > 100)
    with pytest.raises(ValueError, match="indices"):
        n.render(depth, np.array([0, 1, 2]), screen, np.full(3, 5.0, np.float32),
                 np.array([0], np.uint32), frame_object_id=ids, frame_triangle_id=ids)


# ---- out=: the result written into the caller's array, the values of a new one.
def test_out_is_written_and_returned():
    n = hush.wavelet(dim=2, seed=6, tile_size=32)
    pts = np.random.default_rng(4).random((300, 2)).astype(np.float32) * 9
    out = np.empty(300, np.float32)
    assert n(pts, out=out) is out and np.array_equal(out, n(pts))
    grid = np.empty((12, 20), np.float32)
    assert n.grid((12, 20), step=0.3, out=grid) is grid
    assert np.array_equal(grid, n.grid((12, 20), step=0.3))
    assert np.array_equal(n.sample(pts, footprints=np.full(300, 0.5), out=out),
                          n.sample(pts, footprints=np.full(300, 0.5)))
    block = np.empty((5, 7), np.float32)
    n.grid((12, 20), step=0.3, block=((2, 3), (5, 7)), out=block)
    assert np.array_equal(block, grid[2:7, 3:10])
    for bad in (np.empty(299, np.float32), np.empty(300, np.float64),
                np.empty((300, 2), np.float32)[:, 0], [0.0] * 300):
        with pytest.raises(ValueError, match="out"):
            n(pts, out=bad)


@pytest.mark.skipif(hush.glsl_available(), reason="the module has the GL backend (test_glsl.py)")
def test_glsl_without_the_gl_backend_says_so():
    with pytest.raises(ValueError, match="built without the GL backend"):
        hush.perlin(dim=2)(np.zeros((4, 2), np.float32), backend="glsl")
