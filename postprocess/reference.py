"""The reference claims (claims.csv: one row per claim, the stiffness range it is about, its
source and its tolerance) and their evaluation on a study."""
import csv
from pathlib import Path

import numpy as np

from . import limit
from .study import fit_log, fit_power, main_series, ratio_with_error, series

CLAIMS = Path(__file__).with_name("claims.csv")
MEASURES = ("max_abs_deviation", "power_exponent", "log_slope", "log_r2", "ratio_at_stiffest",
            "limit_decision")


def load_claims(path=CLAIMS):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    for row in rows:
        for key in ("kn_min", "kn_max", "low", "high"):
            row[key] = float(row[key])
        if row["measure"] not in MEASURES:
            raise ValueError(f"{path}: claim {row['id']}: unknown measure {row['measure']}")
    return rows


def measure(claim, rows):
    """(value, standard error, '') of the claim on a scene's points within the claim's stiffness
    range, or (nan, nan, why not)."""
    rows = [o for o in rows if claim["kn_min"] <= o["kn"] <= claim["kn_max"]]
    quantity, kind = claim["quantity"], claim["measure"]
    where = f"k_n in [{claim['kn_min']:g}, {claim['kn_max']:g}]"
    if kind == "limit_decision":
        return limit_measure(rows, quantity)
    if kind == "ratio_at_stiffest":
        if not rows:
            return np.nan, np.nan, f"no point with {where}"
        return (*ratio_with_error(rows[-1], *quantity.split("/")), "")
    if len(rows) < 2:
        return np.nan, np.nan, f"needs at least 2 points with {where}, has {len(rows)}"
    kn, values, errors = series(rows, quantity)
    if kind == "max_abs_deviation":
        return float(np.max(np.abs(values - 4.0))), np.nan, ""
    if kind == "power_exponent":
        return (*fit_power(kn, values), "")
    slope, error, r2 = fit_log(kn, values)
    return (slope, error, "") if kind == "log_slope" else (r2, np.nan, "")


def limit_measure(rows, quantity):
    """The hard-sphere-limit rule (postprocess/limit.py) on the runs behind the rows: (the
    floor's lower 95 % bound, nan, '') with the verdict kept for evaluate, or (nan, nan, why
    it was not applied)."""
    runs = [run for o in rows for run in o.get("runs", [o])]
    decision = limit.decide(runs, quantity)
    if decision.verdict.startswith("not applied"):
        return np.nan, np.nan, decision.verdict.replace("not applied: ", "")
    return LimitValue(decision.floor_interval[0], decision), np.nan, ""


class LimitValue(float):
    """A decision claim's value (the floor's lower bound) that carries the decision."""

    def __new__(cls, value, decision):
        self = super().__new__(cls, value)
        self.decision = decision
        return self


def status_of(claim, value):
    """pass or FAIL: a range claim passes inside [low, high]; a limit decision passes if the
    rule says "finite", and fails on "vanishing" and on "undecided" (the claim is then not
    supported by the data)."""
    if claim["measure"] == "limit_decision":
        verdict = value.decision.verdict
        return "pass (finite)" if verdict == "finite" else f"FAIL ({verdict})"
    return "pass" if claim["low"] <= value <= claim["high"] else "FAIL"


def accepted(claim):
    """What a claim accepts, as the comparison tables show it."""
    if claim["measure"] == "limit_decision":
        return "finite (docs/hard_sphere_limit.md)"
    return f"[{claim['low']:g}, {claim['high']:g}]"


def evaluate(scenes, claims=None):
    """[(claim, measured, error, status)] with status pass, FAIL or 'not evaluated: why', on
    each scene's main series."""
    results = []
    for claim in claims or load_claims():
        rows = main_series(scenes.get(claim["scene"], []))
        if not rows:
            results.append((claim, np.nan, np.nan,
                            "not evaluated: no usable points of this scene"))
            continue
        value, error, reason = measure(claim, rows)
        if not np.isfinite(value):
            results.append((claim, value, error, f"not evaluated: {reason or 'no value'}"))
        else:
            results.append((claim, value, error, status_of(claim, value)))
    return results
