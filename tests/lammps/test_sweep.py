"""The runner (python3 -m scripts.sweep): resuming a killed sweep, the multi-partition mode, bad configs, the
runner's ownership of its lmp processes and of its output directory."""
import json
import math
import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from granmn_run import BUILD_PATHS, LMP, MPIEXEC, PLUGIN, law, needs_mpi

ROOT = Path(__file__).resolve().parents[2]
# the runner's command, run from ROOT (as is a child python that imports its modules)
SWEEP = [sys.executable, "-m", "scripts.sweep"]
BUILD = BUILD_PATHS.directory

CONFIG = """
name = "t"
[defaults]
run_time = {run_time}
average_start = 1
[[grid]]
scene = "single_disk"
kn = [5e4, 1e5, 2e5]
"""


def start_sweep(config_path, output, *args):
    """The runner in a session of its own: kill_session() then reaches whatever it left."""
    return subprocess.Popen(SWEEP + [str(config_path), "--output", str(output), "--build",
                                     str(BUILD), *args], cwd=ROOT, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, start_new_session=True)


def sweep(config_path, output, *args, check=True, timeout=300):
    runner = start_sweep(config_path, output, *args)
    try:
        stdout, stderr = runner.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        kill_session(runner.pid)
        kill_processes_mentioning(output)
        runner.communicate()
        raise AssertionError(f"the sweep did not end within {timeout} s")
    proc = subprocess.CompletedProcess(runner.args, runner.returncode, stdout, stderr)
    if check and proc.returncode != 0:
        raise AssertionError(proc.stdout + proc.stderr)
    return proc


def live_processes():
    """{pid: (session id, command line)} of the processes that have not exited."""
    processes = {}
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            fields = (entry / "stat").read_text().rsplit(")", 1)[1].split()
            command = (entry / "cmdline").read_bytes().replace(b"\0", b" ").decode()
        except (OSError, ValueError, IndexError):
            continue
        if fields[0] != "Z":
            processes[int(entry.name)] = (int(fields[3]), command)
    return processes


def processes_mentioning(path):
    return [pid for pid, (_, command) in live_processes().items() if str(path) in command]


def signal_all(pids, number):
    for pid in pids:
        try:
            os.kill(pid, number)
        except ProcessLookupError:
            pass


def kill_processes_mentioning(path):
    signal_all(processes_mentioning(path), signal.SIGKILL)


def kill_session(session):
    for pid, (sid, _) in live_processes().items():
        if sid == session:
            try:
                os.kill(pid, signal.SIGKILL)
            except ProcessLookupError:
                pass


def wait_for(condition, seconds):
    deadline = time.time() + seconds
    while not condition():
        if time.time() > deadline:
            return False
        time.sleep(0.05)
    return True


def done_points(output):
    """The points whose run the runner saw end with done.txt: it wrote their timing.json."""
    return sorted(p.parent.name for p in output.glob("*/*/timing.json")
                  if (p.parent / "done.txt").exists())


def test_killed_sweep_resumes_without_redoing_finished_points(tmp_path):
    config = tmp_path / "sweep.toml"
    config.write_text(CONFIG.format(run_time=15))
    output = tmp_path / "out"
    runner = subprocess.Popen(SWEEP + [str(config), "--output", str(output), "--build",
                                       str(BUILD), "--jobs", "1"], cwd=ROOT,
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                              start_new_session=True)
    deadline = time.time() + 120
    while not done_points(output) and time.time() < deadline:
        time.sleep(0.05)
    os.killpg(runner.pid, signal.SIGKILL)    # the runner and the lmp it was running
    runner.wait()
    finished = done_points(output)
    assert len(finished) == 1, "the first point should have finished before the kill"
    first = next(output.glob(f"*/{finished[0]}"))
    stamp = (first / "energy.txt").stat().st_mtime_ns
    unfinished = [p for p in output.glob("*/*") if p.name not in finished]

    resumed = sweep(config, output, "--jobs", "1")
    assert "1 already done, 2 to run" in resumed.stdout
    assert len(done_points(output)) == 3
    assert (first / "energy.txt").stat().st_mtime_ns == stamp    # not run again
    for point in unfinished:                                       # rerun from scratch
        assert (point / "done.txt").exists() and not (point / "failed.txt").exists()
    again = sweep(config, output)
    assert "3 already done, 0 to run" in again.stdout
    # nothing lost: the same results as a sweep that was never interrupted
    whole = sweep(config, tmp_path / "whole")
    for point in output.glob("*/*"):
        twin = tmp_path / "whole" / point.parent.name / point.name
        for name in ("energy.txt", "counts.txt", "profile.txt"):
            assert (point / name).read_text() == (twin / name).read_text()


@needs_mpi
def test_two_partition_sweep_matches_serial_runs(tmp_path):
    config = tmp_path / "sweep.toml"
    config.write_text(CONFIG.format(run_time=3))
    serial = sweep(config, tmp_path / "serial")
    partitioned = sweep(config, tmp_path / "partitioned", "--partitions", "2")
    assert "done" in serial.stdout and "done" in partitioned.stdout
    points = done_points(tmp_path / "partitioned")
    assert points == done_points(tmp_path / "serial") and len(points) == 3
    for name in points:
        a = next((tmp_path / "serial").glob(f"*/{name}/energy.txt")).read_text()
        b = next((tmp_path / "partitioned").glob(f"*/{name}/energy.txt")).read_text()
        assert a == b
    commands = [c.read_text() for c in (tmp_path / "partitioned").glob("*/*/command.txt")]
    assert sum("mpirun -np 2" in c and "-partition 2x1" in c for c in commands) == 2


@pytest.fixture(scope="module")
def chute_points(tmp_path_factory):
    """Two points of the small chute that two ranks cut across the flow (tests/lammps/
    test_chute_3d.py SPLIT), run by the sweep as serial lmp processes: (config, output)."""
    from test_chute_3d import SPLIT, chute_config
    tmp = tmp_path_factory.mktemp("chute")
    config = chute_config(tmp, {**SPLIT, "seed": [1, 2]})
    sweep(config, tmp / "serial", "--jobs", "1")
    return config, tmp / "serial"


def same_points_as_serial(serial, other):
    """Each point of other is in the directory the serial sweep used (R is not part of a point),
    with the same point.json, and has the serial run's counts, contacts and energies (per
    sphere exactly, energies to rounding); [its point directories]."""
    from test_chute_3d import assert_same_run
    names = done_points(other)
    assert names == done_points(serial) and len(names) == 2
    points = []
    for name in names:
        ours, theirs = serial / "chute_3d" / name, other / "chute_3d" / name
        assert (ours / "point.json").read_text() == (theirs / "point.json").read_text()
        assert_same_run(ours, theirs)
        points.append(theirs)
    return points


@needs_mpi
def test_ranks_run_each_point_on_that_many_mpi_ranks(tmp_path, chute_points):
    """--ranks 2: each point is `mpirun -np 2 lmp` (one LAMMPS world, the domain cut in two), in
    the directory and with the outputs of the serial run; the progress lines say the ranks."""
    config, serial = chute_points
    ranked = sweep(config, tmp_path / "ranked", "--jobs", "1", "--ranks", "2")
    assert "1 point at a time on 2 MPI ranks each: 2 processes" in ranked.stdout, ranked.stdout
    assert len(re.findall(r"\] done chute_3d/\S+ in [\d.]+ s on 2 ranks; ETA", ranked.stdout)) == 2
    for point in same_points_as_serial(serial, tmp_path / "ranked"):
        command = (point / "command.txt").read_text().split()
        assert command[1:3] == ["-np", "2"] and command[3].endswith("lmp"), command
        assert "-partition" not in command
        assert "2 by 1 by 1 MPI processor grid" in (point / "log.lammps").read_text()


@needs_mpi
def test_partitions_of_several_ranks_each(tmp_path, chute_points):
    """--partitions 2 --ranks 2: one `mpirun -np 4 lmp -partition 2x2`, two points of two ranks
    each, with the outputs of the serial run. mpirun must have 4 slots (the test environment
    allows oversubscription; a machine without it refuses, as the next test checks)."""
    if subprocess.run([MPIEXEC, "-np", "4", "true"], capture_output=True,
                      env=dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1",
                               OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")).returncode != 0:
        pytest.skip("mpirun has fewer than 4 slots here")
    config, serial = chute_points
    partitioned = sweep(config, tmp_path / "partitioned", "--partitions", "2", "--ranks", "2")
    assert "2 points at a time on 2 MPI ranks each (2 partitions of one mpirun): 4 processes" \
        in partitioned.stdout, partitioned.stdout
    for point in same_points_as_serial(serial, tmp_path / "partitioned"):
        command = (point / "command.txt").read_text()
        assert "mpirun -np 4 " in command and "-partition 2x2" in command, command
        assert "2 by 1 by 1 MPI processor grid" in (point / "log.lammps").read_text()


@needs_mpi
@pytest.mark.parametrize("mode", ["ranks", "partitions x ranks"])
def test_more_ranks_than_slots_is_refused_before_any_point_runs(tmp_path, mode):
    """mpirun is asked for the processes one of its runs would start: R, or P x R."""
    if any(k.startswith("OMPI_MCA_rmaps_base_oversubscribe") for k in os.environ):
        pytest.skip("oversubscription is allowed here")
    cores = len(os.sched_getaffinity(0))
    options = ["--ranks", str(cores + 1)] if mode == "ranks" else \
        ["--partitions", "2", "--ranks", str(cores)]
    config = single_disk_config(tmp_path, "run_time = 1\naverage_start = 0.5\nkn = [5e4, 1e5]\n")
    proc = sweep(config, tmp_path / "out", *options, check=False)
    assert proc.returncode == 2 and "not enough slots" in proc.stderr, proc.stdout + proc.stderr
    assert " ".join(options) in proc.stderr
    assert not list((tmp_path / "out").glob("*/*/point.json"))


@pytest.mark.parametrize("options", [("--ranks", "2"), ("--partitions", "1")])
def test_mpirun_is_refused_with_a_serial_lammps(tmp_path, options):
    """A serial lmp (GRANMN_MPI=OFF) under `mpirun -np 2` would be two whole runs of the point
    writing the same files: refused by its cause. The build here is this one's lmp and plugin
    with a CMake cache that says serial."""
    serial = tmp_path / "build-serial"
    serial.mkdir()
    for part in ("lammps", "plugin"):
        (serial / part).symlink_to(BUILD / part)
    (serial / "CMakeCache.txt").write_text("GRANMN_MPI:BOOL=OFF\n")
    config = single_disk_config(tmp_path, "run_time = 1\naverage_start = 0.5\n")
    proc = subprocess.run(SWEEP + [str(config), "--output", str(tmp_path / "out"), "--build",
                                   str(serial), *options], cwd=ROOT, capture_output=True,
                          text=True, timeout=120)
    assert proc.returncode == 2, proc.stdout + proc.stderr
    assert f"{options[0]} runs lmp under mpirun, and {serial} is a serial LAMMPS" in proc.stderr
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("ranks", ["0", "-2"])
def test_ranks_below_one_are_refused(tmp_path, ranks):
    config = single_disk_config(tmp_path, "run_time = 1\naverage_start = 0.5\n")
    proc = sweep(config, tmp_path / "out", "--ranks", ranks, check=False)
    assert proc.returncode == 2, proc.stdout + proc.stderr
    assert f"--ranks {ranks}: the MPI ranks per point must be >= 1" in proc.stderr
    assert not (tmp_path / "out").exists()


BAD_CONFIGS = {
    "unknown scene": ('[[grid]]\nscene = "avalanche"\n', "unknown scene 'avalanche'"),
    "no grid": ('name = "x"\n', "needs at least one [[grid]] table"),
    "not toml": ("[[grid]\nscene = 1\n", "not valid TOML"),
    "unknown top-level key": ('nmae = "x"\n[[grid]]\nscene = "single_disk"\n',
                              "unknown top-level keys ['nmae']"),
    "empty list": ('[[grid]]\nscene = "single_disk"\nkn = []\n', "'kn' is an empty list"),
    "bad stiffness": ('[[grid]]\nscene = "single_disk"\nkn = -5\n', "kn = -5 must be > 0"),
    "stiffness not a number": ('[[grid]]\nscene = "single_disk"\nkn = "soft"\n',
                               "kn = 'soft' is not a number"),
    "zero time step": ('[[grid]]\nscene = "single_disk"\ndt_fraction = 0\n',
                       "ERROR: deck variable dt_fraction = 0 must lie in (0,0.5]"),
    "negative run time": ('[[grid]]\nscene = "single_disk"\nrun_time = -5\n',
                          "run_time = -5 must be > 0"),
    "table value": ('[[grid]]\nscene = "single_disk"\n[grid.kn]\na = 1\n',
                    "'kn' must hold numbers or strings"),
    "misspelled variable": ('[[grid]]\nscene = "single_disk"\nsin_thetaa = 0.2\n',
                            "sin_thetaa: not a variable of inputs/single_disk.lmp"),
    "a variable only another scene has": ('[[grid]]\nscene = "single_disk"\nrow_spacing = 3\n',
                                          "row_spacing: not a variable of inputs/single_disk.lmp"),
    "runner's own variable": ('[[grid]]\nscene = "single_disk"\nout = "/tmp"\n',
                              "out set by the sweep runner itself"),
    "name not a word": ('name = 5\n[[grid]]\nscene = "single_disk"\n', "name = 5 must be a word"),
    "grid not tables": ('grid = [1, 2]\n', "grid must be a list of tables"),
    "stiffness without a finite step": ('[[grid]]\nscene = "single_disk"\nkn = 1e308\n',
                                        "kn is too large: the derived coefficients (tau_c, "
                                        "eta_n, kt) overflow"),
    "a step too short for a finite number of steps": (
        '[[grid]]\nscene = "single_disk"\ndt_cap = 1e-300\n',
        "run_time = 200 over its time step dt = 1e-300"),
    "a word for a number": ('[[grid]]\nscene = "frictional_flow"\nrow_spacing = "wide"\n',
                            "row_spacing = 'wide' is not a number"),
    # single_disk has no random start: three seeds would be three copies of one run, averaged
    # as if independent (an error bar of exactly 0)
    "a variable the scene's deck does not use": (
        '[[grid]]\nscene = "single_disk"\nrun_time = 1\naverage_start = 0.5\nseed = [1, 2, 3]\n',
        "seed: inputs/single_disk.lmp does not use it"),
    # its point's name would be empty and its directory <output>/single_disk: starting it
    # removed every point of the scene
    "a grid of the scene alone": ('[[grid]]\nscene = "single_disk"\n',
                                  "a point of scene single_disk with no variable but the scene"),
    "unknown engine": ('[[grid]]\nscene = "single_disk"\nengine = "yade"\nkn = 2e5\n',
                       "unknown engine 'yade' (expected one of lammps, liggghts, event_driven)"),
    "a scene the engine has no deck for": (
        '[[grid]]\nscene = "single_disk"\nengine = "liggghts"\nkn = 2e5\n',
        "unknown scene 'single_disk' of engine liggghts (expected one of chute_3d)"),
    # the LIGGGHTS chute has no early stop: stop_energy only goes into its check (0 or refused)
    "a variable the LIGGGHTS deck does not use": (
        '[[grid]]\nscene = "chute_3d"\nengine = "liggghts"\nstop_energy = 0\n',
        "stop_energy: inputs/liggghts/chute_3d.lmp does not use it"),
    "one value in two spellings": (
        '[[grid]]\nscene = "collisional_flow"\nrun_time = 1\naverage_start = 0.5\n'
        'seed = [1, "01"]\n', 
        "the grids repeat the point collisional_flow/average_start0.5_run_time1_seed1"),
}


@pytest.mark.parametrize("case", sorted(BAD_CONFIGS))
def test_bad_config_is_refused_with_a_message(tmp_path, case):
    text, message = BAD_CONFIGS[case]
    config = tmp_path / "bad.toml"
    config.write_text(text)
    proc = sweep(config, tmp_path / "out", check=False)
    assert proc.returncode == 2 and message in proc.stderr, proc.stderr
    assert not (tmp_path / "out").exists()


def test_partitions_refuse_points_of_another_engine(tmp_path):
    """--partitions runs points as the partitions of one lmp: a LIGGGHTS point is refused by
    name (it would have run in lmp, with a deck lmp cannot read)."""
    config = tmp_path / "engines.toml"
    config.write_text('[[grid]]\nscene = "chute_3d"\nengine = "liggghts"\nseed = [1, 2]\n')
    proc = sweep(config, tmp_path / "out", "--partitions", "2", check=False)
    assert proc.returncode == 2 and "the points of engine liggghts run as processes of their " \
        "own" in proc.stderr, proc.stderr


def test_a_nice_runners_runs_stay_nice_in_their_own_sessions(tmp_path):
    """Each run has a session of its own; under the kernel's autogroup scheduling each session
    is a scheduling group, and a `nice -n 19` runner's runs took a full share of a core (the
    runner's niceness weighed only inside each run's group): a run's group takes the runner's
    niceness."""
    if Path("/proc/sys/kernel/sched_autogroup_enabled").read_text().strip() != "1":
        pytest.skip("this kernel schedules no autogroups")
    # the runner's niceness is 7 above the suite's own (which may itself run under nice)
    code = ("import os, sys; print(os.nice(7));"
            "from scripts.granmn_sweep import processes;"
            "p = processes.start(['sleep', '1'], sys.argv[1], dict(os.environ), []);"
            "print(open(f'/proc/{p.pid}/autogroup').read()); processes.wait(p, [])")
    proc = subprocess.run([sys.executable, "-c", code, str(tmp_path / "run.out")],
                          cwd=ROOT, capture_output=True, text=True, timeout=60)
    assert proc.returncode == 0, proc.stderr
    runner_niceness = proc.stdout.split()[0]
    assert runner_niceness != "0" and proc.stdout.split()[-1] == runner_niceness, proc.stdout


def test_missing_config_file(tmp_path):
    proc = sweep(tmp_path / "nowhere.toml", tmp_path / "out", check=False)
    assert proc.returncode == 2 and "no such config file" in proc.stderr


def test_values_reach_the_deck_with_every_digit(tmp_path):
    """%g would run kn = 1234567.8 as 1.23457e+06, and refuse 1234567.8 and 1234568.1 as one."""
    config = tmp_path / "digits.toml"
    config.write_text('[[grid]]\nscene = "single_disk"\nrun_time = 0.5\naverage_start = 0.1\n'
                      'kn = [1234567.8, 1234568.1]\n')
    sweep(config, tmp_path / "out")
    kns = sorted(float(next(p.glob("params.txt")).read_text().split("kn ")[1].split()[0])
                 for p in (tmp_path / "out" / "single_disk").iterdir())
    assert kns == [1234567.8, 1234568.1]


def test_one_value_is_one_point_whatever_its_spelling(tmp_path):
    """kn 5e4, 50000 and "5e4" (or 1e6 and 1000000) are one stiffness: one point, one name, and
    the deck gets one spelling of it."""
    names = []
    for spelling in ('5e4', '50000', '"5e4"', '"50000.0"', '1e6', '1000000', '"1e6"'):
        config = tmp_path / "spelling.toml"
        config.write_text(f'[[grid]]\nscene = "collisional_flow"\nseed = "01"\nkn = {spelling}\n')
        listing = sweep(config, tmp_path / "out", "--dry-run").stdout
        names += re.findall(r"collisional_flow/(\S+)", listing)
    assert names == ["kn50000_seed1"] * 4 + ["kn1e+06_seed1"] * 3



def test_a_relative_build_is_the_build_under_the_working_directory(tmp_path):
    """--build relative to where the runner is started: the dry run, which runs lmp in a
    directory of its own, still finds lmp and the plugin there."""
    config = tmp_path / "relative.toml"
    config.write_text('[[grid]]\nscene = "single_disk"\nrun_time = 1\naverage_start = 0.5\n')
    proc = subprocess.run(SWEEP + [str(config), "--output", str(tmp_path / "out"), "--build",
                                   os.path.relpath(BUILD, BUILD.parent), "--dry-run"],
                          cwd=BUILD.parent, capture_output=True, text=True, timeout=120,
                          env={**os.environ, "PYTHONPATH": str(ROOT)})
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert re.search(r"todo single_disk/average_start0\.5_run_time1 \d+ steps", proc.stdout)


def test_set_gives_every_point_the_variable(tmp_path):
    """--set NAME=VALUE is a [defaults] entry: it replaces the file's value there and names
    every point; where a grid sets NAME itself (the grid would win) and where it is not
    NAME=VALUE, the sweep is refused before anything runs."""
    config = tmp_path / "set.toml"
    config.write_text('[defaults]\nnewton = "on"\n[[grid]]\nscene = "collisional_flow"\n'
                      'seed = [1, 2]\n[[grid]]\nscene = "collisional_flow"\nseed = 3\n'
                      'kn = 1e5\n')
    listing = sweep(config, tmp_path / "out", "--set", "newton=off", "--dry-run").stdout
    assert re.findall(r"collisional_flow/(\S+)", listing) == [
        "newtonoff_seed1", "newtonoff_seed2", "kn100000_newtonoff_seed3"]
    for setting, message in (("kn=2e5", "--set kn=2e5: grid 2 of"),
                             ("newton", "--set newton: expected NAME=VALUE"),
                             ("=off", "--set =off: expected NAME=VALUE")):
        proc = sweep(config, tmp_path / "out", "--set", setting, check=False)
        assert proc.returncode == 2 and message in proc.stderr, proc.stderr
    assert not (tmp_path / "out").exists()

def single_disk_config(tmp_path, text):
    config = tmp_path / "sweep.toml"
    config.write_text('[[grid]]\nscene = "single_disk"\n' + text)
    return config


# a point whose deck quits past its dry run (inputs/lib/outputs.lmp: more snapshot steps than
# LAMMPS counts), its sibling, and the deck's ERROR line
QUITS = "run_time = 1\naverage_start = 0.5\nsnapshot_interval = [10, 1e12]\n"
QUIT_POINT = "average_start0.5_run_time1_snapshot_interval1e+12"
QUIT_SIBLING = "average_start0.5_run_time1_snapshot_interval10"
QUIT_ERROR = "ERROR: deck variable snapshot_interval = 1e+12 is more than 2^31 - 1 steps of dt"


def test_failed_point_records_its_error_and_the_sweep_goes_on(tmp_path):
    """The deck's checks print their ERROR into log.lammps (lmp runs with -screen none):
    failed.txt must carry it, not an empty output."""
    config = single_disk_config(tmp_path, QUITS)
    proc = sweep(config, tmp_path / "out", check=False)
    assert proc.returncode == 1, proc.stdout + proc.stderr
    points = tmp_path / "out" / "single_disk"
    failed = (points / QUIT_POINT / "failed.txt").read_text()
    assert QUIT_ERROR in failed
    assert (points / QUIT_SIBLING / "done.txt").exists()


@needs_mpi
def test_partition_that_quits_is_a_failed_point_and_its_sibling_is_done(tmp_path):
    """A deck check's `quit 1` in one partition leaves mpirun waiting for ever (that partition
    is in MPI_Finalize, its sibling in MPI_Barrier): the runner must end the batch, record the
    failure, keep the sibling's result and leave no process behind."""
    config = single_disk_config(tmp_path, QUITS)
    output = tmp_path / "out"
    proc = sweep(config, output, "--partitions", "2", check=False, timeout=120)
    assert proc.returncode == 1, proc.stdout + proc.stderr
    points = output / "single_disk"
    failed = (points / QUIT_POINT / "failed.txt").read_text()
    assert QUIT_ERROR in failed
    assert (points / QUIT_SIBLING / "done.txt").exists()
    assert not processes_mentioning(output)


@needs_mpi
def test_partition_error_reruns_its_healthy_sibling(tmp_path):
    """A LAMMPS ERROR in one partition aborts the whole mpirun (MPI_Abort): the sibling it took
    down did not fail, and is run again, with a word. The ERROR: a stiffness too soft to hold
    the disk, which passes through a bump during the run (its dry run is sound)."""
    # the ERROR comes within milliseconds of the loop's start; the sibling's loop (2e7 steps of
    # 1e-6) lasts seconds, so the abort reaches it mid-run even on a loaded machine
    config = single_disk_config(tmp_path, 'run_time = 2\naverage_start = 0.5\nkn = 0.001\n'
                                          '[[grid]]\nscene = "single_disk"\nrun_time = 20\n'
                                          'average_start = 0.5\ndt_cap = 1e-6\n')
    output = tmp_path / "out"
    proc = sweep(config, output, "--partitions", "2", check=False, timeout=120)
    assert proc.returncode == 1, proc.stdout + proc.stderr
    points = output / "single_disk"
    failed = (points / "average_start0.5_kn0.001_run_time2" / "failed.txt").read_text()
    assert "have passed through each other" in failed
    healthy = points / "average_start0.5_dt_cap1e-06_run_time20"
    assert (healthy / "done.txt").exists() and not (healthy / "failed.txt").exists()
    assert re.search(r"rerun single_disk/average_start0.5_dt_cap1e-06_run_time20: .*kn0.001",
                     proc.stdout)
    assert not processes_mentioning(output)


@needs_mpi
def test_more_partitions_than_slots_is_refused_before_any_point_runs(tmp_path):
    if any(k.startswith("OMPI_MCA_rmaps_base_oversubscribe") for k in os.environ):
        pytest.skip("oversubscription is allowed here")
    too_many = len(os.sched_getaffinity(0)) + 1
    kns = ", ".join(str(5e4 * (k + 1)) for k in range(too_many))
    config = single_disk_config(tmp_path, f"run_time = 1\naverage_start = 0.5\nkn = [{kns}]\n")
    proc = sweep(config, tmp_path / "out", "--partitions", str(too_many), check=False)
    assert proc.returncode == 2 and "not enough slots" in proc.stderr, proc.stdout + proc.stderr
    assert not list((tmp_path / "out").glob("*/*/point.json"))


def test_output_path_with_a_space_is_refused(tmp_path):
    """The decks write ${out}/params.txt: LAMMPS would end the file name at the space and
    write into <dir>/a, an unrelated file."""
    unrelated = tmp_path / "a"
    unrelated.write_text("keep me\n")
    config = single_disk_config(tmp_path, "run_time = 1\naverage_start = 0.5\n")
    proc = sweep(config, tmp_path / "a b", check=False)
    assert proc.returncode == 2 and "contains a space" in proc.stderr, proc.stdout + proc.stderr
    assert unrelated.read_text() == "keep me\n" and not (tmp_path / "a b").exists()


LONG = "run_time = 3000\naverage_start = 1\nkn = [5e4, 1e5]\n"    # a minute a point


def running_point(output):
    """The directory of a point whose lmp has started (its log is there)."""
    logs = list(output.glob("*/*/log.lammps"))
    return logs[0].parent if logs else None


def test_killed_runner_takes_its_lmp_with_it(tmp_path):
    """kill -9 of the runner must not leave its lmp running on (it would write into the point
    directory that a resumed sweep has started afresh)."""
    output = tmp_path / "out"
    runner = start_sweep(single_disk_config(tmp_path, LONG), output, "--jobs", "1")
    try:
        assert wait_for(lambda: running_point(output) and processes_mentioning(output), 60)
        os.kill(runner.pid, signal.SIGKILL)
        runner.communicate()
        assert wait_for(lambda: not processes_mentioning(output), 5), \
            processes_mentioning(output)
    finally:
        kill_session(runner.pid)
        kill_processes_mentioning(output)


def test_second_sweep_on_one_output_is_refused_and_sigterm_stops_the_first(tmp_path):
    config = single_disk_config(tmp_path, LONG)
    output = tmp_path / "out"
    first = start_sweep(config, output, "--jobs", "1")
    try:
        assert wait_for(lambda: running_point(output), 60)
        point = running_point(output)
        second = sweep(config, output, "--jobs", "1", check=False, timeout=60)
        assert second.returncode == 2 and f"pid {first.pid}" in second.stderr, \
            second.stdout + second.stderr
        first.send_signal(signal.SIGTERM)
        _, stderr = first.communicate(timeout=30)
        assert first.returncode == 128 + signal.SIGTERM, stderr
        assert wait_for(lambda: not processes_mentioning(output), 10), \
            processes_mentioning(output)
        # the interrupted point is not a failure: it is run again on resume
        assert not (point / "failed.txt").exists() and not (point / "done.txt").exists()
    finally:
        kill_session(first.pid)
        kill_processes_mentioning(output)


def test_resume_is_refused_while_a_run_of_a_killed_sweep_lives(tmp_path):
    """A point's directory names the process running it (running.json); a sweep that finds it
    alive (an lmp a killed sweep left behind, or started by hand) must not wipe the point
    under it."""
    config = single_disk_config(tmp_path, "run_time = 1\naverage_start = 0.5\n")
    output = tmp_path / "out"
    sweep(config, output)
    point = next(output.glob("*/*"))
    (point / "done.txt").unlink()
    orphan = subprocess.Popen(["sleep", "60"], start_new_session=True)
    try:
        # /proc/PID/stat field 22: the start time, which tells the process from a later one
        start = (Path("/proc") / str(orphan.pid) / "stat").read_text().rsplit(")", 1)[1].split()
        (point / "running.json").write_text(json.dumps({"pid": orphan.pid,
                                                        "start": int(start[19])}))
        proc = sweep(config, output, check=False)
        assert proc.returncode == 2 and f"pid {orphan.pid}" in proc.stderr, \
            proc.stdout + proc.stderr
        assert (point / "running.json").exists()    # not wiped
    finally:
        orphan.kill()
        orphan.wait()
    assert "0 already done, 1 to run" in sweep(config, output).stdout   # once it is gone


def test_done_txt_of_another_run_is_not_taken(tmp_path):
    """done.txt counts only with the run token the runner gave the run that wrote the outputs
    (timing.json has it): a done.txt from a left-over process, or one whose run the runner
    never saw end, is rerun."""
    config = tmp_path / "sweep.toml"
    config.write_text(CONFIG.format(run_time=2))
    output = tmp_path / "out"
    sweep(config, output)
    first, second, third = sorted(output.glob("*/*"))
    token = json.loads((first / "timing.json").read_text())["run"]
    assert f"run {token}" in (first / "done.txt").read_text()
    (first / "done.txt").write_text("kn 50000 steps 1 dt 0.001 run 0123456789abcdef\n")
    (second / "timing.json").unlink()
    resumed = sweep(config, output)
    assert "1 already done, 2 to run" in resumed.stdout, resumed.stdout
    assert "3 already done, 0 to run" in sweep(config, output).stdout


def test_dry_run_asks_the_deck_once_per_point_but_its_seed(tmp_path, monkeypatch, capsys):
    """A grid of 60 points, 3 k_n by 20 seeds, asks its deck 3 times (cost.point_sizes): the
    seed draws the start, not its atoms nor its law, and each dry run starts lmp."""
    from scripts.granmn_sweep import cli, cost
    asked = []
    ask = cost.dry_run
    monkeypatch.setattr(cost, "dry_run",
                        lambda *arguments: asked.append(arguments[2]) or ask(*arguments))
    config = tmp_path / "grid.toml"
    config.write_text('[[grid]]\nscene = "collisional_flow"\nkn = [5e4, 1e5, 2e5]\n'
                      f'seed = [{", ".join(str(seed) for seed in range(1, 21))}]\n')
    assert cli.main([str(config), "--output", str(tmp_path / "out"), "--build", str(BUILD),
                     "--dry-run"]) == 0
    assert "60 points" in capsys.readouterr().out
    assert sorted(variables["kn"] for variables in asked) == ["100000", "200000", "50000"]


# scripts/granmn_sweep's modules in the order of docs/index.md (mn_law, mpirun_slots,
# build_layout and checkpoints, which import none of them, first): each imports only those
# before it
RUNNER_MODULES = ["mn_law", "mpirun_slots", "build_layout", "checkpoints", "decks",
                  "event_driven", "config", "cost", "processes", "points", "schedule", "cli",
                  "command"]


@pytest.mark.parametrize("module", RUNNER_MODULES)
def test_a_runner_module_imports_alone_and_only_those_before_it(module):
    """Each module of the runner imports in a fresh interpreter by itself and imports no module
    after it (docs/index.md's order): an import back, a cycle, would work only when another
    module happened to be imported first."""
    import ast
    proc = subprocess.run([sys.executable, "-c", f"import scripts.granmn_sweep.{module}"],
                          cwd=ROOT, capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr
    tree = ast.parse((ROOT / "scripts" / "granmn_sweep" / f"{module}.py").read_text())
    froms = [node for node in ast.walk(tree) if isinstance(node, ast.ImportFrom)]
    # the runner's modules import one another relatively (`from .decks import`, `from . import`)
    imported = {node.module.split(".")[0] for node in froms if node.level == 1 and node.module}
    imported |= {alias.name for node in froms if node.level == 1 and not node.module
                 for alias in node.names} - {"SweepError"}
    assert imported <= set(RUNNER_MODULES[:RUNNER_MODULES.index(module)]), imported

# {name: point}: where dt_fraction x tau_c is the step, where dt_cap is, a 3D point (spheres)
TIME_STEP_POINTS = {
    "fraction": {"scene": "single_disk", "kn": 2e5},
    "cap": {"scene": "single_disk", "kn": 1e4},
    "3D": {"scene": "chute_3d", "kn": 2e5, "dt_fraction": 0.05, "spheres": 5, "length": 3,
           "width": 3},
}
ENGINE_PATHS = {"lammps": Path(LMP), "plugin": Path(PLUGIN)}


@pytest.mark.parametrize("name", sorted(TIME_STEP_POINTS))
def test_the_dry_run_answers_the_time_step_and_atoms_of_the_run(tmp_path, name):
    """The deck's dry run (-var dry_run yes) answers the time step the run takes (done.txt's
    dt, every digit), whichever of dt_fraction x tau_c and dt_cap is the step, and the atoms
    of the run (its log's `with N atoms`), bumps and base included."""
    from scripts.granmn_sweep.cost import ask_deck
    from granmn_run import run_scene
    point = TIME_STEP_POINTS[name]
    run_scene(point["scene"], tmp_path, run_time=0.2, average_start=0.1,
              **{k: v for k, v in point.items() if k != "scene"})
    answer = ask_deck({**point, "run_time": 0.2, "average_start": 0.1}, ENGINE_PATHS)
    done = (tmp_path / "done.txt").read_text().split()
    assert answer["dt"] == float(done[done.index("dt") + 1])
    made = {int(n) for n in re.findall(r" with (\d+) atoms\n",
                                         (tmp_path / "log.lammps").read_text())}
    assert made == {answer["atoms"]} and answer["run_time"] == 0.2


def test_the_dry_run_makes_the_atoms_the_deck_makes_and_writes_nothing(tmp_path):
    """The frictional scene is ten rows of `width` disks: 400 at width 40, as lmp makes them;
    the dry run ends before the deck writes anything into its out."""
    from scripts.granmn_sweep.config import deck_variables
    from scripts.granmn_sweep.decks import DRY_RUN, deck_path, dry_run
    for width in (10, 40):
        variables = deck_variables({"scene": "frictional_flow", "width": width}, PLUGIN)
        assert dry_run(LMP, deck_path("frictional_flow"), variables, "a point")["atoms"] == \
            10 * width
    command = [LMP, "-in", str(deck_path("frictional_flow")), "-log", "none", "-nocite"]
    for name, value in {**variables, "out": tmp_path, "dry_run": "yes"}.items():
        command += ["-var", name, str(value)]
    proc = subprocess.run(command, cwd=tmp_path, capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0 and DRY_RUN in proc.stdout, proc.stdout[-2000:]
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("scene", ["single_disk", "collisional_flow", "frictional_flow",
                                   "chute_3d"])
def test_a_decks_seed_changes_neither_its_atoms_nor_its_time_step(scene):
    """cost.point_sizes asks a deck once for the points that differ in their seed alone: the
    seed draws the start (sizes, heights), never how many atoms there are nor the law."""
    from scripts.granmn_sweep.cost import ask_deck
    small = {"spheres": 20, "length": 3, "width": 3} if scene == "chute_3d" else {}
    one, other = (ask_deck({"scene": scene, "seed": seed, "kn": 1e5, **small}, ENGINE_PATHS)
                  for seed in (1, 7))
    assert one == other


def test_an_event_driven_points_events_are_guessed_from_its_decks_atoms():
    """An event-driven point's size: its LAMMPS deck's atoms (the engine runs the start the deck
    makes), and its scene's guessed events per atom and time unit, at most its events cap; the
    engine's own variables (rule, events) are not the deck's."""
    from scripts.granmn_sweep import cost
    point = {"scene": "collisional_flow", "engine": "event_driven", "seed": 1, "run_time": 300}
    size, capped = cost.point_sizes([point, {**point, "rule": "soft", "events": 1000}],
                                    ENGINE_PATHS, 2)
    atoms = cost.ask_deck({"scene": "collisional_flow", "seed": 1}, ENGINE_PATHS)["atoms"]
    assert size == (math.ceil(300 * atoms * cost.events_per_atom_time(point)), atoms)
    assert capped == (1000, atoms)


def test_the_runner_follows_the_decks_time_step_rule(tmp_path):
    """The time step is the deck's, whatever its rule: decks whose rule is dt = tau_c/50 answer
    tau_c/50 (tau_c: the law's, build/plugin/mn-law). A copy of the rule in Python predicted
    the old rule's steps."""
    import shutil
    from scripts.granmn_sweep.config import deck_variables
    from scripts.granmn_sweep.decks import dry_run
    shutil.copytree(ROOT / "inputs", tmp_path / "inputs")
    time_step = tmp_path / "inputs" / "lib" / "time_step.lmp"
    text = time_step.read_text()
    assert "timestep ${dt_resolved}\n" in text
    time_step.write_text(text.replace("timestep ${dt_resolved}\n", "timestep $(v_mn_tau_c/50)\n"))
    variables = {**deck_variables({"kn": 2e5, "e": 0.7, "beta": 0.7}, PLUGIN),
                 "lib": str(tmp_path / "inputs" / "lib")}
    answer = dry_run(LMP, tmp_path / "inputs" / "collisional_flow.lmp", variables, "a point")
    tau_c = law(2e5, 0.7, 0.7)["tau_c"]
    assert answer["dt"] == pytest.approx(tau_c / 50, rel=1e-14)


def test_a_point_its_deck_refuses_is_refused_before_anything_runs(tmp_path):
    """A point whose deck stops with its ERROR (a width of 2.5 disks per row) is refused by
    the runner, --dry-run or not, naming the point and the deck's ERROR line; nothing is made
    or run."""
    config = tmp_path / "sweep.toml"
    config.write_text('[[grid]]\nscene = "frictional_flow"\nseed = 1\nwidth = [10, 2.5]\n')
    for options in ([], ["--dry-run"]):
        proc = sweep(config, tmp_path / "out", *options, check=False)
        assert proc.returncode == 2, proc.stdout + proc.stderr
        assert "sweep: frictional_flow/seed1_width2.5: inputs/frictional_flow.lmp refuses it " \
            "in its dry run (-var dry_run yes): ERROR: deck variable width = 2.5 must be an " \
            "integer >= 2 (disks per row)" in proc.stderr, proc.stderr
        assert "Traceback" not in proc.stderr and not (tmp_path / "out").exists()


# --output that names a file, or a path through one: {case: (script and options, message)};
# it gave a traceback (FileExistsError, NotADirectoryError), and --dry-run listed every point
# as to do and exited 0.
ACCURACY = [sys.executable, "-m", "scripts.studies.accuracy"]
BAD_OUTPUTS = {
    "`--output` naming a file": ((SWEEP, "{file}"), "is a file, not a directory; choose another --output"),
    "`--output` naming a file, with --dry-run": ((SWEEP, "{file}", "--dry-run"),
                                                  "is a file, not a directory; choose another --output"),
    "`--output` inside a file (a file on the path)": ((SWEEP, "{file}/results"),
                                                        "is a file, not a directory; choose another --output"),
    "`python3 -m scripts.studies.accuracy --output` naming a file": ((ACCURACY, "{file}"),
                                                     "is a file, not a directory; choose another --output"),
}


@pytest.mark.parametrize("case", sorted(BAD_OUTPUTS))
def test_output_that_is_a_file_is_refused_with_a_message(tmp_path, case):
    (script, output, *options), message = BAD_OUTPUTS[case]
    file = tmp_path / "notes.txt"
    file.write_text("mine\n")
    config = single_disk_config(tmp_path, "run_time = 0.5\naverage_start = 0.1\n")
    arguments = [] if script is ACCURACY else [str(config)]
    proc = subprocess.run(script + arguments + ["--output", output.format(file=file), "--build",
                                                str(BUILD), *options],
                          cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert proc.returncode == 2 and message in proc.stderr, proc.stdout + proc.stderr
    assert "Traceback" not in proc.stderr and file.read_text() == "mine\n"


def test_a_grid_of_the_scene_alone_deletes_no_point(tmp_path):
    """A [[grid]] that sets only the scene made a point with an empty name, whose directory
    was <output>/<scene>: starting it removed (rmtree) every completed point of the scene."""
    output = tmp_path / "out"
    sweep(single_disk_config(tmp_path, "run_time = 0.5\naverage_start = 0.1\n"), output)
    done = next((output / "single_disk").iterdir())
    assert (done / "done.txt").exists()
    alone = tmp_path / "alone.toml"
    alone.write_text('[[grid]]\nscene = "single_disk"\n')
    proc = sweep(alone, output, check=False, timeout=60)
    assert proc.returncode == 2 and "no variable but the scene" in proc.stderr, proc.stderr
    assert (done / "done.txt").exists()


# A directory at a point's place that the runner did not make for it, or that holds more than
# a point's outputs: {case: what is put there}. The runner removed it (rmtree) to run the point
# afresh, with whatever was in it.
FOREIGN = {"no point.json": {"mine.txt": "notes\n"},
           "a folder in the point": {"point.json": None, "analysis/fit.txt": "a fit\n"}}


@pytest.mark.parametrize("case", sorted(FOREIGN))
def test_a_directory_the_runner_did_not_make_is_not_removed(tmp_path, case):
    config = single_disk_config(tmp_path, "run_time = 0.5\naverage_start = 0.1\n")
    directory = tmp_path / "out" / "single_disk" / "average_start0.1_run_time0.5"
    for name, text in FOREIGN[case].items():
        (directory / name).parent.mkdir(parents=True, exist_ok=True)
        (directory / name).write_text(text or json.dumps(
            {"scene": "single_disk", "run_time": 0.5, "average_start": 0.1}))
    proc = sweep(config, tmp_path / "out", check=False)
    assert proc.returncode == 2 and "not the runner's to remove" in proc.stderr, \
        proc.stdout + proc.stderr
    for name, text in FOREIGN[case].items():
        assert (directory / name).exists(), name


def test_a_negative_checkpoint_interval_is_refused(tmp_path):
    config = single_disk_config(tmp_path, "run_time = 0.5\naverage_start = 0.1\n")
    proc = sweep(config, tmp_path / "out", "--checkpoint-interval", "-1", check=False)
    assert proc.returncode == 2 and "--checkpoint-interval -1 must be >= 0 (0: none)" in \
        proc.stderr, proc.stderr
    assert not (tmp_path / "out").exists()


def test_a_point_whose_place_is_taken_during_the_sweep_is_refused_and_the_rest_run(tmp_path):
    """A directory made at a point's place after the sweep's check (it passed before any point
    ran) must be left alone and the point refused by name, not end the sweep in a traceback
    with the other points' results unreported."""
    config = single_disk_config(tmp_path, "average_start = 0.1\nrun_time = [100, 0.5]\n")
    output = tmp_path / "out"
    runner = start_sweep(config, output, "--jobs", "1")
    first = output / "single_disk" / "average_start0.1_run_time100"
    taken = output / "single_disk" / "average_start0.1_run_time0.5"
    try:
        deadline = time.time() + 120
        while not (first / "running.json").exists():    # the longer point runs first
            assert time.time() < deadline and runner.poll() is None, runner.communicate()
            time.sleep(0.05)
        (taken / "analysis").mkdir(parents=True)
        (taken / "analysis" / "fit.txt").write_text("a fit\n")
        stdout, stderr = runner.communicate(timeout=300)
    finally:
        kill_session(runner.pid)
    assert runner.returncode == 2, stdout + stderr
    assert "not the runner's to remove" in stderr and "Traceback" not in stderr, stderr
    assert (taken / "analysis" / "fit.txt").read_text() == "a fit\n"
    assert (first / "done.txt").exists()


def test_an_unexpected_error_in_the_runner_stops_its_runs_and_lets_go_of_the_lock(tmp_path):
    """An exception the runner does not expect (here: in the code that ends a point, in its
    pool thread) ended the sweep in a traceback only after every point left had run (the pool
    waits for its threads), and left sweep.lock. Now it says what happened, stops the runs,
    removes sweep.lock (exit status 3), and the same command resumes."""
    config = single_disk_config(tmp_path, "run_time = 1\naverage_start = 0.5\n"
                                          "kn = [5e4, 1e5, 2e5]\n")
    output = tmp_path / "out"
    code = ("import sys\n"
            "from scripts.granmn_sweep import schedule\n"
            "def fault(*args, **kwargs):\n    raise RuntimeError('a fault of the runner')\n"
            "schedule.finish = fault\n"
            "from scripts.granmn_sweep.cli import main\n"
            "sys.exit(main(sys.argv[1:]))\n")
    proc = subprocess.run([sys.executable, "-c", code, str(config),
                           "--output", str(output), "--build", str(BUILD), "--jobs", "1"],
                          cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert proc.returncode == 3, proc.stdout + proc.stderr
    assert "sweep: the runner failed: RuntimeError: a fault of the runner; the runs under way " \
        "were stopped" in proc.stderr and "Traceback" in proc.stderr, proc.stderr
    # the point the pool's thread had begun by then is stopped, the last is not started
    assert len(list(output.glob("*/*/point.json"))) < 3
    assert not list(output.glob("*/*/failed.txt"))
    assert not (output / "sweep.lock").exists() and not processes_mentioning(output)
    assert "0 already done, 3 to run" in sweep(config, output).stdout
    assert not (output / "sweep.lock").exists()


@pytest.fixture
def small_tmpfs(tmp_path):
    """A 64 KiB tmpfs (root only: `mount -t tmpfs`), unmounted afterwards."""
    if os.geteuid() != 0:
        pytest.skip("mounting a tmpfs needs root")
    mount = tmp_path / "small"
    mount.mkdir()
    proc = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=64k", "tmpfs", str(mount)],
                          capture_output=True, text=True)
    if proc.returncode != 0:
        pytest.skip(f"cannot mount a tmpfs here: {proc.stderr.strip()}")
    try:
        yield mount
    finally:
        subprocess.run(["umount", "-l", str(mount)], capture_output=True)


def test_a_full_disk_fails_the_point_with_its_cause(tmp_path, small_tmpfs):
    """A point whose outputs fill the disk: lmp stops with exit status 1 (fix ave/chunk checks
    its writes; where LAMMPS does not, it exits 0), its ERROR lost with the log it writes it
    to, done.txt missing. The point was marked failed with "exit status 1", "no ERROR line",
    "mend what the ERROR names" (the runner's own write of failed.txt raised, where no byte was
    left). Now its progress line and failed.txt name the full filesystem and done.txt."""
    config = single_disk_config(tmp_path, "run_time = 100\naverage_start = 1\n")
    proc = sweep(config, small_tmpfs / "out", check=False)
    assert proc.returncode == 1, proc.stdout + proc.stderr
    assert "Traceback" not in proc.stderr, proc.stderr
    point = next((small_tmpfs / "out" / "single_disk").iterdir())
    cause = re.search(rf"\] FAILED single_disk/{point.name} in [\d.]+ s \((exit status \d+: the "
                      rf"filesystem of {re.escape(str(point))} is full \(\d+ bytes free: "
                      r"ENOSPC\), and done.txt, the deck's last output, is (empty|missing): the "
                      r"run's outputs are cut short[^;]*)(; failed.txt could not be written "
                      r"\(No space left on device \(ENOSPC\): [^)]*\))?\); ETA", proc.stdout)
    assert cause, proc.stdout
    assert "no ERROR line" not in proc.stdout and "mend what the ERROR" not in proc.stdout
    if not cause.group(3):      # failed.txt fitted in what was left
        assert (point / "failed.txt").read_text().startswith(cause.group(1) + "\n")
    assert not (small_tmpfs / "out" / "sweep.lock").exists()
