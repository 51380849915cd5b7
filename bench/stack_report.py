#!/usr/bin/env python3
"""Stacking benchmark (bench/stack_bench.cpp) CSV -> PNG (gnuplot) and a markdown table on stdout.

Usage: stack_report.py STACK.csv        (writes STACK.png beside it)
Left: drift of the top box after 10 s against dt; right: the largest body speed after 2 s. One colour
per scene, one dash per engine; the dashed grey lines are the "stands" limits (1 cm, 1 cm/s). Values
below 1e-5 are drawn at 1e-5 (log axes; Bullet's sleeping bodies have speed 0).
"""
import csv
import os
import shutil
import subprocess
import sys

COLOURS = {"column": "#3d7cc9", "pyramid": "#d9822b", "floor_grid": "#3a9e4f"}
DASHES = {"supermodal": 1, "bullet": 2, "bullet_sleep": 3}
FLOOR = 1e-5


def read(path):
    with open(path, encoding="utf-8") as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


def table(rows):
    print("| engine | scene | N | dt [s] | ms/step (CPU) | drift [m] | max v after 2 s [m/s] | stands |")
    print("|---|---|---|---|---|---|---|---|")
    for r in rows:
        print(f"| {r['engine']} | {r['scene']} | {r['bodies']} | 1/{1 / float(r['dt_s']):.0f} | "
              f"{float(r['cpu_ms_per_step']):.3f} | {float(r['top_drift_m']):.3g} | "
              f"{float(r['max_speed_after_2s']):.3g} | {r['stands']} |")


def subtitle(path):
    """The CSV's settings line (a '# supermodal ...' comment up to its first ':' or ';'), if any."""
    with open(path, encoding="utf-8") as f:
        notes = [line[2:].strip() for line in f if line.startswith("# supermodal")]
    return "\\n" + notes[0].split(";")[0].split(":")[0].replace('"', "'") if notes else ""


def plot(path, rows):
    series = {}  # (scene, engine) -> [(dt, drift, speed)]
    for r in rows:
        series.setdefault((r["scene"], r["engine"]), []).append(
            (float(r["dt_s"]), max(FLOOR, float(r["top_drift_m"])), max(FLOOR, float(r["max_speed_after_2s"]))))
    data = path[:-4] + ".dat"
    with open(data, "w", encoding="utf-8") as f:
        for pts in series.values():
            f.writelines(f"{dt} {drift} {speed}\n" for dt, drift, speed in sorted(pts))
            f.write("\n\n")

    def curves(column):
        return ", ".join(
            f'"{data}" index {i} using 1:{column} with linespoints lw 2 pt 7 dt {DASHES.get(e, 4)} '
            f'lc rgb "{COLOURS.get(s, "#555555")}" title "{s}, {e}"' for i, (s, e) in enumerate(series))

    script = f"""
set terminal pngcairo size 1200,500 font "Helvetica,10" noenhanced
set output "{path[:-4]}.png"
set multiplot layout 1,2 title "Stacking: rounded boxes (half 0.1 m), 10 s, one world substep, one thread{subtitle(path)}"
set logscale xy
set format "%g"
set xrange [0.0008:0.02]
set yrange [{FLOOR}:100]
set grid
set xlabel "dt [s]"
set key bottom right font ",8"
set ylabel "top drift after 10 s [m]"
plot {curves(2)}, 0.01 with lines dt 2 lc rgb "#888888" title "stands: <= 1 cm"
set ylabel "largest body speed after 2 s [m/s]"
plot {curves(3)}, 0.01 with lines dt 2 lc rgb "#888888" title "stands: < 1 cm/s"
unset multiplot
"""
    subprocess.run(["gnuplot"], input=script, text=True, check=True)
    os.remove(data)


def main():
    path = sys.argv[1]
    rows = read(path)
    table(rows)
    if shutil.which("gnuplot"):
        plot(path, rows)
    else:
        print("gnuplot not found: no plot", file=sys.stderr)


if __name__ == "__main__":
    main()
