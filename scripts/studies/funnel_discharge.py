"""How many spheres have run out of examples/granregion's funnel, from the log.lammps files of
in.granregion.funnel.mn and of LAMMPS's in.granregion.funnel with the same count added (thermo
`v_below`, the spheres below the funnel's bottom z = 0): out = those below plus those gone
from the box (`lost warn`), against the time since the bottom opened; a figure if asked.

    python3 -m scripts.studies.funnel_discharge LOG [LOG ...] [--opened STEP] [--dt DT] [--figure funnel.png]
"""
import argparse
import sys

import numpy as np

from scripts.studies import example_runs


def discharge(path, opened, dt):
    """(time since opening, spheres out) of one log's thermo rows (Step, Atoms, v_below) from
    the step the bottom opened on."""
    rows = example_runs.thermo(path, ("Step", "Atoms", "v_below"))
    out = rows["Atoms"].max() - rows["Atoms"] + rows["v_below"]    # all poured, less those left
    after = rows["Step"] >= opened
    if not after.any():
        raise SystemExit(f"funnel_discharge: {path}: no thermo rows from step {opened:g} on")
    return (rows["Step"][after] - opened) * dt, out[after]


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("logs", nargs="+")
    parser.add_argument("--opened", type=float, default=170000, help="the step the bottom opens")
    parser.add_argument("--dt", type=float, default=1.0547660478914302e-04)
    parser.add_argument("--figure")
    args = parser.parse_args(argv)
    curves = {path: discharge(path, args.opened, args.dt) for path in args.logs}
    for path, (t, out) in curves.items():
        marks = ", ".join(f"{out[np.argmin(np.abs(t - s))]:.0f} at {s:g} s"
                          for s in (2.0, 5.0, 10.0) if t.max() >= s)
        print(f"{path}: spheres out {marks}")
    if args.figure:
        example_runs.curves_figure(args.figure, {str(p): c for p, c in curves.items()},
                                   "time since the bottom opened (s)", "spheres out",
                                   "funnel discharge")
    return 0


if __name__ == "__main__":
    sys.exit(main())
