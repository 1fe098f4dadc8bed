"""pair_style gran/mn and fix wall/gran/mn in dimension 3 (solid spheres, docs/model.md section
3.2): the law derived with q = 7/2 gives the requested e, beta and tau_c on an oblique spinning
impact of unequal spheres, and e_w, tau_w (and, with beta = e, the tangential restitution e_w)
on a plane and on a fixed bump.

Tolerances (granmn_run.restitution_error_bound): velocity Verlet's first-order error of a
restitution, 3 (1 + e) |ln e| dt/tau + (dt/tau)^2, plus for the tangential restitution
2 beta |ln beta| dt/tau (its oscillation is cut where the normal contact ends, up to a step
off) as in the 2D tests, plus 1e-3 where the line of centres turns during the contact (a pair,
a bump: by ~1e-4 rad at kn = 256e5). At dt = tau/100 the bound on beta = 0.7 is ~0.024: the
disc mapping (q = 3) on spheres gives 0.620 (docs/model.md 3.1), outside it."""
import numpy as np
import pytest

from collision_decks import contact_interval
from granmn_run import HEADER, PLUGIN, law, restitution_error_bound, run_lammps

HEADER_3D = HEADER.format(plugin=PLUGIN).replace("dimension 2", "dimension 3")
SPHERE_DENSITY = 6 / np.pi    # a sphere of diameter 1 has mass 1
KN = 256e5    # stiff: the line of centres turns little during a contact
AXIS = np.array([0.8, 0.36, 0.48])    # |AXIS| = 1


def sphere_kt(kn, e, beta):
    """k_t for solid spheres (q = 7/2, docs/model.md 3.1), as the header derives it."""
    return law(kn, e, beta, "sphere")["kt"]


def _vector(values):
    return " ".join(repr(float(v)) for v in values)


def _relative(x1, x2, v1, v2, w1, w2, r1, r2):
    """n (from 2 to 1), v_n and the vector v_t of the contact points (docs/model.md 3.2)."""
    n = (x1 - x2) / np.linalg.norm(x1 - x2)
    vij = v1 - v2 + np.cross(n, r1 * w1 + r2 * w2)
    v_n = n @ vij
    return n, v_n, vij - v_n * n


def _atoms_3d(run):
    a = run.atoms()
    order = np.argsort(a["id"])
    pick = lambda *names: np.column_stack([a[n][order] for n in names])
    return pick("x", "y", "z"), pick("vx", "vy", "vz"), pick("omegax", "omegay", "omegaz")


def _styles(material, dt, extra=""):
    kn, e, beta, mu = material
    return f"""
pair_style gran/mn kn {kn!r} e {e!r} beta {beta!r} mu {mu!r} {extra}
pair_coeff * *
timestep {dt!r}
fix integrate mobile nve/sphere
variable st equal step
"""


def two_spheres(material, dt, tau, pre_steps=10, phase=0.5):
    """Spheres of radii 0.5 and 0.35 meeting along AXIS at normal speed 1 (contact `phase` of a
    step after step `pre_steps`), with tangential velocities and spins on three axes."""
    r1, r2 = 0.5, 0.35
    gap = (pre_steps + phase) * dt
    x1, x2 = -(r1 + gap / 2) * AXIS, (r2 + gap / 2) * AXIS
    v1, v2 = np.array([0.5 * 0.8 + 0.05, 0.5 * 0.36 + 0.1, 0.5 * 0.48 - 0.15]), \
        np.array([-0.5 * 0.8, -0.5 * 0.36 + 0.05, -0.5 * 0.48 + 0.08])
    v1 -= ((v1 - v2) @ AXIS - 1.0) * AXIS / 2    # normal approach speed exactly 1
    w1, w2 = np.array([0.3, -0.7, 0.4]), np.array([-0.5, 0.2, 0.9])
    steps = pre_steps + int(np.ceil(tau / dt)) + 20
    deck = f"""
region box block -5 5 -5 5 -5 5
create_box 1 box
create_atoms 1 single {_vector(x1)}
create_atoms 1 single {_vector(x2)}
set atom 1 diameter {2 * r1!r}
set atom 2 diameter {2 * r2!r}
set type 1 density {SPHERE_DENSITY!r}
velocity all set 0 0 0
set atom 1 vx {v1[0]!r} vy {v1[1]!r} vz {v1[2]!r} omega {_vector(w1)}
set atom 2 vx {v2[0]!r} vy {v2[1]!r} vz {v2[2]!r} omega {_vector(w2)}
group mobile type 1
{_styles(material, dt)}
variable dist equal sqrt((x[1]-x[2])^2+(y[1]-y[2])^2+(z[1]-z[2])^2)
fix trace all print 1 "${{st}} ${{dist}}" file trace.txt screen no
thermo 0
run {steps}
write_dump all custom final.txt id x y z vx vy vz omegax omegay omegaz modify sort id format float %.17g
"""
    before = _relative(x1, x2, v1, v2, w1, w2, r1, r2)
    masses = np.array([(2 * r1) ** 3, (2 * r2) ** 3])
    return deck, r1 + r2, before, (r1, r2), masses, masses @ np.array([v1, v2])


def sphere_on_boundary(material, dt, tau, boundary, pre_steps=10, phase=0.5):
    """A sphere of diameter 1 falling at normal speed 1 with a sideways velocity and spins on
    three axes onto the plane z = 0 (fix wall/gran/mn zplane) or onto a fixed sphere of
    diameter 1 below it (a wall_types atom)."""
    gap = (pre_steps + phase) * dt
    v, w = np.array([0.4, -0.2, -1.0]), np.array([1.5, 0.8, -2.0])
    if boundary == "wall":
        atoms = f"create_atoms 1 single 0 0 {0.5 + gap!r}\n"
        styles = _styles(material, dt) + "fix floor mobile wall/gran/mn zplane 0.0 NULL\n"
        contact = 0.5
    else:
        atoms = f"create_atoms 2 single 0 0 0\ncreate_atoms 1 single 0 0 {1.0 + gap!r}\n"
        styles = _styles(material, dt, "wall_types 2")
        contact = 1.0
    steps = pre_steps + int(np.ceil(tau / dt)) + 20
    deck = f"""
boundary p p f
region box block -5 5 -5 5 -5 5
create_box 2 box
{atoms}
set type * diameter 1.0
set type * density {SPHERE_DENSITY!r}
velocity all set 0 0 0
group mobile type 1
set group mobile vx {v[0]!r} vy {v[1]!r} vz {v[2]!r} omega {_vector(w)}
{styles}
variable mobile_id equal count(all)
variable height equal z[v_mobile_id]
fix trace all print 1 "${{st}} ${{height}}" file trace.txt screen no
thermo 0
run {steps}
write_dump all custom final.txt id x y z vx vy vz omegax omegay omegaz modify sort id format float %.17g
"""
    n = np.array([0.0, 0.0, 1.0])
    vij = v + np.cross(n, 0.5 * w)
    return deck, contact, (n, vij @ n, vij - (vij @ n) * n)


def _restitutions(before, after):
    (_, vn0, vt0), (_, vn1, vt1) = before, after
    return -vn1 / vn0, -(vt1 @ vt0) / (vt0 @ vt0)


@pytest.mark.parametrize("e, beta", [(0.7, 0.7), (0.9, 0.5), (0.5, 0.9)])
def test_oblique_spinning_impact_of_unequal_spheres(tmp_path, e, beta):
    """Sticking (mu = 1e6): e, beta and tau_c as requested, at dt = tau_c/100 and /200."""
    ref = law(KN, e, beta)
    tau = ref["tau_c"]
    for fraction in (1 / 100, 1 / 200):
        dt = tau * fraction
        deck, contact, before, (r1, r2), masses, momentum = two_spheres((KN, e, beta, 1e6), dt,
                                                                         tau)
        run = run_lammps(HEADER_3D + deck, tmp_path / f"dt{fraction}", header=False)
        assert "3D: solid spheres, q = 7/2" in run.output
        x, v, w = _atoms_3d(run)
        after = _relative(x[0], x[1], v[0], v[1], w[0], w[1], r1, r2)
        e_measured, beta_measured = _restitutions(before, after)
        duration, _, _ = contact_interval(run.table("trace.txt"), contact, dt)
        bound_e = restitution_error_bound(e, fraction) + 1e-3
        bound_beta = (restitution_error_bound(beta, fraction)
                      + 2 * beta * abs(np.log(beta)) * fraction + 1e-3)
        print(f"e={e} beta={beta} dt=tau_c/{1/fraction:.0f}: e {e_measured:.5f} (+-{bound_e:.1e})"
              f" beta {beta_measured:.5f} (+-{bound_beta:.1e}) duration/tau_c {duration/tau:.5f}")
        assert abs(e_measured - e) <= bound_e
        assert abs(beta_measured - beta) <= bound_beta
        assert abs(duration - tau) <= dt
        # the pair's forces are equal and opposite: momentum is kept
        assert np.linalg.norm(masses @ v - momentum) < 1e-12


@pytest.mark.parametrize("boundary", ["wall", "bump"])
@pytest.mark.parametrize("e", [0.5, 0.7, 0.9])
def test_sphere_on_the_boundary_has_e_w_and_tau_w(tmp_path, boundary, e):
    """Mass scale m_i against a plane (zplane) and a fixed bump: the contact lasts tau_w, the
    normal restitution is e_w; with beta = e the sticking tangential mode against the boundary
    is the normal one for the sphere's own q (docs/model.md 3.1), so the tangential
    restitution is e_w too (the disc mapping gives 0.71 for e_w = 0.78 at e = 0.7)."""
    ref = law(KN, e, e)
    tau = ref["tau_w"]
    for fraction in (1 / 100, 1 / 200):
        dt = tau * fraction
        deck, contact, before = sphere_on_boundary((KN, e, e, 1e6), dt, tau, boundary)
        run = run_lammps(HEADER_3D + deck, tmp_path / f"dt{fraction}", header=False)
        x, v, w = _atoms_3d(run)
        mobile = len(x) - 1
        if boundary == "wall":
            n = np.array([0.0, 0.0, 1.0])
            vij = v[mobile] + np.cross(n, 0.5 * w[mobile])
            after = (n, vij @ n, vij - (vij @ n) * n)
            geometry = 0.0
        else:
            after = _relative(x[1], x[0], v[1], v[0], w[1], w[0], 0.5, 0.5)
            geometry = 1e-3
            assert np.all(x[0] == 0.0) and np.all(v[0] == 0.0)    # the bump has not moved
        e_measured, beta_measured = _restitutions(before, after)
        duration, _, _ = contact_interval(run.table("trace.txt"), contact, dt)
        bound = restitution_error_bound(ref["e_w"], fraction) + geometry
        print(f"{boundary} e={e} dt=tau_w/{1/fraction:.0f}: e_w={ref['e_w']:.5f} measured "
              f"{e_measured:.5f}, tangential {beta_measured:.5f} (+-{bound:.1e}) "
              f"duration/tau_w {duration/tau:.5f}")
        assert abs(e_measured - ref["e_w"]) <= bound
        assert abs(beta_measured - ref["e_w"]) <= bound + 2 * e * abs(np.log(e)) * fraction
        assert abs(duration - tau) <= dt


# A 3D pile: 50 spheres (diameters 0.8-1.0) falling onto the floor of a box periodic in x and y,
# fixed bumps on the floor, a ceiling (fix wall/gran/mn zplane), gravity tilted so that the pile
# slides and rolls (mu = 0.5: contacts stick and slide), with fix contacts/mn. Every variant
# starts from one data file (atom IDs as one rank numbers them) and runs PILE_STEPS in two
# runs with a restart file written between them (a run's setup re-evaluates the forces with
# the full-step velocities: two runs are not one run, in 2D as in 3D). As in the 2D
# consistency tests (test_consistency.py), runs that sum forces in other orders agree "to
# rounding": states are compared as (x, v/omega, r w/omega) against 1e-8 (measured: ~1e-13
# with newton off, 0 with shuffled lists); counts exactly. (These runs do not see a history
# handed over with the wrong sign: the rolling test below does.)
PILE_KN = 2e5
PILE_STEPS = 2000
PILE_OMEGA = (2 * PILE_KN) ** 0.5

# periodic in x and y: z holds the floor and the ceiling (walls need a non-periodic dimension);
# given before create_box and read_data (a data file holds none)
PILE_BOUNDARY = "boundary p p f"

PILE_START = f"""
{PILE_BOUNDARY}
region box block 0 5 0 5 -1 8
create_box 2 box
lattice sc 1.0 origin 0.5 0.5 0.5
region pile block 0 5 0 5 0 2 units lattice
create_atoms 1 region pile
lattice none 1.0
create_atoms 2 single 1.0 1.0 -0.45
create_atoms 2 single 3.5 1.0 -0.45
create_atoms 2 single 1.0 3.5 -0.45
create_atoms 2 single 3.5 3.5 -0.45
group mobile type 1
group bumps type 2
variable diameter atom "0.8 + 0.2*((id*7919)%100)/100"
set group mobile diameter v_diameter
set group bumps diameter 1.0
set type * density {SPHERE_DENSITY!r}
velocity mobile create 0.5 4928459 loop geom
write_data start.data
"""

PILE_FIXES = """
fix integrate mobile nve/sphere
fix gravity mobile gravity 1.0 vector 0.3 0.2 -1
fix floor mobile wall/gran/mn zplane 0.0 7.5
fix c mobile contacts/mn
compute contacts mobile contact/atom
compute ncontacts mobile reduce sum c_contacts
thermo_style custom step ke c_ncontacts
thermo 500
"""

PILE_FINAL = ("write_dump mobile custom final.txt id x y z vx vy vz omegax omegay omegaz radius "
              "f_c[1] f_c[2] modify sort id format float %.17g\n"
              "print \"RESULT sums $(f_c[1]) $(f_c[2]) $(f_c[3]) $(f_c[4]) $(f_c[5])\"\n")


@pytest.fixture(scope="module")
def pile_start(tmp_path_factory):
    run = run_lammps(HEADER_3D + PILE_START, tmp_path_factory.mktemp("start"), header=False)
    return run.workdir / "start.data"


def pile_run(start, workdir, newton="on", nprocs=1, shuffle=False, mu=0.5, ghost_velocity="yes",
             extra=""):
    dt = law(PILE_KN, 0.7, 0.7)["tau_c"] / 50
    shuffle_settings = ("atom_modify sort 7 0.5\nneigh_modify every 1 delay 0 check no\n"
                        if shuffle else "")
    deck = f"""
newton {newton}
processors * 1 1
{PILE_BOUNDARY}
comm_modify vel {ghost_velocity}

read_data {start}
{shuffle_settings}group mobile type 1
pair_style gran/mn kn {PILE_KN} e 0.7 beta 0.7 mu {mu} wall_types 2
pair_coeff * *
timestep {dt!r}
{PILE_FIXES}
{extra}
run {PILE_STEPS // 2}
write_restart mid.restart
run {PILE_STEPS // 2}
{PILE_FINAL}"""
    return run_lammps(HEADER_3D + deck, workdir, nprocs=nprocs, header=False)


def pile_state(run):
    a = run.atoms()
    columns = [a[c] for c in ("x", "y", "z")]
    columns += [a[c] / PILE_OMEGA for c in ("vx", "vy", "vz")]
    columns += [a["radius"] * a[c] / PILE_OMEGA for c in ("omegax", "omegay", "omegaz")]
    return np.column_stack(columns), np.column_stack([a["f_c[1]"], a["f_c[2]"]])


def assert_same_pile(run, reference, label):
    """The state to rounding (1e-8, see above), the counts exactly."""
    state, counts = pile_state(run)
    reference_state, reference_counts = pile_state(reference)
    difference = np.abs(state - reference_state).max()
    print(f"{label}: largest difference {difference:.1e}")
    assert difference < 1e-8
    assert np.array_equal(counts, reference_counts)


@pytest.fixture(scope="module")
def pile_reference(pile_start, tmp_path_factory):
    return pile_run(pile_start, tmp_path_factory.mktemp("pile"))


def test_pile_has_lasting_pair_and_wall_contacts(pile_reference):
    state, counts = pile_state(pile_reference)
    print(f"contacts begun: particle {counts[:, 0].sum():.0f}, boundary {counts[:, 1].sum():.0f}")
    assert counts[:, 0].sum() > 100 and counts[:, 1].sum() > 10
    # the pile has fallen onto the floor and touches it
    assert state[:, 2].min() < 0.6
    assert "3D: solid spheres, q = 7/2" in pile_reference.output


@pytest.mark.parametrize("newton, nprocs, shuffle", [("off", 1, False), ("on", 2, False),
                                                     ("off", 2, False), ("on", 1, True)])
def test_pile_the_same_with_newton_ranks_and_shuffled_lists(pile_start, pile_reference, tmp_path,
                                                            newton, nprocs, shuffle):
    """Newton off and two ranks store a contact's history on both atoms' sides and hand it
    over (u_t is a vector: the partner's copy is -u_t); shuffled lists hand contacts between
    the atoms' lists at every step."""
    run = pile_run(pile_start, tmp_path, newton, nprocs, shuffle)
    assert_same_pile(run, pile_reference, f"newton {newton}, {nprocs} ranks, shuffle {shuffle}")
    assert run.result("sums")[:2] == pile_reference.result("sums")[:2]


def test_pile_the_same_to_the_bit_without_comm_modify_vel_yes(pile_start, tmp_path):
    """Without comm_modify vel yes pair_style gran/mn in 3D turns LAMMPS's own sending of the
    ghosts' v and omega on, here between two ranks: the same pile to the bit (a ghost whose
    velocity is not sent keeps zeros or stale values, and its pairs other forces)."""
    by_deck = pile_run(pile_start, tmp_path / "deck", nprocs=2)
    by_pair = pile_run(pile_start, tmp_path / "pair", nprocs=2, ghost_velocity="no")
    assert np.array_equal(pile_state(by_pair)[0], pile_state(by_deck)[0])
    assert np.array_equal(pile_state(by_pair)[1], pile_state(by_deck)[1])


def test_sheared_pile_without_vel_yes_takes_the_boxs_rate_across_the_boundary(pile_start,
                                                                               tmp_path):
    """fix deform remap v adds the box's rate to the velocity of a ghost across the periodic
    boundary, in LAMMPS's own ghost communication only: without comm_modify vel yes the 3D
    pair style turns it on (2D refuses the deck, docs/bad_input.md), so that the pile sheared
    without vel yes is the one with it to the bit (the style's own sending, without the rate,
    refused the deck). The same shear with remap none (no rate for the ghosts, nor for the
    atoms that cross the boundary) ends elsewhere: the rate reaches the pile."""
    shear = "fix shear all deform 1 x erate 0.05 remap {}"
    with_vel = pile_run(pile_start, tmp_path / "yes", extra=shear.format("v"))
    without_vel = pile_run(pile_start, tmp_path / "no", ghost_velocity="no",
                           extra=shear.format("v"))
    assert np.array_equal(pile_state(without_vel)[0], pile_state(with_vel)[0])
    assert np.array_equal(pile_state(without_vel)[1], pile_state(with_vel)[1])
    rate_left_out = pile_run(pile_start, tmp_path / "none", extra=shear.format("none"))
    assert not np.array_equal(pile_state(rate_left_out)[0], pile_state(with_vel)[0])


def test_pile_continues_across_a_restart(pile_reference, tmp_path):
    """u_t (3 values per contact in the pair's history, 3 per side in the wall's state) and
    the counters come back from the restart file."""
    deck = (f"read_restart {pile_reference.workdir / 'mid.restart'}\n"
            "neighbor 0.1 bin\ncomm_modify vel yes\n" + PILE_FIXES +
            f"run {PILE_STEPS // 2}\n" + PILE_FINAL)
    assert_same_pile(run_lammps(HEADER_3D + deck, tmp_path, header=False), pile_reference,
                     "restarted")


def test_pile_without_friction_is_another_pile(pile_start, pile_reference, tmp_path):
    """The tolerance above sees physics: mu = 0 moves the spheres by far more than 1e-8."""
    run = pile_run(pile_start, tmp_path, mu=0.0)
    assert np.abs(pile_state(run)[0] - pile_state(pile_reference)[0]).max() > 1e-3


def test_contact_rolling_around_a_fixed_sphere_keeps_u_t_in_the_tangent_plane(tmp_path):
    """A sphere rolling without slip around a fixed sphere (a wall_types bump) once, its centre
    moved on the circle by fix move with exact velocities and the spin that makes v_t = 0: a
    sticking contact whose u_t (built first by spinning in place) is only carried around.
    From the force on the sphere (fn = m kn delta exactly, v_n = 0): the tangential force
    F_t = F - fn n stays normal to n and keeps its magnitude m k_t |u_t| to rounding, and its
    parts along the orbit's axis and along the orbit keep their values to the transport's
    O(step angle) error (~1e-3 here); the torque is (-r n) x F_t. Neighbor lists are rebuilt
    every step: as the sphere goes round, the pair changes sides in the half list, and its
    history is handed over (in 3D as -u_t). Not rotating u_t, or handing it over unchanged,
    turns or flips F_t (checked by hand)."""
    kn, e, beta = 1e5, 0.7, 0.7
    ref = law(kn, e, beta)
    dt = ref["tau_c"] / 100
    delta, r = 1e-3, 0.5
    R = 1.0 - delta
    rate = 10.0                        # orbit's angular velocity about y
    spin = -R * rate / r               # omega_y for v_t = 0 (docs/model.md 3.2)
    build_steps, build_w = 20, (0.0, 3.0, 4.0)    # spinning in place: u_t = r (0, -w_z, w_y) t
    orbit_steps = int(round(2 * np.pi / rate / dt))
    every = 50
    deck = f"""
region box block -3 3 -3 3 -3 3
create_box 2 box
create_atoms 2 single 0 0 0
create_atoms 1 single {R!r} 0 0
set type * diameter 1.0
set type * density {SPHERE_DENSITY!r}
group mobile type 1
velocity all set 0 0 0
set group mobile omega {_vector(build_w)}
pair_style gran/mn kn {kn!r} e {e!r} beta {beta!r} mu 1000 wall_types 2
pair_coeff * *
timestep {dt!r}
neigh_modify every 1 delay 0 check no
thermo 0
run {build_steps}
set group mobile omega 0 {spin!r} 0
variable t equal time-{build_steps * dt!r}
variable dx equal {R!r}*cos({rate!r}*v_t)-{R!r}
variable dz equal {R!r}*sin({rate!r}*v_t)
variable vx equal -{R * rate!r}*sin({rate!r}*v_t)
variable vz equal {R * rate!r}*cos({rate!r}*v_t)
variable zero equal 0
fix orbit mobile move variable v_dx v_zero v_dz v_vx v_zero v_vz
dump d mobile custom {every} orbit.txt id x y z fx fy fz tqx tqy tqz
dump_modify d format float %.17g
compute pair all pair/local p1 p5
dump p all local {orbit_steps} pair.txt c_pair[1] c_pair[2]
dump_modify p format float %.17g
run {orbit_steps}
"""
    run = run_lammps(HEADER_3D + deck, tmp_path, header=False)
    lines = [l.split() for l in (tmp_path / "orbit.txt").read_text().splitlines()]
    rows = np.array([[float(x) for x in l] for l in lines if len(l) == 10 and l[0] == "2"])
    x, f, torque = rows[:, 1:4], rows[:, 4:7], rows[:, 7:10]
    n = x / np.linalg.norm(x, axis=1)[:, None]
    # the orbit went once round: every quadrant visited
    angle = np.arctan2(x[:, 2], x[:, 0])
    assert angle.min() < -2.5 and angle.max() > 2.5 and np.any(np.abs(angle) < 0.1)
    fn = 1.0 * kn * (1.0 - np.linalg.norm(x, axis=1))    # mass 1, v_n = 0
    ft = f - fn[:, None] * n
    u_t = r * np.array([0.0, -build_w[2], build_w[1]]) * build_steps * dt
    # built by u_t += v_t dt while spinning in place; its force once v_t = 0 is -m k_t u_t with
    # the spheres' k_t (q = 7/2)
    magnitude = np.linalg.norm(ft, axis=1)
    expected = sphere_kt(kn, e, beta) * np.linalg.norm(u_t)
    print(f"|F_t| = {magnitude.min():.12g} .. {magnitude.max():.12g}, m k_t |u_t| = "
          f"{expected:.12g}")
    assert np.abs(np.einsum("ij,ij->i", ft, n)).max() <= 1e-9 * magnitude.max()
    assert magnitude.max() - magnitude.min() <= 1e-9 * magnitude.max()
    assert abs(magnitude.mean() / expected - 1) <= 1e-9
    # the parts along the axis (y) and along the orbit (y x n) keep their values
    along_axis = ft[:, 1]
    along_orbit = np.einsum("ij,ij->i", ft, np.cross([0.0, 1.0, 0.0], n))
    assert np.abs(along_axis - along_axis[0]).max() <= 2e-3 * magnitude.max()
    assert np.abs(along_orbit - along_orbit[0]).max() <= 2e-3 * magnitude.max()
    assert min(abs(along_axis[0]), abs(along_orbit[0])) > 0.3 * magnitude.max()
    # the torque on the sphere is (-r n) x F_t
    assert np.abs(torque - np.cross(-r * n, ft)).max() <= 1e-9 * r * magnitude.max()
    # compute pair/local (single()) in 3D: |F_t| and |u_t|, at the orbit's start (the run's setup)
    local = [l.split() for l in (tmp_path / "pair.txt").read_text().splitlines()]
    values = [[float(v) for v in l] for l in local if len(l) == 2 and not l[0].startswith("I")]
    (ft_single, ut_single), = values[-1:]
    assert abs(ut_single / np.linalg.norm(u_t) - 1) <= 1e-9
    assert abs(ft_single / magnitude[0] - 1) <= 1e-9


def test_sphere_launched_sliding_on_the_floor_rolls_with_the_cutback_law(tmp_path):
    """Coulomb friction in 3D (cap on |F_t| along the trial force, coulomb_cutback): a solid
    sphere resting on the zplane floor is launched with a velocity and a spin on three axes.
    While it slides, the contact point's velocity v_t keeps its direction and its magnitude
    falls at (1 + m r^2/I) mu g = 7/2 mu g; it sticks at T = |v_t0|/(7/2 mu g) and rolls from
    then on, with the angular momentum about the contact point it started with (the contact
    force acts there): w_xy = L_xy/(I + m r^2), v = r w x n. Sampling and the spring's settling
    put the sticking time within 2 % of T, as in 2D (test_sliding.py)."""
    kn, mu, g, r = 2e5, 0.5, 1.0, 0.5
    v0, w0 = np.array([1.5, 0.5, 0.0]), np.array([2.0, -1.0, 3.0])
    dt = law(kn, 0.7, 0.7)["tau_c"] / 50
    settle = int(round(2.0 / dt))
    z = np.array([0.0, 0.0, 1.0])
    vt0 = v0 + np.cross(z, r * w0)
    T = np.linalg.norm(vt0) / (3.5 * mu * g)
    deck = f"""
boundary p p fm
region box block 0 10 0 10 -1 5
create_box 1 box
create_atoms 1 single 5 5 0.5 units box
set atom 1 diameter 1.0 density {SPHERE_DENSITY!r}
pair_style gran/mn kn {kn!r} e 0.7 beta 0.7 mu {mu!r} coulomb_cutback
pair_coeff * *
timestep {dt!r}
fix gravity all gravity {g!r} vector 0 0 -1
fix integrate all nve/sphere
fix floor all wall/gran/mn zplane 0.0 NULL
thermo 0
run {settle}
velocity all set {_vector(v0)}
set atom 1 omega {_vector(w0)}
variable t equal step*dt-{settle * dt!r}
compute spin all property/atom omegax omegay omegaz
compute w all reduce sum c_spin[1] c_spin[2] c_spin[3]
variable vtx equal vx[1]-{r!r}*c_w[2]
variable vty equal vy[1]+{r!r}*c_w[1]
fix trace all print {max(1, int(round(0.01 / dt)))} "$(v_t) $(v_vtx:%.15g) $(v_vty:%.15g) $(vx[1]:%.15g) $(vy[1]:%.15g) $(c_w[1]:%.15g) $(c_w[2]:%.15g) $(c_w[3]:%.15g)" file trace.txt screen no
run {int(round(3 * T / dt))}
"""
    run_lammps(HEADER_3D + deck, tmp_path, header=False)
    trace = np.loadtxt(tmp_path / "trace.txt", ndmin=2)
    t, vt = trace[:, 0], trace[:, 1:3]
    speed = np.linalg.norm(vt, axis=1)
    before = t < 0.9 * T
    direction = vt[before] / speed[before][:, None]
    assert np.abs(direction - vt0[:2] / np.linalg.norm(vt0)).max() < 1e-3
    assert np.allclose(speed[before], np.linalg.norm(vt0) - 3.5 * mu * g * t[before],
                       atol=0.01 * np.linalg.norm(vt0))
    stuck = t[np.argmax(speed < 1e-3 * np.linalg.norm(vt0))]
    assert abs(stuck - T) < 0.02 * T
    late = t > 1.2 * T
    assert np.all(speed[late] < 1e-3 * np.linalg.norm(vt0))
    m, inertia = 1.0, 0.4 * r * r
    L = inertia * w0 + m * r * np.cross(z, v0)
    w_roll = L[:2] / (inertia + m * r * r)
    v_roll = np.cross(r * np.array([w_roll[0], w_roll[1], 0.0]), z)[:2]
    print(f"T = {T:.4f}, stuck at {stuck:.4f}; rolling v {trace[-1, 3:5]} (predicted {v_roll}), "
          f"w_z {trace[-1, 7]:.6f}")
    assert np.allclose(trace[late][:, 3:5], v_roll, atol=1e-3 * np.linalg.norm(v0))
    assert np.allclose(trace[late][:, 5:7], w_roll, atol=1e-3 * np.linalg.norm(w0))
    # a twist about n is untouched by a force at the contact point
    assert np.allclose(trace[:, 7], w0[2], rtol=1e-9)
