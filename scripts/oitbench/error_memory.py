"""The fixed-memory techniques side by side: per scene and view, each oit case's error against the exact
image beside its bytes per pixel (tables.py --error-memory). The size of a case is the values of the
technique-sizing parameters it reads (the technique table says which), so a new technique needs no entry
here."""
from oitbench import results as oitres
from oitbench import techniques

# Parameters a technique reads that do not size it (they are the same for every case of a comparison).
NOT_SIZES = {"flicker_runs", "guard", "storage", "sync"}
COLUMNS = ("scene", "view", "resolution", "technique", "size", "bytes_per_pixel", "rmse", "max_abs_error",
           "model_max_diff", "status")


def size_of(row):
    name = row.get("technique", "")
    return " ".join(f"{p}={row[p]}" for p in techniques.params(name) if p not in NOT_SIZES and row.get(p))


def rows_of(runs):
    """One dict per oit case (its `total` row), ordered by scene, view, bytes per pixel and rmse."""
    out = []
    for run in runs:
        for r in run.rows_of("oit"):
            if r.get("pass") != "total" or not r.get("rmse"):
                continue
            out.append({"scene": r.get("scene", ""), "view": r.get("view", ""),
                        "resolution": f"{r.get('width')}x{r.get('height')}", "technique": r.get("technique", ""),
                        "size": size_of(r), "bytes_per_pixel": r.get("bytes_per_pixel", ""),
                        "rmse": r.get("rmse", ""), "max_abs_error": r.get("max_abs_error", ""),
                        "model_max_diff": r.get("model_max_diff", ""), "status": oitres.status_of(r)})

    def key(d):
        return (d["scene"], d["view"], d["resolution"], oitres.to_float(d["bytes_per_pixel"]) or 0.0,
                oitres.to_float(d["rmse"]) or 0.0)
    return sorted(out, key=key)


def markdown(rows):
    if not rows:
        return "(no oit rows with an rmse)\n"
    lines = ["| " + " | ".join(COLUMNS) + " |", "|" + "---|" * 5 + "---:|" * 4 + "---|"]
    for d in rows:
        lines.append("| " + " | ".join(d[c] for c in COLUMNS) + " |")
    return "\n".join(lines) + "\n"
