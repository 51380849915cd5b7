#!/usr/bin/env python3
"""Runs render_bench and writes its rows, with the date and machine, as CSV (docs/bench/render.csv).

Usage: bench/render_report.py RENDER_BENCH OUT.csv [NOTE] [-- extra Google Benchmark options]
Rows: date, machine (cores, CPU, load average at the start), commit, the note (e.g. "idle" or "loaded
by builds"), benchmark name, its label (device or encoder), iterations, wall ms per iteration, CPU ms of
the calling thread, fps, cpu_ms_per_frame (every thread) and PNG bytes, as the bench reports them.
"""
import csv
import datetime
import io
import json
import os
import subprocess
import sys

from machine import cpu_name  # bench/machine.py


def main():
    args = sys.argv[1:]
    extra = []
    if "--" in args:
        extra = args[args.index("--") + 1:]
        args = args[:args.index("--")]
    if len(args) < 2:
        sys.exit(__doc__)
    binary, out_path = args[0], args[1]
    note = args[2] if len(args) > 2 else ""
    load = os.getloadavg()[0]
    machine = f"{os.cpu_count()} cores, {cpu_name()}, load {load:.1f}"
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True,
                            cwd=os.path.dirname(os.path.abspath(__file__))).stdout.strip()
    result = subprocess.run([binary, "--benchmark_format=json"] + extra, check=True, capture_output=True,
                            text=True).stdout
    rows = json.loads(result)["benchmarks"]
    date = datetime.date.today().isoformat()
    with open(out_path, "w", newline="", encoding="utf-8") as f:
        w = csv.writer(f)
        w.writerow(["date", "machine", "commit", "note", "name", "label", "iterations", "wall_ms", "cpu_ms",
                    "fps", "cpu_ms_per_frame_all_threads", "png_bytes"])
        for r in rows:
            scale = {"ms": 1.0, "us": 1e-3, "ns": 1e-6, "s": 1e3}[r.get("time_unit", "ns")]
            w.writerow([date, machine, commit, note, r["name"], r.get("label", ""), r["iterations"],
                        f"{r['real_time'] * scale:.2f}", f"{r['cpu_time'] * scale:.2f}",
                        f"{r['fps']:.2f}" if "fps" in r else "",
                        f"{r['cpu_ms_per_frame']:.2f}" if "cpu_ms_per_frame" in r else "",
                        f"{r['bytes']:.0f}" if "bytes" in r else ""])
    print(f"wrote {out_path}: {len(rows)} rows ({machine})")


if __name__ == "__main__":
    main()
