#!/usr/bin/python3
"""What the burglary method breaks, and what the paper's post-check repairs.

For each family and thread count, runs `dtlab triangulate FAMILY:N --method burglary --threads T
--repair --seed S --stats -` for every seed and reports medians over the seeds: burglaries,
potential problems and suspicious tetrahedra per 1000 insertions; non-Delaunay faces and reflex
boundary edges right after the run; what the flips on the marked tetrahedra left; how many runs
needed the fallbacks (sweep over every tetrahedron, sequential rebuild). Writes a Markdown table
on stdout and, with --plot, a PNG of non-Delaunay faces per 1000 points.

Usage: tools/burglary_errors.py N SEEDS [--families a,b] [--threads 2,4,8] [--plot FILE]
       [--dtlab PATH] [--stress]
       tools/burglary_errors.py --plot-from TABLE.md --plot FILE   (plot a table written before)
"""
import argparse
import json
import os
import statistics
import subprocess


def run(dtlab, spec, threads, seed, stress):
    cmd = [dtlab, "triangulate", spec, "--method", "burglary", "--threads", str(threads),
           "--repair=rebuild", "--seed", str(seed), "--stats", "-"]
    if stress:
        cmd.append("--stress")
    return json.loads(subprocess.run(cmd, check=True, capture_output=True, text=True).stdout)


def plot(rows, families, thread_counts, path, title):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7, 3.6))
    width = 0.8 / len(thread_counts)
    for k, threads in enumerate(thread_counts):
        xs = [i + k * width for i in range(len(families))]
        ax.bar(xs, [rows[f][threads] for f in families], width, label="%d threads" % threads)
    ax.set_xticks([i + width * (len(thread_counts) - 1) / 2 for i in range(len(families))])
    ax.set_xticklabels(families)
    ax.set_ylabel("non-Delaunay faces per 1000 points")
    ax.set_title(title)
    ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def plot_table(table_path, path):
    """Plots the non-Delaunay column of a table this script wrote (its first line names N)."""
    lines = open(table_path).read().splitlines()
    n = int(lines[0].split("`")[1].split()[1])
    rows, families, thread_counts = {}, [], []
    for line in lines:
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) < 6 or not cells[1].isdigit():
            continue
        family, threads, bad = cells[0], int(cells[1]), float(cells[5])
        if family not in families:
            families.append(family)
        if threads not in thread_counts:
            thread_counts.append(threads)
        rows.setdefault(family, {})[threads] = 1000.0 * bad / n
    plot(rows, families, thread_counts, path,
         "burglary, %d points (%s)" % (n, os.path.basename(table_path)))


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("n", type=int, nargs="?", default=0)
    parser.add_argument("seeds", type=int, nargs="?", default=0)
    parser.add_argument("--plot-from", default="")
    parser.add_argument("--families", default="uniform,normal,cluster,grid,sphere")
    parser.add_argument("--threads", default="2,4,8")
    parser.add_argument("--plot", default="")
    parser.add_argument("--dtlab", default="build/release/cli/dtlab")
    parser.add_argument("--stress", action="store_true")
    args = parser.parse_args()
    families = args.families.split(",")
    thread_counts = [int(t) for t in args.threads.split(",")]
    if args.plot_from:
        plot_table(args.plot_from, args.plot)
        return

    print("`tools/burglary_errors.py %d %d --families %s --threads %s%s` on %d logical CPUs "
          "(more threads than CPUs are oversubscribed), adaptive kernel, static distribution, "
          "seeds 1..%d; medians over the seeds\n"
          % (args.n, args.seeds, args.families, args.threads, " --stress" if args.stress else "",
             os.cpu_count(), args.seeds))
    print("| family | threads | burglaries / 1000 ins. | potential problems / 1000 | suspicious "
          "tets / 1000 | non-Delaunay faces after the run | reflex boundary edges | left after "
          "flips on the marks | runs needing sweep / rebuild | mesh consistent (all runs) |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---|---|")
    plot_rows = {}
    for family in families:
        for threads in thread_counts:
            rows = [run(args.dtlab, "%s:%d" % (family, args.n), threads, seed, args.stress)
                    for seed in range(1, args.seeds + 1)]

            def med(f):
                return statistics.median(f(r) for r in rows)

            def per_k(key):
                return med(lambda r: 1000.0 * r[key] / r["inserted"])

            pc = [r["post_check"] for r in rows]
            sweeps = sum(1 for c in pc if c["non_delaunay_after_marked"] > 0)
            rebuilds = sum(1 for c in pc if c["rebuilt"])
            bad = med(lambda r: r["post_check"]["non_delaunay_faces"])
            plot_rows.setdefault(family, {})[threads] = 1000.0 * bad / args.n
            print("| %s | %d | %.2f | %.2f | %.2f | %g | %g | %g | %d / %d of %d | %s |"
                  % (family, threads, per_k("burglaries"), per_k("potential_problems"),
                     per_k("suspicious_tetrahedra"), bad,
                     med(lambda r: r["post_check"]["reflex_boundary_edges"]),
                     med(lambda r: r["post_check"]["non_delaunay_after_marked"]),
                     sweeps, rebuilds, len(rows),
                     "yes" if all(c["mesh_consistent"] for c in pc) else "NO"))
            if any(c["non_delaunay_after"] != 0 for c in pc):
                raise SystemExit("a --repair=rebuild run did not end Delaunay")
    if args.plot:
        plot(plot_rows, families, thread_counts, args.plot,
             "burglary, %d points, median of %d seeds, %d CPUs"
             % (args.n, args.seeds, os.cpu_count()))

if __name__ == "__main__":
    main()
