"""The sweep runner (scripts/granmn_sweep) where it needs no lmp: a config or --set that cannot
be a run, point names the filesystem cannot take, a point whose files or whose run's outputs
cannot be written (a full disk). tests/lammps/test_sweep.py runs points."""
import errno
import json
import os
import pathlib
import subprocess
import sys
from pathlib import Path

import pytest

from scripts.granmn_sweep import SweepError, processes
from scripts.granmn_sweep import points as runner_points
from postprocess.rundir import completed

ROOT = Path(__file__).resolve().parents[2]
SWEEP = [sys.executable, "-m", "scripts.sweep"]    # run from ROOT

TWO_POINTS = '[[grid]]\nscene = "single_disk"\nkn = [5e4, 1e5]\n'
# a point of many variables, each with every digit: its name, its variables, is 312 bytes
LONG_NAME = ("[defaults]\nkn = 123456.78901234567\ne = 0.71234567890123456\n"
             "beta = 0.712345678901234567\nmu = 0.51234567890123456\n"
             "sin_theta = 0.451234567890123456\nrun_time = 1700.1234567890123\n"
             "average_start = 200.12345678901234\noutput_interval = 0.11234567890123456\n"
             "snapshot_interval = 10.123456789012345\nprofile_bin = 0.25123456789012345\n"
             "dt_fraction = 0.0112345678901234567\nseed = 1\n"
             '[[grid]]\nscene = "collisional_flow"\n')

# {case: ((config, options), message)}: refused with exit status 2 before anything is made or
# run (the build is not needed to refuse them: the runner is given none here)
BAD_SETTINGS = {
    "`run_time = inf` (TOML's inf, or nan; it was refused as `must be > 0`)": (
        ('[[grid]]\nscene = "single_disk"\nrun_time = inf\n', []),
        "grid 1: run_time = inf is not a finite number"),
    "`--set run_time=inf`": (
        (TWO_POINTS, ["--set", "run_time=inf"]),
        "--set run_time=inf: single_disk point: run_time = 'inf' is not a finite number"),
    "`--set out=DIR`, a variable the runner sets (it was blamed on grid 1 of the config)": (
        (TWO_POINTS, ["--set", "out=/tmp"]),
        "--set out=/tmp: out is set by the sweep runner itself (--output, --build), not by "
        "--set"),
    "`--set` of one variable twice (the last was kept, silently)": (
        (TWO_POINTS, ["--set", "run_time=5", "--set", "run_time=6"]),
        "--set run_time=6: run_time is set twice (--set run_time=5 too): which value is meant "
        "cannot be told"),
    "`--set` of a variable the scene's deck does not have (it was blamed on grid 1)": (
        (TWO_POINTS, ["--set", "sin_thetaa=0.2"]),
        "--set sin_thetaa=0.2: sin_thetaa: not a variable of inputs/single_disk.lmp"),
    "a point whose name, its variables, is longer than the output's filesystem takes with "
    "room for its summary `<point>.json` (PC_NAME_MAX, 255 bytes; the run ended in a traceback "
    "and left sweep.lock)": (
        (LONG_NAME, []),
        "1 point with a name too long for the filesystem of"),
    "an event-driven point that sets a deck variable only LAMMPS reads (its integrator)": (
        ('[[grid]]\nscene = "collisional_flow"\nengine = "event_driven"\nseed = 1\n'
         'integrator = "ab2"\n', []),
        "integrator: the event-driven engine does not use it"),
    "an event-driven point of the 3D chute (the engine is 2D)": (
        ('[[grid]]\nscene = "chute_3d"\nengine = "event_driven"\nseed = 1\n', []),
        "unknown scene 'chute_3d' of engine event_driven"),
    "the same with --dry-run (it listed the point)": (
        (LONG_NAME, ["--dry-run"]),
        "1 point with a name too long for the filesystem of"),
}


@pytest.mark.parametrize("case", sorted(BAD_SETTINGS))
def test_a_setting_that_cannot_be_a_run_is_refused_by_its_source(tmp_path, case):
    (text, options), message = BAD_SETTINGS[case]
    config = tmp_path / "sweep.toml"
    config.write_text(text)
    proc = subprocess.run(SWEEP + [str(config), "--output", str(tmp_path / "out"), "--build",
                                   str(tmp_path / "no_build"), *options],
                          cwd=ROOT, capture_output=True, text=True, timeout=60)
    assert proc.returncode == 2 and message in proc.stderr, proc.stdout + proc.stderr
    assert "Traceback" not in proc.stderr
    assert not (tmp_path / "out").exists()      # no point made, no sweep.lock


def test_the_long_name_refusal_says_the_limit_and_the_remedy(tmp_path):
    config = tmp_path / "sweep.toml"
    config.write_text(LONG_NAME)
    proc = subprocess.run(SWEEP + [str(config), "--output", str(tmp_path / "out"), "--build",
                                   str(tmp_path / "no_build"), "--dry-run"],
                          cwd=ROOT, capture_output=True, text=True, timeout=60)
    limit = os.pathconf(tmp_path, "PC_NAME_MAX")
    assert f"which takes names of at most {limit} bytes: collisional_flow/average_start200." \
        in proc.stderr and "is 312 bytes" in proc.stderr, proc.stderr
    assert "set fewer variables (one at its deck's default need not be set)" in proc.stderr


def test_names_that_fit_are_kept_whole_and_one_byte_more_is_refused(tmp_path, monkeypatch):
    """A name and its summary's, <point>.json, fit the filesystem's limit: 15 + 5 bytes of 20
    pass (and no point is renamed: the runner names a point by its variables alone), 16 are
    refused naming the longest."""
    monkeypatch.setattr(runner_points.os, "pathconf", lambda path, name: 20)
    runner_points.check_names(tmp_path, [("single_disk", "k" * 15)])
    with pytest.raises(SweepError, match=r"^2 points with names too long for the filesystem of "
                                         r".*, which takes names of at most 20 bytes: "
                                         r"single_disk/k{17}\.\.\. is 17 bytes"):
        runner_points.check_names(tmp_path, [("single_disk", "k" * 15),
                                             ("single_disk", "k" * 16),
                                             ("single_disk", "k" * 17)])


# ---- a run whose outputs could not be written, a point whose files cannot be

TOKEN = "0123456789abcdef"


def a_run_that_ended(tmp_path, done):
    """A point's directory as a run of it leaves it, without an ERROR: done.txt holds `done`
    (None: there is none)."""
    directory = tmp_path / "out" / "single_disk" / "kn50000"
    directory.mkdir(parents=True)
    (directory / "point.json").write_text(json.dumps({"scene": "single_disk", "kn": 50000}))
    (directory / "log.lammps").write_text("LAMMPS (29 Sep 2021)\n")
    (directory / "run.out").write_text("")
    if done is not None:
        (directory / "done.txt").write_text(done)
    return directory


def finish(directory, status=0):
    return runner_points.finish(directory, TOKEN, status, 1.0, 1.0,
                                [directory / "log.lammps", directory / "run.out"],
                                directory / "run.out", {}, [])


def full_filesystem(monkeypatch):
    """statvfs says: no block left (as on a full disk, for root and for a user alike)."""
    real = os.statvfs

    def statvfs(path):
        found = real(path)
        return os.statvfs_result((found.f_bsize, found.f_frsize, found.f_blocks, 0, 0,
                                  found.f_files, found.f_ffree, found.f_favail, found.f_flag,
                                  found.f_namemax))
    monkeypatch.setattr(runner_points.os, "statvfs", statvfs)


def failing_writes(monkeypatch, *names):
    """Path.write_text of the files named fails as on a full disk (ENOSPC), leaving the file
    created and empty, as such a write does."""
    write = pathlib.Path.write_text

    def write_text(path, *args, **kwargs):
        if path.name in names:
            path.touch()
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC), str(path))
        return write(path, *args, **kwargs)
    monkeypatch.setattr(pathlib.Path, "write_text", write_text)


@pytest.mark.parametrize("done,status", [("", 0), (None, 0), (None, 1)],
                         ids=["empty", "missing", "exit status 1"])
def test_a_run_on_a_full_disk_fails_with_that_cause(tmp_path, monkeypatch, done, status):
    """lmp exits 0 on a full disk where LAMMPS does not check its writes, and 1 where it does
    (fix ave/chunk: its ERROR lost with the log it writes it to), leaving done.txt empty or
    missing: failed.txt said "exit status 0" (1), "no ERROR line", "mend what the ERROR
    names"."""
    directory = a_run_that_ended(tmp_path, done)
    full_filesystem(monkeypatch)
    outcome, note = finish(directory, status)
    state = "empty" if done == "" else "missing"
    first = (f"exit status {status}: the filesystem of {directory} is full (0 bytes free: "
             f"ENOSPC), and done.txt, the deck's last output, is {state}: the run's outputs are "
             "cut short" + (" (lmp's ERROR went with them: it writes it to log.lammps only)"
                            if status else ""))
    failed = (directory / "failed.txt").read_text()
    assert outcome == "failed" and note == first and failed.startswith(first + "\n"), failed
    assert "what to do: free space there (or choose another --output)" in failed
    assert "mend what the ERROR names" not in failed


def test_a_log_cut_inside_a_line_says_the_writes_failed(tmp_path):
    """A run that ended with status 1 and no ERROR line, its log.lammps cut inside a line (the
    disk was full when it wrote, and has room again): its ERROR went with the log."""
    directory = a_run_that_ended(tmp_path, None)
    (directory / "log.lammps").write_text("LAMMPS (29 Sep 2021)\nfix trajectory all print 10")
    outcome, note = finish(directory, 1)
    assert outcome == "failed" and note == (
        "exit status 1: log.lammps ends inside a line: lmp's writes failed (a disk that was "
        "full, or a quota) (lmp's ERROR went with them: it writes it to log.lammps only), and "
        "done.txt, the deck's last output, is missing"), note


def test_a_run_that_ends_without_error_or_done_txt_says_what_it_left(tmp_path):
    directory = a_run_that_ended(tmp_path, "")
    outcome, note = finish(directory)
    assert outcome == "failed" and note.startswith(
        "exit status 0: lmp ended without an ERROR, but done.txt, the deck's last output, is "
        "empty: its writes failed (a disk that was full, or a quota: LAMMPS does not check all "
        "its writes), or the deck ended before its last output"), note
    failed = (directory / "failed.txt").read_text()
    assert failed.startswith(note + "\n") and "mend what the ERROR names" not in failed
    assert "what to do: check the space and quota of the filesystem of" in failed


def test_a_failed_txt_that_cannot_be_written_is_said_on_the_progress_line(tmp_path,
                                                                         monkeypatch):
    """The runner's own write of failed.txt on a full disk raised OSError (a traceback, the
    sweep ended with its runs' results unreported): the point fails, its note says both."""
    directory = a_run_that_ended(tmp_path, "")
    full_filesystem(monkeypatch)
    failing_writes(monkeypatch, "failed.txt")
    outcome, note = finish(directory)
    assert outcome == "failed" and "is full (0 bytes free: ENOSPC)" in note, note
    assert note.endswith(f"; failed.txt could not be written (No space left on device (ENOSPC): "
                         f"{directory / 'failed.txt'})"), note
    assert not (directory / "failed.txt").exists()      # no half-written file


def test_a_timing_json_that_cannot_be_written_fails_the_point(tmp_path, monkeypatch):
    """A run that wrote done.txt, the runner's timing.json failing (ENOSPC): the point is not
    complete (a rerun), and says so; the write raised OSError."""
    directory = a_run_that_ended(tmp_path, f"kn 50000 steps 1 dt 1 run {TOKEN}\n")
    failing_writes(monkeypatch, "timing.json")
    outcome, note = finish(directory)
    assert outcome == "failed" and note == (
        "exit status 0: the run completed, but the runner could not write timing.json: No space "
        f"left on device (ENOSPC): {directory / 'timing.json'}"), note
    assert not (directory / "timing.json").exists() and not completed(directory)
    assert (directory / "failed.txt").read_text().startswith(note + "\n")


def test_a_point_whose_files_cannot_be_written_fails_and_the_sweep_goes_on(tmp_path,
                                                                          monkeypatch):
    """A point's files failing to be written (ENOSPC) raised out of the runner's thread: the
    sweep ended in a traceback. The point fails with the cause; nothing runs for it; a
    point.json cut short is not left behind (it would make the directory not the runner's to
    remove, and the point refused when the sweep is run again)."""
    from scripts.granmn_sweep.schedule import run_serial
    point = {"scene": "single_disk", "kn": 50000}
    directory = tmp_path / "out" / "single_disk" / "kn50000"
    for name in ("point.json", "command.txt"):
        with monkeypatch.context() as patch:
            failing_writes(patch, name)
            outcome, elapsed, note = run_serial(point, directory, {"plugin": "p", "lammps": "l"},
                                                {}, 1, {}, {})
        assert outcome == "failed" and note == (
            "the runner could not write the point's files: No space left on device "
            f"(ENOSPC): {directory / name}"), note
        if name == "point.json":
            assert not directory.exists()
        else:
            assert (directory / "failed.txt").read_text().startswith(note + "\n")
            assert runner_points.foreign(directory, point) is None   # the runner's to rerun


def test_a_point_directory_left_before_its_point_json_is_the_runners(tmp_path):
    """A runner killed between making a point's directory and writing its point.json left a
    directory the next sweep refused as someone else's: one holding nothing, or only an empty
    point.json, is the runner's to remove and run afresh; one holding anything else is not."""
    point = {"scene": "single_disk", "kn": 50000}
    directory = tmp_path / "single_disk" / "kn50000"
    directory.mkdir(parents=True)
    assert runner_points.foreign(directory, point) is None
    (directory / "point.json").touch()
    assert runner_points.foreign(directory, point) is None
    runner_points.prepare(directory, point, {})
    assert json.loads((directory / "point.json").read_text()) == point
    (directory / "point.json").write_text("")
    (directory / "notes.txt").write_text("a user's\n")
    assert "no point.json" in runner_points.foreign(directory, point)


def test_a_run_whose_running_json_cannot_be_written_is_stopped(tmp_path, monkeypatch):
    """running.json names a run's process (a later sweep must not start a point under it): a
    run it cannot name is stopped at once, and the OSError raised (the point fails with it);
    the process went on, unnamed and unwaited for."""
    failing_writes(monkeypatch, "running.json")
    with pytest.raises(OSError, match="No space left on device"):
        processes.start(["sleep", "30"], tmp_path / "run.out", dict(os.environ), [tmp_path])
    assert not processes._runs and not (tmp_path / "running.json").exists()
    assert not children(b"sleep\x0030\x00")


def children(command):
    """The pids of this process's children (not zombies) whose command line is `command`."""
    found = []
    for entry in os.scandir("/proc"):
        try:
            fields = processes.process_fields(entry.name) if entry.name.isdigit() else None
            if fields and fields[0] != "Z" and int(fields[1]) == os.getpid() and \
                    Path(entry.path, "cmdline").read_bytes() == command:
                found.append(int(entry.name))
        except OSError:
            pass
    return found


# ---- a series carried from machine to machine by its committed summaries (--done-in)

WIDE = ROOT / "data" / "confirm_frictional_wide" / "frictional_flow"


def test_a_point_whose_summary_says_it_ended_is_not_run_again(tmp_path):
    """--done-in: a flowing run's summary makes its point done, an incomplete run's does not
    (its run is lost with the machine it ran on), a point with no summary is run; a summary
    that is not one is refused, not taken as "not done"."""
    from scripts.granmn_sweep.cli import summarized_points
    flowing = sorted(WIDE.glob("*.json"))[0]
    summaries = tmp_path / "summaries" / "frictional_flow"
    summaries.mkdir(parents=True)
    (summaries / flowing.name).write_text(flowing.read_text())
    incomplete = json.loads(flowing.read_text())
    incomplete.update(point=incomplete["point"].replace("seed301", "seed399"),
                      ended="incomplete", params=None, measured=None, energy=None,
                      cpu_seconds=None, reason="did not complete (no done.txt)")
    incomplete["variables"]["seed"] = 399
    (summaries / flowing.name.replace("seed301", "seed399")).write_text(json.dumps(incomplete))
    output = tmp_path / "out" / "frictional_flow"
    plan = [({}, output / name.replace(".json", ""), 0)
            for name in (flowing.name, flowing.name.replace("seed301", "seed399"),
                         flowing.name.replace("seed301", "seed398"))]
    assert summarized_points([tmp_path / "summaries"], plan) == {plan[0][1]}
    (summaries / flowing.name).write_text("{}")
    with pytest.raises(SweepError, match=r"--done-in .*: not a run summary"):
        summarized_points([tmp_path / "summaries"], plan)
    with pytest.raises(SweepError, match=r"--done-in .*absent: not a directory of run summaries"):
        summarized_points([tmp_path / "absent"], plan)


def test_a_resumed_run_records_what_the_point_cost_in_all(tmp_path, monkeypatch):
    """A point stopped by a signal, then failed, then resumed to its end: timing.json holds the
    three runs' seconds (it held the last run's alone, so that a summary's cpu_seconds left out
    all a resumed run went on from); a fresh start counts anew."""
    directory = a_run_that_ended(tmp_path, None)
    logs = [directory / "log.lammps", directory / "run.out"]
    monkeypatch.setattr(processes, "stopped_by", [15])
    assert runner_points.finish(directory, "a" * 16, -15, 10.0, 9.0, logs, logs[1], {},
                                [])[0] == "stopped"
    monkeypatch.setattr(processes, "stopped_by", [])
    assert runner_points.finish(directory, "b" * 16, 1, 5.0, 4.0, logs, logs[1],
                                {"resume": 1, "resume_step": 100}, [])[0] == "failed"
    (directory / "done.txt").write_text(f"kn 50000 steps 1 dt 1 run {TOKEN}\n")
    assert finish(directory) == ("done", "")
    timing = json.loads((directory / "timing.json").read_text())
    assert timing == {"seconds": 16.0, "cpu_seconds": 14.0, "runs": 3, "run": TOKEN}
    runner_points.prepare(directory, {"scene": "single_disk", "kn": 50000}, {})
    (directory / "done.txt").write_text(f"kn 50000 steps 1 dt 1 run {TOKEN}\n")
    assert finish(directory) == ("done", "")
    assert json.loads((directory / "timing.json").read_text())["cpu_seconds"] == 1.0
