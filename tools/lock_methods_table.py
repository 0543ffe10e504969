#!/usr/bin/python3
"""Speedup of every lock method over the sequential engine, measured side by side.

Runs ROUNDS rounds; each round runs the sequential engine (1 thread) and every method at THREADS
threads on INPUT, in that order, and takes seconds.total from `--stats -` (input reading excluded).
Speedup is per round (sequential time of the same round / method time), the table quotes the
median. Writes a Markdown table on stdout and the raw JSON objects to --raw.

Usage: tools/lock_methods_table.py INPUT THREADS ROUNDS [--dtlab PATH] [--raw FILE]
       [--methods m1,m2,...] [--seed S]
"""
import argparse
import json
import os
import platform
import statistics
import subprocess
import sys

METHODS = ["pessimistic", "optimistic-detect", "optimistic-prevent", "burglary", "batch"]


def run(dtlab, input_spec, method, threads, seed):
    cmd = [dtlab, "triangulate", input_spec, "--method", method, "--threads", str(threads),
           "--seed", str(seed), "--stats", "-"]
    out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    return json.loads(out)


def per_thousand(count, inserted):
    return 1000.0 * count / inserted if inserted else 0.0


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("input")
    parser.add_argument("threads", type=int)
    parser.add_argument("rounds", type=int)
    parser.add_argument("--dtlab", default="build/release/cli/dtlab")
    parser.add_argument("--raw", default="")
    parser.add_argument("--methods", default=",".join(METHODS))
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()
    methods = args.methods.split(",")

    runs = {m: [] for m in ["sequential"] + methods}
    for r in range(args.rounds):
        print("round %d/%d" % (r + 1, args.rounds), file=sys.stderr)
        runs["sequential"].append(run(args.dtlab, args.input, "sequential", 1, args.seed))
        for m in methods:
            runs[m].append(run(args.dtlab, args.input, m, args.threads, args.seed))
    if args.raw:
        with open(args.raw, "w") as f:
            json.dump(runs, f, indent=1)

    seq = [d["seconds"]["total"] for d in runs["sequential"]]
    print("`tools/lock_methods_table.py %s %d %d` on %s, %d logical CPUs, seed %d, adaptive "
          "kernel, static distribution (batch: %d locating + 1 inserting thread)\n"
          % (args.input, args.threads, args.rounds, platform.node() or "this machine",
             os.cpu_count(), args.seed, max(1, args.threads - 1)))
    print("| method | seconds per round | median speedup (per-round speedups) | deadlocks / "
          "give-ups / burglaries per 1000 insertions (median) | non-Delaunay faces after the run "
          "(burglary) |")
    print("|---|---|---|---|---|")
    print("| sequential (1 thread) | %s | - | - | - |" % " / ".join("%.2f" % s for s in seq))
    for m in methods:
        times = [d["seconds"]["total"] for d in runs[m]]
        speedups = [s / t for s, t in zip(seq, times)]
        inserted = [d["inserted"] for d in runs[m]]
        dl = statistics.median(per_thousand(d.get("deadlocks", 0), i)
                               for d, i in zip(runs[m], inserted))
        gu = statistics.median(per_thousand(d.get("give_ups", 0), i)
                               for d, i in zip(runs[m], inserted))
        bu = statistics.median(per_thousand(d.get("burglaries", 0), i)
                               for d, i in zip(runs[m], inserted))
        bad = "-"
        if m == "burglary":
            bad = " / ".join("%d + %d reflex" % (d["post_check"]["non_delaunay_faces"],
                                                 d["post_check"]["reflex_boundary_edges"])
                             for d in runs[m])
        print("| %s | %s | %.2f (%s) | %.3f / %.3f / %.3f | %s |"
              % (m, " / ".join("%.2f" % t for t in times), statistics.median(speedups),
                 " / ".join("%.2f" % s for s in speedups), dl, gu, bu, bad))


if __name__ == "__main__":
    main()
