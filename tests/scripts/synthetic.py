"""Small oitbench-shaped CSVs for the script tests, written with the framework's real column layout
(base columns, then metric columns, then parameter columns) so the scripts see what a run writes."""
import csv
import math
import os
import random
import sys

SCRIPTS = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))), "scripts")
sys.path.insert(0, SCRIPTS)
from oitbench import results as oitres  # noqa: E402

RENDERER = "Synthetic GPU (test)"


def write_summary(path, rows, metrics=(), params=(), raw_path=None, reps=5, rng=None, renderer=RENDERER):
    """rows: dicts with experiment, variant, pass, median_ms (and any metric/param values).
    Missing framework fields get plausible values; with raw_path, `reps` samples per row are written
    around the median (and min/max/mad match them)."""
    rng = rng or random.Random(7)
    params = list(params) + [p for p in oitres.FRAMEWORK_PARAMS if p not in params]
    header = oitres.BASE_COLUMNS + list(metrics) + params
    raw_rows = []
    out = []
    for r in rows:
        full = {c: "" for c in header}
        full.update({"schema": "1", "status": "ok", "valid": "1", "backend": "egl", "device": "test",
                     "gl_vendor": "test", "gl_renderer": renderer, "gl_version": "4.5", "width": "64",
                     "height": "64", "reps": str(reps), "warmup": "1", "timer": "cpu", "git_sha": "abc123",
                     "timestamp_utc": "2026-01-01T00:00:00Z", "hostname": "test", "fault": "none", "seed": "1"})
        full.update({k: str(v) for k, v in r.items() if k != "noise"})
        if full["status"] == "ok" and full.get("median_ms"):
            med = float(full["median_ms"])
            noise = r.get("noise", 0.05)
            samples = sorted(med * math.exp(rng.gauss(0, noise)) for _ in range(reps))
            shift = med / oitres.median(samples)  # keep the stated median exactly
            samples = [s * shift for s in samples]
            mad = oitres.median([abs(s - med) for s in samples])
            full.update({"mad_ms": f"{mad:.6g}", "min_ms": f"{samples[0]:.6g}", "max_ms": f"{samples[-1]:.6g}",
                         "samples": str(reps), "mean_ms": f"{sum(samples) / reps:.6g}"})
            for i, s in enumerate(samples):
                raw = {"schema": "1", "experiment": full["experiment"], "variant": full["variant"],
                       "pass": full["pass"], "rep": str(i), "cpu_ms": f"{s:.6g}", "gpu_ms": "-1",
                       "backend": "egl", "gl_renderer": renderer, "git_sha": "abc123",
                       "timestamp_utc": full["timestamp_utc"], "preset": ""}
                raw.update({p: full[p] for p in params})
                raw_rows.append(raw)
        elif full["status"] != "ok":
            full["valid"] = "0"
        out.append(full)
    with open(path, "w", newline="", encoding="utf-8") as f:
        w = csv.DictWriter(f, fieldnames=header, lineterminator="\n")
        w.writeheader()
        w.writerows(out)
    if raw_path:
        raw_header = oitres.RAW_BASE_COLUMNS + params
        with open(raw_path, "w", newline="", encoding="utf-8") as f:
            w = csv.DictWriter(f, fieldnames=raw_header, lineterminator="\n")
            w.writeheader()
            w.writerows(raw_rows)
    return path


def occupancy_rows(draws=8, slow=1.0):
    rows = []
    for variant in ("dynamic", "unrolled"):
        for size in (1, 2, 4, 8, 16, 32, 33, 64):
            per_draw = 0.5 + 0.1 * size if variant == "dynamic" else (0.3 + 0.02 * size if size <= 32 else 0.6 * size)
            rows.append({"experiment": "occupancy", "variant": variant, "pass": "total", "size": size,
                         "draws": draws, "model_gpu": "auto", "median_ms": per_draw * draws * slow,
                         "predicted_occupancy": f"{min(1.0, 64 / (16 + 4 * size)):.3f}",
                         "model_gpu_used": "gtx670"})
    rows.append({"experiment": "occupancy", "variant": "unrolled", "pass": "total", "size": 128, "draws": draws,
                 "model_gpu": "auto", "status": "ok", "valid": "0", "median_ms": 99,
                 "reason": "42 pixels differ from the CPU reference", "mismatched_pixels": 42})
    return rows


OCCUPANCY_METRICS = ["predicted_occupancy", "predicted_threads_per_sm", "model_gpu_used", "mismatched_pixels"]
OCCUPANCY_PARAMS = ["size", "draws", "model_gpu"]


def sort_rows():
    rows = []
    for keys in ("random", "reverse"):
        for variant, cost in (("insertion-direct", 1.0), ("insertion-loop", 0.3), ("insertion-switch", 0.35),
                              ("insertion-if-else", 0.33), ("bubble-early-out", 0.5), ("bubble-no-early-out", 0.6)):
            for n in (4, 8, 16, 32):
                rows.append({"experiment": "sort", "variant": variant, "pass": "total", "n": n, "keys": keys,
                             "median_ms": cost * n * n / 16 * (1.5 if keys == "reverse" else 1.0)})
    return rows


OIT_TECHNIQUES = {"base-is": (1.0, 0.0), "base-ims": (0.8, 0.0), "base-rbs": (0.6, 0.0), "bma-is": (0.5, 0.0),
                  "bma-ims": (0.4, 0.0), "bma-rbs": (0.25, 0.0), "weighted-blend": (0.05, 0.08),
                  "k-buffer": (0.15, 0.01)}


def oit_rows():
    rows = []
    for scene in ("planes", "hairball"):
        for size in (64, 128):
            for variant, (cost, err) in OIT_TECHNIQUES.items():
                capture = 2.0 * size / 64
                resolve = 10.0 * cost * size / 64
                common = {"experiment": "oit", "variant": variant, "scene": scene, "max_frags": size,
                          "rmse": f"{err:.4f}", "max_abs_error": f"{err * 4:.4f}"}
                rows.append(dict(common, **{"pass": "capture", "median_ms": capture}))
                rows.append(dict(common, **{"pass": "resolve", "median_ms": resolve}))
                rows.append(dict(common, **{"pass": "total", "median_ms": capture + resolve + 0.1}))
    rows.append({"experiment": "oit", "variant": "spinlock-naive", "pass": "total", "scene": "planes",
                 "max_frags": 64, "status": "timeout", "reason": "watchdog: no progress for 10 s"})
    return rows


def simple_rows(experiment, variants, param, values, scale=1.0):
    return [{"experiment": experiment, "variant": v, "pass": "total", param: x,
             "median_ms": scale * (i + 1) * (1 + float(x) if isinstance(x, (int, float)) else 1 + j)}
            for i, v in enumerate(variants) for j, x in enumerate(values)]
