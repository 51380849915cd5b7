#!/usr/bin/env python3
"""Runs threads_bench builds on scenes and writes docs/bench/threads.csv and threads.png.

Each LABEL=BINARY is one build of bench/threads_bench.cpp (e.g. before and after a change, both built
Release on the same machine, run one after the other on a quiet machine). Rows: label, scene, threads,
median over 3 repetitions of wall ms/step and CPU ms/step, speed-up against 1 thread of that build,
and the low 32 bits of the state hash (equal for 1 and 2 threads: a determinism check).
       bench/threads_report.py --plot OUT.csv   (the plot again from the CSV)
Usage: bench/threads_report.py OUT.csv LABEL[:COMMIT]=BINARY [...] -- SCENE.json [SCENE.json ...]
(COMMIT: the commit the binary was built from; default the checkout's HEAD).
"""
import datetime
import os
import platform
import subprocess
import sys

from machine import cpu_name  # bench/machine.py
from report_files import benchmark_rows, gnuplot, have_gnuplot, main_or_replot, write_rows  # bench/report_files.py


def run(binary, scenes):
    rows = {}
    for r in benchmark_rows(binary, ["--benchmark_filter=BM_Threads", "--benchmark_report_aggregates_only=true"] + scenes):
        if not r["name"].endswith("_median"):
            continue
        base = r["name"][: -len("_median")]  # BM_Threads/scene.json/1/iterations:1/repeats:3/manual_time
        parts = base.split("/")
        rows[(parts[1], int(parts[2]))] = (float(r["ms_per_step"]), float(r["cpu_ms_per_step"]),
                                           int(float(r["hash_low"])), int(float(r["bodies"])))
    return rows


def main():
    args = sys.argv[1:]
    sep = args.index("--")
    out_csv, builds, scenes = args[0], args[1:sep], args[sep + 1:]
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()
    header = ["date", "machine", "cpu", "commit", "build", "scene", "bodies", "threads", "ms_per_step",
              "cpu_ms_per_step", "speedup", "hash_low"]
    lines = []
    date = datetime.date.today().isoformat()
    for build in builds:
        label, binary = build.split("=", 1)
        label, _, built_from = label.partition(":")
        rows = run(binary, scenes)
        for (scene, threads), (ms, cpu, hsh, bodies) in sorted(rows.items()):
            one = rows[(scene, 1)][0]
            lines.append([date, f"{platform.node()} ({os.cpu_count()} cores)", cpu_name(), built_from or commit,
                          label, scene,
                          bodies, threads, f"{ms:.3f}", f"{cpu:.3f}", f"{one / ms:.3f}", hsh])
    write_rows(out_csv, header, lines)
    print(open(out_csv, encoding="utf-8").read())
    plot(out_csv, lines)


def plot(out_csv, lines):
    """Bars of the 2-thread speed-up per scene and build (gnuplot, if installed)."""
    if not have_gnuplot():
        return
    data = out_csv[:-4] + ".dat"
    bars = 0
    with open(data, "w", encoding="utf-8") as f:
        f.write("# scene build speedup ms_1 ms_2\n")
        ms = {(r[5], r[4], r[3], int(r[7])): r[8] for r in lines}  # a run: scene, build, commit
        for r in lines:
            if int(r[7]) == 2:
                # Three short lines, so six or more bars keep their labels apart.
                ms_1 = float(ms[(r[5], r[4], r[3], 1)])
                label = f"{r[5].replace('.json', '')}\\n{r[4]} {r[0][5:]}\\n{ms_1:.1f} -> {float(r[8]):.1f} ms"
                f.write(f'"{label}" {r[10]}\n')
                bars += 1
    png = out_csv[:-4] + ".png"
    script = f"""
set terminal pngcairo size {max(1400, 130 * bars)},500 font "Helvetica,10" noenhanced
set output "{png}"
set style data histograms
set style fill solid 0.8 border -1
set boxwidth 0.6
set yrange [0:2.2]
set ylabel "speed-up, 2 threads against 1 [-]"
set title "Wall time per step, 1 and 2 threads (threads_bench, Release, 2-core VM)"
set grid ytics
set bmargin 5
unset key
plot "{data}" using 2:xtic(1) lc rgb "#3d7cc9", 1 with lines dt 2 lc rgb "#888888"
"""
    gnuplot(script, data, png)


if __name__ == "__main__":
    main_or_replot(main, plot)
