#!/usr/bin/python3
"""What star splaying (`--repair`) costs, against what it repairs.

Two tables on stdout (Markdown) and, with --plot, a PNG of repair seconds against the
non-Delaunay faces the repair found (every run of both tables):

1. "fast, then repair" beside "adaptive throughout", sequential, per family: for each seed,
   `dtlab triangulate FAMILY:N --predicates fast --repair --validate` and
   `dtlab triangulate FAMILY:N --validate` (adaptive), alternating, medians over the seeds of the
   whole triangulation time (seconds.total, repair included) and of the repair alone; what the
   repair found (non-Delaunay faces, bad tetrahedra, missing vertices) and the stars it built;
   whether every repaired mesh validated.
2. burglary at each thread count: the run's time, the repair's time and share, non-Delaunay faces
   found, stars, validity; beside it the paper's flips with their reported rebuild
   (`--repair=rebuild`) on the same seed.
3. burglary again with `--repair=flips-splay` (exact Lawson flips from the damaged faces first,
   star splaying from the faces they leave), beside plain star splaying: each run's own damage
   (burglary's differs from run to run), so the table gives the cost per face found too.

Usage: tools/repair_costs.py N SEEDS [--families a,b] [--threads 2,4,8] [--location dag|walk]
       [--plot FILE] [--dtlab PATH]
"""
import argparse
import json
import os
import platform
import statistics
import subprocess


def run(dtlab, location, args):
    out = subprocess.run([dtlab, "triangulate"] + args + ["--location", location, "--validate",
                                                          "--stats", "-"],
                         check=True, capture_output=True, text=True).stdout
    return json.loads(out)


def med(values):
    return statistics.median(values) if values else float("nan")


def cpu_model():
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown CPU"


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("n", type=int)
    parser.add_argument("seeds", type=int)
    parser.add_argument("--families", default="uniform,normal,cluster,grid,sphere,cospherical,"
                        "near-duplicates,duplicates,planes")
    parser.add_argument("--threads", default="2,4,8")
    parser.add_argument("--location", default="dag", choices=["dag", "walk"])
    parser.add_argument("--plot", default="")
    parser.add_argument("--dtlab", default="build/release/cli/dtlab")
    args = parser.parse_args()
    families = args.families.split(",")
    thread_counts = [int(t) for t in args.threads.split(",")]
    points = []  # (non-Delaunay faces found, repair seconds, label) for the plot
    hybrid_rows = []  # (family, threads, splay runs, flips-splay runs) for table 3

    print("`tools/repair_costs.py %d %d --families %s --threads %s --location %s` on %s, %d "
          "logical CPUs (thread counts above that are oversubscribed); medians over seeds 1..%d\n"
          % (args.n, args.seeds, args.families, args.threads, args.location, cpu_model(),
             os.cpu_count(), args.seeds))
    print("### Fast kernel, then star splaying, against adaptive predicates throughout "
          "(sequential)\n")
    print("| family | adaptive s | fast + repair s | ratio | repair s | non-Delaunay faces found "
          "| bad tetrahedra | missing vertices | stars splayed | valid (all seeds) |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---|")
    for family in families:
        spec = "%s:%d" % (family, args.n)
        adaptive, fast = [], []
        for seed in range(1, args.seeds + 1):
            fast.append(run(args.dtlab, args.location,
                            [spec, "--seed", str(seed), "--predicates", "fast", "--repair"]))
            adaptive.append(run(args.dtlab, args.location, [spec, "--seed", str(seed)]))
        for r in fast:
            points.append((r["splay"]["non_delaunay_faces"], r["splay"]["seconds"], "fast"))
        a = med([r["seconds"]["total"] for r in adaptive])
        f = med([r["seconds"]["total"] for r in fast])
        print("| %s | %.3f | %.3f | %.2f | %.4f | %g | %g | %g | %g | %s |"
              % (family, a, f, f / a if a > 0 else float("nan"),
                 med([r["splay"]["seconds"] for r in fast]),
                 med([r["splay"]["non_delaunay_faces"] for r in fast]),
                 med([r["splay"]["bad_tetrahedra"] for r in fast]),
                 med([r["splay"]["missing_vertices"] for r in fast]),
                 med([r["splay"]["stars"] for r in fast]),
                 "yes" if all(r["validation"]["valid"] for r in fast) else "NO"))

    print("\n### Burglary, then star splaying (`--repair`), beside the paper's flips with their "
          "reported rebuild (`--repair=rebuild`)\n")
    print("| family | threads | run s (with repair) | repair s | repair share | non-Delaunay faces "
          "found | stars splayed | proven by the post-check | post-check s | valid (all seeds) "
          "| flips: runs rebuilt | flips + rebuild s |")
    print("|---|---:|---:|---:|---:|---:|---:|---|---:|---|---|---:|")
    for family in families:
        spec = "%s:%d" % (family, args.n)
        for threads in thread_counts:
            splay, flips, hybrid = [], [], []
            for seed in range(1, args.seeds + 1):
                common = [spec, "--seed", str(seed), "--method", "burglary", "--threads",
                          str(threads)]
                splay.append(run(args.dtlab, args.location, common + ["--repair"]))
                flips.append(run(args.dtlab, args.location, common + ["--repair=rebuild"]))
                hybrid.append(run(args.dtlab, args.location, common + ["--repair=flips-splay"]))
            hybrid_rows.append((family, threads, splay, hybrid))
            for r in splay:
                points.append((r["splay"]["non_delaunay_faces"], r["splay"]["seconds"],
                               "burglary %d" % threads))
            for r in hybrid:
                points.append((r["splay"]["non_delaunay_faces"], r["splay"]["seconds"],
                               "burglary %d, flips first" % threads))
            total = med([r["seconds"]["total"] for r in splay])
            rep = med([r["splay"]["seconds"] for r in splay])
            print("| %s | %d%s | %.3f | %.4f | %.1f%% | %g | %g | %d of %d | %.3f | %s | %d of %d "
                  "| %.3f |"
                  % (family, threads, " (oversubscribed)" if threads > os.cpu_count() else "",
                     total, rep, 100.0 * rep / total if total > 0 else float("nan"),
                     med([r["splay"]["non_delaunay_faces"] for r in splay]),
                     med([r["splay"]["stars"] for r in splay]),
                     sum(1 for r in splay if r["splay"].get("proven_by_post_check")), len(splay),
                     med([r["post_check"]["seconds_check"] for r in splay]),
                     "yes" if all(r["validation"]["valid"] for r in splay) else "NO",
                     sum(1 for r in flips if r["post_check"]["rebuilt"]), len(flips),
                     med([r["seconds"]["total"] for r in flips])))

    print("\n### Burglary with `--repair=flips-splay` (exact flips first), beside `--repair` (star "
          "splaying alone)\n")
    print("| family | threads | splay: repair s | faces | ms a face | flips-splay: repair s | "
          "faces | ms a face | flips | faces left | stars | repair share | valid (all seeds) |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|")

    def per_face(runs):
        costs = [1000.0 * r["splay"]["seconds"] / r["splay"]["non_delaunay_faces"]
                 for r in runs if r["splay"]["non_delaunay_faces"] > 0]
        return "%.3f" % med(costs) if costs else "-"

    for family, threads, splay, hybrid in hybrid_rows:
        total = med([r["seconds"]["total"] for r in hybrid])
        rep = med([r["splay"]["seconds"] for r in hybrid])
        print("| %s | %d%s | %.4f | %g | %s | %.4f | %g | %s | %g | %g | %g | %.1f%% | %s |"
              % (family, threads, " (oversubscribed)" if threads > os.cpu_count() else "",
                 med([r["splay"]["seconds"] for r in splay]),
                 med([r["splay"]["non_delaunay_faces"] for r in splay]), per_face(splay),
                 rep, med([r["splay"]["non_delaunay_faces"] for r in hybrid]), per_face(hybrid),
                 med([r["splay"].get("flips", 0) for r in hybrid]),
                 med([r["splay"].get("faces_left", 0) for r in hybrid]),
                 med([r["splay"]["stars"] for r in hybrid]),
                 100.0 * rep / total if total > 0 else float("nan"),
                 "yes" if all(r["validation"]["valid"] for r in hybrid) else "NO"))

    if args.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(6.5, 4))
        for label in sorted({p[2] for p in points}):
            xs = [p[0] for p in points if p[2] == label and p[0] > 0]
            ys = [p[1] for p in points if p[2] == label and p[0] > 0]
            ax.scatter(xs, ys, s=14, label=label, marker="x" if "flips first" in label else "o")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("non-Delaunay faces found")
        ax.set_ylabel("repair seconds")
        ax.set_title("repair cost, %d points, %s mode, %s" % (args.n, args.location,
                                                             cpu_model()[:40]), fontsize=9)
        ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(args.plot, dpi=110)


if __name__ == "__main__":
    main()
