#!/usr/bin/env python3
"""Checks that README.md's usage example is examples/basic_usage.cpp verbatim.

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
print("check_readme_example: README.md quotes examples/basic_usage.cpp verbatim")
