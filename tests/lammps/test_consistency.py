"""The same many-disk trajectory with newton on and off, with 1 and 2 MPI ranks, and across a
restart written while many contacts (pair and wall, with tangential history) are active.

The scene: 48 disks (diameters 0.8-1.0) settled on the floor of a periodic box, with fixed bumps
on the floor and a ceiling (fix wall/gran/mn); gravity is then tilted so that the pile starts to
move, mu = 0.5, so that contacts stick and slide, cross rank boundaries and are handed between
atoms as neighbor lists are rebuilt.

"To rounding": a dense pile is chaotic, so two summation orders drift apart from 1e-16, by about
a factor 10 every 400 steps here (measured: positions 2e-15 after 200 steps, 1e-9 after 3000).
Velocities follow positions through the contact frequency omega = sqrt(2 kn), so states are
compared as (x, y, v/omega, r w/omega) against 1e-8. A physical change (mu = 0) moves the disks
by more than 1e-2."""
import numpy as np
import pytest

from granmn_run import law, run_lammps
from pile_decks import BETA, BOUNDARY, E, FINAL, FIXES, KN, styles
STEPS = 1500
ROUNDING = 1e-8
OMEGA = (2 * KN) ** 0.5


def mirrored_data(source, target, box_length=10.0):
    """The data file of the mirror image x -> box_length - x (velocities and spins follow)."""
    out, section = [], None
    for line in source.read_text().splitlines():
        words = line.split()
        if words and words[0] in ("Atoms", "Velocities"):
            section = words[0]
        elif len(words) == 10 and section == "Atoms":
            # id type diameter density x y z ix iy iz
            words[4] = repr(box_length - float(words[4]))
            words[7] = str(-int(words[7]))
            line = " ".join(words)
        elif len(words) == 7 and section == "Velocities":
            # id vx vy vz wx wy wz
            words[1] = repr(-float(words[1]))
            words[6] = repr(-float(words[6]))
            line = " ".join(words)
        out.append(line)
    target.write_text("\n".join(out) + "\n")
    return target


def full_run(settled, workdir, newton="on", nprocs=1, mu=0.5, shuffle=False,
             integrator="nve/sphere disc", ghost_velocity="yes"):
    # shuffle: rebuild neighbor lists every step and re-sort atoms often, so that contacts
    # are handed between the two atoms' lists (and ranks) many times while they last
    shuffle_settings = "atom_modify sort 7 0.5\n" if shuffle else ""
    shuffle_neighbors = "neigh_modify every 1 delay 0 check no\n" if shuffle else ""
    deck = f"""
newton {newton}
comm_modify vel {ghost_velocity}
processors * 1 1
{shuffle_settings}{BOUNDARY}read_data {settled}
{shuffle_neighbors}
group mobile type 1
""" + styles(mu, integrator=integrator) + f"""
fix report all print {STEPS} "RESULT contacts ${{ncontacts}}"
run {STEPS}
write_restart mid.restart
run {STEPS}
""" + FINAL
    return run_lammps(deck, workdir, nprocs=nprocs)


def state(run):
    a = run.atoms()
    # r w: disks of the pile have diameters 0.8-1.0
    return np.column_stack([a["x"], a["y"], a["vx"] / OMEGA, a["vy"] / OMEGA,
                            0.5 * a["omegaz"] / OMEGA])


@pytest.fixture(scope="module")
def reference(settled, tmp_path_factory):
    return full_run(settled, tmp_path_factory.mktemp("reference"))


def test_scene_has_contacts_at_the_restart_and_depends_on_friction(settled, reference, tmp_path):
    # contact/atom counts each pair twice; the halved value is the number of pair contacts
    assert reference.result("contacts")[0] >= 10
    frictionless = full_run(settled, tmp_path, mu=0.0)
    assert np.max(np.abs(state(frictionless) - state(reference))) > 1e-2


@pytest.mark.parametrize("newton,nprocs,shuffle", [("off", 1, False), ("on", 2, False),
                                                    ("off", 2, False), ("on", 1, True),
                                                    ("on", 2, True), ("off", 2, True)])
def test_same_trajectory_with_newton_and_ranks(settled, reference, tmp_path, newton, nprocs,
                                               shuffle):
    other = full_run(settled, tmp_path, newton=newton, nprocs=nprocs, shuffle=shuffle)
    difference = np.max(np.abs(state(other) - state(reference)))
    print(f"newton {newton}, {nprocs} ranks, shuffle {shuffle}: max difference {difference:.2e}")
    assert difference < ROUNDING


@pytest.mark.parametrize("newton,nprocs", [("on", 1), ("on", 2), ("off", 2)])
def test_the_pair_style_sending_ghost_velocities_gives_the_same_trajectory(
        settled, reference, tmp_path, newton, nprocs):
    """Without comm_modify vel yes pair_style gran/mn sends the ghosts' v and omega itself: the
    same values, so the same forces and trajectory to the bit, across the periodic boundary and
    between ranks. (A ghost whose velocity is not sent keeps zeros or stale values: the pairs
    across a boundary get other damping forces, and the pile moves otherwise.)"""
    sent_by_lammps = (reference if (newton, nprocs) == ("on", 1) else
                      full_run(settled, tmp_path / "lammps", newton=newton, nprocs=nprocs))
    sent_by_pair = full_run(settled, tmp_path / "pair", newton=newton, nprocs=nprocs,
                            ghost_velocity="no")
    assert np.array_equal(state(sent_by_pair), state(sent_by_lammps))


def rolling_over_a_bump(angle_deg, gravity, velocity):
    """A unit disk resting on a fixed bump at the origin (gravity pulls it onto the bump),
    starting at polar angle angle_deg around it with the given velocity and the spin of
    rolling, climbing over the bump's summit for t = 1.6."""
    a = np.radians(angle_deg)
    dt = law(KN, E, BETA)["tau_c"] / 50
    return f"""
region box block -3 3 -3 3 -0.5 0.5
create_box 2 box
create_atoms 2 single 0 0 0
create_atoms 1 single {np.cos(a)!r} {np.sin(a)!r} 0
group mobile type 1
set type * diameter 1.0
set type * density/disc 1.2732395447351628
velocity all set 0 0 0
set group mobile vx {velocity[0]!r} vy {velocity[1]!r} omega 0 0 {2 * np.hypot(*velocity)!r}
pair_style gran/mn kn {KN} e {E} beta {BETA} mu 0.5 wall_types 2
pair_coeff * *
timestep {dt!r}
fix integrate mobile nve/sphere disc
fix flat all enforce2d
fix gravity mobile gravity 1.0 vector {gravity[0]} {gravity[1]} 0
run {int(1.6 / dt)}
write_dump mobile custom final.txt id x y vx vy omegaz modify format float %.17g
"""


def test_contact_handed_between_atoms_keeps_its_history(tmp_path):
    """Rotating a scene by 90 degrees is a symmetry of the law, not of LAMMPS's bookkeeping.
    With gravity along -x, the disk rolls over the right side of the bump from below its
    centre line to above it, so the pair moves to the other atom's neighbor list mid-contact (neighbor bins
    are ordered by rows); with gravity along -y it rolls over the top and the pair never
    changes hands. The scalar u_t is the same seen from either atom (t and v_ij both flip),
    so the history must be copied, not negated, on the hand-over: with a negating transfer
    the two runs differ by ~1e-2 (measured), not by rounding."""
    v = 0.9 * np.array([np.sin(np.radians(40)), np.cos(np.radians(40))])
    side = run_lammps(rolling_over_a_bump(-40, (-1, 0), v), tmp_path / "side").atoms()
    top = run_lammps(rolling_over_a_bump(50, (0, -1), (-v[1], v[0])), tmp_path / "top").atoms()
    # the side run, rotated by +90 degrees, is the top run
    assert side["y"][0] > 0.3    # it did roll past the bump's equator
    difference = max(abs(-side["y"][0] - top["x"][0]), abs(side["x"][0] - top["y"][0]),
                     abs(-side["vy"][0] - top["vx"][0]) / OMEGA,
                     abs(side["vx"][0] - top["vy"][0]) / OMEGA,
                     abs(side["omegaz"][0] - top["omegaz"][0]) * 0.5 / OMEGA)
    print(f"rotated runs: max difference {difference:.2e}")
    assert difference < ROUNDING


def test_mirror_image_evolves_as_the_mirror_image(settled, tmp_path):
    """Reflection x -> -x (with v_x and spins reversed) is a symmetry of the law: a flowing
    pile and its mirror image must evolve as mirror images of each other, to rounding. This
    holds only if the signs of t, v_t, the tangential force and the torques agree."""
    def run(data, tilt, name):
        deck = (f"{BOUNDARY}read_data {data}\ngroup mobile type 1\n"
                "neigh_modify every 1 delay 0 check no\n" + styles(0.5, tilt=tilt) +
                f"run {STEPS}\nwrite_dump mobile custom final.txt id xu y vx vy omegaz "
                "modify sort id format float %.17g\n")
        return run_lammps(deck, tmp_path / name)

    original = run(settled, 0.6, "original")
    mirror = run(mirrored_data(settled, tmp_path / "mirror.data"), -0.6, "mirror")
    a, b = original.atoms(), mirror.atoms()
    difference = max(np.max(np.abs(a["xu"] - (10.0 - b["xu"]))), np.max(np.abs(a["y"] - b["y"])),
                     np.max(np.abs(a["vx"] + b["vx"])) / OMEGA,
                     np.max(np.abs(a["vy"] - b["vy"])) / OMEGA,
                     np.max(np.abs(a["omegaz"] + b["omegaz"])) * 0.5 / OMEGA)
    print(f"mirror: max difference {difference:.2e}")
    assert difference < ROUNDING


@pytest.mark.parametrize("nprocs", [1, 2])
def test_restart_in_the_middle_of_contacts_continues_the_trajectory(reference, tmp_path, nprocs):
    deck = f"""
read_restart {reference.workdir / 'mid.restart'}
neighbor 0.1 bin
comm_modify vel yes
""" + FIXES.format(tilt=0.3, integrator="nve/sphere disc") + f"run {STEPS}\n" + FINAL
    restarted = run_lammps(deck, tmp_path / "restarted", nprocs=nprocs)
    difference = np.max(np.abs(state(restarted) - state(reference)))
    print(f"restart on {nprocs} ranks: max difference {difference:.2e}")
    assert difference < ROUNDING


def test_paper_integrator_on_two_ranks_and_across_a_restart(settled, tmp_path):
    """fix nve/ab2 keeps each atom's previous acceleration: it must move with the atom between
    ranks and survive a restart, or the continued trajectory would differ at once."""
    reference = full_run(settled, tmp_path / "reference", integrator="nve/ab2")
    two_ranks = full_run(settled, tmp_path / "two_ranks", nprocs=2, integrator="nve/ab2")
    deck = f"""
read_restart {reference.workdir / 'mid.restart'}
neighbor 0.1 bin
comm_modify vel yes
""" + FIXES.format(tilt=0.3, integrator="nve/ab2") + f"run {STEPS}\n" + FINAL
    restarted = run_lammps(deck, tmp_path / "restarted", nprocs=2)
    for other, name in ((two_ranks, "2 ranks"), (restarted, "restart on 2 ranks")):
        difference = np.max(np.abs(state(other) - state(reference)))
        print(f"ab2, {name}: max difference {difference:.2e}")
        assert difference < ROUNDING
