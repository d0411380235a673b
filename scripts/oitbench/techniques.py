"""The oit experiment's techniques, read from scripts/techniques.json (the binary's export of its technique
table, `oitbench list --techniques --json`; tests/scripts/test_technique_table.py checks the two agree).
Scripts ask here for names and families instead of typing technique names."""
import os

from oitbench.results import ResultsError, read_json

TECHNIQUES_PATH = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "techniques.json")
# Knowles 2014's tables list the exact techniques scheme by scheme in this order (its CUDA-* are our CS-*;
# CPU-NATIVE is ours, last); within a scheme the technique table's order (IS, IMS, RBS-L, AUTO) is kept.
PAPER_SCHEME_ORDER = ("BASE", "G", "CS", "BMA", "CPU")


def load(path=TECHNIQUES_PATH):
    """The technique table: a list of {name, family, scheme, sort, captures, params, ...}. ResultsError
    names the file for one that is not the export."""
    table = read_json(path, "the technique table")
    if not isinstance(table, dict) or not isinstance(table.get("techniques"), list):
        raise ResultsError(f"{path}: not oitbench's technique table (`oitbench list --techniques --json`)")
    return table["techniques"]


TABLE = load()


def _by(**props):
    """The table's techniques whose fields equal `props` (family=, scheme=, sort=, reference=, ...)."""
    return [t for t in TABLE if all(t.get(k) == v for k, v in props.items())]


def find(**props):
    """The name of the one technique with these fields (e.g. scheme="BMA", sort="RBS-L"); ResultsError where
    the table has none or several, so a script that asks for a role the table lost fails with its reason."""
    found = _by(**props)
    if len(found) != 1:
        what = ", ".join(f"{k}={v}" for k, v in props.items())
        raise ResultsError(f"{TECHNIQUES_PATH}: {len(found)} techniques with {what}, expected one")
    return found[0]["name"]


# The roles scripts need, found by property. BASELINE: the table's first technique, the one render/view start
# with (micro/oit/techniques.hpp default_technique()) and the exact baseline the Knowles presets' speedups
# divide by (tests/scripts/test_library.py checks the presets agree). CPU_RESOLVE: the exact technique whose
# resolve runs on the CPU.
BASELINE = TABLE[0]["name"]
CPU_RESOLVE = find(family="exact", scheme="CPU")


def names(*families):
    """The techniques of these families (all when none is given), in the table's order."""
    return [t["name"] for t in TABLE if not families or t["family"] in families]


def scheme(name):
    return next((t["scheme"] for t in TABLE if t["name"] == name), "")


def sort(name):
    return next((t["sort"] for t in TABLE if t["name"] == name), "")


def params(name):
    """The parameters technique `name` reads (the table's params); [] for an unknown name."""
    return next((t["params"] for t in TABLE if t["name"] == name), [])


def primitives(name):
    """What technique `name` draws: "any" scene, or "splats" only (the table's primitives); "" for an unknown name."""
    return next((t.get("primitives", "") for t in TABLE if t["name"] == name), "")


def reads(name, param):
    """Whether technique `name` reads parameter `param` (the table's params); False for an unknown name."""
    return any(param in t["params"] for t in TABLE if t["name"] == name)


def reading(param, *families):
    """The techniques (of these families, all when none is given) that read `param`, in the table's order."""
    return [t["name"] for t in TABLE if param in t["params"] and (not families or t["family"] in families)]


def twin(name, scheme_):
    """The exact technique with `name`'s sort under resolve scheme `scheme_` (BMA-IS for BASE-IS and BMA)."""
    return find(family="exact", scheme=scheme_, sort=sort(name))


def exact_in_paper_order(schemes=PAPER_SCHEME_ORDER):
    """The exact techniques of `schemes`, scheme by scheme as Knowles 2014's tables list them."""
    exact = [t for t in TABLE if t["family"] == "exact" and t["scheme"] in schemes]
    return [t["name"] for t in sorted(exact, key=lambda t: (schemes.index(t["scheme"]), TABLE.index(t)))]
