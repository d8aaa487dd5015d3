#!/usr/bin/env python3
"""The tables and figures the docs quote from runs, kept between markers.

Usage: doc_tables.py replace DOC NAME FILE   put FILE's text between
                                             <!-- NAME:begin --> and <!-- NAME:end --> in DOC
       doc_tables.py check DOC NAME FILE     exit 1, with a diff, when DOC holds other text there

scripts/regenerate_docs.sh makes every table and figure anew through it; the
docs_drift test checks the deterministic ones against a fresh run.
"""
import difflib
import sys


def split(doc_text, name, doc):
    begin, end = f"<!-- {name}:begin -->\n", f"<!-- {name}:end -->"
    if begin not in doc_text or end not in doc_text:
        sys.exit(f"{doc}: no {begin.strip()} ... {end} markers")
    head, rest = doc_text.split(begin, 1)
    body, tail = rest.split(end, 1)
    return head + begin, body, end + tail


def main():
    if len(sys.argv) != 5 or sys.argv[1] not in ("replace", "check"):
        sys.exit(__doc__.split("\n\n")[1])
    verb, doc, name, file = sys.argv[1:]
    text = open(file, encoding="utf-8").read()
    head, body, tail = split(open(doc, encoding="utf-8").read(), name, doc)
    if verb == "replace":
        open(doc, "w", encoding="utf-8").write(head + text + tail)
        print(f"{doc}: {name} written", file=sys.stderr)
        return 0
    if body == text:
        return 0
    print(f"{doc}: the {name} table differs from a fresh run (scripts/regenerate_docs.sh makes it anew):")
    sys.stdout.writelines(difflib.unified_diff(body.splitlines(True), text.splitlines(True), "docs", "fresh run"))
    return 1


if __name__ == "__main__":
    sys.exit(main())
