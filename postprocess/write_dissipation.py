"""The dissipation command: where the contacts' energy goes as k_n grows
(postprocess/dissipation.py), on the terminal and as dissipation.md, dissipation.csv (per k_n),
dissipation_runs.csv (per run: D, the shares, the window's dissipation from the global sums,
a budget that did not close) and dissipation.png in the output directory."""
import csv

from .dissipation import SHARES, analyse_dissipation, per_kn
from .durations import DISSIPATION_NAMES, LASTING
from .figures import dissipation_figure
from .formatting import fmt


def group_lines(group):
    lines = [f"## {group.scene}, tangential law {group.law}", "",
             f"The lasting share ({LASTING:g} binary durations and longer) by rule 2: "
             f"**{group.decision.verdict}**" + (f": {group.decision.why}"
                                                 if group.decision.why else "") + ".", "",
             "| k_n | runs | lasting | multiple | binary | sliding | negative sliding | "
             "negative-sliding contacts per 1000 | rows' D / global |",
             "|---|---|---|---|---|---|---|---|---|"]
    for kn, runs, means, negative, ratio in per_kn(group):
        lines.append(f"| {kn:.4g} | {runs} | " + " | ".join(fmt(*means[s]) for s in SHARES) +
                     f" | {negative:.3g} | {ratio:.3f} |")
    if group.left_out:
        lines += ["", f"Left out: {len(group.left_out)} runs ("
                  + "; ".join(sorted({why for _, why in group.left_out})) + ")."]
    return lines + [""]


def write_dissipation(named, records, out):
    """Prints and writes the shares of `records` (runs.load_runs); the exit status: 1 if no
    run booked its contacts' energies, else 0."""
    groups = analyse_dissipation(records)
    if not groups:
        print(f"dissipation: {named}: no run with contact energies (energies = yes, rows = "
              "yes) that flowed to its end")
        return 1
    out.mkdir(parents=True, exist_ok=True)
    lines = [f"# Where the energy goes: {named}", "",
             "Per scene, tangential law and k_n: the shares of the energy the contacts that "
             "ended in the rows window dissipated (D) lost in lasting contacts, in contacts "
             "that overlapped another contact of one of their particles (multiple), in the "
             "rest (binary), while sliding, and the negative sliding work's share (the literal "
             "law's), each the span-weighted mean over the runs with its standard error; the "
             "rule is docs/hard_sphere_limit.md, \"Where the energy goes\".", ""]
    cpu = sum(r["cpu_seconds"] or 0.0 for g in groups for r in g.runs)
    lines += [f"The runs judged here cost {cpu / 3600:.2f} CPU-hours (their timing.json).", ""]
    for group in groups:
        lines += group_lines(group)
    (out / "dissipation.md").write_text("\n".join(lines))
    with open(out / "dissipation.csv", "w", newline="") as handle:
        writer = csv.writer(handle)
        writer.writerow(["scene", "law", "kn", "runs"] +
                        [f"{s}_{p}" for s in SHARES for p in ("mean", "error")] +
                        ["negative_sliding_contacts_per_1000", "rows_over_global", "verdict"])
        for group in groups:
            for kn, runs, means, negative, ratio in per_kn(group):
                writer.writerow([group.scene, group.law, kn, runs] +
                                [v for s in SHARES for v in means[s]] +
                                [negative, ratio, group.decision.verdict])
    with open(out / "dissipation_runs.csv", "w", newline="") as handle:
        names = ("point", "kn", "span", *DISSIPATION_NAMES, "budget_problem", "cpu_seconds")
        writer = csv.writer(handle)
        writer.writerow(["scene", "law", *names])
        for group in groups:
            for run in sorted(group.runs, key=lambda r: (r["kn"], r["point"])):
                writer.writerow([group.scene, group.law, *(run[n] for n in names)])
    dissipation_figure(groups, out / "dissipation.png")
    for group in groups:
        print(f"dissipation: {group.scene} ({group.law}): lasting share "
              f"{group.decision.verdict}" + (f": {group.decision.why}" if group.decision.why
                                             else ""))
    print(f"dissipation: {out / 'dissipation.md'}")
    return 0
