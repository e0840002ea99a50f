#!/usr/bin/env python3
"""Checks that what README.md and docs/*.md point to exists.

- Every relative link and image (Markdown `[text](target)`, `![alt](target)`, HTML `src=`/`href=`)
  names a file or folder of the repository, and a `#anchor` names a heading (GitHub's slugs) or an
  explicit `id`/`name` of the target page.
- Every `hush ...` command line in a shell code block, and every inline code span that starts
  with `hush ` (or a path to the program), names a subcommand of the program, a noise that
  subcommand takes, and only options the program's usage text (`hush --help`) lists for that
  subcommand and noise. Scripts a command runs (`bash tools/NAME.sh`, `python3 tools/NAME.py`) exist.

usage: check_docs.py [--root DIR] [--hush PROGRAM]   check the docs (exit 1 on any problem)
       check_docs.py --self-test [--hush PROGRAM]    show that broken docs are caught
Without --hush (a build without the program) the commands are not checked. Standard library only.
"""
import argparse
import pathlib
import re
import shlex
import subprocess
import sys
import tempfile
import unicodedata

# ---- Anchors ----------------------------------------------------------------------------------


def slug(heading):
    """GitHub's anchor for a heading: lower case, punctuation dropped, spaces to hyphens."""
    text = re.sub(r"<[^>]+>", "", heading)          # inline HTML
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", text)  # links keep their text
    text = text.replace("`", "").strip().lower()
    kept = []
    for ch in text:
        cat = unicodedata.category(ch)
        if ch in " -_" or cat[0] in "LN" or cat == "Mn":
            kept.append(ch)
    return "".join(kept).replace(" ", "-")


def strip_code(text):
    """The page without its fenced code blocks (their lines become empty)."""
    out, fence = [], None
    for line in text.split("\n"):
        m = re.match(r"^\s*(```+|~~~+)", line)
        if m:
            if fence is None:
                fence = m.group(1)
            elif line.strip().startswith(fence):
                fence = None
            out.append("")
            continue
        out.append("" if fence else line)
    return "\n".join(out)


def anchors(text):
    """Every anchor a page defines: heading slugs (with GitHub's -1, -2 for repeats) and ids."""
    found, seen = set(), {}
    for line in strip_code(text).split("\n"):
        m = re.match(r"^#{1,6}\s+(.*?)\s*#*\s*$", line)
        if m:
            base = slug(m.group(1))
            n = seen.get(base, 0)
            seen[base] = n + 1
            found.add(base if n == 0 else f"{base}-{n}")
    found.update(re.findall(r"""(?:id|name)\s*=\s*["']([^"']+)["']""", text))
    return found


# ---- Links ------------------------------------------------------------------------------------

LINK = re.compile(r"!?\[(?:[^\[\]]|\[[^\]]*\])*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
HTML_LINK = re.compile(r"""(?:src|href)\s*=\s*["']([^"']+)["']""")


def check_links(page, root):
    """Problems with the relative links and images of one page."""
    text = page.read_text(encoding="utf-8")
    prose = re.sub(r"`[^`\n]*`", "", strip_code(text))  # inline code is not a link
    problems = []
    for target in LINK.findall(prose) + HTML_LINK.findall(prose):
        if re.match(r"^[a-z][a-z0-9+.-]*:", target):  # http:, https:, mailto:
            continue
        path_part, _, anchor = target.partition("#")
        dest = page if not path_part else (page.parent / path_part).resolve()
        where = f"{page.relative_to(root)}: link '{target}'"
        try:
            dest.relative_to(root.resolve())
        except ValueError:
            problems.append(f"{where} points outside the repository")
            continue
        if not dest.exists():
            problems.append(f"{where}: {path_part} does not exist")
            continue
        if anchor:
            if dest.suffix != ".md" or dest.is_dir():
                problems.append(f"{where}: an anchor into a file that is not Markdown")
            elif anchor not in anchors(dest.read_text(encoding="utf-8")):
                problems.append(f"{where}: {dest.name} has no heading or id '{anchor}'")
    return problems


# ---- The program's usage text -----------------------------------------------------------------


class Usage:
    """What `hush --help` says: subcommands, their options, and per noise its options."""

    def __init__(self, text):
        self.commands = {}  # tuple of words -> {"options": set, "noises": {name: set}}
        self.top = set()    # the command list's names
        current, noise = None, None
        in_list = False
        for line in text.split("\n"):
            if line.startswith("commands:"):
                in_list = True
                continue
            if in_list:
                m = re.match(r"^  ([a-z][a-z0-9-]*)\s", line)
                if m:
                    self.top.add(m.group(1))
                    continue
                if line.strip():
                    in_list = False
            m = re.match(r"^hush (.*)$", line)
            if m and not line.startswith("hush --help"):
                words = m.group(1).split()
                key = []
                for w in words:
                    if re.fullmatch(r"[a-z][a-z0-9-]*", w):
                        key.append(w)
                    else:
                        break
                if not key:
                    continue
                current = self.commands.setdefault(tuple(key), {"options": set(), "noises": {},
                                                                "takes_noise": False})
                current["takes_noise"] |= "NOISE" in words[len(key):len(key) + 1]
                current["options"].update(re.findall(r"(--[a-z][a-z0-9-]*)", m.group(1)))
                noise = None
                continue
            if current is None:
                continue
            m = re.match(r"^\s+NOISE ([a-z][a-z0-9-]*):", line)
            if m:
                noise = current["noises"].setdefault(m.group(1), set())
                continue
            m = re.match(r"^\s+(--[a-z][a-z0-9-]*)", line)
            if m:
                (noise if noise is not None else current["options"]).add(m.group(1))
            elif not line.startswith(" ") and line.strip():
                current, noise = None, None  # a closing paragraph: no longer a command's

    def check(self, words):
        """Problems with one command line's words after `hush`."""
        if not words or words[0] in ("--help", "-h", "help"):
            return []
        if words[0] not in self.top and (words[0],) not in self.commands:
            return [f"'hush {words[0]}': no such subcommand"]
        key = (words[0],)
        rest = words[1:]
        if rest and (words[0], rest[0]) in self.commands:
            key, rest = (words[0], rest[0]), rest[1:]
        spec = self.commands.get(key)
        if spec is None:
            return []  # listed but without a usage section: nothing more to check
        allowed = set(spec["options"]) | {"--help"}
        problems = []
        name = " ".join(key)
        if spec["takes_noise"]:
            positional = [w for w in rest if not w.startswith("-")]
            noise = positional[0] if positional else None
            if noise is None or noise.isupper() or noise in ("...", "NAME"):
                for opts in spec["noises"].values():  # a placeholder: any noise's options
                    allowed |= opts
            elif noise not in spec["noises"]:
                problems.append(f"'hush {name} {noise}': no such noise for {name} "
                                f"(known: {', '.join(sorted(spec['noises']))})")
            else:
                allowed |= spec["noises"][noise]
        for w in rest:
            if w.startswith("--"):
                opt = w.split("=", 1)[0]
                if opt not in allowed:
                    problems.append(f"'hush {name}': option {opt} is not in its usage")
        return problems


# ---- Commands in code blocks ------------------------------------------------------------------

SHELL_LANGS = {"", "sh", "bash", "shell", "console", "text"}


def code_lines(text):
    """(line number, command line) of the shell code blocks, continuations joined."""
    fence, lang, pending, start = None, "", "", 0
    for number, line in enumerate(text.split("\n"), 1):
        m = re.match(r"^\s*(```+|~~~+)\s*([\w+-]*)", line)
        if m and (fence is None or line.strip().startswith(fence)):
            if fence is None:
                fence, lang = m.group(1), m.group(2).lower()
            else:
                fence = None
            continue
        if fence is None or lang not in SHELL_LANGS:
            continue
        if not pending:
            start = number
        body = re.sub(r"^\s*[$>]\s+", "", line)
        if body.rstrip().endswith("\\"):
            pending += body.rstrip()[:-1] + " "
            continue
        yield start, pending + body
        pending = ""


def split_commands(line):
    """The simple commands of a shell line, as lists of words (comments dropped)."""
    lexer = shlex.shlex(line, posix=True, punctuation_chars=True)
    lexer.whitespace_split = True
    lexer.commenters = "#"
    try:
        tokens = list(lexer)
    except ValueError:
        return []
    commands, current = [], []
    for t in tokens:
        if t and all(c in "|&;()<>" for c in t):
            if current:
                commands.append(current)
            current = []
        else:
            current.append(t)
    if current:
        commands.append(current)
    return commands


def inline_commands(text):
    """(line number, command) of the inline code spans outside code blocks that run the program."""
    for number, line in enumerate(strip_code(text).split("\n"), 1):
        for m in re.finditer(r"`((?:[\w.-]*/)*hush [^`]+)`", line):
            yield number, m.group(1)


def check_commands(page, root, usage):
    problems = []
    text = page.read_text(encoding="utf-8")
    for number, line in list(code_lines(text)) + list(inline_commands(text)):
        for words in split_commands(line):
            while words and re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*=\S*", words[0]):
                words = words[1:]  # VAR=value prefixes
            if not words:
                continue
            where = f"{page.relative_to(root)}:{number}"
            prog = words[0]
            if prog in ("bash", "sh", "python3", "python") and len(words) > 1:
                script = words[1]
                if re.match(r"^(tools|tests|\.ci|examples|bench)/", script) and \
                        not (root / script).exists():
                    problems.append(f"{where}: '{prog} {script}': {script} does not exist")
                continue
            if usage is None or pathlib.PurePosixPath(prog).name != "hush":
                continue
            words = [w.strip("[]") for w in words[1:]]
            words = [w for w in words if w]
            problems += [f"{where}: {p}" for p in usage.check(words)]
    return problems


# ---- Driver -----------------------------------------------------------------------------------


def pages(root):
    return [root / "README.md"] + sorted((root / "docs").glob("*.md"))


def run(root, hush):
    usage = None
    if hush:
        out = subprocess.run([hush, "--help"], capture_output=True, text=True, check=False)
        usage = Usage(out.stdout + out.stderr)
        if not usage.commands:
            return [f"{hush} --help printed no usage sections"]
    problems = []
    for page in pages(root):
        problems += check_links(page, root)
        problems += check_commands(page, root, usage)
    return problems


# The broken page of the self-test. Its made-up names are spelled through {} fields, so that
# the registry test, which looks for named files that do not exist, does not count them.
BAD_PAGE = """# A page

## Real heading

[fine](#real-heading) [missing anchor](#no-such-heading) [missing file](gone.md)
![missing image](gallery/none.png) [bad anchor elsewhere](other.md#nope)
[good elsewhere](other.md#other-page)

```sh
bash tools/{script}
hush no-such-command --out x
hush sample perlin --no-such-option 3 --out x.png
hush sample no-such-noise --out x.png
hush sample perlin --octaves 3 --out x.png
```

Inline, `hush sample perlin --no-such-inline-option 2 --out x.png` is checked too.
"""


SCRIPT = "no_such_script.sh"


def self_test(hush):
    """Runs the checks on a page with one broken thing of each kind; each must be reported."""
    with tempfile.TemporaryDirectory() as tmp:
        root = pathlib.Path(tmp).resolve()
        (root / "docs").mkdir()
        (root / "README.md").write_text("# Readme\n\nSee [the page]({}/page.md).\n".format("docs"))
        (root / "docs" / "page.md").write_text(BAD_PAGE.format(script=SCRIPT))
        (root / "docs" / "other.md").write_text("# Other page\n")
        problems = run(root, hush)
    expected = ["no-such-heading", "gone.md", "gallery/none.png", "other.md#nope",
                f"tools/{SCRIPT}"]
    if hush:
        expected += ["no-such-command", "--no-such-option", "no-such-noise",
                     "--no-such-inline-option"]
    missed = [e for e in expected if not any(e in p for p in problems)]
    false = [p for p in problems if not any(e in p for e in expected)]
    for p in problems:
        print("caught: " + p)
    if missed or false:
        for e in missed:
            print(f"check_docs self-test: a broken '{e}' was not reported")
        for p in false:
            print(f"check_docs self-test: reported something that is fine: {p}")
        return 1
    print(f"check_docs self-test: all {len(expected)} broken references reported")
    return 0


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--root", default=str(pathlib.Path(__file__).resolve().parents[2]))
    parser.add_argument("--hush", default=None, help="the hush program (commands unchecked "
                        "without it)")
    parser.add_argument("--self-test", action="store_true")
    args = parser.parse_args()
    if args.self_test:
        return self_test(args.hush)
    root = pathlib.Path(args.root).resolve()
    problems = run(root, args.hush)
    for p in problems:
        print(p)
    if problems:
        print(f"check_docs: {len(problems)} problem(s) in README.md and docs/*.md")
        return 1
    print(f"check_docs: {len(pages(root))} pages: links, anchors"
          + (", hush commands" if args.hush else "") + " all resolve")
    return 0


if __name__ == "__main__":
    sys.exit(main())
