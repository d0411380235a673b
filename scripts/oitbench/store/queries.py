"""The questions users ask the store, the same SQL on both backends: which runs (filtered by tag, driver,
renderer, commit, date), and a case's results across runs."""
from oitbench.store.sqlschema import q

RUN_FIELDS = ["run_id", "first_utc", "hostname", "machine_id", "driver", "gl_renderer", "gpu_driver_version",
              "mesa_version", "git_sha", "preset", "backend", "source"]


class RunFilter:
    """What selects runs: tags KEY=VALUE (all must match), driver, renderer (substring), commit (prefix),
    run id (prefix), preset, hostname, since/until (ISO dates, on the run's first row's time)."""

    def __init__(self, tags=(), driver=None, renderer=None, commit=None, run=None, preset=None, host=None,
                 since=None, until=None):
        self.tags = dict(t.split("=", 1) for t in tags)
        self.driver, self.renderer, self.commit, self.run = driver, renderer, commit, run
        self.preset, self.host, self.since, self.until = preset, host, since, until

    def where(self, alias="runs"):
        """(SQL condition on `alias`, parameters)."""
        conds, params = ["1 = 1"], []
        for k, v in sorted(self.tags.items()):
            conds.append(f"EXISTS (SELECT 1 FROM run_tags t WHERE t.run_id = {alias}.run_id AND t.key = ? AND "
                         "t.value = ?)")
            params += [k, v]
        for col, value, op in (("driver", self.driver, "="), ("preset", self.preset, "="),
                               ("hostname", self.host, "=")):
            if value:
                conds.append(f"{alias}.{q(col)} {op} ?")
                params.append(value)
        if self.renderer:
            conds.append(f"{alias}.gl_renderer LIKE ?")
            params.append(f"%{self.renderer}%")
        if self.commit:
            conds.append(f"{alias}.git_sha LIKE ?")
            params.append(f"{self.commit}%")
        if self.run:
            conds.append(f"{alias}.run_id LIKE ?")
            params.append(f"{self.run}%")
        if self.since:
            conds.append(f"{alias}.first_utc >= ?")
            params.append(self.since)
        if self.until:
            conds.append(f"{alias}.first_utc < ?")
            params.append(self.until)
        return " AND ".join(conds), params


def runs(store, flt):
    """The runs the filter selects, oldest first, each with its row count, status counts and tags."""
    cond, params = flt.where()
    fields = ", ".join(f"runs.{q(c)}" for c in RUN_FIELDS if c in store.columns("runs"))
    out = store.query(
        f"SELECT {fields}, (SELECT COUNT(*) FROM rows r WHERE r.run_id = runs.run_id) AS rows_stored, "
        f"(SELECT COUNT(*) FROM rows r WHERE r.run_id = runs.run_id AND r.status = 'ok') AS ok_rows "
        f"FROM runs WHERE {cond} ORDER BY runs.first_utc, runs.run_id", params)
    tags = {}
    for t in store.query("SELECT run_id, key, value FROM run_tags ORDER BY run_id, key"):
        tags.setdefault(t["run_id"], {})[t["key"]] = t["value"]
    for r in out:
        r["tags"] = tags.get(r["run_id"], {})
    return out


def case_results(store, flt, experiment=None, case_like=None, pass_name="total"):
    """Summary rows of the selected runs (ok or not) matching a case filter: experiment and a case-key
    pattern (SQL LIKE, % wildcards), with their run's order fields."""
    cond, params = flt.where()
    extra, more = [], []
    if experiment:
        extra.append("r.experiment = ?")
        more.append(experiment)
    if case_like:
        extra.append("r.case_key LIKE ?")
        more.append(case_like)
    if pass_name:
        extra.append("r.pass = ?")
        more.append(pass_name)
    where = " AND ".join([cond] + extra)
    return store.query(
        "SELECT r.run_id, r.case_key, r.status, r.median_ms, r.mean_ms, r.ci_lo_ms, r.ci_hi_ms, r.mad_ms, r.samples, "
        "runs.first_utc, runs.git_sha, runs.driver, runs.gl_renderer, runs.gpu_driver_version, runs.mesa_version, "
        "runs.hostname, runs.machine_id FROM rows r JOIN runs ON runs.run_id = r.run_id "
        f"WHERE {where} ORDER BY r.case_key, runs.first_utc, r.run_id", params + more)


def samples_of(store, run_id, case_key, pass_name="total"):
    """The --raw samples (cpu_ms) of one case in one run."""
    return [r["cpu_ms"] for r in store.query(
        "SELECT cpu_ms FROM samples WHERE run_id = ? AND case_key = ? ORDER BY rep", (run_id, case_key))
        if r["cpu_ms"] is not None]
