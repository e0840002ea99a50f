#!/usr/bin/env python3
"""The registry test: every registered noise has every layer it ships with, and no
doc, comment or CMake file names a repository file that does not exist.

The registry is HUSH_NOISES in the top-level CMakeLists.txt. What a registered noise
ships with (DESIGN.md "What every noise ships with") is in its own tests folder,
tests/<noise>/ships_with.json (keys below); a noise in the registry without one, or one
for a noise not in the registry, fails too. docs/design.md "Adding a noise" lists the
shared files a new noise touches.

  check_registry.py [--program PATH/TO/hush]

With --program, the program's own answers are checked too (its `sample`/`render`
entries and `glsl-export`'s files); without it, only the sources. Prints one line per
problem and exits 1 when there is any, else prints what it checked and exits 0.
Python standard library only.
"""
import argparse
import json
import re
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent.parent

# What each noise ships with: tests/<noise>/ships_with.json, in the noise's own tests
# folder, a JSON object with these keys (paths relative to the repository root):
#  program:               the `hush` command that runs it (argv after `hush`, without --help)
#  glsl_runner:           its GLSL runner's header in backends/glsl/include/hush/glsl/<noise>/
#                         (program.hpp: a noise_program; renderer.hpp: a scene-driven renderer)
#  glsl_export_prefixes:  name prefixes of the files `hush glsl-export` writes for it
#  bench_text:            a text in its rows file, bench/<noise>_cases.cpp, naming its rows
#  golden_case, hard_case: regular expressions matched against the names of the doctest
#                         cases in tests/ (golden values per seed; NaN/Inf and degenerate inputs)
#  doc:                   its user page
SHIPS_WITH = "tests/{noise}/ships_with.json"
KEYS = ("program", "glsl_runner", "glsl_export_prefixes", "bench_text", "golden_case",
        "hard_case", "doc")
# Optional keys, paths that must exist when given: shader (its kit header for the user's own
# shader) and shader_example (the example that uses it).
OPTIONAL_KEYS = ("shader", "shader_example")


def ships_with(noise):
    """The noise's expectations, or None (after reporting why) when missing or malformed."""
    rel = SHIPS_WITH.format(noise=noise)
    if not (ROOT / rel).is_file():
        problem(f"{noise}: registered in CMakeLists.txt but has no {rel}")
        return None
    try:
        want = json.loads(read(rel))
    except json.JSONDecodeError as e:
        problem(f"{rel}: not JSON: {e}")
        return None
    missing = [k for k in KEYS if k not in want]
    unknown = [k for k in want if k not in KEYS + OPTIONAL_KEYS]
    if missing or unknown:
        problem(f"{rel}: missing keys {missing}, unknown keys {unknown}; see check_registry.py")
        return None
    return want


problems = []


def problem(text):
    problems.append(text)


def read(rel):
    return (ROOT / rel).read_text(encoding="utf-8")


def registry():
    text = read("CMakeLists.txt")
    m = re.search(r"^set\(HUSH_NOISES ([^)]*)\)", text, re.M)
    if not m:
        problem("CMakeLists.txt: no `set(HUSH_NOISES ...)`, the registry of noises")
        return []
    return m.group(1).split()


def test_case_names():
    """Every doctest case name under tests/, adjacent string literals joined."""
    names = []
    for path in sorted((ROOT / "tests").rglob("*.cpp")):
        text = path.read_text(encoding="utf-8")
        for m in re.finditer(r"TEST_CASE(?:_TEMPLATE)?\(\s*((?:\"(?:[^\"\\]|\\.)*\"\s*)+)", text):
            names.append("".join(re.findall(r"\"((?:[^\"\\]|\\.)*)\"", m.group(1))))
    return names


def check_simd(noise):
    """include/hush/<noise>/simd_kernel.hpp's entry list, its unit, and the all-in-one unit."""
    macro = "HUSH_SIMD_ENTRIES_" + noise.upper()
    kernel = f"include/hush/{noise}/simd_kernel.hpp"
    inl = f"hush/{noise}/simd-inl.h"
    if not (ROOT / kernel).is_file():
        problem(f"{noise}: no {kernel} (its SIMD entry list and simd_kernel)")
        return
    text = read(kernel)
    m = re.search(r"#define " + macro + r"\(X\)(.*?)\n\n", text, re.S)
    if not m:
        problem(f"{noise}: {kernel} does not define {macro}(X)")
        return
    if f"HUSH_SIMD_DECLARE({macro})" not in text:
        problem(f"{noise}: {kernel} does not declare its list: HUSH_SIMD_DECLARE({macro})")
    entries = re.findall(r"\bX\(\s*(\w+)", m.group(1))
    if not entries:
        problem(f"{noise}: {macro} lists no entry point")
    if not (ROOT / "include" / inl).is_file():
        problem(f"{noise}: no include/{inl} (its kernels)")
    else:
        # The kernels: simd-inl.h and the parts it includes, include/hush/<noise>/*-inl.h.
        kernels = "".join(p.read_text(encoding="utf-8")
                          for p in sorted((ROOT / "include/hush" / noise).glob("*-inl.h")))
        for e in entries:
            if not re.search(r"\bvoid " + e + r"\(", kernels):
                problem(f"{noise}: entry {e} of {macro} has no kernel in "
                        f"include/hush/{noise}/*-inl.h")
    unit = f"src/simd/{noise}.cpp"
    if not (ROOT / unit).is_file():
        problem(f"{noise}: no {unit} (its dispatch unit)")
    else:
        text = read(unit)
        for want in (f'#include "hush/{noise}.hpp"', f'#define HUSH_SIMD_UNIT_INL "{inl}"',
                     f"#define HUSH_SIMD_UNIT_ENTRIES {macro}",
                     '#include "hush/simd/dispatch_unit.hpp"'):
            if want not in text:
                problem(f"{noise}: {unit} lacks `{want}`")
    every = read("include/hush/simd/all-inl.h")
    if f'#include "{inl}"' not in every:
        problem(f"{noise}: include/hush/simd/all-inl.h does not include {inl}")
    if macro + "(X)" not in every.split("#define HUSH_SIMD_ENTRIES_ALL(X)")[-1]:
        problem(f"{noise}: HUSH_SIMD_ENTRIES_ALL (include/hush/simd/all-inl.h) lacks {macro}")


def check_noise(noise, want, cases, program, exported):
    header = f"include/hush/{noise}.hpp"
    if not (ROOT / header).is_file():
        problem(f"{noise}: no public header {header}")
    if f'#include "hush/{noise}.hpp"' not in read("include/hush/hush.hpp"):
        problem(f"{noise}: include/hush/hush.hpp does not include hush/{noise}.hpp")
    check_simd(noise)
    if not any((ROOT / f"tests/{noise}").glob("*_test.cpp")):
        problem(f"{noise}: no tests/{noise}/*_test.cpp (its suites)")
    # Its part of the params fuzz target, which tests/fuzz/fuzz_params.cpp calls for every noise.
    fuzz = f"tests/{noise}/fuzz_{noise}.cpp"
    if not (ROOT / fuzz).is_file():
        problem(f"{noise}: no {fuzz} (defining hush_fuzz::fuzz_{noise}, tests/fuzz)")
    elif not re.search(r"^void fuzz_" + noise + r"\(", read(fuzz), re.M):
        problem(f"{noise}: {fuzz} does not define fuzz_{noise}")
    for key in OPTIONAL_KEYS:
        if key in want and not (ROOT / want[key]).is_file():
            problem(f"{noise}: {key} {want[key]} does not exist")
    glsl_header, prefixes = want["glsl_runner"], want["glsl_export_prefixes"]
    glsl_dir = f"backends/glsl/include/hush/glsl/{noise}"
    if not (ROOT / glsl_dir / glsl_header).is_file():
        problem(f"{noise}: no GLSL runner {glsl_dir}/{glsl_header}")
    glsl_list = "backends/glsl/include/hush/glsl/noises.hpp"
    if f'#include "hush/glsl/{noise}/' not in read(glsl_list):
        problem(f"{noise}: {glsl_list}, the GLSL layer's list, includes no header of "
                f"hush/glsl/{noise}/")
    if exported is not None:
        for prefix in prefixes:
            if not any(name.startswith(prefix) for name in exported):
                problem(f"{noise}: `hush glsl-export` writes no {prefix}* file")
    # Its program entry and its bench rows, each in one file of its own, defining the function
    # the program's tables and the bench's passes call for every noise of HUSH_NOISE_LIST.
    for rel, function in ((f"examples/hush/noise_{noise}.cpp", f"add_{noise}_entries"),
                          (f"bench/{noise}_cases.cpp", f"add_{noise}_cases"),
                          (f"backends/python/src/noise_{noise}.cpp", f"add_{noise}_python")):
        if not (ROOT / rel).is_file():
            problem(f"{noise}: no {rel} (defining {function})")
        elif not re.search(r"^void " + function + r"\(", read(rel), re.M):
            problem(f"{noise}: {rel} does not define {function}")
    bench = f"bench/{noise}_cases.cpp"
    if (ROOT / bench).is_file() and want["bench_text"] not in read(bench):
        problem(f"{noise}: no bench row: {bench} never names {want['bench_text']}")
    for kind in ("golden_case", "hard_case"):
        if not any(re.search(want[kind], name) for name in cases):
            problem(f"{noise}: no test case in tests/ named like /{want[kind]}/ ({kind})")
    doc = want["doc"]
    if not (ROOT / doc).is_file():
        problem(f"{noise}: no user page {doc}")
    elif f"({doc})" not in read("README.md"):
        problem(f"{noise}: README.md does not link {doc}")
    if program:
        argv = [program] + want["program"] + ["--help"]
        run = subprocess.run(argv, capture_output=True, text=True, timeout=60)
        if run.returncode != 0:
            problem(f"{noise}: `hush {' '.join(want['program'])} --help` exits {run.returncode}: "
                    f"{(run.stderr or run.stdout).strip()[:200]}")


# ---- Names of files that do not exist.
# Paths from the repository root, and include paths as `#include "hush/..."` names them.
REPO_PATH = re.compile(r"(?<![\w./-])((?:include|src|tests|bench|examples|tools|docs|backends|"
                       r"cmake|single_include)/[\w./-]*[\w])")
INCLUDE_PATH = re.compile(r"(?<![\w./-])(hush/[\w./-]+\.(?:hpp|h))\b")
INCLUDE_ROOTS = [ROOT / "include"] + sorted(ROOT.glob("backends/*/include"))
SCANNED_SUFFIXES = {".md", ".hpp", ".h", ".cpp", ".py", ".sh", ".cmake", ".in", ".txt"}
# Not sources: made by builds and programs, or named as examples of output.
SKIPPED = re.compile(r"[*<>{}$]|\.\.\.|/NAME|/NOISE|/DIR|/FILE|/N$")
# Files that name headers they make themselves (test fixtures).
MADE_UP = {"tests/single_header/amalgamate_test.py"}


def tracked_files():
    out = subprocess.run(["git", "ls-files", "--cached", "--others", "--exclude-standard"], cwd=ROOT, capture_output=True, text=True)
    if out.returncode != 0:  # not a checkout: every file below the root
        return [p.relative_to(ROOT).as_posix() for p in ROOT.rglob("*") if p.is_file()]
    return [rel for rel in out.stdout.split() if (ROOT / rel).is_file()]  # deleted ones: no


def check_named_files():
    files = tracked_files()
    existing = set(files)
    dirs = {str(Path(f).parent.as_posix()) for f in files}
    for parent in list(dirs):
        p = Path(parent)
        while p.as_posix() not in (".", ""):
            dirs.add(p.as_posix())
            p = p.parent
    for rel in files:
        path = Path(rel)
        if path.suffix not in SCANNED_SUFFIXES and path.name != "CMakeLists.txt":
            continue
        if rel.startswith("single_include/") or rel in MADE_UP:
            continue  # generated from include/, or fixtures
        text = (ROOT / rel).read_text(encoding="utf-8", errors="replace")
        for number, line in enumerate(text.splitlines(), 1):
            if "://" in line:
                line = re.sub(r"\S+://\S+", "", line)
            for m in REPO_PATH.finditer(line):
                name = m.group(1).rstrip(".")
                if SKIPPED.search(name) or name in existing or name in dirs:
                    continue
                if line[m.end():m.end() + 1] in ("<", "{", "*"):
                    continue  # a pattern's fixed part: examples/hush/noise_<noise>.cpp
                problem(f"{rel}:{number}: names {name}, which does not exist")
            for m in INCLUDE_PATH.finditer(line):
                name = m.group(1)
                if SKIPPED.search(name) or any((r / name).is_file() for r in INCLUDE_ROOTS):
                    continue
                problem(f"{rel}:{number}: names {name}, which no include directory holds")


# No hand-written header over MAX_HEADER_LINES lines: one that grows past it holds two
# concepts. Generated files (single_include/) are exempt.
MAX_HEADER_LINES = 1200


def check_header_sizes():
    for rel in tracked_files():
        if not rel.endswith((".hpp", ".h")) or rel.startswith("single_include/"):
            continue
        lines = (ROOT / rel).read_text(encoding="utf-8", errors="replace").count("\n")
        if lines > MAX_HEADER_LINES:
            problem(f"{rel}: {lines} lines, over {MAX_HEADER_LINES}: split it by concept")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--program", help="the hush program, to check its entries and export")
    args = parser.parse_args()
    noises = registry()
    for path in sorted(ROOT.glob(SHIPS_WITH.format(noise="*"))):
        if path.parent.name not in noises:
            problem(f"{path.relative_to(ROOT)}: {path.parent.name} is not in HUSH_NOISES")
    exported = None
    if args.program:
        with tempfile.TemporaryDirectory() as tmp:
            run = subprocess.run([args.program, "glsl-export", tmp], capture_output=True,
                                 text=True, timeout=120)
            if run.returncode != 0:
                problem(f"`hush glsl-export` exits {run.returncode}: {run.stderr.strip()[:200]}")
            exported = [p.name for p in Path(tmp).iterdir()]
    cases = test_case_names()
    for noise in noises:
        want = ships_with(noise)
        if want is not None:
            check_noise(noise, want, cases, args.program, exported)
    check_named_files()
    check_header_sizes()
    for p in problems:
        print(p)
    if problems:
        print(f"registry: {len(problems)} problem(s)")
        return 1
    print(f"registry: {len(noises)} noises, every layer present"
          f"{' (with the program)' if args.program else ''}; every named file exists; "
          f"no header over {MAX_HEADER_LINES} lines")
    return 0


if __name__ == "__main__":
    sys.exit(main())
