"""The finite-size command: the frictional scene's widths compared (postprocess/finite_size.py),
on the terminal and as finite_size.md and finite_size.csv in the output directory."""
import csv

from .finite_size import (COMPARED, DEPENDS_SIGMAS, FLOW_FRACTION, SCATTER_OF,
                          SUGGESTED_SIGMAS, analyse_widths, wilson)
from .formatting import fmt
from .quantities import TABLE


def cell_lines(cells):
    lines = ["| law | k_n | width | runs | flow to the end (95 %) | stopped | selected | "
             "CPU-s | " + " | ".join(f"{TABLE[q].label} (scatter)" for q in COMPARED) + " |",
             "|---|---|---|---|---|---|---|---|" + "---|" * len(COMPARED)]
    for key in sorted(cells):
        c = cells[key]
        low, high = wilson(c.flowing, c.runs)
        values = [f"{fmt(c.means[q], c.errors[q])} ({c.scatter[q]:.0%})" if q in c.means
                  else "n/a" for q in COMPARED]
        lines.append(f"| {c.law} | {c.kn:.4g} | {c.width} | {c.runs} | {c.flowing} "
                     f"({low:.2f}-{high:.2f}) | {c.stopped} | {c.selected} | "
                     f"{c.cpu_seconds:.0f} | " + " | ".join(values) + " |")
    return lines


def dependence_lines(found):
    lines = ["| law | k_n | quantity | width vs | z | resolution | verdict |",
             "|---|---|---|---|---|---|---|"]
    for d in found:
        lines.append(f"| {d.law} | {d.kn:.4g} | {TABLE[d.quantity].label} | {d.width} vs "
                     f"{d.reference} | {d.z:+.2f} | {d.resolution:.0%} | {d.verdict} |")
    return lines


def write_finite_size(named, runs, out):
    """Prints and writes the check of `runs` (runs.load_runs); the exit status: 1 if no law has
    runs of the candidate widths, else 0."""
    cells, found, choices = analyse_widths(runs)
    if not choices:
        print(f"finite-size: {named}: no frictional runs of the candidate widths")
        return 1
    out.mkdir(parents=True, exist_ok=True)
    lines = [f"# The frictional scene's widths: {named}", "",
             "Per law, k_n and width: how the runs ended, and each quantity's mean over the "
             "selected runs with its standard error and, in brackets, the scatter (the "
             "relative standard deviation between runs). The rule "
             "(docs/hard_sphere_limit.md, \"The width\"): a quantity depends on the width where "
             f"|z| > {DEPENDS_SIGMAS:g} against the widest width, a dependence is suggested "
             f"where {SUGGESTED_SIGMAS:g} < |z| <= {DEPENDS_SIGMAS:g}; the resolution is "
             f"{DEPENDS_SIGMAS:g} combined errors over the widest width's mean.", "",
             *cell_lines(cells), "", "## The width dependence", "", *dependence_lines(found),
             "", "## The wide series", ""]
    for choice in choices:
        index = ", ".join(f"C_{w} = {c:.3g}" for w, c in sorted(choice.cost_index.items()))
        lines.append(f"- {choice.law}: {choice.why}; cost index {index or 'n/a'}; "
                     f"scatter of {TABLE[SCATTER_OF].label} {choice.scatter:.0%}, fraction "
                     f"selected {choice.selected_fraction:.2f}: {choice.runs_per_kn} selected "
                     f"runs a k_n, {choice.seeds} seeds a k_n")
    (out / "finite_size.md").write_text("\n".join(lines) + "\n")
    with open(out / "finite_size.csv", "w", newline="") as handle:
        writer = csv.writer(handle)
        writer.writerow(["law", "kn", "width", "runs", "flowing", "stopped", "selected",
                         "cpu_seconds"] + [f"{q}_{s}" for q in COMPARED
                                           for s in ("mean", "error", "scatter")])
        for key in sorted(cells):
            c = cells[key]
            writer.writerow([c.law, c.kn, c.width, c.runs, c.flowing, c.stopped, c.selected,
                             c.cpu_seconds] +
                            [v for q in COMPARED for v in (c.means.get(q), c.errors.get(q),
                                                           c.scatter.get(q))])
    for d in found:
        if d.verdict != "none resolved":
            print(f"{d.law} kn {d.kn:g} {TABLE[d.quantity].label}: width {d.width} vs "
                  f"{d.reference}: z {d.z:+.2f}: {d.verdict}")
    for choice in choices:
        print(f"finite-size: {choice.law}: {choice.why}; {choice.seeds} seeds a k_n "
              f"(scatter {choice.scatter:.0%}, selected {choice.selected_fraction:.2f}, flow "
              f"fraction required {FLOW_FRACTION:g})")
    print(f"finite-size: {out / 'finite_size.md'}")
    return 0
