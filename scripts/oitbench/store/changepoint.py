"""Change points in a case's history, detected against the runs' own noise.

A step is reported only where the statistics resolve it, against the noise the runs themselves show
between each other (no fixed band): binary segmentation over the runs' medians (log scale); a split is
kept when a permutation test of the largest Mann-Whitney statistic over every split point rejects
exchangeable runs (p < alpha; the maximum over the splits is what is permuted, so trying every split is
paid for; ranks, so one stalled run does not make a step). Each segment is then tested again, down to
`min_size` runs a side. `min_step` (a ratio, default 1: none) drops resolved steps too small to matter.

How well: 20 runs, runs 11-20 with 9.4% more work, per-run noise of the median ~2.4% (a between-run factor
of 1.5% and 6% per sample over 15 samples; the A/B pairs of identical code in results/ab-llvmpipe/identical
vary 3.3-3.8% per pair ratio, ~2.5% per run): found 100 of 100, exactly at run 11 in 95, within one run in
100; identical runs: a step in 1 of 100 (alpha 0.01). At ~4% per run (3% between runs, 8% per sample):
found 89 of 100, exactly at run 11 in 67 (the step is then 2.3 sigma of one run)."""
import math
import random



def _rank(values):
    order = sorted(range(len(values)), key=lambda i: values[i])
    ranks = [0.0] * len(values)
    i = 0
    while i < len(order):
        j = i
        while j + 1 < len(order) and values[order[j + 1]] == values[order[i]]:
            j += 1
        for k in range(i, j + 1):
            ranks[order[k]] = (i + j) / 2 + 1
        i = j + 1
    return ranks


def _max_z(ranks, min_size):
    """The largest |z| of the Mann-Whitney U over every split [0,k) | [k,n), and its k."""
    n = len(ranks)
    best, best_k = 0.0, None
    prefix = 0.0
    for k in range(1, n - min_size + 1):
        prefix += ranks[k - 1]
        if k < min_size:
            continue
        m = n - k
        u = prefix - k * (k + 1) / 2
        sd = math.sqrt(k * m * (n + 1) / 12)
        z = abs(u - k * m / 2) / sd if sd else 0.0
        if z > best:
            best, best_k = z, k
    return best, best_k


def split_test(values, min_size=3, permutations=2000, rng=None):
    """(k, p): the most likely split point of `values` and the permutation p-value of its statistic."""
    if len(values) < 2 * min_size:
        return None, 1.0
    rng = rng or random.Random(31)
    ranks = _rank(values)
    observed, k = _max_z(ranks, min_size)
    if k is None:
        return None, 1.0
    shuffled = list(ranks)
    hits = 0
    for _ in range(permutations):
        rng.shuffle(shuffled)
        if _max_z(shuffled, min_size)[0] >= observed - 1e-12:
            hits += 1
    return k, (hits + 1) / (permutations + 1)


def change_points(medians, alpha=0.01, min_size=3, permutations=2000, min_step=1.0, seed=31):
    """Indices i where a step starts (run i differs from the runs before it in its segment), with each
    step's ratio (the later segment's median over the earlier's) and p-value: [(i, ratio, p)]."""
    logs = [math.log(m) for m in medians]
    rng = random.Random(seed)
    found = []

    def segment(a, b):
        k, p = split_test(logs[a:b], min_size, permutations, rng)
        if k is None or p >= alpha:
            return
        left, right = sorted(logs[a:a + k]), sorted(logs[a + k:b])
        step = _median(right) - _median(left)
        if abs(step) >= math.log(min_step):
            found.append((a + k, math.exp(step), p))
        segment(a, a + k)
        segment(a + k, b)

    segment(0, len(logs))
    return sorted(found)


def _median(s):
    n = len(s)
    return s[n // 2] if n % 2 else (s[n // 2 - 1] + s[n // 2]) / 2
