"""A disk launched sliding along the flat floor (docs/model.md section 2, "The literal u_t
while sliding"). Coulomb friction decelerates the contact point at 3 mu g (a disk: 1 + m r^2/I
= 3) until it rolls: from v0 without spin it sticks at T = v0/(3 mu g) and rolls at 2 v0/3,
kinetic energy m v0^2/3. The paper's literal u_t (the integral of v_t since the contact began,
never cut back) has grown to v0^2/(6 mu g) by then: the spring still holds the force at the
Coulomb cap, in the old direction, and drives the contact point backwards until u_t unwinds
(to -v0 at 2T without the tangential dashpot): the disk never settles into rolling and gains
back the energy friction took. The cut-back reading (coulomb_cutback) rolls."""
import numpy as np
import pytest

from collision_decks import DISC_DENSITY
from granmn_run import law, run_lammps

MU, V0, G = 0.5, 2.0, 1.0
T_STICK = V0 / (3 * MU * G)


def slide(tmp_path, kn, keyword):
    ref = law(kn, 0.7, 0.7)
    dt = ref["tau_c"] / 50
    deck = f"""
boundary p fm p
region box block 0 10 -1 5 -0.5 0.5
create_box 1 box
create_atoms 1 single 5 0.5 0 units box
set atom 1 diameter 1.0 density/disc {DISC_DENSITY!r}
pair_style gran/mn kn {kn!r} e 0.7 beta 0.7 mu {MU!r} {keyword}
pair_coeff * *
timestep {dt!r}
fix gravity all gravity {G!r} vector 0 -1 0
fix integrate all nve/sphere disc
fix floor all wall/gran/mn yplane 0.0 NULL
run {int(round(2.0 / dt))}
velocity all set {V0!r} 0 0
compute spin all property/atom omegaz
compute omega all reduce sum c_spin
variable t equal step*dt-{int(round(2.0 / dt)) * dt!r}
variable vt equal vx[1]+0.5*c_omega
variable ke equal 0.5*mass[1]*(vx[1]^2+vy[1]^2)+mass[1]*c_omega^2/16
fix trace all print {max(1, int(round(0.01 / dt)))} "$(v_t) $(v_vt) $(v_ke)" file trace.txt screen no
run {int(round(4 * T_STICK / dt))}
"""
    trace = run_lammps(deck, tmp_path).table("trace.txt")
    return trace[:, 0], trace[:, 1], trace[:, 2]


@pytest.mark.parametrize("kn", [2e5, 2e7])
def test_cutback_law_rolls_after_sliding(tmp_path, kn):
    t, vt, ke = slide(tmp_path, kn, "coulomb_cutback")
    # sticks at T (to within the trace's sampling and the spring's settling, 2 % of T) ...
    stuck = t[np.argmax(np.abs(vt) < 1e-3 * V0)]
    assert abs(stuck - T_STICK) < 0.02 * T_STICK
    # ... and rolls from then on: no reversal, the rolling energy m v0^2/3 kept (a sliding or
    # oscillating contact would be off by O(1))
    late = t > 1.2 * T_STICK
    assert np.all(np.abs(vt[late]) < 1e-3 * V0)
    assert np.allclose(ke[late], V0 ** 2 / 3, rtol=1e-3)


@pytest.mark.parametrize("kn", [2e5, 2e7])
def test_literal_law_reverses_the_sliding_at_any_stiffness(tmp_path, kn):
    t, vt, ke = slide(tmp_path, kn, "")
    # the same deceleration up to T ...
    before = t < 0.9 * T_STICK
    assert np.allclose(vt[before], V0 - 3 * MU * G * t[before], atol=0.01 * V0)
    # ... then the unwinding u_t drives the contact point backwards (to -v0 without the
    # dashpot; Coulomb friction never reverses a sliding contact by itself) ...
    assert vt.min() < -0.5 * V0
    # ... and the disk regains energy friction had taken: friction doing positive work
    rolling = V0 ** 2 / 3
    assert ke[t > T_STICK].max() > rolling + 0.25 * (V0 ** 2 / 2 - rolling)
