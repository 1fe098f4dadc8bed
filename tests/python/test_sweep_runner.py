"""The sweep runner (scripts/granmn_sweep) where it needs no lmp: a config or --set that cannot
be a run. tests/lammps/test_sweep.py runs points."""
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
SWEEP = [sys.executable, str(ROOT / "scripts" / "sweep.py")]

TWO_POINTS = '[[grid]]\nscene = "single_disk"\nkn = [5e4, 1e5]\n'
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
