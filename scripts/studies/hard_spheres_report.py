"""The tables of docs/hard_spheres.md's rules 1 and 3 from committed event-driven runs: their
postprocess summaries (data/<sweep>/<scene>/<point>.json) and the engine's own summary.txt and
collapse.txt, kept beside them (data/<sweep>/event_driven/<scene>/<point>.summary.txt,
.collapse.txt; --keep copies them there from a results directory).

    python3 -m scripts.studies.hard_spheres_report collapse DATA_DIR
    python3 -m scripts.studies.hard_spheres_report tc DATA_DIR SOFT_DATA_DIR
            [--energy-range LOW HIGH] [--min-span T] [--max-width W]
    python3 -m scripts.studies.hard_spheres_report keep RESULTS_DIR DATA_DIR

collapse  rule 1: per scene and e_w, the runs, how many collapsed before run_time, the times to
          collapse (min, median, max) and what the collapsing disk hit (the floor or bumps only,
          or disks too)
tc        rule 3: per k_n, over the seeds (mean and standard error): the TC fraction of the
          event-driven runs, their N_w, and the soft runs' N_w and multiple-contact fraction
          (t_c - N_c tau_c) / t_c. A scene that selects steady parts (the frictional flow)
          gets its own table: the event-driven runs that reached run_time only (those a cap
          or a collapse ended are counted, never averaged), N_w and E over the averaging
          window [average_start, run_time] against the soft runs that flowed to run_time over
          the same window, and the soft series' N_w and (t_c - N_c tau_c) / t_c over the steady
          parts its selection keeps (--energy-range, --min-span, --max-width: as postprocess's,
          for the soft summaries); the soft runs are those of the event-driven runs' tangential
          law in the soft sweep's main series (the variables other than kn and seed shared by
          the most k_n), so that a step check at one k_n is not mixed in
keep      copies each point's summary.txt and collapse.txt into DATA_DIR/event_driven/
"""
import argparse
import shutil
import statistics
import sys
from pathlib import Path

import numpy as np

from postprocess.record import run_name
from postprocess.runs import load_runs
from postprocess.scenes import SCENES
from postprocess.selection import Selection, add_selection_arguments, selection_of
from postprocess.study import label, main_series as study_main_series, varying_variables

ROOT = Path(__file__).resolve().parents[2]


def engine_files(data, record, suffix):
    return data / "event_driven" / (run_name(record) + suffix)


def engine_summary(data, record):
    path = engine_files(data, record, ".summary.txt")
    return dict(line.split() for line in path.read_text().splitlines())


def mean_error(values):
    if not values:
        return float("nan"), float("nan")
    m = statistics.fmean(values)
    return m, (statistics.stdev(values) / len(values) ** 0.5 if len(values) > 1 else float("nan"))


def collapse(data):
    groups = {}
    for r in load_runs(data):
        if r.params is None:
            continue
        groups.setdefault((r.scene, float(r.params["e_w"])), []).append(r)
    print("| scene | e_w | runs | collapsed | t to collapse (min, median, max) | partners of the "
          "collapsing disk | engine CPU-s (setup apart) |")
    print("|---|---|---|---|---|---|---|")
    for (scene, e_w), runs in sorted(groups.items()):
        times = sorted(r.stopped_at for r in runs if r.stopped_at is not None)
        kinds = set()
        for r in runs:
            path = engine_files(data, r, ".collapse.txt")
            if path.exists():
                said = path.read_text().split("partners:")[1]
                kinds.add("disks and boundary" if "disk" in said and ("bump" in said or "floor" in said)
                          else "disks only" if "disk" in said else "boundary only")
        span = (f"{times[0]:.4g}, {statistics.median(times):.4g}, {times[-1]:.4g}"
                if times else "-")
        cpu = sum(float(engine_summary(data, r)["cpu_seconds"]) for r in runs)
        print(f"| {scene} | {e_w:g} | {len(runs)} | {len(times)} | {span} | "
              f"{', '.join(sorted(kinds)) or '-'} | {cpu:.1f} |")


def tc(data, soft, selection=Selection()):
    """The rule 3 tables: the collisional one of the scenes averaged over their whole window,
    then frictional_tc's of those that select steady parts."""
    records = [r for r in load_runs(data) if r.params is not None]
    windowed = [r for r in records if not SCENES[r.scene].selects_steady_parts]
    if windowed:
        collisional_tc(data, windowed, soft)
    for scene in sorted({r.scene for r in records} - {r.scene for r in windowed}):
        frictional_tc(data, [r for r in records if r.scene == scene], soft, selection)


def collisional_tc(data, records, soft):
    hard = {}
    for r in records:
        hard.setdefault(float(r.params["kn"]), []).append(r)
    softs = {}
    for r in load_runs(soft):
        if r.observables is not None:
            softs.setdefault(float(r.observables["kn"]), []).append(r.observables)
    print("| k_n | t_c = tau_c | runs | TC fraction | N_w hard | runs averaged | N_w soft | "
          "(t_c - N_c tau_c)/t_c soft | soft runs |")
    print("|---|---|---|---|---|---|---|---|---|")
    for kn, runs in sorted(hard.items()):
        fraction = mean_error([float(engine_summary(data, r)["tc_fraction"]) for r in runs])
        averaged = [r.observables for r in runs if r.observables is not None]
        nw = mean_error([o["N_w"] for o in averaged])
        s = softs.get(kn, [])
        nw_soft = mean_error([o["N_w"] for o in s])
        mc = mean_error([o["mc_c"] / o["t_c"] for o in s])
        print(f"| {kn:g} | {float(runs[0].params['tc_time']):.4g} | {len(runs)} | "
              f"{fraction[0]:.4g} +- {fraction[1]:.2g} | {nw[0]:.4g} +- {nw[1]:.2g} | "
              f"{len(averaged)} | {nw_soft[0]:.4g} +- {nw_soft[1]:.2g} | "
              f"{mc[0]:.3g} +- {mc[1]:.2g} | {len(s)} |")


# what ended an event-driven run before run_time, by the engine's summary.txt `end`
ENDED_BY = {"events": "the cap on events", "collapse": "a collapse"}


def reached_run_time(data, record):
    """The event-driven run ran to run_time (not ended by its cap on events or by a collapse
    the TC model could not break) and its averaging window was measured."""
    return (engine_summary(data, record)["end"] == "time" and record.ended == "flowing"
            and record.measured is not None and record.measured["problem"] is None)


def window_mean(record, quantity):
    """A run's quantity over its whole averaging window: the mean over the window's blocks
    (equal pieces of it), as the observables average a part."""
    return float(np.mean(record.measured["window"]["blocks"][quantity]))


def main_series(records):
    """The records of the soft sweep's main series (postprocess.study.main_series: the label
    shared by the most k_n)."""
    varying = varying_variables([r.variables for r in records])
    labels = [label(r.variables, varying) for r in records]
    main = study_main_series([{"kn": kn, "label": name} for kn, name in
                              sorted({(float(r.params["kn"]), name)
                                      for r, name in zip(records, labels)})])
    return [r for r, name in zip(records, labels) if main and name == main[0]["label"]]


def spread(values):
    """The range of values over runs, 'lo-hi' (one value where all agree to 4 digits)."""
    lo, hi = f"{min(values):.4g}", f"{max(values):.4g}"
    return lo if lo == hi else f"{lo}-{hi}"


def value_error(values, digits=4):
    """A mean over runs with its standard error; '-' for none, the error 'n/a' for one run
    (not estimable)."""
    if not values:
        return "-"
    m, e = mean_error(values)
    return f"{m:.{digits}g} +- " + (f"{e:.2g}" if len(values) > 1 else "n/a")


def frictional_tc(data, records, soft, selection):
    """Rule 3's table for a scene that averages selected steady parts (the frictional flow):
    per k_n of the event-driven runs, those that reached run_time against the soft runs of the
    same tangential law in the soft sweep's main series, over the same averaging window and,
    for the soft series' own values, over the steady parts the selection keeps."""
    scene = records[0].scene
    laws = {r.params["tangential"] for r in records}
    softs = main_series([r for r in load_runs(soft, selection)
                         if r.scene == scene and r.params is not None
                         and r.params["tangential"] in laws])
    hard = {}
    for r in records:
        hard.setdefault(float(r.params["kn"]), []).append(r)
    print(f"{scene}: N_w and E per disk over the averaging window [average_start, run_time]; "
          "selected: the soft series' steady parts")
    print()
    print("| k_n | t_c = tau_c | runs | reached run_time | TC fraction | E hard | N_w hard | "
          "soft runs to run_time | E soft | N_w soft | soft runs selected | N_w soft, selected "
          "| (t_c - N_c tau_c)/t_c soft, selected |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    left_out, growth = {}, []
    for kn, runs in sorted(hard.items()):
        ended = [r for r in runs if reached_run_time(data, r)]
        blocks = [r.measured["window"]["blocks"]["E_total"] for r in ended]
        if blocks:
            growth.append((kn, len(ended), len(blocks[0]), spread([b[0] for b in blocks]),
                           spread([b[-1] for b in blocks])))
        for r in runs:
            if r not in ended:
                why = ENDED_BY.get(engine_summary(data, r)["end"], "no averaging window")
                left_out[why] = left_out.get(why, 0) + 1
        s = [r for r in softs if float(r.params["kn"]) == kn]
        flowed = [r for r in s if r.ended == "flowing" and r.measured is not None
                  and r.measured["problem"] is None]
        selected = [r.observables for r in s if r.observables is not None]
        print(f"| {kn:g} | {float(runs[0].params['tc_time']):.4g} | {len(runs)} | {len(ended)} | "
              f"{value_error([float(engine_summary(data, r)['tc_fraction']) for r in ended])} | "
              f"{value_error([window_mean(r, 'E_total') for r in ended])} | "
              f"{value_error([window_mean(r, 'N_w') for r in ended])} | {len(flowed)} | "
              f"{value_error([window_mean(r, 'E_total') for r in flowed])} | "
              f"{value_error([window_mean(r, 'N_w') for r in flowed])} | {len(selected)} | "
              f"{value_error([o['N_w'] for o in selected])} | "
              f"{value_error([o['mc_c'] / o['t_c'] for o in selected], 3)} |")
    print()
    # a flow that does not settle (E growing through the window) shows in its first and last
    # blocks, the equal pieces the window's averages are made of
    for kn, n, pieces, first, last in growth:
        print(f"k_n {kn:g}: E hard over the window's first and last blocks (of {pieces}) "
              f"{first} and {last} ({n} run{'' if n == 1 else 's'} to run_time)")
    if growth:
        print()
    series = ", ".join(f"{k} {v}" for k, v in sorted(softs[0].variables.items())
                       if k not in ("kn", "seed", "scene")) if softs else "none"
    print("Event-driven runs left out: "
          + (", ".join(f"{n} ended by {why}" for why, n in sorted(left_out.items())) or "none")
          + f". Soft series: tangential {', '.join(sorted(laws))}, {series}; selection: "
          f"{selection.describe()}.")


def keep(results, data):
    kept = 0
    for summary in Path(results).glob("*/*/summary.txt"):
        point = summary.parent
        to = Path(data) / "event_driven" / point.parent.name
        to.mkdir(parents=True, exist_ok=True)
        shutil.copy(summary, to / (point.name + ".summary.txt"))
        if (point / "collapse.txt").exists():
            shutil.copy(point / "collapse.txt", to / (point.name + ".collapse.txt"))
        kept += 1
    print(f"kept the engine's summaries of {kept} runs in {Path(data) / 'event_driven'}")


def tc_command(args):
    """tc's arguments: the event-driven sweep, the soft sweep, the soft summaries' selection."""
    parser = argparse.ArgumentParser(prog="hard_spheres_report tc", usage=__doc__)
    parser.add_argument("data", type=Path)
    parser.add_argument("soft", type=Path)
    add_selection_arguments(parser)
    options = parser.parse_args(args)
    tc(options.data, options.soft, selection_of(parser, options))


def main(argv):
    commands = {"collapse": (collapse, 1), "keep": (keep, 2)}
    if argv and argv[0] == "tc":
        tc_command(argv[1:])
        return 0
    if not argv or argv[0] not in commands or len(argv) - 1 != commands[argv[0]][1]:
        print(__doc__, file=sys.stderr)
        return 2
    command, _ = commands[argv[0]]
    command(*[Path(a) for a in argv[1:]])
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
