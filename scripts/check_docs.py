#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The documentation check that CI runs (scripts/test.sh; docs/testing.md).

  1. Every relative link in the repository's Markdown resolves: the file exists, and an anchor
     (`page.md#heading`) names a heading of that page, spelled as GitHub spells it.
  2. Every `docs/<page>.md` that a source, script or page names exists, and a section it names
     in quotes right after it (`docs/equations.md, "Self-contact"`) is still on that page.
  3. The wording rule: the docs, comments, scripts and outputs speak of the project alone, so no
     tracked text file has a line that matches WORDING, except the lines that
     docs/wording-allowlist.txt lists, each with its reason.

The guide's code blocks are the third part of the docs check; they are built and run by the
test suite itself (tests/docs/). Standard library only: no package beyond python3.

Usage: python3 scripts/check_docs.py [--root DIR]; exits 1 and lists every finding if any.
"""
import argparse
import pathlib
import re
import subprocess
import sys

# The terms are written as word stems joined at run time, so that the rule's own line does not
# match it and the project needs no exception for it.
_TERMS = ["sess" + "ions?", "iss" + "ue #?[0-9]+", "the fil" + "er"]
WORDING = re.compile(r"\b(" + "|".join(_TERMS) + r")\b", re.IGNORECASE)
ALLOWLIST = "docs/wording-allowlist.txt"
LINK = re.compile(r"(?<!!)\[(?:[^\]\[]|\[[^\]]*\])*\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)")
IMAGE = re.compile(r"!\[[^\]]*\]\(([^)\s]+)\)")
DOC_PATH = re.compile(r"\bdocs/[A-Za-z0-9_-]+\.md\b")
FENCE = re.compile(r"^\s*(```|~~~)")
# A page named with the sections cited after it: `docs/<page>.md, "A"` or `docs/<page>.md ("A" and
# "B")`, in prose or in a comment whose lines the quote may span.
CITED = re.compile(r"\bdocs/([A-Za-z0-9_-]+\.md)(?:,|:)?\s*\(?\s*((?:\"[^\"]+\"(?:\s*(?:,|and|or)\s*)?)+)")
COMMENT_LEAD = re.compile(r"^\s*(?:///?|#+|\*|--)?\s?")


def tracked_files(root):
    out = subprocess.run(["git", "ls-files", "-z"], cwd=root, check=True,
                         capture_output=True).stdout
    return [p for p in out.decode().split("\0") if p]


def read_text(path):
    """The file's text, or None for a binary file."""
    data = path.read_bytes()
    if b"\0" in data[:8192]:
        return None
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError:
        return None


def prose_lines(text):
    """(line number, line) of a Markdown text outside fenced code blocks."""
    fenced = False
    for n, line in enumerate(text.splitlines(), 1):
        if FENCE.match(line):
            fenced = not fenced
            continue
        if not fenced:
            yield n, line


def slug(heading):
    """GitHub's anchor for a heading: its rendered text lower-cased, punctuation dropped
    (letters, digits, `_` and `-` kept), each space a `-`."""
    text = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", heading)  # a link renders as its text
    text = text.replace("`", "").replace("*", "")
    text = text.strip().lower()
    text = "".join(c for c in text if c.isalnum() or c in " _-")
    return text.replace(" ", "-")


def anchors(text):
    """The anchors of a page's headings, duplicates numbered -1, -2, ... as GitHub does."""
    seen = {}
    result = set()
    for _, line in prose_lines(text):
        m = re.match(r"^#{1,6}\s+(.*?)\s*#*\s*$", line)
        if not m:
            continue
        base = slug(m.group(1))
        k = seen.get(base, 0)
        seen[base] = k + 1
        result.add(base if k == 0 else f"{base}-{k}")
    return result


def check_links(root, files):
    findings = []
    cache = {}
    for rel in files:
        if not rel.endswith(".md"):
            continue
        page = root / rel
        text = read_text(page)
        if text is None:
            continue
        for n, line in prose_lines(text):
            line = re.sub(r"`[^`]*`", "", line)  # code spans are not links
            for m in list(LINK.finditer(line)) + list(IMAGE.finditer(line)):
                target = m.group(1)
                if re.match(r"^[a-z][a-z0-9+.-]*:", target):  # http:, https:, mailto:
                    continue
                path_part, _, anchor = target.partition("#")
                dest = page if path_part == "" else (page.parent / path_part)
                try:
                    dest_rel = dest.resolve().relative_to(root.resolve())
                except ValueError:
                    findings.append(f"{rel}:{n}: link leaves the repository: {target}")
                    continue
                if not dest.exists():
                    findings.append(f"{rel}:{n}: no such file: {target}")
                    continue
                if anchor and dest.suffix == ".md":
                    if dest_rel not in cache:
                        cache[dest_rel] = anchors(read_text(dest) or "")
                    if anchor not in cache[dest_rel]:
                        findings.append(f"{rel}:{n}: no heading '#{anchor}' in {dest_rel}")
    return findings


def plain(text):
    """Text as it reads: Markdown's emphasis and code marks dropped, white space collapsed."""
    return " ".join(text.replace("**", "").replace("`", "").split())


def check_doc_paths(root, files):
    findings = []
    pages = {}
    for rel in files:
        text = read_text(root / rel)
        if text is None:
            continue
        for n, line in enumerate(text.splitlines(), 1):
            for m in DOC_PATH.finditer(line):
                if not (root / m.group(0)).exists():
                    findings.append(f"{rel}:{n}: names {m.group(0)}, which does not exist")
        # The quoted sections: the text joined across lines without their comment marks.
        lines = text.splitlines()
        joined, starts = "", []
        for line in lines:
            starts.append(len(joined))
            joined += COMMENT_LEAD.sub("", line, count=1) + " "
        for m in CITED.finditer(joined):
            page = root / "docs" / m.group(1)
            if not page.exists():
                continue
            if page not in pages:
                pages[page] = plain(read_text(page) or "")
            n = sum(1 for s in starts if s <= m.start())
            for title in re.findall(r'"([^"]+)"', m.group(2)):
                if plain(title).lower() not in pages[page].lower():
                    findings.append(f'{rel}:{n}: docs/{m.group(1)} has no section "{plain(title)}"')
    return findings


def read_allowlist(root):
    """Entries `path :: text on the line :: reason`; a reason is required."""
    entries = []
    path = root / ALLOWLIST
    if not path.exists():
        return entries, []
    problems = []
    for n, line in enumerate(path.read_text().splitlines(), 1):
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        parts = [p.strip() for p in line.split("::")]
        if len(parts) != 3 or not all(parts):
            problems.append(f"{ALLOWLIST}:{n}: expected 'path :: text on the line :: reason'")
            continue
        entries.append((parts[0], parts[1]))
    return entries, problems


def check_wording(root, files):
    entries, findings = read_allowlist(root)
    used = set()
    for rel in files:
        if rel == ALLOWLIST:
            continue
        text = read_text(root / rel)
        if text is None:
            continue
        for n, line in enumerate(text.splitlines(), 1):
            if not WORDING.search(line):
                continue
            allowed = [e for e in entries if e[0] == rel and e[1] in line]
            if allowed:
                used.update(allowed)
            else:
                findings.append(f"{rel}:{n}: {line.strip()[:120]}")
    for e in entries:
        if e not in used:
            findings.append(f"{ALLOWLIST}: entry matches no line, remove it: {e[0]} :: {e[1]}")
    return findings


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--root", default=pathlib.Path(__file__).resolve().parent.parent,
                        type=pathlib.Path)
    root = parser.parse_args().root
    files = tracked_files(root)
    failed = False
    for name, check in (("links", check_links), ("docs/ paths", check_doc_paths),
                        ("wording", check_wording)):
        findings = check(root, files)
        print(f"check_docs: {name}: {len(findings)} finding(s)")
        for f in findings:
            print(f"  {f}")
        failed |= bool(findings)
    if failed:
        print("check_docs: FAILED (the wording rule and the allow-list: docs/testing.md)")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
