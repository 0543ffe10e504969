#!/usr/bin/python3
"""Plots one study of `dtlab experiment` from its CSV (the command calls this script).

Usage: tools/plot_study.py NAME STUDY.csv OUT.png
Each study has one figure; thread counts above the CPUs available to the run are shaded and
marked "oversubscribed".
"""
import csv
import statistics
import sys
from collections import OrderedDict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def num(row, key):
    try:
        return float(row[key])
    except (KeyError, ValueError):
        return float("nan")


def ok_rows(path):
    with open(path, newline="") as f:
        return [r for r in csv.DictReader(f) if r["status"] == "ok"]


def all_rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def grouped(rows, keys):
    groups = OrderedDict()
    for r in rows:
        groups.setdefault(tuple(r[k] for k in keys), []).append(r)
    return groups


def median(rows, key):
    values = [num(r, key) for r in rows]
    values = [v for v in values if v == v]
    return statistics.median(values) if values else float("nan")


def mean(rows, key):
    values = [num(r, key) for r in rows]
    values = [v for v in values if v == v]
    return statistics.mean(values) if values else float("nan")


def label(input_name, size, points):
    return "%s %d" % (input_name, points) if size == "0" else "%s:%s" % (input_name, size)


def mark_oversubscribed(ax, rows):
    cores = int(rows[0]["hardware_threads"]) if rows else 0
    threads = sorted({int(r["threads"]) for r in rows})
    ax.set_xticks(threads)
    if cores and threads and threads[-1] > cores:
        ax.axvspan(cores + 0.5, threads[-1] + 0.5, color="0.9", zorder=0)
        low, high = ax.get_ylim()
        ax.text(cores + 0.6, low + 0.02 * (high - low), "oversubscribed (> %d CPUs)" % cores,
                fontsize=7, va="bottom")


def burglary_errors(rows, ax):
    fig = ax.figure
    ax.remove()
    left, right = fig.subplots(1, 2)
    rows = [r for r in rows if r["method"] == "burglary"]
    for (inp, size, loc), g in grouped(rows, ["input", "size_asked", "location"]).items():
        pts = median(g, "points")
        by_t = grouped(g, ["threads"])
        xs = sorted(int(t[0]) for t in by_t)
        ys = [1000.0 * mean(by_t[(str(x),)], "post_check.non_delaunay_faces") / pts for x in xs]
        name = label(inp, size, pts) + ("" if loc == "dag" else " " + loc)
        line, = left.plot(xs, ys, marker="o", label=name)
        right.plot([num(r, "splay.non_delaunay_faces") for r in g],
                   [num(r, "splay.seconds") for r in g], "o", markersize=3,
                   color=line.get_color(), label=name)
    left.set_xlabel("threads")
    left.set_ylabel("non-Delaunay faces per 1000 points (mean)")
    left.set_title("left by burglary (0 after star splaying)", fontsize=9)
    mark_oversubscribed(left, rows)
    right.set_xscale("symlog")
    right.set_yscale("log")
    right.set_xlabel("non-Delaunay faces found")
    right.set_ylabel("star splaying seconds")
    right.set_title("the repair's cost, every run", fontsize=9)


def predicate_errors(rows, ax):
    variants = ["adaptive", "filtered", "exact", "fast", "fast+repair"]
    sources = list(grouped(rows, ["input", "size_asked"]).keys())
    width = 0.8 / len(variants)
    for k, v in enumerate(variants):
        xs, ys, bad = [], [], []
        for i, s in enumerate(sources):
            g = [r for r in rows if (r["input"], r["size_asked"]) == s and r["variant"] == v]
            if not g:
                continue
            xs.append(i + k * width)
            ys.append(median(g, "seconds.total"))
            bad.append(any(r["validation.valid"] != "true" for r in g))
        bars = ax.bar(xs, ys, width, label=v)
        for bar, b in zip(bars, bad):
            if b:
                bar.set_hatch("xx")
    ax.set_xticks([i + 0.4 - width / 2 for i in range(len(sources))])
    ax.set_xticklabels([s[0] for s in sources], rotation=30, ha="right", fontsize=8)
    ax.set_ylabel("seconds (median)")
    ax.set_yscale("log")
    ax.set_title("kernels per family (hatched: some run invalid)")


def speedup(rows, ax):
    fig = ax.figure
    ax.remove()
    seq = {(r["input"], r["size_asked"], r["location"], r["seed"]): num(r, "seconds.total")
           for r in rows if r["method"] == "sequential"}
    inputs = list(grouped(rows, ["input"]).keys())
    axes = fig.subplots(1, len(inputs), squeeze=False)[0]
    for panel, (inp,) in zip(axes, inputs):
        mine = [r for r in rows if r["input"] == inp]
        size = str(max(int(r["size_asked"]) for r in mine))
        colors = {}
        for (method, loc), g in grouped([r for r in mine if r["method"] != "sequential"
                                         and r["size_asked"] == size],
                                        ["method", "location"]).items():
            by_t = grouped(g, ["threads"])
            xs = sorted(int(t[0]) for t in by_t)
            ys = []
            for x in xs:
                values = [seq[k] / num(r, "seconds.total") for r in by_t[(str(x),)]
                          for k in [(r["input"], r["size_asked"], r["location"], r["seed"])]
                          if k in seq]
                ys.append(statistics.median(values) if values else float("nan"))
            color = colors.setdefault(method, "C%d" % len(colors))
            panel.plot(xs, ys, marker="o", linestyle="-" if loc == "walk" else "--",
                       color=color, label="%s (%s)" % (method, loc))
        panel.axhline(1.0, color="0.5", linewidth=0.8)
        panel.set_xlabel("threads")
        panel.set_ylabel("speedup (median of the rounds)")
        points = median(mine, "points") if size == "0" else int(size)
        panel.set_title("%s, %d points" % (inp, points), fontsize=9)
        mark_oversubscribed(panel, mine)


def breakdown(rows, ax):
    for loc, g in grouped(rows, ["location"]).items():
        by_n = grouped(g, ["size_asked"])
        ns = sorted(int(n[0]) for n in by_n)
        for phase, style in [("location", "o"), ("subdivision", "s"), ("legalization", "^"),
                             ("other", "x")]:
            ys = [median(by_n[(str(n),)], "seconds." + phase) for n in ns]
            ax.plot(ns, ys, marker=style, linestyle="-" if loc[0] == "walk" else "--",
                    label="%s (%s)" % (phase, loc[0]))
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("points")
    ax.set_ylabel("seconds (median)")
    ax.set_title("time per phase (paper Fig. 4)")


def flips(rows, ax):
    fig = ax.figure
    ax.remove()
    left, right = fig.subplots(1, 2)
    # One colour per input in both panels, one line style per flip kind: the default colour
    # cycle would give each (input, kind) line its own colour and run out of colours.
    palette = matplotlib.rcParams["axes.prop_cycle"].by_key()["color"]
    colour = {}
    for (inp, loc), g in grouped(rows, ["input", "location"]).items():
        c = colour.setdefault(inp, palette[len(colour) % len(palette)])
        by_n = grouped(g, ["size_asked"])
        ns = sorted(int(n[0]) for n in by_n)
        for kind, style in (("S23", "-"), ("S32", "--"), ("S22", "-."), ("S44", ":")):
            ys = [mean(by_n[(str(n),)], "flips." + kind) / median(by_n[(str(n),)], "points")
                  for n in ns]
            if any(y > 0 for y in ys):
                left.plot(ns, ys, marker="o", linestyle=style, color=c, label="%s %s" % (inp, kind))
        nodes = [num(r, "dag_nodes") for r in g]
        seconds = [num(r, "seconds.total") for r in g]
        right.plot(nodes, seconds, "o", color=c, label="%s (%s)" % (inp, loc))
    left.set_xscale("log")
    left.set_xlabel("points")
    left.set_ylabel("flips per point (mean)")
    left.set_title("flips by type (paper Figs. 8, 9)", fontsize=9)
    right.set_xscale("log")
    right.set_yscale("log")
    right.set_xlabel("DAG nodes")
    right.set_ylabel("seconds")
    right.set_title("time against the DAG's size", fontsize=9)


def deadlocks(rows, ax):
    for (inp, loc, method, size), g in grouped(
            rows, ["input", "location", "method", "size_asked"]).items():
        by_t = grouped(g, ["threads"])
        xs = sorted(int(t[0]) for t in by_t)
        ys = [1000.0 * median(by_t[(str(x),)], "deadlocks") / median(by_t[(str(x),)], "points")
              for x in xs]
        ax.plot(xs, ys, marker="o", label="%s:%s %s (%s)" % (inp, size, method, loc))
    ax.set_xlabel("threads")
    ax.set_ylabel("deadlocks per 1000 points (median)")
    ax.set_title("deadlocks (paper Fig. 14)")
    mark_oversubscribed(ax, rows)


def hull_loss(rows, ax):
    def key(r):
        return (r["input"], r["size_asked"], r["location"], r["seed"])
    inf = {key(r): num(r, "tetrahedra") for r in rows if r["bounding"] == "infinite"}
    aux = [r for r in rows if r["bounding"] == "aux-tet" and key(r) in inf]
    for (inp, loc), g in grouped(aux, ["input", "location"]).items():
        pts, ys = [], []
        for rs in grouped(g, ["size_asked"]).values():
            pts.append(median(rs, "points"))
            ys.append(100.0 * statistics.mean(num(r, "hull_tetrahedra_lost") / inf[key(r)]
                                              for r in rs))
        ax.plot(pts, ys, marker="o", label=inp if loc == "dag" else "%s (%s)" % (inp, loc))
    ax.set_xscale("log")
    ax.set_xlabel("points")
    ax.set_ylabel("hull tetrahedra lost, % of the mesh (mean)")
    ax.set_title("the auxiliary tetrahedron's lost tetrahedra")


def compare(rows, ax):
    sources = grouped(rows, ["input", "size_asked"])
    for i, (source, g) in enumerate(sources.items()):
        engines = grouped(g, ["variant", "threads"])
        names = ["%s %st" % k for k in engines]
        ys = [median(v, "seconds.total") for v in engines.values()]
        ax.barh([n + ("" if len(sources) == 1 else " " + source[1]) for n in names], ys)
    ax.set_xlabel("seconds (median)")
    ax.set_title("dtlab and CGAL, same points")


# The peers study's column order (studies/peers.cpp).
PEER_TOOLS = ["cgal-epick", "cgal-doubles", "qhull-Qt", "qhull-QJ", "tetgen", "dtlab-fast",
              "dtlab-adaptive", "dtlab-filtered"]


def peers(rows, ax):
    """Inputs x tools: each cell coloured by its worst outcome, with the counts written in it."""
    present = set(r["variant"] for r in rows)
    tools = [t for t in PEER_TOOLS if t in present] + sorted(present - set(PEER_TOOLS))
    groups = grouped(rows, ["input", "size_asked"])
    order = ["valid", "refused", "invalid", "crashed", "hung"]  # worst last
    colours = {"right": "#4caf50", "refused": "#ffb74d", "invalid": "#e53935",
               "crashed": "#8e24aa", "hung": "#424242", "valid": "#e53935"}
    no_mesh = {"coplanar", "collinear"}
    ax.set_xlim(0, len(tools))
    ax.set_ylim(0, len(groups))
    for y, ((input_name, size), group) in enumerate(groups.items()):
        for x, tool in enumerate(tools):
            outcomes = [r["outcome"] for r in group if r["variant"] == tool]
            if not outcomes:
                continue
            right = "refused" if input_name in no_mesh else "valid"
            wrong = [o for o in outcomes if o != right]
            worst = max(wrong, key=order.index) if wrong else "right"
            ax.add_patch(plt.Rectangle((x, y), 1, 1, color=colours[worst], ec="white"))
            text = "/".join("%d%s" % (outcomes.count(o), o[0]) for o in order if o in outcomes)
            ax.text(x + 0.5, y + 0.5, text, ha="center", va="center", fontsize=7,
                    color="white" if worst in ("crashed", "hung", "invalid", "right") else "black")
    ax.set_xticks([i + 0.5 for i in range(len(tools))])
    ax.set_xticklabels(tools, rotation=30, ha="right", fontsize=7)
    ax.set_yticks([i + 0.5 for i in range(len(groups))])
    ax.set_yticklabels(["%s:%s" % key for key in groups], fontsize=7)
    ax.invert_yaxis()
    labels = {"right": "right answer", "refused": "refused a valid input",
              "invalid": "invalid mesh (or a mesh of points that have none)"}
    for name, colour in colours.items():
        if name != "valid":
            ax.bar(0, 0, color=colour, label=labels.get(name, name))
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    ax.set_title("Which tools survive which inputs (exact validator; v valid, r refused, "
                 "i invalid, c crashed, h hung)", fontsize=9)


PLOTS = {"burglary-errors": burglary_errors, "predicate-errors": predicate_errors,
         "speedup": speedup, "breakdown": breakdown, "flips": flips, "deadlocks": deadlocks,
         "hull-loss": hull_loss, "compare": compare, "peers": peers}

# Studies whose plot shows the runs that ended without a result too.
ALL_ROWS = {"peers"}


def main():
    if len(sys.argv) != 4 or sys.argv[1] not in PLOTS:
        sys.exit("usage: plot_study.py {%s} STUDY.csv OUT.png" % ",".join(PLOTS))
    name, csv_path, png = sys.argv[1:]
    rows = all_rows(csv_path) if name in ALL_ROWS else ok_rows(csv_path)
    if not rows:
        sys.exit("plot_study.py: %s has no finished run to plot" % csv_path)
    height = 4.5
    if name == "peers":
        height = max(4.5, 1.2 + 0.28 * len(grouped(rows, ["input", "size_asked"])))
    fig, ax = plt.subplots(figsize=(9 if name != "peers" else 10.5, height))
    PLOTS[name](rows, ax)
    for axis in fig.axes:
        handles, _ = axis.get_legend_handles_labels()
        if handles and axis.get_legend() is None:
            axis.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(png, dpi=110)


if __name__ == "__main__":
    main()
