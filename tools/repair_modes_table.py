#!/usr/bin/python3
"""The table of `DTLAB_REPAIR_MODES="splay flips-splay" tools/scaling_runs.sh OUT INPUT THREADS
INSERTION repair`: per run, star splaying alone beside exact flips first, with the repair's share
of the run without it and its cost per face found beyond the pass that lists the store.

Usage: tools/repair_modes_table.py OUT/repair_TAG.jsonl
"""
import json
import sys


def main():
    rows = [json.loads(line) for line in open(sys.argv[1]) if line.strip()]
    print("| threads | seed | --repair= | run s (with repair) | repair s | share | faces found "
          "| listing s | flips | faces left | stars | us a face beyond the listing | after |")
    print("|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|")
    for r in rows:
        rep = r["seconds_repair"] or 0.0
        total = r["seconds_total"]
        faces = r["non_delaunay_faces_found"] or 0
        proven = r["proven_by_post_check"]
        beyond = ("%.0f" % (1e6 * (rep - r["seconds_scan"]) / faces)) if faces and not proven else "-"
        after = ("valid" if r["non_delaunay_faces_after"] == 0 and
                 r["reflex_boundary_edges_after"] == 0 and r["mesh_consistent_after"] else "NOT")
        print("| %d | %d | %s | %.3f | %.3f | %.1f%% | %s | %s | %s | %s | %s | %s | %s |"
              % (r["threads"], r["seed"], r["repair"], total, rep,
                 100.0 * rep / (total - rep) if total > rep else float("nan"),
                 "proven" if proven else faces,
                 "-" if proven else "%.3f" % r["seconds_scan"],
                 r["flips"] if r["repair"] == "flips-splay" and not proven else "-",
                 r["faces_left"] if r["repair"] == "flips-splay" and not proven else "-",
                 r["stars"], beyond, after))


if __name__ == "__main__":
    main()
