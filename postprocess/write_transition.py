"""The transition command: the report of a transition sweep (docs/transition.md)."""
import csv
import datetime

import numpy as np

from . import durations, figures, transition
from .formatting import fmt
from .quantities import COLUMNS
from .scenes import scene as scene_of


def write_transition_report(sweep_dir, runs, groups, left_out, out):
    """transition.md with the per-angle table and figures, transition.csv (that table),
    transition_points.csv (every k_n of every angle), transition_runs.csv (how each run
    ended). Returns the path of transition.md."""
    out.mkdir(parents=True, exist_ok=True)
    table = transition.transition_table(runs, groups)
    columns = ["scene", "sin_theta", "runs", "flowing", "stopped", "accelerating", "drifting",
               "state",
               "exponent_N_c", "exponent_N_c_err", "exponent_N_w", "exponent_N_w_err",
               "kn_stiffest", "mc_fraction", "mc_fraction_err", "t_c", "t_c_err", "t_multiple",
               "t_multiple_err", "z", "z_err", "E_total", "E_total_err", "tail_disk",
               "tail_boundary", "contacts_disk", "contacts_boundary"]
    with open(out / "transition.csv", "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(columns + ["kn_flowing"])
        for row in table:
            writer.writerow([row.get(c, "") for c in columns] +
                            [" ".join(f"{k:g}" for k in row["kn_flowing"])])
    with open(out / "transition_points.csv", "w", newline="") as f:
        writer = csv.writer(f)
        header = ["scene", "sin_theta", "kn", "tau_c", "tau_w", "span", "n_boundary"]
        writer.writerow(header + [x for q in COLUMNS for x in (q, q + "_err")] + ["notes"])
        for (scene, sin_theta), rows in groups.items():
            for o in rows:
                writer.writerow([scene, sin_theta] + [o[k] for k in header[2:]] +
                                [o[x] for q in COLUMNS for x in (q, q + "_err")] +
                                [o["notes"]])
    with open(out / "transition_runs.csv", "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(["scene", "sin_theta", "kn", "seed", "state", "growth", "point"])
        for r in runs:
            writer.writerow([r["scene"], r["sin_theta"], r["kn"], int(r["seed"]), r["state"],
                             r["growth"], r["point"]])

    lines = [f"# Collisional-frictional transition: {sweep_dir}", "",
             f"Written {datetime.datetime.now():%Y-%m-%d %H:%M} by `python3 -m postprocess "
             "transition` (docs/transition.md says how to read it). A run is *stopped* if its "
             "pile came to rest, *accelerating* if E per disk over the last fifth of its "
             f"averaging span exceeds {transition.GROWTH_LIMIT:g} times E over the first "
             "fifth, *drifting* if a straight line through the means of "
             f"{transition.DRIFT_BLOCKS} blocks of E(t) changes over the span by more than E's "
             "standard deviation about it and its slope is more than "
             f"{transition.DRIFT_SIGMAS:g} standard errors from 0, else *flowing*; only "
             "flowing runs "
             "are averaged, over their whole span "
             "after the transient. Exponents: least-squares fits of N ~ k_n^a over the k_n "
             "with flowing runs (error: the fit's). At the stiffest of those k_n: the "
             "multiple-contact fraction (t_c - N_c tau_c)/t_c, the fraction of time with two "
             "or more contacts (t_multiple), the contacts per disk z (boundary included), and "
             f"the fractions of disk (boundary) contacts longer than {durations.TAIL_CUT:g} "
             "tau_c (tau_w). Errors: across seeds, or block errors of a single seed.", ""]
    made = []
    if any(row.get("kn_stiffest") for row in table):
        figures.transition_figure(table, out / "transition.png")
        made.append(("exponents and multiple contacts against sin theta", "transition.png"))
        # P(tau) needs the contact rows (deck variable rows), which a sweep may not have asked for
        densities = _few_densities(runs, table)
        if densities:
            figures.duration_figure(densities, durations.DURATION_EDGES, out / "durations.png")
            made.append(("P(tau/tau_c) for a few inclinations", "durations.png"))
        else:
            lines += ["No P(tau) figure: no flowing inclination has contact rows (deck "
                      "variable rows).", ""]
    for scene in sorted({row["scene"] for row in table}):
        lines += [f"## {scene_of(scene).base} (`{scene}`)", "",
                  "| sin theta | runs: flowing / stopped / accelerating / drifting | k_n flowing | "
                  "N_c exponent | N_w exponent | stiffest k_n | (t_c - N_c tau_c)/t_c | "
                  "t_multiple | z | E | disk > 2 tau_c | boundary > 2 tau_w |",
                  "|---|---|---|---|---|---|---|---|---|---|---|---|"]
        for row in (r for r in table if r["scene"] == scene):
            def cell(key):
                return fmt(row.get(key, np.nan), row.get(key + "_err"))
            kn = row["kn_flowing"]
            lines.append(
                f"| {row['sin_theta']:g} | {row['flowing']} / {row['stopped']} / "
                f"{row['accelerating']} / {row['drifting']} ({row['state']}) | "
                f"{f'{kn[0]:g} ... {kn[-1]:g} ({len(kn)})' if kn else '-'} | "
                f"{cell('exponent_N_c')} | {cell('exponent_N_w')} | "
                f"{fmt(row.get('kn_stiffest', np.nan))} | {cell('mc_fraction')} | "
                f"{cell('t_multiple')} | {cell('z')} | {cell('E_total')} | "
                f"{fmt(row.get('tail_disk', np.nan))} | {fmt(row.get('tail_boundary', np.nan))} |")
        lines.append("")
    for caption, name in made:
        lines += [f"![{caption}]({name})", ""]
    if left_out:
        lines += ["## Left out", ""] + [f"- `{point}`: {reason}" for point, reason in left_out]
        lines.append("")
    (out / "transition.md").write_text("\n".join(lines))
    return out / "transition.md"


def _few_densities(runs, table, most=5):
    """P(tau) at the stiffest flowing k_n of at most `most` inclinations per base, evenly
    spread over those that have contact rows."""
    densities = {}
    for scene in sorted({row["scene"] for row in table}):
        rows = [r for r in table if r["scene"] == scene and r.get("contacts_disk", 0) +
                r.get("contacts_boundary", 0) > 0]
        for row in rows[::max(1, -(-len(rows) // most))]:
            pooled = transition.pooled_durations(runs, scene, row["sin_theta"],
                                                 row["kn_stiffest"])
            densities[(scene, row["sin_theta"], row["kn_stiffest"])] = {
                kind: durations.duration_density(d) for kind, d in pooled.items()}
    return densities
