"""The scatter behind tests/lammps/test_scenes.py::test_collisional_flow_reaches_a_steady_energy:
per run of inputs/sweeps/collisional_steadiness.toml, the ratio of the mean energy per disk over
[500, 800) to that over [200, 500); over the runs of the scene's own restitution, the standard
deviation of the log of that ratio (what the test's bound is measured against); and the ratio of
the runs with another restitution (flows that should fail the test).

    python3 -m scripts.studies.steadiness_calibration SUMMARIES_DIR    # e.g. data/collisional_steadiness"""
import sys

import numpy as np

from postprocess.record import energy_curve
from postprocess.summary import read_summaries

EARLY, LATE = (200, 500), (500, 800)


def ratio(record):
    t, e = energy_curve(record)
    early = e[(t >= EARLY[0]) & (t < EARLY[1])].mean()
    late = e[(t >= LATE[0]) & (t < LATE[1])].mean()
    return late / early


def main(directory):
    records = [r for r in read_summaries(directory) if r.scene == "collisional_flow"]
    if not records:
        sys.exit(f"{directory}: no collisional_flow run summaries")
    same, other = [], []
    for record in sorted(records, key=lambda r: sorted(r.variables.items(), key=str)):
        value = ratio(record)
        restitution = record.variables.get("e")
        print(f"seed {record.variables['seed']:>5} newton {record.variables['newton']:<3} "
              f"e {restitution or 'default':<7} E[500,800) / E[200,500) = {value:.3f}")
        (other if restitution else same).append(value)
    logs = np.log(same)
    print(f"{len(same)} runs of the deck's restitution: sd of ln(ratio) {logs.std(ddof=1):.3f}, "
          f"ratios {min(same):.3f}-{max(same):.3f}")
    if other:
        print("other restitutions:", ", ".join(f"{v:.2f}" for v in other))
    return 0


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    sys.exit(main(sys.argv[1]))
