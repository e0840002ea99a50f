#!/usr/bin/env python3
"""Checks that README.md's (and docs/*.md's) usage examples are the example programs verbatim.

The block under '## Use' is examples/basic_usage.cpp; any other ```cpp block
right after a line `<!-- example: examples/NAME.cpp -->` is that file.

The README quotes the example; CI builds and runs the example, so keeping the
two identical means the README's code is known to compile and run.
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
# The same rule for the docs pages (docs/*.md quote their compiled examples too).
for page in [root / "README.md"] + sorted((root / "docs").glob("*.md")):
    text = page.read_text(encoding="utf-8")
    where = page.relative_to(root)
    for name, code in re.findall(r"<!-- example: (examples/[\w./-]+) -->\n```cpp\n(.*?)```", text,
                                 re.S):
        path = root / name
        if not path.is_file():
            sys.exit(f"check_readme_example: {where} quotes {name}, which does not exist")
        if code != path.read_text(encoding="utf-8"):
            sys.exit(f"check_readme_example: {where}'s quote of {name} differs from the file; "
                     "make them identical")
        quoted.append(f"{name} ({where})")
print("check_readme_example: quoted verbatim: " + ", ".join(quoted))
