#!/usr/bin/env python3
"""Pile benchmark (bench/pile_bench.cpp) JSON -> CSV + PNG (gnuplot).

Usage: pile_report.py RESULT.json OUT_PREFIX COMMIT
The plot shows ms per step (process CPU time, so a shared machine's other jobs do not count) against N
for each shape: one thread solid; two threads dashed (the free-core estimate, see pile_bench.cpp); and
the ellipsoid pile with 2, 3, 4 substeps dotted. Max penetration is written next to each point.
"""
import csv
import json
import re
import shutil
import subprocess
import sys

FIELDS = ["shape", "n", "threads", "substeps", "cpu_ms_per_step", "free_cores_ms_per_step", "ms_per_step",
          "max_penetration_mm", "contacts", "pairs", "ms_broadphase", "ms_narrowphase", "ms_penalty_forces",
          "ms_integrate_forces", "ms_integrate_positions", "ms_events"]


def main():
    src, prefix, commit = sys.argv[1], sys.argv[2], sys.argv[3]
    data = json.load(open(src))
    rows = []
    for b in data["benchmarks"]:
        m = re.match(r"BM_Pile/(\w+)/(\d+)/(\d+)/(\d+)", b["name"])
        if not m:
            continue
        row = {"shape": m.group(1), "n": int(m.group(2)), "threads": int(m.group(3)),
               "substeps": int(m.group(4))}
        row.update({k: float(f"{b[k]:.4g}") if k in b else "" for k in FIELDS[4:]})
        rows.append(row)
    ctx = data["context"]
    with open(prefix + ".csv", "w", newline="") as f:
        f.write(f"# date={ctx['date']}, commit={commit}, host={ctx.get('host_name', '')}, "
                f"cpus={ctx['num_cpus']}, engine build=Release\n")
        w = csv.DictWriter(f, fieldnames=FIELDS)
        w.writeheader()
        w.writerows(rows)
    if shutil.which("gnuplot"):
        plot(prefix, rows)


def plot(prefix, rows):
    series = []  # (title, style, [(n, ms, pen)])
    for shape in ("sphere", "ellipsoid", "rounded_box"):
        for threads, key, style in ((1, "cpu_ms_per_step", "lw 2"), (2, "free_cores_ms_per_step", "dt 2")):
            pts = [(r["n"], r[key], r["max_penetration_mm"]) for r in rows
                   if r["shape"] == shape and r["threads"] == threads and r["substeps"] == 1]
            if pts:
                series.append((f"{shape.replace('_', ' ')}, {threads} thread{'s' if threads > 1 else ''}", style, sorted(pts)))
    for sub in (2, 3, 4):
        pts = [(r["n"], r["cpu_ms_per_step"], r["max_penetration_mm"]) for r in rows
               if r["shape"] == "ellipsoid_substeps" and r["substeps"] == sub]
        if pts:
            series.append((f"ellipsoid, {sub} substeps, 1 thread", "dt 3", sorted(pts)))
    dat = prefix + ".dat"
    with open(dat, "w") as f:
        for title, _, pts in series:
            for n, ms, pen in pts:
                # Penetration does not depend on the thread count: label the one-thread points only.
                label = '""' if "2 threads" in title else f"{pen:.2g}mm"
                f.write(f"{n} {ms} {label}\n")
            f.write("\n\n")
    plots = ", ".join(f'"{dat}" index {i} using 1:2 with linespoints {style} title "{t}"'
                      for i, (t, style, _) in enumerate(series))
    labels = f'"{dat}" using 1:2:3 with labels offset 4,0.5 font ",8" notitle'
    script = (f'set terminal pngcairo noenhanced size 1000,600; set output "{prefix}.png"; set logscale xy; '
              f'set xlabel "bodies N"; set ylabel "ms per step (CPU; 2 threads: on free cores)"; '
              f'set title "Pile, dt = 1/240 s, steps 481-720 (2-core shared VM); labels: max penetration"; '
              f'set key outside right top font ",9"; set grid; set xrange [200:5000]; '
              f'plot {plots}, {labels}, '
              f'"+" using (1000):(9) every ::0::0 with points pt 7 ps 2 lc rgb "red" '
              f'title "goal: ellipsoids, N = 1000, 9 ms, 1 mm"')
    subprocess.run(["gnuplot", "-e", script], check=True)
    import os
    os.remove(dat)


if __name__ == "__main__":
    main()
