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


def flow_profiles(runs_count, rng, height=10.0, slip=1.0, layer=None, bins=100):
    """Per-run density and v_x profiles of a synthetic flow on bins of width 0.2: a density
    plateau up to `height`, v_x rising linearly from `slip`, noise of a few per cent a run; a
    `layer` (first bin, last bin, extra density) adds a layer of its own."""
    y = 0.2 * (np.arange(bins) + 0.5)
    density = np.where(y < height, 0.8, 0.8 * np.exp(-(y - height)))
    vx = slip + 0.5 * y
    if layer:
        density = density.copy()
        density[layer[0]:layer[1]] += layer[2]
    noise = lambda base: base * (1 + 0.03 * rng.standard_normal((runs_count, bins)))
    return noise(density), noise(vx)


def test_the_profiles_of_one_flow_agree_and_a_taller_flow_a_slip_or_a_layer_differ():
    from postprocess.engines import compare_profiles
    rng = np.random.default_rng(7)
    soft_density, soft_vx = flow_profiles(4, rng)
    hard_density, hard_vx = flow_profiles(6, rng)
    occupied = np.ones(100, bool)
    assert compare_profiles(soft_density, hard_density, occupied, occupied).verdict == "agree"
    assert compare_profiles(soft_vx, hard_vx, occupied, occupied).verdict == "agree"
    # a flow 5 % taller: the density's edge moves by 2.5 bins, and the tail above it differs
    taller, _ = flow_profiles(6, rng, height=10.5)
    assert compare_profiles(soft_density, taller, occupied, occupied).verdict == "differ"
    # a slip at the floor of 0.3 against v_x's 3 % noise: every bin near the floor differs
    _, slipping = flow_profiles(6, rng, slip=1.3)
    assert compare_profiles(soft_vx, slipping, occupied, occupied).verdict == "differ"
    # a chattering layer of three bins at the floor, 30 % denser: differs by the neighbours alone
    layered, _ = flow_profiles(6, rng, layer=(0, 3, 0.25))
    result = compare_profiles(soft_density, layered, occupied, occupied)
    assert result.verdict == "differ" and result.longest_run >= 3 and result.differing <= 10


def test_the_profiles_compare_only_bins_both_sides_fill_and_need_two_runs_a_side():
    from postprocess.engines import compare_profiles
    rng = np.random.default_rng(3)
    soft_density, _ = flow_profiles(4, rng)
    hard_density, _ = flow_profiles(6, rng)
    # the hard side's top half empty: a tail there would differ, but is not compared
    hard_density[:, 50:] = 0.0
    occupied_hard = np.arange(100) < 50
    result = compare_profiles(soft_density, hard_density, np.ones(100, bool), occupied_hard)
    assert result.compared == 50 and result.verdict == "agree"
    assert compare_profiles(soft_density[:1], hard_density, np.ones(100, bool),
                            occupied_hard).verdict == "undecided"
