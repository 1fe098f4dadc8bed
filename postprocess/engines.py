"""The same scene run in two engines (a sweep point's `engine`: lammps, liggghts; docs/liggghts.md):
per scene, k_n and observable, each engine's mean over its runs (seeds) with its standard error,
and the rule's verdict on their difference.

The rule (fixed before the cross-check's runs, docs/liggghts.md): the engines agree on an
observable at a k_n where |mean_a - mean_b| <= AGREEMENT_SIGMAS * sqrt(se_a^2 + se_b^2), se the
standard error of the mean over the runs (s/sqrt(n), n >= 2 runs in each engine)."""
import math
from dataclasses import dataclass

import numpy as np

# The observables compared (postprocess/quantities.py names them); against the event-driven
# engine, whose collisions are instantaneous (no contact times), the energy and the collision
# rates with disks and with the boundary.
COMPARED = ("E_total", "N_c", "t_c", "mc_c")
HARD_COMPARED = ("E_total", "N_c", "N_w")
HARD = "event_driven"
# Four combined standard errors: with four runs in each engine the errors are themselves
# uncertain (Welch's t with about 6 degrees of freedom, |t| > 4 by chance with 0.7 %), so that
# one of eight comparisons (two k_n, four observables) fails by chance with about 5 %.
AGREEMENT_SIGMAS = 4.0
ENGINE_DEFAULT = "lammps"


@dataclass
class Comparison:
    scene: str
    kn: float
    quantity: str
    means: dict       # engine: mean
    errors: dict      # engine: standard error of the mean
    counts: dict      # engine: runs
    difference: float = math.nan
    allowed: float = math.nan
    verdict: str = "undecided"   # agree, differ, or undecided (fewer than two runs in one)


def mean_and_error(values):
    n = len(values)
    mean = sum(values) / n
    if n < 2:
        return mean, math.nan
    variance = sum((v - mean) ** 2 for v in values) / (n - 1)
    return mean, math.sqrt(variance / n)


def engine_of(run):
    """The engine a run ran in; an event-driven run's with its collision rule (params.txt's
    rule: paper, (a), or soft, (b)), so that the two rules compare as two engines."""
    engine = (run.variables or {}).get("engine", ENGINE_DEFAULT)
    if engine == HARD and getattr(run, "params", None):
        return f"{HARD} ({run.params.get('rule')})"
    return engine


def left_out(runs):
    """{(scene, engine): [(run's point, why it has no averages)]} of the runs compare_engines
    cannot use: said, not dropped silently (a frictional run whose steady parts the selection
    does not keep has none, and its engine's side of a comparison then has fewer runs, or
    none)."""
    out = {}
    for run in runs:
        if not run.observables:
            # a summary that could not be read (another selection's) has no variables either
            engine = engine_of(run) if run.variables is not None else "unknown: not read"
            out.setdefault((run.scene, engine), []).append(
                (getattr(run, "point", None), getattr(run, "reason", None)))
    return out


def compare_engines(runs):
    """The comparisons of every (scene, k_n) that runs of two engines share, for COMPARED."""
    groups = {}
    for run in runs:
        if not run.observables:
            continue
        key = (run.scene, float(run.observables["kn"]))
        groups.setdefault(key, {}).setdefault(engine_of(run), []).append(run)
    comparisons = []
    for (scene, kn), by_engine in sorted(groups.items()):
        if len(by_engine) != 2:
            continue
        hard = any(engine.startswith(HARD) for engine in by_engine)
        for quantity in HARD_COMPARED if hard else COMPARED:
            stats = {engine: mean_and_error([r.observables[quantity] for r in group])
                     for engine, group in sorted(by_engine.items())}
            comparison = Comparison(scene, kn, quantity,
                                    {e: m for e, (m, _) in stats.items()},
                                    {e: s for e, (_, s) in stats.items()},
                                    {e: len(g) for e, g in by_engine.items()})
            (a, (mean_a, se_a)), (b, (mean_b, se_b)) = stats.items()
            comparison.difference = mean_a - mean_b
            if all(n >= 2 for n in comparison.counts.values()):
                comparison.allowed = AGREEMENT_SIGMAS * math.hypot(se_a, se_b)
                comparison.verdict = ("agree" if abs(comparison.difference) <= comparison.allowed
                                      else "differ")
            comparisons.append(comparison)
    return comparisons


# The profiles' rule (docs/hard_spheres.md): a profile agrees where at most this share of its
# compared bins differ and no PAIR_DIFFERING neighbours do; it differs where more than
# PROFILE_DIFFER_SHARE do or RUN_DIFFERING neighbours do.
PROFILE_AGREE_SHARE = 0.05
PROFILE_DIFFER_SHARE = 0.10
PAIR_DIFFERING = 2
RUN_DIFFERING = 3


@dataclass
class ProfileComparison:
    compared: int            # bins with disks on both sides
    differing: int           # of them, bins whose means differ by more than AGREEMENT_SIGMAS
    longest_run: int         # the most neighbouring differing bins
    largest: float           # the largest |difference| / combined error over the compared bins
    verdict: str


def longest_run(flags):
    best = run = 0
    for flag in flags:
        run = run + 1 if flag else 0
        best = max(best, run)
    return best


def compare_profiles(a, b, occupied_a, occupied_b):
    """The rule's verdict on one profile of two engines. a, b: per-run values, arrays of shape
    (runs, bins); occupied_a, occupied_b: per bin, whether that side's mean density is above 0.
    A bin is compared where both sides have disks, two runs or more and a combined error above 0."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    if len(a) < 2 or len(b) < 2:
        return ProfileComparison(0, 0, 0, math.nan, "undecided")
    combined = np.hypot(a.std(axis=0, ddof=1) / math.sqrt(len(a)),
                        b.std(axis=0, ddof=1) / math.sqrt(len(b)))
    compared = np.asarray(occupied_a) & np.asarray(occupied_b) & (combined > 0)
    z = np.zeros(a.shape[1])
    z[compared] = np.abs(a.mean(axis=0) - b.mean(axis=0))[compared] / combined[compared]
    differing = z > AGREEMENT_SIGMAS
    n, bad, run = int(compared.sum()), int(differing.sum()), longest_run(differing)
    if n == 0:
        return ProfileComparison(0, 0, 0, math.nan, "undecided")
    if bad > PROFILE_DIFFER_SHARE * n or run >= RUN_DIFFERING:
        verdict = "differ"
    elif bad <= PROFILE_AGREE_SHARE * n and run < PAIR_DIFFERING:
        verdict = "agree"
    else:
        verdict = "undecided"
    return ProfileComparison(n, bad, run, float(z[compared].max()), verdict)
