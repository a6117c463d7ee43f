#!/usr/bin/env python3
"""Splice fe bench summaries into docs/BENCHMARKS.md.

usage: update_benchmarks.py DOC NAME=BENCH_OUT_DIR [NAME=DIR ...]

Each NAME's summary.md (written by report.py) replaces the text between the lines
"<!-- fe-bench NAME -->" and "<!-- /fe-bench NAME -->" in DOC, and its charts (PNG) are copied
to docs/bench/NAME/, so the tables in the document come from the tool, never from a hand.
A marker missing from DOC is an error: a section must not silently stop being regenerated.
"""
import os
import shutil
import sys


def main(doc_path, pairs):
    with open(doc_path) as f:
        doc = f.read()
    for pair in pairs:
        name, _, out = pair.partition("=")
        if not name or not out:
            sys.exit(f"update_benchmarks: expected NAME=DIR, got '{pair}'")
        begin, end = f"<!-- fe-bench {name} -->", f"<!-- /fe-bench {name} -->"
        if begin not in doc or end not in doc:
            sys.exit(f"update_benchmarks: {doc_path} has no '{begin}' ... '{end}' section")
        with open(os.path.join(out, "summary.md")) as f:
            summary = f.read().strip()
        charts = os.path.join(out, "charts")
        target = os.path.join(os.path.dirname(os.path.abspath(doc_path)), "bench", name)
        os.makedirs(target, exist_ok=True)
        names = sorted(c for c in os.listdir(charts) if c.endswith(".png")) if os.path.isdir(charts) else []
        for c in names:
            shutil.copy(os.path.join(charts, c), os.path.join(target, c))
        if names:
            summary += "\n\nCharts: " + ", ".join(f"[{c[:-4]}](bench/{name}/{c})" for c in names) + "."
        head, rest = doc.split(begin, 1)
        _, tail = rest.split(end, 1)
        doc = f"{head}{begin}\n{summary}\n{end}{tail}"
    with open(doc_path, "w") as f:
        f.write(doc)


if __name__ == "__main__":
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2:])
