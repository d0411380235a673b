"""FINDINGS.md's sections on the micro experiments: occupancy and Brüll 2018's sorting, storage layout, spin lock
and stencil tables."""
import statistics

from oitbench import papers
from oitbench import results as oitres
from oitbench.findings.common import (
    DASH, f_ms, f_pct, f_x, missing, ms, num, ratio, res, sizes_of, span, table, verdict)


def section_occupancy(f):
    name = "occupancy-fig3"
    lines = ["## Occupancy", "",
             "Knowles 2013 figure 3, local array size against time: the `occupancy` experiment.", ""]
    rows = f.rows(name, "occupancy")
    if not rows:
        return lines + missing(name)
    per = {}
    for r in rows:
        per[(r["variant"], int(r["size"]))] = ms(r) / float(r["draws"])
    sizes = sorted({s for _, s in per})
    r0 = rows[0]
    lines += [f"`presets/{name}.csv`: {res(r0)}, {r0['draws']} full-screen draws per repetition, "
              f"{f.reps(name, r0)}; milliseconds per draw (`median_ms / draws`).", ""]
    body = [[s, f_ms(per.get(("dynamic", s))), f_ms(per.get(("unrolled", s))),
             f_x(ratio(per.get(("dynamic", s)), per.get(("unrolled", s))))] for s in sizes]
    lines += table(["SIZE", "dynamic ms/draw", "unrolled ms/draw", "dynamic / unrolled"], body)
    unrolled = [(s, per[("unrolled", s)]) for s in sizes if ("unrolled", s) in per]
    dynamic = {s: per[("dynamic", s)] for s in sizes if ("dynamic", s) in per}
    if len(unrolled) > 1:
        steps = [(b[1] / a[1], a, b) for a, b in zip(unrolled, unrolled[1:])]
        step, (s0, t0), (s1, t1) = max(steps)
        after = [t / s for s, t in unrolled if s >= s1]
        below = [s for s in dynamic if 1 < s < s1 and ("unrolled", s) in per]
        lines.append(f"- `unrolled`: the largest step between neighbouring sizes is from SIZE {s0} "
                     f"({f_ms(t0)} ms per draw) to {s1} ({f_ms(t1)} ms), {f_x(step)}x. From SIZE {s1} on it "
                     f"costs {span(after, f_ms)} ms per draw per element.")
        if below:
            rs = [dynamic[s] / per[("unrolled", s)] for s in below]
            lines.append(f"- `dynamic` takes {span(rs)}x the time of `unrolled` from SIZE {min(below)} to "
                         f"{max(below)} (`unrolled`: {verdict([1 / r for r in rs], 'sizes')}); at SIZE "
                         f"{sizes[0]} they take {f_ms(dynamic.get(sizes[0]))} and "
                         f"{f_ms(per.get(('unrolled', sizes[0])))} ms.")
        d_below = [dynamic[s] / s for s in dynamic if 8 <= s < s1]
        d_after = [dynamic[s] / s for s in dynamic if s >= s1]
        if d_below and d_after and s0 in dynamic and s1 in dynamic:
            lines.append(f"- `dynamic` per element: {span(d_below, f_ms)} ms per draw from SIZE 8 to {s0}, "
                         f"{span(d_after, f_ms)} from {s1} on; from {s0} to {s1} it steps "
                         f"{f_x(dynamic[s1] / dynamic[s0])}x.")
        around = [dynamic[s] for s in (63, 64, 65) if s in dynamic]
        if len(around) == 3:
            lines.append(f"- `dynamic` at SIZE 63, 64 and 65: {', '.join(f_ms(x) for x in around)} ms per draw, within "
                         f"{(max(around) / min(around) - 1) * 100:.0f}% of each other.")
        both = [per[("unrolled", s)] / dynamic[s] for s in dynamic if s >= s1 and ("unrolled", s) in per]
        if both:
            lines.append(f"- From SIZE {s1} on `unrolled` takes {span(both)}x the time of `dynamic` "
                         f"(`unrolled`: {verdict(both, 'sizes')}).")
    models = sorted({r.get("model_gpu_used", "") for r in rows if r.get("model_gpu_used", "")})
    predicted = [r for r in rows if num(r, "predicted_occupancy") is not None]
    if models:
        lines.append(f"- `model_gpu_used`: {', '.join(f'`{m}`' for m in models)}; `predicted_occupancy` filled in "
                     f"{len(predicted)} of {len(rows)} cases.")
    quick = f.rows("default", "occupancy", variant="unrolled")
    qs = {int(r["size"]): ms(r) for r in quick}
    if 32 in qs and 33 in qs:
        q = quick[0]
        lines.append(f"- The `default` preset's grid ({res(q)}, {q['draws']} draws) shows the same step: "
                     f"`unrolled` {f_x(qs[33] / qs[32])}x from SIZE 32 to 33.")
    lines += ["", "llvmpipe has no occupancy: the shader runs as JIT-compiled SIMD code on CPU threads. The "
              "step is the compiler's own switch from an unrolled array in registers to one indexed in "
              "scratch memory, where NIR stops unrolling loops; it is this driver's version of the papers' "
              "register-against-local-memory effect; the occupancy model has no GPU to match here. See "
              "[docs/experiments/occupancy.md]"
              "(../../docs/experiments/occupancy.md).", ""]
    return lines


def paper_ratio_rows(pairs, comparisons):
    """[comparison, sizes, thesis ratios, ours ratios] for (label, scene, a, b, metric) comparisons."""
    out = []
    for label, scene, a, b, metric in comparisons:
        sizes = sorted({int(k[1]) for k in pairs if k[0] == a and k[2] == scene and k[4] == metric})
        th, ours = [], []
        for s in sizes:
            pa, pb = pairs.get((a, str(s), scene, "", metric)), pairs.get((b, str(s), scene, "", metric))
            th.append(f_x(ratio(pa["paper"], pb["paper"])) if pa and pb else DASH)
            ours.append(f_x(ratio(pa["ours_ms"], pb["ours_ms"])) if pa and pb else DASH)
        out.append([label, ", ".join(map(str, sizes)), ", ".join(th), ", ".join(ours)])
    return out


def section_sort(f):
    name = "bruell2018-sorting"
    lines = ["## Sort and insert", "",
             "Brüll 2018 §4.3–4.5, Tables A.1–A.3, figures 4.7/4.8: the `sort` and `insert` experiments.", ""]
    if not f.run(name):
        return lines + missing(name)
    sort = f.rows(name, "sort")
    r0 = sort[0] if sort else {}
    lines += [f"`presets/{name}.csv`: {res(r0) if r0 else '?'}, {r0.get('stage', '?')} stage, "
              f"{r0.get('keys', '?')} keys, {f.reps(name, r0)}; time ratios of `total` medians "
              "(A / B below 1: A is faster). The thesis's from results/published (GTX 1080, 800x800).", ""]
    a1 = "naive insertion, dynamic index assignment: "
    comparisons = [(f"A.1: {v} / loop", "sort-bench", a1 + v, a1 + "loop", "total_time")
                   for v in ("direct", "switch", "if-else")]
    body = paper_ratio_rows(f.paper_pairs(name, "bruell-A.1"), comparisons)
    body += paper_ratio_rows(f.paper_pairs(name, "bruell-A.3"), [
        ("A.3: bubble with early out / without (ours: both memories' median)", "sort-bench",
         "bubble sort, early out", "bubble sort, no early out",
         "total_time")])
    body += paper_ratio_rows(f.paper_pairs(name, "bruell-A.2"), [
        ("A.2: insertion with early out / without (Village x128; ours: random keys)", "village", a, b, "total_time")
        for a, b in papers.table("bruell-A.2").compare])
    lines += table(["comparison", "n", "thesis", "llvmpipe"], body, [False, False, False, False])

    def t(variant, memory, n):
        return f.median(name, "sort", variant=variant, memory=memory, n=n, assign="listing")

    ns = sizes_of(sort, "n")
    v2 = {n: ratio(t("insertion-v2", "local", n), t("insertion-v2", "registers", n)) for n in ns}
    lines.append(f"Figure 4.7 (the thesis: registers faster than local memory): insertion-v2 local / registers "
                 f"at n = {', '.join(map(str, ns))}: {', '.join(f_x(v2[n]) for n in ns)} "
                 f"(registers: {verdict([1 / r for r in v2.values() if r], 'sizes')}).")
    lines.append("")
    variants = []
    for r in sort:
        if r["variant"] not in variants and r.get("assign", "listing") == "listing":
            variants.append(r["variant"])
    top = max(ns) if ns else None
    base = t("insertion-v2", "registers", top)
    body, best = [], []
    for v in variants:
        loc, reg = t(v, "local", top), t(v, "registers", top)
        fastest = min(x for x in (loc, reg) if x is not None) if (loc or reg) else None
        best.append((ratio(fastest, base), v))
        body.append([v, f_ms(loc), f_ms(reg), f_x(ratio(loc, reg)), f_x(ratio(fastest, base))])
    body.sort(key=lambda row: (oitres.to_float(row[4]) is None, oitres.to_float(row[4]) or 0.0))
    lines += [f"Every sort at n = {top} (ms; {DASH}: not valid or no such form):", ""]
    lines += table(["variant", "local ms", "registers ms", "local / registers", "fastest form / insertion-v2"],
                   body)
    ranked = sorted(b for b in best if b[0] is not None)
    if ranked:
        place = [v for _, v in ranked].index("insertion-v2") + 1 if "insertion-v2" in [v for _, v in ranked] else None
        lines.append(f"- At n = {top} the fastest sort is `{ranked[0][1]}` ({f_x(ranked[0][0])}x insertion-v2's "
                     f"time); insertion-v2 ranks {place} of {len(ranked)} valid sorts.")
    both = []
    for v in variants:
        for n in ns:
            r = ratio(t(v, "local", n), t(v, "registers", n))
            if r is not None:
                both.append((r, v, n))
    if both:
        hi = max(both)
        lines.append(f"- local / registers over every sort with both forms valid and every n: "
                     f"{span([b[0] for b in both])} (median {f_x(statistics.median(b[0] for b in both))}; the "
                     f"largest: `{hi[1]}` at n = {hi[2]}).")
    rbs = [ratio(t("rbs", "registers", n), t("insertion-v2", "registers", n)) for n in ns]
    if any(rbs):
        lines.append(f"- `rbs` (the hand-unrolled network, the one true register array here) takes "
                     f"{span(rbs)}x insertion-v2's time in registers: {verdict(rbs, 'sizes')}.")
    bub = [ratio(t("bubble-early", m, n), t("bubble", m, n)) for m in ("local", "registers") for n in ns]
    if any(bub):
        lines.append(f"- `bubble-early` takes {span(bub)}x the time of `bubble` (both memories, every n): "
                     f"with the early out {verdict(bub)}.")
    ins = f.rows(name, "insert")
    for keys in sorted({r["keys"] for r in ins}):
        sz = sizes_of([r for r in ins if r["keys"] == keys], "size")
        rs = [ratio(f.median(name, "insert", variant="early-out", keys=keys, size=s),
                    f.median(name, "insert", variant="no-early-out", keys=keys, size=s)) for s in sz]
        if any(rs):
            lines.append(f"- `insert` with `{keys}` keys: early-out / no-early-out {span(rs)} over sizes "
                         f"{sz[0]}..{sz[-1]} ({f_x(rs[0])} at {sz[0]}, {f_x(rs[-1])} at {sz[-1]}): "
                         f"with the early out {verdict(rs, 'sizes')}.")
    bad = f.rows(name, "sort", valid=False, where=lambda r: not oitres.is_ok(r) and oitres.status_of(r) == "invalid")
    for v in sorted({r["variant"] for r in bad}):
        mine = [r for r in bad if r["variant"] == v]
        grid = [r for r in f.rows(name, "sort", valid=False, variant=v)]
        full = [int(r["n"]) for r in mine if num(r, "unsorted_pixels") == int(r["width"]) * int(r["height"])]
        lines.append(f"- `{v}` is invalid in {len(mine)} of its {len(grid)} cases (memories "
                     f"{', '.join(sorted({r['memory'] for r in mine}))}; n {span([int(r['n']) for r in mine], str)})"
                     + (f"; from n = {min(full)} on every pixel is out of order" if full else "") + ".")
    lines += ["", "llvmpipe runs `if` as masked straight-line code, so an early exit only adds work, and it "
              "does not unroll nested loops whose inner bound depends on the outer index, so a loop-based "
              "sort's `registers` form stays dynamically indexed like its `local` one. The invalid rows are "
              "miscompiles the validators catch ([docs/experiments/sort.md](../../docs/experiments/sort.md), "
              "[insert.md](../../docs/experiments/insert.md)).", ""]
    ins_rows = []
    for keys in sorted({r["keys"] for r in ins}):
        for s in sizes_of([r for r in ins if r["keys"] == keys], "size"):
            ins_rows.append([keys, s] + [f_ms(f.median(name, "insert", variant=v, keys=keys, size=s))
                                         for v in ("early-out", "no-early-out", "two-moves")])
    if ins_rows:
        r0 = ins[0]
        lines += [f"`insert`, {r0['repeat']} insertions per pixel, {r0['memory']} (ms):", ""]
        lines += table(["keys", "size", "early-out", "no-early-out", "two-moves"], ins_rows,
                       [False, True, True, True, True])
    return lines


def section_layout(f):
    lines = ["## Storage layouts", "", "Brüll 2018 §4.1, Table 4.1: the `layout` experiment.", ""]
    name = "bruell2018-storage"
    layout = f.rows(name, "layout")
    if not layout:
        return lines + missing(name)
    r0 = layout[0]
    nodes = sizes_of(layout, "nodes")
    pairs = f.paper_pairs(name, "bruell-4.1")
    scenes = sorted({k[2] for k in pairs}, key=["powerplant", "village", "sanmiguel"].index)
    paper = papers.table("bruell-4.1")
    thesis = paper.ours  # our layout -> the thesis's row

    def lt(lay, n, src=name):
        return f.median(src, "layout", layout=lay, nodes=n)

    layouts = [x for x in dict.fromkeys(r["layout"] for r in layout) if x != "ssbo"]
    body = []
    for lay in layouts:
        row = [f"`{lay}`"] + [f_x(ratio(lt(lay, n), lt("ssbo", n))) for n in nodes]
        for n in nodes:
            th = []
            for s in scenes:
                a, b = pairs.get((thesis.get(lay, ""), str(n), s, "", "total_time")), \
                    pairs.get((paper.baseline, str(n), s, "", "total_time"))
                th.append(f_x(ratio(a["paper"], b["paper"])) if a and b else DASH)
            row.append(" / ".join(th))
        body.append(row)
    lines += [f"`presets/{name}.csv` ({res(r0)}, {r0['layers']} layers, {f.reps(name, r0)}): time / "
              f"`ssbo` of the `total` medians; the thesis's {paper.baseline.split()[0]} times ({' / '.join(scenes)}) "
              "likewise.", ""]
    lines += table(["layout"] + [f"nodes {n}" for n in nodes] + [f"thesis, {n} nodes" for n in nodes], body)
    for lay, label in (("texture3d", "`texture3d` (image load/store)"), ("texbuffer", "The buffer-texture read path")):
        rs = [ratio(lt(lay, n), lt("ssbo", n)) for n in nodes]
        if any(rs):
            lines.append(f"- {label} takes {span(rs)}x the time of `ssbo`: {verdict(rs, 'node counts')}.")
    inter = [ratio(lt(x, n), lt("ssbo", n)) for x in layouts if x.startswith("interleaved")
             and x != "interleaved-1x1-a1" for n in nodes]
    if any(inter):
        lines.append(f"- The interleaved layouts take {span(inter)}x the time of `ssbo`: {verdict(inter)}.")
    ctl = [ratio(lt("interleaved-1x1-a1", n), lt("ssbo", n)) for n in nodes]
    if any(ctl):
        lines.append(f"- The control `interleaved-1x1-a1`, byte for byte `ssbo`, takes {span(ctl)}x: the "
                     "noise of this comparison.")
    q = [ratio(lt("texture3d", n, "default"), lt("ssbo", n, "default")) for n in sizes_of(
        f.rows("default", "layout"), "nodes")]
    if any(q):
        q0 = f.rows("default", "layout")[0]
        lines.append(f"- The `default` preset's quick grid ({res(q0)}, {q0['layers']} layers): `texture3d` / "
                     f"`ssbo` {span(q)}.")
    every = f.rows(name, "layout", pass_=None) + f.rows("default", "layout", pass_=None)
    lost = sum(num(r, "lost_updates") or 0 for r in every if r["pass"] == "total")
    incons = sum(num(r, "inconsistent_nodes") or 0 for r in every if r["pass"] == "total")
    lines.append(f"- Lost updates over every layout case of both presets: {lost:.0f}; inconsistent nodes: "
                 f"{incons:.0f}.")
    lines += ["", "A CPU rasteriser has no memory transactions to coalesce, and llvmpipe shades a tile's "
              "fragments in primitive order, so the races that interleaved storage invites on a GPU cannot "
              "happen here.", ""]
    return lines


def section_spinlock(f):
    lines = ["## Spinlocks", "", "Brüll 2018 §4.2, Listings 4.1–4.3: the `spinlock` experiment.", ""]
    name = "bruell2018-spinlock"
    spin = f.rows(name, "spinlock", valid=False)
    if not spin:
        return lines + missing(name)
    layers = sizes_of(spin, "layers")
    variants = list(dict.fromkeys(r["variant"] for r in spin))
    body = []
    for n in layers:
        naive = f.median(name, "spinlock", variant="naive", layers=n)
        row = [n]
        for v in variants:
            r = next((x for x in spin if x["variant"] == v and x["layers"] == str(n)), None)
            if r is not None and oitres.is_ok(r):
                row.append(f"{f_ms(ms(r))} ({f_x(ratio(ms(r), naive))}x)")
            else:
                row.append(oitres.status_of(r) if r else DASH)
        body.append(row)
    r0 = spin[0]
    lines += [f"`presets/{name}.csv` ({res(r0)}, {f.reps(name, r0)}, each case in a child process "
              "under the watchdog): `total` ms, and the time over `naive` in brackets.", ""]
    lines += table(["layers"] + [f"`{v}`" for v in variants], body)
    ok = [r for r in spin if oitres.is_ok(r)]
    capped = sum(num(r, "capped_updates") or 0 for r in ok)
    lost = sum(num(r, "lost_updates") or 0 for r in ok)
    timeouts = sum(1 for r in spin if oitres.status_of(r) == "timeout")
    loops = [ratio(f.median(name, "spinlock", variant=v, layers=n), f.median(name, "spinlock", variant="naive",
                                                                           layers=n))
             for v in ("loop", "helper-guard") for n in layers]
    lines.append(f"- Capped updates {capped:.0f}, lost updates {lost:.0f}, timeouts {timeouts}. The loop "
                 f"forms (Listings 4.2/4.3) take {span(loops)}x the naive lock's time: {verdict(loops)}.")
    lines += ["", "The naive lock does not deadlock on llvmpipe, so passing here says nothing about it on a "
              "GPU, where it can hang.", ""]
    return lines


def section_stencil(f):
    lines = ["## Stencil-masked resolve", "", "Brüll 2018 §4.6, Tables A.4/A.5: the `stencil` experiment.", ""]
    name = "bruell2018-stencil"
    st = f.rows(name, "stencil", pass_=None)
    if not st:
        return lines + missing(name)
    cov = sizes_of(st, "coverage")
    resolves = list(dict.fromkeys(r["resolve"] for r in st))

    def s(variant, resolve, c, pass_):
        return f.median(name, "stencil", pass_=pass_, variant=variant, resolve=resolve, coverage=c)

    body, capture, clear = [], [], []
    for c in cov:
        row = [f"{c} %"]
        for rv in resolves:
            for p in ("resolve", "total"):
                row.append(f_x(ratio(s("stencil", rv, c, p), s("no-stencil", rv, c, p))))
            capture.append(ratio(s("stencil", rv, c, "capture"), s("no-stencil", rv, c, "capture")))
            clear.append(ratio(s("no-stencil", rv, c, "clear"), s("no-stencil", rv, c, "total")))
        body.append(row)
    r0 = st[0]
    lines += [f"`presets/{name}.csv` ({res(r0)}, {r0['nodes']} nodes, {r0['layers']} layers, {f.reps(name, r0)}"
              "): stencil / no stencil, by the band's coverage of the screen.", ""]
    lines += table(["coverage"] + [f"{rv} {p}" for rv in resolves for p in ("resolve", "total")], body)
    a4 = f.paper_pairs(name, "bruell-A.4")
    a5 = f.paper_pairs(name, "bruell-A.5")
    (m4, u4), = papers.table("bruell-A.4").compare  # the masked row and the unmasked one
    (m5, u5), = papers.table("bruell-A.5").compare
    th_full = [ratio(a4[k]["paper"], a4[(u4,) + k[1:]]["paper"]) for k in a4
               if k[0] == m4 and k[4] == "fullscreen_pass_time" and (u4,) + k[1:] in a4]
    th_tot = [ratio(a4[k]["paper"], a4[(u4,) + k[1:]]["paper"]) for k in a4
              if k[0] == m4 and k[4] == "total_time" and (u4,) + k[1:] in a4]
    th_u = [ratio(a5[k]["paper"], a5[(u5,) + k[1:]]["paper"]) for k in a5
            if k[0] == m5 and (u5,) + k[1:] in a5]
    if th_full:
        lines.append(f"- The thesis (Village, every node count of Tables A.4/A.5): {m4.split()[0]}'s full-screen pass "
                     f"with the mask takes {span(th_full)}x its time without, its total {span(th_tot)}x; "
                     f"{m5.split()[0]}'s total {span(th_u)}x.")
    lines.append(f"- Here the stencil writes change the capture pass by {span([c for c in capture if c], f_pct)} "
                 f"(with them: {verdict(capture)}); the `clear` pass, the same with and without the mask, is "
                 f"{span(clear)} of the unmasked total, which bounds what the total can gain.")
    lines += ["", "The masked resolve skips the pixels outside the band, so its time follows the coverage; "
              "on llvmpipe `layout(early_fragment_tests)` in the resolve is what lets the mask skip the work.", ""]
    return lines
