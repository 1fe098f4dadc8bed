#!/usr/bin/python3
"""Cost of fix contacts/mn: the same dense flow run with and without it, side by side.

Usage: bench/counter_overhead.py [--repeat 3] [--steps 4000]  (after ./scripts/build.sh)
Prints the loop time of each variant and the ratio."""
import argparse
import os
import re
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
LMP = ROOT / "build" / "lammps" / "lmp"
PLUGIN = ROOT / "build" / "plugin" / "granmnplugin.so"

DECK = """
plugin load {plugin}
units lj
dimension 2
atom_style sphere
boundary p p p
comm_modify vel yes
neighbor 0.1 bin
region box block 0 40 -1 60 -0.5 0.5
create_box 1 box
lattice sq 1.0 origin 0.5 0.5 0
region pile block 0 40 0 40 -0.5 0.5 units lattice
create_atoms 1 region pile
lattice none 1.0
variable diameter atom "0.8 + 0.2*((id*7919)%100)/100"
set type 1 diameter v_diameter
set type 1 density/disc 1.2732395447351628
velocity all create 0.5 4928459 loop geom
pair_style gran/mn kn 2e5 e 0.7 beta 0.7 mu 0.5
pair_coeff * *
timestep $(v_mn_tau_c/50)
fix integrate all nve/sphere disc
fix flat all enforce2d
fix gravity all gravity 1.0 vector 0.3 -1 0
fix floor all wall/gran/mn yplane 0.0 NULL
{counters}
thermo 1000
run {steps}
"""


def loop_time(counters, steps):
    with tempfile.TemporaryDirectory() as work:
        deck = DECK.format(plugin=PLUGIN, steps=steps,
                           counters="fix c all contacts/mn local 100" if counters else "")
        Path(work, "in.bench").write_text(deck)
        out = subprocess.run([str(LMP), "-in", "in.bench", "-log", "none"], cwd=work,
                             capture_output=True, text=True, check=True).stdout
    return float(re.search(r"Loop time of (\S+)", out).group(1))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--steps", type=int, default=4000)
    args = parser.parse_args()
    os.environ.setdefault("OMPI_ALLOW_RUN_AS_ROOT", "1")
    os.environ.setdefault("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
    off, on = [], []
    for _ in range(args.repeat):    # interleaved, so that drifts in machine load hit both
        off.append(loop_time(False, args.steps))
        on.append(loop_time(True, args.steps))
    print(f"1600 disks, {args.steps} steps, best of {args.repeat}:")
    print(f"  counters off: {min(off):.3f} s")
    print(f"  counters on:  {min(on):.3f} s")
    print(f"  overhead:     {100 * (min(on) / min(off) - 1):+.1f} %")


if __name__ == "__main__":
    sys.exit(main())
