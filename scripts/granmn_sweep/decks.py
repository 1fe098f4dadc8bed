"""What the runner reads from the scene decks (inputs/*.lmp and the inputs/lib/ files they
include): the scenes, the variables a deck takes and those it uses, its dimension."""
import functools
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
LIB = ROOT / "inputs" / "lib"
# The scenes are the decks that name themselves (`variable scene index NAME`).
SCENES = tuple(sorted(deck.stem for deck in (ROOT / "inputs").glob("*.lmp")
                      if re.search(r"^variable scene index (\w+)", deck.read_text(), re.M)))
# Deck variables the runner sets itself for every point.
RESERVED = {"plugin", "lib", "out", "run_token", "resume", "resume_step"}


@functools.lru_cache(maxsize=None)
def deck_defaults(scene):
    """{name: default} of the variables a scene deck declares (`variable NAME index VALUE`, its
    own first, then the shared defaults), i.e. what -var can set."""
    defaults = {}
    for deck in (ROOT / "inputs" / f"{scene}.lmp", LIB / "defaults.lmp"):
        for name, value in re.findall(r"^variable (\w+) index (\S+)", deck.read_text(), re.M):
            defaults.setdefault(name, value)
    return {name: value for name, value in defaults.items() if name not in RESERVED}


@functools.lru_cache(maxsize=None)
def scene_dimension(scene):
    """2, or 3 where the scene deck says `variable scene_dimension string 3`
    (inputs/lib/begin.lmp)."""
    found = re.search(r"^variable scene_dimension string (\d)", (ROOT / "inputs" / f"{scene}.lmp")
                      .read_text(), re.M)
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
def deck_uses(scene):
    """Names of the variables a scene deck's commands read, its checks (if ... quit), its
    declarations and its print-outs (params.txt) apart: a variable it takes but not among
    these changes nothing in the run."""
    uses = set()
    for command in deck_commands(ROOT / "inputs" / f"{scene}.lmp"):
        if re.match(r"(print\b|variable \w+ index\b)", command) or \
                (command.startswith("if ") and re.search(r"\bquit\b", command)):
            continue
        uses.update(a or b for a, b in re.findall(r"\$\{(\w+)\}|\bv_(\w+)", command))
    return uses

