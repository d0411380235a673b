"""A/B rounds of two configurations, a paired ratio per case: the library behind scripts/ab.py and
report.py --ab."""
import csv
import math
import os
import shlex

from oitbench import casekey
from oitbench import results as oitres
from oitbench.stats import mad, median_interval

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DEFAULT_EXE = os.path.join(REPO, "build", "oitbench")
MIN_EFFECT = 0.01


def round_order(rounds):
    """A B B A A B ...: (config, index of that config's run) for 2 * rounds runs."""
    order = []
    for k in range(rounds):
        pair = ("A", "B") if k % 2 == 0 else ("B", "A")
        order.extend((c, k) for c in pair)
    return order


def set_names(args_text):
    """The parameter names a configuration's arguments set with --set NAME=..."""
    words = shlex.split(args_text or "")
    names = set()
    for i, w in enumerate(words):
        if w == "--set":
            for x in words[i + 1:]:
                if x.startswith("-"):
                    break
                names.add(x.split("=", 1)[0])
        elif w.startswith("--set="):
            names.add(w[len("--set="):].split("=", 1)[0])
    return names


def case_key(row, skip):
    """The case and the parameters it names, less those A and B set differently."""
    return casekey.named_key(row, skip)


def describe(key):
    exp, variant, pas, w, h = key[:5]
    parts = [exp] + ([variant] if variant else []) + [p for p in key[5:]
                                                     if not p.startswith(("seed=", "fault=none"))]
    if pas != "total":
        parts.append(f"pass={pas}")
    parts.append(f"{w}x{h}")
    return " ".join(parts)


def medians(path, skip):
    """{case key: median_ms} of a round's ok rows."""
    header, rows = oitres.read_csv(path)
    oitres.check_summary_header(path, header)
    out = {}
    for r in rows:
        m = oitres.to_float(r.get("median_ms"))
        if oitres.is_ok(r) and m is not None and m > 0:
            out.setdefault(case_key(r, skip), m)
    return out


def run_identity(path):
    _, rows = oitres.read_csv(path)
    r = rows[0] if rows else {}
    return (f"driver {r.get('driver', '?')} ({r.get('gl_renderer', '?')}), git {r.get('git_sha', '?')}, "
            f"LP_NUM_THREADS {r.get('lp_num_threads', '?')}, env {r.get('env') or '-'}")


class CaseResult:
    def __init__(self, key, a, b, min_effect, confidence):
        self.key = key
        n = min(len(a), len(b))
        self.ratios = [b[i] / a[i] for i in range(n)]
        self.ratio = oitres.median(self.ratios) if self.ratios else float("nan")
        self.ci = median_interval(self.ratios, confidence) if self.ratios else None
        # Neighbouring runs of one configuration: A(k) with A(k+1) where they are adjacent in A B B A A B ...
        logs = []
        for series in (a, b):
            logs += [math.log(series[i + 1] / series[i]) for i in range(len(series) - 1)]
        self.noise = 100 * (math.exp(oitres.robust_sigma(mad(logs))) - 1) if len(logs) >= 2 else float("nan")
        if self.ci is None:
            self.verdict = "too few round pairs for an interval"
        elif self.ci[0] > 1 + min_effect:
            self.verdict = "SLOWER"
        elif self.ci[1] < 1 / (1 + min_effect):
            self.verdict = "FASTER"
        else:
            self.verdict = "no difference resolved"
        self.flagged = self.verdict in ("SLOWER", "FASTER")


def compare_rounds(a_paths, b_paths, skip, min_effect):
    """CaseResults of the cases every round of both configurations has, and the keys left out."""
    a = [medians(p, skip) for p in a_paths]
    b = [medians(p, skip) for p in b_paths]
    keys = [k for k in a[0] if all(k in r for r in a + b)] if a else []
    left_out = sorted({k for r in a + b for k in r} - set(keys))
    confidence = 1 - 0.05 / max(1, len(keys))
    return [CaseResult(k, [r[k] for r in a], [r[k] for r in b], min_effect, confidence) for k in keys], left_out


TABLE_COLUMNS = ["experiment", "case", "pass", "ratio", "ci_low", "ci_high", "noise_pct", "verdict", "flagged",
                 "pairs", "pair_ratios"]


def write_table(path, results):
    with open(path, "w", newline="", encoding="utf-8") as f:
        w = csv.writer(f)
        w.writerow(TABLE_COLUMNS)
        for r in results:
            w.writerow([r.key[0], describe(r.key), r.key[2], f"{r.ratio:.6g}",
                        f"{r.ci[0]:.6g}" if r.ci else "", f"{r.ci[1]:.6g}" if r.ci else "",
                        f"{r.noise:.3g}", r.verdict, int(r.flagged), len(r.ratios),
                        ";".join(f"{x:.5g}" for x in r.ratios)])


def read_table(path):
    """ab.csv's rows (write_table's), each with `ratio`, `ci_low`, `ci_high` (None when empty) and
    `pair_ratios` as numbers; ResultsError naming FILE:LINE for anything else (garbage, a binary file, a
    missing column, a number that is not one)."""
    header, rows = oitres.read_csv(path)
    missing = [c for c in TABLE_COLUMNS if c not in header]
    if missing:
        raise oitres.ResultsError(f"{path}:1: not an ab.py table (ab.csv; no column {', '.join(missing)})")
    out = []
    for line, r in enumerate(rows, 2):
        def number(column, text, empty_ok):
            if text == "" and empty_ok:
                return None
            x = float("nan") if text.strip().lower() == "nan" else oitres.to_float(text)
            if x is None:
                raise oitres.ResultsError(f"{path}:{line}: {column} '{text}' is not a number")
            return x
        row = dict(r)
        row["ratio"] = number("ratio", r["ratio"], False)
        row["ci_low"] = number("ci_low", r["ci_low"], True)
        row["ci_high"] = number("ci_high", r["ci_high"], True)
        row["pair_ratios"] = [number("pair_ratios", x, False) for x in r["pair_ratios"].split(";") if x]
        out.append(row)
    return out


def figure(plt, entries, title, xlabel):
    """Paired ratios per round pair (|), their median (o) and interval (line; red where flagged), one line per
    entry (label, ratios, ci_low, ci_high, ratio, flagged): the figure of ab.py and of report.py --ab."""
    fig, ax = plt.subplots(figsize=(9, 1.4 + 0.3 * len(entries)))
    for y, (_, ratios, lo, hi, ratio, flagged) in enumerate(entries):
        colour = "red" if flagged else "C0"
        ax.plot(ratios, [y] * len(ratios), "|", color="grey", markersize=8)
        if lo is not None and hi is not None:
            ax.plot([lo, hi], [y, y], color=colour, linewidth=2)
        ax.plot([ratio], [y], "o", color=colour)
    ax.axvline(1.0, color="black", linewidth=0.8)
    ax.set_yticks(range(len(entries)))
    ax.set_yticklabels([e[0] for e in entries], fontsize=8)
    ax.invert_yaxis()
    ax.set_xlabel(xlabel)
    ax.set_title(title, fontsize=10)
    ax.grid(True, axis="x", alpha=0.3)
    return fig


def draw(out_dir, results, labels):
    os.environ.setdefault("MPLBACKEND", "Agg")
    import matplotlib
    matplotlib.use(os.environ["MPLBACKEND"])
    import matplotlib.pyplot as plt
    written = []
    by_exp = {}
    for r in results:
        by_exp.setdefault(r.key[0], []).append(r)
    for exp, rs in by_exp.items():
        entries = [(describe(r.key), r.ratios, r.ci[0] if r.ci else None, r.ci[1] if r.ci else None, r.ratio,
                    r.flagged) for r in rs]
        fig = figure(plt, entries, f"{exp}: {sum(r.flagged for r in rs)} of {len(rs)} cases flagged",
                     f"{labels[1]} / {labels[0]}: paired ratio per round (|), median and interval (>1: "
                     f"{labels[1]} slower)")
        with plt.rc_context({"svg.hashsalt": "oitbench"}):
            for fmt in ("png", "svg"):
                path = os.path.join(out_dir, f"ab-{exp}.{fmt}")
                fig.savefig(path, dpi=120, bbox_inches="tight", metadata={"Date": None} if fmt == "svg" else None)
                written.append(path)
        plt.close(fig)
    return written


def summarize(dirs):
    """Trials of one comparison (ab.py's out dirs): how many flagged anything, and per case how often it
    was flagged slower or faster, its ratios and the span of its intervals."""
    per_case = {}
    flagged_trials = 0
    for d in dirs:
        if not os.path.isdir(d):
            raise oitres.ResultsError(f"{d}: not a folder (--summarize takes ab.py's out folders)")
        rows = read_table(os.path.join(d, "ab.csv"))
        flagged_trials += any(r["flagged"] == "1" for r in rows)
        for r in rows:
            per_case.setdefault(r["case"], []).append(r)
    lines = [f"{len(dirs)} trial(s); {flagged_trials} with a flagged case"]
    for case, rs in per_case.items():
        ratios = [r["ratio"] for r in rs]
        los = [r["ci_low"] for r in rs if r["ci_low"] is not None]
        his = [r["ci_high"] for r in rs if r["ci_high"] is not None]
        noise = [float(r["noise_pct"]) for r in rs if r["noise_pct"] not in ("", "nan")]
        lines.append(f"{case}: slower in {sum(r['verdict'] == 'SLOWER' for r in rs)}/{len(rs)}, faster in "
                     f"{sum(r['verdict'] == 'FASTER' for r in rs)}/{len(rs)}; ratio {min(ratios):.3f}-"
                     f"{max(ratios):.3f} (median {oitres.median(ratios):.3f}); intervals within "
                     + (f"{min(los):.3f}-{max(his):.3f}" if los and his else "-")
                     + (f"; neighbouring identical runs {oitres.median(noise):.1f}% apart (median)" if noise else ""))
        # Every trial's round pairs together: as one A/B run of that many rounds.
        pooled = [x for r in rs for x in r["pair_ratios"]]
        ci = median_interval(pooled, 1 - 0.05 / max(1, len(per_case))) if pooled else None
        if ci:
            lines.append(f"  pooled over the trials: {len(pooled)} round pairs, ratio {oitres.median(pooled):.3f} "
                         f"[{ci[0]:.3f}, {ci[1]:.3f}]")
    return "\n".join(lines)


def parse_env(items, ap):
    env = {}
    for item in items or []:
        if "=" not in item:
            ap.error(f"expected NAME=VALUE, got '{item}'")
        k, v = item.split("=", 1)
        env[k] = v
    return env
