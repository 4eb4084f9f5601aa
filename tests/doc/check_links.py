#!/usr/bin/env python3
"""Every relative link of the documentation resolves.

Usage: tests/doc/check_links.py SOURCE_DIR

Checks the Markdown links [text](target) of README.md and of every page
under doc/: a relative target must name an existing file or folder, and a
'#anchor' must match a heading of the target page (GitHub's rule: lower
case, punctuation other than '-' and '_' dropped, spaces to '-'). Links to
http(s) addresses are not followed. Also checks that no page of doc/ cites
a file outside the repository (../shared, design notes), and that every
path `doc/....md` named in the sources, scripts, tests, parameter files and
README exists (the pages that moved keep a page at their old path), and
that every scene prm/<name>.prm has its cookbook doc/cookbooks/<name>.md.
"""
import os
import re
import sys

LINK = re.compile(r"\[[^\]]*\]\(([^)\s]+)\)")
HEADING = re.compile(r"^#{1,6}\s+(.*?)\s*#*\s*$")
OUTSIDE = re.compile(r"\.\./shared|numerics\.md|interface\.md|physics_anchors|"
                     r"friction_anchors|gmg_anchors|numerics section|numerics §")


def anchors(path):
    found, fence = set(), False
    for line in open(path, encoding="utf-8"):
        if line.lstrip().startswith("```"):
            fence = not fence
            continue
        match = None if fence else HEADING.match(line)
        if match:
            text = re.sub(r"[^\w\- ]", "", match.group(1).lower().replace("`", ""))
            found.add(text.replace(" ", "-"))
    return found


def main():
    source = os.path.abspath(sys.argv[1])
    pages = [os.path.join(source, "README.md")]
    for folder, _, files in os.walk(os.path.join(source, "doc")):
        pages += [os.path.join(folder, f) for f in sorted(files) if f.endswith(".md")]
    problems = []
    for page in pages:
        short = os.path.relpath(page, source)
        fence = False
        for number, line in enumerate(open(page, encoding="utf-8"), 1):
            if line.lstrip().startswith("```"):
                fence = not fence
            if fence:
                continue
            if short.startswith("doc") and OUTSIDE.search(line):
                problems.append("%s:%d: cites a file outside the repository" % (short, number))
            for target in LINK.findall(line):
                if re.match(r"[a-z]+:", target):
                    continue
                path, _, anchor = target.partition("#")
                full = os.path.normpath(os.path.join(os.path.dirname(page), path)) if path else page
                if not os.path.exists(full):
                    problems.append("%s:%d: no file %s" % (short, number, path))
                elif anchor and full.endswith(".md") and anchor not in anchors(full):
                    problems.append("%s:%d: no heading #%s in %s" % (short, number, anchor, path or short))
    cited = re.compile(r"\bdoc/[A-Za-z0-9_/]+\.md")
    for top in ("source", "include", "contrib", "tests", "prm", "README.md"):
        base = os.path.join(source, top)
        files = [base] if os.path.isfile(base) else [
            os.path.join(folder, f) for folder, _, names in os.walk(base) for f in names]
        for path in sorted(files):
            try:
                text = open(path, encoding="utf-8").read()
            except (OSError, UnicodeDecodeError):
                continue
            for name in sorted(set(cited.findall(text))):
                if not os.path.exists(os.path.join(source, name)):
                    problems.append("%s: names %s, which does not exist"
                                    % (os.path.relpath(path, source), name))
    for name in sorted(os.listdir(os.path.join(source, "prm"))):
        if name.endswith(".prm"):
            page = os.path.join("doc", "cookbooks", name[:-4] + ".md")
            if not os.path.exists(os.path.join(source, page)):
                problems.append("prm/%s has no cookbook page %s" % (name, page))
    for problem in problems:
        print("FAILED: " + problem)
    print("%d pages checked, %d broken links" % (len(pages), len(problems)))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
