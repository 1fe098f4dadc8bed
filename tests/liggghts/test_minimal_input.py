"""The minimal input of docs/liggghts.md runs as it stands on that page, quietly and with the
energy of a dissipative law.

The spheres start at rest, so their kinetic plus potential energy (the springs' left out) can
only fall: the law dissipates, and velocity Verlet at the input's tau_c/100 errs on a contact's
energy by about (omega dt)^2/8 = 1.2e-4 of it, not cumulatively. KE + M g z_cm may therefore
exceed its start by at most 1e-3 of M g z_cm at the start at any output. Spheres placed closer
than a diameter (the page's former `lattice sc 1.2`, 0.94 apart) release their springs' energy
at the first steps (measured: KE + M g z_cm 178 times its start, and atoms lost from the box).
No atom may be lost, and no line of the output may be a WARNING (the models warn of a start
with deep overlaps; LIGGGHTS of a granular pair style without `neigh_modify delay 0`)."""
import re
from pathlib import Path

import pytest

from liggghts_decks import LIGGGHTS, run_liggghts

pytestmark = pytest.mark.skipif(not LIGGGHTS, reason="LIGGGHTS was not built (GRANMN_LIGGGHTS unset)")

ROOT = Path(__file__).resolve().parents[2]
PAGE = ROOT / "docs" / "liggghts.md"
ENERGY_ERROR = 1e-3


def documented_input():
    """The first code block after the page's heading "A minimal input"."""
    text = PAGE.read_text()
    section = text[text.index("## A minimal input"):]
    return re.search(r"```\n(.*?)```", section, re.S).group(1)


def test_minimal_input_runs_quietly(tmp_path):
    text = documented_input()
    gravity = float(re.search(r"^fix \S+ all gravity (\S+) vector 0 0 -1$", text, re.M).group(1))
    # the energy's terms at each output: thermo lines the test adds before the input's last run
    runs = [m.start() for m in re.finditer(r"^run ", text, re.M)]
    assert runs, "the documented input has no run"
    output = ("variable zcm equal xcm(all,z)\nvariable mass equal mass(all)\n"
              "thermo_style custom step atoms ke v_zcm v_mass\nthermo_modify norm no\n"
              "thermo 1000\n")
    deck = text[:runs[-1]] + output + text[runs[-1]:]
    _, out = run_liggghts(deck, tmp_path)
    rows = [[float(v) for v in line.split()]
            for line in out.splitlines() if re.match(r"^\s*\d+\s+\d+\s+\S+\s+\S+\s+\S+\s*$", line)]
    assert len(rows) > 10, out[-3000:]
    _, atoms, _, zcm_start, mass = rows[0]
    start = mass * gravity * zcm_start
    worst = max(ke + mass * gravity * zcm for _, _, ke, zcm, _ in rows)
    print(f"{len(rows)} outputs; KE + PE at most {worst:.6g} against {start:.6g} at the start")
    assert all(row[1] == atoms for row in rows), "atoms lost"
    assert worst <= start * (1 + ENERGY_ERROR)
    warnings = [line for line in out.splitlines() if "WARNING" in line]
    assert not warnings, warnings
    # the pile fell onto the wall: its centre of mass came down by more than the gap of 0.7
    # below the lowest layer
    assert rows[-1][3] < zcm_start - 0.7
