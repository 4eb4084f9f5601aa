#!/usr/bin/env python3
"""Write doc/manual/parameters.md from `fidus --print-parameters`.

Usage:
    contrib/doc/parameters_reference.py [--fidus PATH] [--input FILE] [--output FILE]

Runs `fidus --print-parameters` (or reads its output from --input FILE,
'-' for stdin), parses the deal.II PRM listing (subsections, the comment
lines that document each entry, `set Name = default`) and prints the
reference page in Markdown, one section per subsection, one paragraph per
entry: its full name, its default and its documentation. The page holds
nothing that --print-parameters does not give, so the output is the same
for the same binary, and tests/doc/check_parameters_reference.sh compares
it with the committed page.

Refresh the committed page (after a build) with
    contrib/doc/parameters_reference.py --fidus build-release/fidus \
        --output doc/manual/parameters.md
"""
import argparse
import os
import subprocess
import sys

HEADER = """\
# Parameters reference

Every entry of a fidus parameter file, with its default and its
documentation, as `fidus --print-parameters` prints them. Entries are named
by their subsections and name, separated by `/`, as the error messages,
`contrib/convergence_study.py --vary` and the rest of this manual name them.
An entry you do not set keeps its default; `used_parameters.prm` in the
Output directory lists every value a run used.

How to use these entries, step by step: [writing_a_scene.md](writing_a_scene.md).

This page is generated; do not edit it by hand. After a change of the
parameters, refresh it with

    contrib/doc/parameters_reference.py --fidus build-release/fidus --output doc/manual/parameters.md

(the test `doc.parameters_reference` fails while it is stale).
"""


def run_fidus(fidus):
    env = dict(os.environ)
    env.setdefault("OMPI_ALLOW_RUN_AS_ROOT", "1")
    env.setdefault("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
    try:
        done = subprocess.run([fidus, "--print-parameters"], env=env,
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                              universal_newlines=True, timeout=120)
    except OSError as e:
        sys.exit("parameters_reference.py: cannot run %s: %s" % (fidus, e))
    if done.returncode != 0:
        sys.exit("parameters_reference.py: %s --print-parameters exited with %d:\n%s"
                 % (fidus, done.returncode, done.stderr))
    return done.stdout


def parse(text):
    """Return [(path list, name, default, documentation)] in listing order."""
    entries = []
    section = []
    comment = []
    for raw in text.splitlines():
        line = raw.strip()
        if not line:
            comment = []
            continue
        if line.startswith("#"):
            body = line[1:].strip()
            # The listing's title and its underline are not documentation.
            if body in ("Listing of Parameters", "---------------------") or \
                    set(body) == {"-"}:
                continue
            comment.append(body)
            continue
        words = line.split(None, 1)
        if words[0] == "subsection":
            section.append(words[1].strip())
            comment = []
        elif words[0] == "end":
            if section:
                section.pop()
            comment = []
        elif words[0] == "set":
            rest = words[1]
            name, _, value = rest.partition("=")
            # deal.II appends '# default: x' when the value differs from it;
            # --print-parameters prints the defaults, so only strip it.
            value = value.split(" # ")[0].strip() if " # " in value else value.strip()
            entries.append((list(section), name.strip(), value, " ".join(comment)))
            comment = []
    return entries


def markdown(entries):
    out = [HEADER]
    groups = []
    for path, name, default, doc in entries:
        key = "/".join(path)
        if not groups or groups[-1][0] != key:
            groups.append((key, []))
        groups[-1][1].append((path, name, default, doc))
    out.append("## Contents\n")
    for key, items in groups:
        title = key if key else "Top level"
        anchor = title.lower().replace("/", "").replace(" ", "-")
        out.append("- [%s](#%s) (%d)" % (title, anchor, len(items)))
    out.append("")
    for key, items in groups:
        out.append("## %s\n" % (key if key else "Top level"))
        for path, name, default, doc in items:
            full = "/".join(path + [name])
            shown = "`%s`" % default if default else "*(empty)*"
            out.append("**`%s`** = %s\n" % (full, shown))
            if doc:
                # A '*' of the documentation (u*, r * eta) is not emphasis.
                out.append(doc.replace("*", "\\*") + "\n")
    return "\n".join(out).rstrip("\n") + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fidus", default=os.environ.get("FIDUS", "build-release/fidus"))
    parser.add_argument("--input", default=None,
                        help="read the listing from this file ('-': stdin) instead of running fidus")
    parser.add_argument("--output", default="-", help="the page to write ('-': stdout)")
    args = parser.parse_args()
    if args.input == "-":
        text = sys.stdin.read()
    elif args.input:
        text = open(args.input).read()
    else:
        text = run_fidus(args.fidus)
    entries = parse(text)
    if not entries:
        sys.exit("parameters_reference.py: no 'set' line in the listing")
    page = markdown(entries)
    if args.output == "-":
        sys.stdout.write(page)
    else:
        with open(args.output, "w") as f:
            f.write(page)


if __name__ == "__main__":
    main()
