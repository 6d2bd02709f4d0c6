#!/usr/bin/env python3
"""Every relative link and picture of the documents points at something that exists: README.md,
docs/*.md and the Markdown files of the packages. A link to another document's `#anchor` must name
one of its headings (GitHub's anchors). Links in code (fenced blocks, `inline`) are not links.

Usage: doc_links_test.py REPOSITORY   (run by ctest as `doc_links`)
"""
import glob
import os
import re
import sys
import unittest

REPO = os.path.abspath(sys.argv[1]) if len(sys.argv) > 1 else os.getcwd()
NOT_SOURCES = ("build", "devel", "out", "install", "node_modules")

# [text](target) and ![alt](target); the target ends at a space (a "title") or the closing parenthesis.
LINK = re.compile(r"!?\[[^\]]*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
HEADING = re.compile(r"^#{1,6}\s+(.*?)\s*#*\s*$")


def documents(repo):
    found = [os.path.join(repo, "README.md")]
    found += sorted(glob.glob(os.path.join(repo, "docs", "**", "*.md"), recursive=True))
    for path in sorted(glob.glob(os.path.join(repo, "*", "*.md"))):
        if os.path.relpath(path, repo).split(os.sep)[0] not in NOT_SOURCES + ("docs",):
            found.append(path)
    return [p for p in found if os.path.isfile(p)]


def prose(text, inline_code=False):
    """The text without fenced code blocks (and without inline code), line numbers kept."""
    lines, fenced = [], False
    for line in text.split("\n"):
        if line.lstrip().startswith("```"):
            fenced = not fenced
            lines.append("")
        elif fenced:
            lines.append("")
        else:
            lines.append(line if inline_code else re.sub(r"`[^`]*`", "", line))
    return lines


def anchor(heading):
    """GitHub's anchor of a heading: lower case, punctuation but - and _ dropped, spaces to -."""
    text = re.sub(r"`|\*\*|\*", "", heading).strip().lower()
    text = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", text)  # a link in a heading anchors by its text
    return re.sub(r"[^\w\- ]", "", text).replace(" ", "-")


def anchors(path):
    with open(path, encoding="utf-8") as f:
        names, seen = set(), {}
        for line in prose(f.read(), inline_code=True):
            m = HEADING.match(line)
            if m:
                a = anchor(m.group(1))
                n = seen.get(a, 0)
                seen[a] = n + 1
                names.add(a if n == 0 else "%s-%d" % (a, n))
        return names


def broken_links(path, text):
    """(line, target, why) of each relative link of `text` (the file `path`) that leads nowhere."""
    broken = []
    for number, line in enumerate(prose(text), 1):
        for target in LINK.findall(line):
            if re.match(r"^[a-z][a-z0-9+.-]*:", target, re.I):  # http:, https:, mailto:
                continue
            file_part, _, fragment = target.partition("#")
            resolved = os.path.normpath(os.path.join(os.path.dirname(path), file_part)) if file_part else path
            if not os.path.exists(resolved):
                broken.append((number, target, "no such file %s" % os.path.relpath(resolved, REPO)))
            elif fragment and resolved.endswith(".md") and fragment not in anchors(resolved):
                broken.append((number, target, "%s has no heading with the anchor #%s"
                               % (os.path.relpath(resolved, REPO), fragment)))
    return broken


class DocLinks(unittest.TestCase):
    def test_every_relative_link_leads_to_a_file_and_heading(self):
        docs = documents(REPO)
        self.assertIn(os.path.join(REPO, "docs", "nets.md"), docs)  # the search found the documents
        report = []
        for path in docs:
            with open(path, encoding="utf-8") as f:
                for number, target, why in broken_links(path, f.read()):
                    report.append("%s:%d: (%s): %s" % (os.path.relpath(path, REPO), number, target, why))
        self.assertEqual(report, [], "broken links:\n" + "\n".join(report))

    def test_a_missing_file_or_heading_is_reported_and_code_is_not_a_link(self):
        readme = os.path.join(REPO, "README.md")
        text = ("[ok](docs/nets.md) [gone](docs/no_such_file.md) ![pic](docs/none.png)\n"
                "[bad anchor](docs/nets.md#no-such-heading) [good anchor](docs/nets.md#writing-a-block)\n"
                "`[not a link](nowhere.md)` [web](https://example.com/x.md)\n"
                "```\n[in code](nowhere.md)\n```\n")
        found = [(line, target) for line, target, _ in broken_links(readme, text)]
        self.assertEqual(found, [(1, "docs/no_such_file.md"), (1, "docs/none.png"),
                                 (2, "docs/nets.md#no-such-heading")])

    def test_anchors_follow_github(self):
        self.assertEqual(anchor("Sub-nets (paper 3.5)"), "sub-nets-paper-35")
        self.assertEqual(anchor("A second robot (six_axis)"), "a-second-robot-six_axis")
        self.assertEqual(anchor("Using `imagenets run`"), "using-imagenets-run")


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1], verbosity=2)
