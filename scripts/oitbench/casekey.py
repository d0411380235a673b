"""Which case a row is: the one case key the scripts join, group and describe rows by.

A key is the row's identity columns (experiment, variant, pass, width, height: the schema's `case` columns
that say what ran, not how often) followed by one entry per parameter. Which parameters, and whether the
schema's applies_where scoping is honoured, is the caller's choice:

- key(row, params): the values of `params` (an experiment's parameter columns), a parameter the schema
  scopes away from this row's case left empty, so schema 1 files (which filled every parameter) join
  later ones (compare.py, report.py --compare);
- key(row, params, with_pass=False, scoped=False): one case's rows, every pass together (the report's
  run facts);
- named_key(row, skip): the parameters the row itself names (its `parameters` column), as "name=value",
  less `skip` (ab.py: the parameters that A and B set differently);
- named_key(row, params=..., pairs=True): (name, value) pairs of the parameters the row uses (a summary
  row's identity among the --raw rows).
"""
from oitbench import results as oitres

# experiment, variant, pass, width, height: the schema's case columns less the repetition counts and the
# list of parameters.
IDENTITY = [c for c in oitres.BASE_COLUMNS
            if c in {col["name"] for col in oitres.SCHEMA["summary_columns"] if col.get("group") == "case"}
            and c not in ("reps", "warmup", "parameters")]
PASS = IDENTITY.index("pass")


def identity(row, with_pass=True):
    """The identity part of a key; experiment and pass must be there, the others may be empty."""
    return tuple(row[c] if c in ("experiment", "pass") else row.get(c, "") for c in IDENTITY
                 if with_pass or c != "pass")


def key(row, params, with_pass=True, scoped=True):
    values = tuple(row.get(p, "") if not scoped or oitres.applies(p, row) else "" for p in params)
    return identity(row, with_pass) + values


def used_params(row, params=()):
    """The parameters a summary row's case uses: its `parameters` column, or (older files without one) the
    ones among `params` that the row fills."""
    names = [p for p in (row.get("parameters") or "").split(";") if p]
    return names or [p for p in params if row.get(p, "") != ""]


def named_key(row, skip=(), params=(), pairs=False):
    names = [p for p in used_params(row, params) if p not in skip]
    values = tuple((p, row.get(p, "")) if pairs else f"{p}={row.get(p, '')}" for p in names)
    return identity(row) + values
