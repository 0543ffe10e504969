#!/usr/bin/env python3
"""Formats one Markdown table row from a `dtlab triangulate --stats -` JSON object on stdin.

Usage: dtlab triangulate ... --stats - | tools/stats_row.py robustness FAMILY KERNEL
       dtlab triangulate ... --stats - | tools/stats_row.py aux FAMILY SEED
"""
import json
import sys

kind, label, variant = sys.argv[1], sys.argv[2], sys.argv[3]
d = json.load(sys.stdin)
if kind == "robustness":
    v = d["validation"]
    cells = [label, variant, d["abandoned_insertions"], v["non_delaunay_faces"],
             "yes" if v["consistent"] else "no", "yes" if v["valid"] else "no",
             "%.2f" % d["seconds"]["total"]]
else:
    cells = [label, variant, d["tetrahedra"], d["hull_tetrahedra_lost"]]
print("| " + " | ".join(str(c) for c in cells) + " |")
