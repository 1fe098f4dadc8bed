"""postprocess/finite_size.py: the frictional scene's finite-size rule. A width whose means sit
beyond the rule's resolution from the widest width's must be called dependent, one within two
combined errors must not; the wide series takes the widest width unless a narrower one both
agrees and is 1.5x cheaper per unit of information; a width that mostly stops is not taken; the
seeds follow the scatter."""
import math
from types import SimpleNamespace

import numpy as np
import pytest

from postprocess.finite_size import (COMPARED, analyse_widths, choose_width, cells_of,
                                     dependences, wilson)

KNS = (1.6e6, 2.56e7)


def runs(width, kn, values, ended="flowing", law="literal"):
    """Runs of one width and k_n, each with every COMPARED quantity at its value (None: a run
    that was not selected)."""
    params = {"tangential": law, "kn": kn}
    if width != 10:
        params["width"] = float(width)
    return [SimpleNamespace(scene="frictional_flow", params=params, ended=ended,
                            cpu_seconds=1.0,
                            observables=None if v is None else {q: v for q in COMPARED})
            for v in values]


def spread(mean, relative, n, seed):
    """n values of exactly this mean and relative standard deviation."""
    x = np.random.default_rng(seed).standard_normal(n)
    x = (x - x.mean()) / x.std(ddof=1)
    return list(mean * (1 + relative * x))


def test_the_paper_width_is_ten_where_params_name_none():
    cells = cells_of(runs(10, 1.6e6, [0.1, 0.2]) + runs(40, 1.6e6, [0.1]))
    assert set(cells) == {("literal", 1.6e6, 10), ("literal", 1.6e6, 40)}


def test_a_shift_beyond_the_resolution_depends_and_one_within_two_errors_does_not():
    base = spread(0.05, 0.1, 8, 1)
    se = np.std(base, ddof=1) / math.sqrt(8)
    combined = math.sqrt(2) * se
    data = runs(40, 1.6e6, base) + runs(20, 1.6e6, [v + 5 * combined for v in base]) + \
        runs(10, 1.6e6, [v + 1.5 * combined for v in base])
    found = {d.width: d for d in dependences(cells_of(data)) if d.quantity == "mc_c"}
    assert found[20].verdict == "depends" and found[20].z == pytest.approx(5)
    assert found[10].verdict == "none resolved" and found[10].z == pytest.approx(1.5)
    assert found[20].reference == 40
    # three combined errors: suggested
    data = runs(40, 1.6e6, base) + runs(20, 1.6e6, [v - 3 * combined for v in base])
    assert {d.verdict for d in dependences(cells_of(data))} == {"suggested"}


def test_the_widest_is_taken_unless_a_narrower_agrees_and_is_clearly_cheaper():
    def check(scatter20, scatter40, shift20=0.0):
        data = []
        for i, kn in enumerate(KNS):
            data += runs(40, kn, spread(0.05, scatter40, 8, 10 + i))
            data += runs(20, kn, [v + shift20 for v in spread(0.05, scatter20, 8, 20 + i)])
        cells = cells_of(data)
        return choose_width(cells, dependences(cells), "literal")
    # C_W = W s^2 / f: 20 x 0.1^2 = 0.2 against 40 x 0.1^2 = 0.4, 2x cheaper: width 20
    assert check(0.1, 0.1).width == 20
    # 20 x 0.13^2 = 0.338: only 1.18x cheaper: width 40
    assert check(0.13, 0.1).width == 40
    # cheaper but shifted by 0.01 (several combined errors): width 40
    assert check(0.1, 0.1, shift20=0.01).width == 40


def test_a_width_that_mostly_stops_is_not_taken_and_the_seeds_follow_the_scatter():
    data = []
    for i, kn in enumerate(KNS):
        # width 40: 6 of 8 flow (0.75, enough), two stopped and not selected
        data += runs(40, kn, spread(0.05, 0.15, 6, 30 + i)) + runs(40, kn, [None, None],
                                                                   ended="stopped")
        # width 20 agrees and is cheap, but only 5 of 8 flow
        data += runs(20, kn, spread(0.05, 0.05, 5, 40 + i)) + runs(20, kn, [None] * 3,
                                                                   ended="stopped")
    cells, found, (choice,) = analyse_widths(data)
    assert choice.width == 40
    # scatter 15 %: 6 selected runs a k_n; selected fraction 0.75: ceil(6 / 0.75) = 8 seeds
    assert choice.scatter == pytest.approx(0.15)
    assert (choice.runs_per_kn, choice.seeds) == (6, 8)
    # a widest width below the flow fraction: no width
    data = [r for r in data if not (r.params.get("width") == 40.0 and r.ended == "flowing")]
    data += runs(40, KNS[0], [0.05] * 5) + runs(40, KNS[1], [0.05] * 5)
    for kn in KNS:
        data += runs(40, kn, [None] * 3, ended="stopped")
    cells, found, (choice,) = analyse_widths(data)
    assert choice.width is None


def test_wilson_interval():
    low, high = wilson(8, 8)
    assert high == 1.0 and low == pytest.approx(0.6756, abs=1e-4)
    low, high = wilson(0, 10)
    assert low == 0.0 and high == pytest.approx(0.2775, abs=1e-4)
