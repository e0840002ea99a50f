#!/usr/bin/env python3
"""Writes the Python module's docstrings from the C++ contract comments (one source of text).

    python3 tools/python_docstrings.py <hush source dir> <output header>

Reads include/hush/<noise>.hpp and include/hush/exec.hpp and writes a C++ header
(hush_python/docstrings.hpp, included by backends/python/src/bindings.hpp) holding:
  - each noise's contract: the header's opening comment block, after the licence line;
  - each params field: its name, its Python type (from the C++ declaration, enums as their
    enumerators) and its comment: the comment lines right above the field and the comment
    after it on its line (continued on the lines below at the same column);
  - the methods the bindings wrap (e.g. wavelet's bound()): the comment lines above the
    declaration;
  - the bullets of exec.hpp's "Contract of every overload" (points, grids, samples, the
    backends), which the evaluation methods' docstrings quote.
CMake runs it at build time whenever a header changes (backends/python/CMakeLists.txt). A field
or method this script cannot find, or a field type it cannot map to Python, stops the build:
the docstrings never drift from the headers silently. Standard library only.
"""

import pathlib
import re
import sys

# Per noise: the header, the class whose contract and methods are read, the params struct
# (its name and the line opening it: nested `struct params {` after the class, or one at
# namespace scope), the methods whose comments the bindings use, and the C++ field names the
# Python keywords spell differently.
NOISES = {
    "perlin": dict(cls="perlin", struct=r"struct params \{"),
    "fractal": dict(cls="fractal", struct=r"struct params \{", keywords={"norm": "normalization"}),
    "wavelet": dict(cls="wavelet", struct=r"struct params \{", methods=["bound"]),
    "gabor": dict(cls="gabor", struct=r"struct params \{"),
    "anisotropic": dict(cls="anisotropic", struct=r"struct params \{"),
    "coherent": dict(cls="basic_coherent_stream", struct=r"^struct coherent_params \{",
                     struct_before_class=True, methods=["advance", "reset"]),
    "npr_gabor": dict(cls="npr_gabor", struct=r"struct params \{", methods=["render"]),
}

SCALARS = {
    "std::uint32_t": "int",
    "int": "int",
    "double": "float",
    "float": "float",
    "bool": "bool",
    "std::vector<double>": "Sequence[float]",
    "std::vector<vec<double, D>>": "Sequence[Sequence[float]]",
    "std::array<int, std::size_t{D}>": "int | Sequence[int]",
}


def fail(msg):
    sys.exit("python_docstrings.py: " + msg)


def enums(root):
    """enum class name -> its enumerators, over every public header."""
    out = {}
    for path in sorted((root / "include" / "hush").rglob("*.hpp")):
        text = re.sub(r"//[^\n]*", "", path.read_text())
        for m in re.finditer(r"enum class (\w+)\s*(?::\s*\w+\s*)?\{([^}]*)\}", text):
            values = [v.split("=")[0].strip() for v in m.group(2).split(",")]
            out.setdefault(m.group(1), [v for v in values if v])
    return out


def comment_text(line):
    """The text of a `// ...` comment line, without the slashes and one space."""
    body = line.strip()[2:]
    return body[1:] if body.startswith(" ") else body


def opening_comment(lines):
    """The header's opening comment block, without the licence line and the blank after it."""
    block = []
    for line in lines:
        if not line.startswith("//"):
            break
        block.append(comment_text(line))
    if block and "MIT License" in block[0]:
        block = block[1:]
    while block and not block[0].strip():
        block = block[1:]
    return "\n".join(block).rstrip()


def comment_above(lines, index):
    """The comment lines right above lines[index] (template lines skipped), joined."""
    i = index - 1
    while i >= 0 and lines[i].strip().startswith("template"):
        i -= 1
    block = []
    while i >= 0 and lines[i].strip().startswith("//"):
        block.insert(0, comment_text(lines[i]))
        i -= 1
    return "\n".join(block)


FIELD = re.compile(r"^(\s*)(?P<type>[\w:<>, {}]+?)\s+(?P<name>\w+)\s*(?:=[^;]*|\{\})?;"
                   r"(?P<trailing>\s*//.*)?$")


def params_fields(lines, start, enum_values, where):
    """(name, python type, doc) of each field of the struct opened at lines[start]."""
    fields, pending = [], []
    i = start + 1
    while i < len(lines):
        line = lines[i]
        stripped = line.strip()
        if stripped.startswith("};"):
            return fields
        if not stripped:
            pending = []
        elif stripped.startswith("//"):
            pending.append(comment_text(line))
        else:
            m = FIELD.match(line)
            if not m:
                fail(f"{where}: cannot read the params line {i + 1}: {line!r}")
            ctype = " ".join(m.group("type").split())
            if ctype in SCALARS:
                ptype = SCALARS[ctype]
            elif ctype in enum_values:
                ptype = "Literal[" + ", ".join(f"'{v}'" for v in enum_values[ctype]) + "]"
            else:
                fail(f"{where}: no Python type for the C++ type {ctype!r} of "
                     f"{m.group('name')} (add it to SCALARS)")
            doc = list(pending)
            if m.group("trailing"):
                column = line.index("//")
                doc.append(comment_text(line[column:]))
                # Continuation: comment-only lines below, starting at the same column.
                while i + 1 < len(lines) and lines[i + 1].strip().startswith("//") and \
                        lines[i + 1].index("//") == column:
                    i += 1
                    doc.append(comment_text(lines[i]))
            fields.append((m.group("name"), ptype, " ".join(d.strip() for d in doc)))
            pending = []
        i += 1
    fail(f"{where}: the params struct does not end")


def find_line(lines, pattern, start, where):
    rx = re.compile(pattern)
    for i in range(start, len(lines)):
        if rx.search(lines[i]):
            return i
    fail(f"{where}: no line matches {pattern!r}")


def exec_bullets(lines):
    """The bullets of exec.hpp's "Contract of every overload": key (first word) -> text."""
    start = find_line(lines, r"^// Contract of every overload:", 0, "exec.hpp")
    bullets, key = {}, None
    for line in lines[start + 1:]:
        if not line.startswith("//"):
            break
        text = comment_text(line)
        if text.startswith(" - "):
            body = text[3:]
            key = re.match(r"[A-Za-z]+", body).group(0)
            bullets[key] = body
        elif key:
            bullets[key] += " " + text.strip()
    return bullets


def cpp_string(text):
    if ")hushdoc\"" in text:
        fail("a comment holds the raw string's delimiter")
    return 'R"hushdoc(' + text + ')hushdoc"'


def main():
    if len(sys.argv) != 3:
        fail("usage: python_docstrings.py <hush source dir> <output header>")
    root, out_path = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
    enum_values = enums(root)
    out = [
        "// Generated by tools/python_docstrings.py from include/hush/*.hpp: do not edit.",
        "// The Python module's docstrings: the C++ contract comments, one source of text.",
        "#ifndef HUSH_PYTHON_DOCSTRINGS_HPP",
        "#define HUSH_PYTHON_DOCSTRINGS_HPP",
        "",
        "#include <cstddef>",
        "",
        "namespace hush_python {",
        "namespace docs {",
        "",
        "// A params field: its Python keyword, C++ name, Python type and contract comment.",
        "struct field {",
        "  const char* keyword;",
        "  const char* cpp_name;",
        "  const char* type;",
        "  const char* doc;",
        "};",
        "struct noise {",
        "  const char* header;    // include/hush/<noise>.hpp",
        "  const char* contract;  // its opening comment",
        "  const field* fields;",
        "  std::size_t field_count;",
        "};",
        "",
    ]
    for name, cfg in NOISES.items():
        rel = f"include/hush/{name}.hpp"
        lines = (root / rel).read_text().splitlines()
        cls = find_line(lines, rf"^(class|struct) {cfg['cls']}\b", 0, rel)
        struct = find_line(lines, cfg["struct"], 0 if cfg.get("struct_before_class") else cls, rel)
        fields = params_fields(lines, struct, enum_values, rel)
        out.append(f"inline constexpr field {name}_fields[] = {{")
        for fname, ptype, doc in fields:
            keyword = cfg.get("keywords", {}).get(fname, fname)
            out.append(f'    {{"{keyword}", "{fname}", "{ptype}", {cpp_string(doc)}}},')
        out.append("};")
        out.append(f"inline constexpr noise {name} = {{\"{rel}\", "
                   f"{cpp_string(opening_comment(lines))}, {name}_fields, {len(fields)}}};")
        for method in cfg.get("methods", []):
            i = find_line(lines, rf"^\s+[\w:<>,&* ]*\b{method}\(", cls, rel)
            doc = comment_above(lines, i)
            if not doc:
                fail(f"{rel}: {method}() has no comment above it")
            out.append(f"inline constexpr const char* {name}_{method} = {cpp_string(doc)};")
        out.append("")
    for key, text in exec_bullets((root / "include/hush/exec.hpp").read_text().splitlines()).items():
        ident = re.sub(r"\W", "_", key)
        out.append(f"inline constexpr const char* exec_{ident} = {cpp_string(text)};")
    for needed in ("points", "grids", "samples", "scalar", "simd", "glsl", "parallel"):
        if not any(line.startswith(f"inline constexpr const char* exec_{needed} ") for line in out):
            fail(f"include/hush/exec.hpp: the contract has no '{needed}' bullet")
    out += ["", "}  // namespace docs", "}  // namespace hush_python", "",
            "#endif  // HUSH_PYTHON_DOCSTRINGS_HPP", ""]
    text = "\n".join(out)
    out_path.parent.mkdir(parents=True, exist_ok=True)
    if not out_path.exists() or out_path.read_text() != text:
        out_path.write_text(text)


if __name__ == "__main__":
    main()
