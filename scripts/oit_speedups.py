#!/usr/bin/env python3
"""Resolve speedups over BASE-IS from an `oitbench run oit` CSV, beside Knowles 2014's table 3.

usage: scripts/oit_speedups.py RESULTS.csv [PAPER_TABLE3.csv]  (markdown table on stdout)
"""
import csv
import sys
from pathlib import Path

ORDER = ["planes", "hairball", "smoke", "engine-grid", "house"]
TECHNIQUES = ["BASE-IS", "BASE-IMS", "BASE-RBS-L", "BMA-IS", "BMA-IMS", "BMA-RBS-L", "CPU-NATIVE"]


def main():
    rows = list(csv.DictReader(open(sys.argv[1])))
    default_paper = Path(__file__).resolve().parent.parent / "results" / "paper" / "knowles2014_table3_speedups.csv"
    paper_path = Path(sys.argv[2]) if len(sys.argv) > 2 else default_paper
    paper = {}
    if paper_path.exists():
        for r in csv.DictReader(open(paper_path)):
            if r["metric"] == "resolve_speedup_vs_BASE-IS":
                paper[(r["scene"], r["view"].lower(), r["technique"])] = r["value"]
    res = {(r["scene"], r["view"], r["technique"], r["pass"]): r for r in rows if r["status"] == "ok"}
    scenes = sorted({(r["scene"], r["view"]) for r in rows}, key=lambda sv: (ORDER.index(sv[0]) if sv[0] in ORDER else 9, sv[1]))
    print("| scene | view | technique | capture ms | resolve ms (MAD) | resolve speedup vs BASE-IS | paper (GTX Titan) | valid | max_abs_error |")
    print("|---|---|---|---|---|---|---|---|---|")
    for scene, view in scenes:
        base = res.get((scene, view, "BASE-IS", "resolve"))
        for t in TECHNIQUES:
            r = res.get((scene, view, t, "resolve"))
            if not r:
                continue
            c = res[(scene, view, t, "capture")]
            speedup = float(base["median_ms"]) / float(r["median_ms"]) if base else float("nan")
            p = "1.0x" if t == "BASE-IS" and (scene, view, "BMA-IS") in paper else (paper.get((scene, view, t), "-") + ("x" if (scene, view, t) in paper else ""))
            print(f"| {scene} | {view} | {t} | {float(c['median_ms']):.0f} | {float(r['median_ms']):.0f} ({float(r['mad_ms']):.0f}) "
                  f"| {speedup:.2f}x | {p} | {r['valid']} | {float(r['max_abs_error']):.2g} |")
    print()
    print("| scene | view | polygons | fragments | peak depth | mean depth | MAX_FRAGS | capture fragments/s (BASE-IS) | tied pixels | BMA intervals (top:pixels) |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for scene, view in scenes:
        r = res.get((scene, view, "BASE-IS", "total"))
        b = res.get((scene, view, "BMA-IS", "total"))
        if r:
            print(f"| {scene} | {view} | {r['polygons']} | {r['total_fragments']} | {r['peak_depth']} | {float(r['mean_depth']):.1f} "
                  f"| {r['max_frags']} | {float(r['fragments_per_s']) / 1e6:.1f} M | {r.get('tied_pixels', '')} | {b['bma_intervals'] if b else ''} |")


if __name__ == "__main__":
    main()
