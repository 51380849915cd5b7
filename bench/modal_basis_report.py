#!/usr/bin/env python3
"""Runs modal_basis_bench builds over lattice sizes and writes docs/bench/modal_basis.csv and .png.

Each LABEL[:COMMIT]=BINARY is one build of bench/modal_basis_bench.cpp (e.g. before and after a change).
Every (build, size) runs in its own process, so peak_mb is that build's peak resident set (the process
starts at about 6 MB). Rows: label, cells per axis, dofs, wall and CPU seconds of one build
(assembly + eigen solve + checks), the assembly and eigen split (wall), peak MB, the solver's rounds,
whether completeness was confirmed, and the first and twelfth frequency (equal across builds to
the digits shown: the same modes).
With --repeat N every size runs N times, the builds alternating run by run (so a change in the shared
machine's load falls on all of them alike), and the row is the run of median CPU time.
Usage: bench/modal_basis_report.py OUT.csv [--cells 4,6,8,10,12] [--repeat N] LABEL[:COMMIT]=BINARY [...]
       bench/modal_basis_report.py --plot OUT.csv [LABEL ...]   (the plot again from the CSV: all
       builds, or those named)
"""
import datetime
import os
import platform
import subprocess
import sys

from machine import cpu_name  # bench/machine.py
from report_files import benchmark_rows, gnuplot, have_gnuplot, read_rows, write_blocks, write_rows  # bench/report_files.py

HEADER = ["date", "machine", "cpu", "commit", "build", "cells", "dofs", "seconds", "cpu_seconds",
          "assembly_s", "eigen_s", "peak_mb", "rounds", "checked", "f1_hz", "f12_hz"]


def run(binary, cells):
    rows = benchmark_rows(binary, [f"--benchmark_filter=BM_ModalBasis_Cube/{cells}/"])
    if len(rows) != 1:
        raise SystemExit(f"{binary}: no result for {cells} cells: {rows}")
    return rows[0]


def main():
    args = sys.argv[1:]
    out_csv = args.pop(0)
    cells = [4, 6, 8, 10, 12]
    repeat = 1
    while args and args[0] in ("--cells", "--repeat"):
        if args[0] == "--cells":
            cells = [int(c) for c in args[1].split(",")]
        else:
            repeat = int(args[1])
        args = args[2:]
    head = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()
    date = datetime.date.today().isoformat()
    machine = f"{platform.node()} ({os.cpu_count()} cores)"
    builds = []
    for build in args:
        label, binary = build.split("=", 1)
        label, _, commit = label.partition(":")
        builds.append((label, commit or head, binary))
    runs = {}
    for n in cells:
        for _ in range(repeat):
            for label, _, binary in builds:
                runs.setdefault((label, n), []).append(run(binary, n))
    lines = []
    for label, commit, _ in builds:
        for n in cells:
            by_cpu = sorted(runs[(label, n)], key=lambda r: float(r["cpu_time"]))
            r = by_cpu[len(by_cpu) // 2]
            lines.append([date, machine, cpu_name(), commit, label, n, int(float(r["dofs"])),
                          f"{float(r['real_time']):.3f}", f"{float(r['cpu_time']):.3f}",
                          f"{float(r['assembly_s']):.3f}", f"{float(r['eigen_s']):.3f}",
                          f"{float(r['peak_mb']):.0f}", int(float(r["rounds"])), int(float(r["checked"])),
                          f"{float(r['f1_hz']):.6f}", f"{float(r['f12_hz']):.6f}"])
            print(",".join(str(v) for v in lines[-1]), "  cpu s of each run:",
                  " ".join(f"{float(x['cpu_time']):.2f}" for x in runs[(label, n)]), flush=True)
    write_rows(out_csv, HEADER, lines)
    plot(out_csv, lines)


def plot(out_csv, lines):
    """CPU seconds and peak MB against dofs, one line per build (gnuplot, if installed)."""
    if not have_gnuplot():
        return
    data, builds = write_blocks(out_csv, lines, 4, (6, 8, 11))
    png = out_csv[:-4] + ".png"
    first, last = min(r[0] for r in lines), max(r[0] for r in lines)
    dates = first if first == last else f"{first} to {last}"
    curves_s = ", ".join(f'"{data}" index {i} using 1:2 with linespoints lw 2 title "{b}"'
                         for i, b in enumerate(builds))
    curves_mb = ", ".join(f'"{data}" index {i} using 1:3 with linespoints lw 2 title "{b}"'
                          for i, b in enumerate(builds))
    script = f"""
set terminal pngcairo size 960,420 font "Helvetica,11" noenhanced
set output "{png}"
set multiplot layout 1,2 title "Modal basis build, rounded cube of 20-node cells, 12 modes ({dates}, {lines[0][1]})"
set logscale xy
set grid
set key top left
set xlabel "degrees of freedom"
set ylabel "CPU seconds per build"
plot {curves_s}
set ylabel "peak resident MB"
plot {curves_mb}
unset multiplot
"""
    gnuplot(script, data, png)


def replot(out_csv, labels):
    plot(out_csv, [r for r in read_rows(out_csv) if not labels or r[4] in labels])


if __name__ == "__main__":
    if len(sys.argv) >= 3 and sys.argv[1] == "--plot":
        replot(sys.argv[2], sys.argv[3:])
    elif len(sys.argv) >= 3:
        main()
    else:
        print(__doc__, file=sys.stderr)
        sys.exit(2)
