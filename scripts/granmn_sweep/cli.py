"""Runs a grid of scene points described in a TOML config, resumably, with progress and ETA.

    python3 -m scripts.sweep CONFIG [--output DIR] [--jobs N | --partitions P] [--ranks R]
                             [--checkpoint-interval T] [--set NAME=VALUE ...] [--dry-run]
    (from the repository root; installed, `granmn sweep CONFIG ...`)

Config (TOML):

    name = "example"              # results go to results/<name> unless --output is given
    [defaults]                    # deck variables for every point
    run_time = 100
    [[grid]]                      # every list is a dimension; points = the cartesian product
    scene = "single_disk"         # single_disk, collisional_flow, frictional_flow or chute_3d
    kn = [5e4, 2e5]
    seed = [1, 2]
    integrator = ["verlet", "ab2"]
    engine = "lammps"             # or "liggghts": the scene's deck inputs/liggghts/<scene>.lmp
                                  # run by build/plugin/liggghts/build/liggghts (chute_3d);
                                  # or "event_driven": the 2D scene's deck makes the start,
                                  # build/plugin/event_driven/mn-event-driven runs it
                                  # (scripts/granmn_sweep/event_driven.py: its variables)

Any other key is passed to the deck as -var KEY VALUE (see inputs/lib/defaults.lmp); a
variable the scene's deck takes but never uses (seed in single_disk: no random start) is
refused. A number is one value whatever its spelling: kn 5e4, 50000 and "5e4" are one point.

Layout: <output>/<scene>/<point>/ holds the deck's outputs (energy.txt, counts.txt, ...),
point.json (the point's variables), runner.json (the runner's: the checkpoint interval of
--checkpoint-interval), command.txt (the exact command), log.lammps, run.out (what
lmp printed), timing.json (wall and CPU seconds, a resumed run's with those of the runs it
went on from: earlier_runs.json), running.json while its lmp runs, failed.txt
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
--done-in DIR (repeatable) counts as done a point whose run summary in DIR
(`python3 -m postprocess summarize --to DIR`: DIR/<scene>/<point>.json) says its run ended
(flowing or stopped): a long series carried from one machine to the next by its committed
summaries, whose run directories are gone, resumes where the summaries stop.

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

A point's directory is named by its variables (those of [defaults] and --set included): a
point whose name the output's filesystem cannot take (with room for its summary <point>.json,
`python3 -m postprocess summarize`) is refused before anything runs, --dry-run included.
A point whose files cannot be written (a full disk) fails with that cause, and a run that ends
without the deck's last output (done.txt) fails with what the runner can tell of why (a full
filesystem, a signal, no ERROR line): failed.txt, and the point's progress line.

Exit status: 0 all done, 1 some points failed, 2 refused (a bad config or path, a busy output),
3 the runner itself failed (an unexpected error: its message and traceback on stderr; the runs
under way are stopped, <output>/sweep.lock is let go and removed, the same command resumes).
"""
import argparse
import math
import os
import re
import shutil
import signal
import sys
import traceback
from pathlib import Path

from . import SweepError
from . import processes
from .build_layout import DEFAULT as DEFAULT_BUILD, build_layout
from .config import expand, load_config, with_settings
from .cost import CostModel, format_seconds, point_sizes
from .decks import ROOT, engine
from .points import check_names, check_output, check_path, foreign, lock_output, \
    unlock_output
from .schedule import check_slots, run_points
from postprocess.rundir import SUMMARY_SUFFIX, completed, point_name, run_name
from postprocess.summary import read_summary
from postprocess.io import DataError


def summarized_points(directories, plan):
    """The point directories of `plan` whose run summary in one of `directories` says the run
    ended (flowing or stopped): a series carried from machine to machine by its committed
    summaries resumes where they stop. A summary there that cannot be read is refused."""
    done = set()
    for directory in directories:
        if not directory.is_dir():
            raise SweepError(f"--done-in {directory}: not a directory of run summaries")
        for _, point_dir, _ in plan:
            path = directory / point_dir.parent.name / (point_dir.name + SUMMARY_SUFFIX)
            if not path.exists():
                continue
            try:
                record = read_summary(path, selection=None)
            except DataError as error:
                raise SweepError(f"--done-in {directory}: {error}")
            if record.ended in ("flowing", "stopped"):
                done.add(point_dir)
    return done


def serial_build(build):
    """Whether the build's LAMMPS is serial (its CMake cache's GRANMN_MPI, CMakeLists.txt)."""
    cache = build / "CMakeCache.txt"
    return cache.exists() and re.search(r"^GRANMN_MPI:BOOL=(OFF|NO|FALSE|0)$",
                                        cache.read_text(errors="replace"), re.M | re.I) is not None


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
    parser.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                        help="a deck variable for every point, as if in the config's "
                             "[defaults] (replacing its value there; a grid may not set it); "
                             "repeatable")
    parser.add_argument("--dry-run", action="store_true",
                        help="list the points and the predicted cost (each deck asked for its "
                             "time step and atoms: -var dry_run yes), run no point")
    parser.add_argument("--build", type=Path, default=DEFAULT_BUILD)
    parser.add_argument("--done-in", type=Path, action="append", default=[], metavar="DIR",
                        help="run summaries (`python3 -m postprocess summarize --to DIR`): a "
                        "point whose summary there ended (flowing or stopped) is done and not "
                        "run; repeatable")
    args = parser.parse_args(argv)
    # the dry runs and the points run lmp elsewhere than here: a relative --build names this
    # directory's
    build = build_layout(args.build)
    args.build = build.directory
    if args.ranks < 1:
        parser.error(f"--ranks {args.ranks}: the MPI ranks per point must be >= 1")
    if args.jobs is None:
        args.jobs = max(1, (os.cpu_count() or 1) // args.ranks)
    if args.jobs < 1 or args.partitions < 0:
        parser.error("--jobs must be >= 1 and --partitions >= 0")
    if not (args.checkpoint_interval >= 0 and math.isfinite(args.checkpoint_interval)):
        parser.error(f"--checkpoint-interval {args.checkpoint_interval:g} must be >= 0 "
                     "(0: none)")

    # each engine's executable under the key of its name (decks.ENGINES)
    paths = {"lammps": build.lammps, "liggghts": build.liggghts,
             "event_driven": build.event_driven, "plugin": build.plugin,
             "mpiexec": shutil.which("mpirun") or "mpirun"}
    try:
        if not (ROOT / "inputs").is_dir():
            raise SweepError(f"{ROOT} is not the project's checkout (no inputs/ with the decks): "
                             "the runner runs from one; install it there with `pip install "
                             "--no-deps --no-build-isolation -e .`, or run `python3 -m scripts.sweep` "
                             "there")
        config = with_settings(load_config(args.config), args.set, args.config)
        points = expand(config, args.config)
        output = args.output or ROOT / "results" / config.get("name", Path(args.config).stem)
        for what, path in (("--output", output), ("--build", args.build), ("the checkout", ROOT)):
            check_path(what, path)
        check_output(output)
        check_names(output, [(p["scene"], point_name(p)) for p in points])
        engines = {engine(p) for p in points}
        if args.partitions and engines != {"lammps"}:
            raise SweepError("--partitions runs the points as the partitions of one lmp: the "
                             "points of engine liggghts run as processes of their own (--jobs), "
                             "as do those of engine event_driven")
        if (args.ranks > 1 or args.checkpoint_interval > 0) and "event_driven" in engines:
            raise SweepError("the event-driven engine runs on one core and writes no "
                             "checkpoints: --ranks and --checkpoint-interval do not apply to "
                             "its points")
        # an event-driven point's start is made by its LAMMPS deck
        needs_lammps = {"lammps", "plugin"} if engines & {"lammps", "event_driven"} else set()
        for key in sorted(engines | needs_lammps):
            if not paths[key].exists():
                raise SweepError(f"{paths[key]} is missing: run ./scripts/build.sh first")
        if (args.partitions or args.ranks > 1) and serial_build(args.build):
            raise SweepError(f"--{'partitions' if args.partitions else 'ranks'} runs lmp under "
                             f"mpirun, and {args.build} is a serial LAMMPS (built with "
                             "GRANMN_MPI=OFF, LAMMPS's STUBS MPI): each rank would run the whole "
                             "point on its own; run the points as processes (--jobs), or build "
                             "with MPI (scripts/build.sh without --serial)")
        # each point's steps and atoms, as its deck says them (cost.point_sizes)
        sizes = point_sizes(points, paths, args.jobs)
    except SweepError as error:
        print(f"sweep: {error}", file=sys.stderr)
        return 2

    model = CostModel()
    plan = [(p, output / run_name(p), s) for p, s in zip(points, sizes)]
    try:
        summarized = summarized_points(args.done_in, plan)
    except SweepError as error:
        print(f"sweep: {error}", file=sys.stderr)
        return 2
    todo = [(p, d, s) for p, d, s in plan if not completed(d) and d not in summarized]
    # the runner's variables of each point: the checkpoint interval, where the point sets none
    extra = {d: ({"checkpoint_interval": args.checkpoint_interval}
                 if args.checkpoint_interval > 0 and "checkpoint_interval" not in p else {})
             for p, d, _ in todo}
    # most expensive first, so that the last points to finish are short ones
    todo.sort(key=lambda item: -model.predict(item[0], item[2]))
    total = sum(model.predict(p, s) for p, _, s in plan)
    # points at a time; each on `ranks` processes
    lanes = args.partitions if args.partitions else args.jobs
    processes_at_once = lanes * args.ranks
    left = sum(model.predict(p, s) for p, _, s in todo)
    print(f"sweep: {len(plan)} points, {len(plan) - len(todo)} already done, {len(todo)} to run; "
          f"predicted {format_seconds(total)} of CPU in all "
          f"({total / 3600:.3g} CPU-hours); output {output}", flush=True)
    print(f"sweep: {lanes} point{'s' if lanes != 1 else ''} at a time on {args.ranks} MPI rank"
          f"{'s' if args.ranks > 1 else ''} each"
          + (f" ({args.partitions} partitions of one mpirun)" if args.partitions else "")
          + f": {processes_at_once} processes (this machine has {os.cpu_count()} logical cores); "
          f"~{format_seconds(left / processes_at_once)} of wall for the points to run if the ranks "
          "scale ideally", flush=True)
    if processes_at_once > (os.cpu_count() or 1):
        print(f"sweep: note: {processes_at_once} processes on {os.cpu_count()} logical cores: they "
              "share them (use fewer --jobs or --ranks to give each its own)", flush=True)
    if args.dry_run:
        for p, d, s in plan:
            state = "done" if completed(d) else "summarized" if d in summarized else "todo"
            print(f"  {state} {d.relative_to(output)} "
                  f"{s.steps} steps ~{format_seconds(model.predict(p, s))}")
        return 0

    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    lock = None
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
        live = processes.live_runs(d for _, d, _ in todo)
        if live:
            raise SweepError(
                f"{len(live)} points are still being run by processes an earlier sweep left "
                "(stop them, e.g. `kill PID`, or let them end; then run the sweep again): " +
                "; ".join(f"pid {pid} in {d}" for d, pid in live[:5]))
    except SweepError as error:
        unlock_output(lock)
        print(f"sweep: {error}", file=sys.stderr)
        return 2
    signal.signal(signal.SIGTERM, processes.stop)
    signal.signal(signal.SIGINT, processes.stop)

    try:
        return run_points(plan, todo, output, paths, env, args.jobs, args.partitions,
                          args.ranks, extra, model, processes_at_once)
    except SweepError as error:
        print(f"sweep: {error}", file=sys.stderr)
        return 2
    except Exception as error:
        print(f"sweep: the runner failed: {type(error).__name__}: {error}; the runs under way "
              "were stopped and the points not done are run by the same command (the "
              "traceback follows: a fault of the runner, please report it)", file=sys.stderr)
        traceback.print_exc()
        return 3
    finally:
        unlock_output(lock)
