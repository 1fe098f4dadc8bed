"""LIGGGHTS 3.8's `model mn tangential mn` against the LAMMPS plugin's gran/mn and against the law.

Both engines integrate with velocity Verlet (nve/sphere) and take the force from the same
header (mn_contact.h) with the same kinematics (full radii as lever arms, 2M as mass scale) and
the same arithmetic in the same order, so over a collision they agree to rounding: measured,
every number of every scene here is identical in all the 15 digits the decks print. What could
still differ is the order in which each engine adds up a particle's forces when it has several
contacts, a few ulps a step; AGREEMENT (1e-13 of the scene's scale) allows that and nothing
physical. A wrong mass scale (meff for 2M), a wrong q (a disc's 3 for a sphere's 7/2) or
LIGGGHTS's own lever arms (r - delta/2) change the outcomes at the 1e-3 to 1e-1 level, so the
agreement rules them out; each test also checks the outcome against the law's own numbers,
which rules out the two engines being wrong the same way."""
import math
import re

import numpy as np
import pytest

from granmn_run import law, restitution_error_bound
from liggghts_decks import (LIGGGHTS, Particle, Scene, data_file, liggghts_deck, outcome,
                            run_both, run_liggghts, run_scene_liggghts, run_scene_on_ranks)
from postprocess.io import COUNTER_COLUMNS

pytestmark = pytest.mark.skipif(not LIGGGHTS, reason="LIGGGHTS was not built (GRANMN_LIGGGHTS unset)")

AGREEMENT = 1e-13
KN, E, BETA = 2e5, 0.7, 0.7

# a square of two triangles in the plane z = 0, the sphere of test_wall_impact over the first
PLANE_STL = "solid plane\n" + "".join(
    "facet normal 0 0 1\nouter loop\n" + "".join(f"vertex {x} {y} 0\n" for x, y in tri)
    + "endloop\nendfacet\n" for tri in (((-10, -10), (10, -10), (10, 10)),
                                        ((-10, -10), (10, 10), (-10, 10)))) + "endsolid plane\n"
MESH_WALL = ("fix cad all mesh/surface file plane.stl type 1\n"
             "fix floor all wall/gran model mn tangential mn mesh n_meshes 1 meshes cad\n")


def assert_same(theirs, ours, scale):
    """Every number of every particle's state equal within AGREEMENT of the scene's scale."""
    a, b = np.array(theirs.states), np.array(ours.states)
    worst = np.max(np.abs(a - b))
    print(f"largest difference LIGGGHTS - gran/mn: {worst:.3g} (scale {scale:g})")
    assert worst <= AGREEMENT * scale, f"LIGGGHTS {a.tolist()}\ngran/mn  {b.tolist()}"


def sphere_law():
    return law(KN, E, BETA, shape="sphere")


@pytest.mark.parametrize("masses", [(1.0, 1.0), (1.0, 0.3)], ids=["equal", "unequal"])
def test_head_on(tmp_path, masses):
    """Two spheres head-on: the rebound gives e whatever the masses and sizes (the 2M mass scale
    makes the relative motion mass-free; meff in its place halves stiffness and damping, and
    e = 0.7 would come out about 0.78), and both engines the same numbers."""
    c = sphere_law()
    dt = c["tau_c"] / 100
    p1 = Particle((-0.505, 0.0, 0.0), v=(0.5, 0.0, 0.0), diameter=1.0, mass=masses[0])
    p2 = Particle((0.455, 0.0, 0.0), v=(-0.5, 0.0, 0.0), diameter=0.9, mass=masses[1])
    scene = Scene([p1, p2], dt=dt, steps=1000, kn=KN, e=E, beta=BETA)
    theirs, ours = run_both(scene, tmp_path)
    assert_same(theirs, ours, 1.0)
    v_after = theirs.states[1][3] - theirs.states[0][3]
    bound = restitution_error_bound(E, dt / c["tau_c"])
    assert v_after / 1.0 == pytest.approx(E, abs=bound)


def test_oblique_with_spin(tmp_path):
    """An oblique impact of two spinning spheres, sticking (mu = 10) and sliding (mu = 0.1) with
    the literal u_t and with the cut-back one: the tangential law (u_t kept in the tangent
    plane, capped, cut back) is the plugin's in all three, to rounding. (The plugin's 3D
    tangential restitution beta is checked against the law in tests/lammps/test_three_d.py.)"""
    c = sphere_law()
    dt = c["tau_c"] / 100
    spins = []
    for name, mu, cutback in (("stick", 10.0, False), ("slide", 0.1, False),
                              ("slide_cutback", 0.1, True)):
        p1 = Particle((-0.505, 0.0, 0.0), v=(0.5, 0.2, -0.1), omega=(0.3, -0.4, 0.6))
        p2 = Particle((0.505, 0.01, 0.0), v=(-0.5, -0.2, 0.1), omega=(-0.2, 0.5, 0.1))
        scene = Scene([p1, p2], dt=dt, steps=1000, kn=KN, e=E, beta=BETA, mu=mu,
                      coulomb_cutback=cutback)
        theirs, ours = run_both(scene, tmp_path / name)
        assert_same(theirs, ours, 1.0)
        spins.append(np.array(theirs.states[0][6:9]))
    # the three laws differ: the tangential part was exercised in each
    assert np.linalg.norm(spins[0] - spins[1]) > 1e-3
    assert np.linalg.norm(spins[1] - spins[2]) > 1e-6


def test_wall_impact(tmp_path):
    """A sphere dropped without gravity onto a primitive plane wall: e_w and the wall's mass
    scale m_i (2M there would give the binary e instead), both engines alike."""
    c = sphere_law()
    dt = c["tau_w"] / 100
    scene = Scene([Particle((3.0, -3.0, 0.51), v=(0.1, 0.0, -0.5), omega=(0.0, 0.2, 0.0))],
                  dt=dt, steps=int(0.1 / dt), kn=KN, e=E, beta=BETA, wall=True)
    theirs, ours = run_both(scene, tmp_path)
    assert_same(theirs, ours, 1.0)
    vz = theirs.states[0][5]
    assert vz / 0.5 == pytest.approx(c["e_w"], abs=restitution_error_bound(c["e_w"], 0.01))
    assert abs(vz / 0.5 - E) > 0.05            # the wall's e_w is not the binary e

    # the same impact on a mesh wall (two triangles, LIGGGHTS's fix mesh/surface), away from
    # their shared edge: the contact is the primitive wall's
    (tmp_path / "mesh").mkdir()
    (tmp_path / "mesh" / "plane.stl").write_text(PLANE_STL)
    mesh = run_scene_liggghts(scene, tmp_path / "mesh", wall=MESH_WALL)
    assert_same(outcome(mesh[1], 1), theirs, 1.0)


def test_discs_in_2d(tmp_path):
    """dimension 2: LIGGGHTS's nve/sphere integrates discs (I = m r^2/2), and the model derives
    the law for q = 3, as gran/mn does with nve/sphere disc: an oblique impact with spin onto
    the wall and between two discs agrees."""
    c = law(KN, E, BETA)
    dt = c["tau_c"] / 100
    p1 = Particle((-0.505, 0.51, 0.0), v=(0.5, -0.1, 0.0), omega=(0.0, 0.0, 0.7))
    p2 = Particle((0.505, 0.51, 0.0), v=(-0.5, -0.3, 0.0), omega=(0.0, 0.0, -0.2))
    scene = Scene([p1, p2], dt=dt, steps=3000, kn=KN, e=E, beta=BETA, mu=0.3, dimension=2,
                  wall=True)
    theirs, ours = run_both(scene, tmp_path)
    assert_same(theirs, ours, 1.0)


def test_rolling_down_a_plane(tmp_path):
    """A sphere on a plane tilted by theta (gravity tilted), sticking (mu = 1 > 2/7 tan theta):
    it rolls with acceleration 5/7 g sin(theta) (a disc's 2/3, or sliding's g (sin - mu cos),
    are 7 % and more off). The tangential spring's start-up ringing decays with beta; the
    acceleration is fitted over the last two thirds, where it has decayed by beta^(t/tau)."""
    theta = math.radians(20.0)
    g = 1.0
    c = sphere_law()
    dt = c["tau_w"] / 50
    overlap = g * math.cos(theta) / KN           # resting overlap against the wall, m_i k_n
    scene = Scene([Particle((0.0, 0.0, 0.5 - overlap))], dt=dt, steps=int(20.0 / dt), kn=KN,
                  e=E, beta=BETA, mu=1.0, wall=True,
                  gravity=(g, math.sin(theta), 0.0, -math.cos(theta)),
                  sample_every=int(0.5 / dt))
    _, text = run_scene_liggghts(scene, tmp_path)
    samples = np.array(outcome(text, 1).samples)
    late = samples[len(samples) // 3:]
    slope = np.polyfit(late[:, 0], late[:, 1], 1)[0]
    print(f"rolling acceleration {slope:.9f} against 5/7 g sin = {5 / 7 * g * math.sin(theta):.9f}")
    assert slope == pytest.approx(5 / 7 * g * math.sin(theta), rel=1e-3)
    # rolling without slip: v = r omega (omega about +y for motion along +x)
    assert late[-1, 1] == pytest.approx(0.5 * late[-1, 2], rel=1e-3)


def test_counters_as_the_plugins(tmp_path):
    """fix contacts/mn in LIGGGHTS counts as the plugin's does: spheres falling onto a frozen
    sphere (fix freeze; the plugin's wall_types 2), a plane wall and each other, with
    multiple contacts; the seven sums (contacts begun with particles and with the boundary,
    time touching each, time with two or more, contacts now, the window) are equal. A
    frozen sphere counted as a particle, a wall contact missed, a contact begun counted at
    every step or a time counted at the setup would each change them by whole contacts or
    steps."""
    c = sphere_law()
    dt = c["tau_c"] / 50
    spheres = [Particle((0.0, 0.0, 0.5), fixed=True),
               Particle((0.3, 0.0, 1.6), omega=(0.0, 1.0, 0.0)),
               Particle((-0.4, 0.2, 2.8)),
               Particle((1.2, 0.1, 0.55), v=(-0.2, 0.0, 0.0), diameter=0.9, mass=0.7)]
    scene = Scene(spheres, dt=dt, steps=int(3.0 / dt), kn=KN, e=E, beta=BETA, mu=0.5,
                  wall=True, gravity=(1.0, 0.0, 0.0, -1.0), counters=True)
    theirs, ours = run_both(scene, tmp_path)
    print("counters LIGGGHTS", theirs.counters, "\ncounters gran/mn ", ours.counters)
    assert_same(theirs, ours, 3.0)
    # LIGGGHTS's global vector: the counters' sums, the window's length
    counters = dict(zip((*COUNTER_COLUMNS, "window"), theirs.counters))
    assert len(theirs.counters) == len(COUNTER_COLUMNS) + 1
    assert counters["begun_disk"] >= 2 and counters["begun_boundary"] >= 3 and \
        counters["time_multiple"] > 0                                           # all kinds seen
    assert counters["window"] == pytest.approx(scene.steps * dt, rel=1e-12)
    assert theirs.counters == pytest.approx(ours.counters, rel=1e-12, abs=1e-12)


def test_deep_overlap_is_said(tmp_path):
    """Two spheres that start overlapping by 0.2 of the smaller radius (placed so): both engines
    warn at the run's start, naming the atoms, the overlap, its fraction and the speed the
    spring gives them, 0.1 sqrt(2 k_n) = 63; at 0.08 of the radius, below the stated 0.1,
    neither does."""
    said = "pair(s) of particles overlap by more than 0.1 of the smaller radius at the start of the run"
    for overlap, deep in ((0.1, True), (0.04, False)):
        centre = 0.5 - overlap / 2
        scene = Scene([Particle((-centre, 0.0, 0.0)), Particle((centre, 0.0, 0.0))],
                      dt=sphere_law()["tau_c"] / 100, steps=10, kn=KN, e=E, beta=BETA)
        theirs, ours = run_both(scene, tmp_path / str(overlap))
        for engine, output in (("model mn", theirs.output), ("pair_style gran/mn", ours.output)):
            warnings = [line for line in output.splitlines() if said in line]
            print(engine, warnings)
            if not deep:
                assert not warnings
                continue
            assert len(warnings) == 1, output[-3000:]
            assert warnings[0].startswith(f"WARNING: {engine}: 1 {said}; the deepest, atoms 1 "
                                          "and 2, by 0.1 (0.2 of radius 0.5): released, it "
                                          "drives them apart at up to 63.2"), warnings[0]


def test_deep_overlap_counted_once_on_two_ranks(tmp_path):
    """Two overlapping pairs, each across the two ranks' boundary (y = 0; newton off: both
    ranks hold each pair): one warning, of 2 pairs (4 if each rank counted its own), the
    deepest (by 0.2, against a sphere of radius 0.3) named, on one rank and on two alike."""
    scene = Scene([Particle((0.0, -0.45, 0.0)), Particle((0.0, 0.45, 0.0)),
                   Particle((10.0, -0.4, 0.0)), Particle((10.0, 0.2, 0.0), diameter=0.6)],
                  dt=sphere_law()["tau_c"] / 100, steps=10, kn=KN, e=E, beta=BETA)
    said = [[line.split(" (")[0] for line in run_scene_on_ranks(scene, tmp_path, ranks)
             .splitlines() if "overlap by more than" in line] for ranks in (1, 2)]
    print(said)
    assert said[0] == said[1] and len(said[0]) == 1
    assert "model mn: 2 pair(s)" in said[0][0] and "atoms 3 and 4, by 0.2" in said[0][0]


def test_neighbour_lists_as_liggghts_own(tmp_path):
    """model mn sees a contact's end without widening LIGGGHTS's neighbour lists: a row of
    spheres 1.2 apart, beyond the radii's sum plus the skin of 0.1, gives lists of no pairs,
    as for LIGGGHTS's own hooke/stiffness (a contact distance factor of 1 + skin/r, as the
    models once registered to see every listed pair, would list each neighbouring pair)."""
    row = [Particle((1.2 * k, 0.0, 0.0)) for k in range(5)]
    scene = Scene(row, dt=sphere_law()["tau_c"] / 100, steps=1, kn=KN, e=E, beta=BETA)
    hooke = ("".join(f"fix {name} all property/global {name} peratomtypepair 1 1.0\n"
                     for name in ("kn", "kt", "gamman", "gammat"))
             + "pair_style gran model hooke/stiffness tangential history ")
    pairs = {}
    for model in ("mn", "hooke/stiffness"):
        deck = liggghts_deck(scene)
        if model != "mn":
            deck = deck.replace("pair_style gran model mn tangential mn ", hooke)
        _, output = run_liggghts(deck, tmp_path / model.replace("/", "_"), data_file(scene))
        pairs[model] = int(re.search(r"Total # of neighbors = (\d+)", output).group(1))
    assert pairs["mn"] == pairs["hooke/stiffness"] == 0, pairs
