"""A sweep's points, analysed: per-scene tables of observables, and what was left out."""
import json
from pathlib import Path

import numpy as np

from .io import DataError, read_energy, read_params, read_profile, read_trajectory
from .observables import point_observables
from .signals import dominant_period

QUANTITIES = ("E_trans", "E_rot", "E_total", "N_c", "N_w", "t_c", "t_w", "mc_c", "mc_w",
              "t_multiple")


def analyse(sweep_dir):
    """{scene: [observables of each usable point, sorted by kn]}, [(point, reason) left out],
    {scene: [completed points]} (usable or not: their time series can still be shown)."""
    sweep_dir = Path(sweep_dir)
    if not sweep_dir.is_dir():
        raise DataError(f"{sweep_dir}: no such sweep directory")
    scenes, left_out, completed = {}, [], {}
    for point in sorted(p for p in sweep_dir.glob("*/*") if (p / "point.json").exists()):
        if not (point / "done.txt").exists():
            left_out.append((point, "did not complete (no done.txt)"))
            continue
        completed.setdefault(point.parent.name, []).append(point)
        try:
            o = point_observables(point)
            o["point"] = point
            o["variables"] = json.loads((point / "point.json").read_text())
            if o["scene"] == "single_disk":
                trajectory = read_trajectory(point)
                late = trajectory["time"] > read_params(point)["average_start"]
                o["period"], _ = dominant_period(trajectory["time"][late],
                                                 trajectory["vy"][late], max_period=20.0)
            scenes.setdefault(o["scene"], []).append(o)
        except DataError as error:
            left_out.append((point, str(error).replace(f"{point}: ", "")))
    scenes = {scene: combine_seeds(rows) for scene, rows in scenes.items()}
    return scenes, left_out, completed


def combine_seeds(rows):
    """Points that differ only in seed become one: the mean over seeds, with the spread across
    seeds (standard error) as the error when there are several, else the block error."""
    groups = {}
    for o in rows:
        key = tuple(sorted((k, v) for k, v in o["variables"].items() if k != "seed"))
        groups.setdefault(key, []).append(o)
    combined = []
    for members in groups.values():
        o = dict(members[0])
        if len(members) > 1:
            for q in QUANTITIES + ("period",):
                if q not in o:
                    continue
                values = np.array([m[q] for m in members])
                o[q] = values.mean()
                o[q + "_err"] = values.std(ddof=1) / np.sqrt(len(values))
            o["span"] = sum(m["span"] for m in members)
            o["notes"] = f"{len(members)} seeds; " + "; ".join(m["notes"] for m in members if m["notes"])
        o["label"] = ", ".join(f"{k} {v}" for k, v in sorted(members[0]["variables"].items())
                               if k not in ("scene", "seed", "kn"))
        combined.append(o)
    combined.sort(key=lambda o: (o["kn"], o["label"]))
    return combined


def series(rows, quantity):
    """kn, values, errors of one quantity over a scene's points."""
    kn = np.array([o["kn"] for o in rows])
    return kn, np.array([o[quantity] for o in rows]), np.array([o[quantity + "_err"] for o in rows])


def fit_power(kn, values, errors=None):
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
    """Slope of values against ln kn: (slope, standard error)."""
    x = np.log(kn)
    if len(x) < 2:
        return np.nan, np.nan
    if len(x) == 2:
        return (values[1] - values[0]) / (x[1] - x[0]), np.nan
    coefficients, covariance = np.polyfit(x, values, 1, cov=True)
    return coefficients[0], np.sqrt(covariance[0, 0])


def profiles(rows):
    out = []
    for o in rows:
        try:
            out.append((o["kn"], read_profile(o["point"])))
        except DataError:
            pass
    return out


def energy_series(points):
    """(kn, energy.txt) of completed points, sorted by kn."""
    out = []
    for point in points:
        params = read_params(point)
        out.append((params["kn"], read_energy(point, params)))
    return sorted(out, key=lambda item: item[0])
