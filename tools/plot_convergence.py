#!/usr/bin/env python3
"""Plots "error against run time" CSV files written by zraka's convergence_log (convergence.hpp).

Two log-log panels side by side: the error against N (samples, or spp for a renderer) and the
error against seconds, with a 1/sqrt(N) guide line (dashed) and, when the file has a std_error
column, the standard error as a dotted line in each curve's colour. Any number of CSV files go
on the same axes.

    python3 tools/plot_convergence.py a.csv b.csv -o fig.png \
        [--labels "uniform,importance"] [--column abs_error] [--title "..."] [--width 400]

It needs only Debian's python3-matplotlib (tools/setup.sh installs it); the image is --width
pixels wide and half as high.

The CSV's first line is `<n>,seconds,<columns...>`. The error plotted is --column, else
abs_error, else the first column after seconds (rmse for a renderer). Rows whose error is not
positive (an exact estimate) are left out, since a log axis has no zero.
"""
import argparse
import csv
import math
import os
import sys


def read(path, column):
    with open(path, newline="", encoding="utf-8") as f:
        rows = list(csv.reader(f))
    if not rows or len(rows[0]) < 3 or rows[0][1] != "seconds":
        sys.exit(f"{path}: not a convergence CSV (header must be <n>,seconds,<columns...>)")
    head = rows[0]
    if column is None:
        column = "abs_error" if "abs_error" in head else head[2]
    if column not in head:
        sys.exit(f"{path}: no column '{column}' (columns: {', '.join(head)})")
    c = head.index(column)
    s = head.index("std_error") if column == "abs_error" and "std_error" in head else None
    n, sec, err, se = [], [], [], []
    for r in rows[1:]:
        if not r:
            continue
        e = float(r[c])
        if e > 0 and math.isfinite(e):
            n.append(float(r[0]))
            sec.append(float(r[1]))
            err.append(e)
            se.append(float(r[s]) if s is not None else float("nan"))
    return head[0], column, n, sec, err, se


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("csv", nargs="+", help="CSV files written by convergence_log::write_csv")
    ap.add_argument("-o", "--out", required=True, help="PNG file to write")
    ap.add_argument("--labels", help="comma-separated legend labels (default: file names)")
    ap.add_argument("--column", help="the error column (default: abs_error, else the first)")
    ap.add_argument("--title", default="", help="title over both panels")
    ap.add_argument("--width", type=float, default=400, help="image width in pixels (default 400)")
    a = ap.parse_args()

    try:
        import matplotlib
    except ImportError:
        # The python3 first on PATH may be another install (pyenv, a venv) without matplotlib:
        # Debian's own interpreter has the python3-matplotlib that tools/setup.sh installs.
        debian = "/usr/bin/python3"
        if os.path.realpath(sys.executable) != os.path.realpath(debian) and os.access(debian, os.X_OK):
            os.execv(debian, [debian, os.path.abspath(__file__)] + sys.argv[1:])
        sys.exit("error: python3 has no matplotlib: run 'bash tools/setup.sh' (Debian's python3-matplotlib)")

    matplotlib.use("Agg")  # no display needed
    import matplotlib.pyplot as plt

    labels = a.labels.split(",") if a.labels else [os.path.splitext(os.path.basename(p))[0] for p in a.csv]
    if len(labels) != len(a.csv):
        sys.exit(f"{len(labels)} labels for {len(a.csv)} files")

    dpi = 100
    plt.rcParams.update({"font.size": 6.5, "lines.linewidth": 1.0, "lines.markersize": 2.5})
    fig, (ax_n, ax_t) = plt.subplots(1, 2, figsize=(a.width / dpi, 0.5 * a.width / dpi), dpi=dpi)
    n_name, column = "n", a.column
    guide_at = None
    for path, label in zip(a.csv, labels):
        n_name, column, n, sec, err, se = read(path, a.column)
        if not n:
            print(f"{path}: no positive errors to plot", file=sys.stderr)
            continue
        (line,) = ax_n.plot(n, err, "o-", label=label)
        if all(math.isfinite(v) and v > 0 for v in se):
            # The standard error sigma/sqrt(N): the size the actual error scatters around.
            ax_n.plot(n, se, ":", color=line.get_color(), linewidth=0.8)
        # Points only: on a busy machine a small run can take longer than a bigger one, and
        # a line joining them in N order would zigzag backwards.
        ax_t.plot(sec, err, "o", color=line.get_color(), label=label)
        if guide_at is None:
            guide_at = (n, err)
    if guide_at:
        # The guide c / sqrt(N) through the geometric mean of the first curve's points.
        n, err = guide_at
        c = math.exp(sum(math.log(e) + 0.5 * math.log(x) for x, e in zip(n, err)) / len(n))
        ax_n.plot([n[0], n[-1]], [c / math.sqrt(n[0]), c / math.sqrt(n[-1])], "k--",
                  linewidth=0.8, label=r"$\propto 1/\sqrt{N}$")
    for ax in (ax_n, ax_t):
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.grid(True, which="major", linewidth=0.3, alpha=0.6)
    ax_n.set_xlabel(n_name)
    ax_n.set_ylabel(column)
    ax_t.set_xlabel("seconds")
    ax_n.legend(frameon=False, fontsize=5.5)
    if a.title:
        fig.suptitle(a.title, fontsize=7)
    fig.tight_layout(pad=0.4)
    tmp = a.out + ".tmp.png"
    fig.savefig(tmp, dpi=dpi)
    os.replace(tmp, a.out)  # a reader never sees half a PNG
    print(f"wrote {a.out}")


if __name__ == "__main__":
    main()
