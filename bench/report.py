#!/usr/bin/env python3
"""Turns a Google Benchmark JSON file into CSV + markdown (+ a PNG plot when gnuplot is present).

Usage: report.py RESULT.json OUT_PREFIX COMMIT
Rows are the median aggregates; items_per_second and every user counter are kept.
"""
import csv
import json
import re
import shutil
import subprocess
import sys


def main():
    src, prefix, commit = sys.argv[1], sys.argv[2], sys.argv[3]
    data = json.load(open(src))
    ctx = data["context"]
    rows = []
    for b in data["benchmarks"]:
        if b.get("aggregate_name") not in (None, "median"):
            continue
        name = b.get("run_name", b["name"])
        skip = {"name", "run_name", "run_type", "repetitions", "repetition_index", "threads", "family_index",
                "per_family_instance_index", "aggregate_name", "aggregate_unit", "iterations", "cpu_time",
                "real_time", "time_unit", "items_per_second"}
        counters = {k: v for k, v in b.items() if k not in skip and isinstance(v, (int, float))}
        rows.append({"name": name, "real_time": b["real_time"], "cpu_time": b["cpu_time"],
                     "time_unit": b["time_unit"], "items_per_second": b.get("items_per_second", ""),
                     **counters})
    meta = {"date": ctx["date"], "commit": commit, "host": ctx.get("host_name", ""),
            "cpus": ctx["num_cpus"], "mhz_per_cpu": ctx["mhz_per_cpu"],
            "build": ctx.get("library_build_type", ""), "threads": 1}
    keys = []
    for r in rows:
        for k in r:
            if k not in keys:
                keys.append(k)
    with open(prefix + ".csv", "w", newline="") as f:
        f.write("# " + ", ".join(f"{k}={v}" for k, v in meta.items()) + "\n")
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        w.writerows(rows)
    with open(prefix + ".md", "w") as f:
        f.write(f"Median of repetitions. {', '.join(f'{k}: {v}' for k, v in meta.items())}\n\n")
        f.write("| " + " | ".join(keys) + " |\n|" + "---|" * len(keys) + "\n")
        for r in rows:
            f.write("| " + " | ".join(fmt(r.get(k, "")) for k in keys) + " |\n")
    plot(prefix, rows)


def fmt(v):
    return f"{v:.4g}" if isinstance(v, float) else str(v)


def plot(prefix, rows):
    """items/s against the benchmark's size argument, one line per family (log-log)."""
    if not shutil.which("gnuplot"):
        return
    families = {}
    for r in rows:
        m = re.match(r"(.+?)/(\d+)", r["name"])
        if m and r["items_per_second"] != "":
            families.setdefault(m.group(1), []).append((int(m.group(2)), float(r["items_per_second"])))
    families = {k: v for k, v in families.items() if len(v) > 1}
    if not families:
        return
    dat = prefix + ".dat"
    with open(dat, "w") as f:
        for name, pts in families.items():
            f.write(f'# {name}\n')  # a comment: gnuplot reads a quoted first line as bad data
            for n, ips in sorted(pts):
                f.write(f"{n} {ips}\n")
            f.write("\n\n")
    plots = ", ".join(f'"{dat}" index {i} with linespoints title "{n}"' for i, n in enumerate(families))
    script = (f'set terminal pngcairo size 800,500 noenhanced; set output "{prefix}.png"; set logscale xy; '
              f'set xlabel "size (bodies or entities)"; set ylabel "items per second"; set key left bottom; '
              f'set grid; plot {plots}')
    subprocess.run(["gnuplot", "-e", script], check=True)
    import os
    os.remove(dat)


if __name__ == "__main__":
    main()
