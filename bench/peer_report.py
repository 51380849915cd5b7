#!/usr/bin/env python3
"""Pile against Bullet (bench/peer_pile.cpp) CSV -> PNG (gnuplot) and a markdown table on stdout.

Usage: peer_report.py PEER.csv [SETTING]   (writes PEER.png beside it; SETTING names the solver settings
       in the title, "one substep" when not given)
Every run the CSV holds (peer_pile appends), in file order: left, supermodal's ms/step over Bullet's
(the `bullet` rows: Bullet's bodies never sleep) per shape, with the goals as dashed lines (ellipsoids
0.33x, rounded boxes 1.0x); right, the deepest overlap at the end of each run, both engines. Runs of one
day share a date on the axis; this VM's speed drifts between minutes, so only each run's ratio counts.
"""
import csv
import os
import shutil
import subprocess
import sys

COLOURS = {"box": "#d9822b", "sphere": "#3a9e4f", "ellipsoid": "#3d7cc9"}
GOALS = {"ellipsoid": 0.33, "box": 1.0}


def read(path):
    with open(path, encoding="utf-8") as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


def runs(rows):
    """(index, date, shape, ratio, overlap supermodal [mm], overlap Bullet [mm]) per supermodal/bullet pair."""
    out, last = [], {}
    for r in rows:
        if r["engine"] == "supermodal":
            last[r["shape"]] = r
        elif r["engine"] == "bullet" and r["shape"] in last:
            sm = last.pop(r["shape"])
            ratio = float(sm["ms_per_step"]) / float(r["ms_per_step"])
            out.append((r["date"], r["shape"], ratio, 1e3 * float(sm["end_overlap_m"]),
                        1e3 * float(r["end_overlap_m"])))
    return out


def table(points):
    print("| date | shape | ratio supermodal / Bullet | overlap supermodal / Bullet [mm] |")
    print("|---|---|---|---|")
    for date, shape, ratio, ov_sm, ov_bt in points:
        print(f"| {date} | {shape} | {ratio:.2f} | {ov_sm:.2f} / {ov_bt:.2f} |")


def plot(path, points, setting):
    shapes = [s for s in COLOURS if any(p[1] == s for p in points)]
    # One x position per run: a run writes each shape once, so a shape seen again starts the next.
    run_of, dates, seen = [], [], set()
    for date, shape, *_ in points:
        if shape in seen or not dates:
            seen.clear()
            dates.append(date)
        seen.add(shape)
        run_of.append(len(dates) - 1)
    data = path[:-4] + ".dat"
    with open(data, "w", encoding="utf-8") as f:
        for s in shapes:
            for i, (date, shape, ratio, ov_sm, ov_bt) in enumerate(points):
                if shape == s:
                    f.write(f"{run_of[i]} {ratio} {ov_sm} {ov_bt}\n")
            f.write("\n\n")
    tics = ", ".join(f'"{d[5:]}" {i}' for i, d in enumerate(dates))

    def curves(column, what):
        return ", ".join(f'"{data}" index {k} using 1:{column} with points pt 7 ps 1.2 '
                         f'lc rgb "{COLOURS[s]}" title "{s}{what}"' for k, s in enumerate(shapes))

    goals = ", ".join(f'{g} with lines dt 2 lw 2 lc rgb "{COLOURS[s]}" title "goal, {s}: {g}x"'
                      for s, g in GOALS.items() if s in shapes)
    bullet = ", ".join(f'"{data}" index {k} using 1:4 with points pt 6 ps 1.2 lc rgb "{COLOURS[s]}" '
                       f'title "{s}, Bullet"' for k, s in enumerate(shapes))
    script = f"""
set terminal pngcairo size 1200,500 font "Helvetica,10" noenhanced
set output "{path[:-4]}.png"
set multiplot layout 1,2 title "Pile of 1000 against Bullet 3.24, dt = 1/240 s, {setting}, one thread (each dot one run)"
set grid
set offsets 0.5, 0.5, 0, 0
set xtics ({tics}) rotate by 45 right font ",8"
set xlabel "run (date)"
set key top right font ",8"
set logscale y
set format y "%g"
set ylabel "ms/step, supermodal over Bullet"
plot {curves(2, "")}, {goals}
set ylabel "deepest overlap at the end [mm]"
plot {curves(3, ", supermodal")}, {bullet}
unset multiplot
"""
    subprocess.run(["gnuplot"], input=script, text=True, check=True)
    os.remove(data)


def main():
    path = sys.argv[1]
    setting = sys.argv[2] if len(sys.argv) > 2 else "one substep"
    points = runs(read(path))
    table(points)
    if shutil.which("gnuplot") and points:
        plot(path, points, setting)
    elif not points:
        print("no supermodal/bullet pairs in the file", file=sys.stderr)
    else:
        print("gnuplot not found: no plot", file=sys.stderr)


if __name__ == "__main__":
    main()
