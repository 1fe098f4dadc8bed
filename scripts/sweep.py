#!/usr/bin/python3
"""Runs a grid of scene points described in a TOML config, resumably, with progress and ETA.

    scripts/sweep.py CONFIG [--output DIR] [--jobs N | --partitions P] [--ranks R]
                     [--checkpoint-interval T] [--dry-run]

Config (TOML):

    name = "example"              # results go to results/<name> unless --output is given
    [defaults]                    # deck variables for every point
    run_time = 100
    [[grid]]                      # every list is a dimension; points = the cartesian product
    scene = "single_disk"         # single_disk, collisional_flow, frictional_flow or chute_3d
    kn = [5e4, 2e5]
    seed = [1, 2]
    integrator = ["verlet", "ab2"]

Any other key is passed to the deck as -var KEY VALUE (see inputs/lib/defaults.lmp); a
variable the scene's deck takes but never uses (seed in single_disk: no random start) is
refused. A number is one value whatever its spelling: kn 5e4, 50000 and "5e4" are one point.

Layout: <output>/<scene>/<point>/ holds the deck's outputs (energy.txt, counts.txt, ...),
point.json (the point's variables), runner.json (the runner's: the checkpoint interval of
--checkpoint-interval), command.txt (the exact command), log.lammps, run.out (what
lmp printed), timing.json (wall and CPU seconds), running.json while its lmp runs, failed.txt
(the ERROR lines and the output) if it failed, and done.txt, written by the deck last.
A point is done when done.txt and timing.json carry the token of one run (the runner gives
each run its own and writes timing.json once that run has ended): such a point is never run
again, so a killed sweep resumes where it stopped. Any other point resumes from its last
checkpoint (checkpoint_interval > 0: checkpoint.txt names the last complete one; its outputs are
cut back to that step, a half-written line or frame included; docs/sweeps.md) if its point.json
is this point's, else it is run again from scratch. A checkpoint the resumed run fails to
start from (cut short, of another step or point) is set aside (checkpoint.N.unreadable) and
the older one tried, then a fresh start; the run so far is kept in
<output>/unresumed/<scene>/<point> until the fresh start has completed.
--checkpoint-interval T checkpoints the points that set no checkpoint_interval every T time
units; it is not part of a point (its name, point.json), and the interval a point was begun
with (runner.json) is the one it resumes with.

The runner owns its lmp processes: they die with it (kill -9 included), SIGTERM or SIGINT
stops them and the sweep (exit status 128 + the signal); it refuses to start while a point's
running.json names a process still alive, or while another sweep holds <output>/sweep.lock.
By default the points run as separate serial lmp processes, as many at once as the machine
has cores (--jobs). --partitions P runs P points at a time in one `mpirun -np P lmp -partition
Px1`, LAMMPS's own multi-partition mode, as on a cluster; mpirun is asked first whether it
has P slots. A point that fails in a partition is recorded as failed; the siblings its
LAMMPS ERROR took down (MPI_Abort) are run again.

--ranks R runs each point on R MPI ranks (LAMMPS's domain decomposition): `mpirun -np R lmp`
per point, --jobs of them at a time (jobs x R processes; --jobs defaults to cores / R), or with
--partitions P one `mpirun -np P*R lmp -partition PxR` (P partitions of R ranks; mpirun is
asked first for P x R slots, and without --partitions for R). R is not part of a point: its
directory, point.json and checkpoints are the same with any R, and a point resumes with any R
(LAMMPS reads a restart file on any number of ranks). R ranks sum the forces in another order:
a point follows the 1-rank trajectory to rounding, and a chaotic dense flow amplifies that
rounding until, after some time units, the run is another realization of the same flow
(docs/sweeps.md).

Exit status: 0 all done, 1 some points failed, 2 refused (a bad config or path, a busy output).
"""
import argparse
import concurrent.futures
import ctypes
import fcntl
import functools
import json
import math
import os
import re
import secrets
import shlex
import shutil
import signal
import subprocess
import sys
import threading
import time
import tomllib
from itertools import product
from pathlib import Path

import checkpoints
from mpirun_slots import slots_problem
from postprocess.rundir import RUNNING, completed     # scripts/postprocess links the package
from mn_law import LawError, derived

ROOT = Path(__file__).resolve().parent.parent
LIB = ROOT / "inputs" / "lib"
# The scenes are the decks that name themselves (`variable scene index NAME`).
SCENES = tuple(sorted(deck.stem for deck in (ROOT / "inputs").glob("*.lmp")
                      if re.search(r"^variable scene index (\w+)", deck.read_text(), re.M)))
NAME = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")
# Deck variables the runner sets itself for every point.
RESERVED = {"plugin", "lib", "out", "run_token", "resume", "resume_step"}
# What LAMMPS's input syntax does not carry in a file name: a word ends at whitespace;
# quotes, $ (a variable) and # (a comment) are syntax.
PATH_SYNTAX = {" ": "a space", "\t": "a tab", "\n": "a newline", '"': "a quote (\")",
               "'": "a quote (')", "$": "a $", "#": "a #"}
# Atoms each scene integrates or pairs with: the cost model's size (bumps included); where the
# size is a deck variable, a function of the point's variables (the deck's defaults filled in).
SCENE_ATOMS = {"single_disk": 11, "collisional_flow": 100, "frictional_flow": 100,
               "chute_3d": lambda v: (int(float(v["spheres"]))
                                      + int(float(v["length"])) * int(float(v["width"])))}
# Seconds per step by the scene's dimension: a fixed part and a part per atom; refined as points
# finish. 3D: the dense chute's CPU seconds per atom-step, measured (docs/scenes.md): 9.9e-8 at
# kn 2e4, 6.2e-8 at 2e5, 5.6e-8 at 2e6 (the stiff points, where a series' time goes).
STEP_COST = {2: (4e-7, 4e-8), 3: (4e-7, 6e-8)}


class SweepError(Exception):
    pass


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


def expand(config, path):
    """The points of the config: dicts of deck variables, each with a scene."""
    points = []
    for number, grid in enumerate(config["grid"], 1):
        merged = dict(config.get("defaults", {}))
        merged.update(grid)
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
            if point["scene"] not in SCENES:
                raise SweepError(f"{path}: grid {number}: unknown scene '{point['scene']}' "
                                 f"(expected one of {', '.join(SCENES)})")
            defaults = deck_defaults(point["scene"])
            unknown = sorted(set(point) - {"scene"} - set(defaults))
            if unknown:
                raise SweepError(f"{path}: grid {number}: {', '.join(unknown)}: not a variable "
                                 f"of inputs/{point['scene']}.lmp (docs/scenes.md lists them)")
            # a deck takes a word where it expects a number without complaint (as 0)
            for name, value in point.items():
                if name in defaults and is_number(defaults[name]):
                    if not is_number(value):
                        raise SweepError(f"{point['scene']} point: {name} = {value!r} is not a "
                                         "number")
                    point[name] = canonical_number(value)
            ignored = sorted(set(point) - {"scene"} - deck_uses(point["scene"]))
            if ignored:
                raise SweepError(f"{path}: grid {number}: {', '.join(ignored)}: "
                                 f"inputs/{point['scene']}.lmp does not use it (every value "
                                 "would give the same run)")
            points.append(point)
    seen = set()
    for p in points:
        if not point_name(p):
            raise SweepError(f"{path}: a point of scene {p['scene']} with no variable but the "
                             "scene: a point's directory is named by its variables, and this one "
                             f"would be <output>/{p['scene']}, where the scene's points are; set "
                             "one (e.g. seed or kn)")
        name = f"{p['scene']}/{point_name(p)}"
        if name in seen:
            raise SweepError(f"{path}: the grids repeat the point {name} (equal numbers are one "
                             "value, however spelt)")
        seen.add(name)
    return points


def canonical_number(value):
    """One value, one spelling: seed 1 and "01" are 1; kn 5e4, 50000 and "5e4" are 50000."""
    number = float(value)
    return int(number) if number.is_integer() and abs(number) < 2 ** 53 else number


def format_value(value):
    """A value as the deck and the point's name get it: %g where that is exact, else every
    digit (1234567.8 is not 1.23457e+06); an integer and its float alike (1e6 is 1000000)."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return str(value)
    short = f"{float(value):g}"
    if float(short) == value:
        return short
    return str(int(value)) if float(value).is_integer() and abs(value) < 2 ** 53 else repr(value)


def point_name(point):
    return "_".join(f"{k}{format_value(v)}" for k, v in sorted(point.items()) if k != "scene")


@functools.lru_cache(maxsize=None)
def deck_defaults(scene):
    """{name: default} of the variables a scene deck declares (`variable NAME index VALUE`, its
    own first, then the shared defaults), i.e. what -var can set."""
    defaults = {}
    for deck in (ROOT / "inputs" / f"{scene}.lmp", LIB / "defaults.lmp"):
        for name, value in re.findall(r"^variable (\w+) index (\S+)", deck.read_text(), re.M):
            defaults.setdefault(name, value)
    return {name: value for name, value in defaults.items() if name not in RESERVED}


def scene_atoms(point):
    """The cost model's size of a point: SCENE_ATOMS of its scene."""
    atoms = SCENE_ATOMS[point["scene"]]
    return atoms({**deck_defaults(point["scene"]), **point}) if callable(atoms) else atoms


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


def is_number(value):
    try:
        float(value)
        return True
    except (TypeError, ValueError):
        return False


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


def point_variables(point, directory, paths, token):
    variables = {k: v for k, v in point.items() if k != "scene"}
    variables.update(plugin=paths["plugin"], lib=LIB, out=directory, run_token=token)
    return variables


def check_path(what, path):
    """The decks write ${out}/params.txt and the like: LAMMPS would end the name at a space
    (and write into an unrelated file) or read a quote, $ or # as syntax."""
    for character, name in PATH_SYNTAX.items():
        if character in str(path):
            raise SweepError(f"{what} {str(path)!r} contains {name}: LAMMPS's input syntax "
                             "cannot carry it in the file names the decks write; choose a path "
                             "without it")


def check_output(output):
    """An --output must be a directory, or a path one can be made at (no file on it)."""
    for path in (output, *output.parents):
        if path.exists():
            if not path.is_dir():
                raise SweepError(f"--output {output}: {path} is a file, not a directory; "
                                 "choose another --output")
            return


def foreign(directory, point):
    """Why the runner may not remove a point's directory to run the point afresh, or None: it
    removes only a directory it made for a point of this scene (point.json, the first file it
    writes there) that holds files alone (a run writes no folder: one is someone else's)."""
    if not directory.exists():
        return None
    if not directory.is_dir():
        return "it is a file"
    try:
        record = json.loads((directory / "point.json").read_text())
    except (OSError, ValueError):
        return "it holds no point.json (the runner writes one into each point it makes)"
    if not isinstance(record, dict) or record.get("scene") != point["scene"]:
        return f"its point.json is not of a {point['scene']} point"
    folders = sorted(entry.name for entry in directory.iterdir() if entry.is_dir())
    if folders:
        return f"it holds folders ({', '.join(folders[:3])}), which no run writes"
    return None


def prepare(directory, point, extra):
    """A fresh directory for a point that has not completed: point.json, and runner.json with
    the variables the runner chose for it (`extra`: the checkpoint interval), which a resumed
    run takes again (its checkpoints were written with them). A directory the runner may not
    remove (foreign) is refused (main() refuses the sweep before any point runs)."""
    why = foreign(directory, point)
    if why:
        raise SweepError(f"{directory} is not the runner's to remove: {why}; move it away")
    if directory.exists():
        shutil.rmtree(directory)
    directory.mkdir(parents=True)
    (directory / "point.json").write_text(json.dumps(point, indent=1, sort_keys=True) + "\n")
    (directory / "runner.json").write_text(json.dumps(extra, sort_keys=True) + "\n")


def kept_aside(directory):
    """Where a point's run that could not be resumed is kept while the point starts afresh:
    <output>/unresumed/<scene>/<point> (not a point's place: the post-processing reads
    <output>/<scene>/<point>)."""
    return directory.parents[1] / "unresumed" / directory.parent.name / directory.name


def resume_or_prepare(directory, point, extra, keep=False):
    """The variables of a point's next run beyond its own: the runner.json ones and {"resume": N,
    "resume_step": S} for a point whose directory holds a checkpoint (checkpoint.N.restart, at
    step S) of the same point, its outputs cut back to it; else `extra` and a fresh directory.
    The deck itself refuses a checkpoint of another point or plugin layout, by name (fix
    checkpoint/mn), and one of another step than S. With `keep` (its resumes failed: the
    ERROR may be lmp's or the plugin's rather than the checkpoints'), the directory a fresh
    start replaces is kept aside (kept_aside), not removed."""
    try:
        same_point = json.loads((directory / "point.json").read_text()) == point
        found = same_point and checkpoints.candidates(directory)
        if found:
            step, slot = found[0]
            kept = json.loads((directory / "runner.json").read_text()) \
                if (directory / "runner.json").exists() else {}
            checkpoints.cut_outputs(directory, step)
            return {**kept, "resume": slot, "resume_step": step}
    except (OSError, ValueError, KeyError):
        pass
    if keep and directory.exists() and not foreign(directory, point):
        aside = kept_aside(directory)
        if aside.exists() and not foreign(aside, point):   # of an earlier sweep
            shutil.rmtree(aside)
        aside.parent.mkdir(parents=True, exist_ok=True)
        directory.replace(aside)
    prepare(directory, point, extra)
    return dict(extra)


# In the log of a run that has passed its first LAMMPS setup (Output::setup prints it there)
SETUP_DONE = "Per MPI rank memory allocation"


def set_aside_failed_resume(directory, variables):
    """After a failed run: if it resumed from a checkpoint and failed before its first setup
    (read_restart's ERROR on a file cut short, a checkpoint of another point, step or layout),
    the file is set aside (checkpoint.N.unreadable), so that the next run of the point resumes
    from the older checkpoint, or starts afresh; what happened, for the progress line and
    failed.txt. None for any other failure."""
    if "resume" not in variables:
        return None
    name = f"checkpoint.{variables['resume']}.restart"
    try:
        log = (directory / "log.lammps").read_text(errors="replace")
    except OSError:
        return None
    # the deck's line before read_restart (its command, echoed, names ${resume_file}): a run
    # that failed before it (the plugin not loaded, say) says nothing about the checkpoint
    if f"resuming from checkpoint {directory / name}\n" not in log or SETUP_DONE in log:
        return None
    (directory / name).replace(directory / f"checkpoint.{variables['resume']}.unreadable")
    errors = error_lines(directory / "log.lammps") or ["no ERROR line"]
    following = checkpoints.candidates(directory)
    then = (f"resuming from checkpoint.{following[0][1]}.restart (step {following[0][0]})"
            if following else f"starting it afresh (the run so far kept in "
                              f"{kept_aside(directory)})")
    return (f"the resume from {name} (step {variables['resume_step']}) failed ({errors[0]}); "
            f"it is set aside as checkpoint.{variables['resume']}.unreadable; {then}")


def wrote_done(directory, token):
    try:
        return re.search(rf"\brun {token}\b", (directory / "done.txt").read_text()) is not None
    except OSError:
        return False


def error_lines(*paths):
    """The ERROR lines (and LAMMPS's `Last command:`) of logs and outputs."""
    lines = []
    for path in paths:
        try:
            text = path.read_text(errors="replace")
        except OSError:
            continue
        lines += [line for line in text.splitlines()
                  if line.startswith(("ERROR", "Last command:"))]
    return lines


# The runs under way, {pid: Popen}. Each run (lmp, or mpirun and the ranks it starts, each of
# those in a process group of its own) is a session of its own: a signal reaches all of it.
_runs = {}
_runs_lock = threading.RLock()   # the signal handler takes it too, in the main thread
_stopped_by = []                 # the signal that stopped the sweep
_libc = ctypes.CDLL(None, use_errno=True)
PR_SET_PDEATHSIG = 1
SIGTERM = int(signal.SIGTERM)
POLL, GRACE = 0.5, 5.0           # seconds


def die_with(runner):
    """preexec_fn of a run: SIGTERM when the runner's thread that started it ends, the runner
    killed with -9 included (PR_SET_PDEATHSIG; mpirun passes it on to its ranks); if the runner
    is gone already, an exit. The pool threads that start runs live as long as the sweep."""
    def setup():
        _libc.prctl(PR_SET_PDEATHSIG, SIGTERM)
        if os.getppid() != runner:
            os._exit(1)
    return setup


def process_fields(pid):
    """/proc/PID/stat from the state on (field 3): state, ppid, pgrp, session, ...; None if
    there is no such process."""
    try:
        return Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    except (OSError, IndexError):
        return None


def process_start(pid):
    """When a process started (clock ticks after boot): with its pid it names one process."""
    fields = process_fields(pid)
    return int(fields[19]) if fields else None


def session_processes(session):
    pids = []
    for entry in os.scandir("/proc"):
        if entry.name.isdigit():
            fields = process_fields(entry.name)
            if fields and fields[0] != "Z" and int(fields[3]) == session:
                pids.append(int(entry.name))
    return pids


def signal_session(session, signum):
    for pid in session_processes(session):
        try:
            os.kill(pid, signum)
        except ProcessLookupError:
            pass


def run_alive(record):
    """Whether the run a running.json names has a process left (its leader, or ranks that
    outlived mpirun), its leader's pid not being another process's now."""
    leader = record.get("pid")
    if not isinstance(leader, int) or leader <= 0:
        return False
    start = process_start(leader)
    return (start is None or start == record.get("start")) and bool(session_processes(leader))


def stop(signum, frame):
    """SIGTERM, SIGINT: no run is started any more and the runs under way are stopped; their
    points are run again when the sweep is."""
    with _runs_lock:
        _stopped_by.append(signum)
        for pid in _runs:
            signal_session(pid, SIGTERM)


def start(command, output, env, directories):
    """Starts a run with what it prints in `output`, unless the sweep is stopping; the
    directories' running.json names it."""
    with _runs_lock:
        if _stopped_by:
            return None
        with open(output, "w") as out:
            proc = subprocess.Popen(command, stdout=out, stderr=subprocess.STDOUT, env=env,
                                    start_new_session=True, preexec_fn=die_with(os.getpid()))
        _runs[proc.pid] = proc
    record = json.dumps({"pid": proc.pid, "start": process_start(proc.pid)}) + "\n"
    for directory in directories:
        (directory / RUNNING).write_text(record)
    return proc


def wait(proc, directories, ended=None):
    """(exit status, wall seconds, CPU seconds of the run and the children it waited for,
    whether the runner had to stop it). With ended(), a run still there GRACE seconds after
    ended() became true, or after the sweep was stopped, is stopped (mpirun never returns once
    one partition has quit): SIGTERM, then SIGKILL. No process of the run is left afterwards."""
    begun, deadline, stuck = time.time(), None, False
    while True:
        pid, status, usage = os.wait4(proc.pid, 0 if ended is None else os.WNOHANG)
        if pid:
            break
        if deadline is None and (_stopped_by or ended()):
            deadline = time.time() + GRACE
        elif deadline is not None and time.time() > deadline:
            signal_session(proc.pid, signal.SIGKILL if stuck else SIGTERM)
            stuck, deadline = True, time.time() + GRACE
        time.sleep(POLL)
    elapsed = time.time() - begun
    signal_session(proc.pid, signal.SIGKILL)
    with _runs_lock:
        del _runs[proc.pid]
    proc.returncode = os.waitstatus_to_exitcode(status)
    for directory in directories:
        (directory / RUNNING).unlink(missing_ok=True)
    return proc.returncode, elapsed, usage.ru_utime + usage.ru_stime, stuck


def run_serial(point, directory, paths, env, ranks, extra, notes):
    """(outcome, wall seconds, note) of a point run as one lmp process, or as `mpirun -np
    ranks lmp` (one LAMMPS world of `ranks` ranks: the domain decomposed). A resume that fails
    (set_aside_failed_resume) is followed at once by the next try: the older checkpoint, then
    a fresh start; `notes[directory]` says what happened."""
    while True:
        if _stopped_by:
            return "stopped", 0.0, ""
        token = secrets.token_hex(8)
        variables = resume_or_prepare(directory, point, extra, keep=directory in notes)
        mpirun = [paths["mpiexec"], "-np", str(ranks)] if ranks > 1 else []
        command = mpirun + [str(paths["lmp"]), "-in",
                            str(ROOT / "inputs" / f"{point['scene']}.lmp"),
                            "-log", str(directory / "log.lammps"), "-screen", "none", "-nocite"]
        for name, value in {**point_variables(point, directory, paths, token),
                            **variables}.items():
            command += ["-var", name, format_value(value)]
        (directory / "command.txt").write_text(shlex.join(command) + "\n")
        proc = start(command, directory / "run.out", env, [directory])
        if proc is None:
            return "stopped", 0.0, ""
        status, elapsed, cpu, _ = wait(proc, [directory])
        failed_resume = not wrote_done(directory, token) and not _stopped_by and \
            set_aside_failed_resume(directory, variables)
        if failed_resume:
            notes.setdefault(directory, []).append(failed_resume)
            print(f"sweep: {directory}: {failed_resume}", flush=True)
            continue
        outcome = finish(directory, token, status, elapsed, cpu,
                         [directory / "log.lammps", directory / "run.out"],
                         directory / "run.out", variables, notes.get(directory, []))
        return outcome, elapsed, ""


def run_partitions(batch, batch_dir, paths, env, ranks, extras, notes):
    """Points of one batch as the partitions of one lmp run, `ranks` MPI ranks each:
    [(outcome, wall seconds, note)]. Each partition's rank 0 writes its point's log and outputs.
    A LAMMPS ERROR in one partition aborts them all (MPI_Abort): a sibling without an ERROR of
    its own did not fail, its outcome is "rerun"; so is a point whose resume failed
    (set_aside_failed_resume: its next run takes the older checkpoint, or starts afresh)."""
    batch_dir.mkdir(parents=True, exist_ok=True)
    directories = [directory for _, directory in batch]
    tokens = [secrets.token_hex(8) for _ in batch]
    resumes = []
    for (point, directory), token in zip(batch, tokens):
        variables = resume_or_prepare(directory, point, extras[directory],
                                      keep=directory in notes)
        resumes.append(variables)
        lines = [f"log {directory / 'log.lammps'}"]
        lines += [f"variable {name} index {format_value(value)}"
                  for name, value in {**point_variables(point, directory, paths, token),
                                      **variables}.items()]
        lines.append(f"include {ROOT / 'inputs' / (point['scene'] + '.lmp')}")
        (directory / "settings.lmp").write_text("\n".join(lines) + "\n")
    driver = batch_dir / "driver.lmp"
    driver.write_text("variable point world " + " ".join(str(d) for d in directories) +
                      "\ninclude ${point}/settings.lmp\n")
    n = len(batch)
    command = [paths["mpiexec"], "-np", str(n * ranks), str(paths["lmp"]), "-partition",
               f"{n}x{ranks}",
               "-in", str(driver), "-log", str(batch_dir / "log.lammps"), "-plog", "none",
               "-pscreen", "none", "-screen", "none", "-nocite"]
    for directory in directories:
        (directory / "command.txt").write_text(shlex.join(command) + "\n")

    def ended():    # every partition has written done.txt or an ERROR
        return all(wrote_done(d, t) or error_lines(d / "log.lammps")
                   for d, t in zip(directories, tokens))

    proc = start(command, batch_dir / "run.out", env, directories)
    if proc is None:
        return [("stopped", 0.0, "")] * n
    status, elapsed, cpu, stuck = wait(proc, directories, ended)
    note = (f" (mpirun stopped by the runner {GRACE:g} s after every partition had ended: it "
            "does not return once a partition has quit)") if stuck else ""
    culprits = [d for d in directories if error_lines(d / "log.lammps")]
    results = []
    for directory, token, variables in zip(directories, tokens, resumes):
        if culprits and directory not in culprits and not wrote_done(directory, token) \
                and not _stopped_by:
            results.append(("rerun", elapsed, "its batch ended with the ERROR of " +
                            ", ".join(d.name for d in culprits)))
            continue
        failed_resume = not wrote_done(directory, token) and not _stopped_by and \
            set_aside_failed_resume(directory, variables)
        if failed_resume:
            notes.setdefault(directory, []).append(failed_resume)
            results.append(("rerun", elapsed, failed_resume))
            continue
        # one process for the batch: its time is shared out equally
        outcome = finish(directory, token, status, elapsed, cpu / n,
                         [directory / "log.lammps", batch_dir / "log.lammps",
                          batch_dir / "run.out"], batch_dir / "run.out", variables,
                         notes.get(directory, []), note)
        results.append((outcome, elapsed, ""))
    return results


def finish(directory, token, status, elapsed, cpu, logs, output, variables, notes, note=""):
    """A point's outcome: "done" (done.txt carries the run's token; timing.json is written with
    it), "stopped" (by a signal to the sweep), else "failed" (failed.txt: the exit status, the
    ERROR lines of logs, how the run began (afresh or from which checkpoint) and what went
    before it (notes: failed resumes), what to do, the end of output)."""
    aside = kept_aside(directory)
    if wrote_done(directory, token):
        (directory / "timing.json").write_text(
            json.dumps({"seconds": elapsed, "cpu_seconds": cpu, "run": token}) + "\n")
        # a fresh start that completed: the run it replaced is of no more use
        if notes and "resume" not in variables and aside.exists() and \
                not foreign(aside, json.loads((directory / "point.json").read_text())):
            shutil.rmtree(aside)
            try:    # unresumed/<scene>/ and unresumed/, if nothing else is kept there
                os.removedirs(aside.parent)
            except OSError:
                pass
        return "done"
    if _stopped_by:
        return "stopped"
    errors = error_lines(*logs) or [f"(no ERROR line in {', '.join(str(p) for p in logs)})"]
    began = (f"from checkpoint.{variables['resume']}.restart (step {variables['resume_step']})"
             if "resume" in variables else "afresh")
    history = "".join(f"before it: {line}\n" for line in notes)
    if notes and "resume" not in variables and aside.exists():
        history += (f"the run that could not be resumed is kept in {aside}: if the ERROR is not "
                    "its checkpoints' (but lmp's or the plugin's, as here where the fresh start "
                    "failed too), mend that, put it back in place of this directory, rename its "
                    "checkpoint.N.unreadable back to checkpoint.N.restart (a resume takes the "
                    "newest its outputs reach) and run the sweep again\n")
    printed = output.read_text(errors="replace") if output.exists() else ""
    (directory / "failed.txt").write_text(
        f"exit status {status}{note}\n" + "\n".join(errors) + f"\nthis run began {began}\n" +
        history + "what to do: mend what the ERROR names, then run the sweep again: it runs "
        "this point from its newest checkpoint if it has one, else afresh (remove this "
        f"directory to start it afresh)\n--- the end of {output}\n{printed[-40000:]}\n")
    return "failed"


def check_slots(mpiexec, slots, env, asked):
    """mpirun's slots (mpirun_slots), asked before any point runs, for the processes one
    mpirun of the sweep starts (`asked`: the options that make them, for the message)."""
    problem = slots_problem([mpiexec, "-np", str(slots)], env)
    if problem:
        raise SweepError(f"{asked}: {problem}: use fewer partitions or ranks, or run under an "
                         "allocation or a hostfile with that many slots")


def lock_output(output):
    """Holds <output>/sweep.lock while the sweep runs (an flock: the kernel lets go when the
    runner dies, kill -9 included); two sweeps on one output would run its points twice at
    once."""
    try:
        output.mkdir(parents=True, exist_ok=True)
        handle = open(output / "sweep.lock", "a+")
    except OSError as error:    # made a file since check_output, or not writable
        raise SweepError(f"--output {output}: {error.strerror}; choose another --output")
    try:
        fcntl.flock(handle, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except BlockingIOError:
        handle.seek(0)
        holder = handle.read().strip() or "unknown"
        handle.close()
        raise SweepError(f"{output} is in use by another sweep (pid {holder}, "
                         f"{output / 'sweep.lock'}): let it end or stop it")
    handle.truncate(0)
    handle.write(f"{os.getpid()}\n")
    handle.flush()
    return handle


def live_runs(directories):
    """[(directory, pid)] of the points whose running.json names a run still alive: left by a
    sweep that was killed before its lmp could be, or started by hand."""
    live = []
    for directory in directories:
        try:
            record = json.loads((directory / RUNNING).read_text())
        except (OSError, ValueError):
            continue
        if isinstance(record, dict) and run_alive(record):
            live.append((directory, record["pid"]))
    return live


def cpu_seconds(directories):
    """CPU seconds the completed points took, from their timing.json."""
    total = 0.0
    for d in directories:
        try:
            total += json.loads((d / "timing.json").read_text()).get("cpu_seconds", 0.0)
        except (OSError, ValueError):
            pass
    return total


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter,
                                     epilog="\n".join(__doc__.splitlines()[2:]))
    parser.add_argument("config")
    parser.add_argument("--output", type=Path, help="results directory")
    parser.add_argument("--jobs", type=int,
                        help="points at a time, each one lmp process, or with --ranks R one "
                             "mpirun of R ranks: jobs x R processes (default: cores / R, at "
                             "least 1)")
    parser.add_argument("--partitions", type=int, default=0,
                        help="run P points at a time as LAMMPS partitions under one mpirun "
                             "(P x R processes)")
    parser.add_argument("--ranks", type=int, default=1,
                        help="MPI ranks per point (LAMMPS's domain decomposition; default 1: "
                             "a serial lmp, no mpirun)")
    parser.add_argument("--checkpoint-interval", type=float, default=0.0, metavar="T",
                        help="checkpoints every T time units (the deck's checkpoint_interval) "
                             "for the points that do not set one: a killed point resumes from "
                             "its last (default 0: none); not part of a point's name")
    parser.add_argument("--dry-run", action="store_true",
                        help="list the points and the predicted cost, run nothing")
    parser.add_argument("--build", type=Path, default=ROOT / "build")
    args = parser.parse_args(argv)
    if args.ranks < 1:
        parser.error(f"--ranks {args.ranks}: the MPI ranks per point must be >= 1")
    if args.jobs is None:
        args.jobs = max(1, (os.cpu_count() or 1) // args.ranks)
    if args.jobs < 1 or args.partitions < 0:
        parser.error("--jobs must be >= 1 and --partitions >= 0")
    if not (args.checkpoint_interval >= 0 and math.isfinite(args.checkpoint_interval)):
        parser.error(f"--checkpoint-interval {args.checkpoint_interval:g} must be >= 0 "
                     "(0: none)")

    paths = {"lmp": args.build / "lammps" / "lmp",
             "plugin": args.build / "plugin" / "granmnplugin.so",
             "mn_law": args.build / "plugin" / "mn-law",
             "mpiexec": shutil.which("mpirun") or "mpirun"}
    try:
        for key in ("lmp", "plugin", "mn_law"):
            if not paths[key].exists():
                raise SweepError(f"{paths[key]} is missing: run ./scripts/build.sh first")
        config = load_config(args.config)
        points = expand(config, args.config)
        output = args.output or ROOT / "results" / config.get("name", Path(args.config).stem)
        for what, path in (("--output", output), ("--build", args.build), ("the checkout", ROOT)):
            check_path(what, path)
        check_output(output)
        steps = [predicted_steps(p, paths["mn_law"]) for p in points]
    except SweepError as error:
        print(f"sweep: {error}", file=sys.stderr)
        return 2

    model = CostModel()
    plan = [(p, output / p["scene"] / point_name(p), s) for p, s in zip(points, steps)]
    todo = [(p, d, s) for p, d, s in plan if not completed(d)]
    # the runner's variables of each point: the checkpoint interval, where the point sets none
    extra = {d: ({"checkpoint_interval": args.checkpoint_interval}
                 if args.checkpoint_interval > 0 and "checkpoint_interval" not in p else {})
             for p, d, _ in todo}
    # most expensive first, so that the last points to finish are short ones
    todo.sort(key=lambda item: -model.predict(item[0], item[2]))
    total = sum(model.predict(p, s) for p, _, s in plan)
    # points at a time; each on `ranks` processes
    lanes = args.partitions if args.partitions else args.jobs
    processes = lanes * args.ranks
    left = sum(model.predict(p, s) for p, _, s in todo)
    print(f"sweep: {len(plan)} points, {len(plan) - len(todo)} already done, {len(todo)} to run; "
          f"predicted {format_seconds(total)} of CPU in all "
          f"({total / 3600:.3g} CPU-hours); output {output}", flush=True)
    print(f"sweep: {lanes} point{'s' if lanes != 1 else ''} at a time on {args.ranks} MPI rank"
          f"{'s' if args.ranks > 1 else ''} each"
          + (f" ({args.partitions} partitions of one mpirun)" if args.partitions else "")
          + f": {processes} processes (this machine has {os.cpu_count()} logical cores); "
          f"~{format_seconds(left / processes)} of wall for the points to run if the ranks "
          "scale ideally", flush=True)
    if processes > (os.cpu_count() or 1):
        print(f"sweep: note: {processes} processes on {os.cpu_count()} logical cores: they "
              "share them (use fewer --jobs or --ranks to give each its own)", flush=True)
    if args.dry_run:
        for p, d, s in plan:
            print(f"  {'done' if completed(d) else 'todo'} {d.relative_to(output)} "
                  f"{s} steps ~{format_seconds(model.predict(p, s))}")
        return 0

    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    try:
        if args.partitions and todo:
            batch = min(args.partitions, len(todo))
            check_slots(paths["mpiexec"], batch * args.ranks, env,
                        f"--partitions {args.partitions}" +
                        (f" --ranks {args.ranks}" if args.ranks > 1 else ""))
        elif args.ranks > 1 and todo:
            check_slots(paths["mpiexec"], args.ranks, env, f"--ranks {args.ranks}")
        lock = lock_output(output)
        others = [(d, why) for p, d, _ in todo for why in [foreign(d, p)] if why]
        if others:
            raise SweepError(
                f"{len(others)} point directories are not the runner's to remove and run afresh "
                "(move them away, then run the sweep again): " +
                "; ".join(f"{d}: {why}" for d, why in others[:5]))
        live = live_runs(d for _, d, _ in todo)
        if live:
            raise SweepError(
                f"{len(live)} points are still being run by processes an earlier sweep left "
                "(stop them, e.g. `kill PID`, or let them end; then run the sweep again): " +
                "; ".join(f"pid {pid} in {d}" for d, pid in live[:5]))
    except SweepError as error:
        print(f"sweep: {error}", file=sys.stderr)
        return 2
    signal.signal(signal.SIGTERM, stop)
    signal.signal(signal.SIGINT, stop)

    unfinished = {d: (p, s) for p, d, s in todo}
    failures = []
    resume_notes = {}      # {directory: [what each failed resume of it did]}

    def report(point, directory, predicted, outcome, elapsed, note):
        if outcome == "stopped":
            return
        if outcome == "rerun":
            print(f"[{len(todo) - len(unfinished)}/{len(todo)}] rerun "
                  f"{directory.relative_to(output)}: {note}", flush=True)
            return
        del unfinished[directory]
        stopped = directory / "stopped.txt"
        if outcome == "failed":
            failures.append(directory)
        elif not stopped.exists():      # a run that ended early says nothing about the cost
            # the model predicts the seconds of one core: the point took elapsed x ranks
            model.learn(predicted, elapsed * args.ranks)
        how = "FAILED" if outcome == "failed" else "done" if not stopped.exists() else \
            f"done (pile stopped: {stopped.read_text().strip()})"
        remaining = sum(model.predict(p, s) for p, s in unfinished.values()) / processes
        on = f" on {args.ranks} ranks" if args.ranks > 1 else ""
        print(f"[{len(todo) - len(unfinished)}/{len(todo)}] {how} "
              f"{directory.relative_to(output)} in {elapsed:.1f} s{on}; "
              f"ETA {format_seconds(remaining)}", flush=True)

    refused = []    # points whose directory became another's during the sweep: not run
    # runs start in pool threads only: the main thread takes the signals
    with concurrent.futures.ThreadPoolExecutor(max_workers=1 if args.partitions else
                                               args.jobs) as pool:
        if args.partitions:
            queue, number = list(todo), 0
            while queue and not _stopped_by:
                batch, queue = queue[:args.partitions], queue[args.partitions:]
                results = pool.submit(run_partitions, [(p, d) for p, d, _ in batch],
                                      output / "batches" / f"batch{number}", paths, env,
                                      args.ranks, extra, resume_notes).result()
                number += 1
                for (p, d, s), (outcome, elapsed, note) in zip(batch, results):
                    if outcome == "rerun":
                        queue.append((p, d, s))
                    # each point of the batch ran for the batch's wall time
                    report(p, d, model.predict(p, s), outcome, elapsed, note)
        else:
            futures = {pool.submit(run_serial, p, d, paths, env, args.ranks, extra[d],
                                   resume_notes): (p, d, s)
                       for p, d, s in todo}
            for future in concurrent.futures.as_completed(futures):
                p, d, s = futures[future]
                try:
                    report(p, d, model.predict(p, s), *future.result())
                except SweepError as error:    # its place taken while the sweep ran
                    print(f"sweep: {error}", file=sys.stderr)
                    refused.append(d)
    lock.close()

    if _stopped_by:
        print(f"sweep: stopped by {signal.Signals(_stopped_by[0]).name}; {len(unfinished)} "
              "points not done: the same command runs them", file=sys.stderr)
        return 128 + _stopped_by[0]
    if refused:
        print(f"sweep: {len(refused)} points not run, their directories not the runner's to "
              "remove (above); the other points ran", file=sys.stderr)
        return 2
    if failures:
        print(f"sweep: {len(failures)} points failed; see failed.txt in:", file=sys.stderr)
        for d in failures:
            print(f"  {d}", file=sys.stderr)
        return 1
    print(f"sweep: all {len(plan)} points done in {output}; they took "
          f"{cpu_seconds(d for _, d, _ in plan) / 3600:.3g} CPU-hours")
    return 0


if __name__ == "__main__":
    sys.exit(main())
