"""The 3D chute in LIGGGHTS (inputs/liggghts/chute_3d.lmp) against the LAMMPS deck, through the
sweep runner (a point's engine) and the post-processing.

The two decks make the same start (inputs/lib/chute_3d_start.lmp) and integrate the same law
the same way, so their first steps agree to rounding; a dense flow of 600 spheres is chaotic,
and the rounding of sums taken in another order grows (measured: 1.8e-10 relative in
energy.txt's columns after 0.2 time units). The energies and counters of the first 0.2 time
units must agree to 1e-6. A different start (a sphere moved, a diameter off) or law would
differ from the first line by far more: the counters count whole contacts."""
import json
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from granmn_run import BUILD_PATHS, INPUTS, LMP, MPIEXEC, PLUGIN
from liggghts_decks import LIGGGHTS

pytestmark = pytest.mark.skipif(not LIGGGHTS, reason="LIGGGHTS was not built (GRANMN_LIGGGHTS unset)")

ROOT = Path(__file__).resolve().parents[2]
DECK = ROOT / "inputs" / "liggghts" / "chute_3d.lmp"
BUILD = BUILD_PATHS.directory
SHORT = {"run_time": 0.3, "average_start": 0.1, "kn": 2e5, "dt_fraction": 0.05, "dt_cap": 1,
         "seed": 3}


def run_liggghts_chute(workdir, check=True, ranks=1, deck=DECK, **variables):
    workdir.mkdir(parents=True, exist_ok=True)
    command = ([MPIEXEC, "-np", str(ranks)] if ranks > 1 else []) + [LIGGGHTS, "-in", str(deck), "-log", str(workdir / "log.lammps"), "-echo",
               "none", "-nocite", "-var", "lib", str(INPUTS / "lib"), "-var", "out",
               str(workdir)]
    for name, value in variables.items():
        command += ["-var", name, str(value)]
    # (LIGGGHTS's errors can end in bytes of no text: it prints the rest of a line buffer)
    proc = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                          errors="replace", timeout=600)
    if check and proc.returncode != 0:
        raise AssertionError(proc.stdout[-3000:])
    return proc


def run_lammps_chute(workdir, **variables):
    workdir.mkdir(parents=True, exist_ok=True)
    command = [LMP, "-in", str(INPUTS / "chute_3d.lmp"), "-log", str(workdir / "log.lammps"),
               "-nocite", "-var", "plugin", PLUGIN, "-var", "lib", str(INPUTS / "lib"), "-var",
               "out", str(workdir), "-var", "stop_energy", "0"]
    for name, value in variables.items():
        command += ["-var", name, str(value)]
    proc = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                          timeout=600)
    assert proc.returncode == 0, proc.stdout[-3000:]


def energy_rows(path):
    rows = [line.split() for line in path.read_text().splitlines()
            if line.strip() and not line.startswith("#")]
    return {int(r[0]): np.array([float(v) for v in r[1:]]) for r in rows}


def test_the_same_chute_as_the_lammps_deck(tmp_path):
    run_liggghts_chute(tmp_path / "liggghts", **SHORT)
    run_lammps_chute(tmp_path / "lammps", **SHORT)
    theirs = energy_rows(tmp_path / "liggghts" / "energy.txt")
    ours = energy_rows(tmp_path / "lammps" / "energy.txt")
    steps = sorted(set(theirs) & set(ours) - {0})
    assert len(steps) >= 2, (sorted(theirs), sorted(ours))
    worst = 0.0
    for step in steps:
        # e_trans, e_rot, e_total and the counters (contacts begun, times, now, window)
        a, b = theirs[step], ours[step]
        worst = max(worst, float(np.max(np.abs(a - b) / np.maximum(np.abs(b), 1e-12))))
    print(f"largest relative difference of energy.txt's columns over {len(steps)} rows: {worst:.3g}")
    assert worst <= 1e-6
    params = [dict(line.split(None, 1) for line in (tmp_path / d / "params.txt").read_text()
                   .splitlines()) for d in ("liggghts", "lammps")]
    for name in ("dt", "tau_c", "tau_w", "n_mobile"):
        assert float(params[0][name]) == pytest.approx(float(params[1][name]), rel=1e-9), name


def test_two_ranks_count_as_one(tmp_path):
    """On two MPI ranks (newton off: a pair across the ranks' boundary is computed on both)
    each contact counts once, for the rank that owns each sphere: after the spheres have
    reached the base, energies and contacts begun are those of one rank, the times equal to
    the rounding of sums taken in another order (measured: identical energies, times 1e-15
    apart). A pair counted on both ranks would count its contacts twice."""
    run = dict(SHORT, run_time=2.5, average_start=1)
    run_liggghts_chute(tmp_path / "one", **run)
    run_liggghts_chute(tmp_path / "two", ranks=2, **run)
    one, two = (energy_rows(tmp_path / d / "energy.txt") for d in ("one", "two"))
    assert sorted(one) == sorted(two)
    last = max(one)
    assert one[last][3] > 1000 and one[last][4] > 100      # contacts with spheres and base
    assert np.allclose(one[last], two[last], rtol=1e-12, atol=0)


def test_contact_ends_as_surfaces_close_sees_them(tmp_path):
    """model mn tells a contact's end from its history's record of the pass that last found it
    touching, with neighbour lists as narrow as LIGGGHTS's own models have them. LIGGGHTS's
    own way, surfacesClose for every listed pair that is apart (a contact distance factor of
    1.5: pairs out to 1.5 times their radii's sum, further than a pair drifts apart before
    the list is built again), must see the same ends. With the atoms' order, bins and ghosts
    fixed (a wider list sorts and bins the atoms otherwise, and forces summed in another order
    differ in the last bits, which a flow amplifies), the chute's energy.txt and counts.txt are
    byte-identical over 3 time units, with thousands of contacts begun. A contact end missed
    (u_t carried into the next contact, a contact not counted as begun) would change the
    counters by whole contacts."""
    text = DECK.read_text()
    fixed = {"communicate single vel yes": "communicate single vel yes cutoff 4.0\n"
                                           "atom_modify sort 0 0.0",
             "neighbor 0.2 bin": "neighbor 0.2 bin\nneigh_modify binsize 0.7"}
    for line, replacement in fixed.items():
        assert text.count(f"\n{line}\n") == 1, line
        text = text.replace(f"\n{line}\n", f"\n{replacement}\n")
    run = dict(SHORT, run_time=3, average_start=1)
    outputs = {}
    for name, extra in (("narrow", ""), ("close", "neigh_modify contact_distance_factor 1.5\n")):
        deck = tmp_path / f"{name}.lmp"
        deck.write_text(text.replace("neigh_modify binsize 0.7\n",
                                     "neigh_modify binsize 0.7\n" + extra))
        proc = run_liggghts_chute(tmp_path / name, deck=deck, **run)
        outputs[name] = proc.stdout
    pairs = {name: int(re.findall(r"Total # of neighbors = (\d+)", out)[-1])
             for name, out in outputs.items()}
    last = energy_rows(tmp_path / "narrow" / "energy.txt")
    begun = last[max(last)][3:5]
    print(f"neighbour pairs {pairs}; contacts begun {begun}")
    assert pairs["close"] > 1.5 * pairs["narrow"]      # the factor widened the lists
    assert begun[0] > 1000 and begun[1] > 100
    for name in ("energy.txt", "counts.txt"):
        assert (tmp_path / "narrow" / name).read_text() == \
            (tmp_path / "close" / name).read_text(), name


def test_through_the_runner_and_the_post_processing(tmp_path):
    """A point with engine = "liggghts" runs the LIGGGHTS deck, its name says so, and the
    post-processing reads it as a LAMMPS run: its observables, with none missing."""
    config = tmp_path / "c.toml"
    config.write_text('name = "e"\n[defaults]\nscene = "chute_3d"\nkn = 2e5\n'
                      'dt_fraction = 0.05\nrun_time = 2\naverage_start = 1\nspheres = 50\n'
                      '[[grid]]\nengine = "liggghts"\nseed = 1\n')
    proc = subprocess.run([sys.executable, "-m", "scripts.sweep", str(config),
                           "--output", str(tmp_path / "out"), "--build", str(BUILD)],
                          cwd=ROOT, capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    point = tmp_path / "out" / "chute_3d" / \
        "average_start1_dt_fraction0.05_engineliggghts_kn200000_run_time2_seed1_spheres50"
    assert json.loads((point / "point.json").read_text())["engine"] == "liggghts"
    assert "liggghts" in (point / "command.txt").read_text()
    from postprocess.runs import load_runs
    [run] = load_runs(tmp_path / "out")
    assert run.reason is None and run.ended == "flowing", run.reason
    for name in ("E_total", "N_c", "N_w", "t_c", "t_w", "mc_c", "mc_w"):
        assert np.isfinite(run.observables[name]), name
    assert run.observables["N_c"] > 0 and run.observables["N_w"] > 0


BAD = {
    "LIGGGHTS chute: stop_energy above 0": (
        {"stop_energy": "1e-5"},
        "deck variable stop_energy = 1e-5: the LIGGGHTS deck has no early stop"),
    "LIGGGHTS chute: checkpoints asked for": (
        {"checkpoint_interval": 10},
        "checkpoint_interval = 10, resume = 0: the LIGGGHTS deck writes no checkpoints"),
    "LIGGGHTS chute: the paper's integrator (ab2)": (
        {"integrator": "ab2"}, "Label wasn't found in input script"),
    "LIGGGHTS chute: contact rows": ({"rows": "yes"}, "Label wasn't found in input script"),
}


@pytest.mark.parametrize("case", sorted(BAD))
def test_what_the_liggghts_deck_cannot_do_is_refused(tmp_path, case):
    variables, message = BAD[case]
    proc = run_liggghts_chute(tmp_path, check=False, **{**SHORT, **variables})
    assert proc.returncode != 0 and message in proc.stdout, proc.stdout[-2000:]


def test_the_dry_runs_of_both_engines_agree():
    """Asked for a point's size (-var dry_run yes, scripts/granmn_sweep/decks.py), the LIGGGHTS
    deck answers what the LAMMPS deck does: the same atoms, law and time step (tau_c to 1e-12:
    one header compiled twice); LIGGGHTS's `quit` ends with exit status 1, the runner reads the
    line."""
    from scripts.granmn_sweep.cost import ask_deck
    paths = {"lammps": Path(LMP), "liggghts": Path(LIGGGHTS), "plugin": Path(PLUGIN)}
    point = {"scene": "chute_3d", "kn": 2e5, "spheres": 50, "seed": 1}
    lammps, liggghts = (ask_deck({**point, "engine": engine}, paths)
                        for engine in ("lammps", "liggghts"))
    assert liggghts["atoms"] == lammps["atoms"] and liggghts["run_time"] == lammps["run_time"]
    assert liggghts["tau_c"] == pytest.approx(lammps["tau_c"], rel=1e-12)
    assert liggghts["dt"] == pytest.approx(lammps["dt"], rel=1e-12)
