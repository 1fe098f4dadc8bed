"""Observables of one point (docs/model.md section 6) from its outputs, with block-average errors."""
from dataclasses import replace

import numpy as np

from .budget import budget_problem
from .durations import run_contacts
from .quantities import BLOCKS
from .io import CUMULATIVE_COUNTERS, DataError, Point
from .scenes import SCENES, scene
from .selection import Selection, in_energy_range, steady_parts
from .signals import dominant_period

# The time resolutions (time units) at which the report counts the steady parts kept, so that
# the reader sees what the choice of resolution does (docs/model.md section 5).
RESOLUTIONS = (0.1, 1.0, 5.0)
# The pieces an averaged span is cut into for its block-average errors.
N_BLOCKS = 5
# A run has come to rest when its kinetic energy per disk stays below REST_ENERGY over its last
# REST_TIME time units. The analysis's own rule, not the run's stop_energy and stop_time:
# params.txt does not carry them, the rule applies as well to runs whose deck never stops
# early (the collisional deck's default stop_energy 0; the single disk has no stop rule), and
# it asks every sample to stay below where inputs/lib/stop.lmp tests a running mean. The
# values are the frictional deck's defaults.
REST_ENERGY, REST_TIME = 1e-5, 10.0


def bottom_layer(counts):
    """Disks that touched the boundary during the window (frictional flow normalisation)."""
    return int(np.count_nonzero((counts["begun_boundary"] > 0) | (counts["time_boundary"] > 0)))


def span_rates(energy, spans, n_particles, n_boundary):
    """Collision rates and contact-time fractions over a union of spans of energy.txt, from the
    increments of the cumulative counter sums (all spans inside one counter window)."""
    length = sum(energy["time"][b - 1] - energy["time"][a] for a, b in spans)
    if length <= 0:
        raise DataError("the selected spans have no length")
    delta = {k: sum(energy[k][b - 1] - energy[k][a] for a, b in spans) for k in CUMULATIVE_COUNTERS}
    return {
        "N_c": delta["begun_disk"] / (n_particles * length),
        "N_w": delta["begun_boundary"] / (n_boundary * length),
        "t_c": delta["time_disk"] / (n_particles * length),
        "t_w": delta["time_boundary"] / (n_boundary * length),
        "t_multiple": delta["time_multiple"] / (n_particles * length),
    }


def with_errors(blocks):
    """Mean over blocks and its standard error, per observable ({quantity: [value per
    block]})."""
    result = {}
    for key, values in blocks.items():
        values = np.array(values)
        result[key] = values.mean()
        result[key + "_err"] = values.std(ddof=1) / np.sqrt(len(values)) if len(values) > 1 else np.nan
    return result


def averaging_rows(energy, params):
    """Rows of energy.txt in the counter window that restarts at average_start (the row written
    at that very step still holds the sums from before the restart)."""
    slack = 1e-9 * params["run_time"]
    return ((energy["time"] >= params["average_start"] - slack) &
            (energy["window"] <= energy["time"] - params["average_start"] + slack))


def rest_time(t, energy):
    """The time from which the energy stays below REST_ENERGY to the end of the series, if it
    does so for at least REST_TIME; else None."""
    above = np.flatnonzero(np.asarray(energy) >= REST_ENERGY)
    first_at_rest = above[-1] + 1 if len(above) else 0
    if first_at_rest >= len(t) or t[-1] - t[first_at_rest] < REST_TIME:
        return None
    return t[first_at_rest]


def contacts_per_disk(contacts_now, n_disks):
    """Mean number of contacts a disk has, boundary contacts included (docs/model.md section
    6), from samples of the sum over the disks of their current contacts: a disk-disk contact
    is in the sum twice, once for each disk, a boundary contact once."""
    return float(np.mean(contacts_now)) / n_disks


def relative(error, point):
    """A DataError's text without the point's directory: the file inside it and the problem."""
    return str(error).replace(f"{point}/", "").replace(f"{point}: ", "")


def span_blocks(energy, a, b, params, n_boundary, n_blocks):
    """The span [a, b) of energy.txt's rows cut into n_blocks pieces: the piece's time span
    and {quantity: [its value in each piece]} (pieces of fewer than 2 rows left out)."""
    n = params["n_mobile"]
    blocks = {q: [] for q in BLOCKS}
    edges = np.linspace(a, b, n_blocks + 1).astype(int)
    for lo, hi in zip(edges[:-1], edges[1:]):
        if hi - lo < 2:
            continue
        block = span_rates(energy, [(lo, hi)], n, n_boundary)
        for key in ("e_trans", "e_rot", "e_total"):
            block[key.replace("e_", "E_")] = energy[key][lo:hi].mean()
        block["mc_c"] = block["t_c"] - block["N_c"] * params["tau_c"]
        block["mc_w"] = block["t_w"] - block["N_w"] * params["tau_w"]
        block["z"] = contacts_per_disk(energy["contacts_now"][lo:hi], n)
        for q in BLOCKS:
            blocks[q].append(float(block[q]))
    return {"span": float(energy["time"][b - 1] - energy["time"][a]), "blocks": blocks}


def single_disk_period(point, scene_def):
    """The single disk's v_y period and the time to pass one bump, from trajectory.txt after
    average_start (point: an io.Point)."""
    trajectory, params = point.trajectory, point.params
    late = trajectory["time"] > params["average_start"]
    if np.count_nonzero(late) < 4:
        raise DataError(f"trajectory.txt: {np.count_nonzero(late)} samples after "
                        f"average_start {params['average_start']:g}, the v_y period needs at "
                        "least 4")
    try:
        period, _ = dominant_period(trajectory["time"][late], trajectory["vy"][late],
                                    max_period=20.0)
    except ValueError as error:
        raise DataError(f"trajectory.txt: {error}")
    return float(period), float(scene_def.bump_spacing / trajectory["vx"][late].mean())


def measure(point, resolutions=(), selection=Selection()):
    """What the averages of a completed run (an io.Point) are made of, before any choice of
    what to average (docs/model.md sections 5-6). A dict:
      problem       why the run cannot be averaged at all (None if it can); then the parts
                    in `steady` have only start, stop and mean, and nothing else follows
      steady        {resolution: [steady part]} for each of `resolutions`: the parts the
                    frictional selection finds in E(t) at that resolution (selection's
                    min_length and max_width), energy range not yet applied; a part is
                    {start, stop, span, mean (of the window means: what the energy range is
                    tested on), mean_samples, blocks}
      window        the whole averaging window as one part {start, stop, span, blocks}
      rest_at       rest_time of the whole run (None: never at rest for REST_TIME)
      n_boundary    the disks the boundary rates are per (all, or the bottom layer)
      period, bump_time, period_problem   (scenes with has_period) the v_y period and the
                    time to pass a bump, or why there are none
      budget_problem   (runs with energies = yes whose energy budget does not close:
                    budget.budget_problem) why; absent where it closes
      contacts, contacts_problem   (runs with contact rows) durations.run_contacts: P(tau)'s
                    histogram and the split of the time with two or more contacts; or why the
                    rows could not be read (contacts None)
    where blocks is {quantity: [value in each of N_BLOCKS pieces]} (BLOCKS)."""
    params, energy, stopped_at = point.params, point.energy, point.stopped_at
    inside = averaging_rows(energy, params)
    first = int(np.argmax(inside))
    # inside is the rows after the counters' restart: all rows from `first` on
    found = {r: steady_parts(energy["time"][first:], energy["e_total"][first:],
                             replace(selection, resolution=r)) if inside.any() else []
             for r in resolutions}
    measured = {"problem": None, "steady": {}}
    try:
        counts = point.counts
        n = params["n_mobile"]
        end = params["run_time"] if stopped_at is None else stopped_at
        if len(counts["id"]) != n:
            raise DataError(f"counts.txt: {len(counts['id'])} disks, params.txt says "
                            f"{n:g}")
        if stopped_at is not None and stopped_at <= params["average_start"]:
            raise DataError(f"the pile stopped at t = {stopped_at:g}, before the "
                            f"averaging span (average_start {params['average_start']:g})")
        if not inside.any():
            raise DataError(f"energy.txt: no samples after average_start "
                            f"{params['average_start']:g}: the run did not reach its averaging "
                            "span")
        if energy["time"][-1] < end - 1.5 * (energy["time"][1] - energy["time"][0]):
            raise DataError(f"energy.txt: ends at t = {energy['time'][-1]:g}, before "
                            f"{'its stop' if stopped_at is not None else 'run_time'} {end:g}: "
                            "truncated?")
        try:
            scene_def = scene(params["scene"])
        except KeyError as error:
            raise DataError(f"params.txt: {error.args[0]}")
    except DataError as error:
        measured["problem"] = relative(error, point.directory)
        measured["steady"] = {r: [dict(start=float(energy["time"][a + first]),
                                       stop=float(energy["time"][b + first - 1]), mean=mean)
                                  for a, b, mean in parts] for r, parts in found.items()}
        return measured

    n_boundary = bottom_layer(counts) if scene_def.boundary_per_bottom_layer else int(n)

    def part(a, b):
        if n_boundary == 0:     # no rates per boundary disk: observables() says so
            return {"span": float(energy["time"][b - 1] - energy["time"][a]),
                    "blocks": {q: [] for q in BLOCKS}}
        return span_blocks(energy, a, b, params, n_boundary, N_BLOCKS)

    def located(a, b):
        return {"start": float(energy["time"][a]), "stop": float(energy["time"][b - 1]),
                **part(a, b)}

    for r, parts in found.items():
        measured["steady"][r] = [
            {**located(a + first, b + first), "mean": mean,
             "mean_samples": float(energy["e_total"][a + first:b + first].mean())}
            for a, b, mean in parts]
    measured.update(window=located(first, len(energy["time"])), n_boundary=n_boundary,
                    rest_at=rest_time(energy["time"], energy["e_total"]))
    if measured["rest_at"] is not None:
        measured["rest_at"] = float(measured["rest_at"])
    if scene_def.has_period:
        try:
            measured["period"], measured["bump_time"] = single_disk_period(point, scene_def)
            measured["period_problem"] = None
        except DataError as error:
            measured.update(period=None, bump_time=None,
                            period_problem=relative(error, point.directory))
    problem = budget_problem(energy, params)
    if problem:
        measured["budget_problem"] = problem
    if (point.directory / "contacts.txt").exists():
        try:
            measured.update(contacts=run_contacts(point, first), contacts_problem=None)
        except (DataError, ValueError) as error:
            measured.update(contacts=None, contacts_problem=relative(error, point.directory))
    return measured


def observables(params, measured, stopped_at, selection=Selection(), scene_def=None):
    """E, N_c, N_w, t_c, t_w, the multiple-contact estimates, the direct fraction of time with
    two or more contacts and the contacts per disk of one run (measure's result), averaged
    over its averaging window or, where the scene selects steady parts, over the parts the
    selection keeps, each with a block-average error; period and bump_time where the scene
    has them. stopped_at: when the run's pile stopped (None: it ran to run_time). scene_def: the
    Scene to average as (default: the run's own). A DataError says why the run has no such
    averages."""
    if measured["problem"]:
        raise DataError(measured["problem"])
    scene_def = scene_def or scene(params["scene"])
    notes = [f"stopped at t = {stopped_at:g}"] if stopped_at is not None else []
    if measured.get("budget_problem"):
        notes.append(measured["budget_problem"])
    if scene_def.selects_steady_parts:
        if selection.resolution not in measured["steady"]:
            raise DataError(f"no steady parts at resolution {selection.resolution:g} here "
                            f"(only at {', '.join(f'{r:g}' for r in measured['steady'])})")
        found = measured["steady"][selection.resolution]
        parts = [p for p in found if in_energy_range(p["mean"], selection)]
        if not parts:
            means = ", ".join(f"{p['mean_samples']:.3g}" for p in found)
            low, high = selection.energy_range
            raise DataError(f"no steady part with mean energy in [{low:g}, {high:g}] "
                            f"at resolution {selection.resolution:g} ({len(found)} steady parts "
                            f"found"
                            f"{', mean E ' + means if found else ''}; "
                            f"{notes[0] if notes else 'flowing to the end'})")
        notes.append(f"{len(parts)} of {len(found)} steady parts selected")
    else:
        parts = [measured["window"]]
        if measured["rest_at"] is not None:
            raise DataError(f"came to rest at t = {measured['rest_at']:.4g} (E per disk below "
                            f"{REST_ENERGY:g} from then on): no steady motion to average")
    if measured["n_boundary"] == 0:
        raise DataError("no disk touched the boundary in the averaging window")
    blocks = {q: [v for p in parts for v in p["blocks"][q]] for q in BLOCKS}
    if len(blocks["E_total"]) < 2:
        raise DataError("the averaging span is too short for error bars")
    result = with_errors(blocks)
    result.update(kn=params["kn"], tau_c=params["tau_c"], tau_w=params["tau_w"],
                  scene=params["scene"], n_boundary=measured["n_boundary"],
                  span=sum(p["span"] for p in parts), notes="; ".join(notes))
    if scene_def.has_period:
        if measured["period_problem"]:
            raise DataError(measured["period_problem"])
        result.update(period=measured["period"], bump_time=measured["bump_time"])
    return result


def point_observables(directory, selection=Selection(), scene_def=None):
    """observables() of a point directory's outputs; a DataError names the point."""
    point = Point(directory)
    averaged_as = scene_def or SCENES.get(point.params["scene"])
    resolutions = ((selection.resolution,) if averaged_as and averaged_as.selects_steady_parts
                   else ())
    measured = measure(point, resolutions, selection)
    try:
        return observables(point.params, measured, point.stopped_at, selection, scene_def)
    except DataError as error:
        raise DataError(f"{directory}: {error}") from None
