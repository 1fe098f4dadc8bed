"""fix wall/gran/region/mn: a region's surface as a wall with the boundary rule (2M -> m_i).
Its flat face is the plane wall of fix wall/gran/mn (whose e_w, tau_w test_boundary.py and
test_three_d.py check); a curved face (the inside of a cylinder) lets a sphere roll at
5/7 g sin(theta); a corner holds a sphere on three faces at once; a moving region's velocity
(a belt) and a rotating one's (a turntable) enter the contact; MPI ranks and a restart continue
the same pile."""
import numpy as np
import pytest

from granmn_run import HEADER, PLUGIN, law, restitution_error_bound, run_lammps
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


def test_a_ball_on_a_turntable_orbits_at_two_sevenths_of_its_rate(tmp_path):
    """A rotating region (region ... rotate): a solid sphere set at rest on a turntable (a
    floor turning at Omega about z) at distance rho from the axis is dragged until it rolls,
    and then, rolling without slipping, its centre obeys dv/dt = (q/(1+q)) Omega x v (q = 2/5):
    it orbits at 2 Omega/7 at constant speed, here around the axis at rho (its speed at
    sticking is 2/7 Omega rho along the table's motion). Measured over a third of an orbit
    after it sticks: the angular rate within 1 % of 2 Omega/7, the distance within 1 % of rho.
    A wall that took the region's translation only, or no wall velocity, would leave it at
    rest; one that rolled it with the table's own rate would orbit at Omega."""
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
region table block -50 50 -50 50 -1 0 side out rotate v_angle 0 0 0 0 0 1 units box
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
