"""The sweep runner runs event-driven points (engine event_driven,
scripts/granmn_sweep/event_driven.py): the start is the deck's own, the engine's outputs are the
files of a LAMMPS run, and postprocess reads them as it reads a LAMMPS run's."""
import json
import subprocess
import sys
from pathlib import Path

import numpy as np

from granmn_run import BUILD_PATHS, law
from postprocess.io import read_counts, read_energy, read_params, read_profile
from postprocess.runs import read_run

ROOT = Path(__file__).resolve().parents[2]
BUILD = BUILD_PATHS.directory

CONFIG = """
[defaults]
scene = "collisional_flow"
engine = "event_driven"
rule = "soft"
collapse = "tc"
kn = 1.28e7
run_time = 30
average_start = 10
# a value of 14 digits: params.txt must give it back as the same number (postprocess compares)
mu = 0.50000000000001
[[grid]]
seed = [1, 2]
"""


def test_an_event_driven_point_runs_from_the_decks_start_and_postprocess_reads_it(tmp_path):
    config = tmp_path / "ed.toml"
    config.write_text(CONFIG)
    out = tmp_path / "out"
    proc = subprocess.run([sys.executable, "-m", "scripts.sweep", str(config),
                           "--output", str(out), "--build", str(BUILD), "--jobs", "1"],
                          cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    tau_c = law(1.28e7, 0.7, 0.7)["tau_c"]
    for seed in (1, 2):
        point = next(p for p in (out / "collisional_flow").iterdir()
                     if p.name.endswith(f"seed{seed}"))
        # the deck's start (inputs/collisional_flow.lmp): disks 51-100 at rest above the valleys,
        # at heights 2 + 4 hash(id, seed); rebuilding it here would not show that the engine
        # ran the deck's
        disks = [l.split() for l in (point / "start.txt").read_text().splitlines()
                 if l.startswith("disk")]
        ids = np.arange(51, 101)
        heights = 2.0 + 4.0 * ((ids * 7919 + seed * 104729) % 10007) / 10007
        assert np.allclose([float(d[2]) for d in disks], heights, rtol=0, atol=1e-12)
        assert np.allclose([float(d[1]) for d in disks], 0.501 + 1.002 * np.arange(50),
                           atol=1e-9)
        assert all(float(v) == 0.0 for d in disks for v in d[3:6])
        assert (point / "start.txt").read_text().count("\nbump ") == 50

        params = read_params(point)
        assert params["engine"] == "event_driven" and params["n_mobile"] == 50
        # t_c = tau_c(k_n), the law's (mn-law): the TC model's time and params.txt's
        assert abs(params["tc_time"] / tau_c - 1) < 1e-9
        assert abs(params["tau_c"] / tau_c - 1) < 1e-9
        energy = read_energy(point, params)
        assert len(energy["time"]) == 301 and energy["e_total"][0] == 0.0
        # the counters' window restarts at average_start: the counts per disk (counts.txt) sum
        # to energy.txt's last sums, which began there
        counts = read_counts(point)
        assert counts["begun_disk"].sum() == energy["begun_disk"][-1]
        assert counts["begun_boundary"].sum() == energy["begun_boundary"][-1]
        assert energy["window"][-1] == 20.0
        # every disk is in a bin of profile.txt at each sample: the mean counts, written to 10
        # digits, sum to 50
        assert abs(read_profile(point)["count"].sum() - 50) < 1e-7
        # params.txt agrees with point.json (mu of every digit included), the outputs read
        record = read_run(point)
        assert record.ended == "flowing" and record.reason is None, record.reason
        summary = dict(l.split() for l in (point / "summary.txt").read_text().splitlines())
        assert summary["end"] == "time"
        assert json.loads((point / "timing.json").read_text())["cpu_seconds"] > 0
