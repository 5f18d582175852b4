#!/usr/bin/env python3
"""The anchors' side_by_side_summarize.py on this harness's results.tsv, with the W4 pair added.

usage: A=shared/bench-anchors python3 bench/lammps/summarize.py [--diff] [--gated] RESULTS.tsv
The anchors' script (medians and ratios; its options --diff and --gated) is run as it is, its list of
LAMMPS/toolkit pairs extended by ("w4_body_polygon", "dem-contacts"). A defaults to shared/bench-anchors
beside the repository.
"""
import os
import sys

here = os.path.dirname(os.path.abspath(__file__))
anchors = os.environ.get("A") or os.path.join(here, "..", "..", "..", "shared", "bench-anchors")
path = os.path.join(anchors, "side_by_side_summarize.py")
src = open(path).read()
marker = "pairs = ["
if marker not in src:
    sys.exit(f"{path}: no 'pairs = [' to extend")
src = src.replace(marker, marker + '("w4_body_polygon", "dem-contacts"), ', 1)
exec(compile(src, path, "exec"), {"__name__": "__main__"})
