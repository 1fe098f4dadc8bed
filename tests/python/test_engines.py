"""postprocess/engines.py: the rule that compares a scene run in two engines. It must pass two
engines that sample the same physics, fail a shift of the mean beyond its resolution (four
combined standard errors: here a shift of six fails, one of three passes), and decide nothing
from a single run."""
import math
from types import SimpleNamespace

import numpy as np

from postprocess.engines import AGREEMENT_SIGMAS, COMPARED, HARD_COMPARED, compare_engines, left_out


def runs(engine, kn, values, scene="chute_3d"):
    """Runs of one engine, the observable values of each seed (every COMPARED one the same)."""
    return [SimpleNamespace(scene=scene, variables={"engine": engine} if engine else {},
                            observables={"kn": kn, **{q: v for q in COMPARED}})
            for v in values]


def test_the_same_physics_agrees_and_a_shift_beyond_the_resolution_differs():
    rng = np.random.default_rng(1)
    same = runs(None, 5e4, 1 + 0.02 * rng.standard_normal(4)) + \
        runs("liggghts", 5e4, 1 + 0.02 * rng.standard_normal(4))
    assert {c.verdict for c in compare_engines(same)} == {"agree"}
    # lammps, named or not, is the default engine; a shift of 6 combined errors differs
    base = 1 + 0.02 * np.array([-1.0, -0.3, 0.4, 0.9])
    se = np.std(base, ddof=1) / 2
    shifted = runs("lammps", 5e4, base) + runs("liggghts", 5e4, base + 6 * math.sqrt(2) * se)
    comparisons = compare_engines(shifted)
    assert len(comparisons) == len(COMPARED)
    assert {c.verdict for c in comparisons} == {"differ"}
    assert comparisons[0].allowed == AGREEMENT_SIGMAS * math.sqrt(2) * se
    # 3 combined errors is within the rule
    near = runs("lammps", 5e4, base) + runs("liggghts", 5e4, base + 3 * math.sqrt(2) * se)
    assert {c.verdict for c in compare_engines(near)} == {"agree"}


def test_one_run_decides_nothing_and_one_engine_is_no_comparison():
    single = runs("lammps", 8e5, [1.0, 1.1]) + runs("liggghts", 8e5, [1.05])
    assert {c.verdict for c in compare_engines(single)} == {"undecided"}
    assert compare_engines(runs("lammps", 8e5, [1.0, 1.1])) == []
    # runs at other k_n are other comparisons
    two = runs("lammps", 8e5, [1.0, 1.1]) + runs("liggghts", 5e4, [1.0, 1.1])
    assert compare_engines(two) == []


def test_against_the_hard_engine_the_rates_are_compared_and_runs_without_averages_are_said():
    """The event-driven engine has no contact times: E, N_c and N_w are compared. A run
    without averages (a frictional run whose steady parts the selection left out) is not
    silently dropped: left_out names it, by scene and engine."""
    hard = [SimpleNamespace(scene="collisional_flow", variables={"engine": "event_driven"},
                            observables={"kn": 1e7, **{q: 1.0 for q in HARD_COMPARED}})
            for _ in range(2)]
    soft = runs("lammps", 1e7, [1.0, 1.0], scene="collisional_flow")
    for r in soft:
        r.observables.update(N_w=1.0)
    comparisons = compare_engines(hard + soft)
    assert [c.quantity for c in comparisons] == list(HARD_COMPARED)
    # the two collision rules of the event-driven engine compare as two engines
    for rule, group in (("paper", hard), ("soft", hard[:1] * 2)):
        for r in group:
            r.params = {"rule": rule}
    assert {tuple(sorted(c.means)) for c in compare_engines(hard)} == \
        {("event_driven (paper)", "event_driven (soft)")}
    empty = SimpleNamespace(scene="frictional_flow", variables={}, observables=None,
                            point="p", reason="no steady part kept")
    assert left_out(hard + soft + [empty]) == {("frictional_flow", "lammps"):
                                               [("p", "no steady part kept")]}
    # a summary read with another selection than its own: not read, its engine unknown
    unread = SimpleNamespace(scene="collisional_flow", variables=None, observables=None,
                             point="q", reason="its steady parts were found with ...")
    assert list(left_out([unread])) == [("collisional_flow", "unknown: not read")]
