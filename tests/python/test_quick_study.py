"""The quick study (inputs/sweeps/quick.toml, the main job's default) as committed in
data/quick (its runs' summaries, made by `./scripts/main.sh` and `python3 -m postprocess
summarize`): no claim fails on it, and a real study with the physics taken out fails."""
import json
import shutil
import tomllib
from pathlib import Path

import numpy as np
import pytest

from postprocess.reference import evaluate
from postprocess.study import analyse, fit_power, main_series, series

ROOT = Path(__file__).resolve().parents[2]
QUICK = ROOT / "data" / "quick"
CONFIG = ROOT / "inputs" / "sweeps" / "quick.toml"


def verdicts(source):
    scenes = analyse(source)[0]
    return {c["id"]: (value, error, status) for c, value, error, status in evaluate(scenes)}, scenes


def test_the_summaries_are_the_quick_presets_points():
    """Every point of quick.toml has a summary and no summary is of another point: the data
    are the preset's, not an older grid's."""
    with open(CONFIG, "rb") as f:
        config = tomllib.load(f)
    wanted = {(grid["scene"], float(kn)) for grid in config["grid"] for kn in grid["kn"]}
    found = {(path.parent.name, json.loads(path.read_text())["params"]["kn"])
             for path in QUICK.glob("*/*.json")}
    assert found == wanted


def test_no_claim_fails_on_the_quick_study():
    results, _ = verdicts(QUICK)
    failing = {k: v for k, v in results.items() if v[2].startswith("FAIL")}
    assert not failing


def test_the_quick_study_without_the_frictional_stiffness_dependence_fails_frictional_nc(
        tmp_path):
    """The end-to-end mutation: the frictional runs' collision counts rescaled by
    kn^-a (a: the study's own exponent), i.e. N_c independent of kn, all else as measured."""
    results, scenes = verdicts(QUICK)
    assert results["frictional-Nc"][2] == "pass"
    kn, values, _ = series(main_series(scenes["frictional_flow"]), "N_c")
    exponent, _ = fit_power(kn, values)
    mutated = tmp_path / "quick"
    shutil.copytree(QUICK, mutated)
    for path in (mutated / "frictional_flow").glob("*.json"):
        summary = json.loads(path.read_text())
        factor = (summary["params"]["kn"] / kn[0]) ** -exponent
        measured = summary["measured"]
        if measured is None or measured.get("window") is None:
            continue
        parts = [measured["window"]] + [p for ps in measured["steady"].values() for p in ps]
        for part in parts:
            blocks = part["blocks"]
            blocks["N_c"] = [v * factor for v in blocks["N_c"]]
            # t_c - N_c tau_c is made of N_c: keep it consistent with the new count
            blocks["mc_c"] = [t - n * summary["params"]["tau_c"]
                              for t, n in zip(blocks["t_c"], blocks["N_c"])]
        path.write_text(json.dumps(summary))
    results, _ = verdicts(mutated)
    value, error, status = results["frictional-Nc"]
    assert value == pytest.approx(0.0, abs=3 * error) and status == "differs"


def test_the_quick_study_given_twice_counts_each_run_once():
    """data/quick given twice is data/quick: each run counted once, each copy a left-out line
    saying so (each run was counted twice: the errors across seeds shrank by sqrt(2) and
    single-E-crossover turned from differs to pass)."""
    once, twice = analyse(QUICK), analyse([QUICK, QUICK])
    assert verdicts([QUICK, QUICK])[0] == verdicts(QUICK)[0]
    for scene, rows in once[0].items():
        assert [{k: v for k, v in o.items() if k not in ("runs", "outputs")} for o in rows] == \
            [{k: v for k, v in o.items() if k not in ("runs", "outputs")}
             for o in twice[0][scene]]
    copies = [(point, reason) for point, reason in twice[1]
              if reason == f"the same run as {point}: counted once"]
    assert sorted(point for point, _ in copies) == sorted(QUICK.glob("*/*.json"))
    assert [item for item in twice[1] if item not in copies] == once[1]
