"""Judges inputs/sweeps/newton_check.toml's runs by the rule its header fixes: does newton off
give the observables of newton on within their errors, and would the rule see a change of the
physics (its mutant points, which must fail it)?

    python3 -m scripts.studies.newton_check SUMMARIES_DIR     # e.g. data/newton_check (postprocess summarize)

Per run the observables of its steady window (the mean of its blocks), for the runs that end
flowing; per scene and variant their mean over the runs and its standard error; a variant
passes against newton on if every observable is within 3.5 combined standard errors and, where
runs stop, the numbers that stop do not differ (two-sided Fisher exact p >= 0.01); with
fewer than two flowing runs an error is undefined and the variant fails. Exit status
0 if newton off passes in every scene and every mutant fails, else 1."""
import json
import math
import sys
from pathlib import Path

from postprocess.engines import mean_and_error

OBSERVABLES = ["E_total", "N_c", "N_w", "t_c", "t_w"]
Z_MAX = 3.5
FISHER_P_MIN = 0.01
# what every point of the config sets; a point that sets anything else is a mutant
SETTINGS = {"scene", "seed", "run_time", "average_start", "newton"}


def variant(summary):
    """The run's variant: 'newton on', 'newton off', or a mutant named by what it changes."""
    values = summary["variables"]
    changed = sorted(set(values) - SETTINGS)
    if not changed:
        return f"newton {values['newton']}"
    shown = (f"{values[n]}" if isinstance(values[n], str) else f"{values[n]:g}" for n in changed)
    return ", ".join(f"{name} = {value}" for name, value in zip(changed, shown)) + \
        f" (newton {values['newton']})"


def fisher_two_sided(a, b, c, d):
    """Fisher's exact test of the table [[a, b], [c, d]]: the chance, with the margins fixed, of
    a table no more likely than this one."""
    n1, n2, k = a + b, c + d, a + c

    def chance(x):
        return math.comb(n1, x) * math.comb(n2, k - x) / math.comb(n1 + n2, k)

    observed = chance(a)
    low, high = max(0, k - n2), min(k, n1)
    return min(1.0, sum(chance(x) for x in range(low, high + 1)
                        if chance(x) <= observed * (1 + 1e-9)))


def main(directory):
    runs = {}
    for path in sorted(Path(directory).rglob("*.json")):
        summary = json.loads(path.read_text())
        if summary.get("schema") != "granmn-run-summary":
            continue
        runs.setdefault((summary["scene"], variant(summary)), []).append(summary)
    if not runs:
        sys.exit(f"{directory}: no run summaries (python3 -m postprocess summarize RESULTS --to DIR)")
    ok = True
    for scene in sorted({scene for scene, _ in runs}):
        reference = runs.get((scene, "newton on"))
        if not reference:
            print(f"{scene}: no newton on runs")
            ok = False
            continue
        table = {}
        for (s, name), summaries in sorted(runs.items()):
            if s != scene:
                continue
            flowing = [r for r in summaries if r["ended"] == "flowing"]
            stats = {}
            for o in OBSERVABLES:
                values = [sum(r["measured"]["window"]["blocks"][o]) /
                          len(r["measured"]["window"]["blocks"][o]) for r in flowing]
                stats[o] = mean_and_error(values) if values else (math.nan, math.nan)
            table[name] = (len(summaries), len(flowing), stats)
        print(f"{scene} (mean over the flowing runs, standard error):")
        print(f"  {'variant':<26} {'runs':>4} {'flow':>4}  " +
              "  ".join(f"{o:>22}" for o in OBSERVABLES))
        for name, (n, flowing, stats) in table.items():
            print(f"  {name:<26} {n:>4} {flowing:>4}  " +
                  "  ".join(f"{m:>11.5g} +- {e:<8.2g}" for m, e in (stats[o] for o in OBSERVABLES)))
        n_on, flowing_on, stats_on = table["newton on"]
        for name, (n, flowing, stats) in table.items():
            if name == "newton on":
                continue
            z = {o: abs(stats[o][0] - stats_on[o][0]) / math.hypot(stats[o][1], stats_on[o][1])
                 for o in OBSERVABLES}
            p = fisher_two_sided(flowing, n - flowing, flowing_on, n_on - flowing_on)
            passes = all(value <= Z_MAX for value in z.values()) and p >= FISHER_P_MIN
            expected = name == "newton off"
            verdict = "passes" if passes else "fails"
            as_expected = passes == expected
            ok &= as_expected
            print(f"  {name} against newton on: |z| " +
                  ", ".join(f"{o} {z[o]:.2f}" for o in OBSERVABLES) +
                  f"; stopped {n - flowing}/{n} against {n_on - flowing_on}/{n_on}, Fisher p "
                  f"{p:.3g}: {verdict}" + ("" if as_expected else
                                           f" (it should {'pass' if expected else 'fail'})"))
    print("verdict:", "newton off passes and every mutant fails" if ok else "NOT as required")
    return 0 if ok else 1


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    sys.exit(main(sys.argv[1]))
