"""scripts/studies/newton_check.py's rule on made-up run summaries: newton off drawn from newton on's
distribution passes; one shifted by 5 of its standard errors fails, as does a variant with a
single run (its error undefined) or with many more piles that stop; a mutant that passes
makes the verdict fail."""
import json

import numpy as np

from scripts.studies import newton_check

SCATTER = 0.1      # per-run scatter of every observable about 1


def write_runs(directory, scene, variables, values, ended=None):
    """One summary per value: every observable's blocks average to that value."""
    ended = ended or ["flowing"] * len(values)
    for i, (value, end) in enumerate(zip(values, ended)):
        blocks = {o: [value, value] for o in newton_check.OBSERVABLES}
        summary = dict(schema="granmn-run-summary", scene=scene, ended=end,
                       variables=dict(variables, seed=i + 1),
                       measured=dict(window=dict(blocks=blocks)))
        path = directory / scene / f"{'_'.join(f'{k}{v}' for k, v in variables.items())}_{i}.json"
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(json.dumps(summary))


def judge(tmp_path, capsys, off_values, mutant_shift=10.0, off_ended=None):
    rng = np.random.default_rng(7)
    n = 12
    write_runs(tmp_path, "collisional_flow", {"newton": "on"}, 1 + SCATTER * rng.standard_normal(n))
    write_runs(tmp_path, "collisional_flow", {"newton": "off"}, off_values, off_ended)
    write_runs(tmp_path, "collisional_flow", {"newton": "on", "e": 0.65},
               1 + mutant_shift * SCATTER / np.sqrt(n) + SCATTER * rng.standard_normal(n))
    status = newton_check.main(tmp_path)
    return status, capsys.readouterr().out


def same_physics(n=12, seed=8):
    return 1 + SCATTER * np.random.default_rng(seed).standard_normal(n)


def test_same_physics_passes_and_the_mutant_fails(tmp_path, capsys):
    status, out = judge(tmp_path, capsys, same_physics())
    assert status == 0, out
    assert "newton off against newton on" in out and "passes" in out


def test_a_shift_of_five_standard_errors_fails(tmp_path, capsys):
    shift = 5 * np.sqrt(2) * SCATTER / np.sqrt(12)    # 5 combined standard errors
    status, out = judge(tmp_path, capsys, same_physics() + shift)
    assert status == 1 and "(it should pass)" in out


def test_a_single_run_cannot_pass(tmp_path, capsys):
    status, out = judge(tmp_path, capsys, same_physics(n=1))
    assert status == 1 and "(it should pass)" in out


def test_many_more_piles_stopping_fails(tmp_path, capsys):
    status, out = judge(tmp_path, capsys, same_physics(),
                        off_ended=["flowing"] * 3 + ["stopped"] * 9)
    assert status == 1 and "stopped 9/12 against 0/12" in out and "(it should pass)" in out


def test_a_mutant_the_rule_cannot_see_fails_the_verdict(tmp_path, capsys):
    status, out = judge(tmp_path, capsys, same_physics(), mutant_shift=0.0)
    assert status == 1 and "(it should fail)" in out and "NOT as required" in out
