"""docs/figures/collision_rules.png: how far the paper's collision rule (a) is from the hard limit
of its own soft law, rule (b) (plugin/mn_collision.h; docs/hard_spheres.md), over the impact
angle phi = atan(|v_t| / |v_n|), for equal disks and a disk against the boundary, at the paper's
e = beta = 0.7, mu = 0.5 (after ./scripts/build.sh: build/plugin/event_driven/mn-collision-rules
computes the outcomes).

    python3 -m scripts.studies.collision_rules_figure [--output PATH]

Top: the outgoing tangential contact velocity over the impact speed, v_t'/|v|, under rule (a)
and rule (b) with the literal and the cut-back u_t (the normal outcome, -e v_n or -e_w v_n, is
the same under both rules). Bottom: (b) - (a). Prints the largest difference of each and where.
"""
import argparse
import subprocess
from pathlib import Path

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from postprocess.figures import save_figure  # noqa: E402
from scripts.granmn_sweep.build_layout import build_layout  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
TOOL = build_layout().collision_rules


def outcomes(angles=360):
    """{partner: array of rows (phi_deg vn_in vt_in a_vn a_vt bl_vn bl_vt bc_vn bc_vt)}."""
    text = subprocess.run([str(TOOL), "0.7", "0.7", "0.5", str(angles)], capture_output=True,
                          text=True, check=True).stdout
    rows = {}
    for line in text.splitlines():
        if line.startswith("#"):
            continue
        words = line.split()
        rows.setdefault(words[0], []).append([float(w) for w in words[1:]])
    return {partner: np.array(r) for partner, r in rows.items()}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--output", type=Path, default=ROOT / "docs" / "figures" /
                        "collision_rules.png")
    args = parser.parse_args()
    data = outcomes()
    fig, axes = plt.subplots(2, 2, figsize=(10, 6.5), sharex=True,
                             gridspec_kw={"height_ratios": [2, 1]})
    for column, (partner, title) in enumerate((("disk", "equal disks"),
                                               ("boundary", "a disk against the boundary"))):
        d = data[partner]
        phi = d[:, 0]
        top, bottom = axes[0, column], axes[1, column]
        top.plot(phi, d[:, 4], "k-", label="(a) the paper's rule, eqs. (2)-(5)")
        top.plot(phi, d[:, 6], "C0--", label="(b) the soft law's limit, literal u_t")
        top.plot(phi, d[:, 8], "C1:", label="(b) the soft law's limit, cut-back u_t")
        top.axhline(0, color="0.8", lw=0.5)
        top.set_title(title)
        top.set_ylabel("v_t' / |v|")
        bottom.plot(phi, d[:, 6] - d[:, 4], "C0--", label="(b) literal - (a)")
        bottom.plot(phi, d[:, 8] - d[:, 4], "C1:", label="(b) cut-back - (a)")
        bottom.axhline(0, color="0.8", lw=0.5)
        bottom.set_xlabel("impact angle atan(|v_t| / |v_n|) (degrees)")
        bottom.set_ylabel("difference")
        for k, name in ((6, "literal"), (8, "cut-back")):
            worst = np.argmax(np.abs(d[:, k] - d[:, 4]))
            print(f"{partner}: (b) {name} - (a): largest |difference| {abs(d[worst, k] - d[worst, 4]):.4f} "
                  f"of the impact speed at phi = {phi[worst]:.1f} degrees")
    axes[0, 0].legend(fontsize=8)
    axes[1, 0].legend(fontsize=8)
    fig.suptitle("Rule (a) against rule (b): e = beta = 0.7, mu = 0.5 (scripts/studies/collision_rules_figure.py)")
    print(f"figure: {save_figure(fig, args.output, dpi=110)}")


if __name__ == "__main__":
    main()
