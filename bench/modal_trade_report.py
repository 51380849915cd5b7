#!/usr/bin/env python3
"""The modal trade table and plot (docs/modal.md "Full model and the modal trade").

Usage: modal_trade_report.py RESULT.json OUT_PREFIX
RESULT.json: full_model_bench --benchmark_format=json. Writes OUT_PREFIX.csv and, with gnuplot,
OUT_PREFIX.png: displacement error at the struck point against the speed-up over the full step, per
body and lattice, for the plain modal path and with mode acceleration (static correction).
"""
import csv
import json
import shutil
import subprocess
import sys

CASES = {(0, 0): "board 8x1x1", (0, 1): "board 16x2x2", (1, 0): "ellipsoid 6x4x3", (1, 1): "ellipsoid 10x7x5"}


def main():
    src, prefix = sys.argv[1], sys.argv[2]
    data = json.load(open(src))
    full, modal, ma = {}, {}, {}
    for b in data["benchmarks"]:
        parts = b["name"].split("/")
        key = (int(parts[1]), int(parts[2]))
        if parts[0] == "BM_FullModel_Step":
            full[key] = b
        elif parts[0] == "BM_Modal_Step":
            modal[key + (int(parts[3]),)] = b
        elif parts[0] == "BM_ModeAcceleration_Step":
            ma[key + (int(parts[3]),)] = b
    rows = []
    for (body, res, r), b in sorted(modal.items()):
        f = full[(body, res)]["cpu_time"]
        m = ma[(body, res, r)]["cpu_time"]
        rows.append({"case": CASES[(body, res)], "dofs": int(full[(body, res)]["dofs"]), "modes": r,
                     "full_us": f, "modal_us": b["cpu_time"], "ma_us": m,
                     "speedup": f / b["cpu_time"], "ma_speedup": f / m,
                     "err_struck": b["err_struck"], "err_far": b["err_far"],
                     "ma_struck": b["ma_struck"], "ma_far": b["ma_far"],
                     "static_struck": b["static_struck"], "static_far": b["static_far"]})
    with open(prefix + ".csv", "w", newline="") as out:
        out.write(f"# {data['context']['date']} {data['context'].get('host_name', '')} "
                  f"{data['context']['num_cpus']} CPUs; CPU time per step in microseconds\n")
        w = csv.DictWriter(out, fieldnames=list(rows[0].keys()))
        w.writeheader()
        for row in rows:
            w.writerow({k: (f"{v:.4g}" if isinstance(v, float) else v) for k, v in row.items()})
    if not shutil.which("gnuplot"):
        return
    blocks, plots = [], []
    for i, case in enumerate(CASES.values()):
        sel = [r for r in rows if r["case"] == case]
        blocks.append("$plain%d << EOD\n%sEOD\n" % (i, "".join(f"{r['speedup']} {r['err_struck']} {r['modes']}\n" for r in sel)))
        blocks.append("$ma%d << EOD\n%sEOD\n" % (i, "".join(f"{r['ma_speedup']} {r['ma_struck']} {r['modes']}\n" for r in sel)))
        plots.append(f"$plain{i} using 1:2 with linespoints lt {i + 1} dt 2 pt 6 title '{case}, modes'")
        plots.append(f"$ma{i} using 1:2 with linespoints lt {i + 1} dt 1 pt 7 title '{case}, modes + static correction'")
    script = "".join(blocks) + f"""
set terminal pngcairo size 900,700 noenhanced
set output '{prefix}.png'
set logscale xy
set xlabel 'speed-up over the full step (CPU time per step)'
set ylabel 'displacement error at the struck point (max over one period / peak)'
set title 'Modal step vs full lattice: r = 1, 3, 6, 12, 24, 48 modes (right to left)'
set key below maxcols 2
set grid
set arrow from graph 0, first 0.02 to graph 1, first 0.02 nohead dt 3 lc rgb 'black'
set label 'goal: <= 2% error at >= 100x' at first 110, first 0.014
set arrow from first 100, graph 0 to first 100, graph 1 nohead dt 3 lc rgb 'black'
plot {', '.join(plots)}
"""
    subprocess.run(["gnuplot"], input=script, text=True, check=True)


if __name__ == "__main__":
    main()
