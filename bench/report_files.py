# SPDX-License-Identifier: MIT
"""The CSV and gnuplot plumbing the bench reports share."""
import csv
import os
import shutil
import subprocess


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
