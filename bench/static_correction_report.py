#!/usr/bin/env python3
"""Runs bench/static_correction_bench.cpp and writes docs/bench/static_correction.csv and .png.

Rows "struck": the soft ellipsoid struck by a half-sine (docs/modal.md "Static correction in the world"),
r modes with and without the static correction, its struck-point error against the same body with every
mode of its lattice, and the CPU per step. Rows "resting": the ellipsoid resting on a plane (6x4x3 and
10x7x5 lattices), CPU per step, its ModalUpdate and UpdateSurfaces stages, and the CPU to create the body.
Usage: bench/static_correction_report.py BINARY OUT.csv
       bench/static_correction_report.py --plot OUT.csv   (the plot again from the CSV)
"""
import datetime
import os
import platform
import subprocess
import sys

from machine import cpu_name  # bench/machine.py
from report_files import benchmark_rows, gnuplot, have_gnuplot, main_or_replot, write_rows  # bench/report_files.py

HEADER = ["date", "machine", "cpu", "commit", "case", "arg", "corrected", "error", "step_us",
          "modal_update_us", "update_surfaces_us", "create_ms"]


def main():
    binary, out_csv = sys.argv[1], sys.argv[2]
    head = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()
    stamp = [datetime.date.today().isoformat(), f"{platform.node()} ({os.cpu_count()} cores)", cpu_name(), head]
    lines = []
    # One run per benchmark: Google Benchmark's CSV writer stops when runs carry different counters.
    rows = [r for name in ("Struck", "Resting") for r in benchmark_rows(binary, [f"--benchmark_filter={name}"])]
    for r in rows:
        name = r["name"].split("/")
        case = "struck" if "Struck" in name[0] else "resting"
        arg = name[1] if case == "struck" else ("6x4x3" if name[1] == "0" else "10x7x5")
        cpu_us = float(r["cpu_time"]) * (1e3 if r["time_unit"] == "ms" else 1.0)
        step_us = float(r["step_us"]) if case == "struck" else cpu_us
        lines.append(stamp + [case, arg, name[2], f"{float(r.get('error') or 0):.4f}", f"{step_us:.2f}",
                              f"{float(r.get('modal_update_us') or 0):.1f}",
                              f"{float(r.get('update_surfaces_us') or 0):.1f}",
                              f"{float(r.get('create_ms') or 0):.1f}"])
        print(",".join(lines[-1]), flush=True)
    write_rows(out_csv, HEADER, lines)
    plot(out_csv, lines)


def plot(out_csv, lines):
    """Struck-point error and CPU per step against r, modes alone and with the correction."""
    if not have_gnuplot():
        return
    data = out_csv[:-4] + ".dat"
    with open(data, "w", encoding="utf-8") as f:
        for corrected in ("0", "1"):
            f.write(f"# corrected {corrected}\n")
            for r in lines:
                if r[4] == "struck" and r[6] == corrected:
                    f.write(f"{r[5]} {r[7]} {r[8]}\n")
            f.write("\n\n")
    png = out_csv[:-4] + ".png"
    gnuplot(f"""
set terminal pngcairo size 1100,420 font ",10"
set output "{png}"
set multiplot layout 1,2
set logscale x
set xlabel "modes r"
set grid
set key top right
set title "Soft ellipsoid struck by a half-sine: struck-point error vs every mode"
set ylabel "max error / peak [-]"
set yrange [0:1.05]
plot "{data}" index 0 using 1:2 with linespoints title "modes alone", \\
     "{data}" index 1 using 1:2 with linespoints title "modes + static correction", \\
     0.05 with lines dashtype 2 title "5%"
set title "CPU per step (free body, host load)"
set ylabel "CPU per step [us]"
set yrange [0:*]
set key top left
plot "{data}" index 0 using 1:3 with linespoints title "modes alone", \\
     "{data}" index 1 using 1:3 with linespoints title "modes + static correction"
unset multiplot
""", data, png)


if __name__ == "__main__":
    main_or_replot(main, plot)
