"""history: a case (or every case a filter matches) across runs, ordered by date, commit or driver
version, with each run's median and interval and the change points the runs' own noise resolves
(changepoint.py); a figure per case. By commit means by the commit graph of a git repository (parents
before children, `git rev-list --topo-order`); where the repository does not know every run's commit the
runs are ordered by date, and a note says which commits were unknown."""
import os
import subprocess

from oitbench.store import queries
from oitbench.store.changepoint import change_points

ORDERS = ("date", "commit", "driver")


def _commit(sha):
    """A row's git_sha as git reads it: 'f792404458eb-dirty' -> 'f792404458eb' (the build's tree differed
    from that commit; its place in the graph is the commit's)."""
    return (sha or "").strip().split("-")[0]


def commit_ranks(shas, repo):
    """({sha: rank} in the commit graph's order, parents first (`git rev-list --topo-order --reverse` of
    the commits), [the shas `repo` does not know]). Every sha is unknown without a repository or git."""
    shas = sorted(set(shas))
    wanted = [s for s in shas if _commit(s) and _commit(s) != "unknown"]
    if not repo or not wanted:
        return {}, shas
    try:
        check = subprocess.run(["git", "-C", repo, "cat-file", "--batch-check=%(objectname)"],
                               input="".join(f"{_commit(s)}^{{commit}}\n" for s in wanted), capture_output=True,
                               text=True, timeout=60)
        full = {}
        if check.returncode == 0:
            for s, line in zip(wanted, check.stdout.splitlines()):
                if len(line.split()) == 1:  # "SHA missing" / "SHA ambiguous" otherwise
                    full[s] = line.strip()
        if not full:
            return {}, shas
        graph = subprocess.run(["git", "-C", repo, "rev-list", "--topo-order", "--reverse"] + sorted(set(full.values())),
                               capture_output=True, text=True, timeout=60)
    except (OSError, subprocess.SubprocessError):
        return {}, shas
    if graph.returncode != 0:
        return {}, shas
    rank = {c: i for i, c in enumerate(graph.stdout.split())}
    ranks = {s: rank[c] for s, c in full.items() if c in rank}
    return ranks, [s for s in shas if s not in ranks]


def default_repo():
    """The git repository these scripts live in, or None (an installed copy has none)."""
    repo = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
    return repo if os.path.exists(os.path.join(repo, ".git")) else None


def _order_key(order, first_seen, ranks=None):
    def key(r):
        date = r["first_utc"] or ""
        if order == "commit" and ranks is not None:
            return (ranks[r["git_sha"] or ""], date, r["run_id"])
        if order == "commit":
            return (first_seen.get(r["git_sha"], ""), date, r["run_id"])
        if order == "driver":
            version = r["gpu_driver_version"] or r["mesa_version"] or r["gl_renderer"] or ""
            parts = [int(p) if p.isdigit() else p for p in version.replace("-", ".").replace(" ", ".").split(".")]
            return ([(0, p) if isinstance(p, int) else (1, p) for p in parts], date, r["run_id"])
        return (date, r["run_id"])
    return key


class Series:
    """One case's runs in order: rows (run_id, median_ms, ci_lo_ms, ci_hi_ms, ...) and its change points
    [(index, ratio, p)]."""

    def __init__(self, case_key, rows, steps):
        self.case_key, self.rows, self.steps = case_key, rows, steps


STATISTICS = ("median", "mean")


def history(store, flt, experiment=None, case_like=None, order="date", alpha=0.01, min_size=3, repo=None,
            notes=None, statistic="median"):
    """The Series of every case the filter matches. order "commit": by `repo`'s commit graph where it
    knows every run's commit, else by the date each commit was first run, with a line appended to
    `notes` (a list) naming the commits it does not know. `statistic`: each run's value the change points
    are found in, its samples' median or mean (a run without a mean uses its median)."""
    if statistic not in STATISTICS:
        raise ValueError(f"statistic {statistic!r}: expected one of {', '.join(STATISTICS)}")
    rows = [r for r in queries.case_results(store, flt, experiment, case_like)
            if r["status"] == "ok" and r["median_ms"]]
    first_seen = {}
    for r in sorted(rows, key=lambda r: r["first_utc"] or ""):
        first_seen.setdefault(r["git_sha"], r["first_utc"] or "")
    ranks = None
    if order == "commit":
        found, unknown = commit_ranks((r["git_sha"] or "" for r in rows), repo)
        if unknown or not found:
            shown = ", ".join(s or "(none)" for s in unknown[:5]) + (f" and {len(unknown) - 5} more" if len(unknown) > 5 else "")
            where = f"the git repository {repo}" if repo else "no git repository (give --repo DIR)"
            if notes is not None:
                notes.append(f"ordered by the date each commit was first run, not by the commit graph: {where} "
                             f"does not know commit {shown}")
        else:
            ranks = found
    by_case = {}
    for r in rows:
        by_case.setdefault(r["case_key"], []).append(r)
    out = []
    for key in sorted(by_case):
        series = sorted(by_case[key], key=_order_key(order, first_seen, ranks))
        values = [r["mean_ms"] if statistic == "mean" and r["mean_ms"] else r["median_ms"] for r in series]
        steps = change_points(values, alpha=alpha, min_size=min_size) if len(series) >= 2 * min_size else []
        out.append(Series(key, series, steps))
    return out


def machine_warnings(series_list):
    seen = {}
    for s in series_list:
        for r in s.rows:
            if r["hostname"] and r["machine_id"]:
                seen.setdefault(r["hostname"], set()).add(r["machine_id"])
    return [f"hostname '{h}' names {len(ids)} machines (machine_id {', '.join(sorted(ids))}): a step may be a "
            "change of machine" for h, ids in sorted(seen.items()) if len(ids) > 1]


def draw(series_list, path, order):
    """One panel per case (at most 12): each run's median with its interval, a line per change point."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    shown = series_list[:12]
    fig, axes = plt.subplots(len(shown), 1, figsize=(9, 2.4 * len(shown)), squeeze=False)
    for ax, s in zip(axes[:, 0], shown):
        xs = list(range(len(s.rows)))
        med = [r["median_ms"] for r in s.rows]
        lo = [r["ci_lo_ms"] if r["ci_lo_ms"] is not None else r["median_ms"] for r in s.rows]
        hi = [r["ci_hi_ms"] if r["ci_hi_ms"] is not None else r["median_ms"] for r in s.rows]
        ax.fill_between(xs, lo, hi, alpha=0.25, step="mid", label="95% interval")
        ax.plot(xs, med, "o-", ms=3, label="median")
        for i, ratio, p in s.steps:
            ax.axvline(i - 0.5, color="red", ls="--")
            ax.annotate(f"x{ratio:.3f} (p={p:.3g})", (i - 0.5, max(hi)), color="red", fontsize=8)
        ax.set_title(s.case_key, fontsize=8)
        ax.set_ylabel("ms")
        ax.set_xlabel(f"run (by {order})")
    axes[0, 0].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)
