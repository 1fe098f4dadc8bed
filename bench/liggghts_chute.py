"""LIGGGHTS 3.8's `model mn tangential mn` against LIGGGHTS's own linear model, `model
hooke/stiffness tangential history` at the law's stiffness and damping, on the project's 3D
chute, both in the project's LIGGGHTS build (plugin/liggghts: both combinations compiled in,
specialised; docs/performance.md, docs/liggghts.md):

- the scene: inputs/lib/chute_3d_start.lmp, the start of inputs/liggghts/chute_3d.lmp (500
  spheres of diameters 0.9-1.1 and mass d^3 from rest on a rough base of 100 spheres frozen by
  fix freeze), sin(theta) = 0.40, STEPS steps of dt = DT_FRACTION tau_c (k_n = 2e5, tau_c =
  0.005; DT_FRACTION 0.05 by default, as the chute's short tests run it, without the decks'
  dt_cap of 1e-4): 40000 steps are 10 time units, in which the spheres land on the base
  within 2 and then flow densely, with about 2600 neighbour pairs at the end (at the decks'
  default, dt_fraction 0.01, 40000 steps are 2 time units, mostly of free fall), no outputs
  and no counters (the chute deck's own are left out: LIGGGHTS's linear model has none);
- mn: k_n = 2e5, e = beta = 0.7, mu = 0.5 (the chute deck's defaults);
- hooke/stiffness: absolute kn = k_n, kt, gamman = eta_n and gammat = eta_t of the same law
  (bench/equivalent_laws.py): the two laws agree for a contact of mass scale 1, the spheres'
  typical 2M; with masses of 0.73-1.33 the flows differ somewhat, the work per contact not;
- with --baseline LIGGGHTS, the mn deck again run by another build's LIGGGHTS: the models
  against the code before a change.

Each round runs every variant once (the order turned round each round), and records the CPU
time of the process (user + system), LIGGGHTS's Pair and Neigh times (the share of the loop
time, times the CPU), the neighbour pairs at the end (LIGGGHTS's "Total # of neighbors") and
the kinetic energy at the end. Then mn's ratios to hooke/stiffness of the same round, median and
range, and the goal of docs/performance.md (mn's CPU at most 1.1x hooke/stiffness's) judged on those by the
sign test of bench/paired.py (15 rounds of 21 decide).

    python3 -m bench.liggghts_chute [--steps 40000] [--dt-fraction 0.05] [--rounds 21] [--build build]
                            [--baseline LIGGGHTS]"""
import argparse
import os
import re
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from bench.equivalent_laws import liggghts_contacts
from bench.paired import against_goal, median_and_range, paired_ratios
from scripts.granmn_sweep.build_layout import DEFAULT as DEFAULT_BUILD, build_layout
from scripts.granmn_sweep.mn_law import derived

ROOT = Path(__file__).resolve().parent.parent
KN, E, BETA, MU = 2e5, 0.7, 0.7, 0.5
SIN_THETA = 0.40
GOAL = 1.1    # docs/performance.md's goal: mn's CPU at most this many times hooke/stiffness's
MN, HOOKE, BASELINE = "mn", "hooke/stiffness", "mn, baseline"
SECTIONS = ("Pair", "Neigh")


def mn_contacts():
    """The law for both atom types (the chute deck's lines, at its defaults)."""
    table = lambda value: "2 " + " ".join([repr(value)] * 4)
    return f"""
fix law_kn all property/global normalStiffnessPerMass peratomtypepair {table(KN)}
fix law_e all property/global coefficientRestitution peratomtypepair {table(E)}
fix law_beta all property/global coefficientTangentialRestitution peratomtypepair {table(BETA)}
fix law_mu all property/global coefficientFriction peratomtypepair {table(MU)}
pair_style gran model mn tangential mn
pair_coeff * *
"""


def deck(contacts, dt, steps):
    """The chute's start, the contact model's lines, the chute's dynamics, `steps` steps."""
    cos_theta = (1 - SIN_THETA ** 2) ** 0.5
    return f"""units lj
dimension 3
atom_style granular
atom_modify map array
boundary p p fm
newton off
communicate single vel yes
neighbor 0.2 bin
neigh_modify delay 0 every 1 check yes
variable length index 10
variable width index 10
variable base_rough index 0.5
variable spheres index 500
variable seed index 2003
include {ROOT / "inputs" / "lib" / "chute_3d_start.lmp"}
{contacts}
fix base bumps freeze
fix gravity mobile gravity 1.0 vector {SIN_THETA!r} 0 {-cos_theta!r}
fix integrate mobile nve/sphere
timestep {dt!r}
thermo_style custom step atoms ke
thermo {steps}
run {steps}
"""


def run(liggghts, text, steps, work):
    """One run: CPU s of the process, Pair and Neigh CPU s, neighbour pairs, KE at the end."""
    (work / "in.bench").write_text(text)
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    proc = subprocess.run([str(liggghts), "-in", "in.bench", "-log", "none", "-echo", "none"],
                          cwd=work, capture_output=True, text=True, errors="replace")
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if proc.returncode != 0 or "Loop time of" not in proc.stdout:
        raise RuntimeError(f"{liggghts} failed:\n{proc.stdout[-2000:]}{proc.stderr[-2000:]}")
    out = proc.stdout
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    # LIGGGHTS 3.8 prints "Pair  time (%) = 1.19 (42.3)": the section's share of the loop
    shares = {name: float(re.search(rf"^{name}\s+time \(%\) = \S+ \((\S+)\)", out, re.M).group(1))
              for name in SECTIONS}
    neighbors = int(float(re.search(r"Total # of neighbors = (\S+)", out).group(1)))
    ke = float(re.findall(rf"^\s*{steps}\s+\d+\s+(\S+)", out, re.M)[-1])
    return {"cpu": cpu, **{name.lower(): cpu * shares[name] / 100 for name in SECTIONS},
            "neighbors": neighbors, "ke": ke}


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--steps", type=int, default=40000)
    parser.add_argument("--dt-fraction", type=float, default=0.05,
                        help="dt in units of tau_c (the chute deck's default: 0.01, and "
                             "at most 1e-4)")
    parser.add_argument("--rounds", type=int, default=21)
    parser.add_argument("--build", type=Path, default=DEFAULT_BUILD)
    parser.add_argument("--baseline", type=Path, metavar="LIGGGHTS",
                        help="also the mn deck run by this LIGGGHTS executable (another build of "
                             "the project's), paired with mn")
    args = parser.parse_args()
    paths = build_layout(args.build.resolve())
    liggghts = paths.liggghts
    if not liggghts.exists():
        sys.exit(f"{liggghts} is missing: run ./scripts/build.sh first")
    law = derived(paths.mn_law, KN, E, BETA, "sphere")
    dt = args.dt_fraction * law["tau_c"]
    variants = {HOOKE: (liggghts, deck(liggghts_contacts(law, KN, MU, types=2), dt, args.steps)),
                MN: (liggghts, deck(mn_contacts(), dt, args.steps))}
    if args.baseline:
        if not args.baseline.is_file():
            sys.exit(f"--baseline {args.baseline}: no such file")
        variants[BASELINE] = (args.baseline.resolve(), variants[MN][1])
    load = os.getloadavg()
    print(f"LIGGGHTS {liggghts}; the 3D chute's start, {args.steps} steps of dt = {dt:.6g}, "
          f"{args.rounds} rounds; load average at the start {load[0]:.2f} {load[1]:.2f} "
          f"{load[2]:.2f}")
    start = time.time()
    rounds = []
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        names = list(variants)
        for k in range(args.rounds):
            rounds.append({})
            for name in (names if k % 2 == 0 else names[::-1]):
                command, text = variants[name]
                rounds[-1][name] = run(command, text, args.steps, work)
    load = os.getloadavg()
    print(f"{time.time() - start:.1f} s of wall time; load average at the end {load[0]:.2f} "
          f"{load[1]:.2f} {load[2]:.2f}")
    best = {name: min((r[name] for r in rounds), key=lambda result: result["cpu"])
            for name in variants}
    print(f"{'variant':<18} {'CPU s':>7} {'Pair s':>7} {'Neigh s':>7} {'neighbours':>10} "
          f"{'KE':>12}  (best of {args.rounds} by CPU)")
    for name, r in best.items():
        print(f"{name:<18} {r['cpu']:7.3f} {r['pair']:7.3f} {r['neigh']:7.3f} "
              f"{r['neighbors']:10d} {r['ke']:12.6g}")
    print(f"paired with {HOOKE} in each of the {len(rounds)} rounds: median (min-max)")
    pairs = [(MN, HOOKE)] + ([(BASELINE, HOOKE), (MN, BASELINE)] if args.baseline else [])
    # (a run too short for the spheres to move by half the skin builds no list after setup)
    fields = [(key, key.lower()) for key in ("CPU",) + SECTIONS
              if all(r[name][key.lower()] > 0 for r in rounds for name in variants)]
    for name, against in pairs:
        print(f"{name + ' / ' + against:<32}" + "".join(
            f" {key} " + median_and_range(paired_ratios(rounds, name, against,
                                                        lambda result: result[field]))
            for key, field in fields))
    cpu = paired_ratios(rounds, MN, HOOKE, lambda result: result["cpu"])
    print(f"goal: mn's CPU at most {GOAL:g}x {HOOKE}'s: {against_goal(cpu, GOAL)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
