"""The compare command: each claim of the paper (postprocess/reference.py) and its verdict, on
the terminal."""
from .formatting import comparison_line, fmt
from .reference import accepted, evaluate, tally


def write_compare(scenes, rule, completed=None):
    """Prints the comparison of a study's scenes and completed runs (study.analyse) under the
    hard-sphere-limit rule `rule`; the exit status: 1 if a claim fails or none could be
    evaluated, else 0."""
    results = evaluate(scenes, rule=rule, completed=completed)
    width = max(len(c["id"]) for c, *_ in results)
    for claim, value, error, status in results:
        print(f"{claim['id']:<{width}}  {fmt(value, error):>18}  "
              f"{accepted(claim)}  {status}")
    print(comparison_line(results))
    counts = tally(results)
    return 1 if counts["FAIL"] or counts["not evaluated"] == len(results) else 0
