"""The statistics the comparisons share: medians' distribution-free intervals, how many round pairs an
interval needs, the median absolute deviation, a bootstrap interval of a ratio of medians."""
import math

from oitbench import results as oitres


def binomial_half_cdf(n, j):
    return sum(math.comb(n, i) for i in range(j + 1)) / 2.0 ** n


def median_interval(values, confidence):
    """The order statistics x(k), x(n+1-k) around the median at `confidence` (as micro/core/sampling.cpp);
    None below the count that allows it."""
    v = sorted(values)
    n = len(v)
    tail = (1 - confidence) / 2
    k = 0
    while k + 1 <= (n + 1) // 2 and binomial_half_cdf(n, k) <= tail:
        k += 1
    if k < 1:
        return None
    return v[k - 1], v[n - k]


def pairs_needed(cases):
    """The fewest round pairs that give an interval at 1 - 0.05 / cases (6 for one case, 7 for two, ...)."""
    n = 1
    while median_interval(list(range(n)), 1 - 0.05 / max(1, cases)) is None:
        n += 1
    return n


def mad(values):
    if not values:
        return 0.0
    m = oitres.median(values)
    return oitres.median([abs(x - m) for x in values])


def bootstrap_ratio_ci(a, b, iterations, rng):
    """Percentile 95% interval of median(b*) / median(a*) over resamples of both sets."""
    ratios = []
    for _ in range(iterations):
        ma = oitres.median(rng.choices(a, k=len(a)))
        mb = oitres.median(rng.choices(b, k=len(b)))
        if ma > 0:
            ratios.append(mb / ma)
    ratios.sort()
    if not ratios:
        return float("nan"), float("nan")
    lo = ratios[int(0.025 * (len(ratios) - 1))]
    hi = ratios[int(math.ceil(0.975 * (len(ratios) - 1)))]
    return lo, hi
