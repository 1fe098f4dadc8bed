"""How often the hard-sphere-limit rule (postprocess/limit.py, docs/hard_sphere_limit.md)
reaches each verdict on synthetic runs of known physics: its power and its false verdicts, for
a seed-to-seed scatter of a given size, a number of selected runs per k_n and a k_n range.

    python3 -m scripts.studies.limit_rule_power [--rule 1|2] [--trials N] [--runs 3 4 6] [--noise 0.05 0.15 0.25]
                                [--kn-powers 4 6 8 10 12 14 16]

k_n = 2^p x 10^5 for the given p (default: the stiff preset's 4 ... 14).
"""
import argparse
from collections import Counter

import numpy as np

from postprocess import limit

# m_c-like series near the paper preset's values (0.09 at 1.6e6, falling as k_n^-0.2 there);
# the flat and slowly falling ones like t_w - N_w tau_w (0.2 per bottom-layer disk)
TRUTHS = {
    "flat": lambda k: 0.2 + 0.0 * k,
    "power law k^-0.05": lambda k: 0.2 * (k / 1.6e6) ** -0.05,
    "power law k^-0.1": lambda k: 0.2 * (k / 1.6e6) ** -0.1,
    "power law k^-0.2": lambda k: 0.09 * (k / 1.6e6) ** -0.2,
    "power law k^-0.4": lambda k: 0.09 * (k / 1.6e6) ** -0.4,
    "floor 0.02 + k^-0.5": lambda k: 0.02 + 0.07 * (k / 1.6e6) ** -0.5,
    "floor 0.02 + k^-0.2": lambda k: 0.02 + 0.07 * (k / 1.6e6) ** -0.2,
}


def runs_of(truth, noise, runs, kn, rng):
    return [{"kn": k, "span": 300.0, "E_total": 0.6,
             "mc_c": truth(k) * (1 + noise * rng.standard_normal())}
            for k in kn for _ in range(runs)]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rule", type=int, choices=limit.RULES, default=limit.RULE)
    parser.add_argument("--trials", type=int, default=40)
    parser.add_argument("--runs", type=int, nargs="+", default=[6], help="selected runs per k_n")
    parser.add_argument("--noise", type=float, nargs="+", default=[0.05, 0.15, 0.25],
                        help="relative seed-to-seed scatter of a run's value")
    parser.add_argument("--kn-powers", type=int, nargs="+", default=list(range(4, 16, 2)),
                        help="p of k_n = 2^p x 10^5")
    parser.add_argument("--samples", type=int, default=500, help="bootstrap resamples")
    args = parser.parse_args()
    kn = 1e5 * 2.0 ** np.array(sorted(args.kn_powers))
    rng = np.random.default_rng(2003)
    print(f"rule {args.rule}, {args.trials} trials, k_n {kn[0]:.3g} ... {kn[-1]:.3g} "
          f"({len(kn)} values), {args.samples} bootstrap resamples")
    print("| truth | scatter | runs per k_n | finite | vanishing | undecided |\n"
          "|---|---|---|---|---|---|")
    for name, truth in TRUTHS.items():
        for noise in args.noise:
            for runs in args.runs:
                verdicts = Counter(limit.decide(runs_of(truth, noise, runs, kn, rng), "mc_c",
                                                samples=args.samples, rule=args.rule).verdict
                                   for _ in range(args.trials))
                print(f"| {name} | {noise:.0%} | {runs} | " + " | ".join(
                    f"{verdicts[v] / args.trials:.0%}" for v in ("finite", "vanishing",
                                                                 "undecided")) + " |",
                    flush=True)


if __name__ == "__main__":
    main()
