"""The poured pile of examples/pour/in.pour.mn (its `-var dump_poured 1` file) and of LAMMPS's
in.pour run with the same dump: the solid fraction of the pile's bulk, and the kinetic
energy's decay while it settles, from the runs' log.lammps (thermo's `ke`) if given.

The bulk: the slab from 1.5 diameters above the floor to 2 below the pile's top (the height
under which 99 % of the centres lie), the 20 x 20 periodic cross-section of the decks; its
solid fraction counts the centres in it (an unbiased estimate for a homogeneous packing: each
sphere's volume pi d^3/6 where its centre lies), with the spread over the slab's three equal
layers as the error.

    python3 -m scripts.studies.pour_packing DUMP [DUMP ...] [--logs LOG ...] [--figure pour.png]
"""
import argparse
import sys

import numpy as np

from scripts.studies import example_runs
from postprocess.io import read_dump_atoms

AREA = 20.0 * 20.0


def solid_fraction(path):
    """(fraction, its error, the slab, the pile's top) of one dump."""
    a = read_dump_atoms(path, ("z", "radius"))
    z, d = a["z"], 2 * a["radius"]
    top = np.quantile(z, 0.99)
    low, high = 1.5 * d.mean(), top - 2.0 * d.mean()
    edges = np.linspace(low, high, 4)
    layers = [np.sum(np.pi / 6 * d[(z >= lo) & (z < hi)] ** 3) / (AREA * (hi - lo))
              for lo, hi in zip(edges[:-1], edges[1:])]
    return float(np.mean(layers)), float(np.std(layers, ddof=1) / np.sqrt(3)), (low, high), top


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("dumps", nargs="+")
    parser.add_argument("--logs", nargs="*", default=[])
    parser.add_argument("--figure")
    args = parser.parse_args(argv)
    for path in args.dumps:
        phi, error, (low, high), top = solid_fraction(path)
        print(f"{path}: solid fraction {phi:.4f} +- {error:.4f} in z = {low:.2f}-{high:.2f} "
              f"(pile top {top:.2f})")
    if args.figure and args.logs:
        curves = {}
        for path in args.logs:
            rows = example_runs.thermo(path, ("Step", "KinEng"))
            steps, ke = rows["Step"], rows["KinEng"]
            settling = (steps <= 25000) & (ke > 0)
            curves[str(path)] = (steps[settling], ke[settling])
        example_runs.curves_figure(args.figure, curves, "step", "kinetic energy (thermo ke)",
                                   "3D pour: pouring and settling", log_y=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
