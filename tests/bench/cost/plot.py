#!/usr/bin/env python3
"""What a step costs as the rain grows, from bench_cost's CSV: ms per step against crates, log–log, one line
per engine (the sweep rows: PhysPix BALANCED, Box2D 2.4, Chipmunk 7). Without matplotlib it says why and
exits 0, so `make bench` never fails on the plot.

    plot.py COST.csv OUT.png
"""
import csv
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from plotting import start  # noqa: E402  (tests/bench/plotting.py)


def load(path):
    """The sweep rows, with bodies and ms per step as numbers."""
    with open(path, newline="") as f:
        rows = [r for r in csv.DictReader(f) if r["group"] == "sweep"]
    for r in rows:
        r["bodies"] = int(r["bodies"])
        r["ms"] = float(r["ms_step_median"])
    return rows


def main(argv):
    plt, rows, png_path = start(argv, __doc__, load)
    fig, ax = plt.subplots(figsize=(7, 5), dpi=100)
    for engine in dict.fromkeys(r["engine"] for r in rows):  # in the CSV's order
        sel = sorted((r for r in rows if r["engine"] == engine), key=lambda r: r["bodies"])
        ax.plot([r["bodies"] for r in sel], [r["ms"] for r in sel], "-o", label=engine)
    ax.set_xscale("log")
    ax.set_yscale("log")
    counts = sorted({r["bodies"] for r in rows})
    ax.set_xticks(counts)
    ax.set_xticks([], minor=True)
    ax.set_xticklabels([str(n) for n in counts])
    steps = "/".join(sorted({r["steps"] for r in rows}))
    ax.set_xlabel(f"crates raining into the pit (the first {steps} steps from the drop)")
    ax.set_ylabel("ms per step (median of runs)")
    ax.set_title("Step cost of the rain: PhysPix, Box2D 2.4, Chipmunk 7")
    ax.grid(True, which="both", alpha=0.25)
    ax.legend(fontsize=8, loc="upper left")
    fig.tight_layout()
    fig.savefig(png_path)
    print(f"wrote {png_path}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
