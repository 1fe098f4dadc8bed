"""Atoms that come into a run: pair_style gran/mn sizes its cut-offs at a run's start from the
atoms present and from the radii that fix pour and fix deposit will insert (they tell them, as
LAMMPS's granular pair styles ask them). A cut-off below two atoms' radii leaves them out of
the neighbor list until they are inside each other."""
import math

import numpy as np

from granmn_run import HEADER, PLUGIN, law, run_lammps

KN, E, BETA, MU = 2e5, 0.5, 0.7, 0.5
G = 1.0


def pile_overlaps(atoms, dimension, periods):
    """Overlaps of every pair (periodic images along the axes with a period) and of every atom
    with the floor at 0 (the last axis)."""
    axes = ("x", "y", "z")[:dimension]
    x = np.column_stack([atoms[a] for a in axes])
    r = atoms["radius"]
    d = x[:, None, :] - x[None, :, :]
    for k, period in enumerate(periods):
        if period:
            d[:, :, k] -= period * np.round(d[:, :, k] / period)
    dist = np.sqrt((d ** 2).sum(axis=2))
    np.fill_diagonal(dist, np.inf)
    pair = r[:, None] + r[None, :] - dist
    floor = r - x[:, -1]
    return pair, floor, dist


def assert_resting_pile(atoms, dimension, periods, n, speed_scale, resting=None):
    """n atoms in a pile on the floor (those of `resting` at rest, all if None), each touching
    something, none inside another, every overlap within the statics: no contact carries more
    than the weight of all n atoms, an overlap of at most n m g / (m kn) = n g / kn (the mass
    scale of two atoms of equal mass is m, against the floor m). A pile whose contacts were not
    computed would have fallen through itself onto the floor (overlaps of the order of the
    radius)."""
    pair, floor, dist = pile_overlaps(atoms, dimension, periods)
    r = atoms["radius"]
    speed = np.sqrt(sum(atoms[v] ** 2 for v in ("vx", "vy", "vz")[:dimension]))
    assert len(r) == n
    bound = n * G / KN
    height = atoms[("x", "y", "z")[dimension - 1]].max()
    print(f"{n} atoms: largest overlap {max(pair.max(), floor.max()):.3g} (bound {bound:.3g}), "
          f"nearest centres {dist.min():.4g}, highest {height:.3g}, fastest {speed.max():.3g}")
    assert pair.max() < bound and floor.max() < bound
    assert np.all(dist > np.maximum(r[:, None], r[None, :]))
    touching = (pair > 0).any(axis=1) | (floor > 0)
    assert touching.all(), np.nonzero(~touching)
    # at rest: slower than a thousandth of the speed they fell in at
    assert speed[resting if resting is not None else slice(None)].max() < 1e-3 * speed_scale
    # a pile, not a layer: atoms rest on atoms
    assert (floor <= 0).sum() > 0


def test_deposited_disks_pile_up_beside_a_small_bystander(tmp_path):
    """2D: fix deposit drops 40 disks of diameter 1 (its radius, 0.5, which it tells the pair
    style; the mass of a sphere of density 1, as LAMMPS creates them) onto the floor beside a
    resting disk of diameter 0.2 and the same mass (a light one under them would be a soft
    spring against the floor: the law scales stiffness with mass). Sized from the bystander
    alone, the cut-off (0.2) left the falling disks out of each other's neighbor list until
    they were inside each other (stopped by the passed-through error, which blamed kn). They
    come to rest in a pile, every contact computed."""
    dt = law(KN, E, BETA)["tau_c"] / 50
    steps = int(36.0 / dt)    # the last disk comes in at 16, falls for 8, then rests
    deck = f"""
boundary p f p
region box block 0 8 0 30 -0.5 0.5
create_box 1 box
create_atoms 1 single 4.0 0.1 0
set atom 1 diameter 0.2
set atom 1 mass {4 * math.pi / 3 * 0.5 ** 3!r}
pair_style gran/mn kn {KN} e {E} beta {BETA} mu {MU}
pair_coeff * *
timestep {dt!r}
fix integrate all nve/disc/mn gravity {G} 0 -1
fix floor all wall/gran/mn yplane 0.0 NULL
region slab block 0.5 7.5 20 28 0 0
fix drop all deposit 40 1 {int(0.4 / dt)} 4821 region slab near 1.0 vy -1.0 -1.0 &
    units box
thermo {int(5.0 / dt)}
run {steps}
write_dump all custom final.txt id radius x y vx vy modify sort id format float %.17g
"""
    run = run_lammps(deck, tmp_path)
    atoms = run.atoms()
    fall = math.sqrt(2 * G * 28.0) + 1.0
    deposited = atoms["radius"] == 0.5
    assert deposited.sum() == 40
    # the bystander, struck, may roll on along the floor (nothing stops a rolling disk)
    assert_resting_pile(atoms, 2, (8.0, None), 41, fall, resting=deposited)


def test_poured_spheres_pile_up_in_an_empty_box(tmp_path):
    """3D, LAMMPS's examples/pour set-up (fix pour into an empty box over a floor, gravity
    along -z, fix nve/sphere), smaller: with no atom present at the start the cut-off was 0,
    and the poured spheres fell into each other. fix pour tells its largest radius (0.5): they
    come to rest in a pile, every contact computed."""
    dt = law(KN, E, BETA, "sphere")["tau_c"] / 50
    steps = int(20.0 / dt)
    n = 60
    deck = HEADER.format(plugin=PLUGIN).replace("dimension 2", "dimension 3").replace(
        "boundary p p p", "boundary p p fm") + f"""
region box block -3 3 -3 3 -0.5 12 units box
create_box 1 box
neigh_modify delay 0
pair_style gran/mn kn {KN} e {E} beta {BETA} mu {MU}
pair_coeff * *
timestep {dt!r}
fix integrate all nve/sphere
fix gravity all gravity {G} spherical 0.0 -180.0
fix floor all wall/gran/mn zplane 0.0 NULL
region slab block -2.5 2.5 -2.5 2.5 6 11 units box
fix pour all pour {n} 1 300719 vol 0.13 50 region slab
thermo {int(2.0 / dt)}
thermo_style custom step atoms ke
run {steps}
write_dump all custom final.txt id radius x y z vx vy vz modify sort id format float %.17g
"""
    run = run_lammps(deck, tmp_path, header=False)
    fall = math.sqrt(2 * G * 11.0)
    assert_resting_pile(run.atoms(), 3, (6.0, 6.0, None), n, fall)


def test_atoms_grown_past_the_cut_off_are_not_blamed_on_kn(tmp_path):
    """Two disks of diameter 0.2 (the cut-off: 0.2) grown to diameter 1 by fix adapt in the
    run (atom_style sphere 1: radii that change), then approaching at a relative speed of 1:
    they enter the neighbor list (cut-off + skin 0.1) with their centres under 0.3 apart,
    inside each other. The error names the cut-off, not kn: a stiffer spring (the former
    advice, kn > 392015, from a speed of 443 it inferred) changes nothing."""
    dt = law(KN, E, BETA)["tau_c"] / 50
    header = HEADER.format(plugin=PLUGIN).replace("atom_style sphere", "atom_style sphere 1")
    deck = header + f"""
boundary p f p
region box block -5 5 -5 5 -0.5 0.5
create_box 1 box
create_atoms 1 single -0.25 0 0
create_atoms 1 single 0.25 0 0
set type 1 diameter 0.2
set type 1 density/disc {4 / math.pi!r}
velocity all set 0 0 0
set atom 1 vx 0.5
set atom 2 vx -0.5
pair_style gran/mn kn {KN} e {E} beta {BETA} mu {MU}
pair_coeff * *
timestep {dt!r}
variable diameter equal 1.0
fix grow all adapt 1 atom diameter v_diameter
fix integrate all nve/sphere disc
run 5000
"""
    run = run_lammps(deck, tmp_path, header=False, check=False)
    assert run.returncode != 0
    assert "have passed through each other" in run.output, run.output[-2000:]
    assert "cut-off for atom types 1 and 1, 0.2, is less than their radii's sum 1" in run.output
    assert "kn >" not in run.output
