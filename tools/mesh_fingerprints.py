#!/usr/bin/env python3
"""Fingerprints of the meshes a dtlab binary makes over the configuration matrix: every generator
family x every method x location (dag, walk) x insertion (flips; cavity with walk), adaptive
predicates, one seed. Each mesh is read from its .ele and put in a canonical form that keeps
orientation (each tetrahedron rotated by an even permutation to start at its smallest vertex, the
other three cycled to start at their smallest, then the list sorted), so two binaries that give
the same oriented tetrahedra give the same line. Burglary runs with --repair (star splaying):
without it its mesh may depend on the interleaving. A run that is refused prints its exit code.

Usage: tools/mesh_fingerprints.py DTLAB-BINARY OUT.txt [--size N] [--threads T]
         [--predicates fast --methods sequential]
Compare two binaries: run it for each, then `diff a.txt b.txt` (no output: identical meshes).
"""
import argparse
import hashlib
import os
import subprocess
import sys
import tempfile

FAMILIES = ["uniform", "normal", "cluster", "grid", "sphere", "planes", "cospherical",
            "duplicates", "near-duplicates", "coplanar", "collinear", "lattice", "tiny", "huge"]
METHODS = ["sequential", "pessimistic", "optimistic-detect", "optimistic-prevent", "burglary",
           "batch"]
MODES = [("dag", "flips"), ("walk", "flips"), ("walk", "cavity")]


def canonical(tet):
    a, b, c, d = tet
    i = tet.index(min(tet))
    # Even permutations bringing position i to the front.
    first = [(a, b, c, d), (b, a, d, c), (c, d, a, b), (d, c, b, a)][i]
    rest = list(first[1:])
    k = rest.index(min(rest))
    rest = rest[k:] + rest[:k]  # a cyclic rotation: even
    return (first[0], *rest)


def fingerprint(ele_path):
    tets = []
    with open(ele_path) as f:
        rows = [line.split() for line in f if line.strip() and not line.startswith("#")]
    count = int(rows[0][0])
    for fields in rows[1:count + 1]:
        tets.append(canonical(tuple(int(x) for x in fields[1:5])))
    tets.sort()
    digest = hashlib.sha256(repr(tets).encode()).hexdigest()[:16]
    return digest, len(tets)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("dtlab")
    parser.add_argument("out")
    parser.add_argument("--size", type=int, default=1000)
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--predicates", default="adaptive")
    parser.add_argument("--methods", default=",".join(METHODS),
                        help="comma-separated (the fast kernel is deterministic sequentially only)")
    args = parser.parse_args()
    lines = []
    with tempfile.TemporaryDirectory() as tmp:
        ele = os.path.join(tmp, "mesh.ele")
        for family in FAMILIES:
            for method in args.methods.split(","):
                for location, insertion in MODES:
                    threads = 1 if method == "sequential" else args.threads
                    cmd = [args.dtlab, "triangulate", f"{family}:{args.size}", "--seed", "1",
                           "--method", method, "--threads", str(threads), "--location",
                           location, "--insertion", insertion, "--predicates", args.predicates,
                           "-o", ele]
                    if method == "burglary":
                        cmd.append("--repair")
                    if os.path.exists(ele):
                        os.remove(ele)
                    run = subprocess.run(cmd, capture_output=True, text=True)
                    key = f"{family} {method} {location} {insertion}"
                    if run.returncode != 0:
                        lines.append(f"{key}: exit {run.returncode}")
                    else:
                        digest, count = fingerprint(ele)
                        lines.append(f"{key}: {count} tetrahedra {digest}")
    with open(args.out, "w") as f:
        f.write("\n".join(lines) + "\n")
    print(f"{len(lines)} configurations written to {args.out}")


if __name__ == "__main__":
    sys.exit(main())
