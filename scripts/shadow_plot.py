#!/usr/bin/env python3
"""Self-shadowing: what an opacity shadow map's accuracy costs (docs/effects.md#self-shadowing).

Reads oit summary CSVs whose scene declares self-shadowing and draws, against shadow_slices, the
opacity map's error against the deep shadow map (shadow_rmse, shadow_max_abs_error; left) and the
median time of its two passes, shadow-sort and shadow-map (right). One figure; one curve per
scene, technique and shadow_resolution that the rows hold. Invalid rows are left out.

  scripts/shadow_plot.py results.csv [more.csv] --out shadow.png
  scripts/shadow_plot.py results.csv --table     # the Markdown table docs/effects.md holds
"""
import argparse
import os
import sys
from collections import defaultdict

from oitbench import cli  # first: a missing module below ends in one line (oitbench/__init__.py)
from oitbench import results as oitres

os.environ.setdefault("MPLBACKEND", "Agg")

import matplotlib  # noqa: E402

matplotlib.use(os.environ["MPLBACKEND"])
import matplotlib.pyplot as plt  # noqa: E402

PASSES = ("shadow-sort", "shadow-map")  # micro/oit/scene/shadow_map.hpp: kShadowSortPass, kShadowMapPass


TABLE_HEADER = ("| scene | technique | shadow_resolution | shadow_slices | shadow_rmse | shadow_max_abs_error "
                "| shadow-sort ms | shadow-map ms | capture ms | shadow_map_bytes |")


def table_rows(rows):
    """The Markdown table of the ok rows: one line per case, medians of its passes."""
    cases = {}
    for r in rows:
        slices = oitres.to_float(r.get("shadow_slices"))
        if r.get("experiment") != "oit" or slices is None or not oitres.is_ok(r):
            continue
        key = (os.path.basename(r.get("scene", "")), r.get("technique", ""),
               int(oitres.to_float(r.get("shadow_resolution")) or 0), int(slices))
        case = cases.setdefault(key, {"rmse": r.get("shadow_rmse"), "max": r.get("shadow_max_abs_error"),
                                      "bytes": oitres.to_float(r.get("shadow_map_bytes"))})
        case[r.get("pass")] = oitres.to_float(r.get("median_ms"))

    def ms(v):
        return "" if v is None else f"{v:.0f}"

    def num(v):
        x = oitres.to_float(v)
        return "" if x is None else f"{x:.3g}"

    lines = [TABLE_HEADER, "|" + "---|" * TABLE_HEADER.count(" | ") + "---|"]
    for (scene, technique, res, slices), c in sorted(cases.items()):
        size = "" if c["bytes"] is None else f"{c['bytes'] / 1e6:.1f} M"
        lines.append(f"| {scene} | {technique} | {res} | {slices} | {num(c['rmse'])} | {num(c['max'])} | "
                     f"{ms(c.get('shadow-sort'))} | {ms(c.get('shadow-map'))} | {ms(c.get('capture'))} | {size} |")
    return lines


def series(rows):
    """{(scene, technique, resolution): {slices: {"rmse", "max", pass: ms}}} from ok rows."""
    out = defaultdict(lambda: defaultdict(dict))
    for r in rows:
        slices = oitres.to_float(r.get("shadow_slices"))
        if r.get("experiment") != "oit" or slices is None or not oitres.is_ok(r):
            continue
        key = (os.path.basename(r.get("scene", "")), r.get("technique", ""), r.get("shadow_resolution", ""))
        point = out[key][int(slices)]
        if r.get("pass") in PASSES:
            point[r["pass"]] = oitres.to_float(r.get("median_ms"))
        for column, name in (("shadow_rmse", "rmse"), ("shadow_max_abs_error", "max")):
            if oitres.to_float(r.get(column)) is not None:
                point[name] = oitres.to_float(r.get(column))
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
    ap.add_argument("--out", help="the figure (PNG, SVG or PDF by its extension)")
    ap.add_argument("--table", action="store_true", help="print the Markdown table of the rows instead")
    args = ap.parse_args(argv)
    if not args.out and not args.table:
        ap.error("give --out FIGURE or --table")
    if args.out and not args.table:
        ext = os.path.splitext(args.out)[1].lstrip(".").lower()
        known = plt.gcf().canvas.get_supported_filetypes()
        if ext not in known:
            ap.error(f"--out {args.out}: the extension names no figure format (known: {', '.join(sorted(known))})")
    rows = []
    try:
        for path in args.csv:
            rows += oitres.Run.load(path).rows
    except oitres.ResultsError as e:
        print(f"shadow_plot.py: {e}", file=sys.stderr)
        return 2
    data = series(rows)
    if not data:
        print("shadow_plot.py: no valid oit rows with shadow_slices (a scene declaring self-shadowing)",
              file=sys.stderr)
        return 2
    if args.table:
        print("\n".join(table_rows(rows)))
        return 0
    plot(data).savefig(args.out, dpi=120)
    print(args.out)
    return 0


if __name__ == "__main__":
    sys.exit(cli.run(main))
