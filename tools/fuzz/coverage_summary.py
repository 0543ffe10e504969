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
    print("| harness | corpus | inputs | " + " | ".join(f"{f} lines" for f in FOLDERS) + " |")
    print("|---|---|---:|" + "---:|" * len(FOLDERS))
    for spec in sys.argv[2:]:
        target, corpus = spec.split("=", 1)
        with open(os.path.join(out, f"{target}.json")) as f:
            data = json.load(f)
        covered = {f: 0 for f in FOLDERS}
        total = {f: 0 for f in FOLDERS}
        for entry in data["data"][0]["files"]:
            folder = folder_of(entry["filename"])
            if folder is None:
                continue
            lines = entry["summary"]["lines"]
            covered[folder] += lines["covered"]
            total[folder] += lines["count"]
        inputs = sum(len(files) for _, _, files in os.walk(corpus))
        cells = []
        for f in FOLDERS:
            if total[f] == 0:
                cells.append("-")
            else:
                cells.append(f"{covered[f]} / {total[f]} ({100.0 * covered[f] / total[f]:.1f} %)")
        print(f"| {target} | {corpus} | {inputs} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
