"""docs/figures/hard_spheres_profiles.png: the collisional flow's density and velocity profiles,
soft against hard, from the profile.txt of point directories (postprocess's reader; the
summaries in data/ keep no profiles, so the runs' own directories are read).

    python3 -m scripts.studies.hard_spheres_profiles SOFT_RESULTS HARD_RESULTS [--kn K] [--output PATH]

SOFT_RESULTS, HARD_RESULTS: results directories of scripts/sweep.py (<scene>/<point>/); the
collisional_flow points at k_n = K (default 1.28e7) of each are averaged over their seeds, bin
by bin (mean and standard error). Prints each profile's verdict by the profiles' rule
(docs/hard_spheres.md; postprocess/engines.py compare_profiles) and its largest difference over
the bins in units of their combined error.
"""
import argparse
from pathlib import Path

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from postprocess.engines import compare_profiles  # noqa: E402
from postprocess.figures import save_figure  # noqa: E402
from postprocess.io import Point  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]


def profiles(results, kn):
    """(bin centres, {column: per-point values, shape (points, bins)}) of the collisional_flow
    points at k_n = kn."""
    found = []
    for directory in sorted((Path(results) / "collisional_flow").iterdir()):
        point = Point(directory)
        if (directory / "profile.txt").exists() and float(point.params["kn"]) == kn:
            found.append(point.profile)
    if not found:
        raise SystemExit(f"{results}: no collisional_flow point at k_n = {kn:g} with profile.txt")
    return found[0]["y"], {column: np.array([p[column] for p in found])
                           for column in ("density", "vx")}


def mean_and_error(values):
    return values.mean(axis=0), (values.std(axis=0, ddof=1) / np.sqrt(len(values))
                                 if len(values) > 1 else np.zeros(values.shape[1]))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("soft", type=Path)
    parser.add_argument("hard", type=Path)
    parser.add_argument("--kn", type=float, default=1.28e7)
    parser.add_argument("--output", type=Path,
                        default=ROOT / "docs" / "figures" / "hard_spheres_profiles.png")
    args = parser.parse_args()
    y, soft = profiles(args.soft, args.kn)
    y_hard, hard = profiles(args.hard, args.kn)
    n_soft, n_hard = len(soft["density"]), len(hard["density"])
    if not np.allclose(y, y_hard):
        raise SystemExit("the soft and the hard profiles have different bins")
    fig, axes = plt.subplots(1, 2, figsize=(9, 4.5), sharey=True)
    for ax, column, label in ((axes[0], "density", "number density"), (axes[1], "vx", "mean v_x")):
        for (mean, error), name, style in ((mean_and_error(soft[column]), f"soft ({n_soft} runs)",
                                            "C0-"),
                                           (mean_and_error(hard[column]), f"hard, rule (b), "
                                            f"t_c = tau_c ({n_hard} runs)", "C3--")):
            ax.plot(mean, y, style, label=name)
            ax.fill_betweenx(y, mean - 2 * error, mean + 2 * error, color=style[:2], alpha=0.2)
        ax.set_xlabel(label)
        result = compare_profiles(soft[column], hard[column], soft["density"].mean(axis=0) > 0,
                                  hard["density"].mean(axis=0) > 0)
        print(f"{column}: {result.verdict}: {result.differing} of {result.compared} bins differ "
              f"(at most {result.longest_run} neighbouring), the largest by {result.largest:.2f} "
              f"combined errors")
    axes[0].set_ylabel("height y")
    axes[0].set_ylim(-1, 12)
    axes[0].legend(fontsize=8)
    fig.suptitle(f"Collisional flow at k_n = {args.kn:g}: profiles over t = 200-700, "
                 "mean over seeds with 2 standard errors")
    print(f"figure: {save_figure(fig, args.output, dpi=110)}")


if __name__ == "__main__":
    main()
