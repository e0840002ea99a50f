# hush's package stubs: the factories of __init__.py over the module's classes (_hush.pyi,
# generated at build time). tests/test_stubs.py checks these against the package.
from typing import Any, Literal, overload

from ._hush import Anisotropic as Anisotropic
from ._hush import CoherentStream as CoherentStream
from ._hush import Fractal2 as Fractal2
from ._hush import Fractal3 as Fractal3
from ._hush import Gabor2 as Gabor2
from ._hush import Gabor3 as Gabor3
from ._hush import NprGabor as NprGabor
from ._hush import Perlin2 as Perlin2
from ._hush import Perlin3 as Perlin3
from ._hush import Wavelet2 as Wavelet2
from ._hush import Wavelet3 as Wavelet3
from ._hush import glsl_available as glsl_available
from ._hush import glsl_renderer as glsl_renderer
from ._hush import simd_target as simd_target
from ._hush import version as version

__version__: str

@overload
def perlin(dim: Literal[2] = ..., **params: Any) -> Perlin2: ...
@overload
def perlin(dim: Literal[3], **params: Any) -> Perlin3: ...
@overload
def fractal(dim: Literal[2] = ..., **params: Any) -> Fractal2: ...
@overload
def fractal(dim: Literal[3], **params: Any) -> Fractal3: ...
@overload
def wavelet(dim: Literal[2] = ..., **params: Any) -> Wavelet2: ...
@overload
def wavelet(dim: Literal[3], **params: Any) -> Wavelet3: ...
@overload
def gabor(dim: Literal[2] = ..., **params: Any) -> Gabor2: ...
@overload
def gabor(dim: Literal[3], **params: Any) -> Gabor3: ...
def anisotropic(**params: Any) -> Anisotropic: ...
def coherent(**params: Any) -> CoherentStream: ...
def npr_gabor(**params: Any) -> NprGabor: ...
