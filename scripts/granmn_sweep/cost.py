"""The cost model: a point's steps (the law's tau_c through build/plugin/mn-law) and its
predicted CPU seconds on one core, rescaled as points finish."""
import functools
import math

from granmn_sweep import SweepError
from granmn_sweep.decks import deck_defaults, scene_dimension
from mn_law import LawError, derived

# Atoms each scene integrates or pairs with: the cost model's size (bumps included); where the
# size is a deck variable, a function of the point's variables (the deck's defaults filled in).
SCENE_ATOMS = {"single_disk": 11, "collisional_flow": 100, "frictional_flow": 100,
               "chute_3d": lambda v: (int(float(v["spheres"]))
                                      + int(float(v["length"])) * int(float(v["width"])))}
# Seconds per step by the scene's dimension: a fixed part and a part per atom; refined as points
# finish. 3D: the dense chute's CPU seconds per atom-step, measured (docs/scenes.md): 9.9e-8 at
# kn 2e4, 6.2e-8 at 2e5, 5.6e-8 at 2e6 (the stiff points, where a series' time goes).
STEP_COST = {2: (4e-7, 4e-8), 3: (4e-7, 6e-8)}


def scene_atoms(point):
    """The cost model's size of a point: SCENE_ATOMS of its scene."""
    atoms = SCENE_ATOMS[point["scene"]]
    return atoms({**deck_defaults(point["scene"]), **point}) if callable(atoms) else atoms


@functools.lru_cache(maxsize=None)
def law(mn_law, kn, e, beta):
    """The law's derived numbers, once per material: a grid of many points has few, and each
    evaluation starts mn-law."""
    try:
        return derived(mn_law, kn, e, beta)
    except LawError as error:
        raise SweepError(str(error))


def predicted_steps(point, mn_law):
    """Steps of a point; the values it needs must be numbers > 0 (the deck checks the rest)."""
    def get(name):
        value = point.get(name, deck_defaults(point["scene"]).get(name))
        number = float(value)    # expand() made sure it is one
        if not (number > 0 and math.isfinite(number)):
            raise SweepError(f"{point['scene']} point: {name} = {value!r} must be > 0")
        return number
    tau_c = law(mn_law, get("kn"), get("e"), get("beta"))["tau_c"]
    dt = min(get("dt_fraction") * tau_c, get("dt_cap"))
    steps = get("run_time") / dt if dt > 0 else math.inf
    if not (math.isfinite(steps) and steps < 2 ** 62):
        raise SweepError(f"{point['scene']} point: kn = {point.get('kn')!r}, run_time = "
                         f"{point.get('run_time')!r} give no finite number of steps "
                         f"(tau_c = {tau_c:g})")
    return math.ceil(steps)


class CostModel:
    """Seconds of a point = steps * (c0 + c1 * atoms) * factor; factor learnt from points run."""

    def __init__(self):
        self.factor, self.samples = 1.0, 0

    def predict(self, point, steps):
        fixed, per_atom = STEP_COST[scene_dimension(point["scene"])]
        return steps * (fixed + per_atom * scene_atoms(point)) * self.factor

    def learn(self, predicted, measured):
        ratio = measured / max(predicted, 1e-9)
        self.samples += 1
        self.factor += (ratio * self.factor - self.factor) / self.samples


def format_seconds(seconds):
    seconds = int(round(seconds))
    return f"{seconds // 3600}h{seconds // 60 % 60:02d}m" if seconds >= 3600 else \
        f"{seconds // 60}m{seconds % 60:02d}s"
