"""The hard-sphere-limit decision rule (postprocess/limit.py, docs/hard_sphere_limit.md) on
synthetic runs whose answer is known: each branch must be reachable and must not be reached by
the other physics."""
import numpy as np
import pytest

from postprocess import durations, limit
from postprocess.formatting import split_lines, tail_lines
from postprocess.scenes import scene

# The stiff preset's k_n (2^p x 10^5, p = 4, 6, ..., 14) and eight runs at each.
KN = 1e5 * 2.0 ** np.arange(4, 16, 2)
RUNS = 8


def synthetic_runs(truth, noise, runs=RUNS, kn=KN, seed=1):
    """Runs whose quantity is truth(kn) with a relative seed-to-seed scatter `noise` (the
    frictional flow's energy levels give ~10-20 %)."""
    rng = np.random.default_rng(seed)
    return [{"kn": k, "span": 300.0, "E_total": 0.6,
             "mc_c": truth(k) * (1 + noise * rng.standard_normal())}
            for k in kn for _ in range(runs)]


def power(k):
    return 3.0 * k ** -0.2       # m_c keeps falling as the paper preset's fit: ~k_n^-0.2


def floor(k):
    # a decay onto a floor: 0.02 of the stiffest value 0.022
    return 0.02 + 0.07 * (k / 1.6e6) ** -0.5


def slow_floor(k):
    # a slow decay onto a floor that is half the stiffest value: beyond this preset's reach
    return 0.02 + 0.07 * (k / 1.6e6) ** -0.2


def test_pure_power_law_vanishes():
    # 5 % scatter: the rule's power is ~97 % here (scripts/studies/limit_rule_power.py)
    d = limit.decide(synthetic_runs(power, 0.05), "mc_c", samples=400)
    assert d.verdict == "vanishing", d.why
    # the fit recovers the exponent it was made with
    assert abs(d.fits.b_power - 0.2) < 3 * d.fits.b_power_error + 0.02


def test_floor_is_finite():
    # 15 % scatter: the rule's power is ~100 % here
    d = limit.decide(synthetic_runs(floor, 0.15), "mc_c", samples=400)
    assert d.verdict == "finite", d.why
    # the interval sits at the floor it was made with
    low, high = d.floor_interval
    assert 0.02 / 1.5 < high and low < 0.02 * 1.5


def test_too_noisy_is_undecided():
    # a slow decay onto a floor, in 25 % scatter: the rule must not pick a side
    d = limit.decide(synthetic_runs(slow_floor, 0.25, runs=3), "mc_c", samples=400)
    assert d.verdict == "undecided", d.why


def test_too_short_a_series_is_not_decided():
    # the quick study's range: four k_n over less than two decades
    runs = synthetic_runs(power, 0.1, kn=1.25e4 * 4.0 ** np.arange(4))
    d = limit.decide(runs, "mc_c", samples=50)
    assert d.verdict.startswith("not applied")


def test_kn_with_too_few_runs_is_left_out_and_listed():
    runs = synthetic_runs(power, 0.1) + [{"kn": 1e10, "span": 300.0, "E_total": 0.6,
                                           "mc_c": 0.01}]
    series, lacking = limit.per_kn(runs, "mc_c")
    assert 1e10 not in series.kn and lacking == [(1e10, 1)]


def test_running_exponents_of_a_power_law():
    runs = synthetic_runs(power, 0.0)
    for r in runs:    # a little scatter, so that the errors are not zero
        r["mc_c"] *= 1 + 1e-3 * (r is runs[0])
    series, _ = limit.per_kn(runs, "mc_c")
    s = np.array([e[2] for e in limit.running_exponents(series)])
    assert np.allclose(s, -0.2, atol=1e-3)


def test_levels_split_the_runs_by_energy():
    runs = synthetic_runs(power, 0.1)
    for i, r in enumerate(runs):
        r["E_total"] = (0.4, 0.65, 0.95)[i % 3]
    levels = dict(scene("frictional_flow").limit_levels)
    decisions = limit.decide_within_levels(runs, "mc_c", levels, samples=50)
    assert set(decisions) == {"low", "middle", "high"}
    # two or three runs per level at each of six k_n: the rule applies in each level
    assert all(not d.verdict.startswith("not applied") for d in decisions.values())


def claim_status(runs):
    """The status of the claim frictional-mc-limit on a frictional series built from runs."""
    from postprocess.reference import evaluate, load_claims
    rows = []
    for k in sorted({r["kn"] for r in runs}):
        members = [r for r in runs if r["kn"] == k]
        rows.append({"kn": k, "label": "", "runs": members, "mc_c": members[0]["mc_c"],
                     "mc_c_err": 0.0})
    claim = [c for c in load_claims() if c["id"] == "frictional-mc-limit"]
    (_, _, _, status), = evaluate({"frictional_flow": rows}, claim)
    return status


def test_the_papers_claim_passes_on_a_floor_and_fails_on_a_power_law():
    assert claim_status(synthetic_runs(floor, 0.15)) == "pass (finite)"
    assert claim_status(synthetic_runs(power, 0.05)) == "differs (vanishing)"
    assert claim_status(synthetic_runs(slow_floor, 0.25, runs=3)) == "FAIL (undecided)"
    # the quick study's short series: not evaluated, neither pass nor fail
    short = synthetic_runs(power, 0.1, kn=1.25e4 * 4.0 ** np.arange(4))
    assert claim_status(short).startswith("not evaluated")


def rows_of_runs(runs):
    """A scene's rows (one per k_n, its runs behind it) as the analysis gives the limit command."""
    return [{"kn": k, "label": "", "runs": [r for r in runs if r["kn"] == k]}
            for k in sorted({r["kn"] for r in runs})]


def test_limit_command_writes_the_verdicts_and_the_figure(tmp_path, capsys):
    from postprocess.write_limit import write_limit
    from postprocess.selection import Selection
    runs = synthetic_runs(floor, 0.15)
    for i, r in enumerate(runs):
        r.update(mc_w=2 * r["mc_c"], t_multiple=0.1 * (r["kn"] / 1.6e6) ** -0.3 *
                 (1 + 0.05 * np.sin(i)), E_total=(0.4, 0.65, 0.95)[i % 3])
    rows = rows_of_runs(runs)
    assert write_limit(tmp_path, {"frictional_flow": rows}, tmp_path / "limit", Selection(),
                       {}) == 0
    text = (tmp_path / "limit" / "limit.md").read_text()
    assert "t_c - N_c tau_c: **finite**" in text
    assert "time with two or more contacts: **vanishing**" in text
    assert "### Within one energy level" in text
    assert (tmp_path / "limit" / "limit_frictional_flow_0.png").stat().st_size > 10000
    out = capsys.readouterr().out
    assert "limit report:" in out
    # the verdicts within the levels on the terminal too, as limit.md's table has them
    table = {line.split(" | ")[0].lstrip("| "): line.strip(" |").split(" | ")[1:]
             for line in text.splitlines() if line.startswith("| t_c - N_c tau_c |")}
    applied = [(name, verdict) for name, verdict in zip(("low", "middle", "high"),
                                                        table["t_c - N_c tau_c"])
               if not verdict.startswith("not applied")]
    assert applied
    assert "t_c - N_c tau_c, within a level: " + "; ".join(
        f"{name} {verdict}" for name, verdict in applied) in out


def test_limit_command_decides_the_3d_chute_without_levels(tmp_path, capsys):
    # the same series as the 3D chute's: decided alike; the 3D flows have no energy levels,
    # so step 4 is said to be skipped rather than split by the 2D disks' levels
    from postprocess.write_limit import write_limit
    from postprocess.selection import Selection
    runs = synthetic_runs(power, 0.05)
    for r in runs:
        r.update(mc_w=2 * r["mc_c"], t_multiple=3 * r["mc_c"])
    rows = rows_of_runs(runs)
    assert write_limit(tmp_path, {"chute_3d": rows}, tmp_path / "limit", Selection(), {}) == 0
    text = (tmp_path / "limit" / "limit.md").read_text()
    assert text.count("# 3D chute") == 1 and "t_c - N_c tau_c: **vanishing**" in text
    assert "### Within one energy level" not in text and "no energy levels" in text
    # a scene the rule is not for: refused, saying which scenes it applies to
    assert write_limit(tmp_path, {"single_disk": rows}, tmp_path / "other", Selection(),
                       {}) == 2
    assert "collisional_flow, frictional_flow, chute_3d" in capsys.readouterr().err


def test_limit_command_decides_the_collisional_floor_alone(tmp_path, capsys):
    # the collisional flow's disks collide binarily (t_c - N_c tau_c < 0): the rule decides on
    # t_w - N_w tau_w only, here a flat floor that rule 2 calls finite
    from postprocess.write_limit import write_limit
    from postprocess.selection import Selection
    runs = synthetic_runs(flat, 0.10)
    for r in runs:
        r.update(mc_w=r["mc_c"], mc_c=-0.02, t_multiple=0.0)
    rows = rows_of_runs(runs)
    assert write_limit(tmp_path, {"collisional_flow": rows}, tmp_path / "limit", Selection(),
                       {}) == 0
    text = (tmp_path / "limit" / "limit.md").read_text()
    assert "t_w - N_w tau_w: **finite**" in text
    assert "t_c - N_c tau_c" not in text and "two or more contacts" not in text


def rows_of(contacts):
    """Contact rows from (i, j, kind, start, duration) tuples."""
    data = np.array(contacts, dtype=float)
    return {"id_i": data[:, 0], "id_j": data[:, 1], "kind": data[:, 2], "start": data[:, 3],
            "duration": data[:, 4]}


def test_split_of_the_multiple_contact_time():
    tau = 0.01
    rows = rows_of([
        (1, 2, 1, 0.0, 1.0),        # a lasting contact of disks 1 and 2 over [0, 1]
        (1, 3, 1, 0.2, 0.01),       # a collision of 1 with 3 during it: lasting part, 0.01
        (4, 5, 1, 0.5, 0.01),       # two short collisions of disk 4 overlapping by 0.005:
        (4, 6, 1, 0.505, 0.01),     #   a burst
        (7, 0, 2, 0.0, 1.0),        # disk 7 resting on the floor, alone: no multiple contact
    ])
    split = durations.multiple_contact_split(rows, tau, tau, 0.0, 1.0, n_particles=10)
    assert split["lasting"] == pytest.approx(0.01 / 10)
    assert split["bursts"] == pytest.approx(0.005 / 10)
    assert split["t_multiple_rows"] == pytest.approx(0.015 / 10)
    # contact time: 2 + 0.02 + 0.04 + 1 (each disk-disk contact counts for both disks)
    assert split["lasting_share_of_contact_time"] == pytest.approx(3.0 / 3.06)
    # the window clips: over [0.3, 1.0] only the burst is left
    clipped = durations.multiple_contact_split(rows, tau, tau, 0.3, 1.0, n_particles=10)
    assert clipped["lasting"] == 0.0 and clipped["bursts"] == pytest.approx(0.005 / 7)


def test_runaway_events_are_found_and_level_changes_are_not():
    t = np.arange(0.0, 400.0, 0.1)
    e = np.where(t < 10, 7.0, 0.6) + 0.05 * np.sin(t)      # the first collapse, then a flow
    e[(t > 150) & (t < 250)] = 1.0                           # a change of level: no event
    assert limit.runaway_events(t, e) == []
    e[(t >= 62) & (t < 70)] = 25.0 * np.exp(-(t[(t >= 62) & (t < 70)] - 62))   # a runaway
    e[(t >= 300) & (t < 301.5)] = 4.0                                       # and a smaller one
    assert limit.runaway_events(t, e) == [62.0, 300.0]


def test_fisher_exact_gives_the_textbook_values():
    """Fisher's lady tasting tea (3 of 4 cups told right each way): one-sided p 17/70, two-sided
    34/70. All 11 events in one series of 124 against none of 120: one-sided p is the chance
    that 11 draws from the 244 runs all come from the 124, C(124, 11)/C(244, 11), and the
    two-sided p adds the tables on the other side that are as unlikely (11 of the 120 without
    any of the 124 is not: p two-sided < 2 x one-sided). A wrong tail or margin fails these."""
    from math import comb
    assert limit.fisher_exact(3, 4, 1, 4) == pytest.approx((17 / 70, 34 / 70), rel=1e-12)
    one, two = limit.fisher_exact(11, 124, 0, 120)
    assert one == pytest.approx(comb(124, 11) / comb(244, 11), rel=1e-12)
    assert one < two < 2 * one
    assert limit.fisher_exact(0, 120, 11, 124) == pytest.approx((one, two), rel=1e-12)
    # no difference at all: two-sided 1; one-sided P(X >= 5), the median draw's upper tail
    one, two = limit.fisher_exact(5, 50, 5, 50)
    assert two == pytest.approx(1.0) and 0.5 < one < 1.0


def test_runaway_table_tests_each_series_against_the_main_one():
    """limit.md's runaway table: per series and k_n, then each series' totals against the main
    series (the one at the most k_n) by Fisher's exact test."""
    from types import SimpleNamespace
    from postprocess.write_limit import runaway_lines
    t = np.arange(0.0, 400.0, 0.5)

    def record(kn, tangential, runaway):
        e = np.full(len(t), 0.6)
        if runaway:
            e[(t >= 100) & (t < 103)] = 20.0
        return SimpleNamespace(energy={"t0": 0.0, "window": 0.5, "E": e}, params={"kn": kn},
                               variables={"kn": kn, "tangential": tangential})
    records = ([record(kn, "literal", k < 3) for kn in (1e6, 4e6, 1.6e7) for k in range(10)] +
               [record(kn, "cutback", False) for kn in (1e6, 4e6) for k in range(10)])
    lines = runaway_lines(records)
    assert "| tangential literal | 1e+06 | 10 | 3 | 100, 100, 100 |" in lines
    one, two = limit.fisher_exact(0, 20, 9, 30)
    assert f"| tangential cutback | 20 | 0 | {one:.2g} | {two:.2g} |" in lines
    assert "| tangential literal | 30 | 9 | - | - |" in lines


# ---- rule 2: rule 1's branches, and "finite" for a series shown not to fall

def flat(k):
    return 0.2 + 0.0 * k         # like t_w - N_w tau_w of the stiff preset: no fall at all


def test_rule_2_says_finite_for_a_series_that_does_not_fall():
    # 10 % scatter (t_w - N_w tau_w's, measured on the stiff preset): the fall over the range
    # is bounded well below a quarter; a rule that needed a decay onto a floor says undecided
    runs = synthetic_runs(flat, 0.10)
    d = limit.decide(runs, "mc_c", samples=400)
    assert d.verdict == "finite" and d.why.startswith("it does not fall"), d.why
    b, error, upper = d.decay
    assert abs(b) < 3 * error and upper < d.decay_limit
    # the resolution is a fall of a quarter over the series' range
    assert (KN[-1] / KN[0]) ** -d.decay_limit == pytest.approx(0.75)
    assert limit.decide(runs, "mc_c", samples=400, rule=1).verdict != "finite"


def test_rule_2_says_finite_for_a_rising_series():
    d = limit.decide(synthetic_runs(lambda k: 0.01 * (k / 1.6e6) ** 0.1, 0.10), "mc_c",
                     samples=400)
    assert d.verdict == "finite" and d.decay[0] < 0, d.why


def test_rule_2_does_not_call_a_slow_decay_finite():
    # k^-0.1 loses half its value over the preset's range: never "does not fall", however
    # much or little scatter; with little scatter the power law is seen
    for noise, runs in ((0.02, 8), (0.10, 8), (0.35, 3)):
        d = limit.decide(synthetic_runs(lambda k: 0.2 * (k / 1.6e6) ** -0.1, noise, runs),
                         "mc_c", samples=400)
        assert not d.why.startswith("it does not fall"), (noise, runs, d.why)


def test_rule_2_keeps_rule_1s_branches():
    assert limit.decide(synthetic_runs(power, 0.05), "mc_c", samples=400).verdict == \
        "vanishing"
    assert limit.decide(synthetic_runs(floor, 0.15), "mc_c", samples=400).verdict == "finite"
    assert limit.decide(synthetic_runs(slow_floor, 0.25, runs=3), "mc_c",
                        samples=400).verdict == "undecided"


def test_rule_2_is_undecided_where_few_noisy_runs_cannot_bound_the_fall():
    # flat, but 35 % scatter (t_c - N_c tau_c's over all levels) and three runs per k_n: the
    # fall cannot be bounded to a quarter, and nothing is decided
    d = limit.decide(synthetic_runs(flat, 0.35, runs=3), "mc_c", samples=400)
    assert d.verdict == "undecided", d.why


def test_rule_2_needs_positive_values_for_the_no_fall_branch():
    runs = synthetic_runs(flat, 0.10)
    for r in runs:
        r["mc_c"] -= 0.2          # values about zero: no logarithm, no "does not fall"
    d = limit.decide(runs, "mc_c", samples=100)
    assert not np.isfinite(d.decay[0]) and d.verdict != "finite"


def test_unknown_rule_is_refused():
    with pytest.raises(ValueError, match="1 or 2"):
        limit.decide(synthetic_runs(flat, 0.10), "mc_c", samples=10, rule=3)


def test_split_table_gives_the_error_over_runs():
    # two runs at one k_n whose lasting parts are 0.010 and 0.020: mean 0.015, standard error
    # 0.005 (a table of means alone cannot say whether the lasting part shrinks with k_n)
    def split(lasting):
        one = {"t_multiple_counters": 0.03, "t_multiple_rows": 0.03, "lasting": lasting,
               "bursts": 0.03 - lasting, "unseen": 0.0, "lasting_share_of_contact_time": 0.5}
        return {durations.LASTING: one, durations.LASTING_ALSO: dict(one)}
    lines = split_lines([(1e6, split(0.010)), (1e6, split(0.020)), (4e6, split(0.01))])
    assert "| 1e+06 | 2 | 0.0300 +- 0.0000 | 0.0300 +- 0.0000 | 0.0150 +- 0.0050 |" in lines[2]
    assert "| 4e+06 | 1 | 0.0300 | 0.0300 | 0.0100 |" in lines[3]


def test_tail_table_is_the_mean_of_each_runs_weight_with_its_error():
    """Three runs at one k_n with 1, 5 and 0 of 10 disk contacts in the tail: per-run weights
    0.1, 0.5, 0 give a mean of 0.2 and a standard error of 0.153 over the runs (a table without
    the error cannot say whether the tail shrinks with k_n). Boundary: 1 of 10 and 9 of 90 are
    0.1 each (error 0), and the run without boundary contacts is left out of that column; had it
    counted as a weight 0 the mean would be 0.067."""
    def contacts(disk_tail, disk, boundary_tail, boundary):
        return {"tail": {"disk": disk_tail, "boundary": boundary_tail},
                "contacts": {"disk": disk, "boundary": boundary}}
    lines = tail_lines([(1e6, contacts(1, 10, 1, 10)), (1e6, contacts(5, 10, 9, 90)),
                        (1e6, contacts(0, 10, 0, 0)), (4e6, contacts(2, 10, 3, 10))], "disk")
    assert lines[2] == "| 1e+06 | 3 | 30 | 0.2000 +- 0.1528 | 100 | 0.1000 +- 0.0000 |"
    assert lines[3] == "| 4e+06 | 1 | 10 | 0.2000 | 10 | 0.3000 |"


def test_a_kn_whose_runs_all_measure_zero_is_named_and_leaves_the_others_errors_alone():
    """One k_n whose runs all measure 0 has no relative scatter: it made the pooled scatter
    nan (a numpy warning) and every k_n's error with it, and the rule said "a k_n whose runs
    all agree exactly" of the whole series. Now the others' errors are the pool of their own
    scatter, that k_n keeps its error 0 and is named."""
    import warnings
    runs = synthetic_runs(power, 0.1)
    for r in runs:
        if r["kn"] == KN[2]:
            r["mc_c"] = 0.0
    alone, _ = limit.per_kn([r for r in runs if r["kn"] != KN[2]], "mc_c")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        series, _ = limit.per_kn(runs, "mc_c")
        d = limit.decide(runs, "mc_c", samples=50)
    others = series.kn != KN[2]
    assert series.error[others] == pytest.approx(alone.error)
    assert series.error[~others] == [0.0]
    assert d.verdict == (f"not applied: at k_n = {KN[2]:g} its {RUNS} runs all measure 0 "
                         "exactly (no error to weigh it by)")


def test_an_undecided_verdict_says_why_its_exponent_has_no_error():
    """A flat series scattered by 40 % over three runs a k_n: rule 1's profile of the power-law
    exponent has its delta chi^2 = 1 interval open at the scan's lower edge, so the exponent has
    no error; the verdict says so in words rather than printing '+- inf'."""
    d = limit.decide(synthetic_runs(lambda k: 0.05, 0.4, runs=3), "mc_c")
    assert d.verdict == "undecided" and not np.isfinite(d.fits.b_power_error)
    assert "inf" not in d.why
    assert f"(no error: its delta chi2 = 1 interval is open within the scanned b >= " \
           f"{limit.EXPONENTS[0]:g})" in d.why


def rows_of_series(series):
    """A scene's rows as the analysis gives them from several series: series is [(variables
    other than kn and seed, runs)]; labels by the variables that vary, as study.combine_seeds."""
    from postprocess.study import label, varying_variables
    varying = varying_variables([v for v, _ in series])
    rows = []
    for variables, runs in series:
        for k in sorted({r["kn"] for r in runs}):
            rows.append({"kn": k, "label": label(variables, varying),
                         "variables": dict(variables, kn=k),
                         "runs": [r for r in runs if r["kn"] == k]})
    return rows


def scaled(runs, factor):
    return [dict(r, **{q: factor * r[q] for q in ("mc_c", "mc_w", "t_multiple")}) for r in runs]


def test_limit_beside_another_sweep_matches_its_series_and_measures_the_difference(tmp_path,
                                                                                   capsys):
    # There: the paper's width, two time steps of the literal law and the cut-back law; here:
    # width 40, the two laws at dt_fraction 0.05, each 0.8 times its counterpart's runs. A
    # series matched with the wrong one (the other law, 1.5 times; the other step, 2 times)
    # would be 40-60 % lower, not 20 %.
    from postprocess.write_limit import write_limit
    from postprocess.selection import Selection
    from postprocess.study import counterparts
    base = synthetic_runs(power, 0.1)
    for i, r in enumerate(base):
        r.update(mc_w=0.2 + 0.01 * np.sin(i), t_multiple=3 * r["mc_c"])
    literal, step = {"dt_fraction": 0.05}, {"dt_fraction": 0.025}
    cutback = {"dt_fraction": 0.05, "tangential": "cutback"}
    there = rows_of_series([(literal, base), (step, scaled(base, 2.0)),
                            (cutback, scaled(base, 1.5))])
    here = rows_of_series([(dict(literal, width=40), scaled(base, 0.8)),
                           (dict(cutback, width=40), scaled(base, 1.2))])
    apart, match = counterparts(here, there)
    assert apart == {"width": (40, None)}
    assert match == {"": "dt_fraction 0.05",
                     "tangential cutback": "dt_fraction 0.05, tangential cutback"}
    assert write_limit(tmp_path, {"frictional_flow": here}, tmp_path / "limit", Selection(), {},
                       beside=("width 10", {"frictional_flow": there})) == 0
    out = capsys.readouterr().out
    lines = [line for line in out.splitlines()
             if line.startswith("beside width 10") and "shared k_n" in line]
    assert len(lines) == 6
    for line in lines:
        # a copy scaled by a constant: lower at every k_n by exactly that factor, the same
        # decay exponent (the fit's chi^2 does not change under the scaling)
        assert "here lower at 6, higher at 0 of 6 shared k_n" in line
        assert "here / there - 1 from -20% to -20%" in line
        assert "b here - there +0.000 +- " in line
    text = (tmp_path / "limit" / "limit.md").read_text()
    assert "width: 40 here, the deck's default there" in text
    assert "### variant tangential cutback beside variant dt_fraction 0.05, tangential cutback" \
        in text
    # every run at E 0.6: the middle level alone is judged, alike in a copy scaled by a constant
    within = [line for line in text.splitlines()
              if line.startswith("| t_c - N_c tau_c | not applied / ")]
    assert len(within) == 2
    for line in within:
        low, middle, high = line.strip(" |").split(" | ")[1:]
        verdict_there, verdict_here = middle.split(" / ")
        assert low == high == "not applied / not applied"
        assert verdict_there == verdict_here != "not applied"
    # here alone has a series there lacks: not matched with another
    lone = rows_of_series([(dict(literal, width=40), base),
                           (dict(literal, width=40, integrator="ab2"), base)])
    assert counterparts(lone, there)[1] == {"": "dt_fraction 0.05", "integrator ab2": None}
