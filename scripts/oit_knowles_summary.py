#!/usr/bin/env python3
"""Resolve and total speedups over the baseline technique from an `oitbench run --preset knowles2014` CSV,
per view and averaged like Knowles 2014 table 1, beside the paper's tables 1 and 3 (our compute-shader
resolves beside its CUDA ones).

usage: scripts/oit_knowles_summary.py RESULTS.csv [PAPER_TABLES_DIR]  (markdown on stdout)
PAPER_TABLES_DIR holds knowles2014_table1_summary.csv and knowles2014_table3_speedups.csv (default: the
repository's results/published).
"""
import argparse
import sys
from pathlib import Path

from oitbench import cli
from oitbench import knowles
from oitbench import results as oitres
from oitbench import techniques

ORDER = ["planes", "hairball", "hair", "smoke", "engine-grid", "house"]
TECHNIQUES = techniques.exact_in_paper_order()  # the paper's order, from scripts/techniques.json


def paper_table(path):
    """The rows of one paper table, or [] when the file is not there."""
    if not path.exists():
        return []
    header, rows = oitres.read_csv(str(path))
    missing = [c for c in ("source", "table", "scene", "view", "technique", "metric", "value") if c not in header]
    if missing:
        raise oitres.ResultsError(f"{path}:1: not a paper table (no column {', '.join(missing)})")
    for line, r in enumerate(rows, 2):
        if oitres.to_float(r["value"]) is None:
            raise oitres.ResultsError(f"{path}:{line}: value '{r['value']}' is not a number")
    return rows


def number(x):
    return float("nan") if x is None else x


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("csv", help="an `oitbench run --preset knowles2014` summary CSV")
    ap.add_argument("paper_dir", nargs="?", help="the paper tables' folder (default: results/published)")
    args = ap.parse_args(argv)
    run = oitres.Run.load(args.csv)
    missing = [c for c in ("scene", "view", "technique") if c not in run.header]
    if missing:
        raise oitres.ResultsError(f"{args.csv}:1: no oit rows to summarize (no column {', '.join(missing)})")
    if not run.rows_of("oit"):
        raise oitres.ResultsError(f"{args.csv}: no oit rows to summarize (run `oitbench run --preset knowles2014`)")
    rows = [r for r in run.rows_of("oit") if r["status"] == "ok" and oitres.to_float(r["median_ms"]) is not None]
    paper_dir = Path(args.paper_dir) if args.paper_dir else \
        Path(__file__).resolve().parent.parent / "results" / "published"
    if not paper_dir.is_dir():
        raise oitres.ResultsError(f"{paper_dir}: no such folder (PAPER_TABLES_DIR)")
    published = knowles.Paper(paper_table(paper_dir / "knowles2014_table3_speedups.csv") +
                          paper_table(paper_dir / "knowles2014_table1_summary.csv"))
    res = {(r["scene"], r["view"], r["technique"], r["pass"]): r for r in rows}
    views = sorted({(r["scene"], r["view"]) for r in rows},
                   key=lambda sv: (ORDER.index(sv[0]) if sv[0] in ORDER else 9, sv[1]))
    # The ratio of the medians (no paired speedups), every row in the per-view table, the valid ones in table 1.
    rsp, tsp = (knowles.view_speedups(rows, p, paired=False) for p in ("resolve", "total"))
    valid = {}  # (scene, view) -> the techniques whose resolve was valid
    print("| scene | view | technique | resolve ms | total ms | resolve speedup | total speedup | paper resolve / total (Titan) | valid | notes |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for scene, view in views:
        for t in TECHNIQUES:
            r, tot = res.get((scene, view, t, "resolve")), res.get((scene, view, t, "total"))
            if not r or not tot:
                continue
            sr = number(rsp.get((scene, view), {}).get(t))
            st = number(tsp.get((scene, view), {}).get(t))
            if r["valid"] == "1":
                valid.setdefault((scene, view), set()).add(t)
            pr, pt = published.speedup(t, scene, view, "resolve"), published.speedup(t, scene, view, "total")
            paper = f"{pr}x / {pt}x" if pr else "-"
            notes = tot.get("bma_auto_choice", "") or ""
            print(f"| {scene} | {view} | {t} | {float(r['median_ms']):.1f} | {float(tot['median_ms']):.1f} | {sr:.2f}x | {st:.2f}x "
                  f"| {paper} | {r['valid']} | {notes} |")
    print()
    print("Averages over the views (table 1's layout; paper: GTX Titan, 1920x1080, its own scenes)")
    print()
    print("| technique | avg total | avg resolve | best total | best resolve | paper avg total | paper avg resolve | paper best total | paper best resolve |")
    print("|---|---|---|---|---|---|---|---|---|")
    def kept(speedups):
        return {v: {t: s for t, s in speedups.get(v, {}).items() if t in ts} for v, ts in valid.items()}

    for t, figures in knowles.table1(kept(rsp), kept(tsp), TECHNIQUES).items():
        ps = " | ".join(f"{x}x" if x is not None else "-" for x in (published.summary(t, m) for m in figures))
        print(f"| {t} | " + " | ".join(f"{x:.2f}x" for x in figures.values()) + f" | {ps} |")
    print()
    print("| scene | view | fragments | peak depth | MAX_FRAGS | capture fragments/s | node_pool_bytes |")
    print("|---|---|---|---|---|---|---|")
    for scene, view in views:
        r = res.get((scene, view, knowles.BASELINE, "total"))
        if r:
            rate = oitres.to_float(r.get("fragments_per_s"))
            print(f"| {scene} | {view} | {r.get('total_fragments', '')} | {r.get('peak_depth', '')} "
                  f"| {r.get('max_frags_used') or r.get('max_frags', '')} "
                  f"| {f'{rate / 1e6:.1f} M' if rate is not None else '-'} | {r.get('node_pool_bytes', '')} |")


if __name__ == "__main__":
    sys.exit(cli.run(main))
