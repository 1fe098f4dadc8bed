"""python3 -m postprocess {report,compare,limit} SWEEP_DIR [SWEEP_DIR ...] [--output DIR]
        [--resolution T] [--energy-range LOW HIGH] [--min-span T] [--max-width W] [--rule R]
        [--beside SWEEP_DIR [SWEEP_DIR ...]]   (limit only)
python3 -m postprocess transition SWEEP_DIR [--output DIR]
python3 -m postprocess summarize RESULTS_DIR [--to DIR] [--replace]
python3 -m postprocess engines SWEEP_DIR [SWEEP_DIR ...] [--output DIR]
python3 -m postprocess finite-size SWEEP_DIR [SWEEP_DIR ...] [--output DIR] [selection options]
python3 -m postprocess dissipation SWEEP_DIR [SWEEP_DIR ...] [--output DIR]

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
engines     a scene run in two engines (a point's engine: lammps, liggghts; docs/liggghts.md):
            per k_n, E, N_c, t_c and t_c - N_c tau_c of each engine (means over the seeds)
            and whether they agree, in DIR (default SWEEP_DIR/engines); exit status 1 if
            they differ on one or nothing could be compared
finite-size the frictional scene at several widths (the deck's width, docs/hard_sphere_limit.md
            "The width"): per law, k_n and width how the runs ended, each quantity's mean,
            error and scatter, the width dependence against the widest width, and the width
            and seeds the rule gives the wide series, in DIR (default SWEEP_DIR/finite-size)
dissipation where the contacts' energy goes as k_n grows (runs with energies = yes and rows =
            yes, docs/hard_sphere_limit.md "Where the energy goes"): per scene, tangential
            law and k_n the shares of the dissipated energy lost in lasting contacts, in
            multiple contacts and in binary collisions, the negative sliding work, and rule 2
            on the lasting share, in DIR (default SWEEP_DIR/dissipation)
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
series was judged by.
--beside SWEEP_DIR ...: limit also applies the rule to another sweep's runs alone (the same
selection) and sets its series beside this sweep's, matched by their variables other than
those that tell the two sweeps apart (e.g. the wide series' width 40 beside the paper's width):
both verdicts, the decay exponents' difference and, per k_n both have, the difference in
combined errors (limit.md's "Beside" section; a line per series and quantity printed)."""
import argparse
import sys
from pathlib import Path

from . import limit
from .io import DataError
from .selection import add_selection_arguments, selection_of
from .study import analyse
from .transition import analyse_transition
from .runs import load_runs
from .write_compare import write_compare
from .write_dissipation import write_dissipation
from .write_engines import write_engines
from .write_finite_size import write_finite_size
from .write_limit import write_limit
from .write_report import write_report
from .write_summaries import write_summaries
from .write_transition import write_transition_report

DATA = Path(__file__).resolve().parents[1] / "data"    # the repository's, run in place
COMMANDS = ("report", "compare", "transition", "limit", "summarize", "engines", "finite-size",
            "dissipation")


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python3 -m postprocess", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("command", choices=COMMANDS)
    parser.add_argument("sweeps", type=Path, nargs="+", metavar="sweep")
    parser.add_argument("--output", type=Path)
    parser.add_argument("--to", type=Path)
    parser.add_argument("--replace", action="store_true")
    add_selection_arguments(parser)
    parser.add_argument("--rule", type=int, choices=limit.RULES, default=limit.RULE)
    parser.add_argument("--beside", type=Path, nargs="+", metavar="sweep")
    args = parser.parse_args(argv)
    if args.beside and args.command != "limit":
        parser.error("--beside is for limit")
    if args.rule != limit.RULE and args.command not in ("limit", "compare"):
        parser.error("--rule is for limit and compare")
    if len(args.sweeps) > 1 and args.command in ("summarize", "transition"):
        parser.error(f"{args.command} takes one directory")
    args.sweep = args.sweeps[0]
    sources = args.sweeps if len(args.sweeps) > 1 else args.sweep
    named = " + ".join(str(p) for p in args.sweeps)
    selection = selection_of(parser, args)
    if (args.to is not None or args.replace) and args.command != "summarize":
        parser.error("--to and --replace are for summarize")
    in_repository = (DATA.parent / "pyproject.toml").exists()
    if args.command == "summarize" and args.to is None and not in_repository:
        parser.error("summarize needs --to DIR where postprocess is installed: its default, "
                     "data/<name>, is the repository's")
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
    if args.command in ("engines", "finite-size", "dissipation"):
        try:
            runs = load_runs(sources, selection)
        except DataError as error:
            print(f"postprocess: {error}", file=sys.stderr)
            return 2
        write = {"engines": write_engines, "finite-size": write_finite_size,
                 "dissipation": write_dissipation}[args.command]
        return write(named, runs, out)
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
        beside = None
        if args.beside:
            try:
                there, there_left_out, _, _ = analyse(
                    args.beside if len(args.beside) > 1 else args.beside[0], selection)
            except DataError as error:
                print(f"postprocess: {error}", file=sys.stderr)
                return 2
            beside_name = " + ".join(str(p) for p in args.beside)
            if there_left_out:
                print(f"beside {beside_name}: {len(there_left_out)} runs left out (limit on it "
                      "alone names them)", file=sys.stderr)
            beside = (beside_name, there)
        return write_limit(named, scenes, out, selection, completed, args.rule, beside)
    if args.command == "report":
        path = write_report(named, scenes, left_out, completed, out, runs, selection)
        print(f"report: {path}")
        return 0
    return write_compare(scenes, args.rule, completed)


def in_the_way(directory):
    """The file that keeps `directory` from being made and written into (it, or the first of
    its parents there), or None."""
    for path in (directory, *directory.parents):
        if path.exists():
            return None if path.is_dir() else path
    return None


if __name__ == "__main__":
    sys.exit(main())
