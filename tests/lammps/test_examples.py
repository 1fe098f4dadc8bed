"""The decks of examples/ (LAMMPS's own examples with the law, and a rotating drum) run as a user
runs them, the short variants the tests can afford, with one line added at their end to write
the final atoms."""
import math
from pathlib import Path

import numpy as np

from granmn_run import PLUGIN, run_lammps
from test_insertion import pile_overlaps

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
G = 1.0


def run_example(deck, tmp_path, **variables):
    """The deck with `variables` set before it (as -var does: its index variables keep them)
    and its final atoms dumped to final.txt."""
    settings = dict(plugin=PLUGIN, **variables)
    text = ("".join(f"variable {k} index {v}\n" for k, v in settings.items())
            + (EXAMPLES / deck).read_text()
            + "\nwrite_dump all custom final.txt id type x y z radius vx vy vz "
              "modify sort id\n")
    return run_lammps(text, tmp_path, header=False)


def impact_bound(kn, drop):
    """The largest overlap a contact can reach on the first impacts of a pour: a particle that
    fell `drop` hits at v = sqrt(2 g drop); undamped, a floor contact (mass m, force m kn delta)
    stops it within v / sqrt(kn), a pair (reduced mass M, force 2M kn delta) within
    v_rel / sqrt(2 kn) with v_rel at most 2 v. Damping and the pile's weight (a few layers:
    n g / kn, < 0.01 here) only lower or barely add to it; a contact left out of the forces
    (a wall that does not hold, an insertion into a neighbour) reaches the radius."""
    v = math.sqrt(2 * G * drop)
    return {"floor": v / math.sqrt(kn), "pair": 2 * v / math.sqrt(2 * kn)}


def test_pour_3d_stays_in_its_box_and_above_its_floor(tmp_path):
    """examples/pour/in.pour.mn, 6000 steps of each stage: the first batches poured (from
    z = 10-15 onto the floor at 0: a fall of < 15 takes 5.5 time units) and then tilted. No
    sphere below the floor or inside another by more than an impact allows; none lost."""
    run = run_example("pour/in.pour.mn", tmp_path, steps=6000)
    atoms = run.atoms()
    # fix pour's schedule ("Particle insertion: 402 every 3162 steps, ..."): a batch at step 1
    # and every 3162 steps after, each whole while the slab is empty below it; a sphere lost
    # through the floor (boundary f below) would be missing
    batch, every = next(map(int, line.split()[2:5:2]) for line in run.output.splitlines()
                        if line.startswith("Particle insertion:"))
    assert len(atoms["id"]) == batch * (1 + (6000 - 1) // every)
    bound = impact_bound(3819.7, 15.0)
    pair, floor, _ = pile_overlaps(atoms, 3, (20.0, 20.0))
    print(f"{len(atoms['id'])} spheres: largest pair overlap {pair.max():.3g} (bound "
          f"{bound['pair']:.3g}), floor {floor.max():.3g} ({bound['floor']:.3g})")
    assert pair.max() < bound["pair"] and floor.max() < bound["floor"]
    assert atoms["z"].min() > 0


def test_pour_2d_settles_into_a_pile(tmp_path):
    """examples/pour/in.pour.2d.mn as the original (25000 steps: all 1000 disks poured from
    y = 30-34.5 into the container, which they fill to a height of ~13): the disks stay between
    the side walls and above the floor within an impact's overlap, and the pile comes to rest,
    with less than 1 % of the potential energy it fell through left as motion (a law that did
    not dissipate, e = 1 or a sign error in the damping, would keep it bouncing)."""
    run = run_example("pour/in.pour.2d.mn", tmp_path)
    atoms = run.atoms()
    assert len(atoms["id"]) == 1000
    bound = impact_bound(3475, 34.5)
    pair, floor, _ = pile_overlaps(atoms, 2, (0.0, 0.0))
    r = atoms["radius"]
    sides = np.maximum(r - atoms["x"], atoms["x"] + r - 100.0)
    print(f"largest pair overlap {pair.max():.3g} (bound {bound['pair']:.3g}), floor "
          f"{floor.max():.3g}, side walls {sides.max():.3g} ({bound['floor']:.3g})")
    assert pair.max() < bound["pair"]
    assert floor.max() < bound["floor"] and sides.max() < bound["floor"]
    mass = 4 / 3 * math.pi * r ** 3     # fix pour's mass for density 1, in 2D as in 3D
    kinetic = 0.5 * (mass * (atoms["vx"] ** 2 + atoms["vy"] ** 2)).sum()
    fallen = (mass * G * (32.0 - atoms["y"])).sum()
    print(f"kinetic energy {kinetic:.3g} of {fallen:.3g} fallen through")
    assert kinetic < 0.01 * fallen


def test_granregion_box_holds_its_spheres_while_it_turns(tmp_path):
    """examples/granregion/in.granregion.box.mn, 1000 steps a stage: 100 spheres poured into
    a box region, which is deleted and defined again turning about z, at rest, turning about
    (1, 1, 1), at rest. Every sphere stays inside the container (centres at least a radius
    less an impact's overlap from each face; the original's `thermo_modify lost ignore` would
    drop one that left the box) through the turns."""
    run = run_example("granregion/in.granregion.box.mn", tmp_path, steps=1000)
    atoms = run.atoms()
    assert len(atoms["id"]) == 100
    bound = impact_bound(7639.4, 6.0)["floor"]
    inside = np.max([np.abs(atoms[c]) for c in ("x", "y", "z")], axis=0)
    print(f"farthest centre from the middle, per axis: {inside.max():.4f} (wall at 6, radius "
          f"0.5, bound {bound:.3g})")
    assert inside.max() < 6.0 - 0.5 + bound


def test_drum_turning_lifts_its_pile_up_the_rising_side(tmp_path):
    """examples/drum/in.drum.mn: the pile settled in the drum at rest has its centre of mass on
    the axis's vertical (|x_cm| < 0.02 R, the lattice start is symmetric); a quarter turn at
    Omega = 0.1 about +y carries it up the side where the wall rises (-x: the wall's velocity
    Omega x r at the bottom points to -x), by more than 0.05 R (a half-filled drum's surface at
    a repose angle alpha puts it at -4R/(3 pi) sin(alpha), -0.18 R at 25 degrees). A wall
    without the rotating region's velocity would leave the pile where it was."""
    turning = run_example("drum/in.drum.mn", tmp_path / "turning", turns=0.25).result("drum")
    still = run_example("drum/in.drum.mn", tmp_path / "still", omega=0).result("drum")
    radius = 6.0
    print(f"x_cm at rest {still[0]:.4f}, turning {turning[0]:.4f} (R = {radius})")
    assert turning[3] == still[3] > 100
    assert abs(still[0]) < 0.02 * radius
    assert turning[0] < -0.05 * radius


def test_granregion_funnel_holds_its_spheres_then_runs_them_out(tmp_path):
    """examples/granregion/in.granregion.funnel.mn with 200 spheres and short stages: poured
    into the funnel (a union of an open cone and a cylinder closed at its bottom, z = 0), none
    gets below the bottom or out of the box while it is closed; opened (the cylinder defined
    again with both ends open), most run out through it. A wall that let spheres through its
    cone or its closed bottom would show them below z = 0 in the first count; one that
    counted an open face as a wall would hold them in the second."""
    run = run_example("granregion/in.granregion.funnel.mn", tmp_path, particles=200,
                      pour_steps=2000, settle_steps=60000, discharge_steps=40000)
    settled, discharged = run.result("settled"), run.result("discharged")
    print(f"settled: {settled[0]:.0f} spheres, {settled[1]:.0f} below the bottom; discharged: "
          f"{discharged[1]:.0f} below")
    assert settled == [200, 0]
    assert discharged[0] == 200 and discharged[1] > 100
