"""The hard-sphere-limit decision rules of docs/hard_sphere_limit.md: does a multiple-contact
time tend to a finite value or vanish as k_n grows? From per-run values (one seed at one k_n),
never from numbers combined elsewhere, so that the bootstrap can resample the runs.

Rule 1 (fixed before the first stiff series) says "finite" only for a decay onto a floor; rule 2
(fixed before the confirmatory series) keeps its branches and also says "finite" for a series
that does not fall (a non-inferiority test on the log-log slope)."""
from dataclasses import dataclass, field
from math import comb

import numpy as np


MIN_RUNS = 3               # selected runs a k_n needs to enter the fits
MIN_RUNS_IN_LEVEL = 2      # ... within one energy level
MIN_KN_IN_LEVEL = 4        # k_n a level needs for the rule to be applied within it
MIN_KN, MIN_DECADES = 5, 2.0   # a series the rule is applied to at all
AIC_MARGIN = 4.0           # dAIC = AIC_P - AIC_F the floor must win by
POWER_SIGMAS = 3.0         # the pure power law's decay must be this many errors from zero
FLOOR_FRACTION = 0.5       # "vanishing": the floor's upper bound below this x m(k_max)
BOOTSTRAP = 2000
# Rule 2's further branch: "finite" where the quantity is shown not to fall by more than
# NO_FALL_FRACTION over the series' k_n range, i.e. where the one-sided NO_FALL_CONFIDENCE upper
# bound of its log-log decay exponent b (m ~ k_n^-b) is below ln(1/(1 - NO_FALL_FRACTION)) /
# ln(k_max/k_min). The bound is the larger of the bootstrap's percentile and the weighted fit's
# b + z sigma_b (sigma_b inflated by sqrt(chi2/dof) where the fit is poor), so that neither few
# runs (a narrow bootstrap) nor a bimodal scatter (a poor normal approximation) can make it
# too easy.
RULES = (1, 2)
RULE = RULES[-1]           # the rule applied unless one is named
NO_FALL_FRACTION = 0.25
NO_FALL_CONFIDENCE = 0.95
NO_FALL_Z = 1.6449         # the standard normal's 95th percentile
EXPONENTS = np.geomspace(0.01, 3.0, 600)   # the decay exponents b the fits scan


@dataclass
class Series:
    """Per k_n: the span-weighted mean over the selected runs and its standard error."""
    kn: np.ndarray
    value: np.ndarray
    error: np.ndarray
    runs: np.ndarray


def per_kn(runs, quantity, min_runs=MIN_RUNS):
    """Series of one quantity from runs (dicts with kn, span and the quantity); k_n with fewer
    than min_runs runs are left out and returned as the second value."""
    groups = {}
    for r in runs:
        groups.setdefault(float(r["kn"]), []).append(r)
    kn, value, error, count, lacking = [], [], [], [], []
    for k in sorted(groups):
        members = groups[k]
        if len(members) < min_runs:
            lacking.append((k, len(members)))
            continue
        mean, sem = weighted_mean([m[quantity] for m in members], [m["span"] for m in members])
        kn.append(k)
        value.append(mean)
        error.append(sem)
        count.append(len(members))
    series = Series(*(np.array(a, dtype=float) for a in (kn, value, error, count)))
    return pooled(series), lacking


def pooled(series):
    """The errors from one relative seed-to-seed scatter pooled over the k_n: the scatter
    comes from the flow's energy levels, alike at every k_n, and an error estimated from a
    handful of runs is itself uncertain by ~30 %, which would give some k_n weights that are
    too large and the floor fit spurious wins. A k_n whose mean is 0 has no relative scatter:
    it is left out of the pool and keeps its own error (0 where its runs all measure 0)."""
    zero = series.value == 0
    if zero.all():
        return series
    relative = series.error[~zero] * np.sqrt(series.runs[~zero]) / np.abs(series.value[~zero])
    scatter = np.sqrt(np.mean(relative ** 2))
    return Series(series.kn, series.value,
                  np.where(zero, series.error,
                           np.abs(series.value) * scatter / np.sqrt(series.runs)), series.runs)


def weighted_mean(values, weights):
    """The span-weighted mean and its standard error from the spread across runs (the same
    estimate as study.combine_seeds)."""
    values, w = np.asarray(values, dtype=float), np.asarray(weights, dtype=float)
    w = w / w.sum()
    mean = float(w @ values)
    n = len(values)
    return mean, float(np.sqrt(n / (n - 1) * np.sum(w ** 2 * (values - mean) ** 2)))


def running_exponents(series):
    """[(kn_low, kn_high, s, error)] between neighbouring k_n: s = dln m / dln k_n (nan where a
    value is not positive)."""
    out = []
    for i in range(len(series.kn) - 1):
        m0, m1 = series.value[i], series.value[i + 1]
        span = np.log(series.kn[i + 1] / series.kn[i])
        if m0 > 0 and m1 > 0:
            s = np.log(m1 / m0) / span
            err = np.hypot(series.error[i] / m0, series.error[i + 1] / m1) / span
        else:
            s = err = np.nan
        out.append((series.kn[i], series.kn[i + 1], s, err))
    return out


def _sums(kn, value, weight, exponents):
    """Weighted sums for the linear parts of the fits, one row per exponent b."""
    x = (kn[None, :] / kn[0]) ** -exponents[:, None]    # k_n scaled: A stays of order m
    w = weight[None, :]
    return x, {"S": w.sum(axis=1), "Sx": (w * x).sum(axis=1), "Sxx": (w * x * x).sum(axis=1),
               "Sy": (w * value).sum(axis=1), "Sxy": (w * x * value).sum(axis=1)}


def _chi2(value, weight, x, c, a):
    return (weight[None, :] * (value[None, :] - c[:, None] - a[:, None] * x) ** 2).sum(axis=1)


def profile_power(kn, value, error, exponents=EXPONENTS):
    """chi^2 of the pure power law m = A k^-b minimised over A, for each b."""
    weight = 1.0 / error ** 2
    x, s = _sums(kn, value, weight, exponents)
    a = s["Sxy"] / s["Sxx"]
    return _chi2(value, weight, x, np.zeros_like(a), a), a


def profile_floor(kn, value, error, exponents=EXPONENTS):
    """chi^2 of m = c + A k^-b with c >= 0, minimised over (c, A), for each b; and c, A."""
    weight = 1.0 / error ** 2
    x, s = _sums(kn, value, weight, exponents)
    det = s["S"] * s["Sxx"] - s["Sx"] ** 2
    with np.errstate(divide="ignore", invalid="ignore"):
        c = (s["Sxx"] * s["Sy"] - s["Sx"] * s["Sxy"]) / det
        a = (s["S"] * s["Sxy"] - s["Sx"] * s["Sy"]) / det
    bound = ~(c > 0)    # the constraint c >= 0 is active (or the system is degenerate)
    c = np.where(bound, 0.0, c)
    a = np.where(bound, s["Sxy"] / s["Sxx"], a)
    return _chi2(value, weight, x, c, a), c, a


@dataclass
class Fits:
    b_power: float          # the pure power law's decay exponent (m ~ k_n^-b)
    b_power_error: float    # from the chi^2 profile (delta chi^2 = 1)
    power_amplitude: float  # A of the pure power law, at k_n scaled by the softest k_n
    chi2_power: float
    floor: float            # c of the floor fit
    floor_amplitude: float  # its A, likewise
    b_floor: float
    chi2_floor: float
    d_aic: float            # AIC_P - AIC_F


def fit_both(series):
    """The two fits of the rule (step 2) on a Series."""
    kn, value, error = series.kn, series.value, series.error
    chi2_p, a_p = profile_power(kn, value, error)
    best = int(np.argmin(chi2_p))
    inside = chi2_p <= chi2_p[best] + 1.0
    if inside[0] or inside[-1]:    # the interval reaches the scanned range's edge
        b_err = np.inf
    elif inside.sum() >= 5:
        b_err = 0.5 * (EXPONENTS[inside].max() - EXPONENTS[inside].min())
    else:    # narrower than the scan's steps: the parabola through the three nearest
        b3, c3 = EXPONENTS[best - 1:best + 2], chi2_p[best - 1:best + 2]
        curvature = np.polyfit(b3, c3, 2)[0]
        b_err = 1.0 / np.sqrt(curvature) if curvature > 0 else np.inf
    chi2_f, c, a_f = profile_floor(kn, value, error)
    best_f = int(np.argmin(chi2_f))
    return Fits(float(EXPONENTS[best]), float(b_err), float(a_p[best]), float(chi2_p[best]),
                float(c[best_f]), float(a_f[best_f]), float(EXPONENTS[best_f]),
                float(chi2_f[best_f]), float(chi2_p[best] - chi2_f[best_f] - 2.0))


def log_slope(series):
    """The decay exponent b of m ~ k_n^-b by weighted least squares of ln m on ln k_n (errors
    sigma/m), and its error, inflated by sqrt(chi2/dof) where the fit is worse than its errors
    say; (nan, nan) unless every value is positive and there are three k_n."""
    if len(series.kn) < 3 or not np.all(series.value > 0) or not np.all(series.error > 0):
        return np.nan, np.nan
    x, y = np.log(series.kn), np.log(series.value)
    w = (series.value / series.error) ** 2
    xm = (w @ x) / w.sum()
    sxx = w @ (x - xm) ** 2
    slope = (w @ ((x - xm) * y)) / sxx
    residual = y - (w @ y) / w.sum() - slope * (x - xm)
    chi2_per_dof = (w @ residual ** 2) / (len(x) - 2)
    return float(-slope), float(np.sqrt(max(1.0, chi2_per_dof) / sxx))


def bootstrap(runs, quantity, kn, samples=BOOTSTRAP, seed=0):
    """Over resamples of the runs within each k_n (the per-k_n means and the pooled errors
    recomputed each time): the floor c of the fit F, and the log-log decay exponent b."""
    rng = np.random.default_rng(seed)
    groups = [[r for r in runs if float(r["kn"]) == k] for k in kn]
    values = [np.array([r[quantity] for r in g], dtype=float) for g in groups]
    spans = [np.array([r["span"] for r in g], dtype=float) for g in groups]
    counts = np.array([len(v) for v in values], dtype=float)
    floors, slopes = np.empty(samples), np.empty(samples)
    for b in range(samples):
        means, errors = np.empty(len(kn)), np.empty(len(kn))
        for i, (v, s) in enumerate(zip(values, spans)):
            pick = rng.integers(0, len(v), len(v))
            means[i], errors[i] = weighted_mean(v[pick], s[pick])
        resampled = pooled(Series(np.asarray(kn), means, errors, counts))
        if not np.all(resampled.error > 0):    # every resample of every k_n alike
            floors[b] = slopes[b] = np.nan
            continue
        chi2_f, c, _ = profile_floor(resampled.kn, resampled.value, resampled.error)
        floors[b] = c[int(np.argmin(chi2_f))]
        slopes[b] = log_slope(resampled)[0]
    return floors, slopes


def no_fall_limit(series):
    """The largest decay exponent that loses at most NO_FALL_FRACTION over the series' k_n."""
    return float(np.log(1.0 / (1.0 - NO_FALL_FRACTION)) / np.log(series.kn[-1] / series.kn[0]))


@dataclass
class Decision:
    quantity: str
    verdict: str                 # finite, vanishing, undecided, or 'not applied: why'
    series: Series = None
    running: list = field(default_factory=list)
    fits: Fits = None
    floor_interval: tuple = (np.nan, np.nan)
    lacking: list = field(default_factory=list)
    why: str = ""
    rule: int = RULE
    decay: tuple = (np.nan, np.nan, np.nan)   # rule 2: log-log b, its error, its upper bound
    decay_limit: float = np.nan               # rule 2: the b that loses NO_FALL_FRACTION


def decide(runs, quantity, min_runs=MIN_RUNS, min_kn=MIN_KN, samples=BOOTSTRAP, rule=RULE):
    """Steps 1-3 of rule 1 or rule 2 on one quantity over runs (dicts with kn, span,
    quantity)."""
    if rule not in RULES:
        raise ValueError(f"the limit rule is 1 or 2, not {rule}")
    series, lacking = per_kn(runs, quantity, min_runs)
    if len(series.kn) < min_kn or (len(series.kn) and
                                   np.log10(series.kn[-1] / series.kn[0]) < MIN_DECADES):
        span = np.log10(series.kn[-1] / series.kn[0]) if len(series.kn) else 0.0
        return Decision(quantity, f"not applied: needs {min_kn} k_n with >= {min_runs} runs "
                                  f"over >= {MIN_DECADES:g} decades, has {len(series.kn)} over "
                                  f"{span:.2g}", series, lacking=lacking, rule=rule)
    if not np.all(series.error > 0):
        exact = "; ".join(f"at k_n = {k:g} its {n:g} runs all measure {v:.4g}" for k, v, e, n
                          in zip(series.kn, series.value, series.error, series.runs)
                          if not e > 0)
        return Decision(quantity, f"not applied: {exact} exactly (no error to weigh it by)",
                        series, lacking=lacking, rule=rule)
    fits = fit_both(series)
    floors, slopes = bootstrap(runs, quantity, series.kn, samples)
    low, high = np.nanpercentile(floors, [2.5, 97.5])
    stiffest = series.value[-1]
    floor_finite = fits.d_aic >= AIC_MARGIN and low > 0
    vanishing = (fits.d_aic < AIC_MARGIN and fits.b_power > POWER_SIGMAS * fits.b_power_error
                 and high < FLOOR_FRACTION * stiffest)
    decay, decay_limit, no_fall = (np.nan, np.nan, np.nan), np.nan, False
    if rule == 2:
        b, b_err = log_slope(series)
        if np.isfinite(b) and np.isfinite(slopes).any():
            upper = max(float(np.nanpercentile(slopes, 100 * NO_FALL_CONFIDENCE)),
                        b + NO_FALL_Z * b_err)
            decay, decay_limit = (b, b_err, upper), no_fall_limit(series)
            no_fall = upper < decay_limit
    lost = (f"at most {1 - (series.kn[-1] / series.kn[0]) ** -decay[2]:.0%} lost over the "
            f"range: m ~ k_n^-{decay[0]:.3g} +- {decay[1]:.2g}, its one-sided "
            f"{NO_FALL_CONFIDENCE:.0%} bound {decay[2]:.3g} < {decay_limit:.3g}" if no_fall else "")
    if no_fall and vanishing:    # a decay too slow to matter yet significant: say neither
        verdict = "undecided"
        why = (f"it falls (m ~ k_n^-{fits.b_power:.3g} +- {fits.b_power_error:.2g}, any floor "
               f"below {high:.3g}) but by less than the resolution ({lost})")
    elif floor_finite:
        verdict = "finite"
        why = (f"the floor improves the fit (dAIC {fits.d_aic:.1f} >= {AIC_MARGIN:g}) and its "
               f"95 % interval [{low:.3g}, {high:.3g}] excludes zero")
    elif no_fall:
        verdict = "finite"
        why = f"it does not fall: {lost}"
    elif vanishing:
        verdict = "vanishing"
        why = (f"no floor is needed (dAIC {fits.d_aic:.1f} < {AIC_MARGIN:g}), m ~ k_n^-"
               f"{fits.b_power:.3g} +- {fits.b_power_error:.2g}, and any floor is below "
               f"{high:.3g} < {FLOOR_FRACTION:g} x {stiffest:.3g} (the stiffest value)")
    else:
        verdict = "undecided"
        # (no finite error: the chi^2 profile's delta chi^2 = 1 interval is not closed within
        # the exponents scanned, fit_both)
        b_error = (f"+- {fits.b_power_error:.2g}" if np.isfinite(fits.b_power_error) else
                   f"(no error: its delta chi2 = 1 interval is open within the scanned "
                   f"b >= {EXPONENTS[0]:g})")
        why = (f"dAIC {fits.d_aic:.1f}, floor interval [{low:.3g}, {high:.3g}], power "
               f"exponent {fits.b_power:.3g} {b_error}, stiffest value "
               f"{stiffest:.3g}" + (f", log-log decay exponent's upper bound {decay[2]:.3g} "
                                    f">= {decay_limit:.3g} (loses more than "
                                    f"{NO_FALL_FRACTION:.0%})" if rule == 2 and
                                    np.isfinite(decay[2]) else "")
               + ": neither branch's conditions all hold")
    return Decision(quantity, verdict, series, running_exponents(series), fits, (low, high),
                    lacking, why, rule, decay, decay_limit)


def level_of(energy, levels):
    """The name of the level (levels: {name: (low, high)}) an energy is in, or None."""
    for name, (low, high) in levels.items():
        if low <= energy < high:
            return name
    return None


def decide_within_levels(runs, quantity, levels, samples=BOOTSTRAP, rule=RULE):
    """Step 4: {level: Decision} for the runs of each energy level (levels: {name: (low,
    high)}, the scene's limit_levels; by their mean E_total)."""
    out = {}
    for name in levels:
        members = [r for r in runs if level_of(r["E_total"], levels) == name]
        out[name] = decide(members, quantity, MIN_RUNS_IN_LEVEL, MIN_KN_IN_LEVEL, samples, rule)
    return out


@dataclass
class Beside:
    """One quantity of a series against its counterpart in another sweep, by the rule's per-k_n
    values and pooled errors (per_kn): at each k_n both have (kn, here, its error, its runs,
    there, its error, its runs, z = (here - there) / the combined error, here / there - 1), and
    the pure power law's decay exponents' difference here - there with its error (nan where
    either series has no fit)."""
    quantity: str
    shared: list
    exponent_difference: tuple = (np.nan, np.nan)


def beside(here, there):
    """Two Decisions on one quantity set side by side (here: this sweep's, there: the other's)."""
    shared = []
    for k, v, e, n in zip(here.series.kn, here.series.value, here.series.error,
                          here.series.runs):
        match = np.flatnonzero(np.isclose(there.series.kn, k, rtol=1e-9, atol=0.0))
        if not len(match):
            continue
        i = match[0]
        w, f, m = there.series.value[i], there.series.error[i], there.series.runs[i]
        combined = np.hypot(e, f)
        shared.append((float(k), float(v), float(e), int(n), float(w), float(f), int(m),
                       float((v - w) / combined) if combined > 0 else np.nan,
                       float(v / w - 1.0) if w else np.nan))
    difference = (np.nan, np.nan)
    if here.fits and there.fits:
        difference = (here.fits.b_power - there.fits.b_power,
                      float(np.hypot(here.fits.b_power_error, there.fits.b_power_error)))
    return Beside(here.quantity, shared, difference)


# ---- runaway events of the literal law (docs/hard_sphere_limit.md)

RUNAWAY_FACTOR = 3.0   # E over windows of 1 above this many times the run's median ...
RUNAWAY_ENERGY = 2.0   # ... and above this (per disk: the steady levels reach ~1.6): an event
SETTLED = 30.0         # the first collapse is over by then


def runaway_events(t, energy, factor=RUNAWAY_FACTOR, settled=SETTLED):
    """Start times of the stretches where E(t), averaged over windows of one time unit, exceeds
    `factor` times its median after `settled` and RUNAWAY_ENERGY: a flowing pile's E wanders
    between its levels (0.4-1.6) by less than that; a runaway throws it up by 4-40
    (docs/hard_sphere_limit.md); a pile that stopped has no median to compare with."""
    t, energy = np.asarray(t, dtype=float), np.asarray(energy, dtype=float)
    late = t >= settled
    if late.sum() < 2:
        return []
    edges = np.arange(np.floor(t[late][0]), t[late][-1] + 1.0)
    which = np.digitize(t[late], edges)
    means = np.array([energy[late][which == k].mean() for k in np.unique(which)])
    starts = edges[np.unique(which) - 1]
    above = (means > factor * np.median(means)) & (means > RUNAWAY_ENERGY)
    rising = above & ~np.concatenate([[False], above[:-1]])
    return [float(s) for s in starts[rising]]


def fisher_exact(hits_a, runs_a, hits_b, runs_b):
    """Fisher's exact test of two series' counts of runs with an event (hits_a of runs_a, hits_b
    of runs_b), the margins fixed: were the events as likely in both, the hits would fall on the
    two sides as a hypergeometric draw. Returns (one-sided p, two-sided p): the probability of
    a split at least as uneven in the direction seen, and of a split as likely as the one seen
    or less, either way."""
    hits, total = hits_a + hits_b, runs_a + runs_b
    probability = {k: comb(runs_a, k) * comb(runs_b, hits - k) / comb(total, hits)
                   for k in range(max(0, hits - runs_b), min(hits, runs_a) + 1)}
    seen = probability[hits_a]
    expected = hits * runs_a / total
    one_sided = sum(p for k, p in probability.items()
                    if (k >= hits_a if hits_a >= expected else k <= hits_a))
    # as likely or less: with a relative margin for the rounding of equal probabilities
    two_sided = sum(p for p in probability.values() if p <= seen * (1 + 1e-9))
    return min(one_sided, 1.0), min(two_sided, 1.0)
