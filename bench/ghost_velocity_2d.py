"""The ghosts' velocities in 2D on one rank (docs/performance.md): the frictional
scene (inputs/frictional_flow.lmp, 100 disks) as committed, where pair gran/mn sends the ghosts'
vx, vy and omega_z itself (no comm_modify vel yes), against the same deck from a copy of inputs/
whose inputs/lib/begin.lmp adds `comm_modify vel yes` (LAMMPS's own: x, v and omega, three
values each). Interleaved, every other round in the reverse order; each run's CPU (LAMMPS's
loop times their CPU share), the paired ratio own / LAMMPS's with its median and range
(bench/paired.py), whether the two energy.txt are the same to the byte, and the load average.

    python3 -m bench.ghost_velocity_2d [--build build] [--rounds 7] [--run-time 60]"""
import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

from bench.paired import median_and_range, paired_ratios
from scripts.granmn_sweep.build_layout import DEFAULT as DEFAULT_BUILD, build_layout

ROOT = Path(__file__).resolve().parent.parent
OWN, LAMMPS = "pair's own (vel no)", "LAMMPS's own (vel yes)"


def run(build, inputs, run_time, work):
    """(CPU seconds of the run's loops, energy.txt) of the frictional scene from `inputs`."""
    paths = build_layout(build)
    out = subprocess.run([str(paths.lammps), "-in",
                          str(inputs / "frictional_flow.lmp"), "-log", "none", "-nocite",
                          "-var", "plugin", str(paths.plugin),
                          "-var", "lib", str(inputs / "lib"), "-var", "out", str(work),
                          "-var", "run_time", str(run_time), "-var", "average_start", "0"],
                         capture_output=True, text=True, errors="replace")
    if out.returncode != 0:
        sys.exit(f"ghost_velocity_2d.py: lmp failed:\n{out.stdout[-2000:]}{out.stderr[-2000:]}")
    cpu = 0.0
    for chunk in out.stdout.split("Loop time of ")[1:]:
        share = re.search(r"([\d.]+)% CPU use", chunk)
        cpu += float(chunk.split()[0]) * float(share.group(1)) / 100
    return cpu, (work / "energy.txt").read_text()


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", type=Path, default=DEFAULT_BUILD)
    parser.add_argument("--rounds", type=int, default=7)
    parser.add_argument("--run-time", type=float, default=60.0)
    args = parser.parse_args()
    build = args.build.resolve()
    print(f"frictional scene, run_time {args.run_time:g}, {args.rounds} rounds, one rank; load "
          f"average {os.getloadavg()[0]:.2f} at the start", flush=True)
    rounds, same = [], True
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        with_vel = tmp / "inputs"
        shutil.copytree(ROOT / "inputs", with_vel)
        begin = with_vel / "lib" / "begin.lmp"
        text = begin.read_text()
        if text.count("\nnewton ${newton}\n") != 1:
            sys.exit("ghost_velocity_2d.py: inputs/lib/begin.lmp has no one line "
                     "'newton ${newton}' to add comm_modify vel yes after")
        begin.write_text(text.replace("\nnewton ${newton}\n",
                                      "\nnewton ${newton}\ncomm_modify vel yes\n"))
        variants = [(OWN, ROOT / "inputs"), (LAMMPS, with_vel)]
        for number in range(args.rounds):
            rounds.append({})
            energies = {}
            for name, inputs in variants[::-1] if number % 2 else variants:
                work = tmp / "work"
                work.mkdir()
                rounds[-1][name], energies[name] = run(build, inputs, args.run_time, work)
                shutil.rmtree(work)
            same = same and energies[OWN] == energies[LAMMPS]
            print(f"round {number + 1}: " + ", ".join(f"{name} {rounds[-1][name]:.3f} s"
                                                      for name, _ in variants), flush=True)
    ratios = paired_ratios(rounds, OWN, LAMMPS)
    print(f"{OWN} / {LAMMPS}, paired: CPU {median_and_range(ratios)}; energy.txt the same to "
          f"the byte in every round: {same}; load average {os.getloadavg()[0]:.2f} at the end")
    return 0


if __name__ == "__main__":
    sys.exit(main())
