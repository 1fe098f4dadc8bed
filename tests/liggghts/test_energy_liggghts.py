"""Where a collision's energy goes in LIGGGHTS 3.8 (`model mn tangential mn energy on`, fix
contacts/mn energy yes) against the LAMMPS plugin (gran/mn, fix contacts/mn energy yes) on the
impacts of test_mn_model.py, and against the law.

Both engines take the force and its energy booking from the same headers (mn_contact.h,
mn_energy.h) and integrate with velocity Verlet: their trajectories agree to rounding
(test_mn_model.py: every state within 1e-13). What differs is the order of operations: LIGGGHTS
books an ended contact's last half step after its pass (the plugin inside it) and each engine
sums a particle's shares in its own order. Each energy is a sum over ~10^3 steps of terms no
larger than the kinetic energy K0, each rounded at ~1e-16, and the decks print 15 digits:
AGREEMENT = 1e-12 K0 is ten times that. What it rules out is at 1e-4 K0 and far above: a
missing tangential dashpot or sliding term (the whole of dissipated_sticking or _sliding, ~0.1
K0), a sign error in a booked power, the last force's second half of an ended contact not
booked (dt/2 F v, ~1e-3 K0 at dt = tau_c/100), a frozen particle's share kept (half of a
contact's energies lost from the mobile group), LIGGGHTS's own lever arms (r - delta/2)."""

import numpy as np
import pytest

from granmn_run import law, restitution_error_bound
from liggghts_decks import LIGGGHTS, Particle, Scene, outcome, run_both, run_scene_on_ranks

pytestmark = pytest.mark.skipif(not LIGGGHTS, reason="LIGGGHTS was not built (GRANMN_LIGGGHTS unset)")

KN, E, BETA = 2e5, 0.7, 0.7
AGREEMENT = 1e-12
DISSIPATED = ("dissipated_normal", "dissipated_sticking", "dissipated_sliding")


def kinetic(particles, states, dimension=3):
    """Translational and rotational kinetic energy; I = 2/5 m r^2 (spheres) or m r^2/2 (discs,
    LIGGGHTS's nve/sphere in 2D and nve/sphere disc)."""
    shape = 0.4 if dimension == 3 else 0.5
    total = 0.0
    for p, s in zip(particles, states):
        if p.fixed:
            continue
        v, w = np.array(s[3:6]), np.array(s[6:9])
        total += 0.5 * p.mass * v @ v + 0.5 * shape * p.mass * (p.diameter / 2) ** 2 * w @ w
    return total


def initial_states(particles):
    return [[*p.x, *p.v, *p.omega] for p in particles]


def check_agreement(scene, tmp_path, scale=None):
    """Both engines' energies of the scene agree within AGREEMENT of K0 (or of `scale`); without
    gravity the energies at the end close LIGGGHTS's budget: K0 = K + stored + dissipated to
    rounding (velocity Verlet's booking is the integrator's own work: with no force acting at the
    start nor at the end it leaves nothing over). (LIGGGHTS's outcome, K0.)"""
    theirs, ours = run_both(scene, tmp_path)
    k0 = kinetic(scene.particles, initial_states(scene.particles), scene.dimension)
    print("LIGGGHTS", theirs.energies, "\ngran/mn ", ours.energies, "\nK0", k0)
    worst = max(abs(theirs.energies[name] - ours.energies[name]) for name in theirs.energies)
    print(f"largest difference LIGGGHTS - gran/mn: {worst:.3g}")
    assert worst <= AGREEMENT * (scale or k0), (theirs.energies, ours.energies)
    if scene.gravity:
        return theirs, k0
    k = kinetic(scene.particles, theirs.states, scene.dimension)
    dissipated = sum(theirs.energies[name] for name in DISSIPATED)
    print(f"budget: K0 - K - stored - dissipated = {k0 - k - theirs.energies['stored'] - dissipated:.3g}")
    assert k + theirs.energies["stored"] + dissipated == pytest.approx(k0, abs=AGREEMENT * k0)
    assert theirs.energies["work_in_flight"] == 0.0
    return theirs, k0


@pytest.mark.parametrize("masses", [(1.0, 1.0), (1.0, 0.3)], ids=["equal", "unequal"])
def test_head_on_loses_one_minus_e_squared(tmp_path, masses):
    """Two spheres head-on at relative speed 1: the normal force dissipates (1 - e^2) of the
    kinetic energy of the normal motion, (1/2) mu_r 1^2 with mu_r the reduced mass, e the law's
    to velocity Verlet's error on a restitution (restitution_error_bound; 2 e that on 1 - e^2),
    and (1 - e_measured^2) of it to rounding by the budget; nothing tangential (no tangential
    motion: rounding only).
    A dashpot booked at twice or half its work, or the spring's stored energy counted as lost,
    is off by 0.1 and more."""
    c = law(KN, E, BETA, shape="sphere")
    dt = c["tau_c"] / 100
    p1 = Particle((-0.505, 0.0, 0.0), v=(0.5, 0.0, 0.0), diameter=1.0, mass=masses[0])
    p2 = Particle((0.455, 0.0, 0.0), v=(-0.5, 0.0, 0.0), diameter=0.9, mass=masses[1])
    scene = Scene([p1, p2], dt=dt, steps=1000, kn=KN, e=E, beta=BETA, energy=True)
    theirs, k0 = check_agreement(scene, tmp_path)
    normal = 0.5 * masses[0] * masses[1] / sum(masses) * 1.0 ** 2
    e_measured = theirs.states[1][3] - theirs.states[0][3]
    lost = theirs.energies["dissipated_normal"] / normal
    print(f"dissipated / normal kinetic energy {lost:.12f}; 1 - e^2 = {1 - E ** 2}, "
          f"1 - e_measured^2 = {1 - e_measured ** 2:.12f}")
    assert lost == pytest.approx(1 - E ** 2, abs=2 * E * restitution_error_bound(E, dt / c["tau_c"]))
    assert lost == pytest.approx(1 - e_measured ** 2, abs=AGREEMENT * k0 / normal)
    for name in ("dissipated_sticking", "dissipated_sliding"):
        assert abs(theirs.energies[name]) <= AGREEMENT * k0, name


@pytest.mark.parametrize("mu, cutback", [(10.0, False), (0.1, False), (0.1, True)],
                         ids=["stick", "slide", "slide_cutback"])
def test_oblique_with_spin(tmp_path, mu, cutback):
    """The oblique impact of two spinning spheres of test_mn_model.py, sticking and sliding with
    the literal and the cut-back u_t: each energy agrees, the budget closes, and the tangential
    force took its share: over 1 % of K0 (the sliding part where it slides, none where it
    sticks)."""
    c = law(KN, E, BETA, shape="sphere")
    p1 = Particle((-0.505, 0.0, 0.0), v=(0.5, 0.2, -0.1), omega=(0.3, -0.4, 0.6))
    p2 = Particle((0.505, 0.01, 0.0), v=(-0.5, -0.2, 0.1), omega=(-0.2, 0.5, 0.1))
    scene = Scene([p1, p2], dt=c["tau_c"] / 100, steps=1000, kn=KN, e=E, beta=BETA, mu=mu,
                  coulomb_cutback=cutback, energy=True)
    theirs, k0 = check_agreement(scene, tmp_path)
    tangential = theirs.energies["dissipated_sticking"] + theirs.energies["dissipated_sliding"]
    assert tangential > 0.01 * k0
    if mu < 1.0:
        assert theirs.energies["dissipated_sliding"] > 0.01 * k0
    else:
        assert theirs.energies["dissipated_sliding"] == 0.0


def test_discs_in_2d(tmp_path):
    """Two spinning discs in dimension 2 (the 2D booking: f_t a component along t)."""
    c = law(KN, E, BETA)
    p1 = Particle((-0.505, 0.51, 0.0), v=(0.5, -0.1, 0.0), omega=(0.0, 0.0, 0.7))
    p2 = Particle((0.505, 0.51, 0.0), v=(-0.5, -0.3, 0.0), omega=(0.0, 0.0, -0.2))
    scene = Scene([p1, p2], dt=c["tau_c"] / 100, steps=1000, kn=KN, e=E, beta=BETA, mu=0.3,
                  dimension=2, energy=True)
    theirs, k0 = check_agreement(scene, tmp_path)
    assert abs(theirs.energies["dissipated_sticking"]) > 1e-3 * k0


def test_on_a_frozen_sphere(tmp_path):
    """A spinning sphere thrown without gravity at a frozen sphere of the same mass (fix freeze;
    the plugin's wall_types 2): the contact's energies are all the mobile sphere's (LIGGGHTS's
    meff cannot tell which of two equal masses is frozen: the fix's group can), its mass scale
    m_i, and both engines agree."""
    c = law(KN, E, BETA, shape="sphere")
    spheres = [Particle((0.0, 0.0, 0.0), fixed=True),
               Particle((0.3, 0.0, 1.02), v=(0.0, 0.1, -0.5), omega=(0.0, 1.0, 0.0))]
    dt = c["tau_w"] / 100
    scene = Scene(spheres, dt=dt, steps=int(0.6 / dt), kn=KN, e=E, beta=BETA, mu=0.5,
                  energy=True)
    theirs, k0 = check_agreement(scene, tmp_path)
    assert sum(theirs.energies[name] for name in DISSIPATED) > 0.1 * k0


def heap():
    """Four spheres above a floor of nine frozen spheres (the floor across y = 0, where two
    ranks split the box), and the potential energy they fall through to the floor's top."""
    c = law(KN, E, BETA, shape="sphere")
    floor = [Particle((x, y, 0.0), fixed=True) for x in (-1.0, 0.0, 1.0) for y in (-1.0, 0.0, 1.0)]
    falling = [Particle((0.3, 0.1, 1.6), omega=(0.0, 1.0, 0.0)),
               Particle((-0.4, 0.2, 2.8)),
               Particle((0.6, -0.5, 4.0), v=(-0.2, 0.0, 0.0), diameter=0.9, mass=0.7),
               Particle((-0.2, -0.4, 5.2), omega=(0.5, 0.0, 0.3))]
    dt = c["tau_c"] / 50
    scene = Scene(floor + falling, dt=dt, steps=int(3.0 / dt), kn=KN, e=E, beta=BETA, mu=0.5,
                  gravity=(1.0, 0.0, 0.0, -1.0), energy=True)
    return scene, sum(p.mass * (p.x[2] - 1.0) for p in falling)


def test_a_heap_on_frozen_spheres(tmp_path):
    """Four spheres falling under gravity onto a floor of nine frozen spheres and onto each
    other, for 3 time units: bounces on the floor and off each other, sliding, contacts that
    end and begin again, and neighbour lists rebuilt under them (81 times; LIGGGHTS hands a pair's history on
    at a rebuild, maybe seen from the other particle: a last force whose normal or tangential
    part kept its sign there would book its second half with the wrong sign). The energies
    agree within AGREEMENT of the potential energy the spheres fall through (m g h, h ~ 2.6);
    the dissipation is most of it."""
    scene, fall = heap()
    theirs, _ = check_agreement(scene, tmp_path, scale=fall)
    assert sum(theirs.energies[name] for name in DISSIPATED) > 0.5 * fall
    assert theirs.energies["dissipated_sliding"] != 0.0


def test_a_heap_on_two_ranks(tmp_path):
    """The heap in LIGGGHTS on one rank and on two (newton off: a pair across the ranks is
    computed on both, each booking its own particle's share): the same energies within
    AGREEMENT of the fall's energy. A share booked on both ranks, or on neither, changes them by
    a contact's whole energy."""
    scene, fall = heap()
    energies = [outcome(run_scene_on_ranks(scene, tmp_path, ranks), len(scene.particles)).energies
                for ranks in (1, 2)]
    print("one rank", energies[0], "\ntwo ranks", energies[1])
    for name in energies[0]:
        assert energies[1][name] == pytest.approx(energies[0][name], abs=AGREEMENT * fall), name
    assert sum(energies[1][name] for name in DISSIPATED) > 0.5 * fall


@pytest.mark.parametrize("dimension", [3, 2])
def test_contacts_across_neighbour_list_builds(tmp_path, dimension):
    """A sphere (a disc in 2D) set on a frozen one off its top, under gravity, rolling and bouncing off it
    (13 contacts, touching 0.7 of 1.5 time units), while LIGGGHTS builds its neighbour lists at
    every step and sorts the atoms every 10 steps. A build drops the history of a pair found
    apart: a contact that ended at that step is booked from fix contact/history's copies, each
    seen from its atom; a sort lists the pair from the other particle, its history seen from
    there (the last force's normal and, in 3D, its tangential force change sign; f_n and the
    energies do not). Measured: without the copies (every end at a build missing its last half
    step) the energies differ from the plugin's by 5e-5, with the signs not changed by 1e-4;
    they agree to the last printed digit."""
    c = law(KN, E, BETA, shape="sphere" if dimension == 3 else "disc")
    dt = c["tau_c"] / 50
    top = (0.1, 0.05, 1.0 - 1.0 / KN) if dimension == 3 else (0.1, 1.0 - 1.0 / KN, 0.0)
    down = (1.0, 0.0, 0.0, -1.0) if dimension == 3 else (1.0, 0.0, -1.0, 0.0)
    spheres = [Particle(top), Particle((0.0, 0.0, 0.0), fixed=True)]
    scene = Scene(spheres, dt=dt, steps=int(1.5 / dt), kn=KN, e=E, beta=BETA, mu=0.5,
                  dimension=dimension, gravity=down, energy=True, counters=True,
                  extra="neigh_modify every 1 delay 0 check no\natom_modify sort 10 0.5\n")
    theirs, _ = check_agreement(scene, tmp_path, scale=1.0)
    assert theirs.counters[1] >= 10                     # contacts begun with the frozen sphere
    assert sum(theirs.energies[n] for n in DISSIPATED) > 1e-3
