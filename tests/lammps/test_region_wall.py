"""fix wall/gran/region/mn: a region's surface as a wall with the boundary rule (2M -> m_i).
Its flat face is the plane wall of fix wall/gran/mn (whose e_w, tau_w test_boundary.py and
test_three_d.py check); a curved face (the inside of a cylinder) lets a sphere roll at
5/7 g sin(theta); a corner holds a sphere on three faces at once; a moving region's velocity
(a belt) and a rotating one's (a turntable) enter the contact; MPI ranks and a restart continue
the same pile."""
import numpy as np
import pytest

from granmn_run import HEADER, PLUGIN, law, restitution_error_bound, run_lammps
from postprocess.io import CONTACT_KINDS, ROW_COLUMNS
from test_three_d import HEADER_3D, SPHERE_DENSITY

KN, E, BETA = 2e5, 0.7, 0.7
FINAL = ("write_dump all custom final.txt id x y z vx vy vz omegax omegay omegaz "
         "modify sort id format float %.17g\n")


def one_atom(dimension, box, start, motion, walls, dt, skin=""):
    """The deck of one disk or sphere (unit diameter) at `start` given `motion`, in the law's
    pair style, integrated, with `walls`, up to its run; `skin`: a neighbor command's."""
    header = HEADER_3D if dimension == 3 else HEADER.format(plugin=PLUGIN)
    density = SPHERE_DENSITY if dimension == 3 else 4 / np.pi
    integrator = "nve/sphere" if dimension == 3 else "nve/sphere disc"
    neighbor = f"neighbor {skin} bin\n" if skin else ""
    return header.replace("boundary p p p\n", "") + neighbor + f"""
{box}create_box 1 box
create_atoms 1 single {start}
set atom 1 diameter 1.0 density {density!r}
set atom 1 {motion}
pair_style gran/mn kn {KN} e {E} beta {BETA} mu 0.5
pair_coeff * *
fix integrate all {integrator}
{walls}
timestep {dt!r}
thermo 0
"""


def oblique_drop(dimension, wall, counters=False):
    """A disk or sphere falling at normal speed 1 with a sideways velocity and a spin onto
    the floor at 0: a plane (fix wall/gran/mn) or the bottom face of a block region around
    it (interior: the atom inside), over the whole contact and beyond."""
    dt = law(KN, E, BETA)["tau_c"] / 100
    plane = "zplane" if dimension == 3 else "yplane"
    if dimension == 3:
        box = "boundary p p f\nregion box block -5 5 -5 5 -1 10\n"
        start, cup = "0 0 0.505", "region cup block -4 4 -4 4 0 9 units box"
        motion = "vx 0.4 vy -0.2 vz -1.0 omega 1.5 0.8 -2.0"
    else:
        box = "boundary p f p\nregion box block -5 5 -1 10 -0.5 0.5\n"
        start, cup = "0 0.505 0", "region cup block -4 4 0 9 -0.5 0.5 units box"
        motion = "vx 0.4 vy -1.0 omega 0 0 -2.0"
    walls = {"plane": f"fix w all wall/gran/mn {plane} 0.0 NULL",
             "region": f"{cup}\nfix w all wall/gran/region/mn cup"}
    return one_atom(dimension, box, start, motion, walls[wall], dt) + (
        COUNTERS if counters else "") + "run 400\n" + FINAL + (
        "print \"RESULT counters $(f_c[1]) $(f_c[2]) $(f_c[3]) $(f_c[4]) $(f_c[5]) $(f_c[6])\"\n"
        if counters else "")


# fix contacts/mn with a row per contact completed, dumped every 100 steps
COUNTERS = ("fix c all contacts/mn local 100\n"
            "dump rows all local 100 rows.txt f_c[1] f_c[2] f_c[3] f_c[4] f_c[5] f_c[6] f_c[7] "
            "f_c[8]\ndump_modify rows format float %.17g\n")


@pytest.mark.parametrize("dimension", [2, 3])
def test_flat_face_is_the_plane_wall(tmp_path, dimension):
    """The bottom face of a block region gives the plane's trajectory bitwise: the same
    normal (the face's, along delz or dely), distance, law and boundary mass, so the same
    e_w, tau_w and tangential restitution that the plane wall's tests measure. A region wall
    that took 2M for m_i, or the wall's radius into the lever, or lost u_t, would bounce
    another way."""
    runs = {w: run_lammps(oblique_drop(dimension, w), tmp_path / w, header=False)
            for w in ("plane", "region")}
    plane, region = ((runs[w].workdir / "final.txt").read_text() for w in ("plane", "region"))
    assert plane == region
    up = "vz" if dimension == 3 else "vy"
    rebound = runs["region"].atoms()[up][0]
    e_w = law(KN, E, BETA)["e_w"]
    print(f"{dimension}D: rebound {rebound:.5f}, e_w {e_w:.5f}")
    assert abs(rebound - e_w) <= restitution_error_bound(e_w, 1 / 100)


@pytest.mark.parametrize("dimension", [2, 3])
def test_the_counters_count_a_region_face_as_the_plane(tmp_path, dimension):
    """fix contacts/mn counts a contact with a region's face as one with the plane wall: the
    same boundary contact begun, the same contact time, the same row (its start, duration,
    peak overlap, normal velocities in and out) to the last digit, the bounce being the
    plane's. A region wall that did not report its contacts would count none; one that
    reported each step's contact as begun would count 100."""
    runs = {w: run_lammps(oblique_drop(dimension, w, counters=True), tmp_path / w, header=False)
            for w in ("plane", "region")}
    counts = {w: r.result("counters") for w, r in runs.items()}
    rows = {w: (r.workdir / "rows.txt").read_text() for w, r in runs.items()}
    print(f"{dimension}D: counters {counts['region']}")
    assert counts["region"] == counts["plane"]
    assert counts["region"][1] == 1    # one boundary contact begun
    assert rows["region"] == rows["plane"] and "ITEM: ENTRIES" in rows["region"]
    assert len(rows["region"].split("ITEM: ENTRIES")[-1].split("\n")) >= 2


def test_sphere_rests_in_a_corner_on_three_faces(tmp_path):
    """Gravity along -(1, 1, 1)/sqrt(3) presses a sphere into the corner of a box region: it
    comes to rest on its three faces at once, each carrying m g/sqrt(3), an overlap of
    g/(sqrt(3) kn) against each (the boundary rule's force m kn delta), and the fix's vector
    (the force on the region) is m g along the diagonal. A wall that kept one contact per atom
    would let the sphere sink through the other two faces. Frictionless: with friction the
    faces' share of the load depends on how the sphere slid in (statically indeterminate)."""
    g, dt = 1.0, law(KN, E, BETA)["tau_c"] / 50
    deck = HEADER_3D.replace("boundary p p p\n", "") + f"""
boundary f f f
region box block -1 6 -1 6 -1 6
create_box 1 box
create_atoms 1 single 0.6 0.7 0.8
set atom 1 diameter 1.0 density {SPHERE_DENSITY!r}
pair_style gran/mn kn {KN} e {E} beta {BETA} mu 0
pair_coeff * *
fix integrate all nve/sphere
fix down all gravity {g} vector -1 -1 -1
region cup block 0 5 0 5 0 5 units box
fix w all wall/gran/region/mn cup
timestep {dt!r}
thermo 0
run {int(round(20 / dt))}
print "RESULT on_region $(f_w[1]:%.15g) $(f_w[2]:%.15g) $(f_w[3]:%.15g)"
""" + FINAL
    run = run_lammps(deck, tmp_path, header=False)
    atoms = run.atoms()
    expected = 0.5 - g / (np.sqrt(3) * KN)
    position = np.array([atoms[c][0] for c in ("x", "y", "z")])
    print(f"centre {position}, expected {expected:.10f} from each face")
    assert np.allclose(position, expected, rtol=0, atol=1e-3 * g / KN)
    assert np.allclose(run.result("on_region"), -g / np.sqrt(3), rtol=1e-6)


def test_sphere_rolls_along_the_inside_of_a_cylinder_at_five_sevenths_g_sin_theta(tmp_path):
    """A solid sphere on the bottom line of a cylinder region (its inside; axis along x,
    periodic in x), gravity tilted by theta along the axis: it rolls without sliding
    (mu = 0.5 > 2/7 tan theta) at a = g sin theta / (1 + I/(m r^2)) = 5/7 g sin theta.
    Frictionless it would slide at g sin theta; a wall whose tangential force ignored the
    curved face's normal would push it off the bottom line. Measured from the velocity's
    slope after the first time unit (the spring's settling), within 0.5 %."""
    g, sin_theta = 1.0, 0.2
    cos_theta = np.sqrt(1 - sin_theta ** 2)
    dt = law(KN, E, BETA)["tau_c"] / 50
    deck = HEADER_3D.replace("boundary p p p\n", "") + f"""
boundary p f f
region box block 0 20 -4 4 -4 4
create_box 1 box
create_atoms 1 single 10 0 {-3 + 0.5 - g / KN!r}
set atom 1 diameter 1.0 density {SPHERE_DENSITY!r}
pair_style gran/mn kn {KN} e {E} beta {BETA} mu 0.5
pair_coeff * *
fix integrate all nve/sphere
region drum cylinder x 0 0 3 -1 21 units box
fix w all wall/gran/region/mn drum
fix down all gravity {g} vector 0 0 -1
timestep {dt!r}
thermo 0
run {int(round(2 / dt))}
unfix down
fix down all gravity {g} vector {sin_theta!r} 0 {-cos_theta!r}
variable t equal step*dt
fix trace all print {int(round(0.05 / dt))} "$(v_t:%.15g) $(vx[1]:%.15g) $(y[1]:%.15g) $(z[1]:%.15g)" file trace.txt screen no
run {int(round(5 / dt))}
"""
    run = run_lammps(deck, tmp_path, header=False)
    trace = run.table("trace.txt")
    t, vx = trace[:, 0] - trace[0, 0], trace[:, 1]
    late = t > 1.0
    slope = np.polyfit(t[late], vx[late], 1)[0]
    print(f"a = {slope:.6f}, 5/7 g sin theta = {5 / 7 * g * sin_theta:.6f}; |y| <= "
          f"{np.abs(trace[:, 2]).max():.2e}")
    assert abs(slope - 5 / 7 * g * sin_theta) < 0.005 * 5 / 7 * g * sin_theta
    assert np.abs(trace[:, 2]).max() < 1e-6    # on the bottom line


def test_a_moving_floor_drags_a_sphere_to_two_sevenths_of_its_speed(tmp_path):
    """A sphere at rest on a floor region that moves at U along x (region ... move): friction
    accelerates it and spins it up until its contact point moves with the floor; its angular
    momentum about the contact point stays 0 (the contact force acts there), so it rolls at
    v = U q/(1 + q) = 2U/7 (q = I/(m r^2) = 2/5). A contact that ignored the wall's velocity
    would leave the sphere at rest. With coulomb_cutback: the paper's literal u_t, never cut
    back while sliding, holds the friction along the old slip after the contact point has
    caught up with the floor, and the sphere overshoots (its contact point reaches 1.9 U; the
    same flaw as test_sliding.py's on a fixed floor)."""
    u, g = 1.0, 1.0
    dt = law(KN, E, BETA)["tau_c"] / 50
    deck = HEADER_3D.replace("boundary p p p\n", "") + f"""
boundary p p f
region box block 0 10 0 10 -2 5
create_box 1 box
create_atoms 1 single 5 5 {0.5 - g / KN!r}
set atom 1 diameter 1.0 density {SPHERE_DENSITY!r}
pair_style gran/mn kn {KN} e {E} beta {BETA} mu 0.5 coulomb_cutback
pair_coeff * *
fix integrate all nve/sphere
fix down all gravity {g} vector 0 0 -1
variable shift equal {u!r}*time
region floor block -1000 1000 -1000 1000 -1 0 side out move v_shift NULL NULL units box
fix w all wall/gran/region/mn floor
timestep {dt!r}
thermo 0
run {int(round(3 / dt))}
""" + FINAL
    atoms = run_lammps(deck, tmp_path, header=False).atoms()
    print(f"v = {atoms['vx'][0]:.6f}, 2U/7 = {2 * u / 7:.6f}; omega_y {atoms['omegay'][0]:.6f}")
    assert abs(atoms["vx"][0] - 2 * u / 7) < 0.005 * 2 * u / 7
    # rolling: the contact point moves with the floor
    assert abs(atoms["vx"][0] - 0.5 * atoms["omegay"][0] - u) < 0.005 * u


DRUM_PILE = """
boundary p f f
region box block 0 6 -3.5 3.5 -3.5 3.5
create_box 1 box
region start cylinder x 0 0 2.2 0 6 units box
lattice sc 1.0 origin 0.5 0.5 0.5
create_atoms 1 region start
lattice none 1.0
variable diameter atom "0.8 + 0.2*((id*7919)%100)/100"
set group all diameter v_diameter
set group all density {density!r}
velocity all create 0.5 4928459 loop geom
write_data start.data
"""


def drum_run(workdir, start, nprocs=1, restart_from=None, mu=0.5, newton="on"):
    """The spheres of DRUM_PILE in a cylinder region (axis x, periodic in x) with gravity
    tilted along the axis and across it: they fall onto the curved wall, slide and roll along
    it; 1000 steps, a restart file, 1000 more (or the second half from a restart file)."""
    dt = law(KN, E, BETA)["tau_c"] / 50
    fixes = f"""
fix integrate all nve/sphere
fix down all gravity 1.0 vector 0.3 0.2 -1
region drum cylinder x 0 0 3 -1 7 units box
fix w all wall/gran/region/mn drum
timestep {dt!r}
thermo 0
"""
    if restart_from:
        body = (f"read_restart {restart_from}\nneighbor 0.1 bin\ncomm_modify vel yes\n" + fixes
                + "run 1000\n")
    else:
        body = (f"newton {newton}\nprocessors * 1 1\nboundary p f f\nread_data {start}\n"
                f"pair_style gran/mn kn {KN} e {E} beta {BETA} mu {mu}\npair_coeff * *\n"
                + fixes + "run 1000\nwrite_restart mid.restart\nrun 1000\n")
    deck = HEADER_3D.replace("boundary p p p\n", "") + body + FINAL
    return run_lammps(deck, workdir, nprocs=nprocs, header=False)


def drum_state(run):
    a = run.atoms()
    omega = np.sqrt(2 * KN)
    return np.column_stack([a["x"], a["y"], a["z"]] + [a[c] / omega for c in ("vx", "vy", "vz")]
                           + [0.5 * a[c] / omega for c in ("omegax", "omegay", "omegaz")])


def test_pile_in_a_cylinder_is_the_same_on_two_ranks_newton_off_and_across_a_restart(tmp_path):
    """u_t of each face in contact moves with its atom between ranks and comes back from a
    restart file: two ranks (the atoms cross between them), with newton on and off, give the
    serial pile to rounding
    (1e-8 on positions and velocities in units of the contact's, as the plane wall's pile
    tests), and so does the second half run from the restart file. Frictionless, the pile is
    another (> 1e-3): the tolerance sees the history."""
    start = run_lammps(HEADER_3D.replace("boundary p p p\n", "")
                       + DRUM_PILE.format(density=SPHERE_DENSITY), tmp_path / "start",
                       header=False).workdir / "start.data"
    serial = drum_run(tmp_path / "serial", start)
    ranks = drum_run(tmp_path / "ranks", start, nprocs=2)
    newton_off = drum_run(tmp_path / "newton_off", start, nprocs=2, newton="off")
    resumed = drum_run(tmp_path / "resumed", start,
                       restart_from=serial.workdir / "mid.restart")
    reference = drum_state(serial)
    assert len(reference) > 20
    assert (reference[:, 1] ** 2 + reference[:, 2] ** 2).max() > 2.0 ** 2    # at the wall
    for label, run in (("two ranks", ranks), ("two ranks, newton off", newton_off)):
        difference = np.abs(drum_state(run) - reference).max()
        print(f"{label}: largest difference {difference:.1e}")
        assert difference < 1e-8
    difference = np.abs(drum_state(resumed) - reference).max()
    print(f"resumed: largest difference {difference:.1e}")
    assert difference < 1e-8
    frictionless = drum_run(tmp_path / "frictionless", start, mu=0.0)
    assert np.abs(drum_state(frictionless) - reference).max() > 1e-3


def belt_deck(body):
    dt = law(KN, E, BETA)["tau_c"] / 50
    return HEADER_3D.replace("boundary p p p\n", "") + body.format(
        density=SPHERE_DENSITY, dt=dt, fixes=f"""
fix integrate all nve/sphere
fix down all gravity 1.0 vector 0 0 -1
variable shift equal 1.0*time
region floor block -1000 1000 -1000 1000 -1 0 side out move v_shift NULL NULL units box
fix w all wall/gran/region/mn floor
timestep {dt!r}
thermo 0
""") + FINAL


def test_a_moving_floor_keeps_its_velocity_at_a_runs_start_and_across_a_restart(tmp_path):
    """A sphere rolling on a floor that moves at U (t = 1: it stuck at 0.57) feels no friction.
    LAMMPS's regions forget their velocity at every run's start (Region::init), and the
    first force evaluation of a run saw the floor at rest: a friction of mu m g = 0.5, a kick
    for a step. The fix gives the region its velocity back, at a new run (`run 0`) and after a
    restart file (which holds it): the force on the floor stays ~0 (below 1e-3 of mu m g), and
    the run continued from the restart file goes on as the uninterrupted one, to rounding
    (1e-12 in the units of drum_state; LAMMPS's time, which moves the floor, is summed anew from
    the restart's step)."""
    setup_force = ('run 0\nprint "RESULT setup_force $(f_w[1]:%.10g) $(f_w[2]:%.10g)"\n')
    through = run_lammps(belt_deck(f"""
boundary p p f
region box block 0 10 0 10 -2 5
create_box 1 box
create_atoms 1 single 5 5 {0.5 - 1.0 / KN!r}
set atom 1 diameter 1.0 density {{density!r}}
pair_style gran/mn kn {KN} e {E} beta {BETA} mu 0.5 coulomb_cutback
pair_coeff * *
{{fixes}}
run 10000
write_restart mid.restart
{setup_force}run 2000
"""), tmp_path / "through", header=False)
    resumed = run_lammps(belt_deck(f"""
read_restart {through.workdir / 'mid.restart'}
neighbor 0.1 bin
comm_modify vel yes
{{fixes}}
{setup_force}run 2000
"""), tmp_path / "resumed", header=False)
    for run in (through, resumed):
        print(f"force on the floor at the run's start: {run.result('setup_force')}")
        assert np.abs(run.result("setup_force")).max() < 1e-3 * 0.5
    difference = np.abs(drum_state(through) - drum_state(resumed)).max()
    print(f"resumed: largest difference {difference:.1e}")
    assert difference < 1e-12


def resting_sphere(motion, g=1.0):
    """A solid sphere (mass 1) at rest on the floor z = 0 at (5, 0), at its static overlap
    g/kn, gravity g along -z, the law's pair style and fix nve/sphere; `motion`: the floor's
    region and wall fix and what follows."""
    dt = law(KN, E, BETA)["tau_c"] / 50
    return HEADER_3D.replace("boundary p p p\n", "") + f"""
boundary p p f
region box block -10 10 -10 10 -2 5
create_box 1 box
create_atoms 1 single 5 0 {0.5 - g / KN!r}
set atom 1 diameter 1.0 density {SPHERE_DENSITY!r}
pair_style gran/mn kn {KN} e {E} beta {BETA} mu 0.5 coulomb_cutback
pair_coeff * *
fix integrate all nve/sphere
fix down all gravity {g} vector 0 0 -1
timestep {dt!r}
thermo 0
""" + motion


@pytest.mark.parametrize("motion", ["move", "rotate"])
def test_a_moving_region_has_its_velocity_at_step_0(tmp_path, motion):
    """A sphere at rest on a floor that moves from step 0 (a belt at U = 1 along x; a turntable
    at Omega = 0.1, whose surface under the sphere moves at Omega rho = 0.5 along y) slides at
    the first force evaluation: the force on the floor is the Coulomb limit mu m g, against the
    floor's motion (the trial force m eta_t v_t is 20 times the limit). LAMMPS's
    Region::set_velocity gives every region velocity 0 at step 0: no friction there."""
    mu, g = 0.5, 1.0
    assert law(KN, E, BETA, "sphere")["eta_t"] * 0.5 > 10 * mu * g
    floor = {"move": "variable shift equal 1.0*time\nregion floor block -100 100 -100 100 -1 0 "
                     "side out move v_shift NULL NULL units box\n",
             "rotate": "variable angle equal 0.1*time\nregion floor block -100 100 -100 100 -1 0 "
                       "side out rotate v_angle 0 0 0 0 0 1 units box\n"}[motion]
    deck = resting_sphere(floor + "fix w all wall/gran/region/mn floor\nrun 0\n"
                          'print "RESULT on_floor $(f_w[1]:%.15g) $(f_w[2]:%.15g)"\n', g)
    on_floor = run_lammps(deck, tmp_path, header=False).result("on_floor")
    expected = [-mu * g, 0.0] if motion == "move" else [0.0, -mu * g]
    print(f"force on the floor at step 0: {on_floor}, expected {expected}")
    assert np.allclose(on_floor, expected, rtol=0, atol=1e-9 * mu * g)


RISE = 0.01    # the floor's speed up
# A floor under the sphere at rest on it, defined or defined again at step 1000 rising at RISE:
# the deck, and whether it rose from step 0 (else from step 1000).
FLOOR_DEFINED_LATER = {
    # a new fix on a region defined at step 1000, its move variable 0.01 time: its face placed
    # 0.01 time below z = 0 then
    "a region defined at a later step": ("""fix w all wall/gran/region/mn floor
run 1000
unfix w
variable rise equal {rise!r}*time
region lift block -100 100 -100 100 -1 $(-{rise!r}*time) side out move NULL NULL v_rise units box
fix w all wall/gran/region/mn lift
""", False),
    # the fix kept, its region (rising from step 0) defined again between runs as it was
    "a region defined again as it was between runs": ("""variable rise equal {rise!r}*time
region lift block -100 100 -100 100 -1 0 side out move NULL NULL v_rise units box
fix w all wall/gran/region/mn lift
run 1000
region lift delete
region lift block -100 100 -100 100 -1 0 side out move NULL NULL v_rise units box
""", True),
    # the fix kept, its region defined again as a piston placed by an offset in its variable
    "a piston placed by an offset in its move variable": ("""fix w all wall/gran/region/mn floor
run 1000
region floor delete
variable rise equal 0.3+{rise!r}*(time-$(time))
region floor block -100 100 -100 100 -1 -0.3 side out move NULL NULL v_rise units box
""", False),
}


@pytest.mark.parametrize("case", sorted(FLOOR_DEFINED_LATER))
def test_a_region_defined_while_it_moves_has_its_velocity_from_its_first_step(tmp_path, case):
    """A floor rising at U = 0.01 under a sphere resting on it, its region defined (or defined
    again) at step 1000. At the first force evaluation after, the normal force is
    m (kn delta - eta_n (v_z - U)), from the sphere's overlap and velocity then (the force on
    the floor, f_w[3], is its opposite), to 1e-6; afterwards the sphere rides on the floor at
    U, its overlap g/kn to 5 % of it (the start's transient has decayed to below 1 %; a wall at
    rest would press it 70 % deeper, eta_n U/kn). Region::set_velocity knew no displacement
    before the region's definition and took its whole displacement over one step for the
    velocity (about 10: the sphere was launched at 14 and lost); its rule for step 0 (velocity
    0) would miss eta_n U = 0.7 of the force."""
    g = 1.0
    text, from_step_0 = FLOOR_DEFINED_LATER[case]
    start = 0.0 if from_step_0 else 1000 * law(KN, E, BETA)["tau_c"] / 50
    coefficients = law(KN, E, BETA, "sphere")
    floor = ("region floor block -100 100 -100 100 -1 0 side out units box\n"
             + text.format(rise=RISE) + "run 0\n"
             'print "RESULT first $(f_w[3]:%.15g) $(z[1]:%.17g) $(vz[1]:%.17g) $(time:%.17g)"\n'
             "run 2000\n"
             'print "RESULT last $(z[1]:%.17g) $(vz[1]:%.17g) $(time:%.17g)"\n')
    run = run_lammps(resting_sphere(floor, g), tmp_path, header=False)
    on_floor, z, vz, time = run.result("first")
    top = RISE * (time - start)    # the floor's face
    expected = -(KN * (0.5 - (z - top)) - coefficients["eta_n"] * (vz - RISE))
    print(f"{case}: force on the floor {on_floor:.10g}, expected {expected:.10g}")
    assert on_floor == pytest.approx(expected, rel=1e-6)
    z, vz, time = run.result("last")
    print(f"after 2000 steps: v_z {vz:.8g}, above the face by {z - RISE * (time - start):.8g}")
    assert vz == pytest.approx(RISE, rel=1e-3)
    assert z - RISE * (time - start) == pytest.approx(0.5 - g / KN, abs=0.05 * g / KN)


# A block region `table` (the sphere inside it, on its bottom face z = 0) that moves (a belt at
# U = 1 along x) or rotates (a turntable at Omega = 0.1 about z), and the wall's region
# `floor` made of it with static regions away from the sphere.
MOVING_TABLES = {"move": "variable shift equal 1.0*time\nregion table block -50 50 -50 50 0 50 "
                         "move v_shift NULL NULL units box\n",
                 "rotate": "variable angle equal 0.1*time\nregion table block -50 50 -50 50 0 50 "
                           "rotate v_angle 0 0 0 0 0 1 units box\n"}
COMPOSITES = {
    "union": "region far block 60 70 60 70 60 70 units box\n"
             "region floor union 2 far table\n",
    "intersect": "region around block -60 60 -60 60 -10 60 units box\n"
                 "region floor intersect 2 around table\n",
    "union in an intersect": "region far block 60 70 60 70 60 70 units box\n"
                             "region around block -60 60 -60 60 -10 60 units box\n"
                             "region both union 2 table far\n"
                             "region floor intersect 2 around both\n",
}


@pytest.mark.parametrize("motion", sorted(MOVING_TABLES))
@pytest.mark.parametrize("composite", sorted(COMPOSITES))
def test_a_moving_member_of_a_union_or_intersect_moves_the_wall(tmp_path, composite, motion):
    """A sphere at rest on the bottom face of a block region that moves or rotates is dragged
    along (test_a_moving_floor_drags_a_sphere_to_two_sevenths_of_its_speed, and the turntable's
    test). The block as a member of a union (with a static block away from it), of an intersect
    (with a static block around it), or of a union in an intersect has the same faces near the
    sphere, each contact takes the velocity of the member whose face it is: the trajectory
    must be the block's own, bitwise. LAMMPS 29 Sep 2021's union and intersect pass no member's
    velocity (the sphere stayed at rest), and its union applies a rotation of its own whose
    angle and axis are never set."""
    def run(name, wall):
        deck = resting_sphere(MOVING_TABLES[motion] + COMPOSITES[composite]
                              + f"fix w all wall/gran/region/mn {wall}\nrun 2000\n")
        return run_lammps(deck + FINAL, tmp_path / name, header=False)

    alone, member = run("alone", "table"), run("member", "floor")
    atoms = alone.atoms()
    print(f"{composite}, {motion}: v ({atoms['vx'][0]:.6f}, {atoms['vy'][0]:.6f})")
    assert np.hypot(atoms["vx"][0], atoms["vy"][0]) > 0.01    # dragged
    assert (member.workdir / "final.txt").read_text() == (alone.workdir / "final.txt").read_text()


def test_a_union_of_moving_members_continues_across_a_restart(tmp_path):
    """Two moving members of a union (the belt under the sphere and a block away from it that
    moves too): the restart file holds each one's motion, and the run continued from it goes
    on as the uninterrupted one, to rounding (1e-12 in the units of drum_state; LAMMPS 29 Sep
    2021 starts the belt's time anew from the restart, which moves it along itself only)."""
    regions = ("variable shift equal 1.0*time\n"
               "region table block -50 50 -50 50 0 50 move v_shift NULL NULL units box\n"
               "region far block 60 70 60 70 60 70 move NULL v_shift NULL units box\n"
               "region floor union 2 far table\nfix w all wall/gran/region/mn floor\n")
    through = run_lammps(resting_sphere(regions + "run 1000\nwrite_restart mid.restart\n"
                                        "run 1000\n") + FINAL, tmp_path / "through",
                         header=False)
    dt = law(KN, E, BETA)["tau_c"] / 50
    resumed = run_lammps(HEADER_3D.replace("boundary p p p\n", "")
                         + f"read_restart {through.workdir / 'mid.restart'}\n"
                         f"neighbor 0.1 bin\ncomm_modify vel yes\nfix integrate all nve/sphere\n"
                         f"fix down all gravity 1.0 vector 0 0 -1\ntimestep {dt!r}\nthermo 0\n"
                         + regions + "run 1000\n" + FINAL, tmp_path / "resumed", header=False)
    assert through.atoms()["vx"][0] > 0.05    # dragged by the belt (mu g t = 0.1; at rest 0)
    difference = np.abs(drum_state(through) - drum_state(resumed)).max()
    print(f"resumed: largest difference {difference:.1e}")
    assert difference < 1e-12


def test_an_exterior_union_is_the_exterior_of_its_members(tmp_path):
    """A union with side out: the atoms outside both members. A sphere bouncing on the top of
    one member (a post), away from the other, must bounce as on the post alone (side out),
    bitwise. LAMMPS 29 Sep 2021's union gave such a contact the distance 0 (its surface_exterior
    sets r from another field): the wall stopped the run at the first touch."""
    def run(name, regions, wall):
        deck = resting_sphere(regions + f"fix w all wall/gran/region/mn {wall}\n"
                              "set atom 1 z 0.8 vz -1.0 vx 0.3\nrun 5000\n")
        return run_lammps(deck + FINAL, tmp_path / name, header=False)

    post = "region post block 3 7 -2 2 -5 0 side out units box\n"
    alone = run("alone", post, "post")
    member = run("member", post.replace(" side out", "") + "region far block -9 -8 -9 -8 -5 0 "
                 "units box\nregion posts union 2 far post side out\n", "posts")
    atoms = alone.atoms()
    print(f"after the bounce: v_z {atoms['vz'][0]:.5f}")
    assert atoms["vz"][0] > 0.5    # bounced off the post's top
    assert (member.workdir / "final.txt").read_text() == (alone.workdir / "final.txt").read_text()


@pytest.mark.parametrize("axis_length", [1, 2])
def test_a_ball_on_a_turntable_orbits_at_two_sevenths_of_its_rate(tmp_path, axis_length):
    """A rotating region (region ... rotate): a solid sphere set at rest on a turntable (a
    floor turning at Omega about z) at distance rho from the axis is dragged until it rolls,
    and then, rolling without slipping, its centre obeys dv/dt = (q/(1+q)) Omega x v (q = 2/5):
    it orbits at 2 Omega/7 at constant speed, here around the axis at rho (its speed at
    sticking is 2/7 Omega rho along the table's motion). Measured over a third of an orbit
    after it sticks: the angular rate within 1 % of 2 Omega/7, the distance within 1 % of rho.
    A wall that took the region's translation only, or no wall velocity, would leave it at
    rest; one that rolled it with the table's own rate would orbit at Omega. The rotate axis
    given with length 2 turns the region at the same rate (LAMMPS rotates about its unit
    vector): LAMMPS's Region::set_velocity multiplies the rate by the axis as given, and the
    wall's surface moved at 2 Omega (the ball orbited at 4 Omega/7)."""
    rate, rho = 0.1, 5.0
    dt = law(KN, E, BETA)["tau_c"] / 50
    deck = HEADER_3D.replace("boundary p p p\n", "") + f"""
boundary p p f
region box block -10 10 -10 10 -2 5
create_box 1 box
create_atoms 1 single {rho!r} 0 {0.5 - 1.0 / KN!r}
set atom 1 diameter 1.0 density {SPHERE_DENSITY!r}
pair_style gran/mn kn {KN} e {E} beta {BETA} mu 0.5 coulomb_cutback
pair_coeff * *
fix integrate all nve/sphere
fix down all gravity 1.0 vector 0 0 -1
variable angle equal {rate!r}*time
region table block -50 50 -50 50 -1 0 side out rotate v_angle 0 0 0 0 0 {axis_length} units box
fix w all wall/gran/region/mn table
timestep {dt!r}
thermo 0
variable t equal step*dt
fix trace all print {int(round(0.5 / dt))} "$(v_t:%.15g) $(x[1]:%.15g) $(y[1]:%.15g)" file trace.txt screen no
run {int(round(40 / dt))}
"""
    trace = run_lammps(deck, tmp_path, header=False).table("trace.txt")
    t, x, y = trace[:, 0], trace[:, 1], trace[:, 2]
    late = t > 2.0
    angle = np.unwrap(np.arctan2(y[late], x[late]))
    orbit = np.polyfit(t[late], angle, 1)[0]
    distance = np.hypot(x[late], y[late])
    print(f"orbit rate {orbit:.6f} (2 Omega/7 = {2 * rate / 7:.6f}), distance "
          f"{distance.min():.4f}-{distance.max():.4f} (rho {rho})")
    assert abs(orbit - 2 * rate / 7) < 0.01 * 2 * rate / 7
    assert np.abs(distance - rho).max() < 0.01 * rho


def test_disk_rolls_down_a_region_floor_at_two_thirds_g_sin_theta(tmp_path):
    """2D: a disk (I = m r^2/2) on the floor of a block region, gravity tilted by theta along
    it: rolling without sliding (mu = 0.5 > tan(theta)/3) at a = g sin(theta)/(1 + 1/2) =
    2/3 g sin(theta), within 0.5 % after the first time unit."""
    g, sin_theta = 1.0, 0.2
    dt = law(KN, E, BETA)["tau_c"] / 50
    deck = HEADER.format(plugin=PLUGIN).replace("boundary p p p\n", "") + f"""
boundary p f p
region box block 0 20 -1 5 -0.5 0.5
create_box 1 box
create_atoms 1 single 10 {0.5 - g / KN!r} 0
set atom 1 diameter 1.0 density {4 / np.pi!r}
pair_style gran/mn kn {KN} e {E} beta {BETA} mu 0.5 coulomb_cutback
pair_coeff * *
fix integrate all nve/sphere disc
region floor block INF INF -1 0 -0.5 0.5 side out units box
fix w all wall/gran/region/mn floor
fix down all gravity {g} vector 0 -1 0
timestep {dt!r}
thermo 0
run {int(round(2 / dt))}
unfix down
fix down all gravity {g} vector {sin_theta!r} {-np.sqrt(1 - sin_theta ** 2)!r} 0
variable t equal step*dt
fix trace all print {int(round(0.05 / dt))} "$(v_t:%.15g) $(vx[1]:%.15g)" file trace.txt screen no
run {int(round(5 / dt))}
"""
    trace = run_lammps(deck, tmp_path, header=False).table("trace.txt")
    t, vx = trace[:, 0] - trace[0, 0], trace[:, 1]
    late = t > 1.0
    slope = np.polyfit(t[late], vx[late], 1)[0]
    print(f"a = {slope:.6f}, 2/3 g sin theta = {2 / 3 * g * sin_theta:.6f}")
    assert abs(slope - 2 / 3 * g * sin_theta) < 0.005 * 2 / 3 * g * sin_theta


def same_with_either_skin(tmp_path, dimension, box, start, motion, cup, dt, run_time):
    """One atom against region `cup` (fix wall/gran/region/mn) for run_time, with a neighbour
    skin of 3 and of 0.1: the final states must be bitwise the same (one atom: the skin changes
    only which builds list it). Returns the atoms of the run with the skin of 3."""
    runs = []
    for skin in (3.0, 0.1):
        deck = one_atom(dimension, box, start, motion,
                        f"{cup}\nfix w all wall/gran/region/mn cup", dt, skin)
        deck += f"run {int(round(run_time / dt))}\n" + FINAL
        runs.append(run_lammps(deck, tmp_path / f"skin{skin}", header=False))
    final = [(run.workdir / "final.txt").read_text() for run in runs]
    assert final[0] == final[1]
    return runs[0].atoms()


@pytest.mark.parametrize("dimension,shape", [(2, "block"), (3, "block"), (2, "cylinder")])
def test_a_face_reached_from_beyond_the_neighbour_skin(tmp_path, dimension, shape):
    """At rest a region's faces are visited only for the atoms within the neighbour skin of
    them at the last neighbour-list build (and those still touching one), as fix wall/gran/mn's
    planes. A disk or sphere inside the region, 2.5 from contact (25 skins of 0.1), moving onto
    its floor (a block's bottom face, with a sideways velocity; in 2D also a circle's rim) at 1
    with a spin, is taken in only by the builds on its way: its bounce is bitwise the one of
    the same run with a skin of 3, which lists it from the start (one atom: the skin changes
    nothing else). A list made only at the run's start would let it through the face; one of
    the atoms already touching at a build would find the contact up to half a skin late."""
    dt = law(KN, E, BETA)["tau_c"] / 100
    if dimension == 3:
        box = "boundary p p f\nregion box block -6 6 -6 6 -1 10\n"
        start, motion = "0 0 3.0", "vx 0.4 vy -0.2 vz -1.0 omega 1.5 0.8 -2.0"
        cup = "region cup block -5 5 -5 5 0 9 units box"
    else:
        box = "boundary f f p\nregion box block -6 6 -6 6 -0.5 0.5\n"
        # on the circle's rim no sideways velocity: the normal stays y's, the rebound vy
        start = "0 -2.0 0"
        motion = ("vx 0.4 vy -1.0 omega 0 0 -2.0" if shape == "block"
                  else "vy -1.0 omega 0 0 -2.0")
        cup = ("region cup block -5 5 -5 5 -0.5 0.5 units box" if shape == "block" else
               "region cup cylinder z 0 0 5.0 -0.5 0.5 units box")

    atoms = same_with_either_skin(tmp_path, dimension, box, start, motion, cup, dt, 3.0)
    normal = "vz" if dimension == 3 else "vy"
    rebound = atoms[normal][0]
    e_w = law(KN, E, BETA)["e_w"]
    print(f"{dimension}D {shape}: rebound {rebound:.5f}, e_w {e_w:.5f}")
    assert abs(rebound - e_w) <= restitution_error_bound(e_w, 1 / 100)


def test_a_disk_outside_an_open_region_meets_the_rim_of_its_side_face(tmp_path):
    """An open region's faces are walls on both sides, and to an atom outside it the region
    reports only the nearest point of its surface; in 2D that can be on the rim of a z face
    (a slab's), which is no wall itself but is no farther in the plane than the faces that are.
    A disk above a box open at the top falls at 1 and drifts at 0.3 onto the top of its side
    face. With a skin of 3 it is within the skin at the start (1.12 from the z face's rim, 1.14
    from the side face's top), and no build falls before it hits: the run must be bitwise the
    one with a skin of 0.1 (a list without that rim's contact let the disk into the face
    unseen, until a build found it 0.4 deep: thrown out at 150), and the disk must come off
    the rim upwards, slower than it came."""
    dt = law(KN, E, BETA)["tau_c"] / 100
    box = "boundary f f p\nregion box block -6 6 -6 8 -0.5 0.5\n"
    cup = "region cup block -5 5 -5 5 -0.5 0.5 open 4 units box"

    atoms = same_with_either_skin(tmp_path, 2, box, "4.45 6.0 0", "vx 0.3 vy -1.0", cup, dt, 2.0)
    speed = np.hypot(atoms["vx"][0], atoms["vy"][0])
    print(f"after the rim: y {atoms['y'][0]:.4f}, v ({atoms['vx'][0]:.4f}, "
          f"{atoms['vy'][0]:.4f}), speed {speed:.4f} of {np.hypot(0.3, 1.0):.4f}")
    assert atoms["y"][0] > 5.0 and atoms["vy"][0] > 0.0
    assert speed < np.hypot(0.3, 1.0)


@pytest.mark.parametrize("shape", ["block", "cylinder"])
def test_a_disk_wider_than_the_slab_ignores_its_z_faces(tmp_path, shape):
    """2D: the regions of a deck span the box's z, -0.5 to 0.5, and a disk of diameter 1.2
    reaches both z faces, which are no wall (the disks lie in the plane). A disk spinning in a
    block's corner (pressed into it by gravity along (-1, -1): friction on both faces), or
    rolling to and fro along a z-cylinder's wall at its bottom, must move as against the same
    region 6 thick in z, which reports no z face, bitwise, and stay on the faces. The region
    wall counted the z faces among the faces it touched (4 of a block's 3, 3 of a cylinder's
    2) and stopped the run."""
    dt = law(KN, E, BETA)["tau_c"] / 50
    box = "boundary f f p\nregion box block -3 3 -3 3 -0.5 0.5\n"
    if shape == "block":    # pressed into each face by g/sqrt(2)
        corner = -2.5 + 0.6 - np.sqrt(0.5) / KN
        start, motion, gravity = f"{corner!r} {corner!r} 0", "omega 0 0 1.0", "-1 -1 0"
    else:
        start, motion, gravity = f"0 {-2.5 + 0.6 - 1.0 / KN!r} 0", "vx -0.3", "0 -1 0"

    def run(z_extent):
        cup = (f"region cup block -2.5 2.5 -2.5 2.5 {z_extent} units box" if shape == "block"
               else f"region cup cylinder z 0 0 2.5 {z_extent} units box")
        deck = one_atom(2, box, start, motion, f"{cup}\nfix w all wall/gran/region/mn cup\n"
                        f"fix down all gravity 1.0 vector {gravity}", dt)
        deck = deck.replace("set atom 1 diameter 1.0", "set atom 1 diameter 1.2")
        return run_lammps(deck + "run 20000\n" + FINAL, tmp_path / z_extent.replace(" ", "_"),
                          header=False)

    thin, thick = run("-0.5 0.5"), run("-3 3")
    assert (thin.workdir / "final.txt").read_text() == (thick.workdir / "final.txt").read_text()
    atoms = thin.atoms()
    x, y = atoms["x"][0], atoms["y"][0]
    print(f"{shape}: at ({x:.5f}, {y:.5f}), v ({atoms['vx'][0]:.4f}, {atoms['vy'][0]:.4f})")
    if shape == "block":    # in the corner
        assert x + 2.5 < 0.61 and y + 2.5 < 0.61
    else:                   # on the wall, near its bottom
        assert 2.5 - np.hypot(x, y) < 0.61 and y < -1.5


# A cylinder (axis z, radius 2, bottom z = -2, top open) and a block beside it (its bottom z =
# -2): sphere 1 rests on the cylinder's bottom, sphere 2 on the block's.
OPENED = """
boundary f f f
region box block -3 6 -3 3 -8 3
create_box 1 box
create_atoms 1 single 0 0 {z!r}
create_atoms 1 single 4 0 {z!r}
set type 1 diameter 1.0
set type 1 density {density!r}
pair_style gran/mn kn {kn} e {e} beta {beta} mu 0.5
pair_coeff * *
fix integrate all nve/sphere
fix down all gravity 1.0 vector 0 0 -1
region pot cylinder z 0 0 2 -2 2 open 2 units box
region beside block 3 5 -1 1 -2 2 units box
region vessel union 2 pot beside
fix w all wall/gran/region/mn vessel
fix c all contacts/mn local 100
dump rows all local 100 rows.txt f_c[1] f_c[2] f_c[3] f_c[4] f_c[5] f_c[6] f_c[7] f_c[8]
dump_modify rows format float %.17g
timestep {dt!r}
thermo 0
run 2000
region pot delete
region vessel delete
region pot cylinder z 0 0 2 -2 2 open 1 open 2 units box
region vessel union 2 {members}
run 3000
write_dump all custom counts.txt id z vz f_c[2] f_c[6] modify sort id format float %.17g
"""


@pytest.mark.parametrize("members", ["pot beside", "beside pot"])
def test_a_face_opened_between_runs_ends_its_contacts(tmp_path, members):
    """Sphere 1 rests on the bottom of a cylinder, sphere 2 on the bottom of a block, the two
    regions a union (a funnel's cylinder and cone, examples/granregion), with fix contacts/mn.
    Between runs the cylinder is defined again with its bottom open (open 1), the union again
    of the same members: sphere 1's contact ends at the run's start and the sphere falls
    freely (v_z = -g t after 3000 steps); its row has no normal velocity at the end (nan: the
    face is gone), the duration of the first run. With the members in the same order the faces
    keep their numbers, and sphere 2's contact carries on (one contact begun, no row); in the
    other order (as the funnel example) they are numbered otherwise, and every contact ends
    at the run's start (a row, nan) and begins again where a face is still touched. The region
    wall stopped the run: "left face ... by more than its radius in one step (time step far too
    large)"."""
    dt = law(KN, E, BETA)["tau_c"] / 50
    deck = HEADER_3D.replace("boundary p p p\n", "") + OPENED.format(
        z=-1.5 - 1.0 / KN, density=SPHERE_DENSITY, kn=KN, e=E, beta=BETA, dt=dt,
        members=members)
    run = run_lammps(deck, tmp_path, header=False)
    counts = run.atoms("counts.txt")
    print({name: list(values) for name, values in counts.items()})
    assert counts["vz"][0] == pytest.approx(-3000 * dt, rel=1e-6)    # falling freely
    assert counts["f_c[6]"][0] == 0 and counts["f_c[2]"][0] == 1
    renumbered = members == "beside pot"
    assert counts["f_c[6]"][1] == 1 and counts["f_c[2]"][1] == (2 if renumbered else 1)
    rows = [tuple(map(float, line.split())) for line in
            (run.workdir / "rows.txt").read_text().splitlines()
            if len(line.split()) == 8 and not line.startswith("ITEM")]
    assert sorted(row[0] for row in rows) == ([1.0, 2.0] if renumbered else [1.0])
    for row in (dict(zip(ROW_COLUMNS, values)) for values in rows):
        assert (row["id_j"], row["kind"], row["start"]) == (0.0, CONTACT_KINDS["boundary"], 0.0)
        assert row["duration"] == pytest.approx(2000 * dt, rel=1e-12)
        assert np.isnan(row["vn_end"])
