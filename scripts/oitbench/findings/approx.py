"""FINDINGS.md's sections on approximate OIT: the approximate techniques, error against time, Gaussian splats and line
rendering."""
import statistics

from oitbench import figures as plot
from oitbench import papers as tables
from oitbench import techniques
from oitbench.findings.common import (
    BASE_IMS, BLENDS, DASH, PER_PIXEL_ARRAY, UNSORTED, WEIGHTED_BLEND, RMSE_FLOOR, f_err, f_m, f_ms, f_num, f_x, field, missing, ms, num, ratio, res,
    scene_key, sizes_of, span, table, verdict, view_key, word)
EXACT = set(techniques.names("exact"))  # the exact family: not MBOIT, STOCHASTIC, WOIT or SLAB, which are approximate too


def approx_key(r):
    return (r["technique"], r.get("nodes", ""), r.get("storage", ""), r.get("wboit_weight", ""))


def approx_label(r):
    label = plot.oit_label(r)
    if r["technique"] in PER_PIXEL_ARRAY and r.get("storage"):
        label += f" {r['storage']}"
    return label


def section_approx(f):
    name = "bruell2018-approx"
    lines = ["## Approximate OIT", "",
             "What accuracy costs in time: Brüll 2018 chapters 5–6, Tables 5.1, 6.1–6.3.", ""]
    rows = f.rows(name, "oit")
    if not rows:
        return lines + missing(name)
    scenes = sorted({r["scene"] for r in rows}, key=scene_key)
    cases = {}
    for r in rows:
        cases.setdefault(approx_key(r), {})[r["scene"]] = r
    def order(k):
        r1 = next(iter(cases[k].values()))
        if k[0] in PER_PIXEL_ARRAY:
            return (2, PER_PIXEL_ARRAY.index(k[0]), int(r1.get("nodes") or 0), r1.get("storage", ""))
        return (0 if k[0] in BLENDS else 1, 0, 0, plot.oit_label(r1))

    keys = sorted(cases, key=order)
    body = []
    for k in keys:
        r1 = next(iter(cases[k].values()))
        body.append([approx_label(r1)] + [x for s in scenes for x in
                                          (f_ms(ms(cases[k].get(s))), f_err(num(cases[k].get(s), "rmse")))])
    r0 = rows[0]
    lines += [f"`presets/{name}.csv` ({res(r0)}, `{r0.get('detail', '')}` scenes, view {r0['view']}, "
              f"{f.reps(name, r0)}): `total` ms and rmse against the exact CPU reference; per-pixel-array "
              "techniques are TECHNIQUE/nodes and their storage.", ""]
    lines += table(["technique"] + [x for s in scenes for x in (f"{s} ms", f"{s} rmse")], body)

    def t(tech, nodes, storage, scene):
        return f.median(name, "oit", technique=tech, nodes=nodes, storage=storage, scene=scene)

    # The thesis's comparisons (results/published/tables.json): which technique against which, in which storage.
    comps = [(f"{a}/{b} (Table {pt.table})", pt.table, a, b, sa, sb) for pt in tables.TABLES
             if pt.source == "bruell2018-thesis" and name in pt.presets for a, b, sa, sb in pt.compare]
    body, found = [], {}
    for label, tab, a, b, sa, sb in comps:
        nodes = sizes_of([r for r in rows if r["technique"] == a], "nodes")
        row = [label, " / ".join(map(str, nodes))]
        for pscene in ("powerplant", "village"):
            row.append(" / ".join(f_x(ratio(f.paper("bruell2018-thesis", tab, a, "total_time", pscene, n),
                                            f.paper("bruell2018-thesis", tab, b, "total_time", pscene, n)))
                                  for n in nodes))
        for s in scenes:
            rs = [ratio(t(a, n, sa, s), t(b, n, sb, s)) for n in nodes]
            found.setdefault(a, []).extend(rs)
            row.append(" / ".join(f_x(x) for x in rs))
        body.append(row)
    in_texture = " ".join(a for _, _, a, _, sa, _ in comps if sa == "texture3d")
    lines += [f"Time ratios beside the thesis's (GTX 1080, 800x800): ours with the interleaved layout, {in_texture} "
              "with the 3D texture, as the thesis ran them.", ""]
    lines += table(["ratio", "nodes", "thesis Powerplant", "thesis Village"] + [f"llvmpipe {s}" for s in scenes],
                   body, [False, False, True, True] + [True] * len(scenes))
    for label, tab, a, b, _, _ in comps:
        th = [ratio(f.paper("bruell2018-thesis", tab, a, "total_time", ps, n),
                    f.paper("bruell2018-thesis", tab, b, "total_time", ps, n))
              for ps in ("powerplant", "village") for n in sizes_of([r for r in rows if r["technique"] == a], "nodes")]
        lines.append(f"- {a} against {b}: {span(found.get(a, []))}x here, {verdict(found.get(a, []))}; the thesis "
                     f"{span(th)}x, {verdict(th)}.")
    _, _, a, b, _, _ = comps[0]  # Table 5.1's pair once more, both in the 3D texture
    tex = [ratio(t(a, n, "texture3d", s), t(b, n, "texture3d", s))
           for s in scenes for n in sizes_of([r for r in rows if r["technique"] == a], "nodes")]
    if any(tex):
        lines.append(f"- {a} against {b} in the 3D texture: {span(tex)}x, {verdict(tex)}.")
    for s in scenes:
        exact = {k[0]: ms(v[s]) for k, v in cases.items() if s in v and k[0] in EXACT}
        ppa = {approx_label(v[s]): ms(v[s]) for k, v in cases.items() if s in v and k[0] in PER_PIXEL_ARRAY}
        if exact and ppa:
            fe = min(exact, key=lambda k: (exact[k], k))
            fa = min(ppa, key=lambda k: (ppa[k], k))
            lines.append(f"- {s}: the fastest exact resolve, {fe} ({f_ms(exact[fe])} ms), against the fastest "
                         f"per-pixel-array approximation, {fa} ({f_ms(ppa[fa])} ms): "
                         f"{word(ratio(exact[fe], ppa[fa]))} for the exact one ({f_x(ratio(exact[fe], ppa[fa]))}x).")
    cheap_t, cheap_e = [], []
    for s in scenes:
        imsr = next((v[s] for k, v in cases.items() if k[0] == BASE_IMS and s in v), None)
        mlab = [v[s] for k, v in cases.items() if k[0] == PER_PIXEL_ARRAY[0] and s in v]
        ref = min(mlab, key=lambda r: (int(r["nodes"]), r.get("storage", ""))) if mlab else None
        for k, v in cases.items():
            if k[0] in BLENDS and s in v and (k[0] == UNSORTED or k[3] == "eq7"):
                cheap_t.append(ratio(ms(v[s]), ms(imsr)))
                cheap_e.append(ratio(num(v[s], "rmse"), num(ref, "rmse")))
    if cheap_t:
        lines.append(f"- Unsorted blending and {WEIGHTED_BLEND} (eq7) take {span(cheap_t)}x {BASE_IMS}'s time, at "
                     f"{span(cheap_e)}x the rmse of the smallest {PER_PIXEL_ARRAY[0]}.")
    diffs = [(num(r, "model_max_diff"), plot.oit_label(r), r["scene"]) for r in rows
             if num(r, "model_max_diff") is not None]
    if diffs:
        worst = max(diffs)
        flick = max((num(r, "flicker") or 0.0 for r in rows), default=0.0)
        capped = sum(num(r, "capped_updates") or 0.0 for r in rows)
        lines.append(f"- Against each technique's own CPU model: `model_max_diff` is 0 in "
                     f"{sum(1 for d in diffs if d[0] == 0)} of {len(diffs)} cases, at most "
                     f"{tables.fmt(worst[0], 2)} ({worst[1]} on {worst[2]}); `flicker` at most "
                     f"{tables.fmt(flick, 2)}; capped insertions {capped:.0f}.")
    lines += ["", "The unbounded variants (UMLAB, UAT, UHAT) trade memory bandwidth for compute. On a CPU "
              "rasteriser the nodes sit in cache while `if` runs as masked straight-line code, so only the "
              "extra compute shows, and every per-pixel-array technique inserts under a spinlock that is CPU "
              "work a GPU would hide.", ""]
    return lines


def section_error_vs_time(f):
    name = "error-vs-time"
    lines = ["## Error against time", "",
             "Every technique on every shipped scene.", ""]
    rows = f.rows(name, "oit")
    if not rows:
        return lines + missing(name)
    groups = {}
    for r in rows:
        groups.setdefault((r["scene"], r["view"], res(r)), []).append(r)
    body, ppa_ratio, on_front, wb = [], [], [], []
    for key in sorted(groups, key=lambda k: (scene_key(k[0]), view_key(k[1]))):
        g = groups[key]
        pts = [(ms(r), max(num(r, "rmse") or 0.0, RMSE_FLOOR), plot.oit_label(r), r) for r in g
               if num(r, "rmse") is not None]
        front = plot.pareto_front(pts)
        exact = [r for r in g if r["technique"] in EXACT]
        ppa = [r for r in g if r["technique"] in PER_PIXEL_ARRAY]
        fe = min(exact, key=lambda r: (ms(r), r["technique"])) if exact else None
        fa = min(ppa, key=lambda r: (ms(r), plot.oit_label(r))) if ppa else None
        ppa_ratio.append(ratio(ms(fa), ms(fe)))
        on_front += [p[2] for p in front if p[2].split("/")[0] in PER_PIXEL_ARRAY]
        u = next((r for r in g if r["technique"] == UNSORTED), None)
        w = next((r for r in g if r["technique"] == WEIGHTED_BLEND), None)
        if u and w:
            wb.append((key, ratio(ms(w), ms(u)), num(w, "rmse"), num(u, "rmse")))
        body.append([key[0], key[1], key[2],
                     "; ".join(f"{p[2]} {f_ms(p[0])} ms / {f_err(num(p[3], 'rmse'))}" for p in front),
                     f"{plot.oit_label(fe)} {f_ms(ms(fe))}" if fe else DASH,
                     f"{plot.oit_label(fa)} {f_ms(ms(fa))}" if fa else DASH, f_x(ratio(ms(fa), ms(fe)))])
    r0 = rows[0]
    lines += [f"`presets/{name}.csv` ({f.reps(name, r0)}): the Pareto front of each scene (no technique "
              f"both faster and more exact; `total` ms / rmse, rmse floored at {tables.fmt(RMSE_FLOOR, 1)} so the "
              "exact ones tie), the fastest exact resolve and the fastest per-pixel-array approximation (ms). "
              "The figure: [report/figures/presets/error-vs-time/oit.png]"
              "(report/figures/presets/error-vs-time/oit.png).", ""]
    lines += table(["scene", "view", "resolution", "Pareto front", "fastest exact", "fastest per-pixel array",
                    "array / exact"], body, [False] * 6 + [True])
    lines.append(f"- Per-pixel-array approximations on a front: {', '.join(on_front) if on_front else 'none'}; the "
                 f"fastest of them takes {span(ppa_ratio)}x the fastest exact resolve "
                 f"(against exact, {verdict(ppa_ratio, 'scenes')}).")
    both_worse = [k for k, tr, we, ue in wb if tr and tr > 1 and we is not None and ue is not None and we > ue]
    better = [k for k, tr, we, ue in wb if we is not None and ue is not None and we < ue]
    if wb:
        lines.append(f"- {WEIGHTED_BLEND} against unsorted blending: both slower and less exact on "
                     f"{', '.join(f'{k[0]} {k[1]}' for k in both_worse) or 'no scene'}; more exact on "
                     f"{', '.join(f'{k[0]} {k[1]}' for k in better) or 'no scene'}.")
    deep = [r for r in rows if r["scene"] == "planes-deep"]
    if deep:
        lines.append("- planes-deep, " + res(deep[0]) + ": " + ", ".join(
            f"{plot.oit_label(r)} {f_ms(ms(r))} ms / {f_err(num(r, 'rmse'))}" for r in sorted(deep, key=ms)) + ".")
    lines += ["", "The cheap end of each front is a blend that ignores order; the exact end is the fastest exact "
              "resolve; on this renderer the per-pixel-array approximations fall between, slower than exact "
              "and less exact than it.", ""]
    return lines


def section_lines(f):
    name = "sintorn-lines"
    lines = ["## Lines", "",
             "Hair as line primitives, the Sintorn et al. poster: the `lines` experiment.", ""]
    if not f.run(name):
        return lines + missing(name)
    poster = {int(float(r["size"])): r["paper"] for r in f.paper_pairs(name, "sintorn-poster").values()
              if r["size"] != ""}
    models = {int(float(r["size"])): r["scene"] for r in f.paper_pairs(name, "sintorn-poster").values()
              if r["size"] != ""}
    segs = sizes_of(f.rows(name, "lines"), "segments")
    body, share, rs = [], [], []
    for n in segs:
        ex = f.rows(name, "lines", technique="exact", segments=n)
        sl = {p: f.median(name, "lines", pass_=p, technique="slices", segments=n) for p in
              ("total", "keys", "sort", "blend")}
        exact = ms(ex[0]) if ex else None
        srow = f.rows(name, "lines", technique="slices", segments=n)
        rs.append(ratio(sl["total"], exact))
        share.append(ratio(sl["sort"], sl["total"]))
        body.append([f"{n:,}", f_m(num(ex[0], "total_fragments")) if ex else DASH,
                     field(ex[0], "peak_depth") if ex else DASH, f_ms(exact),
                     f"{f_ms(sl['total'])} ({f_ms(sl['keys'])} / {f_ms(sl['sort'])} / {f_ms(sl['blend'])})",
                     tables.fmt(1000 / sl["total"], 2) if sl["total"] else DASH,
                     f"{tables.fmt(poster[n], 3)} ({models[n]})" if n in poster else DASH,
                     f_err(num(srow[0], "rmse")) if srow else DASH])
    r0 = f.rows(name, "lines")[0]
    lines += [f"`presets/{name}.csv` ({res(r0)}, {f.reps(name, r0)}, {r0.get('slices', '?')} slices): "
              "per-fragment exact OIT against the per-primitive slice sort; the poster's frame rate on its GPU.", ""]
    lines += table(["segments", "fragments", "peak depth", "exact total ms", "slices total ms (keys / sort / blend)",
                    "slices fps", "poster fps", "slices rmse"], body)
    lines.append("- Slices against exact: " + ", ".join(f"{f_x(r)}x at {n:,} segments ({word(r)})"
                                                       for r, n in zip(rs, segs)) + ".")
    lines.append(f"- The sort is {span(share)} of the slices' time.")
    t_lo = f.median(name, "lines", technique="slices", segments=segs[0])
    t_hi = f.median(name, "lines", technique="slices", segments=segs[-1])
    if segs[0] in poster and segs[-1] in poster:
        lines.append(f"- From {segs[0]:,} to {segs[-1]:,} segments ({f_x(segs[-1] / segs[0])}x) the slices' time "
                     f"grows {f_x(ratio(t_hi, t_lo))}x; the poster's frame rate fell "
                     f"{f_x(ratio(poster[segs[0]], poster[segs[-1]]))}x over the same models.")
    lines += ["", "On a GPU the sort's passes are bandwidth-bound and nearly free for small models; on llvmpipe "
              "every pass is CPU work that grows with the data.", ""]
    return lines


def popping_cells(r):
    """A splat row's popping (mean) and the pixels that pop (a dash where it has none)."""
    return [f_err(num(r, "popping")), f_num(num(r, "popping_pixels"))]


def section_splats(f):
    """Issue 29: the 3DGS global sort (the preset's baseline, named by the rows' baseline column) per million
    splats, and every technique's time over it, its error against the analytic reference and bytes per pixel."""
    name = "splats"
    lines = ["## Gaussian splats", "",
             "StopThePop's and HTGS's question: what the exact per-pixel order, hybrid, stochastic and weighted "
             "blending cost against the 3DGS global sort, and what they gain in error against the analytic "
             "reference ([docs/splats.md](../../docs/splats.md)).", ""]
    rows = f.rows(name, "oit")
    if not rows:
        return lines + missing(name)
    base = {r["baseline"].split("=", 1)[1] for r in rows if r.get("baseline", "").startswith("technique=")}
    groups = {}
    for r in rows:
        groups.setdefault((r["scene"], r.get("splat_depth", ""), res(r)), []).append(r)
    body, per_million = [], []
    for key in sorted(groups, key=lambda k: (num(groups[k][0], "polygons") or 0, k[1])):
        g = groups[key]
        gs = [r for r in g if r["technique"] in base]
        t0 = statistics.median([ms(r) for r in gs]) if gs else None
        splats = num(g[0], "polygons")
        if t0 is not None and splats:
            per_million.append((key, t0 / (splats / 1e6)))
        if gs:
            body.append([key[0], key[1], key[2], f"{plot.oit_label(gs[0])} (median of {len(gs)} row(s))", f_ms(t0),
                         f_x(1.0), f_err(num(gs[0], "truth_rmse"))] + popping_cells(gs[0]) +
                        [f_num(num(gs[0], "bytes_per_pixel"))])
        for r in sorted((r for r in g if r["technique"] not in base), key=ms):
            speedup = num(r, "speedup")
            over = 1.0 / speedup if speedup else ratio(ms(r), t0)  # paired in its interleaving group where it can be
            body.append([key[0], key[1], key[2], plot.oit_label(r) + (f" {r['capture']}" if r.get("capture") and
                                                                     r["technique"] in EXACT else ""),
                         f_ms(ms(r)), f_x(over), f_err(num(r, "truth_rmse"))] + popping_cells(r) +
                        [f_num(num(r, "bytes_per_pixel"))])
    r0 = rows[0]
    lines += [f"`presets/{name}.csv` ({f.reps(name, r0)}): per scene (splat count) and depth key, each valid "
              "case's `total` median (ms), its time over the global sort's (the preset's baseline, paired in its interleaving group: 1 / speedup; below 1 faster; the global sort's row: the median of its rows, one per interleaving group), "
              "its rmse against the analytic reference of its key (`truth_rmse`; empty where the technique does not "
              "report it yet), its popping over the camera path (`popping`: the mean over pixels and neighbouring "
              "frames of the image's change beyond the analytic reference's; `popping_pixels`: pixels that pop by "
              "more than 2/255; a dash where the row has none, [docs/splats.md](../../docs/splats.md#popping)) and its "
              "bytes per pixel.", ""]
    lines += table(["scene", "splat_depth", "resolution", "case", "ms", "over global sort", "truth rmse", "popping",
                    "popping px", "bytes/px"], body, [False] * 4 + [True] * 6)
    for key, t in per_million:
        lines.append(f"- The global sort on {key[0]} ({key[1]}, {key[2]}): {f_ms(t)} ms per million splats.")
    lines.append("")
    return lines
