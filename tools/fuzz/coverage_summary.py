#!/usr/bin/env python3
"""Sums llvm-cov's per-file line counts by folder (engine, predicates, io) for each harness.

Usage: coverage_summary.py OUT TARGET=CORPUS ...   (reads OUT/TARGET.json, prints a Markdown table)
"""
import json
import os
import sys

FOLDERS = ("engine", "predicates", "io")


def folder_of(path):
    parts = path.replace("\\", "/").split("/")
    for folder in FOLDERS:
        for i, part in enumerate(parts[:-1]):
            if part == folder and i + 1 < len(parts) and parts[i + 1] in ("src", "include"):
                return folder
    return None


def main():
    out = sys.argv[1]
    print("| harness | corpus | inputs | " + " | ".join(f"{f} lines" for f in FOLDERS) +
          " | branches (all three) |")
    print("|---|---|---:|" + "---:|" * (len(FOLDERS) + 1))
    for spec in sys.argv[2:]:
        target, corpus = spec.split("=", 1)
        with open(os.path.join(out, f"{target}.json")) as f:
            data = json.load(f)
        covered = {f: 0 for f in FOLDERS}
        total = {f: 0 for f in FOLDERS}
        branches = [0, 0]
        for entry in data["data"][0]["files"]:
            folder = folder_of(entry["filename"])
            if folder is None:
                continue
            lines = entry["summary"]["lines"]
            covered[folder] += lines["covered"]
            total[folder] += lines["count"]
            branches[0] += entry["summary"]["branches"]["covered"]
            branches[1] += entry["summary"]["branches"]["count"]
        inputs = sum(len(files) for _, _, files in os.walk(corpus))
        cells = []
        for f in FOLDERS:
            if total[f] == 0:
                cells.append("-")
            else:
                cells.append(f"{covered[f]} / {total[f]} ({100.0 * covered[f] / total[f]:.1f} %)")
        share = 100.0 * branches[0] / branches[1] if branches[1] else 0.0
        cells.append(f"{branches[0]} / {branches[1]} ({share:.1f} %)")
        print(f"| {target} | {corpus} | {inputs} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
