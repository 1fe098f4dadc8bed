"""What the runner reads from the scene decks (inputs/*.lmp, LIGGGHTS's inputs/liggghts/*.lmp,
and the inputs/lib/ files they include): the scenes, the variables a deck takes and those it
uses, its dimension; and what a deck answers when asked (dry_run: its time step and atoms)."""
import functools
import re
import subprocess
import tempfile
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
RESERVED = {"plugin", "lib", "out", "run_token", "resume", "resume_step", "write_start",
            "dry_run"}
# The line a deck prints under -var dry_run yes (inputs/lib/time_step.lmp), NAME VALUE pairs
# after it
DRY_RUN = "granmn dry run:"


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


def dry_run(executable, deck, variables, what):
    """{name: value} a deck prints under -var dry_run yes (inputs/lib/time_step.lmp: dt, atoms,
    tau_c, run_time), as `executable` (lmp, or LIGGGHTS) makes them of `variables` ({name: value
    as the deck gets it}): it runs the deck in a directory of its own, where the deck ends
    before anything has run or is written. The line decides, not the exit status: LIGGGHTS 3.8
    ends every `quit` with status 1. Refused, naming `what` (the point) and the deck's ERROR
    line: a point the deck refuses."""
    with tempfile.TemporaryDirectory(prefix="granmn-dry-run-") as directory:
        command = [str(executable), "-in", str(deck), "-log", "none", "-nocite"]
        for name, value in {**variables, "out": directory, "dry_run": "yes"}.items():
            command += ["-var", name, str(value)]
        try:
            ran = subprocess.run(command, cwd=directory, stdin=subprocess.DEVNULL,
                                 capture_output=True, text=True, errors="replace")
        except OSError as error:
            raise SweepError(f"{what}: {executable} cannot be run: {error.strerror}")
    lines = (ran.stdout + ran.stderr).splitlines()
    for line in lines:
        if line.startswith(DRY_RUN):
            words = line[len(DRY_RUN):].split()
            return {name: float(value) for name, value in zip(words[::2], words[1::2])}
    errors = [line for line in lines if line.startswith("ERROR")]
    said = errors[0] if errors else \
        f"no ERROR line (exit status {ran.returncode}; it ended with: {' | '.join(lines[-3:])})"
    raise SweepError(f"{what}: {where(deck)} refuses it in its dry run (-var dry_run yes): "
                     f"{said}")
