"""Checks a sharded run against the unsharded one. Usage: check_shards.py WHOLE.csv N SHARD.csv...
Every case of WHOLE is in exactly one shard's CSV with the same status, no shard has a case WHOLE lacks, and
the shards' rows say I/N (1 <= I <= N) in their shard column. Exit 0, or 1 printing what differs."""
import csv
import json
import os
import sys
from collections import Counter

SCHEMA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts", "schema.json")


def total_rows(path):
    with open(path, newline="") as f:
        return [r for r in csv.DictReader(f) if r["pass"] == "total"]


def main(argv):
    if len(argv) < 4:
        print(__doc__)
        return 2
    whole_path, n, shard_paths = argv[1], int(argv[2]), argv[3:]
    with open(SCHEMA) as f:
        params = [c["name"] for c in json.load(f)["summary_columns"] if c.get("role") == "parameter"]
    identity = ["experiment", "width", "height"] + params  # what a case ran

    def key(r):
        return tuple(r.get(c, "") for c in identity)
    whole = total_rows(whole_path)
    expected = Counter(key(r) for r in whole)
    status = {key(r): r["status"] for r in whole}
    got, problems, seen = Counter(), [], set()
    for path in shard_paths:
        for r in total_rows(path):
            got[key(r)] += 1
            seen.add(r["shard"])
            if status.get(key(r), r["status"]) != r["status"]:
                problems.append(f"{path}: a case's status is {r['status']}, unsharded {status[key(r)]}")
    if not whole:
        problems.append(f"{whole_path}: no rows")
    if got != expected:
        problems.append(f"the shards' cases differ from the unsharded run's: {sum((expected - got).values())} "
                        f"missing, {sum((got - expected).values())} extra or repeated")
    if not seen <= {f"{i}/{n}" for i in range(1, n + 1)}:
        problems.append(f"shard columns {sorted(seen)}, expected some of 1/{n}..{n}/{n}")
    for p in problems:
        print("check_shards: " + p)
    if not problems:
        print(f"check_shards: {sum(got.values())} case(s) in {len(shard_paths)} shard(s), each once, the statuses "
              f"of the unsharded run ({dict(Counter(status.values()))})")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
