#!/usr/bin/env python3
"""Where a partitioned run's time goes, beside the sequential walk's on the same points: both
run alternately (`--rounds` times each, each run its own process), and the table gives the
medians of each step's seconds, from the runs' own stats (`--stats`), against the sequential
walk's divided by the threads: what a run with no overhead would take; then the speedup of each
round (the sequential walk's total over the partitioned run's, the two run one after the other).
Nothing else should run meanwhile.

Steps: before the first insertion (`seconds.ordering`); the rounds' passes of one part
(`partition_passes`, one part, not after the rounds: the first, small rounds); the setups of the
rounds' passes of several parts (their `setup_seconds`: cut, sort along the pass curve, walk starts); the rest
of those passes during the rounds (their inserting threads); every pass after the rounds; after
the last insertion (`seconds.output`: the output, the points put back, the input's ids); what is
left of `seconds.total`. The sequential walk's insertions are its total less its ordering and
output; its "ideal" row for the insertions is set beside the sum of the partitioned run's four
insertion rows. Each row is a median of its own, so the rows need not add up to the total's
median exactly.

Usage: tools/time_budget.py DTLAB [--input uniform:1000000] [--threads 2] [--insertion cavity]
         [--rounds 5] [--seed 1]
"""
import argparse
import json
import os
import platform
import statistics
import subprocess


def run(binary, args):
    out = subprocess.run([binary, "triangulate"] + args + ["--stats", "-"], capture_output=True,
                         text=True, check=True).stdout
    return json.loads(out)


def partitioned_steps(stats):
    s = stats["seconds"]
    passes = stats["partition_passes"]
    steps = {
        "ordering": s["ordering"],
        "the rounds' passes of one part":
            sum(p["seconds"] for p in passes if p["parts"] == 1 and not p["after_rounds"]),
        "setups of the passes of several parts":
            sum(p["setup_seconds"] for p in passes if p["parts"] > 1 and not p["after_rounds"]),
        "insertions in the rounds' passes of several parts":
            sum(p["seconds"] - p["setup_seconds"] for p in passes
                if p["parts"] > 1 and not p["after_rounds"]),
        "passes after the rounds": sum(p["seconds"] for p in passes if p["after_rounds"]),
        "output": s["output"],
    }
    steps["rest"] = s["total"] - sum(steps.values())
    steps["total"] = s["total"]
    return steps


def sequential_steps(stats):
    s = stats["seconds"]
    return {"ordering": s["ordering"], "insertions": s["total"] - s["ordering"] - s["output"],
            "output": s["output"], "total": s["total"]}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("dtlab")
    parser.add_argument("--input", default="uniform:1000000")
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--insertion", default="cavity", choices=["cavity", "flips"])
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--seed", type=int, default=1)
    a = parser.parse_args()
    common = [a.input, "--location", "walk", "--insertion", a.insertion, "--seed", str(a.seed)]
    seq_args = common + ["--method", "sequential"]
    par_args = common + ["--method", "partitioned", "--threads", str(a.threads)]
    seq_runs, par_runs = [], []
    for r in range(a.rounds):
        pair = [(seq_args, seq_runs, sequential_steps), (par_args, par_runs, partitioned_steps)]
        for args, runs, steps in (pair if r % 2 == 0 else pair[::-1]):
            runs.append(steps(run(a.dtlab, args)))

    def median(runs, key):
        return statistics.median(r[key] for r in runs)

    seq = {k: median(seq_runs, k) for k in seq_runs[0]}
    par = {k: median(par_runs, k) for k in par_runs[0]}
    t = a.threads
    print(f"{a.input}, {a.insertion}, seed {a.seed}, partitioned at {t} threads against the "
          f"sequential walk; medians of {a.rounds} alternating runs each; "
          f"{platform.node()}, {os.cpu_count()} cores")
    print()
    print("| step | partitioned (s) | sequential / threads (s) | over (ms) |")
    print("|---|---:|---:|---:|")
    insert_rows = ["the rounds' passes of one part",
                   "setups of the passes of several parts",
                   "insertions in the rounds' passes of several parts", "passes after the rounds"]
    print(f"| ordering | {par['ordering']:.3f} | {seq['ordering'] / t:.3f} | "
          f"{1e3 * (par['ordering'] - seq['ordering'] / t):.0f} |")
    for k in insert_rows:
        print(f"| {k} | {par[k]:.3f} | | |")
    inserting = sum(par[k] for k in insert_rows)
    print(f"| all insertions (the four rows above) | {inserting:.3f} | {seq['insertions'] / t:.3f} | "
          f"{1e3 * (inserting - seq['insertions'] / t):.0f} |")
    print(f"| output | {par['output']:.3f} | {seq['output'] / t:.3f} | "
          f"{1e3 * (par['output'] - seq['output'] / t):.0f} |")
    print(f"| rest | {par['rest']:.3f} | | |")
    print(f"| **total** | **{par['total']:.3f}** | **{seq['total'] / t:.3f}** | "
          f"**{1e3 * (par['total'] - seq['total'] / t):.0f}** |")
    print()
    print(f"sequential walk {seq['total']:.3f} s; speedup {seq['total'] / par['total']:.3f}x "
          f"(ratio of the medians); each row a median of its own")
    # Each round's two runs ran one after the other: their ratio, round by round.
    paired = [one["total"] / two["total"] for one, two in zip(seq_runs, par_runs)]
    print(f"speedup per round: {', '.join(f'{x:.3f}' for x in paired)}; "
          f"median {statistics.median(paired):.3f}")


if __name__ == "__main__":
    main()
