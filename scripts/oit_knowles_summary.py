#!/usr/bin/env python3
"""Resolve and total speedups over BASE-IS from an `oitbench run --preset knowles2014` CSV, per view
and averaged like Knowles 2014 table 1, beside the paper's tables 1 and 3 (CS-* beside CUDA-*).

usage: scripts/oit_knowles_summary.py RESULTS.csv [PAPER_TABLES_DIR]  (markdown on stdout)
PAPER_TABLES_DIR holds knowles2014_table1_summary.csv and knowles2014_table3_speedups.csv (default: the
repository's results/published).
"""
import csv
import statistics
import sys
from pathlib import Path

ORDER = ["planes", "hairball", "hair", "smoke", "engine-grid", "house"]
# Our stand-ins for the paper's models (scenes/engine-grid.json, scenes/house.json): same view names.
PAPER_SCENE = {"engine-grid": "powerplant", "house": "atrium"}
TECHNIQUES = ["BASE-IS", "BASE-IMS", "BASE-RBS-L", "RBS-G", "CS-IS", "CS-IMS", "CS-RBS-L",
              "BMA-IS", "BMA-IMS", "BMA-RBS-L", "BMA-AUTO", "CPU-NATIVE"]


def paper_name(t):
    return "CUDA-" + t[3:] if t.startswith("CS-") else t


def main():
    rows = [r for r in csv.DictReader(open(sys.argv[1])) if r["status"] == "ok"]
    paper_dir = Path(sys.argv[2]) if len(sys.argv) > 2 else Path(__file__).resolve().parent.parent / "results" / "published"
    t3, t1 = {}, {}
    if (paper_dir / "knowles2014_table3_speedups.csv").exists():
        for r in csv.DictReader(open(paper_dir / "knowles2014_table3_speedups.csv")):
            t3[(r["scene"], r["view"].lower(), r["technique"], r["metric"].split("_")[0])] = float(r["value"])
    if (paper_dir / "knowles2014_table1_summary.csv").exists():
        for r in csv.DictReader(open(paper_dir / "knowles2014_table1_summary.csv")):
            t1[(r["technique"], r["metric"])] = float(r["value"])
    res = {(r["scene"], r["view"], r["technique"], r["pass"]): r for r in rows}
    views = sorted({(r["scene"], r["view"]) for r in rows},
                   key=lambda sv: (ORDER.index(sv[0]) if sv[0] in ORDER else 9, sv[1]))
    speed = {}  # (technique, resolve|total) -> [speedups over views]
    print("| scene | view | technique | resolve ms | total ms | resolve speedup | total speedup | paper resolve / total (Titan) | valid | notes |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for scene, view in views:
        base = {p: res.get((scene, view, "BASE-IS", p)) for p in ("resolve", "total")}
        for t in TECHNIQUES:
            r, tot = res.get((scene, view, t, "resolve")), res.get((scene, view, t, "total"))
            if not r or not tot:
                continue
            sr = float(base["resolve"]["median_ms"]) / float(r["median_ms"]) if base["resolve"] else float("nan")
            st = float(base["total"]["median_ms"]) / float(tot["median_ms"]) if base["total"] else float("nan")
            if r["valid"] == "1":
                speed.setdefault((t, "resolve"), []).append(sr)
                speed.setdefault((t, "total"), []).append(st)
            key = (PAPER_SCENE.get(scene, scene), view.lower(), paper_name(t))
            pr, pt = t3.get(key + ("resolve",)), t3.get(key + ("total",))
            paper = f"{pr}x / {pt}x" if pr else "-"
            notes = tot.get("bma_auto_choice", "") or ""
            print(f"| {scene} | {view} | {t} | {float(r['median_ms']):.1f} | {float(tot['median_ms']):.1f} | {sr:.2f}x | {st:.2f}x "
                  f"| {paper} | {r['valid']} | {notes} |")
    print()
    print("Averages over the views (table 1's layout; paper: GTX Titan, 1920x1080, its own scenes)")
    print()
    print("| technique | avg total | avg resolve | best total | best resolve | paper avg total | paper avg resolve | paper best total | paper best resolve |")
    print("|---|---|---|---|---|---|---|---|---|")
    for t in TECHNIQUES:
        tv, rv = speed.get((t, "total")), speed.get((t, "resolve"))
        if not tv:
            continue
        p = [t1.get((paper_name(t), m + "_speedup_vs_BASE-IS")) for m in
             ("average_total", "average_resolve", "best_total", "best_resolve")]
        ps = " | ".join(f"{x}x" if x is not None else "-" for x in p)
        print(f"| {t} | {statistics.mean(tv):.2f}x | {statistics.mean(rv):.2f}x | {max(tv):.2f}x | {max(rv):.2f}x | {ps} |")
    print()
    print("| scene | view | fragments | peak depth | MAX_FRAGS | capture fragments/s | node_pool_bytes |")
    print("|---|---|---|---|---|---|---|")
    for scene, view in views:
        r = res.get((scene, view, "BASE-IS", "total"))
        if r:
            print(f"| {scene} | {view} | {r['total_fragments']} | {r['peak_depth']} | {r.get('max_frags_used') or r['max_frags']} "
                  f"| {float(r['fragments_per_s']) / 1e6:.1f} M | {r.get('node_pool_bytes', '')} |")


if __name__ == "__main__":
    main()
