"""The fleet page: one static HTML page from the store (template: fleet.html beside this file): the
matrix of drivers/GPUs x presets with status counts, the fastest technique per scene view per GPU, and
the papers' tables (results/published/) with every GPU's numbers beside the paper's."""
import csv
import html
import os
import string

TEMPLATE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "fleet.html")
STATUSES = ("ok", "invalid", "unsupported", "error", "timeout")


def gpu_of(r):
    return f"{r['driver'] or '?'} | {r['gl_renderer'] or '?'}"


def status_matrix(store):
    rows = store.query("SELECT runs.driver, runs.gl_renderer, COALESCE(runs.preset, '') AS preset, r.status, "
                       "COUNT(*) AS n FROM rows r JOIN runs ON runs.run_id = r.run_id WHERE r.pass = 'total' "
                       "GROUP BY runs.driver, runs.gl_renderer, runs.preset, r.status")
    cells = {}
    for r in rows:
        cells.setdefault((gpu_of(r), r["preset"] or "(none)"), {})[r["status"]] = r["n"]
    return cells


def fastest(store):
    """{(scene, view): {gpu: (technique, median_ms)}} over the oit experiment's ok total rows."""
    rows = store.query("SELECT runs.driver, runs.gl_renderer, r.scene, r.view, r.technique, r.median_ms "
                       "FROM rows r JOIN runs ON runs.run_id = r.run_id WHERE r.experiment = 'oit' AND "
                       "r.pass = 'total' AND r.status = 'ok' AND r.median_ms IS NOT NULL AND r.technique IS NOT NULL")
    best = {}
    for r in rows:
        cell = best.setdefault((r["scene"] or "", r["view"] or ""), {})
        g = gpu_of(r)
        if g not in cell or r["median_ms"] < cell[g][1]:
            cell[g] = (r["technique"], r["median_ms"])
    return best


def paper_tables(store, published_dir):
    """[(file, [(paper row, {gpu: our median})])] for the papers' rows in ms with a technique and scene."""
    ours = {}
    for r in store.query("SELECT runs.driver, runs.gl_renderer, r.scene, r.view, r.technique, r.median_ms FROM rows r "
                         "JOIN runs ON runs.run_id = r.run_id WHERE r.experiment = 'oit' AND r.pass = 'total' AND "
                         "r.status = 'ok' AND r.median_ms IS NOT NULL"):
        ours.setdefault((r["technique"], r["scene"], r["view"] or ""), {}).setdefault(gpu_of(r), []).append(
            r["median_ms"])
    out = []
    for name in sorted(os.listdir(published_dir)) if os.path.isdir(published_dir) else []:
        if not name.endswith(".csv"):
            continue
        with open(os.path.join(published_dir, name), newline="", encoding="utf-8") as f:
            rows = [r for r in csv.DictReader(f) if r.get("unit") == "ms" and r.get("technique")]
        if rows:
            out.append((name, [(r, {g: min(v) for g, v in ours.get((r["technique"], r["scene"], r["view"]), {}).items()})
                               for r in rows]))
    return out


def _table(head, body):
    e = html.escape
    return ("<table><tr>" + "".join(f"<th>{e(str(h))}</th>" for h in head) + "</tr>" +
            "".join("<tr>" + "".join(f"<td>{e(str(c))}</td>" for c in row) + "</tr>" for row in body) + "</table>")


def page(store, published_dir):
    cells = status_matrix(store)
    gpus = sorted({g for g, _ in cells})
    presets = sorted({p for _, p in cells})
    matrix = _table(["driver | renderer"] + presets,
                    [[g] + [" ".join(f"{s} {cells.get((g, p), {}).get(s)}" for s in STATUSES
                                     if cells.get((g, p), {}).get(s)) for p in presets] for g in gpus])
    best = fastest(store)
    best_gpus = sorted({g for cell in best.values() for g in cell})
    fastest_html = _table(["scene", "view"] + best_gpus,
                          [[s, v] + [f"{cell[g][0]} {cell[g][1]:.3g} ms" if g in cell else "" for g in best_gpus]
                           for (s, v), cell in sorted(best.items())])
    papers = []
    for name, rows in paper_tables(store, published_dir):
        papers.append(f"<h3>{html.escape(name)}</h3>" + _table(
            ["table", "gpu", "scene", "view", "technique", "paper ms"] + best_gpus,
            [[r["table"], r["gpu"], r["scene"], r["view"], r["technique"], r["value"]] +
             [f"{mine[g]:.3g}" if g in mine else "" for g in best_gpus] for r, mine in rows]))
    with open(TEMPLATE, encoding="utf-8") as f:
        template = string.Template(f.read())
    runs = store.query("SELECT COUNT(*) AS n FROM runs")[0]["n"]
    return template.substitute(store=html.escape(store.name), runs=runs, matrix=matrix, fastest=fastest_html,
                               papers="\n".join(papers) or "<p>No paper tables found.</p>")
