#!/usr/bin/python3
"""Time per phase (the paper's Fig. 4 split) against input size, sequential engine, adaptive kernel.

Usage: tools/phase_scaling.py [--dtlab PATH] [--family uniform] [--sizes 10000,30000,...]
                              [--seed 1] [--out docs/img/phases.png]
Prints a Markdown table and writes a stacked bar plot (needs python3-matplotlib).
"""
import argparse
import json
import os
import platform
import subprocess

parser = argparse.ArgumentParser()
parser.add_argument("--dtlab", default="build/release/cli/dtlab")
parser.add_argument("--family", default="uniform")
parser.add_argument("--sizes", default="10000,30000,100000,300000,1000000")
parser.add_argument("--seed", default="1")
parser.add_argument("--out", default="docs/img/phases.png")
args = parser.parse_args()

rows = []
for n in [int(s) for s in args.sizes.split(",")]:
    out = subprocess.run([args.dtlab, "triangulate", f"{args.family}:{n}", "--seed", args.seed, "--stats", "-"],
                         check=True, capture_output=True, text=True).stdout
    d = json.loads(out)
    rows.append((n, d))

print(f"{args.family}, seed {args.seed}, adaptive kernel, sequential, DAG location; "
      f"{os.cpu_count()} cores, {platform.machine()}")
print("| points | total s | location | subdivision | legalization | other | us/point | flips/point | DAG nodes/point | DAG steps/point | peak RSS MiB |")
print("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
for n, d in rows:
    s = d["seconds"]
    flips = sum(d["flips"].values())
    pct = lambda k: f"{100 * s[k] / s['total']:.0f}%"
    print(f"| {n} | {s['total']:.2f} | {pct('location')} | {pct('subdivision')} | {pct('legalization')} | {pct('other')} "
          f"| {1e6 * s['total'] / n:.1f} | {flips / n:.1f} | {d['dag_nodes'] / n:.1f} | {d['location_steps'] / n:.1f} "
          f"| {d['peak_rss_bytes'] / 2**20:.0f} |")

try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    print("(matplotlib missing: no plot)")
    raise SystemExit(0)

labels = [f"{n // 1000}k" for n, _ in rows]
bottom = [0.0] * len(rows)
fig, ax = plt.subplots(figsize=(7, 4))
for phase, colour in [("location", "#4c72b0"), ("subdivision", "#55a868"), ("legalization", "#c44e52"), ("other", "#8172b2")]:
    per_point = [1e6 * d["seconds"][phase] / n for n, d in rows]
    ax.bar(labels, per_point, bottom=bottom, label=phase, color=colour)
    bottom = [b + v for b, v in zip(bottom, per_point)]
ax.set_xlabel(f"{args.family} points")
ax.set_ylabel("microseconds per point")
ax.set_title(f"dtlab sequential, adaptive kernel, DAG location (seed {args.seed})")
ax.legend()
fig.tight_layout()
os.makedirs(os.path.dirname(args.out), exist_ok=True)
fig.savefig(args.out, dpi=110)
print(f"plot: {args.out}")
