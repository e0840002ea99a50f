# hush.dask's stubs; tests/test_stubs.py checks them against dask.py.
from typing import Any, Sequence

from ._hush import Backend

def grid(
    noise: Any,
    shape: Sequence[int],
    origin: float | Sequence[float] = ...,
    step: float | Sequence[float] = ...,
    chunks: Any = ...,
    backend: Backend = ...,
    threads: int = ...,
) -> Any: ...
