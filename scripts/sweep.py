#!/usr/bin/python3
"""Runs a grid of scene points described in a TOML config, resumably, with progress and ETA.

    scripts/sweep.py CONFIG [--output DIR] [--jobs N | --partitions P] [--dry-run]

Config (TOML):

    name = "example"              # results go to results/<name> unless --output is given
    [defaults]                    # deck variables for every point
    run_time = 100
    [[grid]]                      # every list is a dimension; points = the cartesian product
    scene = "single_disk"         # single_disk, collisional_flow or frictional_flow
    kn = [5e4, 2e5]
    seed = [1, 2]
    integrator = ["verlet", "ab2"]

Any other key is passed to the deck as -var KEY VALUE (see inputs/lib/defaults.lmp); a
variable the scene's deck takes but never uses (seed in single_disk: no random start) is
refused. A number is one value whatever its spelling: kn 5e4, 50000 and "5e4" are one point.

Layout: <output>/<scene>/<point>/ holds the deck's outputs (energy.txt, counts.txt, ...),
point.json (the point's variables), command.txt (the exact command), log.lammps, run.out (what
lmp printed), timing.json (wall and CPU seconds),
and done.txt, written by the deck last. A point with done.txt is never run again, so a killed
sweep resumes where it stopped; a point without it is run again from scratch.

By default the points run as separate serial lmp processes, as many at once as the machine
has cores (--jobs). --partitions P runs P points at a time in one `mpirun -np P lmp -partition
Px1`, LAMMPS's own multi-partition mode, as on a cluster.
"""
import argparse
import concurrent.futures
import functools
import json
import math
import os
import re
import shlex
import shutil
import subprocess
import sys
import time
import tomllib
from itertools import product
from pathlib import Path

from postprocess.law import LawError, derived    # scripts/postprocess links the package

ROOT = Path(__file__).resolve().parent.parent
LIB = ROOT / "inputs" / "lib"
# The scenes are the decks that name themselves (`variable scene index NAME`).
SCENES = tuple(sorted(deck.stem for deck in (ROOT / "inputs").glob("*.lmp")
                      if re.search(r"^variable scene index (\w+)", deck.read_text(), re.M)))
NAME = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")
# Deck variables the runner sets itself for every point.
RESERVED = {"plugin", "lib", "out"}
# Atoms each scene integrates or pairs with: the cost model's size (bumps included).
SCENE_ATOMS = {"single_disk": 11, "collisional_flow": 100, "frictional_flow": 100}
# Seconds per step: a fixed part and a part per atom; refined as points finish.
STEP_COST = (4e-7, 4e-8)


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


def law(mn_law, kn, e, beta):
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
        return steps * (STEP_COST[0] + STEP_COST[1] * SCENE_ATOMS[point["scene"]]) * self.factor

    def learn(self, predicted, measured):
        ratio = measured / max(predicted, 1e-9)
        self.samples += 1
        self.factor += (ratio * self.factor - self.factor) / self.samples


def format_seconds(seconds):
    seconds = int(round(seconds))
    return f"{seconds // 3600}h{seconds // 60 % 60:02d}m" if seconds >= 3600 else \
        f"{seconds // 60}m{seconds % 60:02d}s"


def point_variables(point, directory, paths):
    variables = {k: v for k, v in point.items() if k != "scene"}
    variables.update(plugin=paths["plugin"], lib=LIB, out=directory)
    return variables


def prepare(directory, point):
    """A fresh directory for a point that has not completed."""
    if directory.exists():
        shutil.rmtree(directory)
    directory.mkdir(parents=True)
    (directory / "point.json").write_text(json.dumps(point, indent=1, sort_keys=True) + "\n")


def run_serial(point, directory, paths, env):
    prepare(directory, point)
    command = [str(paths["lmp"]), "-in", str(ROOT / "inputs" / f"{point['scene']}.lmp"),
               "-log", str(directory / "log.lammps"), "-screen", "none", "-nocite"]
    for name, value in point_variables(point, directory, paths).items():
        command += ["-var", name, format_value(value)]
    (directory / "command.txt").write_text(shlex.join(command) + "\n")
    return finish(directory, *timed_run(command, directory, env))


def timed_run(command, directory, env):
    """Runs command with its output in directory/run.out: (exit status, output, wall seconds,
    CPU seconds of the process and the children it waited for)."""
    start = time.time()
    with open(directory / "run.out", "w") as out:
        proc = subprocess.Popen(command, stdout=out, stderr=subprocess.STDOUT, env=env)
        _, status, usage = os.wait4(proc.pid, 0)
    proc.returncode = os.waitstatus_to_exitcode(status)
    output = (directory / "run.out").read_text(errors="replace")
    return proc.returncode, output, time.time() - start, usage.ru_utime + usage.ru_stime


def run_partitions(batch, batch_dir, paths, env):
    """Points of one batch as the partitions of one lmp run."""
    batch_dir.mkdir(parents=True, exist_ok=True)
    for point, directory in batch:
        prepare(directory, point)
        lines = [f"log {directory / 'log.lammps'}"]
        lines += [f"variable {name} index {format_value(value)}"
                  for name, value in point_variables(point, directory, paths).items()]
        lines.append(f"include {ROOT / 'inputs' / (point['scene'] + '.lmp')}")
        (directory / "settings.lmp").write_text("\n".join(lines) + "\n")
    driver = batch_dir / "driver.lmp"
    driver.write_text("variable point world " + " ".join(str(d) for _, d in batch) +
                      "\ninclude ${point}/settings.lmp\n")
    n = len(batch)
    command = [paths["mpiexec"], "-np", str(n), str(paths["lmp"]), "-partition", f"{n}x1",
               "-in", str(driver), "-log", str(batch_dir / "log.lammps"), "-plog", "none",
               "-pscreen", "none", "-screen", "none", "-nocite"]
    for _, directory in batch:
        (directory / "command.txt").write_text(shlex.join(command) + "\n")
    status, output, elapsed, cpu = timed_run(command, batch_dir, env)
    # one process for the batch: its time is shared out equally
    return [finish(directory, status, output, elapsed, cpu / len(batch)) for _, directory in batch]


def finish(directory, status, output, elapsed, cpu):
    ok = (directory / "done.txt").exists()
    if ok:
        (directory / "timing.json").write_text(
            json.dumps({"seconds": elapsed, "cpu_seconds": cpu}) + "\n")
    else:
        (directory / "failed.txt").write_text(f"exit status {status}\n--- output\n"
                                              f"{output[-40000:]}\n")
    return ok, elapsed


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
    parser.add_argument("--jobs", type=int, default=os.cpu_count(),
                        help="serial lmp processes at once (default: all cores)")
    parser.add_argument("--partitions", type=int, default=0,
                        help="run P points at a time as LAMMPS partitions under mpirun")
    parser.add_argument("--dry-run", action="store_true",
                        help="list the points and the predicted cost, run nothing")
    parser.add_argument("--build", type=Path, default=ROOT / "build")
    args = parser.parse_args(argv)
    if args.jobs < 1 or args.partitions < 0:
        parser.error("--jobs must be >= 1 and --partitions >= 0")

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
        steps = [predicted_steps(p, paths["mn_law"]) for p in points]
    except SweepError as error:
        print(f"sweep: {error}", file=sys.stderr)
        return 2

    model = CostModel()
    plan = [(p, output / p["scene"] / point_name(p), s) for p, s in zip(points, steps)]
    todo = [(p, d, s) for p, d, s in plan if not (d / "done.txt").exists()]
    # most expensive first, so that the last points to finish are short ones
    todo.sort(key=lambda item: -model.predict(item[0], item[2]))
    total = sum(model.predict(p, s) for p, _, s in plan)
    print(f"sweep: {len(plan)} points, {len(plan) - len(todo)} already done, {len(todo)} to run; "
          f"predicted {format_seconds(total)} of CPU in all "
          f"({total / 3600:.3g} CPU-hours); output {output}", flush=True)
    if args.dry_run:
        for p, d, s in plan:
            print(f"  {'done' if (d / 'done.txt').exists() else 'todo'} {d.relative_to(output)} "
                  f"{s} steps ~{format_seconds(model.predict(p, s))}")
        return 0

    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    lanes = args.partitions if args.partitions else args.jobs
    failures, finished = [], 0

    def report(point, directory, predicted, ok, elapsed):
        nonlocal finished
        finished += 1
        stopped = directory / "stopped.txt"
        if not ok:
            failures.append(directory)
        elif not stopped.exists():      # a run that ended early says nothing about the cost
            model.learn(predicted, elapsed)
        how = "FAILED" if not ok else "done" if not stopped.exists() else \
            f"done (pile stopped: {stopped.read_text().strip()})"
        remaining = sum(model.predict(p, s) for p, d, s in todo[finished:]) / lanes
        print(f"[{finished}/{len(todo)}] {how} {directory.relative_to(output)} in "
              f"{elapsed:.1f} s; ETA {format_seconds(remaining)}", flush=True)

    if args.partitions:
        for start in range(0, len(todo), args.partitions):
            batch = todo[start:start + args.partitions]
            results = run_partitions([(p, d) for p, d, _ in batch],
                                     output / "batches" / f"batch{start // args.partitions}",
                                     paths, env)
            for (p, d, s), (ok, elapsed) in zip(batch, results):
                report(p, d, model.predict(p, s) * len(batch), ok, elapsed * len(batch))
    else:
        with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
            futures = {pool.submit(run_serial, p, d, paths, env): (p, d, s) for p, d, s in todo}
            for future in concurrent.futures.as_completed(futures):
                p, d, s = futures[future]
                ok, elapsed = future.result()
                report(p, d, model.predict(p, s), ok, elapsed)

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
