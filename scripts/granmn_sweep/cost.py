"""The cost model: a point's steps (the law's tau_c through build/plugin/mn-law; of an
event-driven point, its events) and its predicted CPU seconds on one core, rescaled as points
finish."""
import functools
import math

from . import SweepError
from .decks import deck_defaults, engine, formula_value, point_deck, scene_atoms, \
    scene_dimension, time_step_formula, where
from .mn_law import LawError, derived

# Seconds per step by the scene's dimension: a fixed part and a part per atom; refined as points
# finish. 3D: the dense chute's CPU seconds per atom-step, measured (docs/scenes.md): 9.9e-8 at
# kn 2e4, 6.2e-8 at 2e5, 5.6e-8 at 2e6 (the stiff points, where a series' time goes).
STEP_COST = {2: (4e-7, 4e-8), 3: (4e-7, 6e-8)}
# An event-driven point's events: no formula gives them (a flow's collision rate, and a collapse
# held off by the TC model, multiply them by orders of magnitude), so the guess is a rate per
# atom (bumps included) and time unit of the dilute collisional flow, and the learnt factor
# (kept per engine) corrects it as points finish; CPU seconds per event, measured from 50 to 1e5
# disks (bench/event_driven.py, docs/hard_spheres.md).
EVENTS_PER_ATOM_TIME = 1e2
EVENT_COST = 2e-6


@functools.lru_cache(maxsize=None)
def law(mn_law, kn, e, beta, shape):
    """The law's derived numbers, once per material and shape: a grid of many points has few,
    and each evaluation starts mn-law."""
    try:
        return derived(mn_law, kn, e, beta, shape)
    except LawError as error:
        raise SweepError(str(error))


def positive(point, name):
    """A variable of a point (the deck's default where the point sets none) that must be a
    number > 0 (expand() made sure it is a number; the deck checks the rest)."""
    value = point.get(name, deck_defaults(point_deck(point)).get(name))
    number = float(value)
    if not (number > 0 and math.isfinite(number)):
        raise SweepError(f"{point['scene']} point: {name} = {value!r} must be > 0")
    return number


def law_numbers(point, mn_law):
    """mn-law's numbers of a point's material, as pair_style gran/mn derives them in its scene:
    of discs in 2D, of spheres in 3D."""
    return law(mn_law, positive(point, "kn"), positive(point, "e"), positive(point, "beta"),
               "sphere" if scene_dimension(point_deck(point)) == 3 else "disc")


def time_step(point, mn_law):
    """A point's time step as its deck computes it (decks.time_step_formula): a formula of the
    point's variables and of the numbers pair_style gran/mn publishes (v_mn_tau_c: mn-law's
    tau_c)."""
    deck = point_deck(point)
    numbers = law_numbers(point, mn_law)

    def value(name):
        if not name.startswith("mn_") and name in {**deck_defaults(deck), **point}:
            return positive(point, name)
        if not name.startswith("mn_"):
            raise SweepError(f"{where(deck)}: its time step reads v_{name}, which is no "
                             "variable a point sets (-var) nor a number of pair_style gran/mn")
        if name[3:] not in numbers:
            raise SweepError(f"{where(deck)}: its time step reads v_{name}, which "
                             f"mn-law does not give ({', '.join(sorted(numbers))})")
        return numbers[name[3:]]
    return formula_value(time_step_formula(deck), value, f"{where(deck)}: timestep")


def predicted_steps(point, mn_law):
    """Steps of a point: run_time over its time step; of an event-driven point, its guessed
    events (EVENTS_PER_ATOM_TIME), at most its events cap."""
    if engine(point) == "event_driven":
        events = positive(point, "run_time") * scene_atoms(point) * EVENTS_PER_ATOM_TIME
        cap = float(point.get("events", 0))
        return math.ceil(min(events, cap) if cap > 0 else events)
    dt = time_step(point, mn_law)
    steps = positive(point, "run_time") / dt if dt > 0 else math.inf
    if not (math.isfinite(steps) and steps < 2 ** 62):
        raise SweepError(f"{point['scene']} point: kn = {point.get('kn')!r}, run_time = "
                         f"{point.get('run_time')!r} give no finite number of steps "
                         f"(tau_c = {law_numbers(point, mn_law)['tau_c']:g})")
    return math.ceil(steps)


class CostModel:
    """Seconds of a point = steps * (c0 + c1 * atoms) * factor (atoms: decks.scene_atoms), of an
    event-driven point events * EVENT_COST * factor; the factor, one per engine, learnt from
    the points run."""

    def __init__(self):
        self.factor, self.samples = {}, {}

    def predict(self, point, steps):
        factor = self.factor.get(engine(point), 1.0)
        if engine(point) == "event_driven":
            return steps * EVENT_COST * factor
        fixed, per_atom = STEP_COST[scene_dimension(point_deck(point))]
        return steps * (fixed + per_atom * scene_atoms(point)) * factor

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
