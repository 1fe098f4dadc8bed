"""The report command: the study report of a sweep (report.md: tables, fits, figures, the
comparison with the references, left-out points; the tables as CSV)."""
import csv
import datetime

import numpy as np

from . import durations, figures
from .formatting import fmt, split_lines
from .io import DataError
from .observables import N_BLOCKS
from .quantities import COLUMNS, EXPONENTS, SCENE_TABLE, TABLE, VARIANTS
from .record import energy_curve
from .reference import accepted, evaluate
from .scenes import scene as scene_of
from .selection import Selection
from .study import (CROSSOVER_SIGMAS, contact_series, crossover,
                    fit_power, main_series, run_summary, same_series, series,
                    variant_differences)


def write_tables(scenes, out):
    for scene, rows in scenes.items():
        with open(out / f"observables_{scene}.csv", "w", newline="") as f:
            writer = csv.writer(f)
            header = ["kn", "tau_c", "tau_w", "span", "n_boundary"]
            for q in COLUMNS:
                header += [q, q + "_err"]
            writer.writerow(header + ["point"])
            for o in rows:
                writer.writerow([o[k] for k in header] + [o["point"]])


def make_figures(scenes, completed, out, selection):
    """{scene: [(caption, file name)]}, and problems met (a figure not drawn, or drawn without a
    point whose file could not be read). Time series and snapshots of every completed run
    (completed: {scene: [RunRecord]}); the stiffness dependences and profiles of the usable
    ones. From summaries: no snapshots, profiles or v_y(t) (only the raw outputs hold them)."""
    made, problems = {}, []
    for scene, points in completed.items():
        raw = all(r.source == "raw" for r in points)
        items = made.setdefault(scene, [])
        rows = main_series(scenes.get(scene, []))
        others = [o for o in scenes.get(scene, []) if rows and o["label"] != rows[0]["label"]]
        variants = [(label, [o for o in others if o["label"] == label])
                    for label in sorted({o["label"] for o in others})]
        # the time series of the main series' runs (all runs if none is usable)
        curves = [(r.params["kn"], *energy_curve(r)) for r in points
                  if not rows or same_series(r.variables, rows[0]["variables"])]
        jobs = [("kinetic energy against time (main series)", f"energy_{scene}.png",
                 lambda p, s=scene, c=curves: figures.energy_figure(s, c, p, selection))]
        if raw:
            jobs.append(("snapshot (stiffest point)", f"snapshot_{scene}.png",
                         lambda p, s=scene, c=points: figures.snapshot_figure(s, c[-1].point, p)))
        if rows:
            jobs.append(("stiffness dependence", f"stiffness_{scene}.png",
                         lambda p, s=scene, r=rows, v=variants: figures.stiffness(s, r, p, v)))
        durations_by_series = contact_series(scenes.get(scene, []))
        if durations_by_series:
            jobs.append(("contact durations P(tau) against k_n", f"durations_{scene}.png",
                         lambda p, s=scene, d=durations_by_series: figures.duration_stiffness(
                             s, d, durations.DURATION_EDGES, p)))
        if rows and raw:
            jobs.append(("profiles", f"profiles_{scene}.png",
                         lambda p, s=scene, r=rows: figures.profile_figure(s, r, p)))
        if scene_of(scene).has_period and rows and raw:
            def vy(p, r=rows):
                trajectories = {}
                for o in (r[0], r[-1]):
                    t = o["outputs"].trajectory
                    trajectories[o["kn"]] = (t["time"], t["vy"])
                figures.vy_figure(r, trajectories, p)
            jobs.append(("v_y(t) at the softest and the stiffest point", "vy_single_disk.png", vy))
        for caption, name, job in jobs:
            try:
                problems += [f"{name}: {problem}" for problem in job(out / name) or ()]
                items.append((caption, name))
            except DataError as error:
                problems.append(f"{name}: {error}")
    return made, problems


# the quantities whose stiffness exponents the report fits, and how many of the stiffest k_n
# the second fit takes (where a power law bends, the stiff end's exponent differs)
STIFF_END = 3


def exponent_lines(rows):
    """Markdown lines: per series of at least STIFF_END k_n, the exponent a of each quantity ~
    k_n^a (least squares in log-log, the fit's standard error) over all its k_n and over the
    stiffest STIFF_END; n/a where a value is not positive (a power law has none)."""
    lines = []
    for name in dict.fromkeys(o["label"] for o in rows):
        points = [o for o in rows if o["label"] == name]
        if len(points) < STIFF_END:
            continue
        kn = np.array([o["kn"] for o in points])
        lines += [f"Stiffness exponents ({name or 'main series'}; {len(points)} k_n, "
                  f"{kn[0]:g} to {kn[-1]:g}): a in quantity ~ k_n^a, least squares in log-log.",
                  "", f"| quantity | all k_n | stiffest {STIFF_END} |", "|---|---|---|"]
        for q in EXPONENTS:
            values = np.array([o[q] for o in points])
            cells = []
            for k, v in ((kn, values), (kn[-STIFF_END:], values[-STIFF_END:])):
                cells.append(fmt(*fit_power(k, v)) if np.all(v > 0) else "n/a (a value <= 0)")
            lines.append(f"| {q} | " + " | ".join(cells) + " |")
        lines.append("")
    return lines


def contact_lines(scene, rows):
    """Markdown lines: per series and k_n with contact rows, the contacts counted and the
    fraction longer than durations.TAIL_CUT binary durations; and, where the rows cover a
    window, what the time with two or more contacts is made of."""
    found = contact_series(rows)
    if not found:
        return []
    particle = scene_of(scene).particle
    lines = ["### Contact durations", "",
             f"From the contact rows (`-var rows yes`) of the contacts that ended after "
             f"average_start: how many, and the fraction lasting longer than "
             f"{durations.TAIL_CUT:g} binary durations (tau_c; tau_w against the boundary); "
             "P(tau) in the figure.", "",
             f"| series | k_n | runs with rows | {particle}-{particle} contacts | "
             f"> {durations.TAIL_CUT:g} tau_c | boundary contacts | > {durations.TAIL_CUT:g} "
             "tau_w |", "|---|---|---|---|---|---|---|"]
    splits = []
    for name, points in found:
        for kn, p in points:
            cells = []
            for kind in ("disk", "boundary"):
                total = p[kind]["contacts"]
                cells += [str(total), fmt(p[kind]["tail"] / total) if total else "n/a"]
            lines.append(f"| {name or '-'} | {kn:g} | {p['runs']} | " + " | ".join(cells) + " |")
            splits += [(name, kn, s) for s in p["splits"]]
    lines.append("")
    for name in dict.fromkeys(n for n, _, _ in splits):
        lines += [f"What the time with two or more contacts is made of ({name or 'main series'}; "
                  f"per {particle} and unit time over the rows window; docs/hard_sphere_limit.md):",
                  ""]
        lines += split_lines([(kn, s) for n, kn, s in splits if n == name])
    return lines


def run_table(runs, selection):
    """Markdown lines: per kn, how the frictional runs ended and what the selection kept."""
    summary = run_summary(runs)
    if not summary:
        return []
    resolutions = sorted(next(iter(summary.values()))["kept"])
    lines = [f"Runs per point (each run: `runs.csv`): flowing to the end, stopped (the pile came to rest and the run "
             f"ended early; median time of the stop), selected (at least one steady part kept "
             f"at resolution {selection.resolution:g}), and the steady parts kept in all when E(t) is "
             "averaged over windows of each resolution (time units), and the runs' CPU time "
             "(timing.json, kept in the summaries; `n timed` where only n of the runs have one):",
             "",
             "| k_n | other variables | runs | flowing | stopped (median t) | selected | " +
             " | ".join(f"parts kept at {r:g}" for r in resolutions) + " | CPU-s |",
             "|---|---|---|---|---|---|" + "---|" * len(resolutions) + "---|"]
    for (kn, label), row in summary.items():
        when = f" ({np.median(row['stop_times']):.0f})" if row["stop_times"] else ""
        timed = "" if row["timed"] == row["runs"] else f" ({row['timed']} timed)"
        lines.append(f"| {kn:g} | {label or '-'} | {row['runs']} | {row['flowing']} | "
                     f"{row['stopped']}{when} | {row['selected']} | " +
                     " | ".join(str(row["kept"][r]) for r in resolutions) +
                     f" | {row['cpu_seconds']:.0f}{timed} |")
    total = sum(row["cpu_seconds"] for row in summary.values())
    timed = sum(row["timed"] for row in summary.values())
    runs_in_all = sum(row["runs"] for row in summary.values())
    lines += ["", f"CPU time of the {timed} timed runs of {runs_in_all}: {total / 3600:.3g} "
                  "CPU-hours."]
    return lines + [""]


def variant_lines(rows):
    """Markdown lines: each variant point against the main series at the same k_n."""
    pairs = variant_differences(rows)
    if not pairs:
        return []
    main = main_series(rows)[0]["label"] or "-"
    lines = [f"Variants against the main series ({main}) at the same k_n: the variant's value, "
             "then (variant - main) in units of the combined error.", "",
             "| k_n | variant | " + " | ".join(VARIANTS) + " |",
             "|---|---|" + "---|" * len(VARIANTS)]
    for o, m, diffs in pairs:
        cells = [f"{fmt(o[q], o[q + '_err'])} ({diffs[q][1]:+.1f} σ)" for q in VARIANTS]
        lines.append(f"| {o['kn']:g} | {o['label']} | " + " | ".join(cells) + " |")
    return lines + [""]


def crossover_note(rows, stiff_from):
    """Where E reaches its stiff value along the main series (study.crossover), as a line."""
    try:
        c = crossover(*series(rows, "E_total"), stiff_from)
    except ValueError as error:
        return f"E crossover: not measured ({error})"
    low, high = c["bracket"]
    differs = (f"; the stiffest point that differs: k_n = {low:g}" if low is not None else
               ": the softest point already agrees")
    return (f"E crossover: E agrees with its stiff value {fmt(c['stiff'], c['stiff_err'])} (the "
            f"mean over the {c['n_stiff']} points at k_n >= {stiff_from:g}) within "
            f"{CROSSOVER_SIGMAS:g} combined errors from k_n = {high:g} on (1/k_n = "
            f"{1 / high:.2g}){differs}")


def write_runs(runs, path):
    """One row per run that the selection looked at: how it ended, what was kept."""
    resolutions = sorted(runs[0]["kept"])
    with open(path, "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(["kn", "seed", "variables", "state", "stopped_at", "selected"] +
                        [f"kept_at_{r:g}" for r in resolutions] + ["point"])
        for r in sorted(runs, key=lambda r: (r["kn"], r["label"], r["seed"])):
            writer.writerow([r["kn"], int(r["seed"]), r["label"], r["state"],
                             "" if r["stopped_at"] is None else r["stopped_at"], r["selected"]] +
                            [r["kept"][k] for k in resolutions] + [r["point"]])


def comparison_lines(results):
    lines = ["| claim | quantity | k_n range | measured | accepted range | alternative (value) | "
             "verdict | source |", "|---|---|---|---|---|---|---|---|"]
    for claim, value, error, status in results:
        alternative = claim["alternative"]
        if np.isfinite(claim["alternative_value"]):
            alternative += f" ({claim['alternative_value']:g})"
        lines.append(f"| {claim['id']} | {claim['quantity']} ({claim['measure']}) | "
                     f"[{claim['kn_min']:g}, {claim['kn_max']:g}] | {fmt(value, error)} | "
                     f"{accepted(claim)} | {alternative} | {status} | {claim['source']} |")
    return lines


def write_report(sweep_dir, scenes, left_out, completed, out, runs=(), selection=Selection()):
    out.mkdir(parents=True, exist_ok=True)
    write_tables(scenes, out)
    made, problems = make_figures(scenes, completed, out, selection)
    if runs:
        write_runs(runs, out / "runs.csv")
    results = evaluate(scenes, completed=completed)
    with open(out / "comparison.csv", "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(["id", "scene", "quantity", "measure", "kn_min", "kn_max", "measured",
                         "error", "low", "high", "alternative", "alternative_value", "status",
                         "source", "why"])
        for claim, value, error, status in results:
            writer.writerow([claim["id"], claim["scene"], claim["quantity"], claim["measure"],
                             claim["kn_min"], claim["kn_max"], value, error, claim["low"],
                             claim["high"], claim["alternative"], claim["alternative_value"],
                             status, claim["source"], claim["why"]])

    lines = [f"# Stiffness study: {sweep_dir}", "",
             f"Written {datetime.datetime.now():%Y-%m-%d %H:%M} by `python3 -m postprocess "
             f"report`. Errors are standard errors of block averages within each run "
             f"({N_BLOCKS} blocks per averaging span), or across seeds where a point has several. "
             f"Frictional steady parts: {selection.describe()}.", ""]
    if any(r.source == "summary" for points in completed.values() for r in points):
        lines += ["From the runs' summaries (docs/sweeps.md): E(t) is drawn from its means over "
                  "windows of 1; snapshots, profiles and v_y(t) need the raw outputs.", ""]
    for scene in completed:
        rows = scenes.get(scene, [])
        scene_def = scene_of(scene)
        lines += [f"## {scene_def.title}", ""]
        if not rows:
            lines += ["No usable point (see Left out).", ""]
        lines += [
                  "| k_n | " + " | ".join(TABLE[q].short for q in SCENE_TABLE) + " | span | point |",
                  "|---|" + "---|" * len(SCENE_TABLE) + "---|---|"] if rows else []
        for o in rows:
            lines.append("| " + " | ".join(
                [f"{o['kn']:g}"] + [fmt(o[q], o[q + "_err"]) for q in SCENE_TABLE] + [f"{o['span']:g}", o["label"]]) + " |")
        notes = [f"k_n = {o['kn']:g}{' (' + o['label'] + ')' if o['label'] else ''}: {o['notes']}"
                 for o in rows if o["notes"]]
        if scene_def.selects_steady_parts:
            lines += run_table(runs, selection)
        lines += variant_lines(rows)
        lines += exponent_lines(rows)
        lines += contact_lines(scene, rows)
        if rows:
            notes += list(scene_def.notes)
        if scene_def.has_period and rows:
            notes.append(f"time to pass one bump ({scene_def.bump_spacing:g} / mean v_x): " +
                         ", ".join(f"{o['kn']:g}: {fmt(o['bump_time'])}" for o in rows))
            notes.append("v_y periods (autocorrelation; a multiple of the bump time where the "
                         "motion repeats every second or third bump): " +
                         ", ".join(f"{o['kn']:g}: {fmt(o['period'])}"
                                                      for o in rows))
        if scene_def.stiff_from and rows:
            notes.append(crossover_note(main_series(rows), scene_def.stiff_from))
        lines += [""] + [f"- {n}" for n in notes] + [""]
        for caption, name in made.get(scene, []):
            lines += [f"![{caption}]({name})", ""]
    lines += ["## Comparison with the references", "",
              "Exponents are least-squares fits in log-log over the points in the claim's k_n "
              "range (errors: the fit's standard error). Each claim names the nearest physics "
              "the paper rules out and the value its measure would take under it. Verdict: "
              "**pass** if the measured value's 2-sigma interval lies inside the accepted "
              "range (the alternative excluded), **differs** if it lies wholly outside (the "
              "data contradict the paper), **FAIL** otherwise (the data cannot tell).", ""]
    lines += comparison_lines(results)
    lines += ["", "The table is also in `comparison.csv`, with the reason for each tolerance.", ""]
    if left_out or problems:
        lines += ["## Left out", ""]
        lines += [f"- `{point}`: {reason}" for point, reason in left_out]
        lines += [f"- figure {p}" for p in problems]
        lines.append("")
    (out / "report.md").write_text("\n".join(lines))
    return out / "report.md"


