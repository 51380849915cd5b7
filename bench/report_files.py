# SPDX-License-Identifier: MIT
"""The CSV and gnuplot plumbing the bench reports share."""
import csv
import io
import os
import shutil
import subprocess
import sys


def write_rows(path, header, lines):
    """The header and the rows as a CSV at `path` (any old file replaced)."""
    with open(path, "w", newline="", encoding="utf-8") as f:
        w = csv.writer(f)
        w.writerow(header)
        w.writerows(lines)


def read_rows(path):
    """A CSV's rows after its header, each a list of strings."""
    with open(path, encoding="utf-8") as f:
        return list(csv.reader(f))[1:]


def benchmark_rows(binary, args):
    """Runs a Google Benchmark program with --benchmark_format=csv and `args`; its rows as dicts. Stops
    the report with the program's message if a benchmark failed (a scene that did not load)."""
    out = subprocess.run([binary, "--benchmark_format=csv"] + args, check=True, capture_output=True,
                         text=True).stdout
    rows = list(csv.DictReader(io.StringIO(out[out.index("name,"):])))
    for r in rows:
        if r.get("error_occurred") == "true":
            sys.exit(f"{binary}: {r['name']}: {r['error_message']}")
    return rows


def write_blocks(out_csv, lines, group, columns, heading="# {}"):
    """gnuplot data beside `out_csv` (its name, .dat): one block per value of column `group`, in the order
    the values first appear, each holding those rows' `columns`, under `heading` with the value.
    Returns the data file's path and the values."""
    groups = list(dict.fromkeys(r[group] for r in lines))
    data = out_csv[:-4] + ".dat"
    with open(data, "w", encoding="utf-8") as f:
        for g in groups:
            f.write(heading.format(g) + "\n")
            for r in lines:
                if r[group] == g:
                    f.write(" ".join(str(r[c]) for c in columns) + "\n")
            f.write("\n\n")
    return data, groups


def have_gnuplot():
    """Whether gnuplot is installed; says so when not (the reports then write no plot)."""
    if shutil.which("gnuplot"):
        return True
    print("gnuplot not found: no plot")
    return False


def gnuplot(script, data, png):
    """Runs a gnuplot script that writes `png` from the file `data`, then removes `data`."""
    subprocess.run(["gnuplot"], input=script, text=True, check=True)
    os.remove(data)
    print(png)


def main_or_replot(main, plot):
    """`SCRIPT --plot OUT.csv` draws the plot again from the CSV (plot(path, rows)); anything else runs
    the report (main())."""
    if len(sys.argv) == 3 and sys.argv[1] == "--plot":
        plot(sys.argv[2], read_rows(sys.argv[2]))
    else:
        main()
