"""The output directory and its points' directories: the paths LAMMPS can carry, the names the
filesystem takes, the lock, which directories the runner may remove, a point's fresh start or
resume from its checkpoint, a failed resume set aside, a run's outcome (done.txt, timing.json,
failed.txt) and its cause."""
import errno
import fcntl
import json
import os
import re
import shutil
import signal

from . import checkpoints
from . import SweepError
from . import processes
from postprocess.rundir import DONE, EARLIER_RUNS, FAILED, POINT, SUMMARY_SUFFIX, TIMING

# What LAMMPS's input syntax does not carry in a file name: a word ends at whitespace;
# quotes, $ (a variable) and # (a comment) are syntax.
PATH_SYNTAX = {" ": "a space", "\t": "a tab", "\n": "a newline", '"': "a quote (\")",
               "'": "a quote (')", "$": "a $", "#": "a #"}


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


def name_limit(output):
    """The longest file name, in bytes, that the filesystem of `output` (or of the nearest
    directory above it that exists) takes: its PC_NAME_MAX; 255, the common limit, where the
    system does not say; None where it sets none."""
    for path in (output, *output.parents):
        if path.is_dir():
            try:
                limit = os.pathconf(path, "PC_NAME_MAX")
            except (OSError, ValueError, AttributeError):
                return 255
            return limit if limit > 0 else None
    return 255


def check_names(output, names):
    """names: [(scene, point name)]. A point's directory is named by its variables, and its
    summary (postprocess summarize) by the point: both must fit the filesystem's limit on a
    name, or the point would fail at its start (ENAMETOOLONG), after the points before it had
    run. The names are kept whole (the name is how a run is known, in its summary and the
    reports): a point whose name does not fit is refused."""
    limit = name_limit(output)
    if limit is None:
        return
    size = {name: len(os.fsencode(name)) for _, name in names}
    over = [(scene, name) for scene, name in names
            if size[name] + len(os.fsencode(SUMMARY_SUFFIX)) > limit]
    if over:
        scene, name = max(over, key=lambda point: size[point[1]])
        raise SweepError(
            f"{len(over)} point{'s with names' if len(over) > 1 else ' with a name'} too long "
            f"for the filesystem of {output}, which takes names of at most {limit} bytes: "
            f"{scene}/{name[:60]}... is {size[name]} bytes, and its summary "
            f"<point>{SUMMARY_SUFFIX} must fit too (a point's directory is named by all its "
            "variables, those of [defaults] and --set included): set fewer variables (one at "
            "its deck's default need not be set) or shorter values")


def foreign(directory, point):
    """Why the runner may not remove a point's directory to run the point afresh, or None: it
    removes only a directory it made for a point of this scene (point.json, the first file it
    writes there) that holds files alone (a run writes no folder: one is someone else's), or one
    holding nothing but perhaps an empty point.json (nothing to lose)."""
    if not directory.exists():
        return None
    if not directory.is_dir():
        return "it is a file"
    entries = list(directory.iterdir())
    if not entries or (len(entries) == 1 and entries[0].name == POINT
                       and entries[0].is_file() and entries[0].stat().st_size == 0):
        return None     # a runner stopped between making the directory and writing point.json
    try:
        record = json.loads((directory / POINT).read_text())
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
    remove (foreign) is refused (cli.main() refuses the sweep before any point runs)."""
    why = foreign(directory, point)
    if why:
        raise SweepError(f"{directory} is not the runner's to remove: {why}; move it away")
    if directory.exists():
        shutil.rmtree(directory)
    directory.mkdir(parents=True)
    try:
        (directory / POINT).write_text(json.dumps(point, indent=1, sort_keys=True) + "\n")
    except OSError:
        # a point.json cut short (a full disk) would make the directory not the runner's
        shutil.rmtree(directory, ignore_errors=True)
        raise
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
        same_point = json.loads((directory / POINT).read_text()) == point
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
        return re.search(rf"\brun {token}\b", (directory / DONE).read_text()) is not None
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


def describe(error, path=None):
    """An OSError in words: its message, its errno's name, the file (No space left on device
    (ENOSPC): <path>); `path` where the error names none (a write, not an open, failed)."""
    name = errno.errorcode.get(error.errno)
    path = error.filename or path
    return (f"{error.strerror or error}" + (f" ({name})" if name else "") +
            (f": {path}" if path else ""))


# Bytes: a filesystem with less free than this is full for a run, which writes MBs. A write that
# failed for want of space leaves some free (a buffer's worth short of the next block, blocks
# a truncation gave back), so "no byte free" would miss it.
FULL = 1 << 20


def free_space(directory):
    """(bytes, inodes) free to this user on the filesystem holding `directory` (inodes None
    where it does not count them), or None if it cannot be told."""
    try:
        found = os.statvfs(directory)
    except OSError:
        return None
    root = os.geteuid() == 0    # root may use the blocks kept for it
    blocks = found.f_bfree if root else found.f_bavail
    inodes = (found.f_ffree if root else found.f_favail) if found.f_files else None
    return blocks * found.f_frsize, inodes


def cut_mid_line(path):
    """Whether a file ends inside a line: its writes stopped there (a full disk, a quota)."""
    try:
        with open(path, "rb") as handle:
            handle.seek(0, os.SEEK_END)
            if handle.tell() == 0:
                return False
            handle.seek(-1, os.SEEK_END)
            return handle.read(1) != b"\n"
    except OSError:
        return False


def done_state(directory, token):
    """What done.txt, the deck's last output, is in a run that did not write it with its
    token."""
    try:
        text = (directory / DONE).read_text(errors="replace")
    except FileNotFoundError:
        return "done.txt, the deck's last output, is missing"
    except OSError as error:
        return f"done.txt cannot be read ({describe(error)})"
    if not text.strip():
        return "done.txt, the deck's last output, is empty"
    return f"done.txt is another run's (not of this run's token {token})"


def failure_cause(directory, token, status, errors):
    """(what went wrong beyond lmp's ERROR lines, or None; what to do) of a run that did not
    write done.txt with its token: a full filesystem, a signal, a log cut short (lmp writes its
    ERROR only to log.lammps: -screen none), or an end without an ERROR."""
    again = (": it runs this point from its newest checkpoint if it has one, else afresh "
             "(remove this directory to start it afresh)")
    done = done_state(directory, token)
    lost = "" if errors or status == 0 else \
        " (lmp's ERROR went with them: it writes it to log.lammps only)"
    free = free_space(directory)
    if free is not None and (free[0] < FULL or free[1] == 0):
        what = f"{free[0]} bytes free" if free[0] < FULL else "no inode free"
        return (f"the filesystem of {directory} is full ({what}: ENOSPC), and {done}: the "
                f"run's outputs are cut short{lost}",
                "free space there (or choose another --output), then run the sweep again" +
                again)
    if errors:
        return None, "mend what the ERROR names, then run the sweep again" + again
    if status < 0:
        try:
            name = signal.Signals(-status).name
        except ValueError:
            name = f"signal {-status}"
        return (f"lmp was killed by {name} (out of memory, or a signal from another process?), "
                f"and {done}",
                "see what killed it (the kernel's log names what its out-of-memory killer "
                "killed), then run the sweep again" + again)
    if status != 0 and cut_mid_line(directory / "log.lammps"):
        return (f"log.lammps ends inside a line: lmp's writes failed (a disk that was full, or "
                f"a quota){lost}, and {done}",
                f"check the space and quota of the filesystem of {directory}, then run the "
                "sweep again" + again)
    if status == 0:
        return (f"lmp ended without an ERROR, but {done}: its writes failed (a disk that was "
                "full, or a quota: LAMMPS does not check all its writes), or the deck ended "
                "before its last output",
                f"check the space and quota of the filesystem of {directory} and the end of "
                "log.lammps, then run the sweep again" + again)
    return (f"lmp ended without an ERROR line, and {done}",
            "see the end of the output below and of log.lammps, then run the sweep again" +
            again)


def write_failed(directory, text):
    """failed.txt with `text`; the note on the failure for the progress line (its first line),
    which also says where failed.txt could not be written (a full disk: no file is left
    half-written, the point then reads as not completed)."""
    note = text.split("\n", 1)[0]
    try:
        (directory / FAILED).write_text(text)
    except OSError as error:
        (directory / FAILED).unlink(missing_ok=True)
        note += (f"; failed.txt could not be written "
                 f"({describe(error, directory / FAILED)})")
    return note


def failed_to_start(directory, error):
    """("failed", note) of a point whose run the runner could not start: it could not write
    the point's files (point.json, command.txt, running.json, ...: a full disk, no
    permission). failed.txt says so where the directory is there (prepare removes one whose
    point.json it could not write)."""
    said = f"the runner could not write the point's files: {describe(error)}"
    if not directory.is_dir():
        return "failed", said
    return "failed", write_failed(directory, said + "\nwhat to do: mend that (free space, or "
                                  "choose another --output), then run the sweep again\n")


def earlier_runs(directory):
    """{"seconds", "cpu_seconds", "runs"} summed over the point's runs that ended before it
    completed (stopped, failed; EARLIER_RUNS), so that the run that completes, resumed from
    their checkpoints, records what the point cost in all, not its own part alone; zeros
    where there were none (a fresh start's directory is new)."""
    try:
        return json.loads((directory / EARLIER_RUNS).read_text())
    except (OSError, ValueError):
        return {"seconds": 0.0, "cpu_seconds": 0.0, "runs": 0}


def finish(directory, token, status, elapsed, cpu, logs, output, variables, notes, note=""):
    """A point's outcome, and a note on it for the progress line: "done" (done.txt carries the
    run's token; timing.json is written with it: the wall and CPU seconds of this run and of
    the earlier ones it resumed from, and how many runs they were), "stopped" (by a signal to
    the sweep; its seconds added to EARLIER_RUNS), else
    "failed" (failed.txt: the exit status and the cause (failure_cause: a full disk, a signal,
    an end without an ERROR), the ERROR lines of logs, how the run began (afresh or from which
    checkpoint) and what went before it (notes: failed resumes), what to do, the end of
    output; the note: its first line and first ERROR). A write that fails here (timing.json,
    failed.txt: a full disk) fails the point with its cause."""
    aside = kept_aside(directory)
    earlier = earlier_runs(directory)
    total = {"seconds": earlier["seconds"] + elapsed,
             "cpu_seconds": earlier["cpu_seconds"] + cpu, "runs": earlier["runs"] + 1}
    if wrote_done(directory, token):
        try:
            (directory / TIMING).write_text(json.dumps({**total, "run": token}) + "\n")
        except OSError as error:
            (directory / TIMING).unlink(missing_ok=True)
            return "failed", write_failed(
                directory, f"exit status {status}{note}: the run completed, but the runner "
                f"could not write timing.json: {describe(error, directory / TIMING)}\n"
                "what to do: free space there (or choose another --output), then run the "
                "sweep again: it runs this point again\n")
        # a fresh start that completed: the run it replaced is of no more use
        if notes and "resume" not in variables and aside.exists() and \
                not foreign(aside, json.loads((directory / POINT).read_text())):
            shutil.rmtree(aside)
            try:    # unresumed/<scene>/ and unresumed/, if nothing else is kept there
                os.removedirs(aside.parent)
            except OSError:
                pass
        return "done", ""
    if processes.stopped_by:
        record_earlier_runs(directory, total)
        return "stopped", ""
    errors = error_lines(*logs)
    cause, todo = failure_cause(directory, token, status, errors)
    errors = errors or [f"(no ERROR line in {', '.join(str(p) for p in logs)})"]
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
    said = write_failed(
        directory, f"exit status {status}{note}" + (f": {cause}" if cause else "") + "\n" +
        "\n".join(errors) + f"\nthis run began {began}\n" + history + f"what to do: {todo}\n"
        f"--- the end of {output}\n{printed[-40000:]}\n")
    record_earlier_runs(directory, total)
    return "failed", said if cause else f"{said}; {errors[0]}"


def record_earlier_runs(directory, total):
    """EARLIER_RUNS of a point whose run ended without completing, after what it says of its
    end (failed.txt comes first where the disk is full)."""
    try:
        (directory / EARLIER_RUNS).write_text(json.dumps(total) + "\n")
    except OSError:
        # a full disk: the point has failed or stopped with that said; only its cost is short
        (directory / EARLIER_RUNS).unlink(missing_ok=True)


def lock_output(output):
    """Holds <output>/sweep.lock while the sweep runs (an flock: the kernel lets go when the
    runner dies, kill -9 included); two sweeps on one output would run its points twice at
    once. unlock_output removes the file: a lock taken on a file removed meanwhile is taken
    again on the file now there."""
    path = output / "sweep.lock"
    while True:
        try:
            output.mkdir(parents=True, exist_ok=True)
            handle = open(path, "a+")
        except OSError as error:    # made a file since check_output, or not writable
            raise SweepError(f"--output {output}: {error.strerror}; choose another --output")
        try:
            fcntl.flock(handle, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            handle.seek(0)
            holder = handle.read().strip() or "unknown"
            handle.close()
            raise SweepError(f"{output} is in use by another sweep (pid {holder}, {path}): let "
                             "it end or stop it")
        try:
            held = os.fstat(handle.fileno())
            there = os.stat(path)
        except FileNotFoundError:
            there = None
        if there is not None and (held.st_dev, held.st_ino) == (there.st_dev, there.st_ino):
            break
        handle.close()      # the sweep that held it removed it: lock the one now there
    handle.truncate(0)
    handle.write(f"{os.getpid()}\n")
    handle.flush()
    return handle


def unlock_output(handle):
    """Lets go of the lock lock_output took, removing sweep.lock (while still holding it)."""
    if handle is None:
        return
    try:
        os.unlink(handle.name)
    except OSError:
        pass
    handle.close()


def cpu_seconds(directories):
    """CPU seconds the completed points took, from their timing.json."""
    total = 0.0
    for d in directories:
        try:
            total += json.loads((d / TIMING).read_text()).get("cpu_seconds", 0.0)
        except (OSError, ValueError):
            pass
    return total
