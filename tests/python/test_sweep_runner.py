"""The sweep runner (scripts/granmn_sweep) where it needs no lmp: a config or --set that cannot
be a run, point names the filesystem cannot take. tests/lammps/test_sweep.py runs points."""
import os
import subprocess
import sys
from pathlib import Path

import pytest

from granmn_sweep import SweepError
from granmn_sweep import points as runner_points

ROOT = Path(__file__).resolve().parents[2]
SWEEP = [sys.executable, str(ROOT / "scripts" / "sweep.py")]

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
                          capture_output=True, text=True, timeout=60)
    assert proc.returncode == 2 and message in proc.stderr, proc.stdout + proc.stderr
    assert "Traceback" not in proc.stderr
    assert not (tmp_path / "out").exists()      # no point made, no sweep.lock


def test_the_long_name_refusal_says_the_limit_and_the_remedy(tmp_path):
    config = tmp_path / "sweep.toml"
    config.write_text(LONG_NAME)
    proc = subprocess.run(SWEEP + [str(config), "--output", str(tmp_path / "out"), "--build",
                                   str(tmp_path / "no_build"), "--dry-run"],
                          capture_output=True, text=True, timeout=60)
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
