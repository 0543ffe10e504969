#!/usr/bin/python3
"""Regenerates docs/experiments.md from docs/experiments.in.md and the studies' outputs.

Usage: tools/experiments_doc.py OUT   (OUT: the directory tools/run_experiments.sh wrote)

In the template, a line `<!-- study: RUN/NAME -->` becomes OUT/RUN/NAME.md (its headings one level
down), followed by a link to its CSV, copied xz-compressed to docs/data/experiments/RUN.csv.xz, and its
plot, copied to docs/img/experiments/RUN.png. Every other line is copied.
"""
import lzma
import os
import re
import shutil
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MARKER = re.compile(r"^<!-- study: ([\w.-]+)/([\w-]+) -->$")


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    out = sys.argv[1]
    template = os.path.join(ROOT, "docs", "experiments.in.md")
    images = os.path.join(ROOT, "docs", "img", "experiments")
    os.makedirs(images, exist_ok=True)
    data = os.path.join(ROOT, "docs", "data", "experiments")
    os.makedirs(data, exist_ok=True)
    lines = []
    for line in open(template).read().splitlines():
        m = MARKER.match(line)
        if not m:
            lines.append(line)
            continue
        run, name = m.groups()
        md_path = os.path.join(out, run, name + ".md")
        if not os.path.exists(md_path):
            sys.exit("experiments_doc: %s is missing (tools/run_experiments.sh %s %s)"
                     % (md_path, out, run))
        for study_line in open(md_path).read().splitlines():
            lines.append("#" + study_line if study_line.startswith("#") else study_line)
        csv_path = os.path.join(out, run, name + ".csv")
        if os.path.exists(csv_path):
            # Every run's row, kept beside the doc (xz: the CSVs compress about tenfold).
            with open(csv_path, "rb") as src, lzma.open(os.path.join(data, run + ".csv.xz"),
                                                        "wb", preset=9) as dst:
                dst.write(src.read())
            lines.append("")
            lines.append("Every run, with every option and stat: "
                         "[data/experiments/%s.csv.xz](data/experiments/%s.csv.xz)." % (run, run))
        png = os.path.join(out, run, name + ".png")
        if os.path.exists(png):
            shutil.copyfile(png, os.path.join(images, run + ".png"))
            lines.append("")
            lines.append("![%s](img/experiments/%s.png)" % (run, run))
    text = "\n".join(lines).rstrip("\n") + "\n"
    left = re.findall(r"@@[A-Z]+:[\w-]+@@", text)
    if left:
        sys.exit("experiments_doc: the template still has placeholders: " + ", ".join(left))
    open(os.path.join(ROOT, "docs", "experiments.md"), "w").write(text)
    print("experiments_doc: wrote docs/experiments.md")


if __name__ == "__main__":
    main()
