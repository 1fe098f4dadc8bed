#!/usr/bin/python3
"""How often the hard-sphere-limit rule (postprocess/limit.py, docs/hard_sphere_limit.md)
reaches each verdict on synthetic runs of known physics, at the stiff preset's k_n and number
of runs: its power and its false verdicts, for a seed-to-seed scatter of a given size.

    scripts/limit_rule_power.py [--trials N] [--runs R] [--noise 0.05 0.15 0.25]
"""
import argparse
from collections import Counter

import numpy as np

from postprocess import limit    # scripts/postprocess links the package

KN = 1e5 * 2.0 ** np.arange(4, 16, 2)    # inputs/sweeps/stiff_frictional.toml
# m_c-like series near the paper preset's values (0.09 at 1.6e6, falling as k_n^-0.2 there)
TRUTHS = {
    "power law k^-0.2": lambda k: 0.09 * (k / 1.6e6) ** -0.2,
    "power law k^-0.4": lambda k: 0.09 * (k / 1.6e6) ** -0.4,
    "floor 0.02 + k^-0.5": lambda k: 0.02 + 0.07 * (k / 1.6e6) ** -0.5,
    "floor 0.02 + k^-0.2": lambda k: 0.02 + 0.07 * (k / 1.6e6) ** -0.2,
}


def runs_of(truth, noise, runs, rng):
    return [{"kn": k, "span": 300.0, "E_total": 0.6,
             "mc_c": truth(k) * (1 + noise * rng.standard_normal())}
            for k in KN for _ in range(runs)]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--trials", type=int, default=40)
    parser.add_argument("--runs", type=int, default=6, help="selected runs per k_n")
    parser.add_argument("--noise", type=float, nargs="+", default=[0.05, 0.15, 0.25],
                        help="relative seed-to-seed scatter of a run's value")
    parser.add_argument("--samples", type=int, default=500, help="bootstrap resamples")
    args = parser.parse_args()
    rng = np.random.default_rng(2003)
    print(f"{args.trials} trials, {args.runs} runs at each of {len(KN)} k_n, "
          f"{args.samples} bootstrap resamples")
    print("| truth | scatter | finite | vanishing | undecided |\n|---|---|---|---|---|")
    for name, truth in TRUTHS.items():
        for noise in args.noise:
            verdicts = Counter(limit.decide(runs_of(truth, noise, args.runs, rng), "mc_c",
                                            samples=args.samples).verdict
                               for _ in range(args.trials))
            print(f"| {name} | {noise:.0%} | " + " | ".join(
                f"{verdicts[v] / args.trials:.0%}" for v in ("finite", "vanishing", "undecided"))
                + " |", flush=True)


if __name__ == "__main__":
    main()
