#!/usr/bin/env python3
"""Plots two builds' frame rates from docs/bench/render.csv side by side (needs gnuplot).

Usage: bench/render_plot.py RENDER.csv OUT.png DATE BEFORE_COMMIT AFTER_COMMIT
Rows are those of DATE measured with the builds of the two commits (the CSV's commit column); each bar
is the median fps of a benchmark over its rows, the error bar their range. Dashed lines: the 60 fps goal of 4x MSAA, the 30 fps goal of capture.
"""
import collections
import csv
import os
import shutil
import statistics
import subprocess
import sys
import tempfile

CASES = [  # (benchmark name prefix, label on the plot)
    ("BM_CaptureChair/samples:1/png:-1/", "1x still"),
    ("BM_CaptureChair/samples:4/png:-1/", "4x still"),
    ("BM_CaptureChairOrbit/samples:4/png:-1/", "4x turning"),
    ("BM_CaptureChair/samples:1/png:1/", "1x PNG files"),
    ("BM_CaptureChair/samples:4/png:1/", "4x PNG files"),
]


def main():
    if len(sys.argv) != 6:
        sys.exit(__doc__)
    src, out, date, before, after = sys.argv[1:]
    if not shutil.which("gnuplot"):
        sys.exit("render_plot.py: gnuplot not found (apt-get install gnuplot-nox)")
    fps = collections.defaultdict(list)
    with open(src, newline="", encoding="utf-8") as f:
        for row in csv.DictReader(f):
            if row["date"] != date:
                continue
            for build, commit in ((0, before), (1, after)):
                if row["commit"] == commit:
                    for i, (prefix, _) in enumerate(CASES):
                        if row["name"].startswith(prefix):
                            fps[(i, build)].append(float(row["fps"]))
    lines = []
    for i, (_, label) in enumerate(CASES):
        cells = [f'"{label}"']
        for build in (0, 1):
            v = fps.get((i, build))
            if not v:
                sys.exit(f"render_plot.py: no rows of {date} for {label!r} of {(before, after)[build]}")
            cells += [f"{statistics.median(v):.2f}", f"{min(v):.2f}", f"{max(v):.2f}"]
        lines.append(" ".join(cells))
    with tempfile.NamedTemporaryFile("w", suffix=".dat", delete=False) as dat:
        dat.write("\n".join(lines) + "\n")
    script = (
        f'set terminal pngcairo size 900,480 noenhanced; set output "{out}"; '
        f'set title "Chair frame 1280x720 on llvmpipe, 2 cores ({date}; median and range)"; '
        'set ylabel "frames per second"; set yrange [0:*]; set grid ytics; '
        'set style data histograms; set style histogram errorbars gap 2 lw 1; '
        'set style fill solid 0.8 border -1; set boxwidth 0.9; set key top right; '
        'set arrow from graph 0, first 60 to graph 1, first 60 nohead dt 2 lc rgb "#555555"; '
        'set arrow from graph 0, first 30 to graph 1, first 30 nohead dt 2 lc rgb "#555555"; '
        f'plot "{dat.name}" using 2:3:4:xtic(1) title "before ({before})" lc rgb "#9aa7b8", '
        f'"" using 5:6:7 title "after ({after})" lc rgb "#d08a3c"')
    try:
        subprocess.run(["gnuplot", "-e", script], check=True)
    finally:
        os.unlink(dat.name)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
