#!/usr/bin/env python3
"""Checks the README and the docs/ pages (issue 27, "a README that is a front door").

    python3 tests/docs/readme_check.py RELIEF_BINARY SOURCE_DIR

(a) Links: every relative link in README.md and in every docs/*.md page names a file or
    directory that exists, and a link with a #anchor into a Markdown file names one of that
    file's headings (GitHub's slugs: lower case, spaces to '-', punctuation other than '-' and
    '_' dropped, '-1', '-2', ... after repeated headings). Links in code are not links.
(b) Commands: every `relief ...` or `build/tools/relief ...` line of README.md's ```sh blocks
    runs with RELIEF_BINARY in its place and exits with 0 within the time limit. Each block
    runs in a fresh temporary directory, its lines in order (a line may use what an earlier
    line of its block wrote); other lines (`make ...`) are not run. A command may not name an
    absolute path or leave its directory ('..'), and the commands must leave the source tree
    as they found it.

One line per check, then "N passed, M failed"; exit status 1 if any check failed. Python 3's
standard library only.
"""
import os
import re
import shlex
import subprocess
import sys
import tempfile
import time
import unicodedata
import urllib.parse

# Seconds one README command may take. The README shows small frames: its slowest line (the
# sweep) takes 3 s in the release build and 13 s in the sanitizer build.
COMMAND_TIME_LIMIT = 120

FENCE = re.compile(r"^ {0,3}(`{3,}|~{3,})\s*([^\s`]*)")
HEADING = re.compile(r"^ {0,3}(#{1,6})[ \t]+(.*?)[ \t]*$")
INLINE_LINK = re.compile(r"\]\(\s*(<[^>]*>|[^()\s]+(?:\([^()\s]*\)[^()\s]*)*)"
                         r"(?:\s+(?:\"[^\"]*\"|'[^']*'))?\s*\)")
REFERENCE_DEFINITION = re.compile(r"^ {0,3}\[[^\]]+\]:\s*(<[^>]*>|\S+)")
HTML_LINK = re.compile(r"""<(?:a|img)\b[^>]*?\b(?:href|src)\s*=\s*["']([^"']+)["']""", re.I)
HTML_ANCHOR = re.compile(r"""<[a-z]+\b[^>]*?\b(?:id|name)\s*=\s*["']([^"']+)["']""", re.I)
SCHEME = re.compile(r"^[a-zA-Z][a-zA-Z0-9+.-]*:")
SHELL_OPERATORS = ("|", "||", "&", "&&", ";", ";;", ">", ">>", "<", "<<", "(", ")", ">&", "<&")


class Report:
    def __init__(self):
        self.passed = 0
        self.failed = 0

    def check(self, ok, what, why=""):
        if ok:
            self.passed += 1
            print(f"ok      {what}")
        else:
            self.failed += 1
            print(f"FAILED  {what}" + (f": {why}" if why else ""))


def split_fences(text):
    """(line number, line, info string of the enclosing fence or None) for every line; fence
    lines themselves are given with the info string "fence"."""
    out = []
    fence = None
    info = None
    for number, line in enumerate(text.split("\n"), 1):
        m = FENCE.match(line)
        if fence is None and m:
            fence, info = m.group(1), m.group(2).lower()
            out.append((number, line, "fence"))
        elif fence is not None and line.strip().startswith(fence[0] * len(fence)) and \
                line.strip().strip(fence[0]) == "":
            fence = None
            out.append((number, line, "fence"))
        else:
            out.append((number, line, info if fence is not None else None))
    return out


def strip_code_spans(line):
    """The line with its inline code spans blanked (`...`, ``...``)."""
    out = []
    i = 0
    while i < len(line):
        if line[i] == "`":
            j = i
            while j < len(line) and line[j] == "`":
                j += 1
            ticks = line[i:j]
            end = line.find(ticks, j)
            while end != -1 and end + len(ticks) < len(line) and line[end + len(ticks)] == "`":
                end = line.find(ticks, end + len(ticks) + 1)
            if end == -1:
                out.append(ticks)
                i = j
            else:
                out.append(" " * (end + len(ticks) - i))
                i = end + len(ticks)
        else:
            out.append(line[i])
            i += 1
    return "".join(out)


def heading_text(raw):
    """A heading's text as GitHub renders it: no closing #s, links and images as their text,
    no code ticks or emphasis stars, no HTML tags."""
    text = re.sub(r"[ \t]+#+$", "", raw)
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", text)
    text = re.sub(r"<[^>]+>", "", text)
    return text.replace("`", "").replace("*", "")


def slug(text):
    """GitHub's anchor for a heading's text."""
    text = unicodedata.normalize("NFC", text.strip().lower())
    kept = []
    for c in text:
        category = unicodedata.category(c)
        if c in "-_ " or category[0] in "LN" or category == "Mn" or category == "Pc":
            kept.append(c)
    return "".join(kept).replace(" ", "-")


_anchor_cache = {}


def anchors(path):
    """The anchors of a Markdown file: its headings' slugs and explicit id/name attributes."""
    if path in _anchor_cache:
        return _anchor_cache[path]
    with open(path, encoding="utf-8") as f:
        text = f.read()
    found = set()
    seen = {}
    for _, line, info in split_fences(text):
        if info is not None:
            continue
        m = HEADING.match(line)
        if m:
            base = slug(heading_text(m.group(2)))
            n = seen.get(base, 0)
            seen[base] = n + 1
            found.add(base if n == 0 else f"{base}-{n}")
        for a in HTML_ANCHOR.findall(line):
            found.add(a)
    _anchor_cache[path] = found
    return found


def links(text):
    """(line number, target) of every link outside code."""
    out = []
    for number, line, info in split_fences(text):
        if info is not None:
            continue
        bare = strip_code_spans(line)
        for m in INLINE_LINK.finditer(bare):
            out.append((number, m.group(1).strip("<>")))
        m = REFERENCE_DEFINITION.match(bare)
        if m:
            out.append((number, m.group(1).strip("<>")))
        for target in HTML_LINK.findall(bare):
            out.append((number, target))
    return out


def check_links(report, source, page):
    path = os.path.join(source, page)
    with open(path, encoding="utf-8") as f:
        text = f.read()
    for number, target in links(text):
        if SCHEME.match(target) or target.startswith("//"):
            continue  # http:, https:, mailto:: not this check's business
        what = f"link {page}:{number} -> {target}"
        file_part, _, anchor = target.partition("#")
        file_part = urllib.parse.unquote(file_part)
        if file_part.startswith("/"):
            report.check(False, what, "an absolute path; links are relative to the page")
            continue
        resolved = os.path.normpath(os.path.join(os.path.dirname(path), file_part)) \
            if file_part else path
        if os.path.relpath(resolved, source).startswith(".."):
            report.check(False, what, "points outside the repository")
            continue
        if not os.path.exists(resolved):
            report.check(False, what, f"{os.path.relpath(resolved, source)} does not exist")
            continue
        if anchor and resolved.endswith(".md") and os.path.isfile(resolved):
            anchor = urllib.parse.unquote(anchor)
            if anchor not in anchors(resolved):
                report.check(False, what,
                             f"no heading of {os.path.relpath(resolved, source)} has the "
                             f"anchor #{anchor}")
                continue
        report.check(True, what)


def sh_blocks(text):
    """The ```sh blocks of a Markdown text: lists of (line number, logical line), a line ending
    in a backslash joined with the next."""
    blocks = []
    current = None
    pending = None
    for number, line, info in split_fences(text):
        if info == "fence":
            if current is None and FENCE.match(line).group(2).lower() == "sh":
                current = []
            elif current is not None:
                blocks.append(current)
                current = None
            continue
        if current is None:
            continue
        if pending is not None:
            start, joined = pending
            line = joined + " " + line.strip()
            number = start
        if line.rstrip().endswith("\\"):
            pending = (number, line.rstrip()[:-1].rstrip())
            continue
        pending = None
        current.append((number, line.strip()))
    return blocks


def relief_argv(line):
    """The argv of a README line that runs relief, or None for other lines."""
    for prefix in ("relief ", "build/tools/relief "):
        if line.startswith(prefix) or line == prefix.strip():
            lexer = shlex.shlex(line, posix=True, punctuation_chars=True)
            lexer.whitespace_split = True
            lexer.commenters = "#"
            return list(lexer)
    return None


# What relief writes (images, floats, reports, its temporary files). The source tree is
# compared for these only, so that an edit made to it while the check runs is not taken for a
# command's output.
WRITTEN = (".png", ".pfm", ".exr", ".json", ".bin", ".csv", ".gp", ".tmp")


def tree_state(source):
    """(path, size, mtime) of the source tree's files that relief could have written; builds,
    .git and caches left out."""
    state = set()
    for root, dirs, files in os.walk(source):
        rel = os.path.relpath(root, source)
        if rel == ".":
            dirs[:] = [d for d in dirs if not d.startswith("build") and d != ".git"]
        dirs[:] = [d for d in dirs if d != "__pycache__"]
        for name in files:
            if not name.endswith(WRITTEN):
                continue
            path = os.path.join(root, name)
            try:
                st = os.lstat(path)
            except OSError:
                continue
            state.add((os.path.relpath(path, source), st.st_size, st.st_mtime_ns))
    return state


def check_commands(report, binary, source):
    with open(os.path.join(source, "README.md"), encoding="utf-8") as f:
        blocks = sh_blocks(f.read())
    before = tree_state(source)
    for block in blocks:
        with tempfile.TemporaryDirectory(prefix="relief-readme-") as work:
            env = dict(os.environ, HOME=work, TMPDIR=work)
            for number, line in block:
                argv = relief_argv(line)
                if argv is None:
                    continue
                what = f"README.md:{number}: {line}"
                shell = [a for a in argv if a in SHELL_OPERATORS]
                if shell:
                    report.check(False, what, f"uses the shell ({' '.join(shell)}); "
                                 "the check runs the command without one")
                    continue
                outside = [a for a in argv[1:] if a.startswith("/") or a.startswith("~") or
                           ".." in re.split(r"[/=]", a)]
                if outside:
                    report.check(False, what, f"names a path outside its directory: {outside[0]}")
                    continue
                started = time.monotonic()
                try:
                    run = subprocess.run([binary] + argv[1:], cwd=work, env=env,
                                         stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                                         stderr=subprocess.PIPE, timeout=COMMAND_TIME_LIMIT)
                except subprocess.TimeoutExpired:
                    report.check(False, what, f"ran past {COMMAND_TIME_LIMIT} s")
                    continue
                except OSError as e:
                    report.check(False, what, f"cannot run {binary}: {e}")
                    continue
                seconds = time.monotonic() - started
                if run.returncode != 0:
                    tail = (run.stderr or run.stdout).decode("utf-8", "replace").strip()
                    tail = " | ".join(tail.splitlines()[-3:])
                    report.check(False, what, f"exit code {run.returncode}: {tail}")
                else:
                    report.check(True, f"{what} ({seconds:.1f} s)")
    after = tree_state(source)
    changed = sorted({p for p, _, _ in before ^ after})
    report.check(not changed, "README commands leave the source tree as they found it",
                 "changed: " + ", ".join(changed[:5]))


def main():
    if len(sys.argv) != 3:
        print("usage: readme_check.py RELIEF_BINARY SOURCE_DIR", file=sys.stderr)
        return 2
    binary = os.path.abspath(sys.argv[1])
    source = os.path.abspath(sys.argv[2])
    report = Report()
    pages = ["README.md"] + sorted(
        "docs/" + name for name in os.listdir(os.path.join(source, "docs"))
        if name.endswith(".md"))
    for page in pages:
        check_links(report, source, page)
    check_commands(report, binary, source)
    print(f"{report.passed} passed, {report.failed} failed")
    return 1 if report.failed else 0


if __name__ == "__main__":
    sys.exit(main())
