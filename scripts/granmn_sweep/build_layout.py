"""Where a build directory keeps what the project runs (CMakeLists.txt makes it; build.sh makes
build/ for Debian 12's LAMMPS, build-2025/ and build-2026/ for the others, scripts/
lammps-generation.sh): the one place the Python side names those paths. Imports no module of
the runner."""
from pathlib import Path
from typing import NamedTuple

DEFAULT = Path(__file__).resolve().parents[2] / "build"


class Build(NamedTuple):
    directory: Path
    lammps: Path             # lmp
    plugin: Path             # granmnplugin.so
    mn_law: Path             # the law's derived numbers (mn-law)
    liggghts: Path           # LIGGGHTS with the law's models
    event_driven: Path       # the event-driven engine (mn-event-driven)
    collision_rules: Path    # its rules' outcomes (mn-collision-rules)
    reference_loop: Path     # bench/reference_loop.cpp built


def build_layout(directory=DEFAULT):
    """The paths of a build directory, made absolute from where the caller runs (the runs
    themselves start elsewhere)."""
    d = Path(directory).absolute()
    return Build(d, d / "lammps" / "lmp", d / "plugin" / "granmnplugin.so",
                 d / "plugin" / "mn-law", d / "plugin" / "liggghts" / "build" / "liggghts",
                 d / "plugin" / "event_driven" / "mn-event-driven",
                 d / "plugin" / "event_driven" / "mn-collision-rules",
                 d / "bench" / "reference-loop")
