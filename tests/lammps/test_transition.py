"""The transition study on real runs (docs/transition.md): P(tau) of binary collisions is a
spike at tau_c; a tiny transition sweep gives each run a state and the report its files."""
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from collision_decks import two_disks
from granmn_run import BUILD_PATHS, law, run_lammps
from postprocess.io import read_params, read_rows
from postprocess.durations import (DURATION_EDGES, contact_durations, duration_density,
                                  tail_fraction)

ROOT = Path(__file__).resolve().parents[2]
ROWS = """fix c mobile contacts/mn local 1
dump rows mobile local 1 contacts.txt f_c[1] f_c[2] f_c[3] f_c[4] f_c[5] f_c[6] f_c[7] f_c[8]
thermo 0
run"""


@pytest.mark.parametrize("kn", [1.25e4, 3.2e6])
def test_binary_collisions_give_a_spike_at_tau_c(tmp_path, kn):
    ref = law(kn, 0.7, 0.7)
    dt = ref["tau_c"] / 10          # the presets' step on the bumpy base
    scaled = []
    for phase in (0.1, 0.3, 0.5, 0.7, 0.9):
        for v_n in (0.5, 2.0):
            deck, _ = two_disks((kn, 0.7, 0.7, 0.5), dt, v_n=v_n, phase=phase)
            run = run_lammps(deck.replace("thermo 0\nrun", ROWS),
                             tmp_path / f"p{phase}v{v_n}")
            d = contact_durations(read_rows(run.workdir), ref["tau_c"], ref["tau_w"], 0.0)
            assert len(d["disk"]) == 1 and len(d["boundary"]) == 0
            scaled.append(d["disk"][0])
    # a duration is a whole number of steps: the count of steps in contact differs from
    # tau_c/dt by less than one; velocity Verlet at this step may shorten the contact by a
    # further fraction of a step: 1.5 dt in all
    assert np.all(np.abs(np.array(scaled) - 1.0) <= 1.5 * dt / ref["tau_c"]), scaled
    assert tail_fraction(scaled) == 0.0
    density = duration_density(scaled)
    occupied = np.flatnonzero(density)
    assert np.all((DURATION_EDGES[occupied + 1] > 1 - 1.5 * dt / ref["tau_c"]) &
                  (DURATION_EDGES[occupied] < 1 + 1.5 * dt / ref["tau_c"]))


TINY = """
name = "tiny"
[defaults]
integrator = "verlet"
dt_cap = 1
kn = [12500, 50000]
rows = "yes"
stop_energy = 1e-5
run_time = 60
average_start = 20
rows_time = 10
[[grid]]
scene = "frictional_flow"
dt_fraction = 0.05
sin_theta = [0.20, 0.45]
[[grid]]
scene = "collisional_flow"
dt_fraction = 0.1
sin_theta = [0.20]
[[grid]]
# the paper's collisional flow, settled by t = 200 (docs/reproduction.md)
scene = "collisional_flow"
dt_fraction = 0.1
sin_theta = [0.45]
run_time = 400
average_start = 200
"""


def test_a_tiny_transition_sweep_and_its_report(tmp_path):
    config = tmp_path / "tiny.toml"
    config.write_text(TINY)
    build = BUILD_PATHS.directory
    out = tmp_path / "sweep"
    subprocess.run([sys.executable, "-m", "scripts.sweep", str(config),
                    "--output", str(out), "--build", str(build)], check=True, cwd=ROOT,
                   capture_output=True)
    proc = subprocess.run([sys.executable, "-m", "postprocess", "transition", str(out)],
                          cwd=ROOT, capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr
    report = out / "transition"
    for name in ("transition.md", "transition.csv", "transition_points.csv",
                 "transition_runs.csv", "transition.png", "durations.png"):
        assert (report / name).exists(), name
    runs = [line.split(",") for line in (report / "transition_runs.csv").read_text().splitlines()[1:]]
    states = {(scene, float(s), float(kn)): state for scene, s, kn, _, state, *_ in runs}
    # the flat base at sin theta 0.45 (tan 0.50, the friction coefficient): the pile gains
    # speed from rest throughout
    assert states[("frictional_flow", 0.45, 12500.0)] == "accelerating"
    assert states[("frictional_flow", 0.45, 50000.0)] == "accelerating"
    # the bumpy base at 0.20: the disks settle in the valleys, and the deck ends the run
    stopped = [p for p in (out / "collisional_flow").glob("*sin_theta0.2_*")
               if (p / "stopped.txt").exists()]
    assert stopped and all(states[("collisional_flow", 0.2, kn)] == "stopped"
                           for kn in (12500.0, 50000.0) if any(f"kn{kn:g}_" in p.name
                                                              for p in stopped))
    # the bumpy base at 0.45 (the paper's collisional flow) flows steadily, or still relaxes
    # from its start over 200 ... 400 (E at 50000 falls by a quarter there, 4 sigma): at least
    # one of the two is averaged
    assert {states[("collisional_flow", 0.45, kn)] for kn in (12500.0, 50000.0)} <= \
        {"flowing", "drifting"}
    assert "flowing" in {states[("collisional_flow", 0.45, kn)] for kn in (12500.0, 50000.0)}
    # rows_time: only the contacts that end within 10 after average_start; the stretch
    # begins at the first multiple of output_steps (a little more than 0.1 each) from there,
    # so it may begin and end up to one such interval late: 0.15 on each side
    for point in out.glob("*/*/"):
        rows = read_rows(point)
        end = rows["start"] + rows["duration"]
        start = read_params(point)["average_start"]
        assert len(end) and end.min() >= start and end.max() <= start + 10 + 2 * 0.15
