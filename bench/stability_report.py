#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Heat maps and markdown tables of the stability map (docs/stability.md).

Usage: stability_report.py MAP.csv OUT_DIR > tables.md
Reads bench/stability_map's CSV; for each slice writes OUT_DIR/<slice>.png (two panels: energy gain and
max penetration over the smallest radius, log colour scale; cells marked N = NaN/Inf, R = refused,
g = a guard acted) with gnuplot, and prints one markdown table per slice. Python stdlib + gnuplot only.
"""
import csv
import math
import os
import subprocess
import sys

# Per slice: (x column, x label, y column, y label, title).
SLICES = {
    "eps_aspect": ("epsilon", "epsilon (both exponents)", "aspect", "aspect ratio",
                   "Drop on a plane: epsilon x aspect (dt 2 ms, frequency at the cap)"),
    "mass_dt": ("mass_ratio", "mass ratio top/bottom", "dt_ratio", "dt / (1/(10 f)), f = 50 Hz",
                "Two-body stack: mass ratio x dt over the contact limit"),
    "freq_speed": ("frequency_hz", "penalty frequency [Hz] (cap 50 Hz at dt 2 ms)", "speed",
                   "impact speed [m/s]", "Sphere impact: penalty frequency x speed (dt 2 ms)"),
    "modal_dt": ("epsilon", "epsilon (both exponents)", "dt_ratio", "dt / (2/omega_max)",
                 "Modal body drop (central difference): epsilon x dt over its limit"),
    "modal_exact_dt": ("epsilon", "epsilon (both exponents)", "dt_ratio", "dt / (2/omega_max)",
                       "Modal body drop (exact integrator): epsilon x dt over 2/omega_max"),
}


def fnum(s):
    return float(s)


def mark(row):
    if row["accepted"] != "1":
        return "R"
    if row["non_finite"] == "1":
        return "N"
    return "g" if row["guard"] == "1" else ""


def log_clip(v, lo):
    return math.log10(max(v, lo)) if math.isfinite(v) else math.log10(lo)


def short(v):
    return "%g" % v


def write_panel_data(path, rows, xs, ys, xcol, ycol, metric, lo):
    with open(path, "w") as f:
        for r in rows:
            i = xs.index(fnum(r[xcol]))
            j = ys.index(fnum(r[ycol]))
            v = fnum(r[metric]) if r["accepted"] == "1" and r["non_finite"] != "1" else float("nan")
            val = log_clip(v, lo) if math.isfinite(v) else "NaN"
            f.write("%d %d %s %s\n" % (i, j, val, mark(r) or '""'))


def plot(slice_name, rows, out_dir):
    xcol, xlabel, ycol, ylabel, title = SLICES[slice_name]
    xs = sorted({fnum(r[xcol]) for r in rows})
    ys = sorted({fnum(r[ycol]) for r in rows})
    gain_dat = os.path.join(out_dir, slice_name + "_gain.dat")
    pen_dat = os.path.join(out_dir, slice_name + "_pen.dat")
    write_panel_data(gain_dat, rows, xs, ys, xcol, ycol, "gain_all", 1e-6)
    write_panel_data(pen_dat, rows, xs, ys, xcol, ycol, "max_penetration_rel", 1e-6)
    xt = ", ".join('"%s" %d' % (short(x), i) for i, x in enumerate(xs))
    yt = ", ".join('"%s" %d' % (short(y), j) for j, y in enumerate(ys))
    png = os.path.join(out_dir, slice_name + ".png")
    script = f"""
set terminal pngcairo size 1400,560 font ",11" noenhanced
set output "{png}"
set multiplot layout 1,2 title "{title}"
set xtics ({xt}) rotate by 45 right
set ytics ({yt})
set xrange [-0.5:{len(xs) - 0.5}]
set yrange [-0.5:{len(ys) - 0.5}]
set xlabel "{xlabel}"
set ylabel "{ylabel}"
set palette defined (-6 "#1a9850", -3 "#a6d96a", -2 "#ffffbf", -1 "#fdae61", 0 "#d73027", 2 "#67001f")
set cbrange [-6:2]
set cblabel "log10 energy gain / E_ref (clipped at 1e-6)"
set title "energy gain (labels: g guard, N NaN/Inf, R refused)"
plot "{gain_dat}" using 1:2:3 with image notitle, "{gain_dat}" using 1:2:4 with labels notitle
set palette defined (-6 "#f7fbff", -3 "#9ecae1", -1 "#4292c6", 0 "#fdae61", 1 "#d73027", 3 "#67001f")
set cbrange [-6:3]
set cblabel "log10 max penetration / smallest radius"
set title "max penetration / smallest radius"
plot "{pen_dat}" using 1:2:3 with image notitle, "{pen_dat}" using 1:2:4 with labels notitle
unset multiplot
"""
    subprocess.run(["gnuplot"], input=script.encode(), check=True)
    os.remove(gain_dat)
    os.remove(pen_dat)
    return xs, ys


def table(slice_name, rows, xs, ys):
    xcol, xlabel, ycol, ylabel, _ = SLICES[slice_name]
    cell = {(fnum(r[xcol]), fnum(r[ycol])): r for r in rows}
    out = ["", "**%s** — rows: %s, columns: %s; each cell: energy gain %% of E_ref (gain_all) / max "
           "penetration over the smallest radius, then marks (g guard, N NaN/Inf, R refused)." %
           (slice_name, ylabel, xlabel), ""]
    out.append("| %s \\ %s | " % (ycol, xcol) + " | ".join(short(x) for x in xs) + " |")
    out.append("|---" * (len(xs) + 1) + "|")
    for y in ys:
        parts = []
        for x in xs:
            r = cell.get((x, y))
            if r is None:
                parts.append("")
            elif r["accepted"] != "1":
                parts.append("R")
            elif r["non_finite"] == "1":
                parts.append("**N**")
            else:
                g = fnum(r["gain_all"]) * 100.0
                gs = "%.2g" % g if abs(g) >= 0.01 else ("<0.01" if g > 0 else "≤0")
                if g > 1.0:
                    gs = "**%s**" % gs
                parts.append("%s / %.2g%s" % (gs, fnum(r["max_penetration_rel"]),
                                             " g" if r["guard"] == "1" else ""))
        out.append("| %s | " % short(y) + " | ".join(parts) + " |")
    return "\n".join(out)


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    with open(sys.argv[1]) as f:
        rows = list(csv.DictReader(f))
    os.makedirs(sys.argv[2], exist_ok=True)
    for name in SLICES:
        sel = [r for r in rows if r["slice"] == name]
        if not sel:
            continue
        xs, ys = plot(name, sel, sys.argv[2])
        print(table(name, sel, xs, ys))


if __name__ == "__main__":
    main()
