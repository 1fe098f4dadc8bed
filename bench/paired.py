"""Ratios of two variants timed in the same rounds, for the benchmarks that interleave their
variants (bench/run_benchmarks.py, bench/peer_chute.py): on a machine whose speed drifts, the
best-of times of two variants can come from rounds of different speed; the ratio within each
round, and its median over the rounds, is the steadier figure. A goal ("at most G times the
other") is judged on those ratios by a rule fixed before any of them was measured (against_goal)."""
import math
import statistics

ALPHA = 0.05    # the one-sided sign test's level


def paired_ratios(rounds, name, reference, value=lambda result: result):
    """value(name's result) / value(reference's) in each round that timed both, sorted."""
    return sorted(value(r[name]) / value(r[reference]) for r in rounds
                  if name in r and reference in r)


def median_and_range(ratios, digits=3):
    """'median (min-max)' of sorted ratios."""
    return (f"{statistics.median(ratios):.{digits}f} "
            f"({ratios[0]:.{digits}f}-{ratios[-1]:.{digits}f})")


def binomial_tail(n, k):
    """P(X >= k) for X ~ Binomial(n, 1/2): how often k or more of n fair coins fall one way."""
    return sum(math.comb(n, m) for m in range(max(k, 0), n + 1)) / 2 ** n


def against_goal(ratios, goal, alpha=ALPHA):
    """The verdict on the goal 'ratio at most goal' from paired ratios, by a one-sided sign test
    on the rounds: 'met' where so many rounds fall below the goal that a median ratio at or
    above it would give that many with probability below alpha, 'not met' where as many fall
    at or above it, 'undecided' otherwise (too few rounds, or a ratio at the goal within this
    machine's noise). A round at the goal exactly counts against it."""
    n, below = len(ratios), sum(r < goal for r in ratios)
    if n and binomial_tail(n, below) < alpha:
        word, p = "met", binomial_tail(n, below)
    elif n and binomial_tail(n, n - below) < alpha:
        word, p = "not met", binomial_tail(n, n - below)
    else:
        word, p = "undecided", min(binomial_tail(n, below), binomial_tail(n, n - below))
    return f"{word} ({below} of {n} rounds below {goal:g}, sign test p = {p:.3g})"
