"""The dynamic angle of repose of examples/drum's turning drums, from their log.lammps files:
the tilt of the pile's centre of mass from below the axis, atan(-x_cm / -z_cm), which for a
half-filled drum with a flat surface is the surface's angle. Averaged from a quarter turn
after the drum starts (the pile has reached its steady tilt) to the end, with the standard
error over four consecutive blocks (the angle swings with the avalanches, so single samples
are not independent); a figure of the angle against time if asked.

    python3 -m scripts.studies.drum_repose LOG [LOG ...] [--omega 0.1] [--start 20] [--figure drum.png]
"""
import argparse
import sys

import numpy as np

from scripts.studies import example_runs

BLOCKS = 4


def repose(path, start, omega):
    """(times, angles in degrees, mean, block standard error) of one log."""
    rows = example_runs.thermo(path, ("Time", "v_xcm", "v_zcm"))
    t, x, z = rows["Time"], rows["v_xcm"], rows["v_zcm"]
    angle = np.degrees(np.arctan2(-x, -z))
    steady = t >= start + 0.5 * np.pi / omega
    blocks = [b.mean() for b in np.array_split(angle[steady], BLOCKS)]
    return t, angle, float(np.mean(blocks)), float(np.std(blocks, ddof=1) / np.sqrt(BLOCKS))


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("logs", nargs="+")
    parser.add_argument("--omega", type=float, default=0.1, help="the drum's angular velocity")
    parser.add_argument("--start", type=float, default=20.0, help="when the drum starts")
    parser.add_argument("--figure")
    args = parser.parse_args(argv)
    results = {path: repose(path, args.start, args.omega) for path in args.logs}
    for path, (_, _, mean, error) in results.items():
        print(f"{path}: dynamic angle of repose {mean:.2f} +- {error:.2f} degrees")
    if args.figure:
        fig, ax = example_runs.axes((7, 3.5))
        for path, (t, angle, mean, error) in results.items():
            ax.plot(t, angle, lw=1, label=f"{path}: {mean:.1f} +- {error:.1f} deg")
        ax.axvline(args.start, color="k", lw=0.6, ls=":")
        ax.set(xlabel="time", ylabel="tilt of the centre of mass (deg)",
               title="half-filled drum, Omega = %g: the pile's tilt" % args.omega)
        example_runs.save(fig, ax, args.figure)
    return 0


if __name__ == "__main__":
    sys.exit(main())
