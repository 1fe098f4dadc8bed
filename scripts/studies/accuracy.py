"""What accuracy costs: dt/tau_c x integrator against the error of each observable and the
wall time per unit of simulated time.

    python3 -m scripts.studies.accuracy [--output results/accuracy] [--quick] [--build build]

For dt/tau_c in {1/10, 1/20, 1/50, 1/100, 1/200} and both integrators it measures: the
restitution e of a binary collision (against the requested e), the bouncing ball's bounce count,
the single disk's E and N_w, the collisional flow's E and N_c (against the finest run of the
same integrator, with the statistical errors of both); and the cost of each point. It writes
accuracy.md (tables, the cheapest dt and integrator per observable whose error stays inside the
statistical error, the speed-up over the paper's tau_c/100, the cost's exponent in kn) and
accuracy.png (error against cost). Resumable: the scene runs go through the sweep runner
(python3 -m scripts.sweep)."""
import argparse
import json
import os
import re
import subprocess
import sys
from pathlib import Path

import numpy as np

from postprocess.study import analyse, fit_power
from scripts.granmn_sweep import SweepError
from scripts.granmn_sweep.build_layout import DEFAULT as DEFAULT_BUILD, build_layout
from scripts.granmn_sweep.points import check_output

ROOT = Path(__file__).resolve().parents[2]

FRACTIONS = [0.1, 0.05, 0.02, 0.01, 0.005]
INTEGRATORS = ["verlet", "ab2"]
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
SCENES = {    # scene: (kn, run_time, average_start)
    "single_disk": (5e4, 150, 50),
    "collisional_flow": (1.25e4, 400, 100),
}


def lmp(build, deck, variables):
    paths = build_layout(build)
    command = [str(paths.lammps), "-in", str(ROOT / "inputs" / deck), "-log", "none",
               "-var", "plugin", str(paths.plugin)]
    for name, value in variables.items():
        command += ["-var", name, str(value)]
    out = subprocess.run(command, capture_output=True, text=True, env=ENV)
    if out.returncode != 0:
        raise RuntimeError(f"{deck} {variables}: {out.stdout[-1500:]}")
    return out.stdout


def deterministic(build):
    """e of a binary collision and the bouncing ball's bounces, per integrator and fraction."""
    rows = {}
    for integrator in INTEGRATORS:
        for fraction in FRACTIONS:
            out = lmp(build, "two_disk_collision.lmp",
                      dict(dt_fraction=fraction, integrator=integrator))
            e = float(re.search(r"measured e = (\S+)", out).group(1))
            out = lmp(build, "bouncing_ball.lmp",
                      dict(dt_fraction=fraction / 1.41,    # dt ~ tau_c fraction
                           integrator=integrator, kn=2e5))
            bounces = float(re.search(r"bounces (\S+)", out).group(1))
            rows[integrator, fraction] = dict(e=e, bounces=bounces)
            print(f"  {integrator} dt = tau_c*{fraction}: e = {e:.5f}, bounces {bounces:.0f}",
                  flush=True)
    return rows


def scene_sweep(build, output, quick):
    config = output / "scenes.toml"
    lines = ['name = "accuracy"', "[defaults]", "dt_cap = 1.0"]
    for scene, (kn, run_time, average_start) in SCENES.items():
        if quick:
            run_time, average_start = run_time // 3, average_start // 3
        lines += ["[[grid]]", f'scene = "{scene}"', f"kn = {kn}", f"run_time = {run_time}",
                  f"average_start = {average_start}",
                  f"dt_fraction = {FRACTIONS}", f"integrator = {json.dumps(INTEGRATORS)}"]
    # the cost's growth with kn: the single disk at the paper's tau_c/100
    lines += ["[[grid]]", 'scene = "single_disk"', "kn = [2e5, 8e5, 3.2e6]",
              f"run_time = {50 if quick else 150}", f"average_start = {15 if quick else 50}",
              "dt_fraction = 0.01", 'integrator = "verlet"']
    config.write_text("\n".join(lines) + "\n")
    subprocess.run([sys.executable, "-m", "scripts.sweep", str(config.resolve()),
                    "--output", str((output / "runs").resolve()), "--build", str(build.resolve())],
                   check=True, env=ENV, cwd=ROOT)
    scenes, left_out, _, _ = analyse(output / "runs")
    for point, reason in left_out:
        print(f"left out {point}: {reason}")
    return scenes


def cost_per_time(o):
    """LAMMPS's loop time (start-up excluded) per unit of simulated time."""
    log = (o["point"] / "log.lammps").read_text()
    seconds = sum(float(t) for t in re.findall(r"Loop time of (\S+)", log))
    return seconds / o["variables"]["run_time"]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--output", type=Path, default=ROOT / "results" / "accuracy")
    parser.add_argument("--quick", action="store_true", help="a third of the spans")
    parser.add_argument("--build", type=Path, default=DEFAULT_BUILD,
                        help="the build whose lmp and plugin run (build-2026/ for LAMMPS 2026)")
    args = parser.parse_args()
    try:
        check_output(args.output)
        args.output.mkdir(parents=True, exist_ok=True)
    except SweepError as error:
        print(f"accuracy: {error}", file=sys.stderr)
        return 2
    except OSError as error:    # not writable
        print(f"accuracy: --output {args.output}: {error.strerror}", file=sys.stderr)
        return 2
    print("binary collision and bouncing ball:")
    det = deterministic(args.build)
    print("scenes:")
    scenes = scene_sweep(args.build, args.output, args.quick)

    md = ["# What accuracy costs", "",
          "Written by `python3 -m scripts.studies.accuracy`. Errors: e against the requested 0.7; bounces, E, N_w, "
          "N_c against the finest run (dt = tau_c/200) of the same integrator; ± is the "
          "statistical error of the difference (block errors of both runs).", "",
          "## Binary collision and bouncing ball (kn = 2e5)", "",
          "| integrator | dt/tau_c | e | e error | bounces | bounce error |", "|---|---|---|---|---|---|"]
    for (integrator, fraction), r in det.items():
        finest = det[integrator, FRACTIONS[-1]]["bounces"]
        md.append(f"| {integrator} | 1/{1 / fraction:.0f} | {r['e']:.5f} | {r['e'] - 0.7:+.5f} | "
                  f"{r['bounces']:.0f} | {r['bounces'] - finest:+.0f} |")
    points = []    # (observable, integrator, fraction, error, statistical error, cost)
    for scene, (kn, _, _) in SCENES.items():
        rows = [o for o in scenes.get(scene, []) if o["kn"] == kn]
        quantities = ("E_total", "N_w") if scene == "single_disk" else ("E_total", "N_c")
        md += ["", f"## {scene} (kn = {kn:g})", "",
               "| integrator | dt/tau_c | " + " | ".join(f"{q} | {q} error" for q in quantities) +
               " | loop s per unit time |", "|---" * (3 + 2 * len(quantities)) + "|"]
        for integrator in INTEGRATORS:
            by_fraction = {o["variables"]["dt_fraction"]: o for o in rows
                           if o["variables"]["integrator"] == integrator}
            if FRACTIONS[-1] not in by_fraction:
                continue
            finest = by_fraction[FRACTIONS[-1]]
            for fraction in FRACTIONS:
                o = by_fraction.get(fraction)
                if o is None:
                    continue
                cells = []
                for q in quantities:
                    error = o[q] - finest[q]
                    sigma = np.hypot(o[q + "_err"], finest[q + "_err"])
                    cells += [f"{o[q]:.4g} ± {o[q + '_err']:.2g}", f"{error:+.3g} ± {sigma:.2g}"]
                    if fraction != FRACTIONS[-1]:
                        points.append((f"{scene} {q}", integrator, fraction, error, sigma,
                                       cost_per_time(o)))
                md.append(f"| {integrator} | 1/{1 / fraction:.0f} | " + " | ".join(cells) +
                          f" | {cost_per_time(o):.4g} |")

    md += ["", "## Cheapest choice per observable", "",
           "The largest dt (cheapest run) whose error stays inside 2 statistical errors, and the "
           "speed-up over the paper's dt = tau_c/100 with the same integrator.", "",
           "| observable | integrator | dt/tau_c | error | speed-up over tau_c/100 |",
           "|---|---|---|---|---|"]
    for observable in sorted({p[0] for p in points}):
        for integrator in INTEGRATORS:
            mine = [p for p in points if p[0] == observable and p[1] == integrator]
            good = [p for p in mine if abs(p[3]) <= 2 * p[4]]
            reference = [p for p in mine if p[2] == 0.01]
            if not good or not reference:
                continue
            best = min(good, key=lambda p: p[5])
            md.append(f"| {observable} | {integrator} | 1/{1 / best[2]:.0f} | {best[3]:+.3g} ± "
                      f"{best[4]:.2g} | {reference[0][5] / best[5]:.2f} |")

    stiff = sorted((o for o in scenes.get("single_disk", [])
                    if o["variables"]["dt_fraction"] == 0.01
                    and o["variables"]["integrator"] == "verlet"), key=lambda o: o["kn"])
    if len(stiff) >= 2:
        kn = np.array([o["kn"] for o in stiff])
        cost = np.array([cost_per_time(o) for o in stiff])
        exponent, error = fit_power(kn, cost)
        md += ["", "## Cost against stiffness", "",
               f"Single disk at dt = tau_c/100, kn = {', '.join(f'{k:g}' for k in kn)}: loop "
               f"seconds per unit time {', '.join(f'{c:.3g}' for c in cost)}; fitted cost ~ "
               f"kn^{exponent:.3f} ± {error:.2g} (expected 1/2: steps per unit time ~ 1/tau_c).", ""]
    (args.output / "accuracy.md").write_text("\n".join(md) + "\n")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(8, 5))
    for observable in sorted({p[0] for p in points}):
        for integrator, marker in zip(INTEGRATORS, "os"):
            mine = sorted((p for p in points if p[0] == observable and p[1] == integrator),
                          key=lambda p: p[5])
            if mine:
                ax.errorbar([p[5] for p in mine], [abs(p[3]) for p in mine],
                            yerr=[p[4] for p in mine], marker=marker, capsize=2,
                            label=f"{observable}, {integrator}")
    ax.set(xscale="log", yscale="log", xlabel="loop seconds per unit of simulated time",
           ylabel="|error| against the finest run", title="accuracy against cost")
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3, which="both")
    fig.tight_layout()
    fig.savefig(args.output / "accuracy.png", dpi=100)
    print(f"report: {args.output / 'accuracy.md'}")


if __name__ == "__main__":
    sys.exit(main())
