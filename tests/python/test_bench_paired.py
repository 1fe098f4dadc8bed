"""bench/paired.py's goal verdict: a one-sided sign test on paired ratios, three ways."""
import math

from bench import paired


def test_binomial_tail_against_its_definition():
    assert paired.binomial_tail(1, 1) == 0.5
    assert paired.binomial_tail(9, 0) == 1.0
    assert paired.binomial_tail(9, 10) == 0.0
    # 8 or more of 9: (9 + 1) / 512
    assert math.isclose(paired.binomial_tail(9, 8), 10 / 512)
    # 15 or more of 21, summed term by term
    assert math.isclose(paired.binomial_tail(21, 15),
                        sum(math.comb(21, k) for k in range(15, 22)) / 2 ** 21)


def test_clearly_below_is_met_and_clearly_above_is_not():
    assert paired.against_goal([0.9] * 9, 1.0).startswith("met (9 of 9")
    assert paired.against_goal([1.1] * 9, 1.0).startswith("not met (0 of 9")


def test_a_ratio_at_the_goal_within_the_noise_is_undecided():
    # 9 rounds, 5 below and 4 above: neither side rejects (p = 0.5 and 0.75)
    ratios = [0.98, 0.99, 0.995, 0.997, 0.999, 1.001, 1.003, 1.01, 1.02]
    assert paired.against_goal(ratios, 1.0).startswith("undecided (5 of 9")


def test_the_boundary_of_the_test_at_nine_and_twenty_one_rounds():
    # 8 of 9 below: p = 10/512 < 0.05, met; 7 of 9: p = 46/512 = 0.09, not decided
    assert paired.against_goal([0.9] * 8 + [1.1], 1.0).startswith("met")
    assert paired.against_goal([0.9] * 7 + [1.1] * 2, 1.0).startswith("undecided")
    # 15 of 21: p = 0.039, met; 14 of 21: p = 0.095
    assert paired.against_goal([0.9] * 15 + [1.1] * 6, 1.0).startswith("met")
    assert paired.against_goal([0.9] * 14 + [1.1] * 7, 1.0).startswith("undecided")


def test_a_round_at_the_goal_exactly_counts_against_it():
    assert paired.against_goal([1.0] * 9, 1.0).startswith("not met (0 of 9")


def test_no_rounds_decide_nothing():
    assert paired.against_goal([], 1.0).startswith("undecided (0 of 0")
