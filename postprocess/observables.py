"""Observables of one point (docs/model.md section 6) from its outputs, with block-average errors."""
from dataclasses import replace

import numpy as np

from .io import DataError, read_counts, read_energy, read_params, read_stopped
from .scenes import scene
from .selection import Selection, select_at_resolution

# The time resolutions (time units) at which the report counts the steady parts kept, so that
# the reader sees what the choice of resolution does (docs/model.md section 5).
RESOLUTIONS = (0.1, 1.0, 5.0)
# A run has come to rest when its kinetic energy per disk stays below REST_ENERGY over its last
# REST_TIME time units (the frictional deck's stop_energy and stop_time).
REST_ENERGY, REST_TIME = 1e-5, 10.0

COUNTERS = ("begun_disk", "begun_boundary", "time_disk", "time_boundary", "time_multiple")


def bottom_layer(counts):
    """Disks that touched the boundary during the window (frictional flow normalisation)."""
    return int(np.count_nonzero((counts["begun_boundary"] > 0) | (counts["time_boundary"] > 0)))


def span_rates(energy, spans, n_particles, n_boundary):
    """Collision rates and contact-time fractions over a union of spans of energy.txt, from the
    increments of the cumulative counter sums (all spans inside one counter window)."""
    length = sum(energy["time"][b - 1] - energy["time"][a] for a, b in spans)
    if length <= 0:
        raise DataError("the selected spans have no length")
    delta = {k: sum(energy[k][b - 1] - energy[k][a] for a, b in spans) for k in COUNTERS}
    return {
        "N_c": delta["begun_disk"] / (n_particles * length),
        "N_w": delta["begun_boundary"] / (n_boundary * length),
        "t_c": delta["time_disk"] / (n_particles * length),
        "t_w": delta["time_boundary"] / (n_boundary * length),
        "t_multiple": delta["time_multiple"] / (n_particles * length),
    }


def with_errors(blocks):
    """Mean over blocks and its standard error, per observable."""
    result = {}
    for key in blocks[0]:
        values = np.array([b[key] for b in blocks])
        result[key] = values.mean()
        result[key + "_err"] = values.std(ddof=1) / np.sqrt(len(values)) if len(values) > 1 else np.nan
    return result


def averaging_rows(energy, params):
    """Rows of energy.txt in the counter window that restarts at average_start (the row written
    at that very step still holds the sums from before the restart)."""
    slack = 1e-9 * params["run_time"]
    return ((energy["time"] >= params["average_start"] - slack) &
            (energy["window"] <= energy["time"] - params["average_start"] + slack))


def kept_spans(point, selection, resolutions=RESOLUTIONS):
    """{resolution: number of steady parts the selection, at that time resolution, keeps} over
    a run's averaging span."""
    params = read_params(point)
    energy = read_energy(point, params)
    inside = averaging_rows(energy, params)
    return {r: len(select_at_resolution(energy["time"][inside], energy["e_total"][inside],
                                        replace(selection, resolution=r))[0])
            for r in resolutions}


def rest_time(t, energy):
    """The time from which the energy stays below REST_ENERGY to the end of the series, if it
    does so for at least REST_TIME; else None."""
    above = np.flatnonzero(np.asarray(energy) >= REST_ENERGY)
    first_at_rest = above[-1] + 1 if len(above) else 0
    if first_at_rest >= len(t) or t[-1] - t[first_at_rest] < REST_TIME:
        return None
    return t[first_at_rest]


def run_state(point):
    """How a completed run ended: ('flowing', None) if it went on to run_time, ('stopped', t) if
    its pile stopped at time t and the run ended early (inputs/lib/stop.lmp)."""
    stopped_at = read_stopped(point)
    return ("flowing", None) if stopped_at is None else ("stopped", stopped_at)


def contacts_per_disk(contacts_now, n_disks):
    """Mean number of contacts a disk has, boundary contacts included (docs/model.md section
    6), from samples of the sum over the disks of their current contacts: a disk-disk contact
    is in the sum twice, once for each disk, a boundary contact once."""
    return float(np.mean(contacts_now)) / n_disks


def point_observables(point, n_blocks=5, selection=Selection(), what=None):
    """E, N_c, N_w, t_c, t_w, the multiple-contact estimates, the direct fraction of time
    with two or more contacts and the contacts per disk, averaged over the point's averaging
    window (or, where the scene selects steady parts, over the parts the selection keeps), each
    with a block-average error. `what`: the Scene to average as (default: the point's own)."""
    params = read_params(point)
    energy = read_energy(point, params)
    counts = read_counts(point)
    state, stopped_at = run_state(point)
    end = params["run_time"] if stopped_at is None else stopped_at
    n = params["n_mobile"]
    if len(counts["id"]) != n:
        raise DataError(f"{point}/counts.txt: {len(counts['id'])} disks, params.txt says {n:g}")
    inside = averaging_rows(energy, params)
    first = int(np.argmax(inside))
    if stopped_at is not None and stopped_at <= params["average_start"]:
        raise DataError(f"{point}: the pile stopped at t = {stopped_at:g}, before the "
                        f"averaging span (average_start {params['average_start']:g})")
    if not inside.any():
        raise DataError(f"{point}/energy.txt: no samples after average_start "
                        f"{params['average_start']:g}: the run did not reach its averaging span")
    if energy["time"][-1] < end - 1.5 * (energy["time"][1] - energy["time"][0]):
        raise DataError(f"{point}/energy.txt: ends at t = {energy['time'][-1]:g}, before "
                        f"{'its stop' if stopped_at is not None else 'run_time'} {end:g}: "
                        "truncated?")

    n_boundary = n
    notes = [f"stopped at t = {stopped_at:g}"] if stopped_at is not None else []
    try:
        what = what or scene(params["scene"])
    except KeyError as error:
        raise DataError(f"{point}/params.txt: {error.args[0]}")
    if what.boundary_per_bottom_layer:
        n_boundary = bottom_layer(counts)
    if what.selects_steady_parts:
        kept, found = select_at_resolution(energy["time"][first:], energy["e_total"][first:],
                                           selection)
        spans = [(a + first, b + first) for a, b in kept]
        if not spans:
            means = ", ".join(f"{energy['e_total'][a + first:b + first].mean():.3g}"
                              for a, b in found)
            low, high = selection.energy_range
            raise DataError(f"{point}: no steady part with mean energy in [{low:g}, {high:g}] "
                            f"at resolution {selection.resolution:g} ({len(found)} steady parts "
                            f"found"
                            f"{', mean E ' + means if found else ''}; "
                            f"{notes[0] if notes else 'flowing to the end'})")
        notes.append(f"{len(spans)} of {len(found)} steady parts selected")
    else:
        spans = [(first, len(energy["time"]))]
        resting = rest_time(energy["time"], energy["e_total"])
        if resting is not None:
            raise DataError(f"{point}: came to rest at t = {resting:.4g} (E per disk below "
                            f"{REST_ENERGY:g} from then on): no steady motion to average")
    if n_boundary == 0:
        raise DataError(f"{point}: no disk touched the boundary in the averaging window")

    # blocks: each span cut into pieces, observables per piece
    blocks = []
    for a, b in spans:
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
            blocks.append(block)
    if len(blocks) < 2:
        raise DataError(f"{point}: the averaging span is too short for error bars")
    result = with_errors(blocks)
    result.update(kn=params["kn"], tau_c=params["tau_c"], tau_w=params["tau_w"],
                  scene=params["scene"], n_boundary=n_boundary,
                  span=sum(energy["time"][b - 1] - energy["time"][a] for a, b in spans),
                  notes="; ".join(notes))
    return result
