"""What scripts/gpu-run.sh would cost on a GPU, projected from its --smoke run (issue 28 item 4): for each step,
the full run's cases (from `oitbench run --dry-run` with the step's GPU-size arguments) times the time a case
spends outside its samples, as the smoke run measured it here, plus its samples estimated from the papers' GPU
timings (results/published). The day a GPU runs the script, its own time account meets this estimate.

The estimate of a sample: each repetition is one frame (or one pass) of the paper's nearest measurement, never
under the sampler's 20 ms floor (a sample repeats a short frame until it lasts --min-sample-ms), and a case
runs warm-up + reps of them. Outside the samples, a case's reference, read-back and validation are scaled from
the smoke size to the step's by pixels (the scenes' small detail is not scaled up: a lower bound there); its
compile, scene and the rest are taken as measured. The papers' GPUs (GTX Titan, GTX 1080) are older than most a user has: an upper
bound for the samples, while the non-sample time measured on llvmpipe includes its JIT compiles (slower than a
GPU driver's) and is an upper bound too.
"""
import csv
import os
import re
import statistics

from oitbench import timeaccount

MIN_SAMPLE_MS = 20.0  # micro/core/sampling.hpp: SamplingPolicy::min_sample_ms


def _rows(published, name):
    path = os.path.join(published, name)
    if not os.path.isfile(path):
        return []
    with open(path, newline="", encoding="utf-8") as f:
        return list(csv.DictReader(f))


def _median(values):
    vals = []
    for v in values:
        try:
            vals.append(float(v))
        except (TypeError, ValueError):
            continue
    return statistics.median(vals) if vals else None


def _pixels(res):
    try:
        w, h = res.split("x")
        return int(w) * int(h)
    except (AttributeError, ValueError):
        return None


# Each step: which published rows stand for one repetition of its cases, and at what resolution they were
# measured (scaled by pixels to the step's resolution). `what` says it in the printed line.
def _frame_estimates(published):
    k14 = _rows(published, "knowles2014_table2_times.csv")
    approx = _rows(published, "bruell2018_tables5_6_approx.csv")
    micro = _rows(published, "bruell2018_appendix_micro.csv")
    fullscreen = _median(r["value"] for r in micro if r["table"] == "A.4" and r["metric"] == "fullscreen_pass_time")
    return {
        "occupancy": (fullscreen, "800x800", "Bruell 2018 A.4's full-screen pass (GTX 1080) per draw", "draws"),
        "sort": (_median(r["value"] for r in micro if r["table"] in ("A.1", "A.3")), "800x800",
                 "Bruell 2018 A.1/A.3 sorts (GTX 1080)", None),
        "knowles2014": (_median(r["value"] for r in k14 if r["metric"] == "total_time" and
                                r["scene"] in ("planes", "hairball")), "1920x1080",
                        "Knowles 2014 table 2, planes and hairball totals (GTX Titan)", None),
        "knowles2014-engine-grid": (_median(r["value"] for r in k14 if r["metric"] == "total_time" and
                                            r["scene"] == "powerplant"), "1920x1080",
                                    "Knowles 2014 table 2, power plant totals (GTX Titan)", None),
        "bruell2018-approx": (_median(r["value"] for r in approx if r["metric"] == "total_time"), "800x800",
                              "Bruell 2018 tables 5.1-6.3 totals (GTX 1080)", None),
    }


def _smoke_pixels(path):
    """The pixels of a smoke CSV's cases (the first total row's width x height)."""
    with open(path, newline="", encoding="utf-8") as f:
        for r in csv.DictReader(f):
            try:
                return int(r["width"]) * int(r["height"])
            except (KeyError, TypeError, ValueError):
                continue
    return None


PLAN_LINE = re.compile(r"^plan: (\S+) (\d+x\d+) cases=(\d+) reps=(?:(\d+)|auto \((\d+)-(\d+)\)) warmup=(\d+)$")


def parse_plan(text):
    """The `plan:` lines of `oitbench run --dry-run`: [(experiment, 'WxH', cases, reps, warmup)]; reps is
    the fixed count, or the adaptive rule's most (`auto (MIN-MAX)`)."""
    out = []
    for line in text.splitlines():
        m = PLAN_LINE.match(line.strip())
        if m:
            reps = int(m.group(4) or m.group(6))
            out.append((m.group(1), m.group(2), int(m.group(3)), reps, int(m.group(7))))
    return out


def projection_lines(smoke_csvs, plans, published, draws=64, prefix="gpu-run.sh: projection"):
    """`smoke_csvs`: the smoke run's step CSVs; `plans`: {step: parse_plan(...) of its full-size dry run}.
    One line per step and one for all: cases, the non-sample seconds (measured here per case), the samples
    (estimated), the sum."""
    per_case = {}  # step: (seconds a case outside its samples that do not grow with pixels, those that do, pixels)
    for path in smoke_csvs:
        step = os.path.splitext(os.path.basename(path))[0]
        acc, pixels = timeaccount.accounts_of_file(path), _smoke_pixels(path)
        if acc is not None and acc.cases:
            scaled = acc.groups["reference+validation"]
            fixed = acc.wall - acc.groups["timed samples"] - scaled
            per_case[step] = (fixed / acc.cases, scaled / acc.cases, pixels)
    estimates = _frame_estimates(published)
    lines, total_s = [], 0.0
    for step, plan in plans.items():
        cases = sum(p[2] for p in plan)
        fixed, scaled, smoke_px = per_case.get(step, (None, 0.0, None))
        frame_ms, at, what, per = estimates.get(step, (None, None, "no paper timing", None))
        samples_s = overhead_s = 0.0
        for _, res, n, reps, warmup in plan:
            if fixed is not None:  # the reference and validation grow with the pixels, the rest does not
                grow = _pixels(res) / smoke_px if smoke_px and _pixels(res) else 1.0
                overhead_s += n * (fixed + scaled * grow)
            if frame_ms is None:
                continue
            ms = frame_ms
            if _pixels(at) and _pixels(res):
                ms *= _pixels(res) / _pixels(at)
            if per == "draws":
                ms *= draws
            samples_s += n * (reps + warmup) * max(ms, MIN_SAMPLE_MS) / 1000.0
        step_s = overhead_s + samples_s
        total_s += step_s
        measured = (f"{fixed:.2f} s a case measured here, its reference and validation {scaled:.2f} s scaled by pixels"
                    if fixed is not None else "not measured")
        lines.append(f"{prefix}: {step}: {cases} cases: outside the samples {overhead_s:.0f} s ({measured}), "
                     f"samples {samples_s:.0f} s (from {what}), about {step_s / 60:.1f} min")
    lines.append(f"{prefix}: all steps: about {total_s / 60:.1f} min on a GPU as fast as the papers' "
                 "(upper bounds: older GPUs, llvmpipe's compiles)")
    return lines
