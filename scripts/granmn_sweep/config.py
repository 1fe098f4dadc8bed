"""A config's points: loading a TOML config, expanding its grids into points (checked against
the scene decks), one spelling of each number."""
import math
import re
import tomllib
from itertools import product
from pathlib import Path

from . import SweepError, event_driven
from .decks import ENGINES, LIB, RESERVED, deck_defaults, deck_uses, engine, point_deck, \
    scenes, where
from postprocess.rundir import format_value, point_name, run_name

NAME = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")
# The keys of a point that the runner reads itself, not a deck: which deck (the scene, of the
# engine) runs it. Both are part of the point's name.
RUNNER_KEYS = {"scene", "engine"}


def deck_variables(point, plugin):
    """The variables a point's deck gets, each as format_value spells it: the point's own (its
    scene and engine apart), and from the runner the plugin and the decks' library; a run adds
    its own (out, run_token, a resume's)."""
    variables = {name: value for name, value in point.items() if name not in RUNNER_KEYS}
    variables.update(plugin=plugin, lib=LIB)
    return {name: format_value(value) for name, value in variables.items()}


def load_config(path):
    try:
        config = tomllib.loads(Path(path).read_text())
    except FileNotFoundError:
        raise SweepError(f"{path}: no such config file")
    except tomllib.TOMLDecodeError as error:
        raise SweepError(f"{path}: not valid TOML: {error}")
    unknown = set(config) - {"name", "defaults", "grid"}
    if unknown:
        raise SweepError(f"{path}: unknown top-level keys {sorted(unknown)} "
                         "(expected name, defaults, grid)")
    if not isinstance(config.get("name", ""), str) or not NAME.match(config.get("name", "x")):
        raise SweepError(f"{path}: name = {config['name']!r} must be a word (letters, digits, _)")
    if not isinstance(config.get("grid"), list) or not config["grid"]:
        raise SweepError(f"{path}: needs at least one [[grid]] table")
    if not all(isinstance(grid, dict) for grid in config["grid"]):
        raise SweepError(f"{path}: grid must be a list of tables ([[grid]]), not "
                         f"{config['grid']!r}")
    if not isinstance(config.get("defaults", {}), dict):
        raise SweepError(f"{path}: [defaults] must be a table")
    return config


def with_settings(config, settings, path):
    """The config with each --set NAME=VALUE in its [defaults], replacing the file's value (the
    same sweep at another setting of one variable), and under "set" {NAME: the --set that gave
    it}, for expand's messages. Refused: a NAME the runner sets itself, a NAME set twice (which
    value was meant cannot be told), a NAME a grid sets itself (the grid's value would win, so
    the --set would be silently void there)."""
    defaults = dict(config.get("defaults", {}))
    given = {}
    for setting in settings:
        name, equals, value = setting.partition("=")
        if not equals or not value or not NAME.match(name):
            raise SweepError(f"--set {setting}: expected NAME=VALUE, NAME a deck variable")
        if name in RESERVED:
            raise SweepError(f"--set {setting}: {name} is set by the sweep runner itself "
                             "(--output, --build), not by --set")
        if name in given:
            raise SweepError(f"--set {setting}: {name} is set twice (--set {given[name]} "
                             "too): which value is meant cannot be told")
        for number, grid in enumerate(config["grid"], 1):
            if name in grid:
                raise SweepError(f"--set {setting}: grid {number} of {path} sets {name} itself")
        defaults[name] = value
        given[name] = setting
    return dict(config, defaults=defaults, set=given)


def expand(config, path):
    """The points of the config: dicts of deck variables, each with a scene. A refusal names
    where the variable was set: the config's grid, or the --set of with_settings."""
    points = []
    for number, grid in enumerate(config["grid"], 1):
        merged = dict(config.get("defaults", {}))
        merged.update(grid)

        def source(name, number=number):
            given = config.get("set", {})
            return f"--set {given[name]}" if name in given else f"{path}: grid {number}"
        for key, value in merged.items():
            if not NAME.match(key):
                raise SweepError(f"{path}: grid {number}: '{key}' is not a deck variable name")
            values = value if isinstance(value, list) else [value]
            if not values:
                raise SweepError(f"{path}: grid {number}: '{key}' is an empty list")
            for v in values:
                if not isinstance(v, (int, float, str)) or isinstance(v, bool):
                    raise SweepError(f"{path}: grid {number}: '{key}' must hold numbers or "
                                     f"strings, not {v!r}")
                if isinstance(v, float) and not math.isfinite(v):
                    raise SweepError(f"{source(key)}: {key} = {v!r} is not a finite number")
        if "scene" not in merged:
            raise SweepError(f"{path}: grid {number} has no scene")
        reserved = sorted(set(merged) & RESERVED)
        if reserved:
            raise SweepError(f"{path}: grid {number}: {', '.join(reserved)} set by the sweep "
                             "runner itself (--output, --build), not by a config")
        keys = sorted(merged)
        lists = [merged[k] if isinstance(merged[k], list) else [merged[k]] for k in keys]
        for combination in product(*lists):
            point = dict(zip(keys, combination))
            if engine(point) not in ENGINES:
                raise SweepError(f"{path}: grid {number}: unknown engine '{engine(point)}' "
                                 f"(expected one of {', '.join(ENGINES)})")
            if point["scene"] not in scenes(engine(point)):
                raise SweepError(f"{path}: grid {number}: unknown scene '{point['scene']}' of "
                                 f"engine {engine(point)} (expected one of "
                                 f"{', '.join(scenes(engine(point)))})")
            deck = point_deck(point)
            defaults = deck_defaults(deck)
            hard = engine(point) == "event_driven"
            known = set(defaults) | (set(event_driven.VARIABLES) if hard else set())
            unknown = sorted(set(point) - RUNNER_KEYS - known)
            if unknown:
                raise SweepError(f"{source(unknown[0])}: {', '.join(unknown)}: not a variable "
                                 f"of {where(deck)} (docs/scenes.md lists them)")
            # a deck takes a word where it expects a number without complaint (as 0)
            for name, value in point.items():
                if name in defaults and is_number(defaults[name]):
                    if not is_number(value):
                        raise SweepError(f"{source(name)}: {point['scene']} point: {name} = "
                                         f"{value!r} is not a number")
                    if not math.isfinite(float(value)):
                        raise SweepError(f"{source(name)}: {point['scene']} point: {name} = "
                                         f"{value!r} is not a finite number")
                    point[name] = canonical_number(value)
            uses = event_driven.deck_uses(deck_uses(deck)) if hard else deck_uses(deck)
            ignored = sorted(set(point) - RUNNER_KEYS - uses)
            if ignored:
                raise SweepError(f"{source(ignored[0])}: {', '.join(ignored)}: "
                                 f"{'the event-driven engine' if hard else where(deck)} does "
                                 "not use it (every value would give the same run)")
            points.append(point)
    seen = set()
    for p in points:
        if not point_name(p):
            raise SweepError(f"{path}: a point of scene {p['scene']} with no variable but the "
                             "scene: a point's directory is named by its variables, and this one "
                             f"would be <output>/{p['scene']}, where the scene's points are; set "
                             "one (e.g. seed or kn)")
        name = run_name(p)
        if name in seen:
            raise SweepError(f"{path}: the grids repeat the point {name} (equal numbers are one "
                             "value, however spelt)")
        seen.add(name)
    return points


def canonical_number(value):
    """One value, one spelling: seed 1 and "01" are 1; kn 5e4, 50000 and "5e4" are 50000."""
    number = float(value)
    return int(number) if number.is_integer() and abs(number) < 2 ** 53 else number


def is_number(value):
    try:
        float(value)
        return True
    except (TypeError, ValueError):
        return False
