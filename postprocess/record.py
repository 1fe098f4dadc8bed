"""The record of one run of a sweep (RunRecord), whichever source it was read from: a point
directory's raw outputs (runs.read_run) or its summary (summary.read_summary); what the loaders
(runs.load_runs) return and the analyses start from."""
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .io import Point
from .selection import in_energy_range, window_means


# How a run ended: completed (rundir.completed) and ran to run_time, completed and its pile
# stopped and the run ended early (stopped.txt), lmp failed (the sweep runner's failed.txt), not
# completed (still running, or killed: rundir), or (a summary only) the summary itself could not
# be read.
ENDINGS = ("flowing", "stopped", "failed", "incomplete", "unreadable")


# The window (time units) over which a record's E(t) is averaged for drawing (energy), unless
# energy.txt's lines are further apart.
DRAWN_WINDOW = 1.0


@dataclass
class RunRecord:
    """One run of a sweep.

    point        its directory (raw) or its summary file
    scene        the scene directory it is in
    source       "raw" or "summary"
    ended        one of ENDINGS
    stopped_at   the time its pile stopped (ended "stopped"), else None
    failure      (ended "failed") the exit status and lmp's last ERROR line
    variables    point.json: the deck variables the sweep set (kn, seed, integrator, ...)
    params       params.txt: every value the deck derived (tau_c, dt, n_mobile, ...)
    measured     observables.measure's result: what its averages are made of
    energy       {"window", "t0", "E"}: E(t) per disk averaged over consecutive windows from
                 the first sample t0, window k starting at t0 + k window (window: DRAWN_WINDOW
                 or, if larger, the largest time between two lines of energy.txt, so that no
                 window is empty); E to 4 significant digits: for drawing
    cpu_seconds  what the run cost (timing.json), if known
    reason       why it has no observables (a DataError's text), else None
    observables  (load_runs) observables.observables' result with load_runs' selection
    outputs      (raw) its io.Point: the files read so far, and the others when asked for
    copies       (load_runs of several directories) the other files of this same run, which
                 another directory given holds too: counted once, as this record"""
    point: Path
    scene: str
    source: str
    ended: str = "incomplete"
    stopped_at: float = None
    failure: str = None
    variables: dict = None
    params: dict = None
    measured: dict = None
    energy: dict = None
    cpu_seconds: float = None
    reason: str = None
    observables: dict = None
    outputs: Point = field(default=None, compare=False, repr=False)
    copies: list = field(default_factory=list)

    def kept(self, selection, resolutions):
        """{resolution: steady parts the selection keeps at it} (frictional runs)."""
        return {r: sum(in_energy_range(p["mean"], selection)
                       for p in self.measured["steady"][r]) for r in resolutions}


def drawn_energy(energy):
    """energy.txt's E(t) per disk as RunRecord.energy keeps it."""
    t = energy["time"]
    window = max(DRAWN_WINDOW, float(np.max(np.diff(t))))
    _, e, _ = window_means(t, energy["e_total"], window)
    return {"window": window, "t0": float(t[0]), "E": [float(f"{v:.4g}") for v in e]}


def energy_curve(record):
    """(t, E per disk) of a completed run: every sample of energy.txt (raw), or the means over
    the windows of RunRecord.energy at their start times (summary)."""
    if record.source == "raw":
        return record.outputs.energy["time"], record.outputs.energy["e_total"]
    drawn = record.energy
    return drawn["t0"] + drawn["window"] * np.arange(len(drawn["E"])), np.array(drawn["E"])


def run_name(record):
    """What a run is called, whatever holds it: its scene and point, <scene>/<point> (a
    point directory <scene>/<point>/ or its summary <scene>/<point>.json), the name reading
    checked against its variables' (rundir.run_name; a run whose variables could not be read
    has this name alone)."""
    return f"{record.scene}/{record.point.stem if record.source == 'summary' else record.point.name}"
