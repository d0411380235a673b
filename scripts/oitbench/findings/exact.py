"""FINDINGS.md's sections on exact OIT: capture, the project's targets, Knowles 2014 and 2013, resolve speedups and
scaling."""
from oitbench import results as oitres
from oitbench import papers as tables
from oitbench import knowles
from oitbench import techniques
from oitbench.findings.common import (
    DASH, EXACT_SHADER, PAPER_SCENE, TARGET_CAPTURE_RATE, TARGET_RESOLVE_VS_CPU, case_key, f_m, f_mb, f_ms,
    f_num, f_paper, f_x, field, max_frags_used, missing, ms, num, ratio, res, scene_key, span, table, verdict,
    view_key, word)

# The techniques these sections single out, found in the technique table by what they are: the baseline, the
# CPU resolve, the baseline's twin under BMA, the register block sort under both schemes, BMA's per-interval
# choice; and what our compute-shader rows stand in for in the paper.
BASE = techniques.BASELINE
CPU = techniques.CPU_RESOLVE
BMA = techniques.twin(BASE, "BMA")
BASE_RBS = techniques.find(family="exact", scheme=techniques.scheme(BASE), sort="RBS-L")
BMA_RBS = techniques.twin(BASE_RBS, "BMA")
BMA_AUTO = techniques.find(family="exact", scheme="BMA", sort="AUTO")
OURS_FOR_CUDA = next(iter(knowles.PAPER_SCHEME))
CS_RBS = techniques.find(family="exact", scheme=OURS_FOR_CUDA, sort="RBS-L")
CHECKED = BASE + "+order-check"


def pairs_by_capture(f, name):
    """{(scene, view, technique, WxH): {capture: {pass: row}}} of the valid oit rows of a preset."""
    out = {}
    for r in f.rows(name, "oit", pass_=None):
        key = (r["scene"], r["view"], r["technique"], res(r))
        out.setdefault(key, {}).setdefault(r.get("capture") or "PPLL", {})[r["pass"]] = r
    return out


def section_capture(f):
    lines = ["## Exact OIT: capture storage", "",
             "Linked lists (PPLL) against packed per-pixel arrays (PPPA), Knowles 2014 §2.2.", ""]
    if not f.run("capture-storage"):
        return lines + missing("capture-storage")
    body, stats = [], []
    for name in ("capture-storage", "oit-scale"):
        pairs = pairs_by_capture(f, name)
        for key in sorted(pairs, key=lambda k: (scene_key(k[0]), view_key(k[1]), k[2], k[3])):
            c = pairs[key]
            if "PPLL" not in c or "PPPA" not in c or "total" not in c["PPLL"] or "total" not in c["PPPA"]:
                continue
            a, b = c["PPLL"], c["PPPA"]
            rr = {p: ratio(ms(b.get(p)), ms(a.get(p))) for p in ("capture", "resolve", "total")}
            mem = ratio(num(b["total"], "node_pool_bytes"), num(a["total"], "node_pool_bytes"))
            share = ratio(num(b.get("capture"), "capture_count_ms"), ms(b.get("capture")))
            stats.append((name, key, rr, mem))
            body.append([f"`{name}`", key[0], key[1], key[2], key[3], f_x(rr["capture"]), f_x(rr["resolve"]),
                         f_x(rr["total"]), f_x(mem), f"{f_ms(ms(a['total']))} \u2192 {f_ms(ms(b['total']))}",
                         f_x(share)])
    lines += ["PPPA / PPLL time of each pass for the same case (below 1: PPPA is faster), the memory of the "
              "fragment storage (`node_pool_bytes`), the `total` ms PPLL \u2192 PPPA, and the share of PPPA's "
              "capture that is its count pass and prefix sum (`capture_count_ms`). Sources: "
              "`presets/capture-storage.csv` and the cases of `presets/oit-scale.csv` run in both layouts.", ""]
    lines += table(["preset", "scene", "view", "technique", "resolution", "capture", "resolve", "total", "memory",
                    "total ms", "count+scan share"], body, [False] * 5 + [True] * 6)

    def over(pass_, name=None, scene=None, technique=None):
        return [rr[pass_] for n, k, rr, _ in stats if (name is None or n == name) and
                (scene is None or k[0] == scene) and (technique is None or k[2] == technique)]

    for pass_ in ("resolve", "capture", "total"):
        parts = []
        for name in ("capture-storage", "oit-scale"):
            scenes = sorted({k[0] for n, k, _, _ in stats if n == name}, key=scene_key)
            per = [f"{sc} {span(over(pass_, name, sc))}" for sc in scenes if over(pass_, name, sc)]
            if per:
                parts.append(f"`{name}`: " + ", ".join(per))
        rs = over(pass_)
        lines.append(f"- {pass_.capitalize()}: PPPA takes {span(rs)}x PPLL's time ({verdict(rs)}); by scene, "
                     + "; ".join(parts) + ".")
    cpu = over("resolve", "capture-storage", technique=CPU)
    if cpu:
        lines.append(f"- {CPU}'s resolve gains most from contiguous fragments: {span(cpu)}x in "
                     "`capture-storage`.")
    lines.append(f"- Memory: PPPA needs {span([m for _, _, _, m in stats])}x PPLL's bytes.")
    lines += ["", "PPPA stores each pixel's fragments side by side, so a resolve reads them in order, but it "
              "draws the geometry twice (a count pass, then the fill): it pays where fragment work dominates "
              "and costs where vertex work does (the CAD stand-ins, the hairball's many thin tubes).", ""]
    return lines


def section_targets(f):
    lines = ["## Exact OIT: targets", "",
             f"Two targets of the project brief: a shader resolve within {f_paper(TARGET_RESOLVE_VS_CPU)}x of "
             f"{CPU}'s, and capture at {tables.fmt(TARGET_CAPTURE_RATE / 1e6, 3)} M fragments/s.", ""]
    body = []
    for name in ("capture-storage", "knowles2014"):
        pairs = pairs_by_capture(f, name)
        groups = {}
        for (scene, view, tech, wh), caps in pairs.items():
            for cap, passes in caps.items():
                if "resolve" in passes:
                    groups.setdefault((scene, view, wh, cap), {})[tech] = ms(passes["resolve"])
        for key in sorted(groups, key=lambda k: (scene_key(k[0]), view_key(k[1]), k[3])):
            techs = groups[key]
            shaders = {t: v for t, v in techs.items() if t != CPU}
            if not shaders or CPU not in techs:
                continue
            best = min(shaders, key=lambda t: (shaders[t], t))
            r = shaders[best] / techs[CPU]
            body.append([f"`{name}`", key[0], key[1], key[2], key[3], f"{best} {f_ms(shaders[best])}",
                         f_ms(techs[CPU]), f_x(r), "yes" if r <= TARGET_RESOLVE_VS_CPU else "no"])
    if body:
        lines += [f"The fastest shader resolve of each case against {CPU}'s resolve (ms); `capture-storage` "
                  "runs two shader resolves, `knowles2014` all of them.", ""]
        lines += table(["preset", "scene", "view", "resolution", "capture", "best shader resolve", CPU,
                        "ratio", "met"], body, [False] * 5 + [False, True, True, False])
        for name in ("capture-storage", "knowles2014"):
            for cap in ("PPLL", "PPPA"):
                mine = [b for b in body if b[0] == f"`{name}`" and b[4] == cap]
                if mine:
                    lines.append(f"- `{name}`, {cap}: met in {sum(b[8] == 'yes' for b in mine)} of {len(mine)} "
                                 f"cases (ratios {span([oitres.to_float(b[7]) for b in mine])}).")
        lines.append("")
    body = []
    for name in ("capture-storage", "oit-scale", "knowles2014"):
        groups = {}
        for r in f.rows(name, "oit"):
            x = num(r, "fragments_per_s")
            if x is not None:
                groups.setdefault((r["scene"], res(r), r.get("capture") or "PPLL"), []).append(x)
        for key in sorted(groups, key=lambda k: (scene_key(k[0]), [int(v) for v in k[1].split("x")], k[2])):
            xs = groups[key]
            met = "yes" if min(xs) >= TARGET_CAPTURE_RATE else ("no" if max(xs) < TARGET_CAPTURE_RATE else "in part")
            body.append([f"`{name}`", key[0], key[1], key[2], len(xs), span([x / 1e6 for x in xs], f_ms), met])
    if body:
        lines += ["Capture rate (`fragments_per_s`, fragments captured per second of the capture pass) over "
                  "every valid case of a scene, resolution and layout:", ""]
        lines += table(["preset", "scene", "resolution", "capture", "cases", "M fragments/s", "met"], body,
                       [False] * 4 + [True, True, False])
    lines += ["On a software renderer capture is CPU rasterisation: the big triangles of the planes reach the "
              "rate, the CAD stand-ins spend their time on vertices, not fragments.", ""]
    return lines


def speedups(f, name, pass_):
    """knowles.view_speedups of a preset's per-pixel-linked-list oit rows (paired where they carry it)."""
    return knowles.view_speedups(f.rows(name, "oit", pass_=pass_, capture="PPLL"), pass_)


def section_knowles2014(f):
    name = "knowles2014"
    lines = ["## Exact OIT: Knowles 2014", "",
             "The resolve sorts of Knowles 2014 (RBS), tables 1 and 3.", ""]
    if not f.run(name):
        return lines + missing(name)
    paper = knowles.Paper(f.paper_rows)
    rsp, tsp = speedups(f, name, "resolve"), speedups(f, name, "total")
    views = sorted(rsp, key=lambda k: (scene_key(k[0]), view_key(k[1])))
    techs = [t for t in EXACT_SHADER + [CPU] if t != BASE and any(t in rsp[v] for v in views)]
    r0 = f.rows(name, "oit")[0]
    blocks = ", ".join(sorted({r["block"] for r in f.rows(name, "oit", pass_=None, valid=False) if r.get("block")}, key=int)) or "?"
    lines += [f"`presets/{name}.csv` ({res(r0)}, {f.reps(name, r0)}, register blocks of {blocks}): "
              f"speedup over {BASE} (time of {BASE} / time; paired per repetition where the rows carry it) per view, the paper's (GTX Titan, 1920x1080) in "
              f"brackets; the engine grid stands in for the power plant, the house for the atrium, {OURS_FOR_CUDA}-* for "
              f"the paper's {knowles.PAPER_SCHEME[OURS_FOR_CUDA]}-* rows.", ""]
    for label, sp, metric in (("Resolve", rsp, "resolve"), ("Total", tsp, "total")):
        body = []
        for t in techs:
            row = [t]
            for v in views:
                ours = sp.get(v, {}).get(t)
                p = paper.speedup(t, v[0], v[1], metric)
                row.append(f_x(ours) + (f" ({f_paper(p)})" if p is not None else ""))
            body.append(row)
        lines += [f"{label} speedups:", ""]
        lines += table(["technique"] + [f"{s} {w}" for s, w in views], body)

    def ours(t, pred, sp=rsp):
        return [sp[v].get(t) for v in views if pred(v) and sp[v].get(t) is not None]

    def theirs(t, pred, metric="resolve"):
        return [p for p in (paper.speedup(t, v[0], v[1], metric) for v in views if pred(v)) if p is not None]

    rev = lambda v: v[1] == "rev"  # noqa: E731
    fwd = lambda v: v[1] == "fwd"  # noqa: E731
    model = lambda v: v[0] in PAPER_SCENE  # noqa: E731
    every = lambda v: True  # noqa: E731
    for v in [v for v in views if rev(v)]:
        lines.append(f"- {v[0]} {v[1]}: {BASE_RBS}'s resolve {f_x(rsp[v].get(BASE_RBS))}x (paper "
                     f"{f_paper(paper.speedup(BASE_RBS, v[0], v[1], 'resolve'))}x), "
                     f"{BMA_RBS} {f_x(rsp[v].get(BMA_RBS))}x (paper "
                     f"{f_paper(paper.speedup(BMA_RBS, v[0], v[1], 'resolve'))}x).")
    rbs_fwd = ours(BASE_RBS, fwd) + ours(BMA_RBS, fwd)
    lines.append(f"- On the sorted `fwd` views the RBS resolves ({BASE_RBS}, {BMA_RBS}) reach {span(rbs_fwd)}x "
                 f"(paper {span(theirs(BASE_RBS, fwd) + theirs(BMA_RBS, fwd), f_paper)}x): against "
                 f"{BASE}, {verdict([1 / x for x in rbs_fwd if x])}.")
    lines.append(f"- On the model views {BMA_RBS}'s resolve speedup is {span(ours(BMA_RBS, model))}x (paper "
                 f"{span(theirs(BMA_RBS, model), f_paper)}x).")
    bma = ours(BMA, every)
    lines.append(f"- {BMA}'s resolve speedup is {span(bma)}x (paper {span(theirs(BMA, every), f_paper)}x): "
                 f"against {BASE}, {verdict([1 / x for x in bma if x], 'views')}.")
    cpu_best = [v for v in views if rsp[v].get(CPU) is not None and
                rsp[v][CPU] >= max(x for x in rsp[v].values() if x is not None)]
    others = [v for v in views if v not in cpu_best]
    text = f"- {CPU}'s resolve is the fastest on {len(cpu_best)} of {len(views)} views"
    if others:
        text += " (elsewhere: " + "; ".join(
            f"{v[0]} {v[1]}, {max((t for t in rsp[v] if rsp[v][t]), key=lambda t: rsp[v][t])} "
            f"{f_x(max(x for x in rsp[v].values() if x))}x against {CPU}'s {f_x(rsp[v].get(CPU))}x"
            for v in others) + ")"
    lines.append(text + f"; {span(ours(CPU, rev))}x on the `rev` views, "
                 f"{span(ours(CPU, lambda v: not rev(v)))}x elsewhere.")
    p_total = paper.speedup(BMA_RBS, "planes", "Rev", "total")
    p_res = paper.speedup(BMA_RBS, "planes", "Rev", "resolve")
    if p_total is not None:
        lines.append(f"- The paper's planes Rev, {BMA_RBS}: total speedup {f_paper(p_total)}x, resolve "
                     f"{f_paper(p_res)}x.")
    lines.append("")

    body, avg = [], knowles.table1(rsp, {v: tsp[v] for v in views}, techs)
    for t, figures in avg.items():
        theirs1 = [paper.summary(t, m) for m in figures]
        body.append([t] + [f"{f_x(x)}x" for x in figures.values()] +
                    [" / ".join(f_paper(p) for p in theirs1[:2]), " / ".join(f_paper(p) for p in theirs1[2:])])
    lines += ["Table 1's layout: the mean and the best speedup over the views (ours: these views; the paper: "
              "its scenes).", ""]
    lines += table(["technique", "avg total", "avg resolve", "best total", "best resolve",
                    "paper avg total / resolve", "paper best total / resolve"], body)
    goal = {m: paper.summary(BMA_RBS, m) for m in ("best_resolve", "average_resolve", "average_total")}
    shader = {t: v for t, v in avg.items() if t != CPU}
    if shader and all(g is not None for g in goal.values()):
        parts = []
        for m, label in (("best_resolve", "best resolve"), ("average_resolve", "average resolve"),
                         ("average_total", "average total")):
            t = max(shader, key=lambda k: (shader[k][m], k))
            parts.append(f"{label} {f_x(shader[t][m])}x ({t}) against {f_paper(goal[m])}x: "
                         f"{'met' if shader[t][m] >= goal[m] else 'not met'}")
        lines.append(f"- The paper's {BMA_RBS} figures as targets for our best shader technique: " +
                     "; ".join(parts) + ".")
        if CPU in avg:
            c = avg[CPU]
            lines.append(f"- {CPU}, outside the shader resolves: best resolve {f_x(c['best_resolve'])}x, "
                         f"average resolve {f_x(c['average_resolve'])}x, average total {f_x(c['average_total'])}x.")
    lines.append("")
    body = []
    for r in sorted(f.rows(name, "oit", technique=BMA_AUTO), key=case_key):
        body.append([r["scene"], r["view"], max_frags_used(r), f"`{r.get('bma_auto_choice', '')}`",
                     r.get("bma_auto_source", "")])
    if body:
        lines += [f"What {BMA_AUTO} chose per depth interval (interval top: sort), calibrated on this driver:", ""]
        lines += table(["scene", "view", "MAX_FRAGS", "choice", "source"], body, [False] * 5)
    body = []
    for v in views:
        rows = f.rows(name, "oit", scene=v[0], view=v[1], capture="PPLL")
        rates = [num(r, "fragments_per_s") for r in rows]
        caps = [ms(r) for r in f.rows(name, "oit", pass_="capture", scene=v[0], view=v[1], capture="PPLL")]
        r1 = rows[0]
        body.append([v[0], v[1], f_num(num(r1, "polygons")), f_num(num(r1, "total_fragments")),
                     field(r1, "peak_depth"), max_frags_used(r1), span([x / 1e6 for x in rates], f_ms),
                     span(caps, f_ms)])
    lines += ["Capture on these views (every technique's capture pass):", ""]
    lines += table(["scene", "view", "polygons", "fragments", "peak depth", "MAX_FRAGS", "M fragments/s",
                    "capture ms"], body)
    lines += ["BMA's gain on a GPU is occupancy, which a CPU rasteriser does not have, so on llvmpipe its "
              "extra passes cost more than its smaller arrays save. On the `fwd` views the lists arrive "
              "sorted and insertion sort is already optimal, while the unrolled network, masked straight-line "
              "code here, always pays its worst case.", ""]
    return lines


RESOLVE_GOAL_REV = 8.7  # the paper's best resolve speedup over its baseline (GTX Titan, table 3)
RESOLVE_GOAL_FWD = 1.2  # the fwd views' goal for our best exact resolve


def resolve_label(r):
    """The technique, /its block sort, +order-check: one oit row's resolve as the preset varies it."""
    label = r["technique"]
    if r.get("block_sort"):
        label += "/" + r["block_sort"]
    if r.get("order_check") == "on":
        label += "+order-check"
    if r.get("capture") == "PPPA":
        label += " on PPPA"
    return label


def memory_text(rows):
    """The Host line's memory latency (the column `memory ns` per row below)."""
    m = host_memory(rows)
    if m is None:
        return ""
    return (f" Memory latency between rounds (a dependent-load chase, the rows' `host_mem_ns`): "
            f"median {m[0]:.0f} ns, slowest {m[1]:.0f} ns. A list traversal's time follows it and a sort's "
            "in local arrays does not, so a pair measured while it rose is not the CPU's doing: "
            "docs/drivers.md, \"The host difference\".")


def host_identification(r):
    """What tells two hosts' resolve speedups apart (issue 32: llvmpipe's JIT follows the CPU's vector
    extensions): the CPU's vendor, family/model/stepping, whether it has AVX-512, LLVM and its vector width."""
    isa = (r.get("cpu_isa") or "").split()
    if not isa and not r.get("cpu_family"):
        return "not recorded (rows without the cpu_isa column)"
    cpu = " ".join(x for x in (r.get("cpu_model"), r.get("cpu_vendor")) if x)
    fms = "/".join(r.get(k) or "?" for k in ("cpu_family", "cpu_model_id", "cpu_stepping"))
    avx = "AVX-512" if any(x.startswith("avx512") for x in isa) else "AVX2" if "avx2" in isa else "no AVX2"
    llvm = f"LLVM {r.get('llvm_version') or '?'}, {r.get('llvm_vector_bits') or '?'}-bit vectors"
    return f"{cpu} (family/model/stepping {fms}), {avx}, {r.get('cpu_count') or '?'} CPUs; {llvm}"


def host_memory(rows):
    """The host's memory latency over the rows (schema 8's host_mem_ns: a pointer chase between rounds), with
    the slowest chase; None for rows without it."""
    med = [v for v in (num(r, "host_mem_ns") for r in rows) if v is not None]
    top = [v for v in (num(r, "host_mem_max_ns") for r in rows) if v is not None]
    if not med:
        return None
    return oitres.median(med), max(top or med)


def memory_cell(r):
    """One row's memory latency: its median chase, and its slowest where that was 1.5 times the median or more
    (an episode during the case: times of a traversal-bound resolve rise with it)."""
    m = host_memory([r])
    if m is None:
        return DASH
    text = f"{m[0]:.0f}"
    return text + f" (max {m[1]:.0f})" if m[1] >= 1.5 * m[0] else text


def speedup_text(entry, pass_):
    """1.23x, with its 95% interval where the row's own pair gave one (not for a chained ratio)."""
    v = entry.get(pass_)
    if not v:
        return DASH
    text = tables.fmt(v, 3) + "x"
    lo, hi = entry.get(pass_ + "_ci") or (None, None)
    if lo is not None and hi is not None and not entry.get("chained_" + pass_):
        text += f" [{tables.fmt(lo, 3)}–{tables.fmt(hi, 3)}]"
    return text


def section_resolve_speedups(f):
    name = "resolve-speedups"
    lines = ["## The fastest exact resolve, paired", ""]
    if not f.run(name):
        return lines + missing(name)
    oit = f.rows(name, "oit", pass_="resolve", valid=False)
    if oit:
        r0 = oit[0]
        paired = any(r.get("speedup") for r in oit)
        lines += [f"`presets/{name}.csv` ({res(r0)}, {f.reps(name, r0)}): each candidate ran in an interleaved "
                  "group that holds its baseline, so its speedup "
                  "(baseline time / its time) is a ratio of medians taken side by side"
                  + (" (the rows' `speedup`: the median of the per-repetition ratios)" if paired else "")
                  + f". The order check's candidates are paired with {BASE} with the order check, chained "
                  f"through that one's pair with plain {BASE}, so every speedup below is over plain {BASE}. "
                  f"`resolve` and `total` passes; blocks of 32 for {CS_RBS}. Goals: the paper's best resolve "
                  f"speedup on planes rev ({RESOLVE_GOAL_REV:g}x) and {RESOLVE_GOAL_FWD:g}x on every fwd view. "
                  "Candidates \"on PPPA\" captured into packed per-pixel arrays; every other row, and every "
                  "baseline, into linked lists.", "",
                  f"Host: {host_identification(r0)}. The same binary and Mesa give other speedups on another CPU "
                  "(llvmpipe compiles for the CPU it runs on: docs/drivers.md#llvmpipe-compiles-for-this-cpu); "
                  "compare speedups across hosts only with this line beside them." + memory_text(oit), ""]
        speed, base_ms = {}, {}
        for pass_ in ("resolve", "total"):
            by_view = {}
            for r in f.rows(name, "oit", pass_=pass_, valid=False):
                by_view.setdefault((r["scene"], r["view"]), []).append(r)
            for view, rows in by_view.items():
                sp = speed.setdefault(view, {})
                if paired:
                    # Schema 4: each row carries its paired speedup over its baseline; a baseline measured in
                    # several groups has rows without one (its own), kept for its times only.
                    for r in rows:
                        label = resolve_label(r)
                        if label == BASE and pass_ == "resolve" and ms(r) is not None:
                            base_ms.setdefault(view, []).append(ms(r))
                        entry = sp.setdefault(label, {"row": r})
                        if label == BASE:
                            entry[pass_], entry[pass_ + "_ms"] = 1.0, ms(r) if oitres.is_ok(r) else None
                            continue
                        value = num(r, "speedup") if oitres.is_ok(r) else None
                        if value is None and entry.get(pass_) is not None:
                            continue  # the same case as another pair's baseline: keep the paired row
                        entry["row"] = r
                        entry[pass_ + "_ms"] = ms(r) if oitres.is_ok(r) else None
                        entry[pass_] = value
                        entry[pass_ + "_ci"] = (num(r, "speedup_ci_lo"), num(r, "speedup_ci_hi"))
                    # Candidates with the order check were divided by BASE with it: chain to plain BASE.
                    link = sp.get(CHECKED, {}).get(pass_)
                    for label, entry in sp.items():
                        if entry["row"].get("order_check") == "on" and label != CHECKED:
                            if entry.get(pass_) is not None and entry.get("chained_" + pass_) is None:
                                entry["chained_" + pass_] = True
                                entry[pass_] = entry[pass_] * link if link else None
                    continue
                for a, b in zip(rows[0::2], rows[1::2]):  # schema 3: the run's groups of two, in the order they ran
                    la, lb = resolve_label(a), resolve_label(b)
                    if la == BASE and pass_ == "resolve" and ms(a) is not None:
                        base_ms.setdefault(view, []).append(ms(a))
                    ok = oitres.is_ok(a) and oitres.is_ok(b) and ms(a) is not None and ms(b)
                    chain = 1.0 if la == BASE else sp.get(la, {}).get(pass_)
                    value = ms(a) / ms(b) * chain if ok and chain else None
                    entry = sp.setdefault(lb, {"row": b})
                    entry[pass_] = value
                    entry[pass_ + "_ms"] = ms(b) if oitres.is_ok(b) else None
        body, best_rows = [], []
        for view in sorted(speed, key=lambda k: (scene_key(k[0]), view_key(k[1]))):
            cases = speed[view]
            order = sorted(cases, key=lambda l: -(cases[l].get("resolve") or 0))
            for label in order:
                c = cases[label]
                body.append([f"{view[0]} {view[1]}", label, f_ms(c.get("resolve_ms")),
                             speedup_text(c, "resolve"), speedup_text(c, "total"), memory_cell(c["row"])])
            if order and cases[order[0]].get("resolve"):
                best = cases[order[0]]
                goal = RESOLVE_GOAL_REV if view == ("planes", "rev") else RESOLVE_GOAL_FWD if view[1] == "fwd" else None
                met = DASH if goal is None else ("met" if best["resolve"] >= goal else "not met")
                b = base_ms.get(view, [])
                best_rows.append([f"{view[0]} {view[1]}", order[0], tables.fmt(best["resolve"], 3) + "x",
                                  tables.fmt(best.get("total"), 3) + "x" if best.get("total") else DASH,
                                  f"{goal:g}x" if goal else DASH, met,
                                  f"{f_ms(min(b))}–{f_ms(max(b))}" if b else DASH])
        lines += table(["view", "resolve", "resolve ms", "resolve speedup", "total speedup", "memory ns"], body,
                       [False, False, True, True, True, True])
        lines += [f"The fastest per view, and how far {BASE} itself moved between the view's groups (the "
                  "reason only paired ratios are compared):", ""]
        lines += table(["view", "fastest resolve", "resolve speedup", "total speedup", "goal", "goal met",
                        f"{BASE} resolve ms across groups"], best_rows, [False, False, True, True, True, False, True])
        lines += ["A list that arrives far-to-near needs no sort and one that arrives near-to-far only a "
                  "reversal: the order check turns both into a load and a pass, where every sort still pays for "
                  "its comparisons. The register networks sort without a branch, so on a driver that runs `if` "
                  "as masked straight-line code they cost their fixed size and no more.", ""]
    sort = f.rows(name, "sort")
    if sort:
        r0 = sort[0]
        ms_of = {(r["variant"], r["n"]): ms(r) for r in sort}
        body = []
        for n in sorted({r["n"] for r in sort}, key=int):
            rbs = ms_of.get(("rbs", n))
            for v in ("insertion-v2", "bitonic-network", "odd-even-merge-network"):
                if (v, n) in ms_of:
                    body.append([n, v, f_ms(ms_of[(v, n)]), f_ms(rbs), tables.fmt(ratio(ms_of[(v, n)], rbs), 3),
                                 word(ratio(ms_of[(v, n)], rbs))])
        lines += [f"The register networks against RS, the insertion network of the RBS block sort (`sort` "
                  f"experiment in the same preset, {res(r0)}, {r0.get('keys', '?')} keys, registers, one "
                  "interleaving group): time / RS's time.", ""]
        lines += table(["n", "sort", "ms", "RS ms", "/ RS", ""], body, [True, False, True, True, True, False])
    return lines

def section_knowles2013(f):
    name = "knowles2013"
    lines = ["## Exact OIT: Knowles 2013", "",
             "BMA against the baseline, Knowles 2013 table 2.", ""]
    if not f.run(name):
        return lines + missing(name)
    pairs = f.paper_pairs(name, "knowles2013-2")
    groups = {}
    for r in f.rows(name, "oit", pass_=None):
        groups.setdefault((r["scene"], r["view"], res(r), max_frags_used(r)), {})[(r["technique"], r["pass"])] = ms(r)
    body, auto = [], []
    for key in sorted(groups, key=lambda k: (scene_key(k[0]), int(k[3] or 0))):
        g = groups[key]
        base, bma = g.get((BASE, "total")), g.get((BMA, "total"))
        pscene = PAPER_SCENE.get(key[0], key[0])
        p = next((r["paper"] for k, r in pairs.items() if k[0] == "BMA-OIT" and k[2] == pscene and k[1] == key[3]
                  and k[4] == "total_speedup_vs_OIT"), None)
        a = ratio(base, g.get((BMA_AUTO, "total")))
        auto.append(a)
        body.append([key[0], key[1], key[2], key[3], f_ms(base), f_ms(bma), f_x(ratio(base, bma)),
                     f"{f_paper(p)} ({pscene})" if p is not None else DASH, f_x(a),
                     f_ms(g.get((BASE, "resolve")))])
    r0 = f.rows(name, "oit")[0]
    lines += [f"`presets/{name}.csv` ({f.reps(name, r0)}): `total` ms and the speedup over {BASE} "
              "(the paper's OIT); the paper's BMA-OIT speedup on its GPU (GTX 670, 1680x1050) for the scene "
              "our stand-in replaces.", ""]
    lines += table(["scene", "view", "resolution", "MAX_FRAGS", BASE, BMA, f"{BMA} speedup",
                    "paper", f"{BMA_AUTO} speedup", f"{BASE} resolve"], body,
                   [False, False, False, True, True, True, True, False, True, True])
    smoke = sorted((k for k in groups if k[0] == "smoke"), key=lambda k: int(k[3] or 0))
    if len(smoke) >= 2:
        lo, hi = groups[smoke[0]], groups[smoke[-1]]
        p_lo = f.paper("knowles2013-bma", "2", "OIT", "total_time", scene="smoke", size=smoke[0][3])
        p_hi = f.paper("knowles2013-bma", "2", "OIT", "total_time", scene="smoke", size=smoke[-1][3])
        lines.append(f"- Smoke, MAX_FRAGS {smoke[0][3]} \u2192 {smoke[-1][3]}: {BASE} total "
                     f"{f_ms(lo.get((BASE, 'total')))} \u2192 {f_ms(hi.get((BASE, 'total')))} ms, resolve "
                     f"{f_ms(lo.get((BASE, 'resolve')))} \u2192 {f_ms(hi.get((BASE, 'resolve')))} ms; the "
                     f"paper's OIT {f_ms(p_lo)} \u2192 {f_ms(p_hi)} ms.")
    lines.append(f"- {BMA_AUTO}'s total speedup over {BASE}: {span(auto)}x; against {BASE}, "
                 f"{verdict([1 / a for a in auto if a])}.")
    lines += ["", "A bigger MAX_FRAGS costs the baseline little here, because no occupancy is lost to a bigger "
              "local array on a CPU; so BMA, which exists to avoid that cost, has nothing to win.", ""]
    return lines


def section_scale(f):
    name = "oit-scale"
    lines = ["## Exact OIT at scale", ""]
    if not f.run(name):
        return lines + missing(name)
    body = []
    for r in sorted(f.rows(name, "oit", valid=False), key=lambda r: (case_key(r), r.get("capture", ""),
                                                                     r["technique"])):
        status = oitres.status_of(r)
        body.append([r["scene"], r.get("detail", ""), r["view"], res(r), r.get("capture", ""), r["technique"],
                     max_frags_used(r), status, f_m(num(r, "total_fragments")), f_mb(num(r, "node_pool_bytes")),
                     f_m(num(r, "fragments_per_s")), f_ms(ms(r)) if status == "ok" else DASH])
    r0 = f.rows(name, "oit", valid=False)[0]
    lines += [f"`presets/{name}.csv` ({f.reps(name, r0)}, every case validated): fragments, the storage's "
              "memory (`node_pool_bytes`), capture rate and `total` ms. Why a case is not ok: above.", ""]
    lines += table(["scene", "detail", "view", "resolution", "capture", "technique", "MAX_FRAGS", "status",
                    "fragments", "memory", "fragments/s", "total ms"], body, [False] * 8 + [True] * 4)
    ok = [r for r in f.rows(name, "oit")]
    if ok:
        big = max(ok, key=lambda r: (num(r, "node_pool_bytes") or 0, r["technique"]))
        lines.append(f"- {len(ok)} of {len(body)} cases valid; the largest valid storage: {big['scene']} at "
                     f"{res(big)}, {f_m(num(big, 'total_fragments'))} fragments in "
                     f"{f_mb(num(big, 'node_pool_bytes'))} ({big.get('capture', '')}).")
    lines += ["", "Past llvmpipe's texel-buffer limit a case is `unsupported` with the reason; past its loop "
              "budget (a shader invocation's loops end after a fixed total number of iterations) the deep "
              "resolves go wrong and the validator marks them `invalid`.", ""]
    return lines
