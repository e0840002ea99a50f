"""hush: procedural noise for rendering, from Python.

Every noise of the C++ library, evaluated by the same code (results equal the C++ API bit for
bit), on the backend named per call: ``backend="simd"`` (default), ``"scalar"`` or ``"glsl"``
(GLSL compute shaders on one headless GL device per process, where the module was built with
OSMesa or EGL: ``hush.glsl_available()``), and, on the CPU, ``threads=1`` (default), ``0``
(one per hardware thread) or ``n``. The GIL is released while hush computes::

    import numpy as np, hush
    n = hush.wavelet(dim=3, seed=7, tile_size=64)
    values = n(np.random.rand(1000, 3).astype(np.float32))   # (1000,) float32
    volume = n.grid((64, 128, 128), step=0.05)                # (nz, ny, nx) float32
    terrain = hush.fractal(dim=2, octaves=8).grid((1024, 1024), step=1 / 256, threads=0)

Parameters are the C++ params structs' fields as keywords (each class's docstring quotes their
C++ contract comments, and ``Class.keywords`` maps each name to its type and comment); a
value outside its domain raises ValueError naming it, an unknown keyword TypeError. Positions
are float32 (N, D) arrays, used without a copy (other real dtypes are converted); grids take
their origin and step in double. ``hush.dask`` builds dask arrays of any size in chunks.
"""

from ._hush import (  # noqa: F401
    Anisotropic,
    CoherentStream,
    Fractal2,
    Fractal3,
    Gabor2,
    Gabor3,
    NprGabor,
    Perlin2,
    Perlin3,
    Wavelet2,
    Wavelet3,
    glsl_available,
    glsl_renderer,
    simd_target,
    version,
)

__version__ = version

_BY_DIM = {
    "perlin": {2: Perlin2, 3: Perlin3},
    "fractal": {2: Fractal2, 3: Fractal3},
    "wavelet": {2: Wavelet2, 3: Wavelet3},
    "gabor": {2: Gabor2, 3: Gabor3},
}


def _make(name, dim, params):
    classes = _BY_DIM[name]
    if dim not in classes:
        raise ValueError(f"hush.{name}: dim={dim!r} is invalid; valid: 2, 3")
    return classes[dim](**params)


def perlin(dim=2, **params):
    """Perlin noise, values in [-1, 1]: hush.Perlin2 or hush.Perlin3 (seed, period)."""
    return _make("perlin", dim, params)


def fractal(dim=2, **params):
    """fBm or turbulence over Perlin noise: hush.Fractal2 or hush.Fractal3."""
    return _make("fractal", dim, params)


def wavelet(dim=2, **params):
    """Wavelet noise (Cook & DeRose), band-limited: hush.Wavelet2 or hush.Wavelet3."""
    return _make("wavelet", dim, params)


def gabor(dim=2, **params):
    """Gabor noise (Lagae et al.), spectral control: hush.Gabor2 or hush.Gabor3."""
    return _make("gabor", dim, params)


def anisotropic(**params):
    """Anisotropic noise (Goldberg et al.), 2D texture space: hush.Anisotropic."""
    return Anisotropic(**params)


def coherent(**params):
    """Coherent noise for animation (Kass & Pesare): a hush.CoherentStream."""
    return CoherentStream(**params)


def npr_gabor(**params):
    """NPR Gabor noise (Benard et al.): hush.NprGabor, rendered per frame."""
    return NprGabor(**params)
