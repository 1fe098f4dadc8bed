"""A sweep's points, analysed: per-scene tables of observables, and what was left out."""
import numpy as np

from .durations import pooled
from .observables import RESOLUTIONS
from .quantities import COLUMNS, VARIANTS
from .runs import load_runs
from .scenes import SCENES
from .selection import Selection

def analyse(source, selection=Selection()):
    """A sweep from its raw outputs or its summaries (runs.load_runs): {scene: [observables of
    each usable run, seeds combined, sorted by kn, with its point, variables and outputs (the
    run's io.Point; None from summaries)]}, [(point, reason) left out], {scene:
    [RunRecord of each completed run]} (usable or not: their time series can still be shown),
    and [run records] of the frictional runs (how each ended, what the selection kept:
    frictional_run). `selection`: the frictional steady-part rule (docs/model.md section 5)."""
    scenes, left_out, completed, runs = {}, [], {}, []
    resolutions = sorted(set(RESOLUTIONS) | {selection.resolution})
    for record in load_runs(source, selection):
        left_out += [(copy, f"the same run as {record.point}: counted once")
                     for copy in record.copies]
        if record.reason is not None:
            left_out.append((record.point, record.reason))
        if record.ended in ("flowing", "stopped") and record.energy is not None:
            completed.setdefault(record.scene, []).append(record)
        if record.measured is not None and SCENES[record.scene].selects_steady_parts:
            runs.append(frictional_run(record, selection, resolutions))
        if record.observables is not None:
            o = dict(record.observables, point=record.point, variables=record.variables,
                     outputs=record.outputs, contacts=record.measured.get("contacts"))
            scenes.setdefault(o["scene"], []).append(o)
    scenes = {scene: combine_seeds(rows) for scene, rows in scenes.items()}
    varying = varying_variables([r["variables"] for r in runs])
    for r in runs:
        r["label"] = label(r["variables"], varying)
    return scenes, left_out, completed, runs


def frictional_run(record, selection, resolutions):
    """How one frictional run went: kn, seed, state ('flowing' to the end or 'stopped'), the
    stop time, the steady parts kept at each of `resolutions`, and whether any is kept at the
    analysis resolution."""
    kept = record.kept(selection, resolutions)
    return {"point": record.point, "kn": record.params["kn"], "seed": record.params["seed"],
            "state": record.ended, "stopped_at": record.stopped_at, "kept": kept,
            "selected": kept[selection.resolution] > 0, "variables": record.variables,
            "cpu_seconds": record.cpu_seconds}


def run_summary(runs):
    """Per (kn, other variables than the seed): runs, flowing to the end, stopped, selected,
    the median stop time, the steady parts kept at each resolution, summed over the runs, and
    their CPU time (cpu_seconds: the sum over the runs that recorded one; timed: how many)."""
    table = {}
    for r in runs:
        row = table.setdefault((r["kn"], r["label"]),
                               {"runs": 0, "flowing": 0, "stopped": 0, "selected": 0,
                                "stop_times": [], "kept": {k: 0 for k in r["kept"]},
                                "cpu_seconds": 0.0, "timed": 0})
        if r["stopped_at"] is not None:
            row["stop_times"].append(r["stopped_at"])
        if r.get("cpu_seconds") is not None:
            row["cpu_seconds"] += r["cpu_seconds"]
            row["timed"] += 1
        row["runs"] += 1
        row[r["state"]] += 1
        row["selected"] += r["selected"]
        for k, v in r["kept"].items():
            row["kept"][k] = row["kept"].get(k, 0) + v
    return dict(sorted(table.items()))


def combine_seeds(rows):
    """Points that differ only in seed become one: the mean over seeds weighted by each seed's
    averaged span, with the spread across seeds (the weighted standard error) as the error
    when there are several, else the block error."""
    groups = {}
    for o in rows:
        key = tuple(sorted((k, v) for k, v in o["variables"].items() if k != "seed"))
        groups.setdefault(key, []).append(o)
    combined = []
    varying = varying_variables([o["variables"] for o in rows])
    for members in groups.values():
        o = dict(members[0])
        if len(members) > 1:
            # weighted by span: the time average over all the selected data, as the paper's
            weights = np.array([m["span"] for m in members], dtype=float)
            weights /= weights.sum()
            n = len(members)
            for q in COLUMNS + ("period", "bump_time"):
                if q not in o:
                    continue
                values = np.array([m[q] for m in members])
                o[q] = float(weights @ values)
                o[q + "_err"] = float(np.sqrt(n / (n - 1) * np.sum(weights ** 2 *
                                                                  (values - o[q]) ** 2)))
            o["span"] = sum(m["span"] for m in members)
            said = [m["notes"] for m in members if m["notes"]]
            o["notes"] = f"{len(members)} seeds" + "".join(
                f"; {note}" + (f" (x{said.count(note)})" if said.count(note) > 1 else "")
                for note in sorted(set(said), key=said.index))
        o["label"] = label(members[0]["variables"], varying)
        o["runs"] = members    # the runs behind the row, for rules that resample them
        combined.append(o)
    combined.sort(key=lambda o: (o["kn"], o["label"]))
    return combined


def same_series(a, b):
    """Two points' variables differ at most in kn and seed."""
    ignore = ("kn", "seed")
    return ({k: v for k, v in a.items() if k not in ignore} ==
            {k: v for k, v in b.items() if k not in ignore})


def label(variables, varying):
    """A point's variables other than seed and kn that vary among its scene's points
    (`varying`), as text: what tells it apart from its neighbours."""
    return ", ".join(f"{k} {v}" for k, v in sorted(variables.items()) if k in varying)


def varying_variables(variable_sets):
    """The names, other than scene, seed and kn, whose values differ among the given points."""
    names = set().union(*variable_sets) - {"scene", "seed", "kn"} if variable_sets else set()
    return {n for n in names if len({repr(v.get(n)) for v in variable_sets}) > 1}


def main_series(rows):
    """A scene's main series: the points of the label shared by the most k_n (ties: the first
    label in order). Claims are evaluated on it; points of other labels are variants (another
    integrator, time step, tangential law ...) compared with it at the same k_n."""
    if not rows:
        return []
    counts = {}
    for o in rows:
        counts[o["label"]] = counts.get(o["label"], 0) + 1
    best = max(sorted(counts), key=lambda k: counts[k])
    return [o for o in rows if o["label"] == best]


def variant_differences(rows):
    """[(variant row, main row, {quantity: (difference, difference / combined error)})] for
    every point outside the main series that has a main-series point at the same k_n."""
    main = main_series(rows)
    by_kn = {o["kn"]: o for o in main}
    out = []
    for o in rows:
        if o["label"] == (main[0]["label"] if main else None) or o["kn"] not in by_kn:
            continue
        m = by_kn[o["kn"]]
        diffs = {}
        for q in VARIANTS:
            d = o[q] - m[q]
            sigma = np.hypot(o[q + "_err"], m[q + "_err"])
            diffs[q] = (d, d / sigma if sigma > 0 else np.nan)
        out.append((o, m, diffs))
    return out


def series(rows, quantity):
    """kn, values, errors of one quantity over a scene's points."""
    kn = np.array([o["kn"] for o in rows])
    return kn, np.array([o[quantity] for o in rows]), np.array([o.get(quantity + "_err", np.nan)
                                                                for o in rows])


def ratio_with_error(o, top, bottom):
    """o[top] / o[bottom] and its error from both errors (not relative to the numerator, which
    may be zero)."""
    ratio = o[top] / o[bottom]
    return ratio, np.hypot(o[top + "_err"], ratio * o[bottom + "_err"]) / abs(o[bottom])


def fit_power(kn, values):
    """Exponent of values ~ kn^a by least squares in log-log (positive values only):
    (a, standard error)."""
    good = values > 0
    if good.sum() < 2:
        return np.nan, np.nan
    x, y = np.log(kn[good]), np.log(values[good])
    if good.sum() == 2:
        return (y[1] - y[0]) / (x[1] - x[0]), np.nan
    coefficients, covariance = np.polyfit(x, y, 1, cov=True)
    return coefficients[0], np.sqrt(covariance[0, 0])


def fit_log(kn, values):
    """Slope of values against ln kn: (slope, standard error, R^2 of the straight line)."""
    x = np.log(kn)
    if len(x) < 2:
        return np.nan, np.nan, np.nan
    if len(x) == 2:
        return (values[1] - values[0]) / (x[1] - x[0]), np.nan, 1.0
    coefficients, covariance = np.polyfit(x, values, 1, cov=True)
    residual = values - np.polyval(coefficients, x)
    spread = np.sum((values - values.mean()) ** 2)
    r2 = 1 - residual @ residual / spread if spread > 0 else np.nan    # flat: no line to fit
    return coefficients[0], np.sqrt(covariance[0, 0]), r2


def fit_log_bend(kn, values):
    """How far values bend away from a straight line in ln kn, as the exponent p of the power
    law that bends as much: with values = a + b x + c x^2 (x = ln kn - its mean), p = 2c/b
    (a power law A kn^p has exactly this p; a logarithm has 0). (p, standard error from the
    fit's covariance; nan where values have no slope)."""
    x = np.log(kn) - np.log(kn).mean()
    (c, b, _), covariance = np.polyfit(x, values, 2, cov=True)
    if b == 0:
        return np.nan, np.nan      # no slope, nothing that bends
    p = 2 * c / b
    gradient = np.array([2 / b, -2 * c / b ** 2])     # d p / d (c, b)
    return p, float(np.sqrt(gradient @ covariance[:2, :2] @ gradient))


# "Within its error" for the crossover: a point agrees with the stiff value when it lies within
# CROSSOVER_SIGMAS combined standard errors of it. One sigma would put a dozen flat stiff points
# out of agreement by chance (each has a 1 in 3 chance); two let ~1 in 20 out.
CROSSOVER_SIGMAS = 2.0


def crossover(kn, values, errors, stiff_from, sigmas=CROSSOVER_SIGMAS):
    """Where a series reaches its stiff value. The stiff value is the mean of the values at
    kn >= stiff_from, with its standard error (their scatter over sqrt(n)); the crossover is
    the smallest kn from which on every point agrees with it within `sigmas` combined errors
    (the point's and the stiff value's). A dict: kn (the crossover), bracket (the stiffest kn
    that differs, or None where the softest point already agrees; the crossover: the curve
    reaches the stiff value between them), stiff, stiff_err, n_stiff."""
    order = np.argsort(kn)
    kn, values, errors = (np.asarray(a, dtype=float)[order] for a in (kn, values, errors))
    stiff = kn >= stiff_from
    if stiff.sum() < 2:
        raise ValueError(f"the stiff value needs two or more points at k_n >= {stiff_from:g}, "
                         f"found {stiff.sum()}")
    level = values[stiff].mean()
    level_err = values[stiff].std(ddof=1) / np.sqrt(stiff.sum())
    differs = np.abs(values - level) > sigmas * np.hypot(errors, level_err)
    last = np.flatnonzero(differs)
    if len(last) and last[-1] == len(kn) - 1:
        raise ValueError(f"the stiffest point (k_n = {kn[-1]:g}) differs from the stiff value")
    first = last[-1] + 1 if len(last) else 0
    return {"kn": float(kn[first]), "bracket": (float(kn[first - 1]) if first else None,
                                                float(kn[first])),
            "stiff": float(level), "stiff_err": float(level_err), "n_stiff": int(stiff.sum())}



def contact_series(rows):
    """[(label, [(kn, durations.pooled of its runs' contact rows)])] of a scene's points
    (combine_seeds' rows), the main series first; only k_n with rows."""
    if not rows:
        return []
    main = main_series(rows)[0]["label"]
    out = []
    for name in [main] + sorted({o["label"] for o in rows} - {main}):
        points = [(o["kn"], pooled([m.get("contacts") for m in o.get("runs", [o])]))
                  for o in rows if o["label"] == name]
        points = [(k, p) for k, p in points if p is not None]
        if points:
            out.append((name, points))
    return out


def counterparts(rows_here, rows_there):
    """One scene's series in two sweeps matched by their variables: ({name: (value here,
    value there)} of the variables that tell the sweeps apart as wholes, each with one value
    throughout each sweep but not the same one (None: the deck's default), and {label here:
    label there, or None where the other sweep has no such series}). Two series match where
    their other variables than kn and seed are the same."""
    def values(rows, name):
        return {repr(o["variables"].get(name)) for o in rows}
    names = set().union(*(o["variables"] for o in rows_here + rows_there)) - {"kn", "seed"}
    apart = {}
    for name in sorted(names):
        here, there = values(rows_here, name), values(rows_there, name)
        if len(here) == len(there) == 1 and here != there:
            apart[name] = (rows_here[0]["variables"].get(name),
                           rows_there[0]["variables"].get(name))

    def key(o):
        return tuple(sorted((k, repr(v)) for k, v in o["variables"].items()
                            if k not in apart and k not in ("kn", "seed")))
    there_of = {key(o): o["label"] for o in rows_there}
    return apart, {o["label"]: there_of.get(key(o)) for o in rows_here}
