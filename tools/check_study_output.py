#!/usr/bin/python3
"""Checks the files of one `dtlab experiment NAME` run: their presence and their columns, not
their numbers (CI runs every study with --quick and this check).

Usage: tools/check_study_output.py DIR NAME
Exits 1 with a message for the first thing missing.
"""
import csv
import json
import os
import sys

# Columns every study's CSV has: the run, its options, the engine's stats, the validator, the audit.
COMMON = ["run_key", "study", "input", "source", "size_asked", "variant", "engine", "round",
          "status", "outcome", "error", "hardware_threads", "oversubscribed", "seconds_wall", "points",
          "inserted", "duplicates", "tetrahedra", "seconds.total", "seconds.location",
          "flips.S23", "flips.S44", "dag_nodes", "store_slots", "abandoned_insertions",
          "peak_rss_bytes", "bytes_per_point", "waits", "deadlocks", "give_ups", "burglaries",
          "potential_problems", "suspicious_tetrahedra", "post_check.non_delaunay_faces",
          "post_check.non_delaunay_after", "splay.stars", "splay.seconds", "method", "threads",
          "distribution", "predicates", "location", "bounding", "repair", "seed",
          "validation.valid", "validation.non_delaunay_faces", "audit.calls",
          "audit.wrong_sign", "audit.stage.A", "commit", "finished_utc",
          "options.max_flips_per_insertion", "options.stress", "options.validate",
          "options.audit"]

# Per study: columns that must hold a value in every finished row of the kind named.
FILLED = {
    "burglary-errors": ("method", "burglary", ["post_check.non_delaunay_faces",
                                               "post_check.reflex_boundary_edges",
                                               "post_check.non_delaunay_after", "splay.stars",
                                               "potential_problems", "suspicious_tetrahedra"]),
    "predicate-errors": ("variant", "fast", ["validation.valid", "validation.non_delaunay_faces",
                                             "seconds.total"]),
    "speedup": ("method", "optimistic-detect", ["seconds.total", "deadlocks", "give_ups"]),
    "breakdown": ("method", "sequential", ["seconds.location", "seconds.subdivision",
                                           "seconds.legalization", "seconds.other"]),
    "flips": ("method", "sequential", ["flips.S23", "flips.S32", "flips.S22", "flips.S44",
                                       "dag_nodes"]),
    "deadlocks": ("method", "optimistic-detect", ["deadlocks", "stale_cycles", "give_ups"]),
    "hull-loss": ("bounding", "aux-tet", ["hull_tetrahedra_lost",
                                          "validation.reflex_boundary_edges"]),
    "compare": ("engine", "cgal", ["seconds.total", "tetrahedra", "peak_rss_bytes"]),
    "peers": ("variant", "cgal-epick", ["outcome", "validation.valid", "seconds.total",
                                        "peer.version"]),
}
# Studies whose runs may end without a result (a peer that refuses, crashes or hangs is a finding):
# every row has an outcome instead, and FILLED applies to the finished rows.
OUTCOMES = {"peers": {"valid", "invalid", "refused", "crashed", "hung"}}
MACHINE = ["cpu_model", "hardware_threads", "cpus_available", "physical_cores", "memory_gib", "compiler", "build_type", "cxx_flags",
           "commit", "date_utc", "command"]


def fail(message):
    sys.exit("check_study_output: " + message)


def main():
    if len(sys.argv) != 3 or sys.argv[2] not in FILLED:
        fail("usage: check_study_output.py DIR {%s}" % ",".join(FILLED))
    directory, name = sys.argv[1:]
    for file in (name + ".csv", name + ".md", name + ".png", "machine.json"):
        if not os.path.isfile(os.path.join(directory, file)):
            fail("%s is missing in %s" % (file, directory))
    path = os.path.join(directory, name + ".csv")
    with open(path, newline="") as f:
        reader = csv.reader(f)
        header = next(reader)
        rows = list(reader)
    missing = [c for c in COMMON if c not in header]
    if missing:
        fail("%s lacks columns %s" % (path, missing))
    if not rows:
        fail(path + " has no run")
    keys = set()
    for i, row in enumerate(rows):
        if len(row) != len(header):
            fail("%s row %d has %d fields, the header %d" % (path, i + 1, len(row), len(header)))
        r = dict(zip(header, row))
        if r["study"] != name:
            fail("%s row %d belongs to study %s" % (path, i + 1, r["study"]))
        if name in OUTCOMES:
            if r["outcome"] not in OUTCOMES[name]:
                fail("%s: run %s has outcome %r" % (path, r["run_key"], r["outcome"]))
        elif r["status"] != "ok":
            fail("%s: run %s ended %s: %s" % (path, r["run_key"], r["status"], r["error"]))
        if r["run_key"] in keys:
            fail("%s: run %s twice" % (path, r["run_key"]))
        keys.add(r["run_key"])
    column, value, filled = FILLED[name]
    kind = [dict(zip(header, row)) for row in rows
            if dict(zip(header, row))[column] == value and dict(zip(header, row))["status"] == "ok"]
    if not kind:
        fail("%s has no run with %s = %s" % (path, column, value))
    for r in kind:
        empty = [c for c in filled if c not in r or r[c] == ""]
        if empty:
            fail("%s: run %s has no value in %s" % (path, r["run_key"], empty))

    md = open(os.path.join(directory, name + ".md")).read()
    if not md.startswith("## " + name + ":"):
        fail(name + ".md does not start with its heading")
    table_rows = [line for line in md.splitlines() if line.startswith("| ")]
    if len(table_rows) < 2:
        fail(name + ".md has no table with a row")
    with open(os.path.join(directory, name + ".png"), "rb") as f:
        png = f.read()
    if not png.startswith(b"\x89PNG\r\n\x1a\n") or len(png) < 2000:
        fail(name + ".png is not a plot")
    machine = json.load(open(os.path.join(directory, "machine.json")))
    absent = [k for k in MACHINE if k not in machine or machine[k] in ("", None)]
    if absent:
        fail("machine.json lacks " + ", ".join(absent))
    print("check_study_output: %s: %d runs, %d columns, table, plot and machine record"
          % (name, len(rows), len(header)))


if __name__ == "__main__":
    main()
