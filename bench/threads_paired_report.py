#!/usr/bin/env python3
"""Runs threads_bench's paired benchmark (BM_Paired) of some builds, rounds of the builds taken in turn,
and writes docs/bench/threads_paired.csv and threads_paired.png.

BM_Paired steps a 1-thread and a 2-thread world of one scene in alternation (blocks of 10 steps: one
thread, two blocks of two threads, one thread), so a virtual machine whose speed drifts slows both
alike; each repetition's speed-up is the ratio of the two sums. `copies` is what two independent
1-thread worlds on two threads of their own got from the machine at the same time against each alone
(2 = two free cores; well under 2 = the machine was busy). One row per repetition (3 per run).
Usage: bench/threads_paired_report.py OUT.csv ROUNDS LABEL[:COMMIT]=BINARY [...] -- SCENE.json
       bench/threads_paired_report.py --plot OUT.csv   (the plot again from the CSV)
(COMMIT: the commit the binary was built from; default the checkout's HEAD).
"""
import datetime
import os
import platform
import statistics
import subprocess
import sys

from machine import cpu_name  # bench/machine.py
from report_files import benchmark_rows, gnuplot, have_gnuplot, main_or_replot, write_blocks, write_rows  # bench/report_files.py

HEADER = ["date", "machine", "cpu", "commit", "build", "round", "scene", "bodies", "ms_one_thread",
          "ms_two_threads", "speedup", "copies", "same_hash"]


def run(binary, scene):
    """The repetitions of BM_Paired on one scene: (bodies, ms one thread, ms two, speed-up, copies, same)."""
    rows = []
    for r in benchmark_rows(binary, ["--benchmark_filter=BM_Paired", scene]):
        if r["name"].endswith(("_mean", "_median", "_stddev", "_cv")):
            continue
        rows.append((int(float(r["bodies"])), float(r["ms_one_thread"]), float(r["ms_per_step"]),
                     float(r["speedup"]), float(r["copies_speedup"]), int(float(r["same_hash"]))))
    return rows


def main():
    args = sys.argv[1:]
    sep = args.index("--")
    out_csv, rounds, builds, scene = args[0], int(args[1]), args[2:sep], args[sep + 1]
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()
    date = datetime.date.today().isoformat()
    machine = f"{platform.node()} ({os.cpu_count()} cores)"
    lines = []
    for rnd in range(1, rounds + 1):
        for build in builds:
            label, binary = build.split("=", 1)
            label, _, built_from = label.partition(":")
            for bodies, one, two, speedup, copies, same in run(binary, scene):
                lines.append([date, machine, cpu_name(), built_from or commit, label, rnd,
                              os.path.basename(scene), bodies, f"{one:.3f}", f"{two:.3f}", f"{speedup:.3f}",
                              f"{copies:.3f}", same])
                print(",".join(map(str, lines[-1])), flush=True)
    write_rows(out_csv, HEADER, lines)
    plot(out_csv, lines)


def plot(out_csv, lines):
    """Each repetition's speed-up against the machine's `copies` at the time, one colour per build."""
    for build in dict.fromkeys(r[4] for r in lines):
        ups = [float(r[10]) for r in lines if r[4] == build]
        print(f"{build}: speed-up median {statistics.median(ups):.3f} of {len(ups)} (min {min(ups):.3f}, "
              f"max {max(ups):.3f})")
    if not have_gnuplot():
        return
    data, builds = write_blocks(out_csv, lines, 4, (11, 10), heading='"{}"')
    png = out_csv[:-4] + ".png"
    series = ", ".join(f'"{data}" index {i} using 1:2 with points pt 7 ps 1.2 title columnheader(1)'
                       for i in range(len(builds)))
    script = f"""
set terminal pngcairo size 900,560 font "Helvetica,11" noenhanced
set output "{png}"
set xlabel "two independent 1-thread runs against one alone, same moment [-] (2 = two free cores)"
set ylabel "speed-up, 2 threads against 1 [-]"
set title "Paired 1- and 2-thread runs of {lines[0][6]} (threads_bench BM_Paired, Release, {lines[0][0]})"
set grid
set key top left
set yrange [1:2.1]
set offsets 0.03, 0.03, 0, 0
plot {series}, 1.8 with lines dt 2 lc rgb "#888888" title "1.8"
"""
    gnuplot(script, data, png)


if __name__ == "__main__":
    main_or_replot(main, plot)
