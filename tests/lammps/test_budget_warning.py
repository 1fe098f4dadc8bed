"""The decks' own check of their energy budget (energies = yes; inputs/lib/budget_check.lmp):
a run whose budget leaves the integrator's bound 10 (dt/tau_c)^2 max(1, E) per disk
(docs/model.md section 9) says so in a WARNING naming the first step beyond it and the residual
there, and goes on to its end; a run whose budget closes says nothing. The deck and the
post-processing (postprocess/budget.py, on energy.txt) apply the same bound: both name the same
step."""
import re

import numpy as np
import pytest

from granmn_run import energy_of, run_scene
from postprocess.budget import BOUND_FACTOR, budget_problem
from postprocess.io import read_params
from test_checkpoint import data_lines, kill_mid_chunk, point_dir
from test_sweep import sweep

WARNING = re.compile(r"^WARNING: the energy budget does not close: its residual is (\S+) per "
                     r"disk at step (\d+) \(t = (\S+)\), beyond the integrator bound (\S+) ",
                     re.MULTILINE)
# Adams-Bashforth 2 a little short of its stability limit for the normal mode of two disks
# (0.343 tau_c at e = 0.7, which the pair style enforces): each collision gains energy of the
# order of (dt/tau_c)^2 of its own, and unlike velocity Verlet's (bounded in time: docs/model.md
# section 9) the gains add up, collision after collision, past the bound within a few time
# units of the collisional flow.
UNSTABLE = dict(integrator="ab2", dt_fraction=0.34, dt_cap=1, run_time=6, average_start=1,
                energies="yes")
# the bad input as docs/bad_input.md lists it: {case: (deck variables, what the run says)}
BAD = {"a run with energies = yes whose energy budget does not close":
       (UNSTABLE, "WARNING: the energy budget does not close: its residual is ")}


def residual_and_bound(directory):
    """Per line of energy.txt: the step, |e_budget - its first value| and the bound
    (docs/model.md section 9)."""
    energy, params = energy_of(directory), read_params(directory)
    residual = np.abs(energy["e_budget"] - energy["e_budget"][0])
    bound = (BOUND_FACTOR * (params["dt"] / params["tau_c"]) ** 2
             * np.maximum(1.0, energy["e_total"]))
    return energy["step"], residual, bound


def warnings_in(text):
    """[(step, residual, bound)] of the deck's budget warnings (not its commands echoed)."""
    return [(int(m[2]), float(m[1]), float(m[4])) for m in WARNING.finditer(text)]


def check_warning_against_energy_txt(directory, warning):
    """The warned step is a line of energy.txt beyond the bound, with the residual said; no
    line before it is beyond (energy.txt's 12 digits against the deck's full ones: a line
    within 1e-6 of the bound may fall either side)."""
    step, residual, bound = residual_and_bound(directory)
    said_step, said_residual, said_bound = warning
    k = np.flatnonzero(step == said_step)
    assert len(k) == 1, (said_step, step)
    k = k[0]
    assert residual[k] == pytest.approx(said_residual, rel=5e-3)
    assert bound[k] == pytest.approx(said_bound, rel=5e-3)
    assert residual[k] > bound[k] * (1 - 1e-6)
    assert np.all(residual[:k] <= bound[:k] * (1 + 1e-6)), np.flatnonzero(
        residual[:k] > bound[:k])


def test_a_budget_that_does_not_close_is_warned_of_and_the_run_goes_on(tmp_path):
    """The first warning names the first line of energy.txt beyond the bound, and the
    post-processing, on the same energy.txt, names the same step. One warning at most per
    LAMMPS run of the deck (here the transient and the span), each naming the first step
    beyond the bound since the last; the run goes on to its end and writes all its outputs."""
    (variables, message), = BAD.values()
    run = run_scene("collisional_flow", tmp_path, **variables)
    assert message in run.output
    warnings = warnings_in(run.output)
    assert warnings, run.output[-3000:]
    assert len(warnings) <= 2, warnings
    assert [w[0] for w in warnings] == sorted({w[0] for w in warnings})
    check_warning_against_energy_txt(tmp_path, warnings[0])
    problem = budget_problem(energy_of(tmp_path), read_params(tmp_path))
    assert problem is not None and f"at step {warnings[0][0]} " in problem, problem
    # the run went on as it would have without the check: every output, and the trajectory
    # of energies = no (which has none) to the bit, to the last output step
    assert (tmp_path / "done.txt").exists()
    for name in ("counts.txt", "profile.txt", "snapshots.lammpstrj"):
        assert (tmp_path / name).exists(), name
    assert not (tmp_path / "budget_reference.lmp").exists()
    run_scene("collisional_flow", tmp_path / "off", **{**variables, "energies": "no"})
    on, off = energy_of(tmp_path), energy_of(tmp_path / "off")
    for name in ("step", "e_trans", "e_rot"):
        assert np.array_equal(on[name], off[name]), name
    assert data_lines(tmp_path / "snapshots.lammpstrj") == data_lines(
        tmp_path / "off" / "snapshots.lammpstrj")
    output_interval = 0.1    # the decks' default
    assert on["time"][-1] > variables["run_time"] - output_interval - 1e-9


def test_a_budget_that_closes_is_not_warned_of(tmp_path):
    """The collisional flow under velocity Verlet at tau_c/100 (the decks' default): its
    residual, (dt^2/8)(sum |F|^2/m + |T|^2/I now - at the start), stays under the bound through
    many collisions, and neither the deck nor the post-processing says a word."""
    run_scene("collisional_flow", tmp_path, kn=2e5, run_time=3, average_start=1,
              energies="yes", checkpoint_interval=1)
    log = (tmp_path / "log.lammps").read_text()
    assert not warnings_in(log)
    assert "the energy budget does not close" not in log.replace(
        "print 'WARNING: the energy budget does not close", "")
    energy = energy_of(tmp_path)
    dissipated = (energy["dissipated_normal"] + energy["dissipated_sticking"]
                  + energy["dissipated_sliding"])
    assert dissipated[-1] > 1.0    # many collisions
    _, residual, bound = residual_and_bound(tmp_path)
    assert np.all(residual <= bound)
    assert budget_problem(energy, read_params(tmp_path)) is None
    assert not (tmp_path / "budget_reference.lmp").exists()


def test_a_resumed_run_warns_as_the_run_it_continues(tmp_path):
    """A point killed after its checkpoints and resumed by the runner measures the residual
    from the run's start, not from the step it resumed at (the start's value is kept beside
    the checkpoints): after the resume it gives the warnings of the uninterrupted run, and
    none twice for a step the killed run had checked."""
    config = tmp_path / "unstable.toml"
    variables = "".join(f"{name} = {value!r}\n".replace("'", '"')
                        for name, value in UNSTABLE.items())
    config.write_text(f'name = "b"\n[defaults]\ncheckpoint_interval = 1\n{variables}'
                      '[[grid]]\nscene = "collisional_flow"\nkn = 2e7\n')
    sweep(config, tmp_path / "whole", "--jobs", "1")
    whole = point_dir(tmp_path / "whole")
    uninterrupted = warnings_in((whole / "log.lammps").read_text())
    assert len(uninterrupted) >= 2, uninterrupted
    directory, resumed_at = kill_mid_chunk(config, tmp_path / "killed", after=3)
    sweep(config, tmp_path / "killed", "--jobs", "1")
    resumed_log = (directory / "log.lammps").read_text()
    assert "resuming from checkpoint" in resumed_log
    after_resume = [w for w in uninterrupted if w[0] > resumed_at]
    assert after_resume, (uninterrupted, resumed_at)
    assert warnings_in(resumed_log) == after_resume
    assert data_lines(directory / "energy.txt") == data_lines(whole / "energy.txt")
    assert not (directory / "budget_reference.lmp").exists()
