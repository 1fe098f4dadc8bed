"""The event-driven engine (plugin/event_driven: mn-event-driven, docs/hard_spheres.md) as an
engine of the sweep runner. A point of engine event_driven runs its scene's LAMMPS deck only to
make the start (-var write_start yes, inputs/lib/write_start.lmp: the same seed, the same start),
turns it into the engine's start file (start.txt), runs mn-event-driven on it, which writes the
files of a LAMMPS run of the scene (params.txt, energy.txt, counts.txt, profile.txt:
plugin/event_driven/outputs.h) and summary.txt, and ends with done.txt carrying the run's token.

    scripts/event_driven_point.py --lmp LMP --engine EXE --deck DECK NAME=VALUE ...

NAME=VALUE: the runner's variables (plugin, lib, out, run_token) and the point's. A point's
variables are the deck's that the engine takes (DECK_VARIABLES: the physics, the times and the
outputs), the deck's that make the start (its geometry, seed), and the engine's own (VARIABLES,
mn-event-driven's parameters with its defaults); a deck variable only LAMMPS reads (LAMMPS_ONLY:
the integrator, the time step, checkpoints, the pile's stop) is refused by the runner, since no
value of it changes the run. A run that a detected collapse ends before run_time has completed:
its stopped.txt says when, as a LAMMPS run whose pile stopped, so that postprocess averages up to
there; summary.txt says "end collapse", and collapse.txt holds the report. A run that reaches its
events cap has completed too, but its outputs end early: postprocess calls them truncated and
averages nothing (summary.txt: "end events")."""
import argparse
import subprocess
from pathlib import Path

from .decks import deck_defaults

# mn-event-driven's parameters a point may set (their defaults are the engine's: main.cpp)
VARIABLES = ("rule", "collapse", "tc_time", "tc_beta", "e_w", "beta_w", "collapse_count",
             "collapse_time", "events")
# the deck's variables the engine takes, under the same names
DECK_VARIABLES = ("kn", "e", "beta", "mu", "sin_theta", "tangential", "seed", "run_time",
                  "average_start", "output_interval", "profile_bin")
# the deck's variables only LAMMPS reads
LAMMPS_ONLY = {"integrator", "integration", "newton", "dt_fraction", "dt_cap",
               "snapshot_interval", "rows", "rows_time", "counters", "checkpoint_interval",
               "timer", "stop_energy", "stop_time"}
# the start the deck writes, in the point's directory (inputs/lib/write_start.lmp), and the
# engine's start file made of it
START_DUMP = "start.lammpstrj"
START_FLOOR = "start.floor"
START = "start.txt"


class StartError(Exception):
    pass


def deck_uses(uses):
    """The variables an event-driven point of a deck that uses `uses` (decks.deck_uses) may
    set."""
    return (set(uses) - LAMMPS_ONLY) | set(DECK_VARIABLES) | set(VARIABLES)


def read_start_dump(path):
    """(box {x: (lo, hi), y: (lo, hi)}, [(id, x, y, vx, vy, omega, diameter, mobile)]) of the
    snapshot inputs/lib/write_start.lmp writes."""
    lines = Path(path).read_text().splitlines()
    try:
        bounds = lines.index(next(l for l in lines if l.startswith("ITEM: BOX BOUNDS")))
        box = {axis: tuple(float(v) for v in lines[bounds + 1 + k].split()[:2])
               for k, axis in enumerate("xy")}
        header = lines.index(next(l for l in lines if l.startswith("ITEM: ATOMS")))
    except (StopIteration, ValueError, IndexError):
        raise StartError(f"{path}: not the start snapshot inputs/lib/write_start.lmp writes")
    columns = lines[header].split()[2:]
    wanted = ("id", "x", "y", "vx", "vy", "omegaz", "diameter", "v_start_mobile")
    if any(c not in columns for c in wanted):
        raise StartError(f"{path}: the columns {' '.join(columns)} are not {' '.join(wanted)}")
    atoms = []
    for line in lines[header + 1:]:
        words = line.split()
        atoms.append(tuple(float(words[columns.index(c)]) for c in wanted))
    return box, sorted(atoms)


def write_start(dump, floor, path):
    """The engine's start file (plugin/event_driven/start.h) of the deck's start: the box along
    x, the floor, the flowing disks (in the order of their ids) and the bumps. Returns the box."""
    box, atoms = read_start_dump(dump)
    words = Path(floor).read_text().split()
    if len(words) != 2 or words[0] != "floor":
        raise StartError(f"{floor}: expected 'floor Y' or 'floor none'")
    lines = [f"# the start of {dump} (inputs/lib/write_start.lmp)",
             f"box {box['x'][0]!r} {box['x'][1]!r}"]
    if words[1] != "none":
        lines.append(f"floor {float(words[1])!r}")
    for _, x, y, vx, vy, omega, diameter, mobile in atoms:
        lines.append(f"disk {x!r} {y!r} {vx!r} {vy!r} {omega!r} {diameter!r}" if mobile else
                     f"bump {x!r} {y!r} {diameter!r}")
    Path(path).write_text("\n".join(lines) + "\n")
    return box


def deck_value(variables, defaults, name):
    return variables.get(name, defaults.get(name))


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--lmp", required=True)
    parser.add_argument("--engine", required=True)
    parser.add_argument("--deck", required=True, type=Path)
    parser.add_argument("variables", nargs="*", metavar="NAME=VALUE")
    args = parser.parse_args(argv)
    variables = dict(v.split("=", 1) for v in args.variables)
    out = Path(variables["out"])
    defaults = deck_defaults(args.deck)
    scene = deck_value(variables, defaults, "scene")
    # the start: the deck's own, with the point's deck variables
    command = [args.lmp, "-in", str(args.deck), "-log", str(out / "log.lammps"), "-screen",
               "none", "-nocite", "-var", "write_start", "yes"]
    for name, value in variables.items():
        if name not in VARIABLES:
            command += ["-var", name, value]
    made = subprocess.run(command)
    if made.returncode != 0 or not (out / START_DUMP).exists():
        print(f"ERROR: {args.deck} did not write the start {out / START_DUMP} (exit status "
              f"{made.returncode}; see {out / 'log.lammps'})", flush=True)
        return 1
    try:
        box = write_start(out / START_DUMP, out / START_FLOOR, out / START)
    except (OSError, StartError) as error:
        print(f"ERROR: {error}", flush=True)
        return 1
    parameters = [f"start={out / START}", f"out={out}", f"scene={scene}",
                  f"profile_lo={box['y'][0]!r}", f"profile_hi={box['y'][1]!r}"]
    for name in DECK_VARIABLES:
        if name == "tangential" and name not in variables:
            continue    # the engine takes it under rule soft only: its default is the deck's
        parameters.append(f"{name}={deck_value(variables, defaults, name)}")
    parameters += [f"{name}={variables[name]}" for name in VARIABLES if name in variables]
    if variables.get("collapse") == "tc" and "tc_time" not in variables:
        parameters.append("tc_time=tau_c")
    print("mn-event-driven " + " ".join(parameters), flush=True)
    status = subprocess.run([args.engine] + parameters).returncode
    if status not in (0, 3):
        return status
    # the point's file names spelled here, not taken from postprocess/rundir.py: this runs as
    # scripts/event_driven_point.py, where only granmn_sweep is importable
    summary = dict(line.split(None, 1) for line in (out / "summary.txt").read_text().splitlines())
    if summary["end"].strip() == "collapse":
        (out / "stopped.txt").write_text(f"stopped_at {float(summary['time']):.10g}\n")
    (out / "done.txt").write_text(f"kn {variables.get('kn', defaults.get('kn'))} events "
                                  f"{summary['events'].strip()} end {summary['end'].strip()} "
                                  f"run {variables['run_token']}\n")
    return 0
