#!/usr/bin/env python3
"""dtlab.triangulate beside scipy.spatial.Delaunay on the same points, each run in a child
process of its own (peak memory is the child's ru_maxrss), rounds interleaved; every mesh judged
by dtlab's exact validator (either orientation accepted, for Qhull's). Prints a Markdown table
with the machine, the commit and the command.

Usage: PYTHONPATH=build/release/python python3 tools/python_vs_scipy.py
         [--inputs uniform:100000,uniform:1000000,grid:1000000] [--rounds 3] [--out table.md]
"""
import argparse
import json
import os
import platform
import statistics
import subprocess
import sys

CHILD = r"""
import json, resource, sys, time
import numpy as np
import dtlab
family, n = sys.argv[2].split(":")
points = dtlab.generate(family, int(n), seed=1)
tool = sys.argv[1]
start = time.perf_counter()
if tool == "scipy":
    from scipy.spatial import Delaunay
    simplices = Delaunay(points).simplices
else:
    simplices = dtlab.triangulate(points, **json.loads(tool)).simplices
seconds = time.perf_counter() - start
peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024
report = dtlab.validate(points, simplices, oriented=False) if sys.argv[3] == "1" else {}
print(json.dumps({"seconds": seconds, "peak": peak, "tetrahedra": len(simplices),
                  "valid": report.get("valid"), "flat": report.get("non_positive_orientation"),
                  "non_delaunay": report.get("non_delaunay_faces"),
                  "inconsistent": report.get("inconsistent_faces")}))
"""

TOOLS = {"dtlab": "{}", "dtlab, 2 threads": '{"method": "optimistic-detect", "threads": 2}',
         "scipy": "scipy"}


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--inputs", default="uniform:100000,uniform:1000000,grid:100000")
    parser.add_argument("--timeout", type=float, default=600,
                        help="seconds a run may take (scipy on grid:1000000 took over 390 s)")
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--out")
    args = parser.parse_args()
    results = {}
    for r in range(args.rounds):
        for spec in args.inputs.split(","):
            for name, tool in TOOLS.items():
                if results.get((spec, name), {}).get("timed_out"):
                    continue
                try:
                    run = subprocess.run([sys.executable, "-c", CHILD, tool, spec,
                                          "1" if r == 0 else "0"],
                                         capture_output=True, text=True, timeout=args.timeout)
                except subprocess.TimeoutExpired:
                    results[(spec, name)] = {"timed_out": True}
                    continue
                if run.returncode != 0:
                    sys.exit(f"{name} on {spec}: {run.stderr}")
                one = json.loads(run.stdout)
                entry = results.setdefault((spec, name), {"seconds": [], "peak": []})
                entry["seconds"].append(one["seconds"])
                entry["peak"].append(one["peak"])
                if r == 0:
                    entry.update({k: one[k] for k in ("tetrahedra", "valid", "flat", "non_delaunay",
                                                      "inconsistent")})
        print(f"round {r + 1} of {args.rounds} done", file=sys.stderr)
    import dtlab
    cpu = next((line.split(":", 1)[1].strip() for line in open("/proc/cpuinfo")
                if line.startswith("model name")), platform.processor())
    lines = [f"Machine: {cpu}, {os.cpu_count()} hardware threads, {platform.node()}; dtlab "
             f"{dtlab.__version__}; scipy {__import__('scipy').__version__}; {args.rounds} "
             f"rounds interleaved, medians; seed 1.",
             f"Command: `PYTHONPATH=build/release/python python3 tools/python_vs_scipy.py "
             f"--inputs {args.inputs} --rounds {args.rounds} --timeout {args.timeout:.0f}`", "",
             "| input | tool | time (s) | peak memory (MiB) | tetrahedra | exact validator |",
             "|---|---|---:|---:|---:|---|"]
    for (spec, name), e in results.items():
        if e.get("timed_out"):
            lines.append(f"| {spec} | {name} | > {args.timeout:.0f} (stopped) | | | |")
            continue
        verdict = "valid" if e["valid"] else (
            f"invalid: {e['flat']} flat, {e['inconsistent']} inconsistent faces, "
            f"{e['non_delaunay']} non-Delaunay faces")
        lines.append(f"| {spec} | {name} | {statistics.median(e['seconds']):.2f} | "
                     f"{statistics.median(e['peak']) / 2**20:.0f} | {e['tetrahedra']:,} | {verdict} |")
    text = "\n".join(lines) + "\n"
    print(text)
    if args.out:
        with open(args.out, "w") as f:
            f.write(text)


if __name__ == "__main__":
    main()
