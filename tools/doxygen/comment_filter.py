#!/usr/bin/env python3
"""Doxygen INPUT_FILTER: hush's contract comments are plain `//` blocks; this hands them to
Doxygen as `///` documentation.

A block of `//` lines directly above a declaration at namespace or class scope (not inside a
function body) becomes that declaration's documentation; a block followed by a blank line, a
preprocessor line or a closing brace stays a plain comment, as do comments inside bodies and at
the ends of lines. Characters Doxygen would read as commands or HTML (\\ @ < > & #) are
escaped, and `::` too (Doxygen would try to link
qualified names of private members), so the text shows as written. Standard library only; prints the filtered file.
"""
import re
import sys

SCOPE = re.compile(r"^\s*(?:template\s*<.*>\s*)?(?:inline\s+)?(?:namespace|struct|class|union|"
                   r"enum|extern\s+\"C\")\b")


def code_part(line):
    """The line without strings, character literals and comments (for brace counting)."""
    line = re.sub(r'"(?:\\.|[^"\\])*"', '""', line)
    line = re.sub(r"'(?:\\.|[^'\\])*'", "''", line)
    return line.split("//", 1)[0]


def escape(text):
    text = re.sub(r"([\\@<>&#$%])", r"\\\1", text)
    return text.replace("::", "\\::")  # no links guessed from qualified names


def main(path):
    lines = open(path, encoding="utf-8").read().split("\n")
    stack = []             # True for a scope brace (namespace, class), False for a body brace
    pending_scope = False  # a scope keyword seen, its brace not yet
    block = []             # indices of the current run of whole-line // comments
    out = list(lines)
    in_block_comment = False

    def flush(next_line):
        stripped = next_line.strip()
        documentable = (all(stack) and stripped and not stripped.startswith(("#", "}", "//"))
                        and not stripped.startswith(("public:", "private:", "protected:")))
        if documentable and block:
            for i in block:
                m = re.match(r"^(\s*)//(?![/!])(.*)$", lines[i])
                if m:  # lines already written for Doxygen (/// or //!) pass unchanged
                    out[i] = m.group(1) + "///" + escape(m.group(2))
        block.clear()

    for i, line in enumerate(lines):
        if in_block_comment:
            if "*/" in line:
                in_block_comment = False
            continue
        if re.match(r"^\s*//", line):
            block.append(i)
            continue
        flush(line)
        code = code_part(line)
        if "/*" in code and "*/" not in code:
            in_block_comment = True
        if code.lstrip().startswith("#"):
            continue
        if SCOPE.match(code) and ";" not in code.split("{")[0]:
            pending_scope = True
        for ch in code:
            if ch == "{":
                stack.append(pending_scope)
                pending_scope = False
            elif ch == "}" and stack:
                stack.pop()
        if ";" in code and "{" not in code:
            pending_scope = False
    sys.stdout.write("\n".join(out))


if __name__ == "__main__":
    main(sys.argv[1])
