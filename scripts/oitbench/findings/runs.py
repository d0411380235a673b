"""FINDINGS.md's sections about the runs themselves: what ran, what was not ok, warm-up and the scenes."""
import re

from oitbench import results as oitres
from oitbench import figures as plot
from oitbench import papers as tables
from oitbench.findings.common import (
    DASH, f_ms, f_num, field, max_frags_used, num, res, scene_key, stamp, table, view_key)
from oitbench.findings.approx import approx_label


def section_runs(f):
    lines = ["## The runs", ""]
    every = [r for run in f.runs.values() for r in run.rows]
    facts = []
    for col, label in (("gl_renderer", "renderer"), ("gl_version", "GL"), ("backend", "backend"),
                       ("device", "device"), ("cpu_model", "CPU"), ("lp_num_threads", "LP_NUM_THREADS"),
                       ("timer", "primary clock"), ("hostname", "host")):
        values = sorted({r.get(col, "") for r in every if r.get(col, "")})
        if values:
            facts.append(f"{label} {', '.join(f'`{v}`' for v in values)}")
    envs = sorted({r.get("env", "") for r in every if r.get("env", "")})
    facts.append("environment " + (", ".join(f"`{e}`" for e in envs) if envs else "none recorded"))
    lines += ["On " + "; ".join(facts) + ".", ""]
    rows = []
    for name, run in sorted(f.runs.items()):
        totals = [r for r in run.rows if r.get("pass") == "total"]
        count = {s: sum(1 for r in totals if oitres.status_of(r) == s)
                 for s in ("ok", "invalid", "unsupported", "error", "timeout")}
        times = sorted(t for t in (stamp(r.get("timestamp_utc")) for r in run.rows) if t)
        took = ""
        if times:
            secs = int((times[-1] - times[0]).total_seconds())
            took = f"{secs // 60}m{secs % 60:02d}s"
        rows.append([f"`{name}`", len(totals)] + [count[s] for s in count] +
                    [", ".join(sorted({res(r) for r in totals}, key=lambda s: [int(x) for x in s.split("x")])),
                     ", ".join(sorted({r.get("reps", "") for r in totals}, key=int)),
                     ", ".join(sorted({r.get("git_sha", "") for r in run.rows})),
                     times[0].strftime("%Y-%m-%d %H:%M") if times else "", took])
    lines += ["One CSV per preset in [presets/](presets/). Cases count `total` rows; *rows span* is the time "
              "between the first and the last row's timestamp, a lower bound of the preset's wall time.", ""]
    lines += table(["preset", "cases", "ok", "invalid", "unsupported", "error", "timeout", "resolution", "reps",
                    "commit", "first row (UTC)", "rows span"], rows,
                   [False] + [True] * 6 + [False] * 3 + [False, True])
    return lines


def normalised_reason(reason):
    """The reason's first line with its numbers blanked: cases failing the same way group together."""
    return re.sub(r"[0-9][0-9.e+-]*", "#", (reason.strip().splitlines() or [""])[0])


# Parameters that name a case in the list of failures (the rest vary or say little).
IDENTIFYING = ("technique", "scene", "view", "capture", "memory", "layers", "n", "size")


def section_not_ok(f):
    lines = ["## Cases that are not ok", "",
             "Every case whose status is not `ok`, grouped where only the numbers in the reason differ. An "
             "`invalid` case ran but its result differs from the CPU reference, so it carries no time; an "
             "`unsupported` one needs what this driver lacks.", ""]
    rows = []
    for name, run in sorted(f.runs.items()):
        groups = {}
        for exp in run.experiments():
            params = [p for p in run.params(exp) if p not in oitres.FRAMEWORK_PARAMS]
            for r in run.rows_of(exp):
                if r.get("pass") != "total" or oitres.is_ok(r):
                    continue
                key = (exp, oitres.status_of(r), normalised_reason(r.get("reason", "")))
                groups.setdefault(key, (params, []))[1].append(r)
        for (exp, status, _), (params, group) in groups.items():
            vary = oitres.varying(group, params)
            # What the cases have in common that names them, then each case (or each varying value).
            same = [f"{p}={group[0][p]}" for p in IDENTIFYING if p in params and p not in vary and group[0].get(p)]
            head = " ".join(x for x in [group[0].get("variant", "")] + same if x)
            if len(group) <= 4:
                each = "; ".join(" ".join(f"{p}={r[p]}" for p in vary if r.get(p)) for r in group)
            else:
                each = "; ".join(f"{p} " + ", ".join(sorted({r[p] for r in group}, key=oitres.sort_key))
                                 for p in vary)
            cases = ": ".join(x for x in (head, each) if x)
            first = (group[0].get("reason", "").strip().splitlines() or [""])[0]
            first = first if len(first) <= 240 else first[:239] + "\u2026"
            rows.append([f"`{name}`", exp, status, len(group), cases.replace("|", "/"),
                         first.replace("|", "/")])
    if not rows:
        return lines + ["Every case of every preset is `ok`.", ""]
    lines += table(["preset", "experiment", "status", "cases", "which", "reason (of the first)"], rows,
                   [False, False, False, True, False, False])
    return lines


def case_label(row, vary):
    """'oit hairball rev MLAB/8 interleaved' or 'sort rbs n=32 memory=registers': what a reader needs to find
    the case. oit rows are named by technique (plot.oit_label), so a parameter that does not apply to a
    technique, empty in schema 2, changes nothing."""
    if row.get("experiment") == "oit":
        parts = [row.get("scene", ""), row.get("view", ""), approx_label(row)]
        if row.get("capture", "") not in ("", "PPLL"):
            parts.append(row["capture"])
        if "detail" in vary:
            parts.append(f"detail={row.get('detail', '')}")
        return "oit " + " ".join(p for p in parts if p)
    return f"{row.get('experiment', '')} " + oitres.describe_case(row, [p for p in vary if p != "max_frags"])


def section_warmup(f):
    lines = ["## Preparation and the first draw", "",
             "`compile_ms` is compile, link and set-up; `warmup_ms` the first warm-up repetition, where "
             "llvmpipe JIT-compiles the shader; neither enters the statistics. `program_cache` counts how "
             "many cases' programs came from oitbench's program cache.", ""]
    rows = []
    for name, run in sorted(f.runs.items()):
        cases = []
        for exp in run.experiments():
            params = [p for p in run.params(exp) if p not in oitres.FRAMEWORK_PARAMS]
            vary = oitres.varying(run.rows_of(exp), params)
            cases += [(r, vary) for r in run.rows_of(exp) if r.get("pass") == "total"]
        out = [f"`{name}`"]
        for col in ("compile_ms", "warmup_ms"):
            best = max(cases, key=lambda c: num(c[0], col) or -1.0)
            x = num(best[0], col)
            out.append(f"{f_ms(x)} ({case_label(best[0], best[1])})" if x is not None else DASH)
        cache = {}
        for r, _ in cases:
            if r.get("program_cache"):
                cache[r["program_cache"]] = cache.get(r["program_cache"], 0) + 1
        out.append(", ".join(f"{k} {v}" for k, v in sorted(cache.items())) or DASH)
        rows.append(out)
    lines += table(["preset", "largest compile_ms (case)", "largest warmup_ms (case)", "program_cache"], rows,
                   [False, False, False, False])
    return lines


def section_scenes(f):
    lines = ["## Scenes", "",
             "Statistics of the shipped scenes as captured (`polygons`, `total_fragments`, `peak_depth`, "
             "`mean_depth`, and the MAX_FRAGS the case used), from the first valid exact case of each scene, "
             "detail, view and resolution in these presets.", ""]
    seen = {}
    for name in ("knowles2014", "knowles2013", "error-vs-time", "capture-storage", "oit-scale"):
        for r in f.rows(name, "oit"):
            if r["technique"] in plot.OIT_APPROX:
                continue
            key = (r["scene"], r.get("detail", ""), r["view"], res(r))
            seen.setdefault(key, (name, r))
    body = []
    for key in sorted(seen, key=lambda k: (scene_key(k[0]), k[1], view_key(k[2]),
                                           [int(x) for x in k[3].split("x")])):
        name, r = seen[key]
        body.append(list(key) + [f_num(num(r, "polygons")), f_num(num(r, "total_fragments")), field(r, "peak_depth"),
                                 tables.fmt(num(r, "mean_depth"), 3), max_frags_used(r), f"`{name}`"])
    lines += table(["scene", "detail", "view", "resolution", "polygons", "fragments", "peak depth", "mean depth",
                    "MAX_FRAGS", "from"], body, [False] * 4 + [True] * 5 + [False])
    return lines
