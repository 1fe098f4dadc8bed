"""The tables of docs/hard_spheres.md's rules 1 and 3 from committed event-driven runs: their
postprocess summaries (data/<sweep>/<scene>/<point>.json) and the engine's own summary.txt and
collapse.txt, kept beside them (data/<sweep>/event_driven/<scene>/<point>.summary.txt,
.collapse.txt; --keep copies them there from a results directory).

    python3 -m scripts.studies.hard_spheres_report collapse DATA_DIR
    python3 -m scripts.studies.hard_spheres_report tc DATA_DIR SOFT_DATA_DIR
    python3 -m scripts.studies.hard_spheres_report keep RESULTS_DIR DATA_DIR

collapse  rule 1: per scene and e_w, the runs, how many collapsed before run_time, the times to
          collapse (min, median, max) and what the collapsing disk hit (the floor or bumps only,
          or disks too)
tc        rule 3: per k_n, over the seeds (mean and standard error): the TC fraction of the
          event-driven runs, their N_w, and the soft runs' N_w and multiple-contact fraction
          (t_c - N_c tau_c) / t_c
keep      copies each point's summary.txt and collapse.txt into DATA_DIR/event_driven/
"""
import shutil
import statistics
import sys
from pathlib import Path

from postprocess.record import run_name
from postprocess.runs import load_runs

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


def tc(data, soft):
    hard = {}
    for r in load_runs(data):
        if r.params is not None:
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


def main(argv):
    commands = {"collapse": (collapse, 1), "tc": (tc, 2), "keep": (keep, 2)}
    if not argv or argv[0] not in commands or len(argv) - 1 != commands[argv[0]][1]:
        print(__doc__, file=sys.stderr)
        return 2
    command, _ = commands[argv[0]]
    command(*[Path(a) for a in argv[1:]])
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
