"""Stiff cases stay stable (docs/model.md section 7, paper section II D): no NaN, no lost atoms, no
energy from nowhere, and the many-body collapse behaves as the hard-sphere theory says."""
import numpy as np
import pytest

from collision_decks import DISC_DENSITY, bounces, two_disks
from granmn_run import law, restitution_error_bound, run_lammps
from pile_decks import BOUNDARY, FIXES

VERY_STIFF = 2 ** 20 * 1e5


@pytest.mark.parametrize("kn", [2 ** 18 * 1e5, VERY_STIFF])
def test_binary_collision_at_extreme_stiffness(tmp_path, kn):
    tau = law(kn, 0.7, 0.7)["tau_c"]
    deck, _ = two_disks((kn, 0.7, 0.7, 0.5), tau / 100)
    a = run_lammps(deck, tmp_path).atoms()
    assert np.all(np.isfinite(a["vx"])) and len(a["vx"]) == 2
    assert abs(-(a["vx"][0] - a["vx"][1]) - 0.7) <= restitution_error_bound(0.7, 0.01)


def three_disks(kn, e):
    """Three disks on a line, no gravity: the outer two approach at speed 1 (the right one
    0.15 further away), the middle one at rest, so that it is struck alternately. Stops at
    the first step with a three-body contact (two contacts at once)."""
    return f"""
region box block -5 5 -5 5 -0.5 0.5
create_box 1 box
create_atoms 1 single -1.3 0 0
create_atoms 1 single 0 0 0
create_atoms 1 single 1.45 0 0
set type 1 diameter 1.0
set type 1 density/disc {DISC_DENSITY!r}
velocity all set 0 0 0
set atom 1 vx 1
set atom 3 vx -1
pair_style gran/mn kn {kn!r} e {e!r} beta 0.7 mu 0
pair_coeff * *
timestep $(v_mn_tau_c/100)
fix integrate all nve/sphere disc
fix flat all enforce2d
fix c all contacts/mn
variable multiple equal f_c[5]
fix stop all halt 10 v_multiple > 0 error continue
run $(ceil(2.0/dt))
print "RESULT collapse $(f_c[1]/2) $(f_c[5]) $(count(all))"
"""


def test_three_disk_collapse_takes_ln_kn_collisions(tmp_path):
    """e = 0.05 < 7 - 4 sqrt(3): hard disks would collapse (infinitely many collisions); soft
    ones end in a three-body contact once the interval between collisions is shorter than
    tau_c ~ kn^-1/2, after a number of collisions linear in ln kn."""
    kns = [2 ** p * 1e5 for p in range(0, 17, 2)]
    counts = []
    for kn in kns:
        collisions, multiple, atoms = run_lammps(three_disks(kn, 0.05),
                                                 tmp_path / f"{kn:g}").result("collapse")
        assert multiple > 0 and atoms == 3
        counts.append(collisions)
    x = np.log(kns)
    slope, intercept = np.polyfit(x, counts, 1)
    r2 = 1 - np.sum((counts - (slope * x + intercept)) ** 2) / np.sum((counts - np.mean(counts)) ** 2)
    print(f"collisions before the three-body contact: {counts}, slope {slope:.3f}, R^2 {r2:.3f}")
    assert slope > 0 and r2 > 0.9


def test_no_collapse_above_the_critical_restitution(tmp_path):
    """e = 0.3 > 7 - 4 sqrt(3): a few collisions, then the disks separate, at any stiffness."""
    for kn in (2 ** 4 * 1e5, 2 ** 16 * 1e5):
        collisions, multiple, _ = run_lammps(three_disks(kn, 0.3),
                                             tmp_path / f"{kn:g}").result("collapse")
        assert multiple == 0 and collisions <= 4


def test_stiff_bouncing_ball_comes_to_rest(tmp_path):
    """kn = 2^20 x 10^5: the ball comes to rest on the wall, without NaN, after as many bounces
    as the ln kn law predicts from a softer ball (2^12 x 10^5, same drop): ln(2^8)/(2|ln e_w|)
    = 11.0 more, +-2 for two integer counts (test_counters fits the law itself)."""
    soft, stiff = bounces(tmp_path, 2 ** 12 * 1e5), bounces(tmp_path, VERY_STIFF)
    expected = soft + np.log(2 ** 8) / (2 * abs(np.log(law(VERY_STIFF, 0.7, 0.7)["e_w"])))
    print(f"bounces at 2^12: {soft:.0f}, at 2^20: {stiff:.0f}, expected {expected:.1f}")
    assert abs(stiff - expected) <= 2


def test_settled_pile_held_at_high_stiffness_neither_heats_nor_creeps(settled, tmp_path):
    """The pile settled at kn = 2e5 is stiffened by doublings up to 2^8 x 10^5 (0.5 time units
    each, so that the released elastic energy stays small), then held for 2 time units: the
    kinetic energy only decays (the largest value of the second half of the hold is not above
    that of the first half), no atom is lost, and no disk of the pile moves by more than 1e-6
    (nothing creeps). A disk that ends up alone on the floor next to the pile may roll on at
    constant speed: rolling without slip costs nothing in this law (measured: one disk,
    v = 1.9e-3, KE 1.2e-6, constant); it must then be rolling exactly."""
    stiffen = ""
    for p in range(2, 9):
        kn = 2 ** p * 1e5
        stiffen += (f"pair_style gran/mn kn {kn!r} e 0.7 beta 0.7 mu 0.5 wall_types 2\n"
                    "timestep $(v_mn_tau_c/50)\nrun $(ceil(0.5/dt))\n")
    deck = f"{BOUNDARY}read_data {settled}\ngroup mobile type 1\n" + f"""
pair_style gran/mn kn 2e5 e 0.7 beta 0.7 mu 0.5 wall_types 2
pair_coeff * *
timestep $(v_mn_tau_c/50)
""" + FIXES.format(tilt=0.0, integrator="nve/sphere disc") + "thermo 100000\n" + stiffen + """
fix start mobile store/state 0 x y
variable moved atom sqrt((x-f_start[1])^2+(y-f_start[2])^2)
compute moved mobile reduce max v_moved
compute kinetic mobile ke
fix energy all ave/time $(ceil(0.02/dt)) 1 $(ceil(0.02/dt)) c_kinetic c_moved file energy.txt
compute neighbours mobile contact/atom
dump final mobile custom $(ceil(2.0/dt)) final.txt id radius vx omegaz v_moved c_neighbours
dump_modify final sort id format float %.17g
run $(ceil(2.0/dt))
print "RESULT hold $(count(mobile))"
"""
    run = run_lammps(deck, tmp_path)
    n, = run.result("hold")
    table = run.table("energy.txt")
    ke, moved = table[:, 1], table[:, 2]
    half = len(ke) // 2
    print(f"max displacement {moved.max():.2e}; KE first half max {ke[:half].max():.2e}, "
          f"second half max {ke[half:].max():.2e}")
    assert n == 48 and np.all(np.isfinite(table))
    assert ke[half:].max() <= ke[:half].max()
    lines = (tmp_path / "final.txt").read_text().split("ITEM: TIMESTEP")[-1].splitlines()
    final = np.loadtxt(lines[9:], ndmin=2)    # id radius vx omegaz moved neighbours
    in_pile = final[:, 5] > 0
    print(f"pile: max displacement {final[in_pile, 4].max():.2e}; "
          f"{np.count_nonzero(~in_pile)} lone disks")
    assert final[in_pile, 4].max() < 1e-6
    lone = final[~in_pile]
    # on the floor n = (0, 1), t = (-1, 0): no slip is v_x = -r omega
    assert np.all(np.abs(lone[:, 2] + lone[:, 1] * lone[:, 3]) <= 1e-6 * np.abs(lone[:, 2]))
