"""Ratios of two variants timed in the same rounds, for the benchmarks that interleave their
variants (bench/run_benchmarks.py, bench/peer_chute.py): on a machine whose speed drifts, the
best-of times of two variants can come from rounds of different speed; the ratio within each
round, and its median over the rounds, is the steadier figure."""
import statistics


def paired_ratios(rounds, name, reference, value=lambda result: result):
    """value(name's result) / value(reference's) in each round that timed both, sorted."""
    return sorted(value(r[name]) / value(r[reference]) for r in rounds
                  if name in r and reference in r)


def median_and_range(ratios, digits=3):
    """'median (min-max)' of sorted ratios."""
    return (f"{statistics.median(ratios):.{digits}f} "
            f"({ratios[0]:.{digits}f}-{ratios[-1]:.{digits}f})")
