"""The runner's lmp processes: each run a session of its own that dies with the runner,
started, waited for and stopped here; the sweep's stop on SIGTERM or SIGINT."""
import ctypes
import json
import os
import signal
import subprocess
import threading
import time
from pathlib import Path

from postprocess.rundir import RUNNING

# The runs under way, {pid: Popen}. Each run (lmp, or mpirun and the ranks it starts, each of
# those in a process group of its own) is a session of its own: a signal reaches all of it.
_runs = {}
_runs_lock = threading.RLock()   # the signal handler takes it too, in the main thread
stopped_by = []                 # what stopped the sweep: a signal, or None (the runner failed)
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
        keep_niceness()
    return setup


def keep_niceness():
    """A run has a session of its own (start_new_session: a signal reaches all it starts).
    Where the kernel schedules each session as a group of its own (Linux's autogroup), the
    niceness it inherits from the runner (`nice -n 19 python3 -m scripts.sweep`) would weigh only
    within that group, and the run would take a full share of a core: the group is given the
    same niceness."""
    niceness = os.nice(0)
    if niceness > 0:
        try:
            with open("/proc/self/autogroup", "w") as group:
                group.write(str(niceness))
        except OSError:
            pass    # no autogroup here: the niceness already applies


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


def stop_runs(cause):
    """No run is started any more and the runs under way are stopped (SIGTERM); their points
    are run again when the sweep is. cause: the signal's number, None where the runner itself
    failed."""
    with _runs_lock:
        stopped_by.append(cause)
        for pid in _runs:
            signal_session(pid, SIGTERM)


def stop(signum, frame):
    """SIGTERM, SIGINT: the sweep stops (stop_runs)."""
    stop_runs(signum)


def start(command, output, env, directories):
    """Starts a run with what it prints in `output`, unless the sweep is stopping; the
    directories' running.json names it. Where running.json cannot be written (a full disk),
    the run is stopped and the OSError raised: no run goes on that nothing names."""
    with _runs_lock:
        if stopped_by:
            return None
        with open(output, "w") as out:
            proc = subprocess.Popen(command, stdout=out, stderr=subprocess.STDOUT, env=env,
                                    start_new_session=True, preexec_fn=die_with(os.getpid()))
        _runs[proc.pid] = proc
    record = json.dumps({"pid": proc.pid, "start": process_start(proc.pid)}) + "\n"
    try:
        for directory in directories:
            (directory / RUNNING).write_text(record)
    except OSError:
        signal_session(proc.pid, signal.SIGKILL)
        wait(proc, directories)
        raise
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
        if deadline is None and (stopped_by or ended()):
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
