"""scripts/studies/steadiness_calibration.py's ratio, on made-up energy curves as a run summary keeps
them (1-unit window means from t = 0): a steady energy gives 1, an energy growing linearly from
rest 650/350 (the figure the collisional steadiness test's docstring gives such a flow)."""
from types import SimpleNamespace

import numpy as np
import pytest

from scripts.studies import steadiness_calibration


def summary_record(energy_of_t):
    starts = np.arange(800.0)
    return SimpleNamespace(source="summary", energy={
        "t0": 0.0, "window": 1.0, "E": list(energy_of_t(starts + 0.5))})


def test_a_steady_energy_gives_one():
    assert steadiness_calibration.ratio(summary_record(lambda t: 9.7 + 0 * t)) == \
        pytest.approx(1.0, rel=1e-12)


def test_an_energy_growing_from_rest_gives_650_over_350():
    assert steadiness_calibration.ratio(summary_record(lambda t: 0.05 * t)) == \
        pytest.approx(650 / 350, rel=1e-9)
