"""Knowles 2014's tables, computed once: the speedup over the baseline (techniques.BASELINE) per view (table 3), its mean and best
over the views (table 1), and the paper's own numbers for both. scripts/tables.py (through
papers.summary_rows), scripts/findings.py and scripts/oit_knowles_summary.py all take them from here."""
import statistics

from oitbench import results as oitres
from oitbench import techniques

BASELINE = techniques.BASELINE
SOURCE = "knowles2014-rbs"
# Table 1's four figures per technique, in the paper's column order.
TABLE1_METRICS = ("average_total", "average_resolve", "best_total", "best_resolve")
# Our stand-ins for the papers' models (scenes/engine-grid.json, scenes/house.json): same view names.
PAPER_SCENE = {"engine-grid": "powerplant", "house": "atrium"}
# The paper ran CUDA kernels where we run compute shaders: our resolve scheme -> the paper's, same sort.
PAPER_SCHEME = {"CS": "CUDA"}


def paper_name(technique):
    """Knowles 2014's name for our technique: our compute-shader resolves stand in for its CUDA ones
    (PAPER_SCHEME), named by scheme and sort as the paper names them."""
    scheme = PAPER_SCHEME.get(techniques.scheme(technique))
    return f"{scheme}-{techniques.sort(technique)}" if scheme else technique


def ratio(base, x):
    """Baseline time / technique time, None where either is missing or the time is 0."""
    return base / x if base is not None and x else None


def view_speedups(rows, pass_, paired=True):
    """{(scene, view): {technique: BASELINE's time / technique time}} of one pass of the oit rows given,
    for the views that have a BASELINE row. paired: a row's own `speedup` where its baseline is BASELINE
    (schema 4: the two ran side by side in one group) is taken before the ratio of the two medians.
    Where a view has two rows of a technique the last one counts."""
    times, pairs = {}, {}
    for r in rows:
        if r["pass"] != pass_:
            continue
        view = (r["scene"], r["view"])
        times.setdefault(view, {})[r["technique"]] = oitres.to_float(r.get("median_ms"))
        if paired and r.get("speedup") and r.get("baseline") == "technique=" + BASELINE:
            pairs.setdefault(view, {})[r["technique"]] = oitres.to_float(r["speedup"])
    return {k: {t: pairs.get(k, {}).get(t) or ratio(v[BASELINE], x) for t, x in v.items()}
            for k, v in times.items() if BASELINE in v}


def summarize(speedups, metric):
    """Table 1's figure `metric` (average_* or best_*, with or without _speedup_vs_BASELINE) of a list of
    per-view speedups: their mean or their maximum; None for an empty list."""
    if not speedups:
        return None
    return max(speedups) if metric.startswith("best") else statistics.mean(speedups)


def table1(resolve, total, techniques):
    """Table 1's layout of ours: {technique: {average_total, average_resolve, best_total, best_resolve}}
    over the views of `resolve` and `total` (view_speedups() results) where a technique has a speedup;
    techniques without one in either pass are left out. Keys follow `techniques`' order."""
    out = {}
    for t in techniques:
        per = {"resolve": [s[t] for s in resolve.values() if s.get(t) is not None],
               "total": [s[t] for s in total.values() if s.get(t) is not None]}
        if not per["resolve"] or not per["total"]:
            continue
        out[t] = {m: summarize(per[m.split("_")[1]], m) for m in TABLE1_METRICS}
    return out


class Paper:
    """The paper's tables 1 and 3 from results/published's tidy rows (papers.load_paper)."""

    def __init__(self, paper_rows):
        self.table3, self.table1 = {}, {}
        for r in paper_rows:
            if r.get("source") != SOURCE:
                continue
            value = oitres.to_float(r["value"])
            if r["table"] == "3":
                key = (r["scene"].lower(), r["view"].lower(), r["technique"], r["metric"].split("_")[0])
                self.table3.setdefault(key, value)
            elif r["table"] == "1":
                self.table1.setdefault((r["technique"], r["metric"]), value)

    def speedup(self, technique, scene, view, pass_):
        """Table 3's speedup of our `technique` (read as paper_name()) on our scene (the stand-ins read as
        the paper's models) and view, for pass_ resolve or total; None where the paper has none."""
        key = (PAPER_SCENE.get(scene, scene).lower(), view.lower(), paper_name(technique), pass_)
        return self.table3.get(key)

    def summary(self, technique, metric):
        """Table 1's figure (one of TABLE1_METRICS) for our technique; None where the paper has none."""
        return self.table1.get((paper_name(technique), metric + "_speedup_vs_" + BASELINE))
