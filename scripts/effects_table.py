#!/usr/bin/env python3
"""What each scene effect costs and saves (docs/effects.md): per scene, view and technique, the cases
that ran different effect sets (effects=transparency,opaque+transparency) side by side: the fragments
each captured, those the opaque depth hid, the median of each effect's own passes, the total, and the
total's ratio to the first effect set's. Only valid (ok) rows; cases of a single effect set are left out.

  scripts/effects_table.py results/effects/house-opaque-128.csv     # the Markdown table docs/effects.md holds
"""
import argparse
import sys
from collections import defaultdict


from oitbench import results as oitres  # noqa: E402
from oitbench import cli  # noqa: E402

EFFECT_PASSES = ("shadow-sort", "shadow-map", "opaque")  # micro/oit/scene/scene_passes.cpp: effect_pass_names()
HEADER = ("| scene | view | technique | effects | fragments captured | hidden_fragments | "
          + " | ".join(f"{p} ms" for p in EFFECT_PASSES) + " | technique's passes ms | total ms | total vs first |")


def fmt(v, digits=3):
    if v is None:
        return ""
    return f"{v:,.0f}" if abs(v) >= 1000 else f"{v:.{digits}g}"


def table(rows):
    cases = defaultdict(dict)  # (scene, view, technique) -> effects -> pass -> row
    for r in rows:
        if r.get("experiment") != "oit" or not oitres.is_ok(r) or not r.get("effects"):
            continue
        label = r.get("technique", "")
        if r.get("nodes"):
            label += f"/{r['nodes']}"
        cases[(r.get("scene", ""), r.get("view", ""), label)].setdefault(r["effects"], {})[r["pass"]] = r
    lines = [HEADER, "|" + "---|" * (HEADER.count("|") - 1)]
    for key in sorted(cases):
        sets = cases[key]
        if len(sets) < 2:
            continue
        order = sorted(sets, key=lambda e: (len(e.split("+")), e))
        first_total = None
        for e in order:
            passes = sets[e]
            total = passes.get("total")
            if total is None:
                continue
            t = oitres.to_float(total.get("median_ms"))
            first_total = t if first_total is None else first_total
            effect_ms = [oitres.to_float(passes[p]["median_ms"]) if p in passes else None for p in EFFECT_PASSES]
            own = [oitres.to_float(r["median_ms"]) for p, r in passes.items() if p != "total" and p not in EFFECT_PASSES]
            own_ms = sum(own) if own else (t if not any(effect_ms) else None)
            ratio = t / first_total if t is not None and first_total else None
            lines.append("| " + " | ".join([
                key[0], key[1], key[2], e, fmt(oitres.to_float(total.get("total_fragments"))),
                fmt(oitres.to_float(total.get("hidden_fragments"))),
                *[fmt(x) for x in effect_ms], fmt(own_ms), fmt(t), f"{ratio:.2f}x" if ratio else ""]) + " |")
    return "\n".join(lines) + "\n"


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    ap.add_argument("csv", nargs="+", help="oit summary CSVs (oitbench run --out)")
    args = ap.parse_args(argv)
    rows = []
    for path in args.csv:
        try:
            rows += oitres.Run.load(path).rows
        except oitres.ResultsError as e:
            print(f"effects_table.py: {e}", file=sys.stderr)
            return 2
    out = table(rows)
    if out.count("\n") <= 2:
        print("effects_table.py: no valid oit rows with more than one effect set per case", file=sys.stderr)
        return 2
    sys.stdout.write(out)
    return 0


if __name__ == "__main__":
    sys.exit(cli.run(main))
