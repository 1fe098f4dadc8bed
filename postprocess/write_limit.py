"""The limit command: the hard-sphere-limit rule (postprocess/limit.py, docs/hard_sphere_limit.md)
on each series of the scenes it applies to, limit.md and its figures; the verdicts printed."""
import sys

import numpy as np

from . import durations, figures, limit
from .formatting import split_lines, tail_lines
from .quantities import TABLE
from .scenes import SCENES, scene as scene_of
from .study import counterparts, label, main_series, varying_variables


def report_lines(decisions, within, levels):
    """Markdown: per quantity the per-k_n values, running exponents, fits and verdict; then
    the verdicts within each energy level. decisions: [Decision]; within: {quantity: {level:
    Decision}}; levels: {name: (low, high)} (empty: the scene's flows have no levels)."""
    lines = []
    for d in decisions:
        lines += [f"### {TABLE[d.quantity].label}: **{d.verdict}**", ""]
        if d.why:
            lines += [d.why, ""]
        s = d.series
        lines += ["| k_n | runs | value | error | running exponent to the next k_n |",
                  "|---|---|---|---|---|"]
        running = {r[0]: r for r in d.running}
        for k, v, e, n in zip(s.kn, s.value, s.error, s.runs):
            r = running.get(k)
            exponent = f"{r[2]:.3f} +- {r[3]:.3f}" if r and np.isfinite(r[2]) else ""
            lines.append(f"| {k:.4g} | {int(n)} | {v:.4g} | {e:.2g} | {exponent} |")
        for k, n in d.lacking:
            lines.append(f"| {k:.4g} | {n} | (too few runs) | | |")
        if d.fits:
            f = d.fits
            lines += ["", f"- pure power law: b = {f.b_power:.3f} +- {f.b_power_error:.3f}, "
                          f"chi2 = {f.chi2_power:.2f} ({len(s.kn) - 2} dof)",
                      f"- power law onto a floor: c = {f.floor:.4g}, b = {f.b_floor:.3f}, "
                      f"chi2 = {f.chi2_floor:.2f} ({len(s.kn) - 3} dof); dAIC = {f.d_aic:.2f}",
                      f"- floor's bootstrap 95 % interval: [{d.floor_interval[0]:.3g}, "
                      f"{d.floor_interval[1]:.3g}]"]
            if d.rule == 2 and np.isfinite(d.decay[0]):
                lines.append(f"- log-log decay exponent (rule 2): b = {d.decay[0]:.3f} +- "
                             f"{d.decay[1]:.3f}, one-sided {limit.NO_FALL_CONFIDENCE:.0%} upper bound "
                             f"{d.decay[2]:.3f}; 'does not fall' below {d.decay_limit:.3f} (at "
                             f"most {limit.NO_FALL_FRACTION:.0%} lost over the range)")
        lines.append("")
    if not levels:
        return lines + ["The scene's flows have no energy levels to apply the rule within "
                        "(postprocess/scenes.py, limit_levels).", ""]
    lines += ["### Within one energy level", "",
              "| quantity | " + " | ".join(f"{n} E in [{lo:g}, {hi:g})" for n, (lo, hi)
                                           in levels.items()) + " |",
              "|---|" + "---|" * len(levels)]
    for quantity, by_level in within.items():
        lines.append(f"| {TABLE[quantity].label} | " + " | ".join(
            by_level[n].verdict for n in levels) + " |")
    lines.append("")
    for quantity, by_level in within.items():
        for n, d in by_level.items():
            if d.fits:
                s = d.series
                lines.append(f"- {TABLE[quantity].label}, {n} level: **{d.verdict}** ({d.why}); "
                             + ", ".join(f"{k:.3g}: {v:.4g} ({int(r)} runs)"
                                         for k, v, r in zip(s.kn, s.value, s.runs)))
    return lines + [""]


def contact_splits(runs):
    """[(kn, {3.0: split, 10.0: split})] of the runs whose contact rows cover a window
    (measured by durations.run_contacts, raw or from summaries)."""
    return [(o["kn"], {float(k): v for k, v in o["contacts"]["split"].items()})
            for o in runs if o.get("contacts") and "split" in o["contacts"]]


def runaway_lines(records):
    """Markdown: per series and k_n, the completed runs, those with a runaway event (limit.
    runaway_events on E(t) over windows of one time unit) and the events' times."""
    varying = varying_variables([r.variables for r in records])
    table = {}
    for r in records:
        e = r.energy
        t = e["t0"] + e["window"] * np.arange(len(e["E"]))
        events = limit.runaway_events(t, e["E"])
        row = table.setdefault((label(r.variables, varying), r.params["kn"]), [0, 0, []])
        row[0] += 1
        row[1] += bool(events)
        row[2] += [f"{x:g}" for x in events]
    lines = ["| series | k_n | completed runs | runs with a runaway | events at t = |",
             "|---|---|---|---|---|"]
    for (name, kn), (runs, hit, times) in sorted(table.items()):
        lines.append(f"| {name or '-'} | {kn:.4g} | {runs} | {hit} | {', '.join(times)} |")
    totals = {}
    for (name, _), (runs, hit, _) in table.items():
        total = totals.setdefault(name, [0, 0])
        total[0] += runs
        total[1] += hit
    if len(totals) < 2:
        return lines + [""]
    main = main_series([{"label": name} for name, _ in table])[0]["label"]
    lines += ["", f"Each series against the main one ({main or '-'}), all its k_n together: "
              "Fisher's exact test of the counts (the chance of a split of the runs with a "
              "runaway as uneven as this, were the events as likely in both; one-sided: in the "
              "direction seen):", "",
              "| series | completed runs | runs with a runaway | p, one-sided | p, two-sided |",
              "|---|---|---|---|---|"]
    main_runs, main_hit = totals[main]
    for name, (runs, hit) in sorted(totals.items()):
        tests = ("- | -" if name == main else
                 "{:.2g} | {:.2g}".format(*limit.fisher_exact(hit, runs, main_hit, main_runs)))
        lines.append(f"| {name or '-'} | {runs} | {hit} | {tests} |")
    return lines + [""]


def write_limit(sweep, scenes, out, selection, completed, rule=limit.RULE, beside=None):
    """The limit command: limit.md and a figure per series in out, for each scene the rule
    applies to (Scene.decides_limit): its main series first, then each variant with enough
    k_n; the verdicts on the terminal. completed: {scene: [RunRecord of each completed run]},
    for the runaway events; rule: 1 or 2; beside: (name, scenes) of another sweep, analysed
    alike, whose series are set beside this one's (beside_lines)."""
    names = [name for name in scenes if scene_of(name).decides_limit and scenes[name]]
    if not names:
        print(f"postprocess: {sweep}: no usable points of a scene the rule applies to ("
              + ", ".join(n for n, s in SCENES.items() if s.decides_limit) + ")",
              file=sys.stderr)
        return 2
    out.mkdir(parents=True, exist_ok=True)
    lines = [f"# The hard-sphere-limit rule {rule} on {sweep}", "",
             f"Selection of the steady parts (scenes that select them): {selection.describe()}.",
             ""]
    for name in names:
        series = scene_series(name, scenes[name], rule)
        lines += limit_scene_lines(name, series, out, completed.get(name, []), rule)
        if beside is not None:
            lines += beside_lines(name, scenes[name], series, beside, rule)
    (out / "limit.md").write_text("\n".join(lines))
    print(f"limit report: {out / 'limit.md'}")
    return 0


def scene_series(name, rows, rule):
    """[(number, label, runs, decisions, within)] of one scene's series (rows: its analysed
    rows) that the rule is applied to: the main series (number 0) first, then each variant,
    unless the rule is applied to none of its quantities; within: {quantity: {level:
    Decision}} in the scene's energy levels."""
    quantities = scene_of(name).limit_quantities
    levels = dict(scene_of(name).limit_levels)
    main = main_series(rows)
    labels = [main[0]["label"]] + sorted({o["label"] for o in rows} - {main[0]["label"]})
    out = []
    for number, series_label in enumerate(labels):
        runs = [run for o in rows if o["label"] == series_label for run in o.get("runs", [o])]
        decisions = [limit.decide(runs, q, rule=rule) for q in quantities]
        if number and all(d.verdict.startswith("not applied") for d in decisions):
            continue    # a variant at too few k_n (a check of the step at one k_n: the report's
                        # variant table compares it with the main series)
        within = {q: limit.decide_within_levels(runs, q, levels, rule=rule) for q in quantities}
        out.append((number, series_label, runs, decisions, within))
    return out


def series_title(number, series_label):
    return (f"{'main series' if number == 0 else 'variant'} "
            f"{series_label or '(no variable varies)'}")


def limit_scene_lines(name, series, out, records, rule):
    """limit.md's lines for one scene (series: scene_series; figures written to out) under
    rule 1 or 2; the verdicts printed."""
    scene_def = scene_of(name)
    levels = dict(scene_def.limit_levels)
    lines = [f"# {scene_def.title}", ""]
    for number, series_label, runs, decisions, within in series:
        title = series_title(number, series_label)
        lines += [f"## {title}: {len(runs)} selected runs", ""]
        lines += report_lines(decisions, within, levels)
        if any(d.fits for d in decisions):
            figure = f"limit_{name}_{number}.png"
            figures.limit_figure([d for d in decisions if d.fits], out / figure)
            lines += [f"![the rule's data and fits]({figure})", ""]
        splits = contact_splits(runs)
        if splits:
            lines += ["### What the time with two or more contacts is made of", "",
                      f"Per {scene_def.particle} and unit time over each run's contact-rows "
                      "window (the span's first rows_time, less 0.5 at its end), the mean over "
                      "the runs with rows: the part during which one of the contacts lasts more "
                      "than 3 (or 10) binary durations, and the part made of short contacts "
                      "only (bursts); `unseen`: the counters' time not in the rows (contacts "
                      "longer than the rows window, lasting ones).", ""]
            lines += split_lines(splits)
        with_rows = [(o["kn"], o["contacts"]) for o in runs if o.get("contacts")]
        if with_rows:
            figure = f"durations_{name}_{number}.png"
            by_kn = [(k, durations.pooled([c for kn, c in with_rows if kn == k]))
                     for k in sorted({kn for kn, _ in with_rows})]
            figures.duration_stiffness(name, [(series_label, by_kn)], durations.DURATION_EDGES,
                                       out / figure)
            lines += ["### P(tau): the weight of its tail", "",
                      "Contacts that ended after average_start, per run with rows: the fraction "
                      f"lasting longer than {durations.TAIL_CUT:g} binary durations, mean and "
                      "standard error over the runs; P(tau) of all of them in the figure.", ""]
            lines += tail_lines(with_rows, scene_def.particle)
            lines += [f"![P(tau) per k_n]({figure})", ""]
        for d in decisions:
            print(f"{scene_def.title}, {title}: {TABLE[d.quantity].label}: {d.verdict}" +
                  (f" ({d.why})" if d.why else ""))
        for quantity, by_level in within.items():
            applied = {n: d for n, d in by_level.items() if d.fits}
            if applied:
                print(f"{scene_def.title}, {title}: {TABLE[quantity].label}, within a level: " +
                      "; ".join(f"{n} {d.verdict}" for n, d in applied.items()))
    if records:
        lines += ["## Runaway events", "",
                  f"E(t), averaged over windows of one time unit, above {limit.RUNAWAY_FACTOR:g} "
                  f"times the run's median and above {limit.RUNAWAY_ENERGY:g} after t = "
                  f"{limit.SETTLED:g}, in every completed run (selected or not):", ""]
        lines += runaway_lines(records)
    return lines


def beside_lines(name, rows, series, beside, rule):
    """limit.md's section setting one scene's series (rows, series: scene_series) beside their
    counterparts in another sweep (beside: (its name, its scenes), study.counterparts), the
    rule applied to each sweep's runs alone; a line per series and quantity printed."""
    there_name, there_scenes = beside
    there_rows = there_scenes.get(name, [])
    scene_def = scene_of(name)
    if not there_rows:
        print(f"beside {there_name}: {scene_def.title}: no usable runs there")
        return [f"## Beside {there_name}", "", "No usable runs of the scene there.", ""]
    apart, there_label = counterparts(rows, there_rows)
    there_series = {entry[1]: entry for entry in scene_series(name, there_rows, rule)}
    told = "; ".join(f"{k}: {default(a)} here, {default(b)} there"
                     for k, (a, b) in apart.items())
    lines = [f"## Beside {there_name}", "",
             f"The rule applied to the other sweep's runs alone; its series matched with this "
             f"sweep's by their variables other than kn, seed and those that tell the two "
             f"sweeps apart ({told or 'none'}). Per quantity, both verdicts and the pure power "
             "law's decay exponents b (m ~ k_n^-b) with their difference here - there; at "
             "each k_n both have, here - there in combined errors (z, the rule's pooled "
             "errors) and relative to there.", ""]
    for number, series_label, _, decisions, within in series:
        title = series_title(number, series_label)
        other = there_series.get(there_label.get(series_label))
        if other is None:
            print(f"beside {there_name}: {scene_def.title}, {title}: no counterpart there "
                  "(none, or at too few k_n for the rule)")
            lines += [f"### {title}: no counterpart there", ""]
            continue
        there_title = series_title(other[0], there_label[series_label])
        lines += [f"### {title} beside {there_title}", "",
                  "| quantity | verdict there | verdict here | b there | b here | "
                  "b here - there |", "|---|---|---|---|---|---|"]
        _, _, _, there_decisions, there_within = other
        pairs = [(d, t, limit.beside(d, t)) for d, t in zip(decisions, there_decisions)]
        for d, t, b in pairs:
            lines.append(f"| {TABLE[d.quantity].label} | {t.verdict} | {d.verdict} | "
                         f"{exponent(t)} | {exponent(d)} | {difference(b)} |")
        lines.append("")
        levels = [level for level, _ in scene_def.limit_levels]
        if levels:
            lines += ["Within one energy level, the verdict there / here:", "",
                      "| quantity | " + " | ".join(levels) + " |", "|---|" + "---|" * len(levels)]
            for q in scene_def.limit_quantities:
                pair = {n: (short(there_within[q][n]), short(within[q][n])) for n in levels}
                lines.append(f"| {TABLE[q].label} | " +
                             " | ".join(f"{a} / {b}" for a, b in pair.values()) + " |")
                applied = [f"{n} {a} / {b}" for n, (a, b) in pair.items()
                           if (a, b) != ("not applied", "not applied")]
                if applied:
                    print(f"beside {there_name}: {scene_def.title}, {title}: {TABLE[q].label}, "
                          "within a level, there / here: " + "; ".join(applied))
            lines.append("")
        for d, t, b in pairs:
            lines += [f"{TABLE[d.quantity].label}:", "",
                      "| k_n | there (runs) | here (runs) | z | here / there - 1 |",
                      "|---|---|---|---|---|"]
            lines += [f"| {k:.4g} | {w:.4g} +- {f:.2g} ({m}) | {v:.4g} +- {e:.2g} ({n}) | "
                      f"{z:+.2f} | {r:+.1%} |" for k, v, e, n, w, f, m, z, r in b.shared]
            lines.append("")
            print(f"beside {there_name}: {scene_def.title}, {title}: {TABLE[d.quantity].label}:"
                  f" there {t.verdict}, here {d.verdict}; {shared_summary(b)}")
    return lines


def short(decision):
    """A verdict without a 'not applied' one's reason."""
    return decision.verdict.split(":")[0]


def default(value):
    return "the deck's default" if value is None else value


def exponent(decision):
    f = decision.fits
    return f"{f.b_power:.3f} +- {f.b_power_error:.3f}" if f else "-"


def difference(b):
    d, e = b.exponent_difference
    return f"{d:+.3f} +- {e:.3f}" if np.isfinite(d) else "-"


def shared_summary(b):
    """One line of a Beside: where here lies against there over the shared k_n."""
    if not b.shared:
        return "no k_n in common"
    z = np.array([s[7] for s in b.shared])
    r = np.array([s[8] for s in b.shared])
    lower, higher = int((z < 0).sum()), int((z > 0).sum())
    return (f"here lower at {lower}, higher at {higher} of {len(z)} shared k_n; z from "
            f"{z.min():+.2f} to {z.max():+.2f}, here / there - 1 from {r.min():+.0%} to "
            f"{r.max():+.0%}; b here - there {difference(b)}")
