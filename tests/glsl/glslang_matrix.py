#!/usr/bin/env python3
# hush — procedural noise for rendering. MIT License, see LICENSE.
"""Compiles every file `hush glsl-export` writes, in every GLSL dialect it is for.

Usage: glslang_matrix.py --hush PATH/TO/hush --glslang PATH/TO/glslangValidator
                         --params-layout PATH/TO/glsl_vulkan_params_layout --dir DIR

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
parallel, one per CPU. Each complete shader's Vulkan compile also dumps glslang's reflection (-q),
and the Vulkan params block there (the uniform block at binding 16, hush/glsl/dialect.hpp) must
be the one hush lays out (hush::glsl::vulkan_params_layout_of, printed by --params-layout for
every complete shader): the same members, each with the same offset, GLSL type, array size and
array stride, and the same block size; a shader without one in either is checked to have none in
the other. Exit 0 when every (file, dialect) compiles and every layout agrees; otherwise 1, with
one line per failure naming the file and the dialect and glslang's first errors, or the file and
the member that differ. Python standard library only.
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
# glslang's reflection names types by their GL enum; the GLSL names hush's layout prints.
GL_TYPES = {
    0x1406: "float", 0x1404: "int", 0x1405: "uint", 0x8B56: "bool",
    0x8B50: "vec2", 0x8B51: "vec3", 0x8B52: "vec4", 0x8B53: "ivec2", 0x8B54: "ivec3",
    0x8B55: "ivec4", 0x8DC6: "uvec2", 0x8DC7: "uvec3", 0x8DC8: "uvec4", 0x8B57: "bvec2",
    0x8B58: "bvec3", 0x8B59: "bvec4", 0x8B5A: "mat2", 0x8B5B: "mat3", 0x8B5C: "mat4",
    0x8B65: "mat2x3", 0x8B66: "mat2x4", 0x8B67: "mat3x2", 0x8B68: "mat3x4", 0x8B69: "mat4x2",
    0x8B6A: "mat4x3",
}
PARAMS_BINDING = 16  # hush::glsl::kVulkanParamsBinding
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
    """(ok, first error lines, output) of one glslangValidator run."""
    p = subprocess.run([glslang] + args, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       universal_newlines=True)
    errors = [l for l in p.stdout.splitlines() if "ERROR" in l][:3]
    return p.returncode == 0, errors, p.stdout


def reflection_params(output):
    """(block name, size, {member: (offset, type, array size, stride)}) of the uniform block at
    PARAMS_BINDING in glslang's -q reflection, or None when there is none."""
    section, members, blocks = None, [], []
    for line in output.splitlines():
        if line.endswith("reflection:"):
            section = line
            continue
        m = re.match(r"(\S+): (.*)$", line)
        if not m or section not in ("Uniform reflection:", "Uniform block reflection:"):
            continue
        fields = dict(f.strip().split(" ", 1) for f in m.group(2).split(","))
        (members if section == "Uniform reflection:" else blocks).append((m.group(1), fields))
    for name, f in blocks:
        if int(f["binding"]) == PARAMS_BINDING:
            inside = {n: (int(g["offset"]), GL_TYPES.get(int(g["type"], 16), g["type"]),
                          int(g["size"]), int(g.get("arrayStride", "0")))
                      for n, g in members if g["index"] == f["index"]}
            return name, int(f["size"]), inside
    return None


def compare_params(name, mine, theirs):
    """Failure lines where hush's layout of one file (block, size, members as
    reflection_params gives them) differs from glslang's reflection."""
    if theirs is None and mine[0] == "-" and not mine[2]:
        return []
    out = []
    if theirs is None or mine[:2] != theirs[:2]:
        out.append("%s [params block]: hush lays out %s, %s bytes; glslang reflects %s"
                   % (name, mine[0], mine[1], "none" if theirs is None else
                      "%s, %d bytes" % theirs[:2]))
        if theirs is None:
            return out
    for member in sorted(set(mine[2]) | set(theirs[2])):
        a, b = mine[2].get(member), theirs[2].get(member)
        if a != b:
            out.append("%s [params block] %s: hush (offset, type, count, stride) %s, glslang %s"
                       % (name, member, a, b))
    return out


def hush_params(program, paths):
    """{file name: (block, size, members)} as the --params-layout program prints them, members
    as reflection_params gives them (a non-array is one element with stride 0)."""
    p = subprocess.run([program] + paths, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                       universal_newlines=True)
    if p.returncode != 0:
        raise RuntimeError(p.stderr.strip())
    out = {}
    for line in p.stdout.splitlines():
        words = line.split(" ")
        name = os.path.basename(words[0])
        if words[1] == "block":
            out[name] = (words[2], int(words[3]), {})
        else:
            member, type_, count, offset, stride = words[2], words[3], *map(int, words[4:7])
            out[name][2][member] = (offset, type_, max(count, 1), stride)
    return out


def jobs_for(path, scratch):
    """(file, dialect, glslangValidator arguments) for every compile of one exported file."""
    name = os.path.basename(path)
    ext = os.path.splitext(name)[1]
    if ext in STAGES:
        stage = STAGES[ext]
        spv = os.path.join(scratch, name + ".spv")
        return [(name, "OpenGL", ["-S", stage, path]),
                (name, "Vulkan", ["-V", "-S", stage, "-q", "--reflect-all-block-variables",
                                  "-o", spv, path])]
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
    ap.add_argument("--params-layout", required=True,
                    help="the program printing hush's Vulkan params block layouts")
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
        reflected = {}
        with concurrent.futures.ThreadPoolExecutor(max_workers=os.cpu_count() or 1) as pool:
            results = pool.map(lambda j: (j, run(a.glslang, j[2])), jobs)
            for (name, dialect, args), (ok, errors, output) in results:
                if not ok:
                    failures.append("%s [%s]: %s" % (name, dialect, " | ".join(errors)))
                elif "-q" in args:
                    reflected[name] = reflection_params(output)
    # The params blocks: hush's layout of every complete shader against glslang's reflection.
    complete = [f for f in files if os.path.splitext(f)[1] in STAGES]
    try:
        mine = hush_params(a.params_layout, complete)
    except RuntimeError as e:
        mine = {}
        failures.append("--params-layout failed: %s" % e)
    blocks = 0
    for name in sorted(reflected):
        if name not in mine:
            failures.append("%s [params block]: no layout from --params-layout" % name)
            continue
        blocks += reflected[name] is not None
        failures += compare_params(name, mine[name], reflected[name])
    dialects = {}
    for name, dialect, _ in jobs:
        dialects.setdefault(dialect, 0)
        dialects[dialect] += 1
    summary = ", ".join("%s %d" % (d, n) for d, n in sorted(dialects.items()))
    print("glslang_matrix: %d files, %d compiles (%s), %d params blocks of %d complete shaders "
          "compared with glslang's reflection, %d failed, %.1f s"
          % (len(files), len(jobs), summary, blocks, len(reflected), len(failures),
             time.time() - start))
    for f in failures:
        print("FAILED " + f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
