#!/usr/bin/env python3
"""Keeps the code's shape as a model to learn from.

    python3 tools/check_shape.py [--list N]

Python 3 standard library only; reads the files git tracks. Outside tests (a `tests/`
folder, a `tests.rs` file, a `#[cfg(test)]` module, benches) it fails when it finds

- a function over 120 lines or a file over 900 lines: a concept per file, a function
  that fits on a screen (pbrt-v4 and ripgrep are read this way);
- `Result<_, String>` in a library crate: errors are typed, as ripgrep's are;
- `#[allow(clippy::too_many_arguments)]`: a parameter struct named for what it is;
- a confidence interval computed by hand (`mean ± z · std_error`) outside crates/stats:
  every interval comes from `invlight_stats::Estimate::interval`;
- "issue N" in code, tests or docs: a reader has no tracker; name the behaviour.

`--list N` prints every function over N lines (longest first) and exits 0.
Exit status 0 when every check passes.
"""

import argparse
import os
import re
import subprocess
import sys

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MAX_FUNCTION = 120
MAX_FILE = 900

FN = re.compile(r"^\s*(?:pub(?:\([^)]*\))?\s+)?(?:const\s+)?(?:async\s+)?(?:unsafe\s+)?"
                r"(?:extern\s+\"C\"\s+)?fn\s+(\w+)")
TEST_MODULE = re.compile(r"^\s*#\[cfg\(test\)\]\s*$")
STRING_RESULT = re.compile(r"Result<[^<>]*(?:<[^<>]*>[^<>]*)*,\s*String\s*>")
HAND_INTERVAL = re.compile(r"[-+]\s*\(?\s*z\w*\s*\*\s*[\w.]*std_error")
ISSUE_NUMBER = re.compile(r"\bissues?\s+#?\d+", re.IGNORECASE)


def tracked(*patterns):
    out = subprocess.check_output(["git", "ls-files", *patterns], cwd=REPO, text=True)
    return out.split()


def is_test_path(path):
    return "/tests/" in path or path.startswith("tests/") or path.endswith("tests.rs") \
        or "/benches/" in path or path.startswith("benches/") or "/fuzz/" in path


def code_only(text):
    """The text with comments, strings and char literals blanked (newlines kept), so that
    braces count only where they are code."""
    out, i, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif text.startswith("/*", i):
            depth, j = 1, i + 2
            while j < n and depth:
                if text.startswith("/*", j):
                    depth, j = depth + 1, j + 2
                elif text.startswith("*/", j):
                    depth, j = depth - 1, j + 2
                else:
                    j += 1
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c == "r" and re.match(r'r#*"', text[i:i + 8]) and not (i and (text[i - 1].isalnum() or text[i - 1] == "_")):
            hashes = len(re.match(r"r(#*)", text[i:]).group(1))
            end = text.find('"' + "#" * hashes, i + 2 + hashes)
            j = n if end < 0 else end + 1 + hashes
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c == '"':
            j = i + 1
            while j < n and text[j] != '"':
                j += 2 if text[j] == "\\" else 1
            out.append(re.sub(r"[^\n]", " ", text[i:j + 1]))
            i = j + 1
        elif c == "'":
            m = re.match(r"'(?:\\(?:u\{[0-9a-fA-F]+\}|x[0-9a-fA-F]{2}|.)|[^\\'\n])'", text[i:i + 12])
            if m:
                out.append(" " * len(m.group(0)))
                i += len(m.group(0))
            else:
                out.append(c)
                i += 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


def functions(path):
    """(lines, name, first line) of each function outside test modules."""
    lines = code_only(open(os.path.join(REPO, path), encoding="utf-8").read()).split("\n")
    found, i = [], 0
    while i < len(lines):
        if TEST_MODULE.match(lines[i]):
            i = skip_item(lines, i + 1)
            continue
        m = FN.match(lines[i])
        if m:
            end = skip_item(lines, i)
            if end is not None:
                found.append((end - i, m.group(1), i + 1))
        i += 1
    return found


def test_lines(lines):
    """The indices of the lines of the file's `#[cfg(test)]` modules."""
    inside, i = set(), 0
    while i < len(lines):
        if TEST_MODULE.match(lines[i]):
            end = skip_item(lines, i + 1)
            inside.update(range(i, end))
            i = end
        else:
            i += 1
    return inside


def skip_item(lines, start):
    """The line after the item (a function or module) beginning at `start`: the line
    after its braces close, or after a `;` when it has no body."""
    depth, opened = 0, False
    for j in range(start, len(lines)):
        for ch in lines[j]:
            if ch == "{":
                depth, opened = depth + 1, True
            elif ch == "}":
                depth -= 1
            elif ch == ";" and not opened:
                return j + 1
        if opened and depth <= 0:
            return j + 1
    return len(lines)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--list", type=int, metavar="N", help="print functions over N lines")
    args = ap.parse_args()
    rust = [p for p in tracked("*.rs") if not is_test_path(p)]
    long = sorted(((n, p, line, name) for p in rust for n, name, line in functions(p)),
                  reverse=True)
    if args.list is not None:
        for n, p, line, name in long:
            if n > args.list:
                print("%4d %s:%d %s" % (n, p, line, name))
        return 0
    problems = []
    for n, p, line, name in long:
        if n > MAX_FUNCTION:
            problems.append("%s:%d: fn %s is %d lines (at most %d)" % (p, line, name, n, MAX_FUNCTION))
    for p in rust:
        text = open(os.path.join(REPO, p), encoding="utf-8").read()
        body = code_only(text).split("\n")
        tests = test_lines(body)
        if len(body) - len(tests) > MAX_FILE:
            problems.append("%s: %d lines outside its tests (at most %d)"
                            % (p, len(body) - len(tests), MAX_FILE))
        library = p.startswith("crates/") and "/src/" in p
        for k, l in enumerate(text.split("\n")):
            if k in tests:
                continue
            where = "%s:%d" % (p, k + 1)
            if library and STRING_RESULT.search(body[k]):
                problems.append(where + ": Result<_, String> (give it a typed error)")
            if "too_many_arguments" in l:
                problems.append(where + ": allow(too_many_arguments) (give it a parameter struct)")
            if not p.startswith("crates/stats/") and HAND_INTERVAL.search(body[k]):
                problems.append(where + ": an interval by hand (use Estimate::interval)")
    for p in tracked("*.rs", "*.md", "*.py", "*.sh", "*.toml", ".ci/run"):
        if p.endswith("tools/check_shape.py"):
            continue
        for k, l in enumerate(open(os.path.join(REPO, p), encoding="utf-8").read().split("\n")):
            if ISSUE_NUMBER.search(l):
                problems.append("%s:%d: an issue number (name the behaviour)" % (p, k + 1))
    for problem in problems:
        print(problem)
    print("shape: %d problem%s" % (len(problems), "" if len(problems) == 1 else "s"))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
