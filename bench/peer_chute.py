"""LAMMPS's own granular benchmark, bench/in.chute (32000 spheres, a 3D chute on a frozen base),
from the LAMMPS tree the build uses, in four variants side by side
(docs/performance.md):

- as LAMMPS ships it: pair_style gran/hooke/history 200000 NULL 50 NULL 0.5 0;
- with gran/mn at matched stiffness and damping: kn = 2e5 / m per unit mass scale (m = pi/6,
  the spheres' mass: 2M = m between two of them), e from eta_n = 25 (gran/hooke's meff gamma_n
  = m/2 x 50 = 2M x 25), beta = 1 (no tangential damping, as dampflag 0), mu = 0.5,
  coulomb_cutback (gran/hooke/history cuts the shear back), `wall_types 2` for the frozen base
  in place of the base's neigh_modify exclude (its contacts take m_i, as gran/hooke's meff
  with a frozen partner);
- the gran/mn deck without comm_modify vel yes: gran/mn then sends the ghosts' v and omega
  itself (the same forces to the bit);
- with pair_style granular (hooke 2e5 50, tangential linear_history 2/7 x 2e5 0 0.5, damping
  mass_velocity);
- with --baseline-plugin PLUGIN, the gran/mn deck again with another build's plugin (built
  against the same LAMMPS): a change of the plugin against the code before it.

Each variant runs STEPS steps, interleaved (every other round in the reverse order), best of
--repeat: the loop time times LAMMPS's CPU
share, the Pair time, LAMMPS's timer breakdown, memory per rank, and the final kinetic energy
(they simulate the same flow: gran/mn's k_t is (2 k_n - eta_n^2)/7 per unit mass, times
m: 0.08 % below gran/hooke's 2/7 k_n, so their energies agree closely, not exactly).
Then each variant's CPU and Pair time against gran/hooke/history's of the same round, the
median over the rounds with their range: on a machine whose speed drifts (a shared one: its
best-of times can come from rounds of different speed) the paired ratio is the steadier one.
Last, the goals of docs/performance.md for gran/mn (at most 1.0x gran/hooke/history's CPU, at most 0.7x pair
granular's) judged on those paired ratios: met, not met or undecided by a one-sided sign test
(bench/paired.py; 7 rounds of 7, 8 of 9 or 15 of 21 decide).

--variants NAME ... runs those only (e.g. `--variants gran/mn "gran/mn, comm_modify vel no"`:
the ghosts' velocities sent or not by the deck); --replicate NX NY NZ replicates the
read chute (2 2 1: 128000 spheres) before the run.

    python3 -m bench.peer_chute [--steps 400] [--repeat 3] [--build build] [--decks DIR]
                        [--baseline-plugin PLUGIN] [--variants NAME ...] [--replicate NX NY NZ]"""
import argparse
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

from bench.paired import against_goal, median_and_range, paired_ratios
from scripts.granmn_sweep.build_layout import DEFAULT as DEFAULT_BUILD, build_layout
from scripts.granmn_sweep.mn_law import derived

ROOT = Path(__file__).resolve().parent.parent
SECTIONS = ("Pair", "Neigh", "Comm", "Output", "Modify", "Other")
MASS = math.pi / 6           # data.chute: diameter 1, density 1
KN, GAMMA_N, MU = 2e5, 50.0, 0.5
BASELINE = "gran/mn, baseline"    # the variant of --baseline-plugin
# the goals of docs/performance.md for gran/mn's CPU per step, judged on the paired ratios (bench/paired.py)
GOALS = {"gran/hooke/history": 1.0, "granular": 0.7}


def restitution_for(eta_n, kn):
    """e whose eta_n = sqrt(2 kn ln^2 e / (pi^2 + ln^2 e)) is the given one (docs/model.md 3)."""
    ln2 = eta_n ** 2 * math.pi ** 2 / (2 * kn - eta_n ** 2)
    return math.exp(-math.sqrt(ln2))


def gran_mn_style(mn_law):
    """The pair_style line of gran/mn at gran/hooke/history's stiffness and damping."""
    kn_mn = KN / MASS
    e = restitution_for(GAMMA_N / 2, kn_mn)
    # the law's own mapping (mn-law, the header's) gives back eta_n = 25 for that e
    eta_n = derived(mn_law, kn_mn, e, 1.0, "sphere")["eta_n"]
    assert abs(eta_n - GAMMA_N / 2) < 1e-9 * GAMMA_N, eta_n
    return (f"pair_style gran/mn kn {kn_mn!r} e {e!r} beta 1 mu {MU!r} coulomb_cutback "
            "wall_types 2")


def with_command(deck, command, replacement):
    """deck with its one line whose words are those of `command` replaced by the line
    `replacement` ("" drops it). LAMMPS splits a line at any white space, and its trees write
    bench/in.chute with tabs (2021) or spaces (2025 on): lines are matched by their words."""
    lines = deck.splitlines(keepends=True)
    found = [k for k, line in enumerate(lines) if line.split() == command.split()]
    if len(found) != 1:
        sys.exit(f"peer_chute.py: bench/in.chute has {len(found)} lines '{command}' where this "
                 "reads one: not the deck it was written for")
    lines[found[0]] = replacement + "\n" if replacement else ""
    return "".join(lines)


def variants(shipped, mn_style):
    """The decks by variant from LAMMPS's bench/in.chute; mn_style: gran/mn's pair_style line."""
    hooke = "pair_style gran/hooke/history 200000.0 NULL 50.0 NULL 0.5 0"
    exclude = "neigh_modify exclude group bottom bottom"
    ghost_velocity = "comm_modify vel yes"
    with_mn = with_command(with_command(shipped, hooke, mn_style), exclude, "")
    granular = with_command(with_command(shipped, hooke, "pair_style granular"), "pair_coeff * *",
                            f"pair_coeff * * hooke {KN!r} {GAMMA_N!r} tangential linear_history "
                            f"{2 / 7 * KN!r} 0 {MU!r} damping mass_velocity")
    return {"gran/hooke/history": shipped,
            "gran/mn": with_mn,
            "gran/mn, comm_modify vel no": with_command(with_mn, ghost_velocity, ""),
            "granular": granular}


def deck_text(plugin, deck, steps, replicate=None):
    """A variant's deck as run: the plugin loaded, the chute replicated (NX, NY, NZ; None: as
    read), `steps` steps, thermo at the last."""
    text = with_command(with_command(deck, "run 100", f"run {steps}"), "thermo 100",
                        f"thermo {steps}")
    if replicate:
        text = with_command(text, "read_data data.chute", "read_data data.chute\nreplicate " +
                            " ".join(str(n) for n in replicate))
    return f"plugin load {plugin}\n" + text


def run(lmp, plugin, deck, steps, work, replicate=None):
    (work / "in.bench").write_text(deck_text(plugin, deck, steps, replicate))
    proc = subprocess.run([str(lmp), "-in", "in.bench", "-log", "log.bench", "-nocite"],
                          cwd=work, capture_output=True, text=True, errors="replace")
    if proc.returncode != 0:
        raise RuntimeError(f"lmp failed:\n{proc.stdout[-2000:]}{proc.stderr[-2000:]}")
    out = proc.stdout
    loop = float(re.search(r"Loop time of (\S+)", out).group(1))
    share = float(re.search(r"([\d.]+)% CPU use", out).group(1)) / 100
    sections = {name: float(re.search(rf"^{name}\s*\|.*\|\s*(\S+)\s*$", out, re.M).group(1))
                for name in SECTIONS}
    memory = float(re.search(r"memory allocation.*= \S+ \| (\S+) \| \S+ Mbytes", out).group(1))
    thermo = re.findall(rf"^\s*{steps}\s+\d+\s+(\S+)\s+(\S+)", out, re.M)
    return {"cpu": loop * share, "pair": loop * share * sections["Pair"] / 100,
            "sections": sections, "memory": memory, "ke": float(thermo[-1][0])}


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--steps", type=int, default=400)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--build", type=Path, default=DEFAULT_BUILD)
    parser.add_argument("--baseline-plugin", type=Path, metavar="PLUGIN",
                        help="also the gran/mn deck with this granmnplugin.so (another build "
                             "of the plugin against the same LAMMPS), paired with gran/mn")
    parser.add_argument("--decks", type=Path, metavar="DIR",
                        help="write the decks (in.<variant>, STEPS steps) and data.chute "
                             "into DIR and run nothing: for callgrind (docs/performance.md)")
    parser.add_argument("--variants", nargs="+", metavar="NAME",
                        help="run these variants only (default: all; the first is the "
                             "reference of the ratios where gran/hooke/history is not run)")
    parser.add_argument("--replicate", type=int, nargs=3, metavar=("NX", "NY", "NZ"),
                        help="replicate the chute before the run (2 2 1: 128000 spheres)")
    args = parser.parse_args()
    paths = build_layout(args.build.resolve())
    build, lmp, plugin = paths.directory, paths.lammps, paths.plugin
    cache = (build / "CMakeCache.txt").read_text()
    tree = Path(re.search(r"^LAMMPS_SOURCE_DIR:PATH=(.*)$", cache, re.M).group(1))
    version = re.search(r'LAMMPS_VERSION "(.*)"', (tree / "src" / "version.h").read_text())
    print(f"LAMMPS {version.group(1)} ({tree}); {args.steps} steps" +
          ("" if args.decks else f", best of {args.repeat}; load average "
                                 f"{os.getloadavg()[0]:.2f} at the start"))
    decks = variants((tree / "bench" / "in.chute").read_text(),
                     gran_mn_style(paths.mn_law))
    if args.variants:
        unknown = [name for name in args.variants if name not in decks]
        if unknown:
            sys.exit(f"peer_chute.py: --variants {', '.join(map(repr, unknown))}: not a variant "
                     f"({', '.join(map(repr, decks))})")
        decks = {name: decks[name] for name in args.variants}
    plugins = {name: plugin for name in decks}
    if args.baseline_plugin:
        if not args.baseline_plugin.is_file():
            sys.exit(f"--baseline-plugin {args.baseline_plugin}: no such file")
        decks[BASELINE] = decks["gran/mn"]
        plugins[BASELINE] = args.baseline_plugin.resolve()
    if args.decks:
        args.decks.mkdir(parents=True, exist_ok=True)
        shutil.copy(tree / "bench" / "data.chute", args.decks)
        for name, deck in decks.items():
            (args.decks / f"in.{re.sub(r'[/, ]+', '_', name)}").write_text(
                deck_text(plugins[name], deck, args.steps, args.replicate))
        print(f"decks: {', '.join(sorted(p.name for p in args.decks.glob('in.*')))} in "
              f"{args.decks}")
        return 0
    best, rounds = {}, []
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        shutil.copy(tree / "bench" / "data.chute", work)
        for round_number in range(args.repeat):
            rounds.append({})
            # every other round in the reverse order: a variant's place in the round (the one
            # run after another, with its files cached) weighs on no ratio one way only
            order = list(decks.items())
            for name, deck in order[::-1] if round_number % 2 else order:
                try:
                    result = run(lmp, plugins[name], deck, args.steps, work, args.replicate)
                except RuntimeError as error:
                    if name == "granular":    # an older LAMMPS's pair granular takes other words
                        print(f"{name}: {str(error).splitlines()[-1]}", file=sys.stderr)
                        continue
                    # e.g. a --baseline-plugin built against another LAMMPS: lmp's words
                    sys.exit(f"peer_chute.py: the {name} variant ({plugins[name]}): {error}")
                rounds[-1][name] = result
                if name not in best or result["cpu"] < best[name]["cpu"]:
                    best[name] = result
    first = "gran/hooke/history" if "gran/hooke/history" in best else next(iter(best))
    reference = best[first]
    short = "/hooke" if first == "gran/hooke/history" else "/first"
    print(f"{'variant':<28} {'CPU s':>8} {short:>7} {'Pair s':>8} {short:>7} "
          f"{'MB/rank':>8} {'KE':>14}  " + " ".join(f"{s:>6}" for s in SECTIONS) + "  (% loop)")
    for name, r in best.items():
        print(f"{name:<28} {r['cpu']:8.3f} {r['cpu'] / reference['cpu']:7.3f} {r['pair']:8.3f} "
              f"{r['pair'] / reference['pair']:7.3f} {r['memory']:8.2f} {r['ke']:14.8g}  " +
              " ".join(f"{r['sections'][s]:6.1f}" for s in SECTIONS))
    if "granular" in best and "gran/mn" in best:
        print(f"gran/mn / granular: CPU {best['gran/mn']['cpu'] / best['granular']['cpu']:.3f}")
    print(f"paired with {first} in each of the {len(rounds)} rounds: median (min-max)")
    pairs = [(name, first) for name in best if name != first]
    for name, against in (("gran/mn, comm_modify vel no", "gran/mn"), ("gran/mn", BASELINE),
                          ("gran/mn", "granular")):
        if name in best and against in best and (name, against) not in pairs:
            pairs.append((name, against))
    for name, against in pairs:
        label = name if against == first else f"{name} / {against}"
        print(f"{label:<38}" + "".join(
            f" {key} " + median_and_range(paired_ratios(rounds, name, against,
                                                        lambda result: result[field]))
            for key, field in (("CPU", "cpu"), ("Pair", "pair"))))
    for against, goal in GOALS.items():
        if against in best and "gran/mn" in best:
            cpu = paired_ratios(rounds, "gran/mn", against, lambda result: result["cpu"])
            print(f"goal: gran/mn's CPU at most {goal:g}x {against}'s: "
                  f"{against_goal(cpu, goal)}")
    print(f"load average {os.getloadavg()[0]:.2f} at the end")
    return 0


if __name__ == "__main__":
    sys.exit(main())
