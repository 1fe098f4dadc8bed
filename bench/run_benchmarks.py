"""The benchmarks of the contact law, side by side in one run (after ./scripts/build.sh):

- the per-step cost of the paper's flowing scenes (inputs/frictional_flow.lmp and
  inputs/collisional_flow.lmp) as the study runs them (counters and outputs on), with the
  counters off, and in the hand-written reference loop of the same law (bench/reference_loop.cpp),
  with LAMMPS's timer breakdown, and with glibc's memset kept from `rep stosb` (VECTOR_MEMSET:
  what that choice costs LAMMPS's force clear); --baseline compares with another checkout's
  decks and plugin;
- per-step cost of pair_style gran/mn against LAMMPS's gran/hooke/history on the same dense
  monodisperse flow, parameters matched so that both laws agree while contacts stick,
  with fix contacts/mn off and on;
- the same scene in Debian's LIGGGHTS 3.8 (hooke/stiffness);
- 1 against 2 MPI ranks on that scene, and a 2-partition sweep against two serial runs;
- memory per particle (LAMMPS's own accounting).

    python3 -m bench.run_benchmarks [--steps 4000] [--repeat 3] [--side 40] [--scenes-only]
                            [--warmup 10] [--span 10] [--baseline SOURCE_TREE]
                            [--build build|build-2025|build-2026]

Each figure is the best of --repeat runs, the variants interleaved so that drifts in the
machine's load hit all of them; the scenes' ratios to the reference loop are also given paired
round by round (median and range over the rounds), and the goals of docs/performance.md for
them (frictional at most 1.5x, collisional 2x, counters and outputs on) judged on those: met,
not met or undecided by a one-sided sign test (bench/paired.py: 7 rounds of 7, 8 of 9 decide)."""
import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from collections import namedtuple
from pathlib import Path

from bench.equivalent_laws import LIGGGHTS_FLOOR, hooke_history_contacts, liggghts_contacts
from bench.paired import against_goal, median_and_range, paired_ratios
from scripts.granmn_sweep.build_layout import build_layout
from scripts.granmn_sweep.mn_law import derived

ROOT = Path(__file__).resolve().parent.parent
SCENES = {"frictional_flow": "frictional", "collisional_flow": "collisional"}
# docs/performance.md's goals: a scene as the study runs it (counters and outputs) at most this
# many times the reference loop's CPU per step, judged on the paired ratios (bench/paired.py)
GOALS = {"frictional_flow": 1.5, "collisional_flow": 2.0}
TIMER_SECTIONS = ("Pair", "Neigh", "Comm", "Output", "Modify", "Other")
KN, E, BETA, MU = 2e5, 0.7, 0.7, 0.5
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
# glibc's memset switches to `rep stosb` from 2 kB up; LAMMPS's force clear (f and torque of the
# atoms and ghosts, 2.5-3 kB each in the scenes) falls just above. A variant of the scenes runs
# with the switch moved out of the way, the rest unchanged (the same zeros, the same outputs),
# to show what that choice costs on the machine at hand (after any tunables the caller set).
VECTOR_MEMSET = {"GLIBC_TUNABLES": ":".join(
    filter(None, (os.environ.get("GLIBC_TUNABLES"), "glibc.cpu.x86_rep_stosb_threshold=1048576")))}


class Build(namedtuple("Build", "directory lmp plugin mn_law reference_loop")):
    """What a checkout's build directory holds: ./scripts/build.sh makes `build` (Debian 12's
    LAMMPS), `--lammps 2025` and `--lammps 2026` make `build-2025` and `build-2026`."""

    @property
    def programs(self):
        """What a run needs built: lmp, the plugin, mn-law and the reference loop."""
        return self[1:]

    @classmethod
    def of(cls, tree, name):
        paths = build_layout(tree / name)
        return cls(paths.directory, paths.lammps, paths.plugin, paths.mn_law,
                   paths.reference_loop)


def law(build):
    return derived(build.mn_law, KN, E, BETA)


def data_file(path, side):
    """side x side unit disks (mass 1) touching on a square lattice above the floor y = 0,
    with small deterministic velocities: a dense pile that starts to flow under tilted gravity."""
    n = side * side
    width = side * 1.0 + 0.5
    lines = ["dense flow benchmark", "", f"{n} atoms", "1 atom types", "",
             f"0 {width} xlo xhi", f"-1 {side + 20} ylo yhi", "-0.5 0.5 zlo zhi", "",
             "Atoms", ""]
    for k in range(n):
        i, j = k % side, k // side
        lines.append(f"{k + 1} 1 1.0 1.0 {0.5 + i} {0.5 + j * 1.0} 0")
    lines += ["", "Velocities", ""]
    for k in range(n):
        lines.append(f"{k + 1} {0.1 * ((k * 7919) % 13 - 6) / 6} 0 0 0 0 0")
    path.write_text("\n".join(lines) + "\n")


def lammps_deck(build, data, style, counters, steps, dt):
    c = law(build)
    common = f"""
units lj
dimension 2
atom_style sphere
boundary p fm p
comm_modify vel yes
neighbor 0.2 bin
read_data {data}
set type 1 mass 1.0
"""
    if style == "gran/mn":
        contact = f"""plugin load {build.plugin}
{common}
pair_style gran/mn kn {KN} e {E} beta {BETA} mu {MU}
pair_coeff * *
fix floor all wall/gran/mn yplane 0.0 NULL
"""
    else:
        contact = common + hooke_history_contacts(c, KN, MU)
    return contact + f"""
timestep {dt!r}
fix integrate all nve/sphere disc
fix flat all enforce2d
fix gravity all gravity 1.0 vector 0.3 -1 0
{'fix c all contacts/mn' if counters else ''}
thermo {steps}
run {steps}
"""


def liggghts_deck(build, data, steps, dt):
    c = law(build)
    return f"""
atom_style granular
dimension 2
boundary p fm p
newton off
communicate single vel yes
units lj
read_data {data}
set type 1 mass 1.0
neighbor 0.2 bin
{liggghts_contacts(c, KN, MU)}{LIGGGHTS_FLOOR}
timestep {dt!r}
fix integrate all nve/sphere
fix flat all enforce2d
fix gravity all gravity 1.0 vector 0.3 -1 0
thermo {steps}
run {steps}
"""


def run(command, deck, work):
    (work / "in.bench").write_text(deck)
    start = time.time()
    proc = subprocess.run(command + ["-in", "in.bench", "-log", "log.bench"], cwd=work,
                          capture_output=True, text=True, errors="replace", env=ENV)
    wall = time.time() - start
    if proc.returncode != 0:
        raise RuntimeError(f"{command[0]} failed:\n{proc.stdout[-2000:]}{proc.stderr[-2000:]}")
    loop = float(re.search(r"Loop time of (\S+)", proc.stdout).group(1))
    memory = re.search(r"memory allocation.*= \S+ \| (\S+) \| \S+ Mbytes", proc.stdout)
    return loop, (float(memory.group(1)) if memory else float("nan")), wall


def scene_run(lmp, source, scene, counters, timer, integration, environment, dt_fraction,
              warmup, span, work):
    """One scene deck and plugin of `source` (a Build of a checkout, its plugin built against
    lmp's LAMMPS), run by lmp with `environment` added to its own (or nothing): CPU us/step
    over the span after the warm-up (the deck's second run), its timer breakdown (% of the
    loop; None unless the deck's timer is normal or full), mean E per disk over the span."""
    out = work / f"{scene}-{counters}-{timer}-{integration}-{bool(environment)}"
    out.mkdir(exist_ok=True)
    tree = source.directory.parent
    command = [str(lmp), "-in", str(tree / "inputs" / f"{scene}.lmp"), "-log", "none",
               "-var", "plugin", str(source.plugin),
               "-var", "lib", str(tree / "inputs" / "lib"), "-var", "out", str(out),
               "-var", "kn", repr(KN), "-var", "run_time", repr(warmup + span),
               "-var", "average_start", repr(warmup), "-var", "stop_energy", "0",
               "-var", "dt_fraction", repr(dt_fraction)]
    if counters is not None:
        command += ["-var", "counters", counters]
    if timer is not None:
        command += ["-var", "timer", timer]
    if integration is not None:
        command += ["-var", "integration", integration]
    proc = subprocess.run(command, cwd=work, capture_output=True, text=True, errors="replace",
                          env=dict(ENV, **(environment or {})))
    if proc.returncode != 0:
        raise RuntimeError(f"{scene} failed:\n{proc.stdout[-2000:]}{proc.stderr[-2000:]}")
    loops = re.findall(r"Loop time of (\S+) on \d+ procs for (\d+) steps", proc.stdout)
    span_log = proc.stdout[proc.stdout.rfind("Loop time of"):]
    # CPU time, not wall time: LAMMPS's loop time times its share of a core ("CPU use"), so
    # that other processes on the machine weigh less
    cpu_share = float(re.search(r"([\d.]+)% CPU use", span_log).group(1)) / 100
    seconds, steps = float(loops[-1][0]) * cpu_share, int(loops[-1][1])
    sections = {name: re.search(rf"^{name}\s*\|.*\|\s*(\S+)\s*$", span_log, re.M)
                for name in TIMER_SECTIONS}
    breakdown = ({name: float(m.group(1)) for name, m in sections.items()}
                 if all(sections.values()) else None)
    energy = [float(line.split()[3]) for line in (out / "energy.txt").read_text().splitlines()
              if not line.startswith("#")]
    in_span = energy[int(len(energy) * warmup / (warmup + span)):]
    return 1e6 * seconds / steps, breakdown, sum(in_span) / len(in_span)


def reference_run(build, scene, dt_fraction, warmup, span):
    """build's reference loop on the same scene, time step and span: CPU us/step, E per disk,
    contacts per step."""
    dt = min(dt_fraction * law(build)["tau_c"], 1e-4)    # as the decks (dt_cap 1e-4)
    proc = subprocess.run([str(build.reference_loop), SCENES[scene], repr(KN),
                           repr(dt_fraction), repr(warmup), str(int(span / dt))],
                          capture_output=True, text=True, check=True)
    fields = proc.stdout.split()
    values = dict(zip(fields[::2], fields[1::2]))
    return float(values["us_per_step"]), float(values["energy_per_disk"]), \
        float(values["contacts_per_step"])


def scene_comparison(args, build, work):
    """Each scene in LAMMPS (counters on, off; the baseline's) against the reference loop,
    the variants interleaved, best of --repeat; then each variant against the reference loop
    of the same round, the median over the rounds with their range (the machine's speed drifts
    between rounds: a best-of time and the loop's can come from rounds of different speed)."""
    # The decks run LAMMPS's timer at `loop` (the total only); the breakdown comes from the same
    # run with the timer at `normal`, which costs a few % more.
    # (source, counters, timer, integration, environment); None: the deck's default
    variants = {"LAMMPS, counters + outputs": (build, "yes", None, None, None),
                "LAMMPS, counters off": (build, "no", None, None, None),
                "LAMMPS, counters + outputs, timer": (build, "yes", "normal", None, None),
                "LAMMPS, fix nve/sphere + gravity": (build, "yes", None, "separate", None),
                "LAMMPS, memset by vector stores": (build, "yes", None, None, VECTOR_MEMSET)}
    if args.baseline:
        baseline = Build.of(Path(args.baseline).resolve(), args.build)
        variants["baseline, counters + outputs"] = (baseline, None, None, None, None)
        variants["baseline, counters off"] = (baseline, "no", None, None, None)
    print(f"Scenes at kn = {KN:g}, dt = tau_c x {args.dt_fraction:g}, {args.span:g} time units "
          f"after a {args.warmup:g} warm-up, best of {args.repeat}; CPU us per step:")
    print(f"{'scene':<17} {'variant':<34} {'us/step':>8} {'vs reference':>13} {'E/disk':>7}  "
          + " ".join(f"{name:>6}" for name in TIMER_SECTIONS) + "  (% of the loop)")
    for scene in SCENES:
        best, rounds = {}, []
        for _ in range(args.repeat):
            rounds.append({})
            for name, (source, counters, timer, integration, environment) in variants.items():
                result = scene_run(build.lmp, source, scene, counters, timer, integration,
                                   environment, args.dt_fraction, args.warmup, args.span, work)
                rounds[-1][name] = result[0]
                if name not in best or result[0] < best[name][0]:
                    best[name] = result
            loops = {"reference": build}
            if args.baseline:
                loops["baseline reference"] = baseline
            for key, loop in loops.items():
                reference = reference_run(loop, scene, args.dt_fraction, args.warmup, args.span)
                rounds[-1][key] = reference[0]
                if key not in best or reference[0] < best[key][0]:
                    best[key] = reference
        base, ref_energy, ref_contacts = best.pop("reference")
        baseline_loop = best.pop("baseline reference", None)
        for name, (us, breakdown, energy) in best.items():
            print(f"{scene:<17} {name:<34} {us:8.3f} {us / base:13.2f} {energy:7.3f}  "
                  + " ".join(f"{breakdown[s]:6.1f}" if breakdown else f"{'-':>6}"
                             for s in TIMER_SECTIONS))
        print(f"{scene:<17} {'reference loop (no counters)':<34} {base:8.3f} {1:13.2f} "
              f"{ref_energy:7.3f}  ({ref_contacts:.1f} contacts per step)")
        if args.baseline:
            old_base = baseline_loop[0]
            print(f"{scene:<17} {'baseline reference loop':<34} {old_base:8.3f} "
                  f"{old_base / base:13.2f} {baseline_loop[1]:7.3f}  (the baseline's own loop)")
            print(f"{scene:<17} baseline against its own loop: counters + outputs "
                  f"{best['baseline, counters + outputs'][0] / old_base:.2f}, counters off "
                  f"{best['baseline, counters off'][0] / old_base:.2f}; baseline / this tree: "
                  f"{best['baseline, counters + outputs'][0] / best['LAMMPS, counters + outputs'][0]:.2f}")
        paired = [f"{name.split(', ', 1)[1]} "
                  + median_and_range(paired_ratios(rounds, name, "reference"), digits=2)
                  for name in ("LAMMPS, counters + outputs", "LAMMPS, counters off",
                               "LAMMPS, memset by vector stores")]
        print(f"{scene:<17} against the reference loop of the same round, median of "
              f"{len(rounds)} (range): " + ", ".join(paired))
        print(f"{scene:<17} goal: counters + outputs at most {GOALS[scene]:g}x the reference "
              "loop: " + against_goal(paired_ratios(rounds, "LAMMPS, counters + outputs",
                                                    "reference"), GOALS[scene]))


def sweep_comparison(build, work):
    """Two short single-disk points: one 2-partition run against two serial runs."""
    config = work / "sweep.toml"
    config.write_text('[defaults]\nrun_time = 40\naverage_start = 10\n'
                      '[[grid]]\nscene = "single_disk"\nkn = [5e4, 5.1e4]\n')
    times = {}
    for mode, extra in (("serial", ["--jobs", "1"]), ("partitions", ["--partitions", "2"])):
        out = work / mode
        start = time.time()
        subprocess.run([sys.executable, "-m", "scripts.sweep", str(config.resolve()),
                        "--output", str(out.resolve()), "--build", str(build.directory.resolve()),
                        *extra], check=True, capture_output=True, env=ENV, cwd=ROOT)
        times[mode] = time.time() - start
    return times


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=4000)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--side", type=int, default=40, help="disks per side of the pile")
    parser.add_argument("--scenes-only", action="store_true",
                        help="only the scenes against the reference loop")
    parser.add_argument("--warmup", type=float, default=30.0,
                        help="time before the scenes' measured span (the deck's transient)")
    parser.add_argument("--span", type=float, default=10.0, help="the scenes' measured time")
    parser.add_argument("--dt-fraction", type=float, default=0.01,
                        help="the scenes' dt in units of tau_c (the decks' default; the paper "
                             "presets use 0.05 and 0.1)")
    parser.add_argument("--baseline", help="another checkout, built, to run the scenes of too")
    parser.add_argument("--build", default="build",
                        help="the build directory of this checkout (and of the baseline's) to "
                             "run: build (Debian 12's LAMMPS), build-2025 or build-2026 (the "
                             "LAMMPS of ./scripts/build.sh --lammps 2025 or 2026)")
    args = parser.parse_args()
    build = Build.of(ROOT, args.build)
    for path in build.programs:
        if not path.exists():
            sys.exit(f"{path} is missing: run ./scripts/build.sh first")
    if args.baseline:
        baseline = Build.of(Path(args.baseline), args.build)
        for path in (baseline.plugin, baseline.reference_loop):
            if not path.exists():
                sys.exit(f"--baseline {args.baseline}: {path} is missing (the baseline "
                         "checkout must be built against the same LAMMPS: its "
                         "./scripts/build.sh)")
    print(f"LAMMPS of {build.directory}")
    with tempfile.TemporaryDirectory() as tmp:
        scene_comparison(args, build, Path(tmp))
    if args.scenes_only:
        return
    dt = law(build)["tau_c"] / 50
    mpirun = shutil.which("mpirun") or "mpirun"
    liggghts = shutil.which("liggghts")
    n = args.side ** 2
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        data = work / "pile.data"
        data_file(data, args.side)
        variants = {
            "gran/hooke/history": ([str(build.lmp)],
                                   lammps_deck(build, data, "hooke", False, args.steps, dt)),
            "gran/mn": ([str(build.lmp)],
                        lammps_deck(build, data, "gran/mn", False, args.steps, dt)),
            "gran/mn + contacts/mn": ([str(build.lmp)],
                                      lammps_deck(build, data, "gran/mn", True, args.steps, dt)),
            "gran/mn, 2 MPI ranks": ([mpirun, "-np", "2", str(build.lmp)],
                                     lammps_deck(build, data, "gran/mn", False, args.steps, dt)),
        }
        if liggghts:
            variants["LIGGGHTS hooke/stiffness"] = ([liggghts],
                                                    liggghts_deck(build, data, args.steps, dt))
        best = {}
        for _ in range(args.repeat):
            for name, (command, deck) in variants.items():
                result = run(command, deck, work)
                if name not in best or result[0] < best[name][0]:
                    best[name] = result
        sweep_times = sweep_comparison(build, work)

    base = best["gran/hooke/history"][0]
    print(f"{n} disks, dense flow, {args.steps} steps of dt = tau_c/50, best of {args.repeat}:")
    print(f"{'variant':<28} {'loop s':>8} {'us/atom-step':>13} {'vs hooke/history':>17} "
          f"{'MB/rank':>8} {'bytes/disk':>11}")
    for name, (loop, memory, _) in best.items():
        print(f"{name:<28} {loop:8.3f} {1e6 * loop / (n * args.steps):13.4f} "
              f"{loop / base:17.3f} {memory:8.2f} {memory * 2**20 / n:11.0f}")
    print(f"counters on / off: {best['gran/mn + contacts/mn'][0] / best['gran/mn'][0]:.3f}")
    print(f"2 ranks / 1 rank (loop time): "
          f"{best['gran/mn, 2 MPI ranks'][0] / best['gran/mn'][0]:.3f}")
    if not liggghts:
        print("LIGGGHTS: not installed (scripts/setup.sh installs it)")
    print(f"sweep of 2 points: 2 partitions {sweep_times['partitions']:.2f} s, "
          f"2 serial runs {sweep_times['serial']:.2f} s, ratio "
          f"{sweep_times['partitions'] / sweep_times['serial']:.3f}")
    print("(memory: LAMMPS's per-rank estimate at the start of the run; LIGGGHTS reports its own)")


if __name__ == "__main__":
    main()
