#!/usr/bin/env python3
"""Speed against error of PhysPix's world settings, from bench_accuracy's CSV: every setting as a
point (ms/step, combined score), the Pareto front as a line, the presets and the poster's method
named. Without matplotlib it says why and exits 0, so `make bench` never fails on the plot.

    plot.py ACCURACY.csv OUT.png
"""
import csv
import os
import math
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from plotting import start  # noqa: E402  (tests/bench/plotting.py)

CAP = 100.0  # scores above this are drawn at it


def load(path):
    """The CSV's rows with the numbers the plot needs as floats."""
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        r["ms"] = float(r["ms_pyramid_tower"])
        r["score_f"] = float(r["score"])  # "inf" parses as infinity
        r["roles_set"] = set(r["roles"].split("+"))
    return rows


def main(argv):
    plt, rows, png_path = start(argv, __doc__, load)
    # Scores past CAP (stacks that fell apart or blew up) are drawn on the CAP line, so that the
    # region around 1, where the choice is made, keeps the room.
    for r in rows:
        r["y"] = max(min(r["score_f"], CAP), 1e-3)

    fig, ax = plt.subplots(figsize=(11, 7), dpi=110)
    ax.set_xscale("log")
    ax.set_yscale("log")

    # Every setting; hollow where a run was cut short by the time budget (score counts what ran).
    for r in rows:
        done = r["complete"] == "1"
        ax.scatter(r["ms"], r["y"], s=30, zorder=3, color="tab:blue",
                   facecolors="tab:blue" if done else "none")
        # Failed settings crowd together: name only those that are on the front or are presets.
        if r["y"] < 10 or r["pareto"] == "1" or r["roles_set"] & {"FAST", "BALANCED", "ACCURATE", "default"}:
            ax.annotate(r["setting"], (r["ms"], r["y"]), xytext=(4, 3), textcoords="offset points",
                        fontsize=7, color="0.25")

    front = sorted((r for r in rows if r["pareto"] == "1"), key=lambda r: r["ms"])
    if front:
        ax.step([r["ms"] for r in front], [r["y"] for r in front], where="post", color="tab:red",
                lw=1.5, zorder=2, label="Pareto front")
        ax.scatter([r["ms"] for r in front], [r["y"] for r in front], s=90, facecolors="none",
                   edgecolors="tab:red", lw=1.5, zorder=4)

    marks = [("FAST", "v", "tab:green"), ("BALANCED", "s", "tab:orange"), ("ACCURATE", "^", "tab:purple"),
             ("default", "D", "black"), ("poster", "*", "tab:brown")]
    for role, marker, color in marks:
        sel = [r for r in rows if role in r["roles_set"]]
        if sel:
            ax.scatter([r["ms"] for r in sel], [r["y"] for r in sel], marker=marker, s=140, color=color,
                       zorder=5, alpha=0.8, label=f"{role} ({sel[0]['setting']})")

    ax.axhline(1.0, color="0.4", ls="--", lw=1)
    ax.text(ax.get_xlim()[0], 1.0, " score 1: meets every target", va="bottom", fontsize=8, color="0.3")
    if any(r["score_f"] >= CAP for r in rows):
        ax.axhline(CAP, color="0.7", ls=":", lw=1)
        ax.text(ax.get_xlim()[0], CAP, f" score {CAP:g} or more (a stack fell apart or blew up)", va="bottom",
                fontsize=8, color="0.4")
    ax.set_ylim(top=CAP * 1.6)
    ax.set_xlabel("ms per step (median, sleep off): pyramid + tower")
    ax.set_ylabel("combined error score (worst metric / its target; lower is better)")
    ax.set_title("PhysPix settings: speed against accuracy (hollow: run cut short by the time budget)")
    ax.grid(True, which="both", alpha=0.25)
    ax.legend(fontsize=8, loc="upper right")
    fig.tight_layout()
    fig.savefig(png_path)
    print(f"wrote {png_path}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
