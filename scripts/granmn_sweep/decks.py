"""What the runner reads from the scene decks (inputs/*.lmp, LIGGGHTS's inputs/liggghts/*.lmp,
and the inputs/lib/ files they include): the scenes, the variables a deck takes and those it
uses, its dimension, the atoms it makes, its time step's formula; the value of such a formula."""
import ast
import functools
import operator
import re
from pathlib import Path

from . import SweepError

ROOT = Path(__file__).resolve().parents[2]
LIB = ROOT / "inputs" / "lib"
# The engines a point runs in (its `engine`; lammps where it names none), and the folder of
# each one's scene decks, under inputs/: the event-driven engine takes its start and variables
# from LAMMPS's 2D decks (granmn_sweep/event_driven.py).
ENGINES = {"lammps": ".", "liggghts": "liggghts", "event_driven": "."}


def engine(point):
    return point.get("engine", "lammps")


def deck_path(scene, engine_name="lammps"):
    return ROOT / "inputs" / ENGINES[engine_name] / f"{scene}.lmp"


def point_deck(point):
    """The deck a point runs: its scene's, of its engine."""
    return deck_path(point["scene"], engine(point))


def where(deck):
    """A deck as the runner's messages name it (inputs/chute_3d.lmp)."""
    return str(deck.relative_to(ROOT)) if deck.is_relative_to(ROOT) else str(deck)


def scenes(engine_name="lammps"):
    """The scenes of an engine: its decks that name themselves (`variable scene index NAME`);
    of the event-driven engine, the 2D ones."""
    return tuple(sorted(deck.stem for deck in (ROOT / "inputs" / ENGINES[engine_name]).glob("*.lmp")
                        if re.search(r"^variable scene index (\w+)", deck.read_text(), re.M)
                        and (engine_name != "event_driven" or scene_dimension(deck) == 2)))


# Deck variables the runner sets itself for every point.
RESERVED = {"plugin", "lib", "out", "run_token", "resume", "resume_step", "write_start"}
# The operators of the decks' formulas that formula_value() reads; a comparison is 1 or 0.
ARITHMETIC = {ast.Add: operator.add, ast.Sub: operator.sub, ast.Mult: operator.mul,
              ast.Div: operator.truediv}
COMPARISONS = {ast.Lt: operator.lt, ast.LtE: operator.le, ast.Gt: operator.gt,
               ast.GtE: operator.ge, ast.Eq: operator.eq, ast.NotEq: operator.ne}


@functools.lru_cache(maxsize=None)
def deck_defaults(deck):
    """{name: default} of the variables a scene deck declares (`variable NAME index VALUE`, its
    own first, then the shared defaults), i.e. what -var can set."""
    defaults = {}
    for path in (deck, LIB / "defaults.lmp"):
        for name, value in re.findall(r"^variable (\w+) index (\S+)", path.read_text(), re.M):
            defaults.setdefault(name, value)
    return {name: value for name, value in defaults.items() if name not in RESERVED}


@functools.lru_cache(maxsize=None)
def scene_dimension(deck):
    """2, or 3 where the scene deck says `variable scene_dimension string 3`
    (inputs/lib/begin.lmp)."""
    found = re.search(r"^variable scene_dimension string (\d)", deck.read_text(), re.M)
    return int(found.group(1)) if found else 2


def deck_commands(path):
    """The commands of a LAMMPS input file and of the files it includes from ${lib}: comments
    dropped, continuation lines and triple-quoted strings joined into their command."""
    text = re.sub(r'""".*?"""', lambda m: m.group(0).replace("\n", " "), path.read_text(),
                  flags=re.S)
    text = "\n".join(re.match(r"""((?:[^#"']|"[^"]*"|'[^']*')*)""", line).group(1)
                     for line in text.splitlines())
    commands = []
    for command in re.sub(r"&[ \t]*\n", " ", text).splitlines():
        included = re.match(r"include \$\{lib\}/(\S+)", command.strip())
        commands += deck_commands(LIB / included.group(1)) if included else [command.strip()]
    return commands


@functools.lru_cache(maxsize=None)
def deck_uses(deck):
    """Names of the variables a scene deck's commands read, its checks (if ... quit), its
    declarations and its print-outs (params.txt) apart: a variable it takes but not among
    these changes nothing in the run."""
    uses = set()
    for command in deck_commands(deck):
        if re.match(r"(print\b|variable \w+ index\b)", command) or \
                (command.startswith("if ") and re.search(r"\bquit\b", command)):
            continue
        uses.update(a or b for a, b in re.findall(r"\$\{(\w+)\}|\bv_(\w+)", command))
    return uses


def equal_formula(commands, name, where):
    """The formula of `variable NAME equal FORMULA` (one such command among `commands`)."""
    found = [re.match(rf"variable {name} equal (.+)", command) for command in commands]
    found = [match.group(1).strip() for match in found if match]
    if len(found) != 1:
        raise SweepError(f"{where}: {len(found)} commands `variable {name} equal ...` (the "
                         "runner reads one)")
    return found[0][1:-1] if found[0][:1] == found[0][-1:] == '"' else found[0]


@functools.lru_cache(maxsize=None)
def time_step_formula(deck):
    """The formula of a scene deck's time step: of its one `timestep` command (in
    inputs/lib/time_step.lmp), the value, $(FORMULA), or ${NAME} of `variable NAME equal`."""
    commands = deck_commands(deck)
    steps = [command.split(None, 1)[1] for command in commands
             if command.startswith("timestep ")]
    if len(steps) != 1:
        raise SweepError(f"{where(deck)}: {len(steps)} timestep commands (the runner reads one)")
    named = re.fullmatch(r"\$\{(\w+)\}", steps[0])
    if named:
        return equal_formula(commands, named.group(1), where(deck))
    immediate = re.fullmatch(r"\$\((.+)\)", steps[0])
    return immediate.group(1) if immediate else steps[0]


@functools.lru_cache(maxsize=None)
def scene_atoms_formula(deck):
    """The formula of the atoms a scene deck makes, its `variable scene_atoms equal`."""
    return equal_formula(deck_commands(deck), "scene_atoms", where(deck))


def scene_atoms(point):
    """The atoms a point's scene makes (bumps and base included), of the point's variables and
    the deck's defaults: its deck's scene_atoms, which the deck checks against the atoms it has
    made (inputs/lib/dynamics.lmp)."""
    deck = point_deck(point)
    at = f"{where(deck)}: scene_atoms"
    values = {**deck_defaults(deck), **point}

    def value(name):
        try:
            return float(values[name])
        except (KeyError, ValueError):
            raise SweepError(f"{at}: v_{name} is no number a point sets or the deck defaults")
    return formula_value(scene_atoms_formula(deck), value, at)


def formula_value(formula, value, where):
    """The value of a deck's formula as LAMMPS computes it, in doubles: numbers, the variables
    v_NAME (value(NAME)), + - * /, a comparison (1 or 0), parentheses; anything else is
    refused, by name, rather than read otherwise than LAMMPS reads it."""
    def evaluate(node):
        if isinstance(node, ast.Constant) and type(node.value) in (int, float):
            return float(node.value)
        if isinstance(node, ast.Name) and node.id.startswith("v_"):
            return value(node.id[2:])
        if isinstance(node, ast.BinOp) and type(node.op) in ARITHMETIC:
            return ARITHMETIC[type(node.op)](evaluate(node.left), evaluate(node.right))
        if isinstance(node, ast.Compare) and len(node.ops) == 1 and \
                type(node.ops[0]) in COMPARISONS:
            return float(COMPARISONS[type(node.ops[0])](evaluate(node.left),
                                                        evaluate(node.comparators[0])))
        raise SweepError(f"{where}: the runner reads no {ast.unparse(node)!r} in the formula "
                         f"{formula!r} (it reads numbers, v_NAME, + - * /, a comparison, "
                         "parentheses)")
    try:
        tree = ast.parse(formula, mode="eval")
    except SyntaxError:
        raise SweepError(f"{where}: the runner cannot read the formula {formula!r}")
    return evaluate(tree.body)
