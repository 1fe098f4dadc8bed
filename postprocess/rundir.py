"""A sweep point's directory, <output>/<scene>/<point>/ (docs/scenes.md, docs/sweeps.md): its
name, the names of its files and what state it is in, for the sweep runner (scripts/sweep.py)
and the post-processing alike. Standard library only: the runner imports it without numpy.

A run's identity is its point.json: the scene and the deck variables the runner set, written
before the run starts. Everything else that names the run is derived from it (run_name: its
directory, its summary's file) or checked against it on reading (postprocess.io: the directory's
or summary's name, and params.txt, where the deck prints the variables it was given).

The states of a point, from its files:

completed  done.txt (the deck's last output) and timing.json (the runner's, written once it saw
           that run end) carry the token of one run, or (from a runner before tokens) neither
           has one. A completed run either ran to run_time ("flowing" in the analysis) or ended
           early because its pile stopped ("stopped": stopped.txt).
failed     not completed, and the runner wrote failed.txt (lmp's exit status, the ERROR lines).
running    neither, and running.json names the process of a run under way (the runner checks
           that process is still alive before it trusts it; the analysis cannot tell a run under
           way from one killed before its end, and calls both incomplete).
incomplete neither completed nor failed: not run yet, under way, or stopped before its end (a
           sweep stopped by a signal leaves its points so: the next sweep runs them again).
"""
import json
import re
from pathlib import Path

POINT = "point.json"        # the deck variables the runner passes (it writes this first)
PARAMS = "params.txt"       # every value the deck derived
ENERGY = "energy.txt"
COUNTS = "counts.txt"
ROWS = "contacts.txt"       # fix contacts/mn's rows (-var rows yes)
PROFILE = "profile.txt"
PROFILE_CHUNKS = "profile_chunks.txt"   # the profile of a run with checkpoints, per chunk
TRAJECTORY = "trajectory.txt"
STOPPED = "stopped.txt"     # the pile stopped: the run ended early
DONE = "done.txt"           # the deck's last output, with the run's token
TIMING = "timing.json"      # the runner's, once it saw the run end: the wall and CPU seconds
                            # of it and of the runs it resumed from, and its token
EARLIER_RUNS = "earlier_runs.json"  # the runner's: the seconds of the point's runs that ended
                                    # before it completed (a resumed run went on from them)
FAILED = "failed.txt"       # the runner's, for a run that failed
RUNNING = "running.json"    # the runner's, while a run of the point is under way
LOG = "log.lammps"
# A point's summary (postprocess summarize) is named by the point: <scene>/<point>.json, so a
# point's name must leave room for it
SUMMARY_SUFFIX = ".json"


def format_value(value):
    """A value as the deck and the point's name get it: %g where that is exact, else every
    digit (1234567.8 is not 1.23457e+06); an integer and its float alike (1e6 is 1000000)."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return str(value)
    short = f"{float(value):g}"
    if float(short) == value:
        return short
    return str(int(value)) if float(value).is_integer() and abs(value) < 2 ** 53 else repr(value)


def point_name(variables):
    """A point's directory name (and its summary's, with SUMMARY_SUFFIX): its variables but the
    scene, sorted, each name followed by its value."""
    return "_".join(f"{k}{format_value(v)}" for k, v in sorted(variables.items()) if k != "scene")


def run_name(variables):
    """How a run is known, <scene>/<point>, from its point.json's variables: where the runner
    puts its directory and summarize its summary, and what the reports call it."""
    return f"{variables['scene']}/{point_name(variables)}"


def read_timing(directory):
    """timing.json's record (seconds, cpu_seconds, the run's token), or None if there is none."""
    try:
        timing = json.loads((Path(directory) / TIMING).read_text())
    except (OSError, ValueError):
        return None
    return timing if isinstance(timing, dict) else None


_UNREAD = object()


def completed(directory, timing=_UNREAD):
    """Whether a point's outputs are those of a run that ended (see the module's docstring);
    timing: its read_timing, if read already."""
    directory = Path(directory)
    timing = read_timing(directory) if timing is _UNREAD else timing
    try:
        done = (directory / DONE).read_text()
    except OSError:
        return False
    token = re.search(r"\brun (\w+)", done)
    return timing is not None and timing.get("run") == (token and token.group(1))


def ending(directory, timing=_UNREAD):
    """How a point's run ended, before its outputs are read: ('completed', None), ('failed',
    the exit status failed.txt gives and lmp's last ERROR line), else ('incomplete', None).
    timing: its read_timing, if read already."""
    directory = Path(directory)
    if completed(directory, timing):
        return "completed", None
    path = directory / FAILED
    if not path.exists():
        return "incomplete", None
    lines = path.read_text(errors="replace").splitlines()
    # lmp run with -screen none prints its errors only to its log
    log = directory / LOG
    for said in (lines, log.read_text(errors="replace").splitlines() if log.exists() else []):
        errors = [l.strip() for l in said if l.startswith("ERROR")]
        if errors:
            break
    return "failed", "; ".join(([lines[0].strip()] if lines else []) + errors[-1:])


def incomplete_reason(state, failure):
    """Why a run that did not complete has no outputs to analyse (state, failure: ending's)."""
    return (f"crashed ({failure}; see {FAILED})" if state == "failed"
            else f"did not complete (no {DONE} and {TIMING} of one run)")
