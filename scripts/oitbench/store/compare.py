"""compare: two sets of runs from the store, case by case, with compare.py's rules (oitbench.compare's
Case and Comparison, unchanged): the ratio of medians (B / A: above 1 is slower), its 95% interval (a
bootstrap over the samples: a run's --raw repetitions, or the runs' medians when a set has several runs),
the between-run noise band max(min_effect, exp(k * sqrt(cv_a^2 + cv_b^2))) and whether the two sets'
values overlap; SLOWER/FASTER only when the interval excludes 1, the ratio is beyond the band and the
values are apart."""
import argparse
import random

from oitbench import compare as oitcompare
from oitbench import results as oitres
from oitbench import stats
from oitbench.store import queries

MIN_EFFECT = oitcompare.MIN_EFFECT
NO_DIFFERENCE, IN_BAND, OVERLAP, CHANGED = (oitcompare.NO_DIFFERENCE, oitcompare.IN_BAND, oitcompare.OVERLAP,
                                            oitcompare.CHANGED)


def side(rows, samples_of):
    """An oitbench.compare.Case for one case in one set of runs."""
    if len(rows) == 1:
        r = rows[0]
        text = {k: "" if v is None else str(v) for k, v in r.items()}
        return oitcompare.Case(text, samples_of(r["run_id"], r["case_key"]))
    medians = [r["median_ms"] for r in rows]
    row = {"median_ms": str(oitres.median(medians)), "mad_ms": str(stats.mad(medians)), "samples": str(len(rows)),
           "min_ms": str(min(medians)), "max_ms": str(max(medians))}
    return oitcompare.Case(row, medians)


def compare(store, filter_a, filter_b, experiment=None, case_like=None, min_effect=MIN_EFFECT):
    """[Comparison] for every ok case both sets have, in case order (each with .key, .ratio, .ci, .kind,
    .verdict); and warnings: a hostname that names different machines across the two sets."""
    def ok_rows(flt):
        by_case = {}
        for r in queries.case_results(store, flt, experiment, case_like):
            if r["status"] == "ok" and r["median_ms"]:
                by_case.setdefault(r["case_key"], []).append(r)
        return by_case

    a, b = ok_rows(filter_a), ok_rows(filter_b)

    def samples_of(run_id, key):
        return queries.samples_of(store, run_id, key)

    args = argparse.Namespace(bootstrap=oitcompare.BOOTSTRAP, min_effect=min_effect, noise_k=oitcompare.NOISE_K)
    rng = random.Random(oitcompare.SEED)
    out, warnings = [], set()
    for key in sorted(set(a) & set(b)):
        out.append(oitcompare.Comparison(key, "B", side(a[key], samples_of), side(b[key], samples_of), args, rng))
        machines = {}
        for r in a[key] + b[key]:
            if r["hostname"] and r["machine_id"]:
                machines.setdefault(r["hostname"], set()).add(r["machine_id"])
        for host, ids in machines.items():
            if len(ids) > 1:
                warnings.add(f"hostname '{host}' names {len(ids)} machines (machine_id {', '.join(sorted(ids))}): "
                             "the sets may differ by machine, not only by what you compare")
    return out, sorted(warnings)
