"""The reference claims (claims.csv: one row per claim, its source and its tolerance) and their
evaluation on a study."""
import csv
from pathlib import Path

import numpy as np

from .study import fit_log, fit_power, series

CLAIMS = Path(__file__).with_name("claims.csv")


def load_claims(path=CLAIMS):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    for row in rows:
        row["low"], row["high"] = float(row["low"]), float(row["high"])
    return rows


def measure(claim, rows):
    """The claim's measured value on a scene's points, or (nan, reason)."""
    quantity, kind = claim["quantity"], claim["measure"]
    if len(rows) < 2 and kind != "ratio_at_stiffest":
        return np.nan, "needs at least 2 points"
    if kind == "max_abs_deviation":
        values = np.array([o[quantity] for o in rows])
        return float(np.max(np.abs(values - 4.0))), ""
    if kind == "ratio_at_stiffest":
        top, bottom = quantity.split("/")
        stiffest = rows[-1]
        return stiffest[top] / stiffest[bottom], ""
    kn, values, errors = series(rows, quantity)
    if kind == "log_slope":
        return fit_log(kn, values)[0], ""
    if kind == "power_exponent":
        return fit_power(kn, values)[0], ""
    if kind == "relative_spread":
        return float(np.ptp(values) / np.mean(values)), ""
    raise ValueError(f"claims.csv: unknown measure {kind}")


def evaluate(scenes, claims=None):
    """[(claim, measured, status)] with status pass, FAIL or 'not evaluated: why'."""
    results = []
    for claim in claims or load_claims():
        rows = scenes.get(claim["scene"], [])
        if not rows:
            results.append((claim, np.nan, "not evaluated: no usable points of this scene"))
            continue
        value, reason = measure(claim, rows)
        if not np.isfinite(value):
            results.append((claim, value, f"not evaluated: {reason or 'no value'}"))
        else:
            results.append((claim, value, "pass" if claim["low"] <= value <= claim["high"]
                            else "FAIL"))
    return results
