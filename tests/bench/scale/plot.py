#!/usr/bin/env python3
"""How PhysPix's cost scales, from bench_scale's CSV: one subplot per curve (bodies, terrain size,
body size, overlap, edits), raster beside ODE's analytic boxes. Without matplotlib it says why
and exits 0, so `make bench` never fails on the plot.

    plot.py SCALE.csv OUT.png
"""
import csv
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from plotting import start  # noqa: E402  (tests/bench/plotting.py)

RASTER, ANALYTIC = "tab:blue", "tab:orange"


def load(path):
    """The CSV's rows, grouped by curve, with the numbers as floats."""
    curves = {}
    with open(path, newline="") as f:
        for r in csv.DictReader(f):
            for k in ("x", "ms_median", "narrow_ms", "narrow_us_per_contact", "edit_ms", "ratio_raster_analytic"):
                r[k] = float(r[k])
            curves.setdefault(r["curve"], []).append(r)
    return curves


def series(rows, engine, variant=None, key="ms_median", scale=1.0):
    """(xs, ys) of one engine (and variant) in x order."""
    sel = sorted((r for r in rows if r["engine"] == engine and (variant is None or r["variant"] == variant)),
                 key=lambda r: r["x"])
    return [r["x"] for r in sel], [r[key] * scale for r in sel], [r["label"] for r in sel]


def plot_bodies(ax, rows):
    for engine, color in (("raster", RASTER), ("analytic", ANALYTIC)):
        for variant, style in (("awake", "-o"), ("asleep", "--s")):
            x, y, _ = series(rows, engine, variant)
            if x:
                ax.plot(x, y, style, color=color, label=f"{engine}, {variant}")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("crates resting on the terrain")
    ax.set_ylabel("ms per step (median)")
    ax.set_title("Body count: awake (sleep off) and asleep")
    asleep = {r["x"]: r["ms_median"] for r in rows if r["engine"] == "raster" and r["variant"] == "asleep"}
    awake = {r["x"]: r["ms_median"] for r in rows if r["engine"] == "raster" and r["variant"] == "awake"}
    if asleep and awake:
        n = max(set(asleep) & set(awake))
        ax.text(0.03, 0.97, f"raster asleep/awake at {n:.0f}: {100 * asleep[n] / awake[n]:.1f}% (target < 10%)",
                transform=ax.transAxes, va="top", fontsize=8)


def plot_terrain(ax, rows):
    labels = []
    for engine, color in (("raster", RASTER), ("analytic", ANALYTIC)):
        x, y, labels_e = series(rows, engine, key="narrow_us_per_contact")
        if x:
            ax.plot(x, y, "-o", color=color, label=f"{engine} (largest/smallest {max(y) / min(y):.2f})")
            labels = labels or (x, labels_e)
    ax.set_xscale("log")
    ax.set_yscale("log")
    if labels:
        ax.set_xticks(labels[0])
        ax.set_xticklabels(labels[1], rotation=30, fontsize=7)
        ax.minorticks_off()
    ax.set_xlabel("terrain bitmap, px")
    ax.set_ylabel("narrowphase µs per contact and substep")
    ax.set_title("Terrain size: narrowphase per contact (target: flat within 20%)")
    ax.legend(fontsize=7, loc="center right")


def plot_body_size(ax, rows):
    right = ax.twinx()
    for engine, color in (("raster", RASTER), ("analytic", ANALYTIC)):
        x, y, _ = series(rows, engine)
        if x:
            ax.plot(x, y, "-o", color=color, label=f"{engine}: ms/step")
        x, y, _ = series(rows, engine, key="narrow_us_per_contact")
        if x:
            right.plot(x, y, ":^", color=color, label=f"{engine}: narrowphase µs/contact")
    for a in (ax, right):
        a.set_xscale("log", base=2)
        a.set_yscale("log")
    ax.set_xlabel("crate side, px (4 crates)")
    ax.set_ylabel("ms per step (median), solid")
    right.set_ylabel("narrowphase µs per contact and substep, dotted")
    ax.set_title("Body bitmap size")
    lines = ax.get_legend_handles_labels(), right.get_legend_handles_labels()
    ax.legend(lines[0][0] + lines[1][0], lines[0][1] + lines[1][1], fontsize=7, loc="upper left")


def plot_overlap(ax, rows):
    for engine, color in (("raster", RASTER), ("analytic", ANALYTIC)):
        for variant, style in (("aligned", "-o"), ("rotated", "--s")):
            x, y, _ = series(rows, engine, variant, scale=1e3)
            if x:
                ax.plot(x, y, style, color=color, label=f"{engine}, {variant}")
    ax.set_xscale("log", base=2)
    ax.set_yscale("log")
    ax.set_xlabel("overlap depth d, px (two 256 px boxes)")
    ax.set_ylabel("µs per collision query (median)")
    ax.set_title("Overlap: pp_world_collide against dCollide")


def plot_edits(ax, rows):
    x, y, _ = series(rows, "raster")
    xe, ye, _ = series(rows, "raster", key="edit_ms")
    if x:
        ax.plot(x, y, "-o", color=RASTER, label="raster: step with its erases")
        ax.plot(xe, ye, ":^", color=RASTER, label="raster: the erases alone")
    ax.set_xscale("symlog", linthresh=1)
    ax.set_xlabel("erases per step (radius 16 px, 4096×2048 terrain)")
    ax.set_ylabel("ms per step (median)")
    ax.set_title("Edits per step")
    ax.text(0.03, 0.97, "no analytic line: ODE's boxes cannot be edited", transform=ax.transAxes, va="top",
            fontsize=8)


def main(argv):
    plt, curves, png_path = start(argv, __doc__, load)
    panels = [("bodies", plot_bodies), ("terrain", plot_terrain), ("body_size", plot_body_size),
              ("overlap", plot_overlap), ("edits", plot_edits)]
    fig, axes = plt.subplots(2, 3, figsize=(17, 10), dpi=100)
    for ax, (name, draw) in zip(axes.flat, panels):
        if name in curves:
            draw(ax, curves[name])
            ax.grid(True, which="both", alpha=0.25)
            if not ax.get_legend():
                ax.legend(fontsize=7, loc="lower right")
        else:
            ax.set_axis_off()
            ax.text(0.5, 0.5, f"{name}: not in this run", ha="center", transform=ax.transAxes)
    axes.flat[-1].set_axis_off()  # five curves in a 2×3 grid
    fig.suptitle("PhysPix scaling: raster bodies (blue) against ODE's analytic boxes (orange), same scenes and "
                 "solver settings")
    fig.tight_layout()
    fig.savefig(png_path)
    print(f"wrote {png_path}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
