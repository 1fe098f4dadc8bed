"""The transition study's observables on synthetic data with known answers
(postprocess/transition.py, docs/transition.md)."""
import numpy as np
import pytest

from postprocess.observables import contacts_per_disk
from postprocess.durations import (DURATION_EDGES, contact_durations, duration_density,
                                   tail_fraction)
from postprocess.transition import GROWTH_LIMIT, flow_state, transition_table

RNG = np.random.default_rng(14)


def test_contacts_per_disk_counts_a_disk_contact_for_both_disks():
    # 10 disks: 3 disk-disk contacts (6 in the sum) and 2 on the floor, then 5 and 0
    assert contacts_per_disk([6 + 2, 10 + 0], 10) == pytest.approx((0.8 + 1.0) / 2)


def test_duration_density_of_binary_collisions_is_a_spike_at_one():
    scaled = np.full(1000, 1.0) * (1 + RNG.uniform(-0.02, 0.02, 1000))
    density = duration_density(scaled)
    centre = np.flatnonzero(density)
    assert len(centre) <= 2 and np.all((DURATION_EDGES[centre] <= 1.02) &
                                       (DURATION_EDGES[centre + 1] >= 0.98))
    # a density: it integrates to the fraction of contacts inside the bins (all of them)
    assert np.sum(density * np.diff(DURATION_EDGES)) == pytest.approx(1.0)
    assert tail_fraction(scaled) == 0.0


def test_duration_density_of_an_exponential_tail():
    # durations 1 + exponential(mean 3): P(tau > 2) = exp(-1/3), density exp(-(x-1)/3)/3
    scaled = 1 + RNG.exponential(3.0, 200000)
    assert tail_fraction(scaled) == pytest.approx(np.exp(-1 / 3), abs=0.005)
    density = duration_density(scaled)
    centres = np.sqrt(DURATION_EDGES[1:] * DURATION_EDGES[:-1])
    inside = (centres > 3) & (centres < 10)
    exact = [np.exp(-(a - 1) / 3) - np.exp(-(b - 1) / 3) for a, b in
             zip(DURATION_EDGES[:-1][inside], DURATION_EDGES[1:][inside])]
    assert density[inside] * np.diff(DURATION_EDGES)[inside] == pytest.approx(exact, rel=0.05)


def test_contact_durations_split_by_kind_in_their_own_units_and_by_when_they_end():
    rows = {"start": np.array([5.0, 9.5, 12.0, 15.0]),
            "duration": np.array([0.1, 1.0, 0.02, 0.03]),
            "kind": np.array([1, 2, 1, 2])}
    d = contact_durations(rows, tau_c=0.01, tau_w=0.015, since=10.0)
    # the first ended before 10; the second began before 10 but ended after: it counts
    assert d["disk"] == pytest.approx([2.0])
    assert d["boundary"] == pytest.approx([1.0 / 0.015, 2.0])


def noisy(t, level):
    return level * (1 + 0.2 * np.sin(0.37 * t) + 0.05 * RNG.uniform(-1, 1, len(t)))


def test_flow_state_of_a_steady_an_accelerating_and_a_stopped_run():
    t = np.arange(0, 600, 0.1)
    state, growth = flow_state(t, noisy(t, 0.6), 100.0)
    assert state == "flowing" and growth == pytest.approx(1.0, abs=0.2)
    # free acceleration: E ~ t^2, growth over [100, 600] between the fifths = (550/150)^2
    state, growth = flow_state(t, 0.01 * t ** 2 + 1e-3, 100.0)
    assert state == "accelerating" and growth == pytest.approx((550 / 150) ** 2, rel=0.05)
    # a flow that came to rest at t = 300 without an early end, and one that ended early
    assert flow_state(t, np.where(t < 300, noisy(t, 0.6), 1e-7), 100.0)[0] == "stopped"
    assert flow_state(t[t < 300], noisy(t[t < 300], 0.6), 100.0, stopped_at=300.0)[0] == \
        "stopped"
    # just below and just above the limit: E rising linearly so that the fifths differ by
    # 0.9 and 1.1 times GROWTH_LIMIT (below it, a line without noise drifts)
    for factor, expected in ((0.9, "drifting"), (1.1, "accelerating")):
        g = factor * GROWTH_LIMIT
        # means of the first and last fifth of a line a + b t over [100, 600): a + 150 b and
        # a + 550 b
        b = (g - 1) / (550 - 150 * g)
        assert flow_state(t, 1 + b * t, 100.0)[0] == expected


def test_a_flow_whose_energy_drifts_by_more_than_it_fluctuates_is_not_averaged():
    """E rising by half over the span, or jumping to another level in its middle: neither
    grows by GROWTH_LIMIT, and neither is a steady flow; the same flow without the drift is."""
    t = np.arange(0, 600, 0.1)
    steady = noisy(t, 0.6)
    rising = steady * (1 + 0.5 * np.clip((t - 100) / 500, 0, 1))
    jumping = steady * np.where(t < 350, 1.0, 1.6)
    assert flow_state(t, steady, 100.0)[0] == "flowing"
    for energy in (rising, jumping):
        state, growth = flow_state(t, energy, 100.0)
        assert state == "drifting" and growth < GROWTH_LIMIT
    # a drift smaller than the fluctuation (E's sd about its line is ~0.14 of E here)
    assert flow_state(t, steady * (1 + 0.05 * (t - 100) / 500), 100.0)[0] == "flowing"


def run(scene, sin_theta, kn, seed, state, **observables):
    o = {"kn": kn, "label": "", "notes": "", "span": 100.0, "variables": {"kn": kn, "seed": seed}}
    for q, value in observables.items():
        o[q], o[q + "_err"] = value, 0.01 * abs(value)
    r = {"scene": scene, "sin_theta": sin_theta, "kn": kn, "seed": seed, "state": state,
         "growth": 1.0}
    if state == "flowing":
        r["observables"] = o
        r["durations"] = {"disk": np.array([1.0, 1.0, 3.0, 5.0]), "boundary": np.array([1.0])}
    return r


def test_transition_table_measures_known_exponents_and_counts_states():
    from postprocess.study import combine_seeds
    kn = [5e4, 2e5, 8e5, 3.2e6]
    runs = [run("frictional_flow", 0.2, k, s, "flowing", N_c=20 * (k / 5e4) ** 0.4,
                N_w=5 * (k / 5e4) ** 0.4, t_c=0.4, mc_c=0.1 + 0.01 * (2 * s - 3),
                t_multiple=0.3, z=2.5,
                E_total=0.6) for k in kn for s in (1, 2)]
    runs += [run("frictional_flow", 0.2, 5e4, 3, "stopped"),
             run("frictional_flow", 0.45, 5e4, 1, "accelerating")]
    groups = {("frictional_flow", 0.2): combine_seeds([r["observables"] for r in runs
                                                      if "observables" in r])}
    table = transition_table(runs, groups)
    assert [(r["sin_theta"], r["state"]) for r in table] == [(0.2, "flowing"),
                                                            (0.45, "accelerating")]
    row = table[0]
    assert (row["runs"], row["flowing"], row["stopped"]) == (9, 8, 1)
    assert row["exponent_N_c"] == pytest.approx(0.4) and row["exponent_N_w"] == pytest.approx(0.4)
    assert row["kn_stiffest"] == 3.2e6
    assert row["mc_fraction"] == pytest.approx(0.25)
    # seeds at 0.09 and 0.11 with equal spans: error across seeds sqrt(2 (2 x 0.5^2 0.01^2))
    # = 0.01 on mc_c; t_c the same in both: no error
    assert row["mc_fraction_err"] == pytest.approx(0.01 / 0.4)
    assert row["z"] == pytest.approx(2.5)
    assert row["tail_disk"] == pytest.approx(0.5) and row["tail_boundary"] == 0.0
    assert row["contacts_disk"] == 8
    assert np.isnan(table[1]["exponent_N_c"]) and "kn_stiffest" not in table[1]


def test_the_transition_study_of_summaries_says_it_needs_the_raw_outputs(tmp_path, capsys):
    """data/transition holds the transition sweep's summaries: the study needs every sample
    of energy.txt and the contact rows (it said "no sweep points here", as of an empty
    directory)."""
    from pathlib import Path
    from postprocess.__main__ import main
    summaries = Path(__file__).resolve().parents[2] / "data" / "transition"
    assert main(["transition", str(summaries), "--output", str(tmp_path / "t")]) == 2
    assert (f"postprocess: {summaries}: the transition study needs the raw outputs, and these "
            "are run summaries (<scene>/<point>.json): summaries hold E(t) only as its means "
            "over windows of 1") in capsys.readouterr().err
    assert not (tmp_path / "t").exists()


def test_a_transition_sweep_without_contact_rows_gets_its_report_without_p_tau(tmp_path):
    """A sweep run without the deck variable rows has no contact durations: the report and the
    exponents' figure are written, the P(tau) figure is left out with the reason (an empty
    figure raised from matplotlib)."""
    from postprocess.quantities import COLUMNS
    from postprocess.study import combine_seeds
    from postprocess.write_transition import write_transition_report
    kn = [5e4, 2e5, 8e5]
    runs = [run("frictional_flow", 0.2, k, s, "flowing", N_c=20 * (k / 5e4) ** 0.4,
                N_w=5 * (k / 5e4) ** 0.4, t_c=0.4, mc_c=0.1, t_multiple=0.3, z=2.5,
                E_total=0.6) for k in kn for s in (1, 2)]
    for r in runs:
        r["durations"] = {"disk": np.array([]), "boundary": np.array([])}
        r["point"] = f"kn{r['kn']:g}_seed{r['seed']}"
        r["observables"].update(tau_c=1e-3, tau_w=1e-3, n_boundary=10)
        for q in COLUMNS:
            r["observables"].setdefault(q, 1.0)
            r["observables"].setdefault(q + "_err", 0.0)
    groups = {("frictional_flow", 0.2): combine_seeds([r["observables"] for r in runs])}
    report = write_transition_report("sweep", runs, groups, [], tmp_path)
    assert (tmp_path / "transition.png").exists() and not (tmp_path / "durations.png").exists()
    assert "No P(tau) figure: no flowing inclination has contact rows" in report.read_text()
