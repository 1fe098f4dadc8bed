"""What a sweep's time-stepped runs cost (LAMMPS's, LIGGGHTS's), from their records (timing.json's cpu_seconds, kept in the
summaries): per scene, tangential law, mobile atoms and k_n, the CPU seconds per step (steps:
the time a run reached, run_time or where its pile stopped, over dt) and per atom-step; per scene
and atoms, the median per step, which the runner's cost model (scripts/granmn_sweep/cost.py)
rests on; and the runs that cost far less per atom-step than those of their group that flowed
to the end: runs resumed from a checkpoint by a runner that recorded a point's last run alone
(the runner adds the earlier runs since: earlier_runs.json), with what they would add at their
group's median rate.

    python3 -m scripts.studies.run_costs SWEEP_DIR [SWEEP_DIR ...] [--short F]
        [selection options: those the summaries were written with, e.g. --min-span 250
        --max-width 1 for the stiff and confirmatory series; the costs do not depend on them]
"""
import argparse
import statistics
import sys
from pathlib import Path

from postprocess.io import DataError
from postprocess.runs import load_runs
from postprocess.selection import add_selection_arguments, selection_of

# A run below this fraction of its group's median CPU per atom-step is counted short: within a
# group the runs that flowed to the end spread by about +-20 % (the machine's load, the flow's
# contacts), and a resumed run's last part alone is a fifth to three fifths of a whole run.
SHORT = 0.7
MIN_GROUP = 3    # runs that flowed to the end a group needs for its median to judge by


def run_cost(record):
    """(group key, steps, atoms, cpu_seconds, flowed to the end) of a completed time-stepped
    run that recorded its CPU, else None (an event-driven run has events, not steps)."""
    if record.ended not in ("flowing", "stopped") or not record.cpu_seconds or not record.params:
        return None
    engine = (record.variables or {}).get("engine", "lammps")
    if engine == "event_driven":
        return None
    p = record.params
    reached = record.stopped_at if record.ended == "stopped" else float(p["run_time"])
    atoms = int(float(p["n_mobile"]))
    key = (record.scene, engine, p.get("tangential", "literal"), atoms, float(p["kn"]))
    return key, reached / float(p["dt"]), atoms, record.cpu_seconds, record.ended == "flowing"


def costs(records, short=SHORT):
    """{key: [(record, steps, atoms, cpu, flowed)]} of the completed runs, and the short ones:
    [(record, its CPU per atom-step over its group's median, the CPU it would add at that
    median)]."""
    groups = {}
    for r in records:
        cost = run_cost(r)
        if cost:
            groups.setdefault(cost[0], []).append((r, *cost[1:]))
    short_runs = []
    for members in groups.values():
        whole = [cpu / (steps * atoms) for _, steps, atoms, cpu, flowed in members if flowed]
        if len(whole) < MIN_GROUP:
            continue
        # the runs counted short would pull the median down: it is taken again without them
        first = statistics.median(whole)
        median = statistics.median([x for x in whole if x >= short * first])
        for r, steps, atoms, cpu, flowed in members:
            ratio = cpu / (steps * atoms) / median
            if flowed and ratio < short:
                short_runs.append((r, ratio, median * steps * atoms - cpu))
    return groups, short_runs


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("sweeps", type=Path, nargs="+")
    parser.add_argument("--short", type=float, default=SHORT,
                        help=f"a run below this fraction of its group's median CPU per "
                             f"atom-step is counted short (default {SHORT})")
    add_selection_arguments(parser)
    args = parser.parse_args(argv)
    selection = selection_of(parser, args)
    if not 0 < args.short < 1:
        parser.error(f"--short {args.short:g}: a fraction of the median, between 0 and 1")
    try:
        records = load_runs(args.sweeps if len(args.sweeps) > 1 else args.sweeps[0], selection)
    except DataError as error:
        print(f"run_costs: {error}", file=sys.stderr)
        return 2
    groups, short_runs = costs(records, args.short)
    if not groups:
        print("run_costs: no completed time-stepped run that recorded its CPU (an event-driven "
              "run has events, not steps)", file=sys.stderr)
        return 2
    print("| scene | engine | law | atoms | k_n | runs | flowed | CPU s per step (median) | "
          "ns per atom-step (median) | CPU s |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    by_size = {}
    for key, members in sorted(groups.items()):
        per_step = [cpu / steps for _, steps, _, cpu, _ in members]
        scene, engine, law, atoms, kn = key
        by_size.setdefault((scene, engine, atoms), []).extend(per_step)
        print(f"| {scene} | {engine} | {law} | {atoms} | {kn:.4g} | {len(members)} | "
              f"{sum(m[4] for m in members)} | {statistics.median(per_step):.3g} | "
              f"{1e9 * statistics.median(per_step) / atoms:.1f} | "
              f"{sum(m[3] for m in members):.0f} |")
    print()
    for (scene, engine, atoms), per_step in sorted(by_size.items()):
        print(f"{scene} ({engine}), {atoms} atoms: {statistics.median(per_step):.3g} CPU s per "
              f"step (median of {len(per_step)} runs)")
    counted = sum(m[3] for members in groups.values() for m in members)
    missing = sum(m for _, _, m in short_runs)
    print()
    for r, ratio, more in short_runs:
        print(f"counted short: {r.point} ({ratio:.2f} of its group's median per atom-step; "
              f"{more:.0f} CPU s more at that median)")
    print(f"CPU counted: {counted / 3600:.3g} CPU-hours; {len(short_runs)} runs counted short "
          f"(below {args.short:g} of their group's median), {missing / 3600:.2g} CPU-hours "
          f"more at their groups' medians: about {(counted + missing) / 3600:.3g} in all")
    return 0


if __name__ == "__main__":
    sys.exit(main())
