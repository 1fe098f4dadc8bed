"""The event-driven engine's cost (after ./scripts/build.sh; docs/hard_spheres.md "What it
costs"):

    python3 -m bench.event_driven [--widths 5 50 500 5000 10000] [--events-per-disk 20]
                          [--kn 1.28e7 3.2768e9] [--soft-span 20] [--workdir DIR]

1. Cost per event against the number of disks: the frictional flow's deck at width W (10 W
   disks in ten rows, inputs/frictional_flow.lmp) writes its start (-var write_start yes), and
   mn-event-driven runs it for --events-per-disk events a disk, at least 2e5 (rule (b), the TC
   model at t_c = tau_c(1.28e7)): the rows fall onto the floor and each other, the pile forms and
   flows. Printed per size: events, the
   engine's CPU seconds (its own clock, the start's reading excluded), microseconds per event.
   An O(log N) event queue gives a cost per event that grows by a constant step per decade of N
   (the cells keep the neighbour searches O(1)); a list searched linearly would grow 10x.
2. Soft against hard, side by side: the collisional flow (50 disks on 50 bumps, seed 101) for
   --soft-span time units, the soft run at each k_n of --kn as the committed soft series runs it
   (velocity Verlet at dt = tau_c/10: inputs/sweeps/confirm_collisional.toml; LAMMPS's loop
   time) and the event-driven run from the same start under rule (b) with t_c = tau_c(k_n)
   (the engine's CPU seconds, its setup included), one after the other on the same core.
   Printed: both CPU seconds and their ratio.
3. The bouncing ball: a unit disk dropped from 1.3 above a flat floor (rule (a), collapse =
   stop) comes to rest at t_0 + 2 e_w v_0 / (g (1 - e_w)) (t_0, v_0: its first impact); printed
   per e_w: the engine's collapse time (the collapse is detected when a bounce interval falls
   below collapse_time / collapse_count), the closed form, their relative difference and the
   bounces.
"""
import argparse
import math
import re
import subprocess
import sys
import tempfile
from pathlib import Path

from scripts.granmn_sweep.build_layout import build_layout
from scripts.granmn_sweep.event_driven import START, START_DUMP, START_FLOOR, write_start

ROOT = Path(__file__).resolve().parents[1]

BUILD = build_layout()
LMP, PLUGIN, ENGINE = BUILD.lammps, BUILD.plugin, BUILD.event_driven


def lammps(scene, out, variables):
    """Runs a scene deck with -var NAME VALUE; LAMMPS's loop time summed over its runs."""
    out.mkdir(parents=True, exist_ok=True)
    command = [str(LMP), "-in", str(ROOT / "inputs" / f"{scene}.lmp"), "-log",
               str(out / "log.lammps"), "-screen", "none", "-nocite"]
    for name, value in {"plugin": PLUGIN, "lib": ROOT / "inputs" / "lib", "out": out,
                        **variables}.items():
        command += ["-var", name, str(value)]
    subprocess.run(command, check=True)
    log = (out / "log.lammps").read_text()
    return sum(float(t) for t in re.findall(r"^Loop time of (\S+)", log, re.M))


def start_of(scene, out, variables):
    """The deck's start as the engine reads it (the sweep runner's way: event_driven.py); the
    box."""
    lammps(scene, out, {**variables, "write_start": "yes"})
    return write_start(out / START_DUMP, out / START_FLOOR, out / START)


def engine(out, parameters):
    """mn-event-driven on out's start: its summary.txt as a dict."""
    done = subprocess.run([str(ENGINE), f"start={out / START}", f"out={out}", *parameters],
                          capture_output=True, text=True)
    if done.returncode not in (0, 3):
        raise SystemExit(done.stderr)
    return {k: v for k, v in (line.split() for line in (out / "summary.txt").read_text().splitlines())}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--widths", type=int, nargs="+", default=[5, 50, 500, 5000, 10000])
    parser.add_argument("--events-per-disk", type=int, default=20)
    parser.add_argument("--kn", type=float, nargs="+", default=[1.28e7, 3.2768e9])
    parser.add_argument("--soft-span", type=float, default=20.0)
    parser.add_argument("--workdir", type=Path)
    args = parser.parse_args()
    work = args.workdir or Path(tempfile.mkdtemp(prefix="bench_event_driven_"))
    print(f"# python3 -m bench.event_driven {' '.join(sys.argv[1:])} (work in {work})")
    print("# 1. frictional flow, rule (b), TC at t_c = tau_c(1.28e7), "
          f"{args.events_per_disk} events a disk (at least 2e5)\n"
          "# disks events end time cpu_seconds us_per_event")
    for width in args.widths:
        out = work / f"width{width}"
        start_of("frictional_flow", out, {"width": width, "seed": 101})
        s = engine(out, ["scene=frictional_flow", "rule=soft", "collapse=tc", "tc_time=tau_c",
                         "kn=1.28e7", "sin_theta=0.2", "run_time=1e6",
                         f"events={max(200000, 10 * width * args.events_per_disk)}"])
        events, cpu = int(s["events"]), float(s["cpu_seconds"])
        print(f"{10 * width} {events} {s['end']} {float(s['time']):.4g} {cpu:.3f} "
              f"{1e6 * cpu / events:.3f}", flush=True)
    print(f"# 2. collisional flow, seed 101, run_time {args.soft_span:g}: soft (Verlet, dt = "
          "tau_c/10) against event-driven (rule (b), TC at t_c = tau_c(k_n))\n"
          "# kn soft_cpu_seconds hard_cpu_seconds hard_events ratio")
    for kn in args.kn:
        soft = lammps("collisional_flow", work / f"soft{kn:g}",
                      {"kn": kn, "seed": 101, "integrator": "verlet", "dt_fraction": 0.1,
                       "dt_cap": 1, "run_time": args.soft_span, "average_start": 0,
                       "newton": "off"})
        out = work / f"hard{kn:g}"
        start_of("collisional_flow", out, {"seed": 101})
        s = engine(out, ["scene=collisional_flow", "rule=soft", "collapse=tc", "tc_time=tau_c",
                         f"kn={kn!r}", "sin_theta=0.45", f"run_time={args.soft_span!r}"])
        hard = float(s["setup_cpu_seconds"]) + float(s["cpu_seconds"])
        print(f"{kn:g} {soft:.3f} {hard:.3f} {s['events']} {soft / hard:.1f}", flush=True)
    print("# 3. bouncing ball from 1.3 above the floor, rule (a)\n"
          "# e_w collapse_time closed_form relative_difference bounces")
    height = 1.3
    t0, v0 = math.sqrt(2 * height), math.sqrt(2 * height)
    for e_w in (0.5, 0.7777, 0.9, 0.99):
        out = work / f"ball{e_w:g}"
        out.mkdir(parents=True, exist_ok=True)
        (out / START).write_text(f"box -3 3\nfloor 0\ndisk 0 {0.5 + height!r} 0 0 0 1\n")
        s = engine(out, ["scene=bouncing_ball", "rule=paper", f"e_w={e_w!r}", "run_time=1e4"])
        rest = t0 + 2 * e_w * v0 / (1 - e_w)
        print(f"{e_w:g} {float(s['time']):.15g} {rest:.15g} "
              f"{abs(float(s['time']) - rest) / rest:.2g} {s['boundary_collisions']}", flush=True)


if __name__ == "__main__":
    main()
