#!/usr/bin/env python3
"""Runs threads_bench builds on scenes and writes docs/bench/threads.csv and threads.png.

Each LABEL=BINARY is one build of bench/threads_bench.cpp (e.g. before and after a change, both built
Release on the same machine, run one after the other on a quiet machine). Rows: label, scene, threads,
median over 3 repetitions of wall ms/step and CPU ms/step, speed-up against 1 thread of that build,
and the low 32 bits of the state hash (equal for 1 and 2 threads: a determinism check).
Usage: bench/threads_report.py OUT.csv LABEL=BINARY [LABEL=BINARY ...] -- SCENE.json [SCENE.json ...]
"""
import csv
import datetime
import io
import os
import platform
import shutil
import subprocess
import sys


def cpu_name():
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def run(binary, scenes):
    out = subprocess.run([binary, "--benchmark_format=csv", "--benchmark_report_aggregates_only=true"] +
                         scenes, check=True, capture_output=True, text=True).stdout
    start = out.index("name,")
    rows = {}
    for r in csv.DictReader(io.StringIO(out[start:])):
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
        rows = run(binary, scenes)
        for (scene, threads), (ms, cpu, hsh, bodies) in sorted(rows.items()):
            one = rows[(scene, 1)][0]
            lines.append([date, f"{platform.node()} ({os.cpu_count()} cores)", cpu_name(), commit, label, scene,
                          bodies, threads, f"{ms:.3f}", f"{cpu:.3f}", f"{one / ms:.3f}", hsh])
    with open(out_csv, "w", newline="", encoding="utf-8") as f:
        w = csv.writer(f)
        w.writerow(header)
        w.writerows(lines)
    print(open(out_csv, encoding="utf-8").read())
    plot(out_csv, lines)


def plot(out_csv, lines):
    """Bars of wall ms/step per scene, build and thread count (gnuplot, if installed)."""
    if not shutil.which("gnuplot"):
        print("gnuplot not found: no plot")
        return
    data = out_csv[:-4] + ".dat"
    with open(data, "w", encoding="utf-8") as f:
        f.write("# group ms_1_thread ms_2_threads\n")
        groups = {}
        for row in lines:
            groups.setdefault((row[5], row[4]), {})[row[7]] = row[8]
        for (scene, label), by in groups.items():
            f.write(f'"{scene.replace(".json", "")}\\n{label}" {by.get(1, "nan")} {by.get(2, "nan")}\n')
    png = out_csv[:-4] + ".png"
    script = f"""
set terminal pngcairo size 900,480 font "Helvetica,11"
set output "{png}"
set style data histograms
set style histogram clustered gap 1
set style fill solid 0.8 border -1
set ylabel "wall time per step [ms]"
set title "Step time on 1 and 2 threads (threads_bench, Release)"
set key top left
set grid ytics
plot "{data}" using 2:xtic(1) title "1 thread", "" using 3 title "2 threads"
"""
    subprocess.run(["gnuplot"], input=script, text=True, check=True)
    os.remove(data)
    print(png)


if __name__ == "__main__":
    main()
