"""Cross-checks against LAMMPS's own granular tools (independent of this plugin's code):

- pair style tracker (MISC) watches the same pairs as fix contacts/mn in one run: the same
  completed contacts, the same durations to one step;
- pair_style granular with a linear (hooke) normal model and `damping coeff_restitution`,
  its stiffness and damping matched to gran/mn's 2M-scaled law, gives the same head-on
  rebound for equal disks; for unequal disks the restitution stays but the contact time
  differs as the 2M scaling says (docs/model.md section 2)."""
import math
import os
import re

import numpy as np
import pytest

from collision_decks import two_disks
from granmn_run import law, run_lammps
from pile_decks import PILE, styles

# yyyymmdd of the LAMMPS the suite runs against (tests/CMakeLists.txt)
LAMMPS_VERSION = int(os.environ.get("GRANMN_LAMMPS_VERSION", "0"))
# 24Mar2022 moved pair tracker's output from fix pair/tracker into the pair style (an internal
# fix store/local), with times in steps rather than time units
TRACKER_IN_PAIR_STYLE = LAMMPS_VERSION >= 20220324

WINDOW = 500     # steps between the trackers' outputs (both keep rows for one window)
TRACKED = "id1 id2 time/created time/total"


def tracked_pile(tilt, steps):
    """The pile of pile_decks with friction, rows from fix contacts/mn and from pair tracker."""
    deck = PILE + styles(0.5, tilt=tilt)
    gran_mn = re.search(r"^pair_style (gran/mn .*)$", deck, re.M).group(1)
    if TRACKER_IN_PAIR_STYLE:
        pair = (f"pair_style hybrid/overlay {gran_mn} tracker track {WINDOW} finite {TRACKED}\n")
        tracker_fix = ""
    else:
        pair = f"pair_style hybrid/overlay {gran_mn} tracker finite\n"
        tracker_fix = f"fix track all pair/tracker {WINDOW} {TRACKED}\n"
    deck = deck.replace(f"pair_style {gran_mn}\npair_coeff * *\n",
                        pair + "pair_coeff * * gran/mn\npair_coeff * * tracker\n")
    return deck + tracker_fix + f"""
fix c mobile contacts/mn local {WINDOW}
dump ours mobile local {WINDOW} ours.txt f_c[1] f_c[2] f_c[4] f_c[5]
dump_modify ours format float %.17g
dump theirs all local {WINDOW} theirs.txt f_track[1] f_track[2] f_track[3] f_track[4]
dump_modify theirs format float %.17g
run {steps}
print "RESULT dt $(dt:%.17g)"
"""


def local_rows(path):
    rows = []
    lines = path.read_text().splitlines()
    k = 0
    while k < len(lines):
        if lines[k].startswith("ITEM: NUMBER OF ENTRIES"):
            n = int(lines[k + 1])
            k += 3    # ITEM: BOX BOUNDS / ENTRIES header lines follow
            while not lines[k].startswith("ITEM: ENTRIES"):
                k += 1
            rows += [tuple(map(float, l.split())) for l in lines[k + 1:k + 1 + n]]
            k += 1 + n
        else:
            k += 1
    return rows


@pytest.mark.parametrize("scene,tilt,steps", [("settling", 0.0, 20000), ("flowing", 0.5, 20000)])
def test_pair_tracker_sees_the_same_contacts(tmp_path, scene, tilt, steps):
    run = run_lammps(tracked_pile(tilt, steps), tmp_path)
    dt = run.result("dt")[0]
    # ours: ids, start and duration in time units; only pair contacts (a wall row has id 0)
    ours = sorted((min(i, j), max(i, j), round(start / dt), round(duration / dt))
                  for i, j, start, duration in local_rows(tmp_path / "ours.txt") if j > 0)
    theirs = []
    for i, j, created, total in local_rows(tmp_path / "theirs.txt"):
        if not TRACKER_IN_PAIR_STYLE:       # then in time units
            created, total = created / dt, total / dt
        theirs.append((min(i, j), max(i, j), round(created), round(total)))
    theirs.sort()
    print(f"{scene}: {len(ours)} completed pair contacts (fix contacts/mn), {len(theirs)} "
          f"(pair tracker), LAMMPS {LAMMPS_VERSION}")
    assert len(ours) > 50
    assert [(i, j) for i, j, _, _ in ours] == [(i, j) for i, j, _, _ in theirs]
    starts = np.array([o[2] - t[2] for o, t in zip(ours, theirs)])
    durations = np.array([o[3] - t[3] for o, t in zip(ours, theirs)])
    print(f"start differences (steps) {sorted(set(starts))}, durations {sorted(set(durations))}")
    assert np.all(np.abs(starts) <= 1) and np.all(np.abs(durations) <= 1)


# pair granular's hooke model: F_n = k delta - gamma v_n; with damping coeff_restitution,
# gamma = sqrt(4 m_eff k / (1 + (pi/ln e)^2)). gran/mn: F_n = 2M (kn delta - eta_n v_n).
# For equal disks of mass m, 2M = m: k = m kn makes the two laws one (gamma = m eta_n).
KN, E = 2e5, 0.7
HAS_COEFF_RESTITUTION = LAMMPS_VERSION >= 20230208


def head_on(tmp_path, style, d2):
    dt = law(KN, E, 0.7)["tau_c"] / 50
    deck, contact = two_disks((KN, E, 0.7, 0.0), dt, d2=d2)
    if style == "granular":
        k = KN * 1.0              # the mass of the unit disk of equal pairs
        deck = re.sub(r"pair_style gran/mn .*\npair_coeff \* \*\n",
                      f"pair_style granular\npair_coeff * * hooke {k!r} {E!r} damping "
                      "coeff_restitution tangential linear_nohistory 0 0\n", deck)
    run = run_lammps(deck, tmp_path / style)
    final = run.atoms()
    trace = np.loadtxt(tmp_path / style / "trace.txt", ndmin=2)
    steps_in_contact = int(np.sum(trace[:, 1] < contact))
    return final["vx"], steps_in_contact, dt


@pytest.mark.skipif(not HAS_COEFF_RESTITUTION,
                    reason=f"pair granular's damping coeff_restitution is not in LAMMPS "
                           f"{LAMMPS_VERSION} (it is in 2025's)")
def test_pair_granular_hooke_rebound_equals_gran_mn_for_equal_disks(tmp_path):
    v_mn, steps_mn, _ = head_on(tmp_path, "gran_mn", 1.0)
    v_g, steps_g, _ = head_on(tmp_path, "granular", 1.0)
    print(f"gran/mn v {v_mn}, {steps_mn} steps; granular v {v_g}, {steps_g} steps; "
          f"largest difference {np.max(np.abs(v_mn - v_g)):.3g}")
    assert steps_mn == steps_g
    # the same law summed in another order: rounding of a few ulps per step over the contact
    assert np.allclose(v_mn, v_g, rtol=0, atol=1e-12 * steps_mn)
    assert abs((v_mn[1] - v_mn[0]) - E) < 0.01     # both rebound with e (disks met at 1.0)


@pytest.mark.skipif(not HAS_COEFF_RESTITUTION,
                    reason=f"pair granular's damping coeff_restitution is not in LAMMPS "
                           f"{LAMMPS_VERSION} (it is in 2025's)")
def test_unequal_disks_keep_e_but_not_the_contact_time(tmp_path):
    """Disks of diameters 1 and 0.8 (masses 1, 0.64; M = 0.39): gran/mn's force scales with
    2M, so its contact lasts tau_c = pi / sqrt(2 kn - eta_n^2) whatever the masses; pair
    granular's fixed k (matched for unit pairs) and restitution-derived damping give
    pi / sqrt(k/M - (gamma/2M)^2) = tau_c sqrt(2M): here a contact shorter by 12 %."""
    d2 = 0.8
    m2 = d2 ** 2
    two_m = 2 * m2 / (1 + m2)
    v_mn, steps_mn, dt = head_on(tmp_path, "gran_mn", d2)
    v_g, steps_g, _ = head_on(tmp_path, "granular", d2)
    tau_c = law(KN, E, 0.7)["tau_c"]
    print(f"2M = {two_m:.4f}: gran/mn {steps_mn} steps ({tau_c / dt:.2f} predicted), "
          f"granular {steps_g} steps ({tau_c / dt * math.sqrt(two_m):.2f} predicted)")
    assert abs(steps_mn - tau_c / dt) <= 1
    assert abs(steps_g - tau_c / dt * math.sqrt(two_m)) <= 1
    # both keep the restitution (of the relative velocity): the damping scales with m_eff in both
    e_mn = v_mn[1] - v_mn[0]
    e_g = v_g[1] - v_g[0]
    assert abs(e_mn - E) < 0.01 and abs(e_g - E) < 0.01
