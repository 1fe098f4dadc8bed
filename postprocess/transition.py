"""The collisional-frictional transition (docs/transition.md): how each run ended, the
distribution of contact durations, and per base and inclination what tells the paper's two
flows apart (the stiffness exponents of N_c and N_w, the multiple-contact fraction, the
contacts per disk, the tail of P(tau))."""
from pathlib import Path

import numpy as np

from . import rundir
from .durations import contact_durations, tail_fraction
from .io import CONTACT_KINDS, DataError
from .observables import observables, relative, rest_time
from .runs import read_run
from .scenes import SCENES, transition_scene
from .signals import block_means, trend
from .study import combine_seeds, fit_power, ratio_with_error

# The flow-state rule, the one place it is stated (docs/transition.md):
#   stopped       the run ended early because its pile stopped (stopped.txt), or its kinetic
#                 energy per disk stayed below REST_ENERGY for its last REST_TIME
#                 (observables.rest_time): there is no flow to average;
#   accelerating  E per disk, averaged over the last fifth of the averaging span, is more than
#                 GROWTH_LIMIT times its average over the first fifth: no steady state within
#                 the run (E of a flow gaining speed freely grows like t^2);
#   drifting      not accelerating, but E per disk changes over the averaging span by more
#                 than it fluctuates: the trend of E(t) over the span (a line through the means
#                 of DRIFT_BLOCKS blocks) changes by more than the standard deviation of E(t)
#                 about it, and the trend is significant (its slope more than DRIFT_SIGMAS
#                 standard errors from 0: a steady flow whose E wanders slowly has a slope of
#                 ~1 standard error). A flow still settling, slowing down or changing level is
#                 not a steady flow to average;
#   flowing       otherwise: averaged.
# Why 2: the steady frictional flows at sin theta = 0.20 wander within the selection's width
# 0.45 at E ~ 0.6 (a factor below 2 between any two stretches of a steady part), while a flow
# that accelerates from rest over the span grows by far more than 2 (flat base, sin theta 0.45,
# k_n 5e4: a factor ~3.4 between t = 100 and 300, measured).
GROWTH_LIMIT = 2.0
DRIFT_BLOCKS, DRIFT_SIGMAS = 10, 3.0
STATE_BLOCKS = 5
STATES = ("flowing", "stopped", "accelerating", "drifting")
def flow_state(t, energy, average_start, stopped_at=None):
    """(state, growth) of a run from its E(t) per disk: state one of STATES by the rule above,
    growth the ratio of E over the last to the first fifth of the averaging span (nan where
    the run stopped)."""
    t, energy = np.asarray(t, dtype=float), np.asarray(energy, dtype=float)
    if stopped_at is not None or rest_time(t, energy) is not None:
        return "stopped", np.nan
    inside = t >= average_start
    if np.count_nonzero(inside) < STATE_BLOCKS:
        raise DataError(f"fewer than {STATE_BLOCKS} samples after average_start "
                        f"{average_start:g}: no state")
    span_t = t[inside]
    end = span_t[-1] + 0.5 * (span_t[-1] - span_t[-2])
    _, means = block_means(span_t, energy[inside], span_t[0], end, STATE_BLOCKS)
    growth = means[-1] / means[0] if means[0] > 0 else np.inf
    if growth > GROWTH_LIMIT:
        return "accelerating", growth
    slope, slope_err = trend(span_t, energy[inside], span_t[0], end, DRIFT_BLOCKS)
    fluctuation = np.std(energy[inside] - slope * span_t)     # about the trend
    drifts = (abs(slope) * (end - span_t[0]) > fluctuation and
              abs(slope) > DRIFT_SIGMAS * slope_err)
    return ("drifting" if drifts else "flowing"), growth


def transition_run(record):
    """One completed run (a RunRecord read without steady parts) as the transition study sees
    it: its variables, state and growth, and (flowing runs) its observables averaged as the
    study does and its contact durations (if it wrote rows)."""
    params, energy = record.params, record.outputs.energy
    state, growth = flow_state(energy["time"], energy["e_total"], params["average_start"],
                               record.stopped_at)
    run = {"point": record.point, "scene": params["scene"], "sin_theta": params["sin_theta"],
           "kn": params["kn"], "seed": params["seed"], "state": state, "growth": growth,
           "variables": record.variables}
    if state == "flowing":
        o = observables(params, record.measured, record.stopped_at,
                        scene_def=transition_scene(params["scene"]))
        o.update(point=record.point, variables=record.variables)
        run["observables"] = o
        if (record.point / rundir.ROWS).exists():
            run["durations"] = contact_durations(record.outputs.rows, params["tau_c"],
                                                 params["tau_w"], params["average_start"])
    return run


def analyse_transition(sweep_dir):
    """[transition_run of each run], {(scene, sin_theta): [observables per kn, seeds
    combined]}, [(point, reason) left out] of a transition sweep."""
    sweep_dir = Path(sweep_dir)
    points = sorted(p for p in sweep_dir.glob("*/*") if (p / rundir.POINT).exists())
    if not points and any(sweep_dir.glob("*/*.json")):
        raise DataError(f"{sweep_dir}: the transition study needs the raw outputs, and these are "
                        "run summaries (<scene>/<point>.json): summaries hold E(t) only as its "
                        "means over windows of 1 and the contact durations only as a "
                        "histogram; the study classifies each run from every sample of "
                        "energy.txt and pools the durations in contacts.txt")
    if not points:
        raise DataError(f"{sweep_dir}: no sweep points here (no <scene>/<point>/point.json)")
    runs, left_out = [], []
    for point in points:
        if point.parent.name not in SCENES or not SCENES[point.parent.name].base:
            left_out.append((point, f"scene '{point.parent.name}' is not a base of the "
                                    "transition study"))
            continue
        record = read_run(point, resolutions=())
        if record.reason is not None:
            left_out.append((point, record.reason))
            continue
        try:
            runs.append(transition_run(record))
        except DataError as error:
            left_out.append((point, relative(error, point)))
    groups = {}
    for r in runs:
        if "observables" in r:
            groups.setdefault((r["scene"], r["sin_theta"]), []).append(r["observables"])
    return runs, {key: combine_seeds(rows) for key, rows in sorted(groups.items())}, left_out


def pooled_durations(runs, scene, sin_theta, kn):
    """{kind: the scaled durations of every flowing run of one point, seeds pooled}."""
    chosen = [r["durations"] for r in runs if "durations" in r and r["scene"] == scene and
              r["sin_theta"] == sin_theta and r["kn"] == kn]
    return {kind: np.concatenate([d[kind] for d in chosen]) if chosen else np.array([])
            for kind in CONTACT_KINDS}


def transition_table(runs, groups):
    """One row per (scene, sin_theta): how the runs ended, the stiffness exponents of N_c and
    N_w over the k_n with flowing runs, and at the stiffest of them the multiple-contact
    fraction (t_c - N_c tau_c)/t_c, the time with two or more contacts, the contacts per disk,
    E and the tail of P(tau)."""
    table = []
    for scene, sin_theta in sorted({(r["scene"], r["sin_theta"]) for r in runs}):
        mine = [r for r in runs if r["scene"] == scene and r["sin_theta"] == sin_theta]
        row = {"scene": scene, "sin_theta": sin_theta, "runs": len(mine)}
        for state in STATES:
            row[state] = sum(r["state"] == state for r in mine)
        # the region: the state of most runs (ties: the first of STATES)
        row["state"] = max(STATES, key=lambda s: row[s])
        points = groups.get((scene, sin_theta), [])
        row["kn_flowing"] = [o["kn"] for o in points]
        kn = np.array(row["kn_flowing"])
        for q in ("N_c", "N_w"):
            values = np.array([o[q] for o in points])
            row[f"exponent_{q}"], row[f"exponent_{q}_err"] = (
                fit_power(kn, values) if len(points) >= 2 else (np.nan, np.nan))
        if points:
            top = points[-1]
            row["kn_stiffest"] = top["kn"]
            row["mc_fraction"], row["mc_fraction_err"] = ratio_with_error(top, "mc_c", "t_c")
            for q in ("t_multiple", "z", "E_total", "t_c"):
                row[q], row[q + "_err"] = top[q], top[q + "_err"]
            durations = pooled_durations(runs, scene, sin_theta, top["kn"])
            for kind in CONTACT_KINDS:
                row[f"tail_{kind}"] = tail_fraction(durations[kind])
                row[f"contacts_{kind}"] = len(durations[kind])
        table.append(row)
    return table
