"""Strong scaling of the 3D chute (inputs/chute_3d.lmp) over MPI ranks (after ./scripts/build.sh):
one settled flowing state, then the same span of the flow on each rank count.

    python3 -m bench.scaling [--ranks 1 2 4 8] [--span 20] [--repeat 3] [--settle 100]
                     [--oversubscribe] [--mpirun-args "--hostfile H"] [--figure PATH]
                     [--workdir DIR] [--kn 2e5] [--dt-fraction 0.05] [--spheres 500] ...

The dense chute (the deck's defaults: 500 spheres on the 10 x 10 rough base, sin theta 0.40,
e = beta = 0.7, mu = 0.5; here k_n 2e5 at dt = tau_c/20 and seed 1, as the preset runs it,
inputs/sweeps/chute_3d.toml) is run once, on --settle-ranks ranks, to t = --settle with the
deck's checkpoints (checkpoint_interval = settle): the lmp run is stopped once its first
checkpoint is complete, right after t = settle (the span after it must be long enough for the
stop to come first: a few hundred steps are, here).
Each measurement resumes the deck from that checkpoint (a copy of the settled directory, its
outputs cut back to the checkpoint as scripts/sweep.py does) on R ranks (`mpirun -np R lmp`)
and runs --span time units of the steady flow with the study's outputs and counters on and
LAMMPS's timer at `normal`. Printed per rank count: the wall seconds per step of the span
(LAMMPS's loop time over its steps; the best of --repeat, the rank counts interleaved so that
a drift in the machine's load hits all of them), the speed-up over the smallest rank count R0
and the parallel efficiency (speed-up / (R / R0)), the timer breakdown (Pair, Neigh, Comm,
Output, Modify, Other: % of the loop, of the best run), and whether the run's outputs agree with
R0's: counts.txt (each sphere's counters over the span) exactly, and how far into the span
energy.txt agrees to its 10 digits. All runs start from one state with the same atom ids, but
R ranks sum the forces in another order: the flow, chaotic, takes the rounding difference to
all digits within a few time units, so over a long span the counts differ (the runs are two
realizations of one flow) and the time energy.txt agrees over is the point of that column.

A rank count above the slots mpirun has (OpenMPI: one per physical core) is refused by mpirun
unless --oversubscribe (passed to mpirun as --oversubscribe; times then mean little) or an
allocation or hostfile (--mpirun-args) gives them. --figure PATH draws the speed-up against the
ranks, with the ideal line (matplotlib, Agg). --workdir keeps the settled state and the runs;
a later call with the same settings and --workdir reuses the settled state (--span included: the
run's length is part of the point its checkpoint belongs to).
"""
import argparse
import json
import math
import os
import re
import shlex
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from postprocess.io import read_params
from scripts.granmn_sweep import checkpoints
from scripts.granmn_sweep.build_layout import DEFAULT as DEFAULT_BUILD, build_layout
from scripts.granmn_sweep.mpirun_slots import slots_problem

ROOT = Path(__file__).resolve().parent.parent

DECK = ROOT / "inputs" / "chute_3d.lmp"
TIMER_SECTIONS = ("Pair", "Neigh", "Comm", "Output", "Modify", "Other")
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")


class BenchError(Exception):
    pass


def deck_variables(args, build, out, run_time):
    """The deck variables of every run: the point (the same for the settling run and each
    measurement, as the checkpoint's signature requires) and where it writes."""
    return {"plugin": build_layout(build).plugin, "lib": ROOT / "inputs" / "lib",
            "out": out, "kn": repr(args.kn), "e": repr(args.e), "beta": repr(args.beta),
            "dt_fraction": repr(args.dt_fraction), "dt_cap": repr(args.dt_cap),
            "spheres": args.spheres, "length": args.length, "width": args.width,
            "sin_theta": repr(args.sin_theta), "seed": args.seed,
            "run_time": repr(run_time), "average_start": repr(args.settle),
            "checkpoint_interval": repr(args.settle), "stop_energy": 0}


def mpirun(args, ranks):
    return ([args.mpirun, "-np", str(ranks)] + (["--oversubscribe"] if args.oversubscribe else [])
            + shlex.split(args.mpirun_args))


def lmp_command(args, build, ranks, out, run_time, extra=()):
    command = mpirun(args, ranks) + [str(build_layout(build).lammps), "-in", str(DECK), "-log",
                                     str(out / "log.lammps"), "-screen", "none", "-nocite"]
    for name, value in {**deck_variables(args, build, out, run_time), **dict(extra)}.items():
        command += ["-var", name, str(value)]
    return command


def check_slots(args, ranks):
    problem = slots_problem(mpirun(args, ranks), ENV)
    if problem:
        raise BenchError(f"{problem}: pass --oversubscribe (the times then mean little), or run "
                         "under an allocation or with --mpirun-args '--hostfile FILE'")


def session_processes(session):
    pids = []
    for entry in os.scandir("/proc"):
        if entry.name.isdigit():
            try:
                fields = Path(f"/proc/{entry.name}/stat").read_text().rsplit(")", 1)[1].split()
            except (OSError, IndexError):
                continue
            if fields[0] != "Z" and int(fields[3]) == session:
                pids.append(int(entry.name))
    return pids


def stop_session(proc):
    """SIGKILL to every process of the run's session (mpirun and its ranks), then reaps it."""
    for _ in range(100):
        alive = session_processes(proc.pid)
        if not alive:
            break
        for pid in alive:
            try:
                os.kill(pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
        time.sleep(0.05)
    proc.wait()


def settle(args, build, work, run_time):
    """The settled state: work/settled holds the deck's first checkpoint (t ~ settle) and the
    outputs up to it; reused if a call with the same settings left it."""
    settled = work / "settled"
    settings = json.dumps({k: v for k, v in vars(args).items()
                           if k in ("kn", "e", "beta", "dt_fraction", "dt_cap", "spheres",
                                    "length", "width", "sin_theta", "seed", "settle")} |
                          {"run_time": run_time}, sort_keys=True)
    if (settled / "settings.json").exists() and \
            (settled / "settings.json").read_text() == settings and checkpoints.latest(settled):
        print(f"settled state: reusing {settled}", flush=True)
        return settled, checkpoints.latest(settled)
    shutil.rmtree(settled, ignore_errors=True)
    settled.mkdir(parents=True)
    command = lmp_command(args, build, args.settle_ranks, settled, run_time,
                          {"run_token": "settle"})
    (settled / "command.txt").write_text(shlex.join(command) + "\n")
    start = time.time()
    with open(settled / "run.out", "w") as out:
        proc = subprocess.Popen(command, stdout=out, stderr=subprocess.STDOUT, env=ENV,
                                start_new_session=True)
    try:
        while checkpoints.latest(settled) is None:
            if proc.poll() is not None:
                done = (settled / "done.txt").exists()
                log = settled / "log.lammps"
                said = [line for line in (log.read_text(errors="replace") if log.exists()
                                          else "").splitlines() if line.startswith("ERROR")]
                raise BenchError(
                    "the settling run ran to its end before it could be stopped after its "
                    "checkpoint (it deletes it then): use a longer --span" if done else
                    f"the settling run ended (exit status {proc.returncode}) without a "
                    f"checkpoint: {' '.join(said) or f'see {settled}/log.lammps and run.out'}")
            time.sleep(0.002)
    finally:
        # the first checkpoint is complete (checkpoint.txt names it): the rest is not needed.
        # mpirun's ranks may be in process groups of their own, not in its session's
        stop_session(proc)
    latest = checkpoints.latest(settled)
    if latest is None:
        raise BenchError("the settling run ran to its end before it could be stopped after its "
                         "checkpoint (it deletes it then): use a longer --span")
    (settled / "settings.json").write_text(settings)
    print(f"settled state: t = {args.settle:g} on {args.settle_ranks} rank(s) in "
          f"{time.time() - start:.1f} s wall (checkpoint at step {latest[0]})", flush=True)
    return settled, latest


def measure(args, build, settled, latest, ranks, run_time, out):
    """One measured span on `ranks` ranks, resumed from the settled checkpoint in a copy of the
    settled directory: (seconds of the loop, steps, {section: seconds}, % CPU use)."""
    shutil.rmtree(out, ignore_errors=True)
    shutil.copytree(settled, out)
    step, slot = latest
    checkpoints.cut_outputs(out, step)
    command = lmp_command(args, build, ranks, out, run_time,
                          {"run_token": f"np{ranks}", "resume": slot, "timer": "normal"})
    (out / "command.txt").write_text(shlex.join(command) + "\n")
    proc = subprocess.run(command, capture_output=True, text=True, errors="replace", env=ENV)
    log = (out / "log.lammps").read_text(errors="replace") if (out / "log.lammps").exists() \
        else ""
    if proc.returncode != 0 or not (out / "done.txt").exists():
        errors = [line for line in log.splitlines() if line.startswith("ERROR")]
        raise BenchError(f"the run on {ranks} ranks failed (exit status {proc.returncode}): "
                         f"{' '.join(errors) or (proc.stdout + proc.stderr)[-1500:]} (in {out})")
    if "resuming from checkpoint" not in log:
        raise BenchError(f"the run on {ranks} ranks did not resume from the checkpoint ({out})")
    # each LAMMPS `run` of the span (one, unless the span is longer than --settle): its loop
    # time and the timer's avg seconds per section
    loops = [(float(m[1]), int(m[2]), int(m[3])) for m in
             re.finditer(r"Loop time of (\S+) on (\d+) procs for (\d+) steps", log)]
    if not loops or any(procs != ranks for _, procs, _ in loops):
        raise BenchError(f"no loop time of {ranks} procs in {out}/log.lammps")
    sections = {name: 0.0 for name in TIMER_SECTIONS}
    for name in TIMER_SECTIONS:
        for m in re.finditer(rf"^{name}\s*\|([^|]*)\|([^|]*)\|", log, re.M):
            sections[name] += float(m[2])
    cpu = [float(m) for m in re.findall(r"([\d.]+)% CPU use", log)]
    return (sum(t for t, _, _ in loops), sum(n for _, _, n in loops), sections,
            min(cpu) if cpu else math.nan)


def data_lines(path):
    return [line for line in path.read_text().splitlines() if line[:1].isdigit()]


def agreement(reference, other, start_step):
    """(counts.txt the same, energy.txt's lines of the span the same as reference's up to the
    first that differs: their number, and the step of the last of them; the span's lines)."""
    same_counts = data_lines(reference / "counts.txt") == data_lines(other / "counts.txt")
    ours = [line for line in data_lines(reference / "energy.txt")
            if int(line.split()[0]) > start_step]
    theirs = [line for line in data_lines(other / "energy.txt")
              if int(line.split()[0]) > start_step]
    equal = 0
    while equal < min(len(ours), len(theirs)) and ours[equal] == theirs[equal]:
        equal += 1
    until = int(ours[equal - 1].split()[0]) if equal else start_step
    return same_counts, equal, until, len(ours)


def figure(path, table, args):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import matplotlib.ticker
    ranks = [r for r, _ in table]
    speedup = [s for _, s in table]
    r0 = ranks[0]
    fig, ax = plt.subplots(figsize=(5, 4))
    ax.plot(ranks, [r / r0 for r in ranks], "k--", label="ideal")
    ax.plot(ranks, speedup, "o-", label="measured")
    for r, s in table:
        ax.annotate(f"{s / (r / r0):.0%}", (r, s), textcoords="offset points", xytext=(4, -12),
                    fontsize=8)
    ax.set_xscale("log", base=2)
    ax.set_yscale("log", base=2)
    ax.set_xticks(ranks, [str(r) for r in ranks])
    ax.yaxis.set_major_formatter(matplotlib.ticker.FuncFormatter(lambda y, _: f"{y:g}"))
    ax.yaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    ax.set_xlabel("MPI ranks")
    ax.set_ylabel(f"speed-up over {r0} rank{'s' if r0 > 1 else ''}")
    ax.set_title(f"3D chute, {args.spheres} spheres on {args.length} x {args.width}, "
                 f"k_n {args.kn:g}", fontsize=9)
    ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter,
                                     epilog="\n".join(__doc__.splitlines()[2:]))
    parser.add_argument("--ranks", type=int, nargs="+", default=[1, 2],
                        help="rank counts to measure (default 1 2)")
    parser.add_argument("--span", type=float, default=20.0,
                        help="measured time units of the flow after the settled state")
    parser.add_argument("--repeat", type=int, default=3, help="runs per rank count; the best")
    parser.add_argument("--settle", type=float, default=100.0,
                        help="time of the settled state (the flow steady: docs/scenes.md)")
    parser.add_argument("--settle-ranks", type=int, default=1,
                        help="ranks of the settling run (default 1)")
    parser.add_argument("--kn", type=float, default=2e5)
    parser.add_argument("--e", type=float, default=0.7)
    parser.add_argument("--beta", type=float, default=0.7)
    parser.add_argument("--dt-fraction", type=float, default=0.05)
    parser.add_argument("--dt-cap", type=float, default=1.0)
    parser.add_argument("--spheres", type=int, default=500)
    parser.add_argument("--length", type=int, default=10)
    parser.add_argument("--width", type=int, default=10)
    parser.add_argument("--sin-theta", type=float, default=0.40)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--oversubscribe", action="store_true",
                        help="pass --oversubscribe to mpirun (more ranks than slots)")
    parser.add_argument("--mpirun", default=shutil.which("mpirun") or "mpirun")
    parser.add_argument("--mpirun-args", default="",
                        help="more mpirun options, e.g. '--hostfile FILE --bind-to core'")
    parser.add_argument("--figure", type=Path, help="speed-up against ranks (PNG, PDF, ...)")
    parser.add_argument("--workdir", type=Path,
                        help="keep the settled state and the runs here (default: a temporary "
                             "directory, removed)")
    parser.add_argument("--build", type=Path, default=DEFAULT_BUILD)
    args = parser.parse_args()
    ranks = sorted(set(args.ranks))
    if ranks[0] < 1 or args.settle_ranks < 1 or args.repeat < 1:
        parser.error("--ranks, --settle-ranks and --repeat must be >= 1")
    if not (args.span > 0 and args.settle > 0):
        parser.error("--span and --settle must be > 0")
    for path in build_layout(args.build)[1:3]:    # lmp and the plugin
        if not path.exists():
            sys.exit(f"{path} is missing: run ./scripts/build.sh first")

    # the deck checkpoints every --settle (rounded to its output steps, the deck's rule):
    # the span runs from its first checkpoint to run_time, --span to within an output interval
    run_time = args.settle + args.span
    work = args.workdir or Path(tempfile.mkdtemp(prefix="granmn-scaling-"))
    try:
        for r in sorted({*ranks, args.settle_ranks}):
            check_slots(args, r)
        settled, latest = settle(args, args.build, work, run_time)
        best, outputs = {}, {}
        for repeat in range(args.repeat):
            for r in ranks:     # interleaved
                out = work / f"np{r}-{repeat + 1}"
                result = measure(args, args.build, settled, latest, r, run_time, out)
                print(f"  {r} rank(s), run {repeat + 1}: {result[0]:.3f} s for {result[1]} "
                      f"steps", flush=True)
                outputs.setdefault(r, []).append(out)
                if r not in best or result[0] < best[r][0]:
                    best[r] = result
    except BenchError as error:
        if not args.workdir:
            shutil.rmtree(work, ignore_errors=True)
        sys.exit(f"scaling: {error}")

    params = read_params(settled)
    dt = params["dt"]
    r0 = ranks[0]
    base = best[r0][0] / best[r0][1]
    steps = best[r0][1]
    print(f"\nStrong scaling of the 3D chute: {args.spheres} spheres on a {args.length} x "
          f"{args.width} base ({args.spheres + args.length * args.width} atoms), sin theta "
          f"{args.sin_theta:g}, k_n {args.kn:g}, dt = {dt:.4g} (tau_c x {dt / params['tau_c']:.3g}); "
          f"{steps} steps ({steps * dt:.3g} time units) from the state settled at t = "
          f"{latest[0] * dt:.4g}; best of {args.repeat}, rank counts interleaved; mpirun "
          f"{shlex.join(mpirun(args, 0)[3:]) or '(no options)'}")
    print(f"{'ranks':>5} {'s/step':>10} {'speed-up':>9} {'efficiency':>10}  "
          + " ".join(f"{name:>6}" for name in TIMER_SECTIONS)
          + f"  {'CPU use':>7}  as {r0} rank{'s' if r0 > 1 else ''}: counts.txt; energy.txt")
    table = []
    for r in ranks:
        seconds, n, sections, cpu = best[r]
        per_step = seconds / n
        speedup = base / per_step
        table.append((r, speedup))
        same, equal, until, lines = agreement(outputs[r0][0], outputs[r][0], latest[0])
        repeats_agree = all(agreement(outputs[r][0], other, latest[0])[:2] == (True, lines)
                            for other in outputs[r][1:])
        print(f"{r:5d} {per_step:10.4g} {speedup:9.3f} {speedup / (r / r0):10.1%}  "
              + " ".join(f"{100 * sections[name] / seconds:6.1f}" for name in TIMER_SECTIONS)
              + f"  {cpu:6.1f}%  {'same' if same else 'differ'}; "
              + (f"all {lines} lines" if equal == lines else
                 f"{equal} of {lines} lines, to t = {until * dt:.4g}")
              + ("" if repeats_agree else f" (its {args.repeat} runs differ among themselves)"))
    print("(s/step: LAMMPS's loop time per step, wall; the sections: % of the loop, the ranks' "
          "mean; CPU use: LAMMPS's, the lowest of the runs' `run`s; counts.txt: each sphere's "
          "counters over the span; energy.txt: its lines of the span, one per output "
          "interval, equal to their 10 digits)")
    if args.figure:
        figure(args.figure, table, args)
        print(f"figure: {args.figure}")
    if not args.workdir:
        shutil.rmtree(work, ignore_errors=True)
    else:
        print(f"runs kept in {work}")


if __name__ == "__main__":
    main()
