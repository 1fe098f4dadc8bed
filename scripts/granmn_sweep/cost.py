"""The cost model: a point's size as its deck says it (its steps and atoms; of an event-driven
point, its guessed events) and its predicted CPU seconds on one core, rescaled as points
finish."""
import concurrent.futures
import math
from typing import NamedTuple

from . import SweepError, event_driven
from .config import deck_variables
from .decks import dry_run, engine, point_deck, scene_dimension
from postprocess.rundir import run_name

# Seconds per step by the scene's dimension: a fixed part and a part per atom; refined as points
# finish. 2D: the frictional flow's, measured at its widths (the committed summaries of the
# paper preset and the finite-size check): 3.4e-6 at 100 disks, 4.1e-6 at 200, 8.2e-6 at 400.
# 3D: the dense chute's CPU seconds per atom-step, measured (docs/scenes.md): 9.9e-8 at
# kn 2e4, 6.2e-8 at 2e5, 5.6e-8 at 2e6 (the stiff points, where a series' time goes).
STEP_COST = {2: (1.5e-6, 1.5e-8), 3: (4e-7, 6e-8)}
# An event-driven point's events: no formula gives them (a flow's collision rate, and a collapse
# held off by the TC model, multiply them by orders of magnitude), so the guess is a rate per
# atom (bumps included) and time unit by scene: the dense frictional flow's under the TC model
# at t_c = tau_c (from 6e3 at k_n 1.6e6 to 4e4 at 2.56e7 in its runs of docs/hard_spheres.md),
# elsewhere the dilute collisional flow's; the learnt factor (kept per engine) corrects it as
# points finish; CPU seconds per event, measured from 50 to 1e5 disks (bench/event_driven.py).
EVENTS_PER_ATOM_TIME = {"frictional_flow": 1e4}
DILUTE_EVENTS_PER_ATOM_TIME = 1e2
EVENT_COST = 2e-6
# The variable that draws a start's sizes and heights in the decks: it changes neither how many
# atoms a deck makes nor its law, so the points that differ in it alone take one dry run
# (tests/lammps/test_sweep.py holds each scene to it)
START_DRAW = "seed"


class Size(NamedTuple):
    """A point's size: its steps (of an event-driven point, its events) and its atoms."""
    steps: int
    atoms: int


def deck_question(point, paths):
    """(executable, deck, variables) of a point's dry run: its engine's, of its scene; an
    event-driven point's start is made by its LAMMPS deck, which takes the point's variables but
    the engine's own."""
    variables = deck_variables(point, paths["plugin"])
    if engine(point) == "event_driven":
        variables = {name: value for name, value in variables.items()
                     if name not in event_driven.VARIABLES}
    executable = paths["lammps" if engine(point) == "event_driven" else engine(point)]
    return executable, point_deck(point), variables


def ask_deck(point, paths):
    """What a point's deck answers to -var dry_run yes (decks.dry_run: dt, atoms, tau_c,
    run_time)."""
    return dry_run(*deck_question(point, paths), run_name(point))


def events_per_atom_time(point):
    """The guessed events per atom and time unit of an event-driven point's scene."""
    return EVENTS_PER_ATOM_TIME.get(point["scene"], DILUTE_EVENTS_PER_ATOM_TIME)


def predicted_steps(point, answer):
    """Steps of a point: run_time over the time step its deck answered; of an event-driven
    point, its guessed events (events_per_atom_time), at most its events cap."""
    if engine(point) == "event_driven":
        events = answer["run_time"] * answer["atoms"] * events_per_atom_time(point)
        cap = float(point.get("events", 0))
        return math.ceil(min(events, cap) if cap > 0 else events)
    dt = answer["dt"]
    steps = answer["run_time"] / dt if dt > 0 else math.inf
    if not (math.isfinite(steps) and steps < 2 ** 62):
        raise SweepError(f"{run_name(point)}: run_time = "
                         f"{answer['run_time']:g} over its time step dt = {dt:g} (tau_c = "
                         f"{answer['tau_c']:g}) gives no finite number of steps")
    return math.ceil(steps)


def point_sizes(points, paths, jobs):
    """[Size] of the points, each from its deck's dry run (ask_deck): one dry run for the points
    that differ in START_DRAW alone, `jobs` at a time."""
    def key(point):
        executable, deck, variables = deck_question(point, paths)
        return executable, deck, tuple(sorted((name, value) for name, value in
                                              variables.items() if name != START_DRAW))
    asked = {}
    for point in points:
        asked.setdefault(key(point), point)
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, jobs)) as pool:
        answers = dict(zip(asked, pool.map(lambda point: ask_deck(point, paths),
                                           asked.values())))
    return [Size(predicted_steps(point, answers[key(point)]), int(answers[key(point)]["atoms"]))
            for point in points]


class CostModel:
    """Seconds of a point of Size `size` = steps * (c0 + c1 * atoms) * factor, of an
    event-driven point events * EVENT_COST * factor; the factor, one per engine, learnt from
    the points run."""

    def __init__(self):
        self.factor, self.samples = {}, {}

    def predict(self, point, size):
        factor = self.factor.get(engine(point), 1.0)
        if engine(point) == "event_driven":
            return size.steps * EVENT_COST * factor
        fixed, per_atom = STEP_COST[scene_dimension(point_deck(point))]
        return size.steps * (fixed + per_atom * size.atoms) * factor

    def learn(self, point, predicted, measured):
        name = engine(point)
        ratio = measured / max(predicted, 1e-9)
        factor = self.factor.get(name, 1.0)
        self.samples[name] = self.samples.get(name, 0) + 1
        self.factor[name] = factor + (ratio * factor - factor) / self.samples[name]


def format_seconds(seconds):
    seconds = int(round(seconds))
    return f"{seconds // 3600}h{seconds // 60 % 60:02d}m" if seconds >= 3600 else \
        f"{seconds // 60}m{seconds % 60:02d}s"
