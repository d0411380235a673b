"""Reading one oitbench CSV for the store, carefully: the whole file or nothing. A file that is not an
oitbench summary or --raw file, a row with the wrong number of fields (a damaged or cut-off last row), an
unterminated last line or a schema version this oitbench does not know is refused with FILE:LINE."""
import csv
import hashlib
import io
import json
import math
import re
import uuid

from oitbench import results
from oitbench.store.sqlschema import CSV_SCHEMA, PARAMETERS, RAW_TYPES, SUMMARY_TYPES

_INTEGER = re.compile(r"^[+-]?\d+$")
# Rows of files written before run ids (schema < 5) get one derived from what they have in common.
_LEGACY_NAMESPACE = uuid.UUID("6f1c1f0e-31a5-4c5e-9f31-0b1e0c31a531")


class CsvRefused(Exception):
    """The file cannot be stored; the message names the file (and line)."""


class CsvFile:
    """One CSV: its kind ('summary' or 'raw'), header, rows (dicts of text) with their line numbers, and the
    sha256 of its bytes."""

    def __init__(self, path, kind, header, rows, lines, sha256):
        self.path, self.kind, self.header, self.rows, self.lines, self.sha256 = path, kind, header, rows, lines, sha256

    @property
    def types(self):
        return SUMMARY_TYPES if self.kind == "summary" else RAW_TYPES


def file_kind(header):
    if "experiment" in header and "median_ms" in header:
        return "summary"
    if "experiment" in header and "rep" in header and "cpu_ms" in header:
        return "raw"
    return None


def read(path):
    try:
        with open(path, "rb") as f:
            data = f.read()
    except OSError as e:
        raise CsvRefused(f"{path}: cannot read ({e.strerror})") from e
    try:  # the library's careful reader: not UTF-8, or a NUL byte, with the line of the first bad byte
        text = results.read_text(path)
    except results.ResultsError as e:
        raise CsvRefused(f"{e}; nothing stored from this file") from e
    if not text:
        raise CsvRefused(f"{path}: empty file")
    reader = csv.reader(io.StringIO(text, newline=""))
    try:
        header = next(reader)
        kind = file_kind(header)
        if kind is None:
            raise CsvRefused(f"{path}:1: not an oitbench summary or --raw CSV (no experiment/median_ms or "
                             "rep/cpu_ms columns)")
        if "schema" not in header:
            raise CsvRefused(f"{path}:1: not an oitbench run CSV (no schema column: a derived table?)")
        rows, lines = [], []
        start = reader.line_num + 1
        for fields in reader:
            if len(fields) != len(header):
                raise CsvRefused(f"{path}:{start}: damaged row: {len(fields)} fields where the header has "
                                 f"{len(header)}; nothing stored from this file")
            row = dict(zip(header, fields))
            version = row["schema"]
            if not _INTEGER.match(version) or not 1 <= int(version) <= CSV_SCHEMA:
                raise CsvRefused(f"{path}:{start}: unknown schema version '{version}' (this oitbench reads "
                                 f"1 to {CSV_SCHEMA}); nothing stored from this file")
            rows.append(row)
            lines.append(start)
            start = reader.line_num + 1
    except csv.Error as e:
        raise CsvRefused(f"{path}:{reader.line_num}: not valid CSV ({e}); nothing stored from this file") from e
    if not text.endswith("\n"):
        raise CsvRefused(f"{path}:{lines[-1] if lines else 1}: the last row is cut off (no line end: a run "
                         "interrupted while writing?); nothing stored from this file")
    return CsvFile(path, kind, header, rows, lines, hashlib.sha256(data).hexdigest())


def case_params(row):
    """The parameters of the row's case, NAME -> VALUE: the `parameters` column where the row has it, else
    every filled parameter column."""
    names = row.get("parameters")
    if names:
        keys = [n for n in names.split(";") if n]
    else:
        keys = [n for n in PARAMETERS if row.get(n, "") != ""]
    return {k: row.get(k, "") for k in sorted(keys)}


def case_key(row):
    """A case's identity across runs: experiment, variant, pass, resolution and parameters (never the run's
    columns), e.g. occupancy/unrolled/total/800x600/draws=64;size=32."""
    params = ";".join(f"{k}={v}" for k, v in case_params(row).items())
    return (f"{row.get('experiment', '')}/{row.get('variant', '')}/{row.get('pass', '')}/"
            f"{row.get('width', '')}x{row.get('height', '')}/{params}")


def legacy_run_id(row, folder):
    """A stable id for rows of a file without run_id: its commit, backend, driver, renderer and preset, in
    its folder (a summary and its --raw file beside it get the same)."""
    key = "|".join([folder] + [row.get(c, "") for c in ("git_sha", "backend", "driver", "gl_renderer", "preset")])
    return str(uuid.uuid5(_LEGACY_NAMESPACE, key))


def row_hashes(rows):
    """One content hash per row (independent of column order and of the file's name; a row repeated in a
    file gets its occurrence number), so the same rows stored twice are one."""
    seen = {}
    out = []
    for row in rows:
        content = "\x1f".join(f"{k}={v}" for k, v in sorted(row.items()) if v != "")
        n = seen.get(content, 0)
        seen[content] = n + 1
        out.append(hashlib.sha256(f"{content}\x1e{n}".encode()).hexdigest())
    return out


def typed(value, sql_type):
    """(value for the typed column, or None) and whether it was kept (False: goes to extra as text)."""
    if value == "":
        return None, True
    if sql_type == "text":
        return value, True
    if sql_type in ("integer", "flag"):
        return (int(value), True) if _INTEGER.match(value) else (None, False)
    try:
        x = float(value)
    except ValueError:
        return None, False
    if not math.isfinite(x):
        return None, False
    return x, True


def split_row(row, types):
    """The row's typed values by column (this schema's columns) and its `extra` JSON (the rest, as text)."""
    values, extra = {}, {}
    for name, value in row.items():
        t = types.get(name)
        if t is None:
            if value != "":
                extra[name] = value
            continue
        v, kept = typed(value, t)
        values[name] = v
        if not kept:
            extra[name] = value
    return values, (json.dumps(extra, sort_keys=True) if extra else None)
