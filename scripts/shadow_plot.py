#!/usr/bin/env python3
"""Self-shadowing: what an opacity shadow map's accuracy costs (docs/effects.md#self-shadowing).

Reads oit summary CSVs whose scene declares self-shadowing and draws, against shadow_slices, the
opacity map's error against the deep shadow map (shadow_rmse, shadow_max_abs_error; left) and the
median time of its two passes, shadow-sort and shadow-map (right). One figure; one curve per
scene, technique and shadow_resolution that the rows hold. Invalid rows are left out.

  scripts/shadow_plot.py results.csv [more.csv] --out shadow.png
"""
import argparse
import os
import sys
from collections import defaultdict

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
os.environ.setdefault("MPLBACKEND", "Agg")

import matplotlib  # noqa: E402

matplotlib.use(os.environ["MPLBACKEND"])
import matplotlib.pyplot as plt  # noqa: E402

import oitcsv  # noqa: E402

PASSES = ("shadow-sort", "shadow-map")  # micro/oit/shadow_map.hpp: kShadowSortPass, kShadowMapPass


def series(rows):
    """{(scene, technique, resolution): {slices: {"rmse", "max", pass: ms}}} from ok rows."""
    out = defaultdict(lambda: defaultdict(dict))
    for r in rows:
        slices = oitcsv.to_float(r.get("shadow_slices"))
        if r.get("experiment") != "oit" or slices is None or not oitcsv.is_ok(r):
            continue
        key = (os.path.basename(r.get("scene", "")), r.get("technique", ""), r.get("shadow_resolution", ""))
        point = out[key][int(slices)]
        if r.get("pass") in PASSES:
            point[r["pass"]] = oitcsv.to_float(r.get("median_ms"))
        for column, name in (("shadow_rmse", "rmse"), ("shadow_max_abs_error", "max")):
            if oitcsv.to_float(r.get(column)) is not None:
                point[name] = oitcsv.to_float(r.get(column))
    return out


def plot(data):
    fig, (err_ax, ms_ax) = plt.subplots(1, 2, figsize=(11, 4.5))
    for (scene, technique, res), points in sorted(data.items()):
        xs = sorted(points)
        label = f"{scene} {technique} {res}px"
        rmse = [(x, points[x]["rmse"]) for x in xs if "rmse" in points[x]]
        peak = [(x, points[x]["max"]) for x in xs if "max" in points[x]]
        if rmse:
            line, = err_ax.plot(*zip(*rmse), marker="o", label=f"{label} rmse")
            if peak:
                err_ax.plot(*zip(*peak), marker="x", linestyle="--", color=line.get_color(), label=f"{label} max")
        for p, style in zip(PASSES, ("-", ":")):
            ms = [(x, points[x][p]) for x in xs if points[x].get(p) is not None]
            if ms:
                ms_ax.plot(*zip(*ms), marker="o", linestyle=style, label=f"{label} {p}")
    for ax in (err_ax, ms_ax):
        ax.set_xscale("log", base=2)
        ax.set_xlabel("shadow_slices")
        ax.grid(True, which="both", alpha=0.3)
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=7)
    err_ax.set_yscale("log")
    err_ax.set_ylabel("transmittance error vs the deep shadow map")
    err_ax.set_title("opacity shadow map: error")
    ms_ax.set_ylabel("median ms per pass")
    ms_ax.set_title("opacity shadow map: time")
    fig.tight_layout()
    return fig


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("csv", nargs="+", help="oit summary CSV(s)")
    ap.add_argument("--out", required=True, help="the figure (PNG, SVG or PDF by its extension)")
    args = ap.parse_args(argv)
    rows = []
    try:
        for path in args.csv:
            rows += oitcsv.read_csv(path)[1]
    except oitcsv.ResultsError as e:
        print(f"shadow_plot.py: {e}", file=sys.stderr)
        return 2
    data = series(rows)
    if not data:
        print("shadow_plot.py: no valid oit rows with shadow_slices (a scene declaring self-shadowing)",
              file=sys.stderr)
        return 2
    plot(data).savefig(args.out, dpi=120)
    print(args.out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
