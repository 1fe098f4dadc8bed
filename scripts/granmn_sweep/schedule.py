"""Running the points: each as one lmp (or mpirun of R ranks), --jobs at a time, or P at a time
as the partitions of one mpirun; a failed resume tried again at once; progress and ETA; the
sweep's end and exit status."""
import concurrent.futures
import secrets
import shlex
import signal
import sys

from . import SweepError
from . import processes
from .config import deck_variables
from .cost import format_seconds
from .decks import ROOT, engine, point_deck
from .points import cpu_seconds, error_lines, failed_to_start, finish, \
    resume_or_prepare, set_aside_failed_resume, wrote_done
from .mpirun_slots import slots_problem
from postprocess.rundir import format_value


def point_variables(point, directory, paths, token):
    return {**deck_variables(point, paths["plugin"]), "out": directory, "run_token": token}


def run_serial(point, directory, paths, env, ranks, extra, notes):
    """(outcome, wall seconds, note) of a point run as one lmp process, or as `mpirun -np
    ranks lmp` (one LAMMPS world of `ranks` ranks: the domain decomposed). A resume that fails
    (set_aside_failed_resume) is followed at once by the next try: the older checkpoint, then
    a fresh start; `notes[directory]` says what happened. A point whose files the runner cannot
    write (a full disk) fails with that cause."""
    try:
        return run_serial_tries(point, directory, paths, env, ranks, extra, notes)
    except OSError as error:
        outcome, note = failed_to_start(directory, error)
        return outcome, 0.0, note


def run_serial_tries(point, directory, paths, env, ranks, extra, notes):
    """run_serial's tries of a point, until one is not a failed resume."""
    while True:
        if processes.stopped_by:
            return "stopped", 0.0, ""
        token = secrets.token_hex(8)
        variables = resume_or_prepare(directory, point, extra, keep=directory in notes)
        mpirun = [paths["mpiexec"], "-np", str(ranks)] if ranks > 1 else []
        given = {**point_variables(point, directory, paths, token), **variables}
        if engine(point) == "event_driven":
            # the deck makes the start, the engine runs it (granmn_sweep/event_driven.py)
            command = [sys.executable, str(ROOT / "scripts" / "event_driven_point.py"),
                       "--lmp", str(paths["lammps"]), "--engine", str(paths["event_driven"]),
                       "--deck", str(point_deck(point))]
            command += [f"{name}={format_value(value)}" for name, value in given.items()]
        else:
            # LIGGGHTS takes LAMMPS's command line
            command = mpirun + [str(paths[engine(point)]), "-in", str(point_deck(point)),
                                "-log", str(directory / "log.lammps"), "-screen", "none",
                                "-nocite"]
            for name, value in given.items():
                command += ["-var", name, format_value(value)]
        (directory / "command.txt").write_text(shlex.join(command) + "\n")
        proc = processes.start(command, directory / "run.out", env, [directory])
        if proc is None:
            return "stopped", 0.0, ""
        status, elapsed, cpu, _ = processes.wait(proc, [directory])
        failed_resume = not wrote_done(directory, token) and not processes.stopped_by and \
            set_aside_failed_resume(directory, variables)
        if failed_resume:
            notes.setdefault(directory, []).append(failed_resume)
            print(f"sweep: {directory}: {failed_resume}", flush=True)
            continue
        outcome, note = finish(directory, token, status, elapsed, cpu,
                               [directory / "log.lammps", directory / "run.out"],
                               directory / "run.out", variables, notes.get(directory, []))
        return outcome, elapsed, note


def run_partitions(batch, batch_dir, paths, env, ranks, extras, notes):
    """Points of one batch as the partitions of one lmp run, `ranks` MPI ranks each:
    [(outcome, wall seconds, note)]. Each partition's rank 0 writes its point's log and outputs.
    A LAMMPS ERROR in one partition aborts them all (MPI_Abort): a sibling without an ERROR of
    its own did not fail, its outcome is "rerun"; so is a point whose resume failed
    (set_aside_failed_resume: its next run takes the older checkpoint, or starts afresh). A
    point whose files the runner cannot write (a full disk) fails with that cause, and the
    others run without it."""
    results, prepared = {}, []     # prepared: [(directory, token, variables)]
    for point, directory in batch:
        token = secrets.token_hex(8)
        try:
            variables = resume_or_prepare(directory, point, extras[directory],
                                          keep=directory in notes)
            lines = [f"log {directory / 'log.lammps'}"]
            lines += [f"variable {name} index {format_value(value)}"
                      for name, value in {**point_variables(point, directory, paths, token),
                                          **variables}.items()]
            lines.append(f"include {point_deck(point)}")
            (directory / "settings.lmp").write_text("\n".join(lines) + "\n")
        except OSError as error:
            outcome, note = failed_to_start(directory, error)
            results[directory] = (outcome, 0.0, note)
            continue
        prepared.append((directory, token, variables))
    if prepared:
        try:
            results.update(run_batch(prepared, batch_dir, paths, env, ranks, notes))
        except OSError as error:
            for directory, _, _ in prepared:
                outcome, note = failed_to_start(directory, error)
                results[directory] = (outcome, 0.0, note)
    return [results[directory] for _, directory in batch]


def run_batch(prepared, batch_dir, paths, env, ranks, notes):
    """{directory: (outcome, wall seconds, note)} of the prepared points (run_partitions) run
    as the partitions of one lmp."""
    directories = [directory for directory, _, _ in prepared]
    batch_dir.mkdir(parents=True, exist_ok=True)
    driver = batch_dir / "driver.lmp"
    driver.write_text("variable point world " + " ".join(str(d) for d in directories) +
                      "\ninclude ${point}/settings.lmp\n")
    n = len(prepared)
    command = [paths["mpiexec"], "-np", str(n * ranks), str(paths["lammps"]), "-partition",
               f"{n}x{ranks}",
               "-in", str(driver), "-log", str(batch_dir / "log.lammps"), "-plog", "none",
               "-pscreen", "none", "-screen", "none", "-nocite"]
    for directory in directories:
        (directory / "command.txt").write_text(shlex.join(command) + "\n")

    def ended():    # every partition has written done.txt or an ERROR
        return all(wrote_done(d, t) or error_lines(d / "log.lammps") for d, t, _ in prepared)

    proc = processes.start(command, batch_dir / "run.out", env, directories)
    if proc is None:
        return {directory: ("stopped", 0.0, "") for directory in directories}
    status, elapsed, cpu, stuck = processes.wait(proc, directories, ended)
    note = (f" (mpirun stopped by the runner {processes.GRACE:g} s after every partition had "
            "ended: it does not return once a partition has quit)") if stuck else ""
    culprits = [d for d in directories if error_lines(d / "log.lammps")]
    results = {}
    for directory, token, variables in prepared:
        if culprits and directory not in culprits and not wrote_done(directory, token) \
                and not processes.stopped_by:
            results[directory] = ("rerun", elapsed, "its batch ended with the ERROR of " +
                                  ", ".join(d.name for d in culprits))
            continue
        failed_resume = not wrote_done(directory, token) and not processes.stopped_by and \
            set_aside_failed_resume(directory, variables)
        if failed_resume:
            notes.setdefault(directory, []).append(failed_resume)
            results[directory] = ("rerun", elapsed, failed_resume)
            continue
        # one process for the batch: its time is shared out equally
        outcome, said = finish(directory, token, status, elapsed, cpu / n,
                               [directory / "log.lammps", batch_dir / "log.lammps",
                                batch_dir / "run.out"], batch_dir / "run.out", variables,
                               notes.get(directory, []), note)
        results[directory] = (outcome, elapsed, said)
    return results


def check_slots(mpiexec, slots, env, asked):
    """mpirun's slots (mpirun_slots), asked before any point runs, for the processes one
    mpirun of the sweep starts (`asked`: the options that make them, for the message)."""
    problem = slots_problem([mpiexec, "-np", str(slots)], env)
    if problem:
        raise SweepError(f"{asked}: {problem}: use fewer partitions or ranks, or run under an "
                         "allocation or a hostfile with that many slots")


def run_points(plan, todo, output, paths, env, jobs, partitions, ranks, extra, model,
               processes_at_once):
    """Runs the points to do (todo: [(point, directory, cost.Size)] of the sweep's plan)
    as serial runs, `jobs` at a time, or `partitions` at a time as one mpirun's partitions,
    `ranks` ranks each, with a line per point that ends (the ETA: what the cost model predicts
    for the points left, over processes_at_once); the exit status (cli's docstring), with the
    sweep's last lines."""
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
            model.learn(point, predicted, elapsed * ranks)
        how = "FAILED" if outcome == "failed" else "done" if not stopped.exists() else \
            f"done (pile stopped: {stopped.read_text().strip()})"
        remaining = sum(model.predict(p, s) for p, s in unfinished.values()) / processes_at_once
        on = f" on {ranks} ranks" if ranks > 1 else ""
        why = f" ({note})" if outcome == "failed" and note else ""
        print(f"[{len(todo) - len(unfinished)}/{len(todo)}] {how} "
              f"{directory.relative_to(output)} in {elapsed:.1f} s{on}{why}; "
              f"ETA {format_seconds(remaining)}", flush=True)

    refused = []    # points whose directory became another's during the sweep: not run
    # runs start in pool threads only: the main thread takes the signals
    with concurrent.futures.ThreadPoolExecutor(max_workers=1 if partitions else jobs) as pool:
        try:
            if partitions:
                queue, number = list(todo), 0
                while queue and not processes.stopped_by:
                    batch, queue = queue[:partitions], queue[partitions:]
                    results = pool.submit(run_partitions, [(p, d) for p, d, _ in batch],
                                          output / "batches" / f"batch{number}", paths, env,
                                          ranks, extra, resume_notes).result()
                    number += 1
                    for (p, d, s), (outcome, elapsed, note) in zip(batch, results):
                        if outcome == "rerun":
                            queue.append((p, d, s))
                        # each point of the batch ran for the batch's wall time
                        report(p, d, model.predict(p, s), outcome, elapsed, note)
            else:
                futures = {pool.submit(run_serial, p, d, paths, env, ranks, extra[d],
                                       resume_notes): (p, d, s)
                           for p, d, s in todo}
                for future in concurrent.futures.as_completed(futures):
                    p, d, s = futures[future]
                    try:
                        report(p, d, model.predict(p, s), *future.result())
                    except SweepError as error:    # its place taken while the sweep ran
                        print(f"sweep: {error}", file=sys.stderr)
                        refused.append(d)
        except BaseException:
            # the pool's end waits for its threads: no run starts any more, those under way stop
            processes.stop_runs(None)
            raise

    if processes.stopped_by:
        print(f"sweep: stopped by {signal.Signals(processes.stopped_by[0]).name}; "
              f"{len(unfinished)} points not done: the same command runs them", file=sys.stderr)
        return 128 + processes.stopped_by[0]
    if refused:
        print(f"sweep: {len(refused)} points not run, their directories not the runner's to "
              "remove (above); the other points ran", file=sys.stderr)
        return 2
    if failures:
        print(f"sweep: {len(failures)} points failed (their lines above say why); see "
              "failed.txt in:", file=sys.stderr)
        for d in failures:
            print(f"  {d}", file=sys.stderr)
        return 1
    print(f"sweep: all {len(plan)} points done in {output}; they took "
          f"{cpu_seconds(d for _, d, _ in plan) / 3600:.3g} CPU-hours")
    return 0
