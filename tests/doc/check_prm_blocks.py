#!/usr/bin/env python3
"""Check the parameter-file examples of the manual and the cookbooks.

Usage: tests/doc/check_prm_blocks.py FIDUS SOURCE_DIR

Convention for fenced code blocks in doc/manual/*.md and doc/cookbooks/*.md
(and doc/README.md):

  ```prm            a complete parameter file. It is written to a file in a
                    fresh temporary folder (the working directory of the
                    check) and must pass `fidus --validate`, which checks
                    every entry, value and the scene and writes nothing.
  ```prm-fragment   an excerpt (a few entries with their subsections), not a
                    file on its own. Every `set` in it must name an entry that
                    `fidus --print-parameters` lists, at its subsection path,
                    and every `subsection` must be closed by `end`.

Other blocks (```sh, ```text, indented code) are not checked. A block that
fails is named by its page and first line; the test then exits with 1.
"""
import os
import re
import subprocess
import sys
import tempfile

PAGES_DIRS = ["doc/manual", "doc/cookbooks"]
EXTRA_PAGES = ["doc/README.md"]
FENCE = re.compile(r"^(\s*)```\s*([A-Za-z0-9_-]*)\s*$")


def environment():
    env = dict(os.environ)
    env.setdefault("OMPI_ALLOW_RUN_AS_ROOT", "1")
    env.setdefault("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
    return env


def blocks(path):
    """Yield (kind, first line number, text) of the fenced blocks of a page."""
    kind = None
    lines = []
    start = 0
    indent = ""
    for number, line in enumerate(open(path, encoding="utf-8"), 1):
        match = FENCE.match(line)
        if kind is None:
            if match:
                indent = match.group(1)
                kind = match.group(2) or "plain"
                start = number + 1
                lines = []
        elif match and not match.group(2):
            yield kind, start, "".join(lines)
            kind = None
        else:
            lines.append(line[len(indent):] if line.startswith(indent) else line)


def known_entries(fidus):
    done = subprocess.run([fidus, "--print-parameters"], env=environment(),
                          stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                          universal_newlines=True, timeout=120)
    if done.returncode != 0:
        sys.exit("check_prm_blocks.py: %s --print-parameters failed:\n%s"
                 % (fidus, done.stderr))
    names, section = set(), []
    for line in done.stdout.splitlines():
        words = line.strip().split(None, 1)
        if not words or words[0].startswith("#"):
            continue
        if words[0] == "subsection":
            section.append(words[1].strip())
        elif words[0] == "end":
            section.pop()
        elif words[0] == "set":
            names.add("/".join(section + [words[1].split("=")[0].strip()]))
    return names


def check_fragment(text, names):
    section, problems = [], []
    for line in text.splitlines():
        words = line.split("#")[0].strip().split(None, 1)
        if not words:
            continue
        if words[0] == "subsection" and len(words) == 2:
            section.append(words[1].strip())
        elif words[0] == "end":
            if not section:
                problems.append("'end' without 'subsection'")
            else:
                section.pop()
        elif words[0] == "set" and len(words) == 2 and "=" in words[1]:
            name = "/".join(section + [words[1].split("=")[0].strip()])
            if name not in names:
                problems.append("unknown entry '%s'" % name)
        else:
            problems.append("not a parameter line: '%s'" % line.strip())
    if section:
        problems.append("subsection '%s' not closed" % "/".join(section))
    return problems


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    fidus = os.path.abspath(sys.argv[1])
    source = os.path.abspath(sys.argv[2])
    pages = [os.path.join(source, p) for p in EXTRA_PAGES]
    for folder in PAGES_DIRS:
        full = os.path.join(source, folder)
        pages += sorted(os.path.join(full, f) for f in os.listdir(full) if f.endswith(".md"))
    names = known_entries(fidus)
    checked = failed = 0
    for page in pages:
        if not os.path.exists(page):
            continue
        short = os.path.relpath(page, source)
        for kind, line, text in blocks(page):
            if kind == "prm":
                checked += 1
                with tempfile.TemporaryDirectory() as work:
                    prm = os.path.join(work, "block.prm")
                    with open(prm, "w") as f:
                        f.write(text)
                    done = subprocess.run([fidus, "--validate", prm], cwd=work,
                                          env=environment(), stdout=subprocess.PIPE,
                                          stderr=subprocess.STDOUT,
                                          universal_newlines=True, timeout=120)
                if done.returncode != 0:
                    failed += 1
                    print("FAILED: %s:%d (prm block): fidus --validate exited with %d:\n%s"
                          % (short, line, done.returncode, done.stdout.strip()))
                else:
                    print("%s:%d (prm block) validates: OK" % (short, line))
            elif kind == "prm-fragment":
                checked += 1
                problems = check_fragment(text, names)
                if problems:
                    failed += 1
                    print("FAILED: %s:%d (prm-fragment block): %s"
                          % (short, line, "; ".join(problems)))
                else:
                    print("%s:%d (prm-fragment block) names known entries: OK" % (short, line))
    print("%d blocks checked, %d failed" % (checked, failed))
    if checked == 0:
        print("FAILED: no prm block found")
        return 1
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
