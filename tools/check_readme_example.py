#!/usr/bin/env python3
"""Checks that README.md's (and docs/*.md's) usage examples are the example programs verbatim.

The block under '## Use' is examples/basic_usage.cpp; any other ```cpp block
right after a line `<!-- example: examples/NAME.cpp -->` (or tests/docs/NAME.cpp,
the page examples built by tests/docs/CMakeLists.txt) is that file.

The pages quote the examples; CI builds and runs the examples, so keeping the
two identical means the pages' code is known to compile and run. Every noise
page (NOISE_PAGES below) must quote at least one such example: its main one.
Exits 1 with a message when they differ. Standard library only.
"""
import pathlib
import re
import sys

root = pathlib.Path(__file__).resolve().parent.parent
readme = (root / "README.md").read_text(encoding="utf-8")
example = (root / "examples" / "basic_usage.cpp").read_text(encoding="utf-8")
match = re.search(r"## Use\n\n```cpp\n(.*?)```", readme, re.S)
if not match:
    sys.exit("check_readme_example: README.md has no ```cpp block under '## Use'")
if match.group(1) != example:
    sys.exit("check_readme_example: README.md's usage example differs from "
             "examples/basic_usage.cpp; make them identical")
quoted = ["examples/basic_usage.cpp"]
quoting = set()
NOISE_PAGES = ["perlin.md", "fractal.md", "wavelet.md", "gabor.md", "anisotropic.md",
               "coherent.md", "npr-gabor.md"]
# The same rule for the docs pages (docs/*.md quote their compiled examples too).
for page in [root / "README.md"] + sorted((root / "docs").glob("*.md")):
    text = page.read_text(encoding="utf-8")
    where = page.relative_to(root)
    for name, code in re.findall(r"<!-- example: ((?:examples|tests/docs)/[\w./-]+) -->\n```cpp\n(.*?)```", text,
                                 re.S):
        path = root / name
        if not path.is_file():
            sys.exit(f"check_readme_example: {where} quotes {name}, which does not exist")
        if code != path.read_text(encoding="utf-8"):
            sys.exit(f"check_readme_example: {where}'s quote of {name} differs from the file; "
                     "make them identical")
        quoted.append(f"{name} ({where})")
        quoting.add(page.name)
missing = [p for p in NOISE_PAGES if p not in quoting]
if missing:
    sys.exit("check_readme_example: these noise pages quote no compiled example "
             "(<!-- example: examples/NAME.cpp --> before a ```cpp block): " + ", ".join(missing))
print("check_readme_example: quoted verbatim: " + ", ".join(quoted))
