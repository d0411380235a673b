"""Bencher's metric format (BMF JSON) from the store: one benchmark per case (its case key), the measure
`latency` in ms: value = median_ms, lower_value/upper_value = the row's 95% interval (ci_lo_ms, ci_hi_ms;
the median where the run had too few samples for one). A run's testbed is its renderer and driver, its
branch and hash come from its tags (branch=, hash= or commit=; else the git_sha), so a team's Bencher
server gets its thresholds and alerts:  bencher run --adapter json --file F --testbed T --branch B --hash H"""
import re

from oitbench.store import queries


def testbed(run):
    name = f"{run.get('gl_renderer') or 'unknown'} {run.get('driver') or ''}".strip()
    return re.sub(r"[^A-Za-z0-9._-]+", "-", name).strip("-")[:64]


def export_run(store, run_id):
    """(BMF dict, {testbed, branch, hash}) for one run's ok total rows."""
    run = store.query("SELECT * FROM runs WHERE run_id = ?", (run_id,))[0]
    tags = {t["key"]: t["value"] for t in store.query("SELECT key, value FROM run_tags WHERE run_id = ?", (run_id,))}
    bmf = {}
    for r in store.query("SELECT case_key, median_ms, ci_lo_ms, ci_hi_ms FROM rows WHERE run_id = ? AND "
                         "status = 'ok' AND median_ms IS NOT NULL ORDER BY case_key", (run_id,)):
        lo = r["ci_lo_ms"] if r["ci_lo_ms"] is not None else r["median_ms"]
        hi = r["ci_hi_ms"] if r["ci_hi_ms"] is not None else r["median_ms"]
        bmf[r["case_key"]] = {"latency": {"value": r["median_ms"], "lower_value": lo, "upper_value": hi}}
    sha = (run.get("git_sha") or "").replace("-dirty", "")
    meta = {"testbed": testbed(run), "branch": tags.get("branch", "main"),
            "hash": tags.get("hash") or tags.get("commit") or sha}
    return bmf, meta


def latest_run(store, flt):
    runs = queries.runs(store, flt)
    return runs[-1]["run_id"] if runs else None
