"""The reference claims (claims.csv: one row per claim of the paper, the stiffness range it is
about, the measure that tests it, the range of that measure the paper's physics gives, the
nearest physics the paper rules out and the value the measure takes under it) and their
evaluation on a study.

A claim's verdict, from the measured value v and its standard error:
  pass      v lies inside the accepted range [low, high] (the paper's physics) and the
            alternative's value lies outside v's 2-sigma interval [v - 2 err, v + 2 err]
  differs   the 2-sigma interval lies wholly outside the range: the data contradict the paper
  FAIL      neither: the data cannot tell the paper's physics from the alternative
A measure without an error bar (a maximum over points) is compared as it is. The
hard-sphere-limit decision maps finite / vanishing / undecided to pass / differs / FAIL."""
import csv
from pathlib import Path

import numpy as np

from . import limit
from .scenes import scene
from .study import (crossover, fit_log, fit_log_bend, fit_power, main_series, ratio_with_error,
                    series)

CLAIMS = Path(__file__).with_name("claims.csv")
MEASURES = ("max_abs_deviation", "power_exponent", "log_slope", "log_bend", "ratio_at_stiffest",
            "crossover_kn", "limit_decision", "collapse_fraction")
# collapse_fraction's quantities: which event-driven runs it counts, by their boundary
# restitution e_w (params.txt)
COLLAPSE_RUNS = {"e_w<1": lambda e_w: e_w < 1.0, "e_w=1": lambda e_w: e_w == 1.0}
NUMBERS = ("kn_min", "kn_max", "low", "high", "reference", "expected", "alternative_value")
SIGMAS = 2.0    # the width, in standard errors, of the interval a verdict compares


def load_claims(path=CLAIMS):
    """The claims, each checked to be able to fail: its alternative's value lies outside the
    accepted range (or on an end of it) and the paper's expected value inside it."""
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    for row in rows:
        where = f"{path}: claim {row['id']}"
        for key in NUMBERS:
            row[key] = float(row[key]) if row[key] not in ("", None) else np.nan
        if row["measure"] not in MEASURES:
            raise ValueError(f"{where}: unknown measure {row['measure']}")
        if not row.get("alternative"):
            raise ValueError(f"{where}: names no alternative physics")
        if row["measure"] == "limit_decision":
            continue
        if not row["low"] <= row["expected"] <= row["high"]:
            raise ValueError(f"{where}: the paper's value {row['expected']:g} is outside "
                             f"[{row['low']:g}, {row['high']:g}]")
        # on an end of the range it cannot pass either: a 2-sigma interval around it sticks out
        if row["low"] < row["alternative_value"] < row["high"]:
            raise ValueError(f"{where}: the alternative's value {row['alternative_value']:g} "
                             f"passes [{row['low']:g}, {row['high']:g}]: the claim cannot fail")
        if row["measure"] == "collapse_fraction" and row["quantity"] not in COLLAPSE_RUNS:
            raise ValueError(f"{where}: collapse_fraction counts the runs of "
                             f"{' or '.join(COLLAPSE_RUNS)}, not {row['quantity']}")
        if row["measure"] == "max_abs_deviation" and not np.isfinite(row["reference"]):
            raise ValueError(f"{where}: max_abs_deviation needs a reference value")
    return rows


def measure(claim, rows, rule=limit.RULE):
    """(value, standard error, '') of the claim on a scene's points within the claim's stiffness
    range, or (nan, nan, why not); rule: the hard-sphere-limit rule a decision claim uses."""
    rows = [o for o in rows if claim["kn_min"] <= o["kn"] <= claim["kn_max"]]
    quantity, kind = claim["quantity"], claim["measure"]
    where = f"k_n in [{claim['kn_min']:g}, {claim['kn_max']:g}]"
    if kind == "limit_decision":
        return limit_measure(rows, quantity, rule)
    if kind == "ratio_at_stiffest":
        if not rows:
            return np.nan, np.nan, f"no point with {where}"
        return (*ratio_with_error(rows[-1], *quantity.split("/")), "")
    # a fit's error bar needs one point more than its parameters
    needed = {"max_abs_deviation": 2, "log_bend": 4}.get(kind, 3)
    if len(rows) < needed:
        return np.nan, np.nan, f"needs at least {needed} points with {where}, has {len(rows)}"
    kn, values, errors = series(rows, quantity)
    if kind == "crossover_kn":
        return crossover_measure(kn, values, errors, scene(claim["scene"]).stiff_from)
    if kind == "max_abs_deviation":
        return float(np.max(np.abs(values - claim["reference"]))), np.nan, ""
    if kind == "power_exponent":
        if np.any(values <= 0):
            return np.nan, np.nan, (f"{quantity} <= 0 at k_n = "
                                    f"{', '.join(f'{k:g}' for k in kn[values <= 0])}: "
                                    "no power law to fit")
        return (*fit_power(kn, values), "")
    if kind == "log_bend":
        return (*fit_log_bend(kn, values), "")
    slope, error, _ = fit_log(kn, values)
    return slope, error, ""


def collapse_measure(claim, records):
    """The fraction of a scene's pure event-driven runs (engine event_driven, collapse = stop:
    a detected inelastic collapse ends the run, which then says when: stopped_at) of the
    claim's e_w that collapsed before run_time, with its binomial standard error
    sqrt(p (1 - p) / n); (nan, nan, why) where there are none."""
    chosen = COLLAPSE_RUNS[claim["quantity"]]
    runs = [r for r in records or []
            if (r.variables or {}).get("engine") == "event_driven" and r.params
            and r.params.get("collapse") == "stop" and chosen(float(r.params["e_w"]))]
    if not runs:
        return np.nan, np.nan, (f"no completed event-driven run with collapse = stop and "
                                f"{claim['quantity']}")
    p = sum(r.stopped_at is not None for r in runs) / len(runs)
    return p, float(np.sqrt(p * (1 - p) / len(runs))), ""


def crossover_measure(kn, values, errors, stiff_from):
    """log10 of the k_n from which the series agrees with its stiff value (study.crossover),
    with half its bracket's width in log10 as the error; (nan, nan, why) where there is none."""
    try:
        c = crossover(kn, values, errors, stiff_from)
    except ValueError as error:
        return np.nan, np.nan, str(error)
    softer, at = c["bracket"]
    if softer is None:
        return np.nan, np.nan, (f"the softest point (k_n = {at:g}) already agrees: the "
                                "crossover lies below the points")
    return np.log10(at), 0.5 * np.log10(at / softer), ""


def limit_measure(rows, quantity, rule=limit.RULE):
    """The hard-sphere-limit rule (postprocess/limit.py) on the runs behind the rows: (the
    floor's lower 95 % bound, nan, '') with the verdict kept for evaluate, or (nan, nan, why
    it was not applied)."""
    runs = [run for o in rows for run in o.get("runs", [o])]
    decision = limit.decide(runs, quantity, rule=rule)
    if decision.verdict.startswith("not applied"):
        return np.nan, np.nan, decision.verdict.replace("not applied: ", "")
    return LimitValue(decision.floor_interval[0], decision), np.nan, ""


class LimitValue(float):
    """A decision claim's value (the floor's lower bound) that carries the decision."""

    def __new__(cls, value, decision):
        self = super().__new__(cls, value)
        self.decision = decision
        return self


LIMIT_VERDICTS = {"finite": "pass (finite)", "vanishing": "differs (vanishing)",
                  "undecided": "FAIL (undecided)"}


def status_of(claim, value, error=np.nan):
    """pass, differs or FAIL (module docstring)."""
    if claim["measure"] == "limit_decision":
        return LIMIT_VERDICTS[value.decision.verdict]
    spread = SIGMAS * error if np.isfinite(error) else 0.0
    lo, hi = value - spread, value + spread
    if claim["low"] <= value <= claim["high"] and not lo <= claim["alternative_value"] <= hi:
        return "pass"
    if hi < claim["low"] or lo > claim["high"]:
        return "differs"
    return "FAIL"


def accepted(claim):
    """What a claim accepts, as the comparison tables show it."""
    if claim["measure"] == "limit_decision":
        return "finite (docs/hard_sphere_limit.md)"
    return f"[{claim['low']:g}, {claim['high']:g}]"


def evaluate(scenes, claims=None, rule=limit.RULE, completed=None):
    """[(claim, measured, error, status)] with status pass, differs, FAIL or 'not evaluated:
    why', on each scene's main series (collapse_fraction: on the scene's completed runs,
    `completed`, study.analyse's); rule: the hard-sphere-limit rule (1 or 2)."""
    results = []
    for claim in claims or load_claims():
        if claim["measure"] == "collapse_fraction":
            value, error, reason = collapse_measure(claim, (completed or {}).get(claim["scene"]))
            results.append((claim, value, error,
                            status_of(claim, value, error) if np.isfinite(value)
                            else f"not evaluated: {reason}"))
            continue
        # the paper's claims on its soft model: event-driven runs are not part of its series
        rows = main_series([o for o in scenes.get(claim["scene"], [])
                            if (o.get("variables") or {}).get("engine") != "event_driven"])
        if not rows:
            results.append((claim, np.nan, np.nan,
                            "not evaluated: no usable points of this scene"))
            continue
        value, error, reason = measure(claim, rows, rule)
        if not np.isfinite(value):
            results.append((claim, value, error, f"not evaluated: {reason or 'no value'}"))
        else:
            results.append((claim, value, error, status_of(claim, value, error)))
    return results


def tally(results):
    """{'pass': n, 'differs': n, 'FAIL': n, 'not evaluated': n} of evaluate's results."""
    counts = {"pass": 0, "differs": 0, "FAIL": 0, "not evaluated": 0}
    for *_, status in results:
        counts[next(k for k in counts if status.startswith(k))] += 1
    return counts
