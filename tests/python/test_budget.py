"""The energy budget's check (postprocess/budget.py): a budget that closes to the integrator's
error passes; one that leaves out a share of the dissipation (a wall whose contacts book
nothing) is flagged with the step where it first leaves its bound, and a summary keeps the
flag."""
import json
from pathlib import Path

import numpy as np
import pytest

from postprocess.budget import BOUND_FACTOR, budget_problem
from postprocess.summary import read_summary

DT, TAU_C = 1e-4, 2e-3      # dt = tau_c/20: the bound is 10 (1/20)^2 = 0.025 per disk at E <= 1


def energy_columns(budget, e_total=0.6):
    """energy.txt's columns that the check reads (io.read_energy), every 1000 steps."""
    steps = np.arange(len(budget)) * 1000.0
    return {"step": steps, "time": steps * DT, "e_total": np.full(len(budget), e_total),
            "e_budget": np.asarray(budget, dtype=float)}


PARAMS = {"dt": DT, "tau_c": TAU_C}


def test_a_budget_within_the_integrators_error_closes():
    """Velocity Verlet's residual: (dt^2/8) sum |F|^2/m, here the collisions' 2.5 (dt/tau_c)^2 E
    term at its largest, oscillating with the contacts: no flag."""
    rng = np.random.default_rng(3)
    wobble = 2.5 * (DT / TAU_C) ** 2 * 0.6 * rng.uniform(-1, 1, 200)
    assert budget_problem(energy_columns(4.0 + wobble), PARAMS) is None


def test_a_budget_that_misses_a_share_of_the_dissipation_is_flagged():
    """A wall whose contacts dissipate 0.01 per disk and time unit and book nothing: the budget
    falls by that and leaves the bound (0.025 per disk) after 2.5 time units (lines every 0.1);
    the flag names the first step beyond it."""
    t = np.arange(200) * 1000 * DT
    problem = budget_problem(energy_columns(4.0 - 0.01 * t), PARAMS)
    bound = BOUND_FACTOR * (DT / TAU_C) ** 2
    first = int(np.flatnonzero(0.01 * t > bound)[0]) * 1000
    assert problem is not None and f"at step {first} " in problem, problem
    assert "does not close" in problem


def test_a_run_without_a_budget_is_not_checked():
    energy = energy_columns([4.0, 9.0])
    del energy["e_budget"]
    assert budget_problem(energy, PARAMS) is None


@pytest.mark.parametrize("energy,allowed", [(0.5, 0.025), (4.0, 0.1)])
def test_the_bound_grows_with_the_energy_per_disk(energy, allowed):
    """The bound is BOUND_FACTOR (dt/tau_c)^2 max(1, E): a residual just inside it at E passes,
    just beyond it is flagged."""
    inside = energy_columns([4.0] + [4.0 + 0.99 * allowed] * 3, energy)
    beyond = energy_columns([4.0] + [4.0 + 1.01 * allowed] * 3, energy)
    assert budget_problem(inside, PARAMS) is None
    assert budget_problem(beyond, PARAMS) is not None


def test_a_summary_keeps_the_flag(tmp_path):
    source = next((Path(__file__).resolve().parents[2] / "data" / "confirm_frictional_wide" /
                   "frictional_flow").glob("*.json"))
    data = json.loads(source.read_text())
    data["measured"]["budget_problem"] = "energy.txt: the energy budget does not close: ..."
    path = tmp_path / "frictional_flow" / source.name
    path.parent.mkdir()
    path.write_text(json.dumps(data))
    assert read_summary(path, selection=None).measured["budget_problem"] == \
        data["measured"]["budget_problem"]
