"""A run's time account (CSV schema 6): where its cases' wall time went, from the case_wall_s and
phase_*_s columns of their total rows (docs/measurement.md, "Where a run's time goes"). Rows of older
schemas have no account and are left out."""
import os

from oitbench import results as oitres

# The phases, as micro/core/phases.hpp names them.
PHASES = ("scene", "compile", "pool", "warmup", "samples", "readback", "reference", "validate", "other")
# The shares oitbench's closing line on stderr prints, and the phases each one sums.
GROUPS = (("timed samples", ("samples",)), ("compile", ("compile",)), ("warm-up", ("warmup",)),
          ("reference+validation", ("readback", "reference", "validate")), ("scene", ("scene", "pool")),
          ("other", ("other",)))


def column(phase):
    return f"phase_{phase}_s"


class Account:
    """Seconds per group over some cases, and their wall time."""

    def __init__(self):
        self.cases = 0
        self.wall = 0.0
        self.groups = dict.fromkeys((name for name, _ in GROUPS), 0.0)

    def add(self, row):
        """Adds a total row's account; returns False (and adds nothing) for a row without one."""
        if row.get("pass") != "total":
            return False
        wall = oitres.to_float(row.get("case_wall_s"))
        if wall is None:
            return False
        for name, phases in GROUPS:
            self.groups[name] += sum(oitres.to_float(row.get(column(p))) or 0.0 for p in phases)
        self.wall += wall
        self.cases += 1
        return True

    def share(self, name):
        """The group's share of the wall time, in %."""
        return 100.0 * self.groups[name] / self.wall if self.wall > 0 else 0.0


def accounts(rows):
    """{(preset, experiment): Account} over the rows that have an account, in first-seen order."""
    out = {}
    for r in rows:
        key = (r.get("preset", ""), r.get("experiment", ""))
        acc = out.get(key) or Account()
        if acc.add(r):
            out[key] = acc
    return out


def shares_text(acc, wall=None):
    """'timed samples 3.1 s (25%), compile ...' of an Account, in % of `wall` (default: its own)."""
    wall = acc.wall if wall is None else wall
    return ", ".join(f"{name} {acc.groups[name]:.1f} s ({100.0 * acc.groups[name] / wall if wall > 0 else 0:.0f}%)"
                     for name, _ in GROUPS)


def step_lines(paths, script_s=None, prefix="gpu-run.sh: time"):
    """The time account of a run of several steps (scripts/gpu-run.sh: one summary CSV per step): one line
    per step, one for all, and where `script_s` (the script's own wall time) is given, what the steps'
    cases leave of it (each oitbench's start, info, the report). Files without an account are skipped."""
    lines, everything = [], Account()
    for path in paths:
        acc = Account()
        try:
            _, rows = oitres.read_csv(path)
        except oitres.ResultsError as e:
            lines.append(f"{prefix}: {e}")
            continue
        for r in rows:
            if acc.add(r):
                everything.add(r)
        if acc.cases:
            name = os.path.splitext(os.path.basename(path))[0]
            lines.append(f"{prefix}: {name}: {acc.cases} cases, {acc.wall:.1f} s: {shares_text(acc)}")
    if everything.cases:
        lines.append(f"{prefix}: all steps: {everything.cases} cases, {everything.wall:.1f} s: {shares_text(everything)}")
        if script_s:
            rest = script_s - everything.wall
            lines.append(f"{prefix}: the script's {script_s:.0f} s: the cases {everything.wall:.1f} s "
                         f"({100.0 * everything.wall / script_s:.0f}%; timed samples "
                         f"{100.0 * everything.groups['timed samples'] / script_s:.0f}%), the rest {rest:.1f} s "
                         "(each oitbench's start and writing, info, device, the report)")
    return lines


def accounts_of_file(path):
    """The Account of every total row of one summary CSV (None where it cannot be read)."""
    try:
        _, rows = oitres.read_csv(path)
    except oitres.ResultsError:
        return None
    acc = Account()
    for r in rows:
        acc.add(r)
    return acc


def minutes(seconds):
    """'12m05s' of a number of seconds."""
    s = int(round(seconds))
    return f"{s // 60}m{s % 60:02d}s"


def list_lines(runs, prefix="[reference] time"):
    """The time account of scripts/reference_runs.sh: `runs` is [(list, preset, wall_s, csv path)] in the
    order they ran, `list` 'default' or 'opt-in'. One line per preset (its wall time as the script
    measured it, its cases' shares), then per list its total wall time and the shares of its cases' wall
    time (timed samples, compile, warm-up, reference+validation, scene, other), and what the cases leave of
    the presets' wall (each oitbench's start, writing). A CSV without an account (schema < 6) says so."""
    lines = []
    per_list = {}
    for which, preset, wall, path in runs:
        acc = Account()
        try:
            _, rows = oitres.read_csv(path)
        except oitres.ResultsError as e:
            rows = []
            lines.append(f"{prefix}: {preset}: {e}")
        for r in rows:
            acc.add(r)
        total_wall, total_acc, names = per_list.setdefault(which, [0.0, Account(), []])
        per_list[which][0] = total_wall + wall
        names.append(preset)
        for r in rows:
            total_acc.add(r)
        what = f"{acc.cases} cases: {shares_text(acc)}" if acc.cases else "no time account in its rows"
        lines.append(f"{prefix}: {preset} ({which}): {minutes(wall)}; {what}")
    for which in ("default", "opt-in"):
        if which not in per_list:
            continue
        wall, acc, names = per_list[which]
        line = f"{prefix}: the {which} list: {len(names)} preset(s), {minutes(wall)}"
        if acc.cases:
            line += (f"; its {acc.cases} cases {acc.wall:.0f} s: {shares_text(acc)}; the rest of its wall time "
                     f"{max(0.0, wall - acc.wall):.0f} s (each oitbench's start and writing)")
        lines.append(line)
    return lines
