"""A sweep's runs, one record each, from either source: the raw outputs of a results
directory (<scene>/<point>/, docs/scenes.md) or the compact summaries that `python3 -m
postprocess summarize` writes of them (<scene>/<point>.json, docs/sweeps.md). The report,
compare and any later analysis start from load_runs; read_run is the one place that reads a
point directory (through an io.Point, which reads each file once)."""
import math
from pathlib import Path

from . import rundir
from .io import DataError, Point, checked_agreement
from .observables import RESOLUTIONS, measure, observables, relative
from .scenes import SCENES, scene
from .record import RunRecord, drawn_energy, run_name
from .selection import Selection
from .summary import read_summaries


def cpu_seconds(outputs):
    """What the run cost (timing.json), or None if it does not say."""
    try:
        return float(outputs.timing["cpu_seconds"])
    except (KeyError, TypeError, ValueError):
        return None


def read_run(point, resolutions=RESOLUTIONS, selection=Selection()):
    """The RunRecord of a point directory's outputs (observables not yet chosen): how it ended,
    its variables and params, and (completed runs) what its averages are made of, with the
    frictional selection's steady parts at each of `resolutions` (selection's min_length and
    max_width). Never raises for broken outputs: `reason` says what is wrong."""
    point = Path(point)
    outputs = Point(point)
    record = RunRecord(point=point, scene=point.parent.name, source="raw",
                       cpu_seconds=cpu_seconds(outputs), outputs=outputs)
    try:
        scene(record.scene)
    except KeyError as error:
        record.reason = error.args[0]
        return record
    ending, record.failure = outputs.ending
    if ending != "completed":
        record.ended = ending
        record.reason = rundir.incomplete_reason(ending, record.failure)
        try:
            record.variables = outputs.variables
        except DataError:
            pass        # the reason is the crash
        return record
    record.ended = "stopped" if (point / rundir.STOPPED).exists() else "flowing"
    try:
        record.variables = outputs.variables
        record.params = checked_agreement(record.variables, outputs.params,
                                          point / rundir.POINT, point / rundir.PARAMS)
        record.stopped_at = outputs.stopped_at
        record.energy = drawn_energy(outputs.energy)
    except DataError as error:
        record.reason = relative(error, point)
        return record
    record.measured = measure(outputs,
                              resolutions if SCENES[record.scene].selects_steady_parts else (),
                              selection)
    return record


def load_runs(source, selection=Selection()):
    """Every run of a sweep, as a sorted list of RunRecord, from a results directory
    (<scene>/<point>/ with point.json: the raw outputs) or from a directory of summaries
    (<scene>/<point>.json, `python3 -m postprocess summarize`); both give the same records
    but for `point`, `source` and the resolution of `energy`.

    Each record has `observables` (E_total, N_c, N_w, t_c, t_w, mc_c = t_c - N_c tau_c,
    mc_w = t_w - N_w tau_w, t_multiple, z, E_trans, E_rot, each with its block error
    <name>_err; kn, tau_c, tau_w, span, n_boundary, notes; single disk: period, bump_time)
    averaged as the report averages them, with `selection` for the frictional steady parts;
    or `reason` says why it has none (did not complete, crashed, no steady part kept, ...).
    `ended` says how it ended, `variables` and `params` what it was. From summaries the
    selection's resolution must be one of observables.RESOLUTIONS and its min_length and
    max_width those the summaries were written with (they hold the steady parts found so).
    A list of directories is read as one sweep: their records sorted as one directory's, each
    run once (distinct_runs)."""
    if isinstance(source, (list, tuple)):
        return distinct_runs(sorted((r for one in source for r in load_runs(one, selection)),
                                    key=lambda r: (r.point.parent.name, r.point.name)))
    source = Path(source)
    if not source.is_dir():
        raise DataError(f"{source}: no such sweep directory")
    points = sorted(p for p in source.glob("*/*") if (p / rundir.POINT).exists())
    if points:
        resolutions = sorted(set(RESOLUTIONS) | {selection.resolution})
        records = [read_run(p, resolutions, selection) for p in points]
    else:
        records = read_summaries(source, selection)
    for record in records:
        if record.reason is None:
            try:
                record.observables = observables(record.params, record.measured,
                                                 record.stopped_at, selection)
            except DataError as error:
                record.reason = str(error)
    return records


# what two records of one run name must share to be the same run, counted once
SAME_RUN = ("ended", "stopped_at", "failure", "variables", "params", "reason", "observables")


def same_value(a, b):
    """a == b, nan equal to nan (a run's observables hold nan where it has no period)."""
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(same_value(a[k], b[k]) for k in a)
    if isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b):
        return True
    return a == b


def distinct_runs(records):
    """records (sorted by run_name) with each run once: several records of one run name (a
    directory given twice, or a results directory and its own summaries) that agree in every
    one of SAME_RUN are one run, kept once (the raw outputs' record if there is one, else the
    first), the others in its `copies`; records of one name that differ are two different runs
    claiming one name (a rerun, a run on other ranks), and a DataError names them and what
    differs: which one to count is the user's choice. Unreadable summaries are left as they
    are (nothing says which run they are)."""
    out, where = [], {}      # where: run name -> the index of its record in out
    for record in records:
        name = run_name(record)
        if record.ended == "unreadable":
            out.append(record)
            continue
        if name not in where:
            where[name] = len(out)
            out.append(record)
            continue
        kept = out[where[name]]
        differ = [n for n in SAME_RUN if not same_value(getattr(kept, n), getattr(record, n))]
        if differ:
            raise DataError(f"{kept.point} and {record.point} are both the run {name}, but "
                            f"their {', '.join(differ)} differ: two different runs under one "
                            "name (analyse them apart)")
        if record.source == "raw" and kept.source != "raw":
            record.copies, kept.copies = kept.copies + [kept.point], []
            out[where[name]] = record
        else:
            kept.copies.append(record.point)
    return out
