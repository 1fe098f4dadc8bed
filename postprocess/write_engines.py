"""The engines command: a scene run in two engines (postprocess/engines.py), compared per k_n
and observable, on the terminal and as engines.md and engines.csv in the output directory."""
import csv

from .engines import AGREEMENT_SIGMAS, COMPARED, HARD, HARD_COMPARED, compare_engines, left_out
from .formatting import fmt
from .quantities import TABLE


def write_engines(named, runs, out):
    """Prints and writes the comparisons of `runs` (runs.load_runs); the exit status: 1 if the
    engines differ on an observable or nothing could be compared, else 0."""
    comparisons = compare_engines(runs)
    missing = left_out(runs)
    notes = [f"- not compared: {len(said)} runs of {scene} in engine {engine} have no averages "
             f"(e.g. {said[0][0]}: {said[0][1]})" for (scene, engine), said in sorted(missing.items())]
    for note in notes:
        print(f"engines: note{note[1:]}")
    if not comparisons:
        print(f"engines: {named}: no scene and k_n with runs of two engines")
        return 1
    engines = sorted(comparisons[0].means)
    out.mkdir(parents=True, exist_ok=True)
    lines = [f"# The engines compared: {named}", "",
             f"Means over the runs (seeds) with their standard errors; the engines agree where "
             f"they differ by at most {AGREEMENT_SIGMAS:g} combined standard errors "
             "(docs/liggghts.md). Observables: " +
             ", ".join(TABLE[q].label for q in COMPARED) + f"; against the {HARD} engine " +
             ", ".join(TABLE[q].label for q in HARD_COMPARED) + ".", "", *notes,
             *([""] if notes else []),
             "| scene | k_n | observable | " + " | ".join(f"{e} (runs)" for e in engines) +
             " | difference | allowed | verdict |",
             "|---|---|---|" + "---|" * len(engines) + "---|---|---|"]
    rows = []
    for c in comparisons:
        cells = [f"{fmt(c.means[e], c.errors[e])} ({c.counts[e]})" for e in engines]
        lines.append(f"| {c.scene} | {c.kn:g} | {TABLE[c.quantity].label} | " +
                     " | ".join(cells) + f" | {c.difference:.4g} | {c.allowed:.4g} | "
                     f"{c.verdict} |")
        rows.append({"scene": c.scene, "kn": c.kn, "quantity": c.quantity,
                     **{f"{e}_mean": c.means[e] for e in engines},
                     **{f"{e}_error": c.errors[e] for e in engines},
                     **{f"{e}_runs": c.counts[e] for e in engines},
                     "difference": c.difference, "allowed": c.allowed, "verdict": c.verdict})
        print(f"{c.scene} kn {c.kn:g} {TABLE[c.quantity].label}: " +
              ", ".join(f"{e} {fmt(c.means[e], c.errors[e])}" for e in engines) +
              f": {c.verdict} (difference {c.difference:.4g}, allowed {c.allowed:.4g})")
    (out / "engines.md").write_text("\n".join(lines) + "\n")
    with open(out / "engines.csv", "w", newline="") as handle:
        writer = csv.DictWriter(handle, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    failed = [c for c in comparisons if c.verdict != "agree"]
    print(f"engines: {len(comparisons) - len(failed)} of {len(comparisons)} agree; "
          f"{out / 'engines.md'}")
    return 1 if failed else 0
