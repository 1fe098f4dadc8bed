"""python3 -m postprocess {report,compare,limit} SWEEP_DIR [SWEEP_DIR ...] [--output DIR]
        [--resolution T] [--energy-range LOW HIGH] [--min-span T] [--max-width W] [--rule R]
python3 -m postprocess transition SWEEP_DIR [--output DIR]
python3 -m postprocess summarize RESULTS_DIR [--to DIR] [--replace]

Several SWEEP_DIRs are analysed as one sweep (a preset and its extension, e.g. data/chute_3d
data/chute_3d_stiff); the output goes to the first's report/ or limit/ unless --output says.
A run found in two of them (the same <scene>/<point> with the same values: a directory given
twice, a results directory and its summaries) is counted once; two different runs under one
name are refused.

report      tables, figures, the comparison and report.md in DIR (default SWEEP_DIR/report)
compare     the comparison table on the terminal: each claim of the paper passes, differs
            (the data contradict it: a finding) or FAILs (the data cannot tell the paper's
            physics from the alternative the claim names); exit status 1 if a claim fails or
            none could be evaluated
transition  a transition sweep (inputs/sweeps/transition.toml, docs/transition.md): per base
            and inclination, how the runs ended, the stiffness exponents, the multiple
            contacts and P(tau), with figures, in DIR (default SWEEP_DIR/transition)
limit       the hard-sphere-limit rule (docs/hard_sphere_limit.md) on each series of the scenes
            it applies to (the 2D frictional flow and the 3D chute; the collisional flow's
            t_w - N_w tau_w): running exponents, the fits, the verdicts, what the multiple
            contacts are made of (runs with contact rows), in DIR (default SWEEP_DIR/limit)
summarize   one compact summary per run of RESULTS_DIR, DIR/<scene>/<point>.json (default
            DIR: data/<name of RESULTS_DIR> in the repository); report and compare take a
            directory of summaries as SWEEP_DIR as well as a results directory (docs/sweeps.md);
            a summary there that is more complete than the new one (its run completed, the
            new one's did not; its outputs were read or measured, the new one's not; its E(t)
            reaches further; it has contact rows, the new one not), or that this code cannot
            read, is kept unless --replace

--resolution T: the frictional steady-part selection works on E(t) averaged over windows of
T time units (default 1).
--energy-range LOW HIGH: the mean energy per disk a steady part must have (default: the
paper's 0.4 0.8); other values show whether a conclusion depends on the window.
--min-span T: the shortest steady part kept, in time units (default: the paper's 500; the
stiff preset's runs average over 300 and use 250, docs/hard_sphere_limit.md). Summaries hold
the steady parts found with one min-span: summarize and read them with the same.
--max-width W: the widest range of E(t) (after averaging over --resolution) a steady part may
have (default 0.45; the stiff preset's rule uses 1.0, docs/hard_sphere_limit.md); summaries
likewise hold one.
--rule R: the hard-sphere-limit rule limit and compare apply (docs/hard_sphere_limit.md):
2 (default) says "finite" also for a series shown not to fall; 1 is the rule the first stiff
series was judged by."""
import argparse
import sys
from pathlib import Path

import numpy as np

from . import figures, limit
from .io import DataError
from .quantities import TABLE
from .reference import accepted, evaluate, tally
from .report import comparison_line, fmt, write_report, write_transition_report
from .scenes import SCENES, scene as scene_of
from .selection import Selection
from .study import analyse, label, main_series, varying_variables
from .summary import write_summaries
from .transition import analyse_transition

DATA = Path(__file__).resolve().parents[1] / "data"


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python3 -m postprocess", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("command", choices=("report", "compare", "transition", "limit",
                                            "summarize"))
    parser.add_argument("sweeps", type=Path, nargs="+", metavar="sweep")
    parser.add_argument("--output", type=Path)
    parser.add_argument("--to", type=Path)
    parser.add_argument("--replace", action="store_true")
    parser.add_argument("--resolution", type=float, default=1.0)
    parser.add_argument("--energy-range", type=float, nargs=2, default=(0.4, 0.8),
                        metavar=("LOW", "HIGH"))
    parser.add_argument("--min-span", type=float, default=Selection.min_length)
    parser.add_argument("--max-width", type=float, default=Selection.max_width)
    parser.add_argument("--rule", type=int, choices=limit.RULES, default=limit.RULE)
    args = parser.parse_args(argv)
    if args.rule != limit.RULE and args.command not in ("limit", "compare"):
        parser.error("--rule is for limit and compare")
    if len(args.sweeps) > 1 and args.command in ("summarize", "transition"):
        parser.error(f"{args.command} takes one directory")
    args.sweep = args.sweeps[0]
    sources = args.sweeps if len(args.sweeps) > 1 else args.sweep
    named = " + ".join(str(p) for p in args.sweeps)
    if not args.resolution > 0:
        parser.error(f"--resolution {args.resolution:g} must be > 0")
    low, high = args.energy_range
    if not 0 <= low < high:
        parser.error(f"--energy-range {low:g} {high:g} must satisfy 0 <= LOW < HIGH")
    if not args.min_span > 0:
        parser.error(f"--min-span {args.min_span:g} must be > 0")
    if not args.max_width > 0:
        parser.error(f"--max-width {args.max_width:g} must be > 0")
    selection = Selection(resolution=args.resolution, energy_range=(low, high),
                          min_length=args.min_span, max_width=args.max_width)
    if (args.to is not None or args.replace) and args.command != "summarize":
        parser.error("--to and --replace are for summarize")
    # where the command writes (compare: nowhere), and the option that named it
    out, option = {"summarize": (args.to or DATA / args.sweep.resolve().name, "--to"),
                   "compare": (None, None)}.get(
        args.command, (args.output or args.sweep / args.command, "--output"))
    if out is not None and in_the_way(out):
        print(f"postprocess: {option if out in (args.to, args.output) else 'output directory'} "
              f"{out}: {in_the_way(out)} is a file, not a directory", file=sys.stderr)
        return 2
    if args.command == "summarize":
        to = out
        try:
            written, kept = write_summaries(args.sweep, to, selection, args.replace)
        except DataError as error:
            print(f"postprocess: {error}", file=sys.stderr)
            return 2
        for path, why in kept:
            print(f"kept {path}: {why} (--replace writes the new one)", file=sys.stderr)
        size = sum(p.stat().st_size for p in written)
        print(f"summaries: {len(written)} runs written in {to} ({size / 1024:.0f} kB)" +
              (f", {len(kept)} kept as they were" if kept else ""))
        return 0
    if args.command == "transition":
        try:
            runs, groups, left_out = analyse_transition(args.sweep)
        except DataError as error:
            print(f"postprocess: {error}", file=sys.stderr)
            return 2
        for point, reason in left_out:
            print(f"left out {point}: {reason}", file=sys.stderr)
        path = write_transition_report(args.sweep, runs, groups, left_out, out)
        print(f"transition report: {path}")
        return 0
    try:
        scenes, left_out, completed, runs = analyse(sources, selection)
    except DataError as error:
        print(f"postprocess: {error}", file=sys.stderr)
        return 2
    for point, reason in left_out:
        print(f"left out {point}: {reason}", file=sys.stderr)
    if args.command == "limit":
        return write_limit(named, scenes, out, selection, completed, args.rule)
    if args.command == "report":
        path = write_report(named, scenes, left_out, completed, out, runs, selection)
        print(f"report: {path}")
        return 0
    results = evaluate(scenes, rule=args.rule)
    width = max(len(c["id"]) for c, *_ in results)
    for claim, value, error, status in results:
        print(f"{claim['id']:<{width}}  {fmt(value, error):>18}  "
              f"{accepted(claim)}  {status}")
    print(comparison_line(results))
    counts = tally(results)
    return 1 if counts["FAIL"] or counts["not evaluated"] == len(results) else 0


def in_the_way(directory):
    """The file that keeps `directory` from being made and written into (it, or the first of
    its parents there), or None."""
    for path in (directory, *directory.parents):
        if path.exists():
            return None if path.is_dir() else path
    return None


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
    return lines + [""]


def write_limit(sweep, scenes, out, selection, completed, rule=limit.RULE):
    """The limit command: limit.md and a figure per series in out, for each scene the rule
    applies to (Scene.decides_limit): its main series first, then each variant with enough
    k_n; the verdicts on the terminal. completed: {scene: [RunRecord of each completed run]},
    for the runaway events; rule: 1 or 2."""
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
        lines += limit_scene_lines(name, scenes[name], out, completed.get(name, []), rule)
    (out / "limit.md").write_text("\n".join(lines))
    print(f"limit report: {out / 'limit.md'}")
    return 0


def limit_scene_lines(name, rows, out, records, rule):
    """limit.md's lines for one scene (its series, figures written to out) under rule 1 or 2;
    the verdicts printed."""
    scene_def = scene_of(name)
    levels = dict(scene_def.limit_levels)
    main = main_series(rows)
    labels = [main[0]["label"]] + sorted({o["label"] for o in rows} - {main[0]["label"]})
    lines = [f"# {scene_def.title}", ""]
    for number, series_label in enumerate(labels):
        runs = [run for o in rows if o["label"] == series_label for run in o.get("runs", [o])]
        decisions = [limit.decide(runs, q, rule=rule) for q in scene_def.limit_quantities]
        if number and all(d.verdict.startswith("not applied") for d in decisions):
            continue    # a variant at too few k_n (a check of the step at one k_n)
        within = {q: limit.decide_within_levels(runs, q, levels, rule=rule)
                  for q in scene_def.limit_quantities}
        title = (f"{'main series' if number == 0 else 'variant'} "
                 f"{series_label or '(no variable varies)'}")
        lines += [f"## {title}: {len(runs)} selected runs", ""]
        lines += limit.report_lines(decisions, within, levels)
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
            lines += limit.split_lines(splits)
        for d in decisions:
            print(f"{scene_def.title}, {title}: {TABLE[d.quantity].label}: {d.verdict}" +
                  (f" ({d.why})" if d.why else ""))
    if records:
        lines += ["## Runaway events", "",
                  f"E(t), averaged over windows of one time unit, above {limit.RUNAWAY_FACTOR:g} "
                  f"times the run's median and above {limit.RUNAWAY_ENERGY:g} after t = "
                  f"{limit.SETTLED:g}, in every completed run (selected or not):", ""]
        lines += runaway_lines(records)
    return lines


if __name__ == "__main__":
    sys.exit(main())
