"""scripts/sweep.py: resuming a killed sweep, the multi-partition mode, bad configs."""
import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from granmn_run import PLUGIN

ROOT = Path(__file__).resolve().parents[2]
SWEEP = [sys.executable, str(ROOT / "scripts" / "sweep.py")]
BUILD = Path(PLUGIN).resolve().parents[1]

CONFIG = """
name = "t"
[defaults]
run_time = {run_time}
average_start = 1
[[grid]]
scene = "single_disk"
kn = [5e4, 1e5, 2e5]
"""


def sweep(config_path, output, *args, check=True):
    proc = subprocess.run(SWEEP + [str(config_path), "--output", str(output), "--build",
                                   str(BUILD), *args], capture_output=True, text=True)
    if check and proc.returncode != 0:
        raise AssertionError(proc.stdout + proc.stderr)
    return proc


def done_points(output):
    return sorted(p.parent.name for p in output.glob("*/*/done.txt"))


def test_killed_sweep_resumes_without_redoing_finished_points(tmp_path):
    config = tmp_path / "sweep.toml"
    config.write_text(CONFIG.format(run_time=15))
    output = tmp_path / "out"
    runner = subprocess.Popen(SWEEP + [str(config), "--output", str(output), "--build",
                                       str(BUILD), "--jobs", "1"],
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
    unfinished = [p for p in output.glob("*/*") if not (p / "done.txt").exists()]

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
                       "dt_fraction = 0 must be > 0"),
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
                                        "give no finite number of steps"),
    "a word for a number": ('[[grid]]\nscene = "frictional_flow"\nrow_spacing = "wide"\n',
                            "row_spacing = 'wide' is not a number"),
    # single_disk has no random start: three seeds would be three copies of one run, averaged
    # as if independent (an error bar of exactly 0)
    "a variable the scene's deck does not use": (
        '[[grid]]\nscene = "single_disk"\nrun_time = 1\naverage_start = 0.5\nseed = [1, 2, 3]\n',
        "seed: inputs/single_disk.lmp does not use it"),
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
