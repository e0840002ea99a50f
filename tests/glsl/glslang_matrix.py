#!/usr/bin/env python3
# hush — procedural noise for rendering. MIT License, see LICENSE.
"""Compiles every file `hush glsl-export` writes, in every GLSL dialect it is for.

Usage: glslang_matrix.py --hush PATH/TO/hush --glslang PATH/TO/glslangValidator --dir DIR

DIR is emptied and filled by `hush glsl-export DIR`; then every file in it is compiled with
glslangValidator, found by globbing DIR (a newly exported file is checked without editing this
script):
  - complete shaders (*.comp, *.vert, *.tesc, *.tese, *.geom, *.frag: their own #version line)
    for OpenGL (`-S STAGE`) and for Vulkan (`-V -S STAGE`, SPIR-V; glslang defines VULKAN);
  - function files (*.glsl: no #version line, included in the user's shader) wrapped as a
    fragment shader, `#version V` + the file + an empty main(), for V = 430 core, 450 (Vulkan,
    -V) and 300 es. A file whose header has a line `GLSL versions: ...` is compiled only for the
    versions that line names ("430 core", "Vulkan 450", "300 es").
Any other file in DIR fails the test (a new kind of file needs a rule here). The compiles run in
parallel, one per CPU. Exit 0 when every (file, dialect) compiles; otherwise 1, with one line per
failure naming the file and the dialect and glslang's first errors. Python standard library only.
"""
import argparse
import concurrent.futures
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

STAGES = {".comp": "comp", ".vert": "vert", ".tesc": "tesc", ".tese": "tese",
          ".geom": "geom", ".frag": "frag"}
# Function files: dialect -> (#version line, glslangValidator options).
WRAPPED = {
    "430 core": ("#version 430 core", []),
    "Vulkan 450": ("#version 450", ["-V"]),
    "300 es": ("#version 300 es", []),
}


def stated_versions(text):
    """The dialects a function file names in a `GLSL versions:` header line, else all."""
    for line in text.splitlines()[:60]:
        m = re.search(r"GLSL versions:\s*(.*)", line)
        if m:
            return [d for d in WRAPPED if d in m.group(1)]
    return list(WRAPPED)


def run(glslang, args):
    """(ok, first error lines) of one glslangValidator run."""
    p = subprocess.run([glslang] + args, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       universal_newlines=True)
    errors = [l for l in p.stdout.splitlines() if "ERROR" in l][:3]
    return p.returncode == 0, errors


def jobs_for(path, scratch):
    """(file, dialect, glslangValidator arguments) for every compile of one exported file."""
    name = os.path.basename(path)
    ext = os.path.splitext(name)[1]
    if ext in STAGES:
        stage = STAGES[ext]
        spv = os.path.join(scratch, name + ".spv")
        return [(name, "OpenGL", ["-S", stage, path]),
                (name, "Vulkan", ["-V", "-S", stage, "-o", spv, path])]
    if ext == ".glsl":
        with open(path, encoding="utf-8") as f:
            text = f.read()
        out = []
        for dialect in stated_versions(text):
            version, options = WRAPPED[dialect]
            wrapped = os.path.join(scratch, "%s.%s.frag" % (name, dialect.replace(" ", "_")))
            with open(wrapped, "w", encoding="utf-8") as f:
                f.write(version + "\n" + text + "\nvoid main() {}\n")
            spv = ["-o", wrapped + ".spv"] if "-V" in options else []
            out.append((name, dialect, options + spv + [wrapped]))
        return out
    return [(name, "?", None)]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--hush", required=True, help="the hush program")
    ap.add_argument("--glslang", required=True, help="glslangValidator")
    ap.add_argument("--dir", required=True, help="export directory (emptied first)")
    a = ap.parse_args()
    start = time.time()
    shutil.rmtree(a.dir, ignore_errors=True)
    os.makedirs(a.dir)
    p = subprocess.run([a.hush, "glsl-export", a.dir], stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, universal_newlines=True)
    if p.returncode != 0:
        print("glslang_matrix: `hush glsl-export %s` failed:\n%s" % (a.dir, p.stdout))
        return 1
    files = sorted(os.path.join(a.dir, f) for f in os.listdir(a.dir))
    if not files:
        print("glslang_matrix: `hush glsl-export` wrote no files")
        return 1
    failures = []
    with tempfile.TemporaryDirectory() as scratch:
        jobs = [j for f in files for j in jobs_for(f, scratch)]
        for name, dialect, args in jobs:
            if args is None:
                failures.append("%s: no rule for this kind of file (glslang_matrix.py)" % name)
        jobs = [j for j in jobs if j[2] is not None]
        with concurrent.futures.ThreadPoolExecutor(max_workers=os.cpu_count() or 1) as pool:
            results = pool.map(lambda j: (j, run(a.glslang, j[2])), jobs)
            for (name, dialect, _), (ok, errors) in results:
                if not ok:
                    failures.append("%s [%s]: %s" % (name, dialect, " | ".join(errors)))
    dialects = {}
    for name, dialect, _ in jobs:
        dialects.setdefault(dialect, 0)
        dialects[dialect] += 1
    summary = ", ".join("%s %d" % (d, n) for d, n in sorted(dialects.items()))
    print("glslang_matrix: %d files, %d compiles (%s), %d failed, %.1f s"
          % (len(files), len(jobs), summary, len(failures), time.time() - start))
    for f in failures:
        print("FAILED " + f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
