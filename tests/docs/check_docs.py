#!/usr/bin/env python3
"""The docs' references resolve: in README.md, docs/*.md and docs/history/*.md every relative Markdown
link or image names a file (and its #anchor a heading there), every repository path written in the text
(renderer/..., docs/..., with * globs and {a,b} alternatives) exists, and every test named in backticks
as `Suite.Name` or `Suite.*` is defined by a TEST, TEST_F or TEST_P under tests/.
Usage: check_docs.py [SOURCE_DIR]; prints each miss and exits 1 when there is one."""
import glob
import os
import re
import sys

PATH = re.compile(r"(?<![\w/.])((?:docs|renderer|scene|io|cli|tests|scripts|configs)/[\w./*{},-]*[\w*}])")
LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)\)")
TEST = re.compile(r"\b(?:TEST|TEST_F|TEST_P|TYPED_TEST)\(\s*(\w+)\s*,\s*(\w+)\s*\)")
TEST_REF = re.compile(r"\b([A-Z][A-Za-z0-9]+)\.([A-Z][A-Za-z0-9_]+|\*)")


def headings(path):
    """GitHub-style anchors of a Markdown file's headings."""
    out = set()
    for line in open(path, encoding="utf-8"):
        m = re.match(r"#+\s+(.*)", line)
        if m:
            out.add(re.sub(r"[^\w\- ]", "", m.group(1).strip().lower()).replace(" ", "-"))
    return out


def defined_tests():
    names = set()
    for f in glob.glob("tests/**/*.cpp", recursive=True) + glob.glob("tests/**/*.h", recursive=True):
        names.update(f"{a}.{b}" for a, b in TEST.findall(open(f, encoding="utf-8").read()))
    return names


def check(path, text, tests):
    misses = []
    for m in LINK.finditer(text):
        target = m.group(1)
        if re.match(r"[a-z]+:", target):
            continue  # http:, mailto:
        file, _, anchor = target.partition("#")
        full = os.path.normpath(os.path.join(os.path.dirname(path), file)) if file else path
        if not os.path.exists(full):
            misses.append(f"link {target}: no {full}")
        elif anchor and full.endswith(".md") and anchor not in headings(full):
            misses.append(f"link {target}: no heading #{anchor} in {full}")
    for m in PATH.finditer(text):
        p = m.group(1).rstrip(".,")
        if "####" in p:
            continue  # a frame pattern, not a file
        b = re.search(r"\{([^}]*)\}", p)
        for alt in [p[:b.start()] + x + p[b.end():] for x in b.group(1).split(",")] if b else [p]:
            if not glob.glob(alt):
                misses.append(f"path {p}: nothing at {alt}")
    # Names may be wrapped across lines inside their backticks.
    for span in re.findall(r"`([^`]*)`", re.sub(r"\n\s*", "", text)):
        for suite, name in TEST_REF.findall(span):
            ok = any(t.startswith(suite + ".") for t in tests) if name == "*" else f"{suite}.{name}" in tests
            if not ok:
                misses.append(f"test {suite}.{name}: no such TEST under tests/")
    return misses


def main():
    os.chdir(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "../.."))
    tests = defined_tests()
    if not tests:
        print("no TEST definitions found under tests/: wrong source dir?")
        return 1
    bad = 0
    for path in ["README.md"] + sorted(glob.glob("docs/*.md")) + sorted(glob.glob("docs/history/*.md")):
        for miss in check(path, open(path, encoding="utf-8").read(), tests):
            print(f"{path}: {miss}")
            bad += 1
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
