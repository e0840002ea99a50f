#!/usr/bin/env python3
"""tools/amalgamate.py's refusals, on headers made here: a hush header first included
inside a conditional (it would vanish where the conditional is false, while later
includes of it are dropped) and an include cycle are errors; a header first included
unconditionally, later again inside a conditional, and an -inl.h kernel first included
inside one are not. Exits 1 naming the first expectation that fails."""
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tools"))
import amalgamate  # noqa: E402

GUARDED = "#ifndef {g}\n#define {g}\n{body}#endif\n"


def run(headers):
    """amalgamate.inline over hush/top.hpp in a tree of `headers`: None or the error text."""
    with tempfile.TemporaryDirectory() as tmp:
        for name, text in headers.items():
            path = Path(tmp) / name
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_text(text)
        amalgamate.INCLUDE_DIR = Path(tmp)
        try:
            amalgamate.inline("hush/top.hpp", [], set(), [])
        except amalgamate.AmalgamationError as e:
            return str(e)
    return None


LEAF = GUARDED.format(g="LEAF", body="int leaf;\n")
cases = [
    ("first include inside #if is refused",
     {"hush/top.hpp": GUARDED.format(g="TOP", body='#if X\n#include "hush/leaf.hpp"\n#endif\n'),
      "hush/leaf.hpp": LEAF}, "first included inside a conditional"),
    ("first include inside #if of a nested header is refused",
     {"hush/top.hpp": GUARDED.format(g="TOP", body='#include "hush/mid.hpp"\n'),
      "hush/mid.hpp": GUARDED.format(g="MID", body='#ifdef Y\n#include "hush/leaf.hpp"\n#endif\n'),
      "hush/leaf.hpp": LEAF}, "first included inside a conditional"),
    ("unconditional first, conditional later is accepted",
     {"hush/top.hpp": GUARDED.format(
         g="TOP", body='#include "hush/leaf.hpp"\n#if X\n#include "hush/leaf.hpp"\n#endif\n'),
      "hush/leaf.hpp": LEAF}, None),
    ("an -inl.h kernel inside #if is accepted",
     {"hush/top.hpp": GUARDED.format(g="TOP", body='#if X\n#include "hush/k-inl.h"\n#endif\n'),
      "hush/k-inl.h": "#if defined(K_) == defined(HWY_TARGET_TOGGLE)\nint k;\n#endif\n"}, None),
    ("a cycle is refused",
     {"hush/top.hpp": GUARDED.format(g="TOP", body='#include "hush/leaf.hpp"\n'),
      "hush/leaf.hpp": GUARDED.format(g="LEAF", body='#include "hush/top.hpp"\n')},
     "include cycle"),
]
failed = 0
for what, headers, want in cases:
    got = run(headers)
    ok = (got is None) if want is None else (got is not None and want in got)
    if not ok:
        failed += 1
        print(f"FAILED: {what}: got {got!r}")
print(f"{len(cases) - failed} passed, {failed} failed")
sys.exit(1 if failed else 0)
