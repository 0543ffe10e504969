#!/usr/bin/env python3
"""Old and new dtlab binaries timed side by side, alternating, on one machine: each configuration
runs `--rounds` times per binary (the order of the two flips every round), and the table gives
the median of the engine's own time (`seconds.total` of --stats) and of the peak memory per
point, and the ratio new / old. Nothing else should run meanwhile.

Usage: tools/compare_speed.py OLD-DTLAB NEW-DTLAB [--rounds 5] [--out table.md] [--steps]
         [--config "uniform:1000000 --location walk" ...]

--steps adds a second table: the medians of the steps before the first insertion and after the
last (`seconds.ordering`, `seconds.output`) and of the inserting threads' own time summed
(`seconds.location + subdivision + legalization`), old and new, for changes to those steps.
"""
import argparse
import json
import os
import platform
import statistics
import subprocess
import sys

DEFAULT_CONFIGS = [
    "uniform:1000000 --location walk",
    "uniform:1000000 --location walk --insertion cavity",
    "uniform:1000000 --location walk --method optimistic-detect --threads 2",
    "uniform:1000000 --location walk --insertion cavity --method optimistic-detect --threads 2",
    "uniform:200000 --location dag",
    "uniform:200000 --location dag --method optimistic-detect --threads 2",
]


STEPS = ("ordering", "output", "thread_seconds")


def run(binary, config, seed):
    cmd = [binary, "triangulate"] + config.split() + ["--seed", str(seed), "--stats", "-"]
    out = subprocess.run(cmd, capture_output=True, text=True, check=True).stdout
    stats = json.loads(out)
    s = stats["seconds"]
    # Binaries older than the steps' stats have none: their cells say so.
    steps = {"ordering": s.get("ordering"), "output": s.get("output"),
             "thread_seconds": s["location"] + s["subdivision"] + s["legalization"]}
    return s["total"], stats["bytes_per_point"], stats["tetrahedra"], steps


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("old")
    parser.add_argument("new")
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--out")
    parser.add_argument("--config", action="append")
    parser.add_argument("--steps", action="store_true")
    args = parser.parse_args()
    configs = args.config or DEFAULT_CONFIGS
    times = {c: {"old": [], "new": []} for c in configs}
    memory = {c: {"old": [], "new": []} for c in configs}
    steps = {c: {"old": [], "new": []} for c in configs}
    for r in range(args.rounds):
        for c in configs:
            order = ["old", "new"] if r % 2 == 0 else ["new", "old"]
            counts = set()
            for which in order:
                seconds, bpp, tets, step_seconds = run(getattr(args, which), c, args.seed)
                times[c][which].append(seconds)
                steps[c][which].append(step_seconds)
                memory[c][which].append(bpp)
                counts.add(tets)
            if len(counts) != 1:
                sys.exit(f"{c}: the binaries gave different tetrahedron counts {counts}")
        print(f"round {r + 1} of {args.rounds} done", file=sys.stderr)
    lines = [f"Machine: {platform.node()}, {os.cpu_count()} hardware threads; {args.rounds} "
             f"rounds, seed {args.seed}, binaries alternating; medians of seconds.total.", "",
             "| configuration | old s | new s | new / old | old B/pt | new B/pt | old runs | new runs |",
             "|---|---:|---:|---:|---:|---:|---|---|"]
    worst = 0.0
    for c in configs:
        old = statistics.median(times[c]["old"])
        new = statistics.median(times[c]["new"])
        worst = max(worst, new / old)
        lines.append(
            f"| `{c}` | {old:.3f} | {new:.3f} | {new / old:.3f} | "
            f"{statistics.median(memory[c]['old']):.0f} | {statistics.median(memory[c]['new']):.0f} | "
            + ", ".join(f"{t:.2f}" for t in times[c]["old"]) + " | "
            + ", ".join(f"{t:.2f}" for t in times[c]["new"]) + " |")
    lines.append("")
    lines.append(f"Largest new / old: {worst:.3f}")
    if args.steps:
        lines += ["", "Medians of the steps (s): ordering and output (before the first insertion, "
                  "after the last), and the inserting threads' location + subdivision + "
                  "legalization summed.", "",
                  "| configuration | " + " | ".join(f"old {k} | new {k}" for k in STEPS) + " |",
                  "|---|" + "---:|" * (2 * len(STEPS))]
        for c in configs:
            cells = []
            for k in STEPS:
                for which in ("old", "new"):
                    values = [x[k] for x in steps[c][which] if x[k] is not None]
                    cells.append(f"{statistics.median(values):.3f}" if values else "n/a")
            lines.append(f"| `{c}` | " + " | ".join(cells) + " |")
    text = "\n".join(lines) + "\n"
    print(text)
    if args.out:
        with open(args.out, "w") as f:
            f.write(text)


if __name__ == "__main__":
    main()
