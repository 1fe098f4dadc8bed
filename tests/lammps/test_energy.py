"""Where a collision's energy goes, through lmp (fix contacts/mn energy yes; docs/model.md
section 9): the global sums and the contact's row against the kinetic energy the disks lost, and
against the law's closed forms for a sticking and a sliding collision."""
import os
from pathlib import Path

import numpy as np
import pytest

from collision_decks import two_disks
from granmn_run import (HEADER, ORDER_RATIO, PLUGIN, SECOND_ORDER_RATIO, convergence_ratio,
                        energy_of, law, restitution_error_bound, run_lammps, run_scene)
from postprocess.io import SCHEMA, read_rows

# the global vector's entries (1-based, as f_c[k]) and a row's columns by the schema's names
VECTOR = {name: k + 1 for k, name in enumerate(
    (*SCHEMA["counters"], *SCHEMA["vector_extras"], *SCHEMA["energy_sums"],
     *SCHEMA["wall_work"]))}
ROW = {name: k for k, name in enumerate((*SCHEMA["rows"], *SCHEMA["row_energy"]))}
ENERGIES = SCHEMA["energy_sums"]
# two unit disks (mass 1, radius 1/2, I = m r^2/2): reduced mass 1/2, q = 3 (docs/model.md 3.1)
REDUCED_MASS, Q = 0.5, 3.0


def kinetic(atoms):
    """Translational and rotational kinetic energy of unit-density discs (mass = diameter^2)."""
    mass = atoms["mass"]
    inertia = 0.5 * mass * atoms["radius"] ** 2
    return float(np.sum(0.5 * mass * (atoms["vx"] ** 2 + atoms["vy"] ** 2)
                        + 0.5 * inertia * atoms["omegaz"] ** 2))


def collide(tmp_path, material, dt_over_tau, vy=0.0, extra=""):
    """Two unit disks meeting head-on at relative speed 1 (contact half-way through a step),
    with spin 0.6 each if `spin`, and tangential velocities +-vy: the energies of fix
    contacts/mn at the end, the kinetic energy before and after, the contact's row."""
    tau = law(*material[:3])["tau_c"]
    deck, _ = two_disks(material, tau * dt_over_tau, spin=0.6 if "spin" in extra else 0.0)
    names = " ".join(f"$(f_c[{VECTOR[name]}]:%.17g)" for name in ENERGIES)
    columns = " ".join(f"f_c[{k + 1}]" for k in range(len(ROW)))
    deck = deck.replace("group mobile type 1", f"""group mobile type 1
set atom 1 vy {vy!r}
set atom 2 vy {-vy!r}
write_dump all custom initial.txt id mass radius vx vy omegaz modify sort id format float %.17g
fix c all contacts/mn local 1 energy yes
dump rows all local 1 rows.txt {columns}
dump_modify rows format float %.17g""")
    if "limit_damping" in extra:
        deck = deck.replace("pair_style gran/mn", "pair_style gran/mn limit_damping")
    deck = deck.replace("write_dump all custom final.txt id x y vx vy omegaz",
                        f'print "RESULT energies {names}"\n'
                        "write_dump all custom final.txt id x y mass radius vx vy omegaz")
    run = run_lammps(HEADER.format(plugin=PLUGIN) + deck, tmp_path, header=False)
    before, after = run.atoms("initial.txt"), run.atoms()
    rows = [line.split() for line in (tmp_path / "rows.txt").read_text().splitlines()
            if line and not line.startswith("ITEM") and len(line.split()) == len(ROW)]
    assert len(rows) == 1, rows    # one contact, one row
    n = np.array([after["x"][0] - after["x"][1], after["y"][0] - after["y"][1]])
    n /= np.linalg.norm(n)
    v_n_after = n @ np.array([after["vx"][0] - after["vx"][1], after["vy"][0] - after["vy"][1]])
    return dict(energies=dict(zip(ENERGIES, run.result("energies"))), row=np.array(
        rows[0], dtype=float), kinetic_before=kinetic(before), kinetic_after=kinetic(after),
        v_n_after=v_n_after)


def check_budget(c):
    """Once the contact has ended its springs store nothing, and under velocity Verlet the
    booked work is the integrator's own: kinetic energy lost = dissipated, to rounding (the
    residual (dt^2/8) sum |F|^2/m vanishes with no force at either end). A booking with the
    force's power seen half a step late, a half counted twice or a term in the wrong frame
    misses by O(dt) of the collision's energy, 1e-3 and more here. The row holds the same
    contact's total and sliding part."""
    e = c["energies"]
    dissipated = e["dissipated_normal"] + e["dissipated_sticking"] + e["dissipated_sliding"]
    lost = c["kinetic_before"] - c["kinetic_after"]
    assert e["stored"] == 0.0
    assert dissipated == pytest.approx(lost, rel=1e-10, abs=1e-14)
    assert c["row"][ROW["dissipated"]] == pytest.approx(dissipated, rel=1e-12)
    assert c["row"][ROW["dissipated_sliding"]] == pytest.approx(e["dissipated_sliding"],
                                                                rel=1e-12, abs=1e-15)
    return dissipated


@pytest.mark.parametrize("e", [0.5, 0.9])
def test_head_on_collision_dissipates_one_minus_e_squared(tmp_path, e):
    """Head-on, no spin: the contact dissipates (1 - e^2) of the normal kinetic energy of the
    relative motion, (reduced mass) v_n^2 / 2 = 1/4, in its normal force, nothing
    tangentially. Velocity Verlet's restitution is first order in dt (restitution_error_bound):
    the loss then errs by at most (2 e b + b^2)/4, and halving dt halves the error."""
    errors = []
    for dt_over_tau in (1 / 100, 1 / 200):
        c = collide(tmp_path / f"dt{dt_over_tau}", (2e5, e, 0.7, 0.5), dt_over_tau)
        dissipated = check_budget(c)
        assert c["energies"]["dissipated_sticking"] == 0.0
        assert c["energies"]["dissipated_sliding"] == 0.0
        expected = (1 - e ** 2) * 0.25
        bound = restitution_error_bound(e, dt_over_tau)
        error = dissipated - expected
        print(f"e={e} dt=tau/{1 / dt_over_tau:.0f}: dissipated {dissipated:.10f} expected "
              f"{expected:.10f} error {error:+.3e} bound {(2 * e * bound + bound ** 2) / 4:.3e}")
        assert abs(error) <= (2 * e * bound + bound ** 2) / 4
        errors.append(error)
    low, high = ORDER_RATIO["verlet"]
    assert low <= errors[0] / errors[1] <= high, errors


@pytest.mark.parametrize("beta", [0.5, 0.9])
def test_sticking_collision_adds_the_tangential_share_for_beta(tmp_path, beta):
    """Both disks spinning at 0.6 (v_t = -0.6), mu = 1000: the contact sticks, and the
    tangential mode, of energy (reduced mass / q) v_t^2 / 2 = 0.03, keeps beta^2 of it: the
    contact dissipates (1 - e^2) 1/4 + (1 - beta^2) 0.03, nothing while sliding. Tolerance: each
    mode's restitution bound as above, the tangential one widened by 2 beta |ln beta| dt/tau
    (its oscillation is cut where the normal contact ends, up to a step off) and both by 1e-3
    for the line of centres' turn during the contact (as test_binary_collision's)."""
    kn, e = 256e5, 0.7
    kinetic_t = 0.5 * REDUCED_MASS / Q * 0.6 ** 2
    errors = []
    for dt_over_tau in (1 / 100, 1 / 200):
        c = collide(tmp_path / f"dt{dt_over_tau}", (kn, e, beta, 1000.0), dt_over_tau,
                    extra="spin")
        dissipated = check_budget(c)
        assert c["energies"]["dissipated_sliding"] == 0.0
        expected_n = (1 - e ** 2) * 0.25
        expected_t = (1 - beta ** 2) * kinetic_t
        b_n = restitution_error_bound(e, dt_over_tau) + 1e-3
        b_t = (restitution_error_bound(beta, dt_over_tau)
               + 2 * beta * abs(np.log(beta)) * dt_over_tau + 1e-3)
        bound = (2 * e * b_n + b_n ** 2) * 0.25 + (2 * beta * b_t + b_t ** 2) * kinetic_t
        error = dissipated - expected_n - expected_t
        print(f"beta={beta} dt=tau/{1 / dt_over_tau:.0f}: normal "
              f"{c['energies']['dissipated_normal']:.8f} ({expected_n:.8f}) sticking "
              f"{c['energies']['dissipated_sticking']:.8f} ({expected_t:.8f}) error "
              f"{error:+.3e} bound {bound:.3e}")
        assert abs(error) <= bound
        # the tangential share is there, and only there: without it the sum misses
        # (1 - beta^2) 0.03, more than the bound
        assert abs(c["energies"]["dissipated_sticking"] - expected_t) <= (
            2 * beta * b_t + b_t ** 2) * kinetic_t
        errors.append(error)
    low, high = ORDER_RATIO["verlet"]
    assert low <= errors[0] / errors[1] <= high, errors


def test_sliding_collision_does_the_coulomb_work(tmp_path):
    """Head-on at v_n = 1 with tangential velocities +-1 (v_t = -2) and mu = 0.1: the contact
    slides throughout (eta_t |v_t| > mu eta_n v_n from its first step), so the tangential force
    is mu F_n against v_t and the relative tangential velocity drops by q mu J_n / (reduced
    mass), J_n the normal impulse, (reduced mass)(v_n + v_n'), v_n' the speed the disks part at
    (limit_damping: F_n >= 0, so that the cap's |F_n| is F_n). The Coulomb force does the work
    (reduced mass / q)(v_t^2 - v_t'^2)/2, all of it booked as sliding. Velocity Verlet's forces
    see velocities half a step old: the work errs at first order (halving dt halves it), within
    the restitution bound's 3 (1 + e)|ln e| dt/tau of it. The closed form holds for a line of
    centres that does not turn: during the contact it turns by |v_t| tau_c / sigma, which moves
    the impulses between the normal and the tangent by as much (at k_n = 2e5, 1 %, more than the
    integrator's error): k_n = 2^17 1e5 makes it 1e-4, and the bound takes 2 |v_t| tau_c of the
    work on top. That part does not change with dt: the order is shown by the differences at
    dt, dt/2 and dt/4 (convergence_ratio), which it leaves out."""
    mu, e, kn = 0.1, 0.7, 2 ** 17 * 1e5
    tau = law(kn, e, 0.7)["tau_c"]
    errors = []
    for dt_over_tau in (1 / 100, 1 / 200, 1 / 400):
        c = collide(tmp_path / f"dt{dt_over_tau}", (kn, e, 0.7, mu), dt_over_tau, vy=1.0,
                    extra="limit_damping")
        check_budget(c)
        v_t = 2.0
        v_t_after = v_t - Q * mu * (1.0 + c["v_n_after"])
        expected = 0.5 * REDUCED_MASS / Q * (v_t ** 2 - v_t_after ** 2)
        sliding = c["energies"]["dissipated_sliding"]
        error = sliding - expected
        bound = (3 * (1 + e) * abs(np.log(e)) * dt_over_tau + 2 * v_t * tau) * expected
        print(f"dt=tau/{1 / dt_over_tau:.0f}: sliding {sliding:.10f} expected {expected:.10f} "
              f"error {error:+.3e} bound {bound:.3e} sticking "
              f"{c['energies']['dissipated_sticking']:+.3e}")
        assert abs(error) <= bound
        errors.append(error)
    low, high = ORDER_RATIO["verlet"]
    assert low <= convergence_ratio(errors) <= high, errors


# The floors a disk bounces on: a plane wall, the bottom face of a block region (its inside)
FLOORS = {"plane": "fix floor all wall/gran/mn yplane 0.0 NULL",
          "region": "region cup block -2.9 2.9 0 2.9 -1 1 units box\n"
                    "fix floor all wall/gran/region/mn cup"}


def bounce(tmp_path, e, beta, dt_over_tau, vx, floor="plane"):
    """One unit disk (mass 1, radius 1/2) falling at 1, sliding at vx, onto a floor (FLOORS;
    the law of the pair style, mu = 1000: it sticks), no gravity: the energies of fix
    contacts/mn once it has left the floor, the kinetic energy before and after, the contact's
    row."""
    tau = law(2e5, e, beta)["tau_c"]
    dt = tau * dt_over_tau
    names = " ".join(f"$(f_c[{VECTOR[name]}]:%.17g)" for name in ENERGIES)
    columns = " ".join(f"f_c[{k + 1}]" for k in range(len(ROW)))
    # the contact begins half-way through step 21 at every dt (the same phase: the error is
    # then smooth in dt), and the disk has left the floor at the end
    height = 0.5 + 20.5 * dt
    steps = 40 + int(np.ceil(2 * law(2e5, e, beta)["tau_w"] / dt))
    deck = f"""
boundary p f p
region box block -3 3 0 3 -0.5 0.5
create_box 1 box
create_atoms 1 single 0 {height!r} 0
set type 1 density/disc 1.2732395447351628
set atom 1 vx {vx!r} vy -1.0
pair_style gran/mn kn 2e5 e {e!r} beta {beta!r} mu 1000
pair_coeff * *
timestep {dt!r}
fix integrate all nve/sphere disc
fix flat all enforce2d
{FLOORS[floor]}
fix c all contacts/mn local 1 energy yes
dump rows all local 1 rows.txt {columns}
dump_modify rows format float %.17g
write_dump all custom initial.txt id mass radius vx vy omegaz modify sort id format float %.17g
run {steps}
print "RESULT energies {names}"
write_dump all custom final.txt id mass radius vx vy omegaz modify sort id format float %.17g
"""
    run = run_lammps(deck, tmp_path)
    rows = [line.split() for line in (tmp_path / "rows.txt").read_text().splitlines()
            if line and not line.startswith("ITEM") and len(line.split()) == len(ROW)]
    assert len(rows) == 1, rows    # one contact, one row
    assert run.atoms()["vy"][0] > 0.0    # it has left the floor
    return dict(energies=dict(zip(ENERGIES, run.result("energies"))), row=np.array(
        rows[0], dtype=float), kinetic_before=kinetic(run.atoms("initial.txt")),
        kinetic_after=kinetic(run.atoms()))


@pytest.mark.parametrize("e", [0.5, 0.9])
def test_a_bounce_on_a_plane_floor(tmp_path, e):
    """A disk bouncing on a floor at rest, beta = e: against a wall both modes last tau_w and
    keep e_w of their velocity (docs/model.md section 3), so the wall's contact dissipates
    (1 - e_w^2) of the normal kinetic energy m v_n^2/2 = 1/2 and of the tangential mode's,
    (m/q) v_t^2/2 with q = 3 (a disk on a wall: its whole mass), all booked to the disk, the
    kinetic energy lost to rounding (velocity Verlet, no force at either end). Tolerance: the
    restitution bound (restitution_error_bound at dt/tau_w) of each mode, first order: it halves
    with dt, and the error stays within it at three dt. (The measured error is not smooth in
    dt: the contact's end falls at another phase of a step at each dt; Richardson's ratio of
    three dt came out -1.3 and -1.7 for e = 0.3 and 0.9, 1.6 to 2.4 for e = 0.5, 0.7.) A wall that booked nothing, booked half (a pair's
    share) or twice, or used the pair's e instead of e_w misses by far more."""
    for dt_over_tau in (1 / 100, 1 / 200, 1 / 400):
        check_bounce_loss(bounce(tmp_path / f"dt{dt_over_tau}", e, e, dt_over_tau, BOUNCE_VX),
                          e, dt_over_tau)


BOUNCE_VX = 0.3     # the bounces' tangential speed


def check_bounce_loss(c, e, dt_over_tau):
    """A bounce (of `bounce`, with BOUNCE_VX) lost (1 - e_w^2) of both modes' energy within the
    restitution bound at dt/tau_w, none of it while sliding, and its budget closes."""
    derived = law(2e5, e, e)
    e_w, tau_w = derived["e_w"], derived["tau_w"]
    kinetic = 0.5 + 0.5 / Q * BOUNCE_VX ** 2
    dissipated = check_budget(c)
    assert c["energies"]["dissipated_sliding"] == 0.0
    expected = (1 - e_w ** 2) * kinetic
    b = restitution_error_bound(e_w, dt_over_tau * derived["tau_c"] / tau_w)
    bound = (2 * e_w * b + b ** 2) * kinetic
    error = dissipated - expected
    print(f"e={e} dt=tau/{1 / dt_over_tau:.0f}: normal {c['energies']['dissipated_normal']:.8f}"
          f" sticking {c['energies']['dissipated_sticking']:.8f} expected {expected:.8f} error "
          f"{error:+.3e} bound {bound:.3e}")
    assert abs(error) <= bound


@pytest.mark.parametrize("e", [0.5, 0.9])
def test_a_bounce_on_a_region_floor(tmp_path, e):
    """The bounce of test_a_bounce_on_a_plane_floor on the bottom face of a block region (fix
    wall/gran/region/mn, which keeps its contacts per face): the same (1 - e_w^2) of the normal
    and tangential modes' energy within the same restitution bound, the kinetic energy lost to
    rounding, and the plane floor's energies to the bit (the face's trajectory is the plane's
    bitwise, test_region_wall.py): a region wall that booked nothing, half or twice, or booked
    another slot's history, misses by far more."""
    for dt_over_tau in (1 / 100, 1 / 200, 1 / 400):
        c = bounce(tmp_path / f"dt{dt_over_tau}", e, e, dt_over_tau, BOUNCE_VX, floor="region")
        check_bounce_loss(c, e, dt_over_tau)
        plane = bounce(tmp_path / f"plane{dt_over_tau}", e, e, dt_over_tau, BOUNCE_VX)
        assert c["energies"] == plane["energies"]
        for column in SCHEMA["row_energy"]:
            assert c["row"][ROW[column]] == plane["row"][ROW[column]], column


# What fix contacts/mn energy yes refuses (docs/bad_input.md): deck text after a box with one
# disk above a floor, and the message.
BAD = {
    "energy without yes or no": ("fix c all contacts/mn energy", "energy needs yes or no"),
}


@pytest.mark.parametrize("case", sorted(BAD))
def test_bad_energy_input(tmp_path, case):
    text, message = BAD[case]
    deck = f"""
boundary p f p
region box block -3 3 0 6 -0.5 0.5
create_box 1 box
create_atoms 1 single 0 2 0
set type 1 density/disc 1.2732395447351628
pair_style gran/mn kn 2e5 e 0.7 beta 0.7 mu 0.5
pair_coeff * *
timestep 1e-5
fix integrate all nve/sphere disc
fix flat all enforce2d
{text}
run 1
"""
    run = run_lammps(deck, tmp_path, check=False)
    assert run.returncode != 0 and message in run.output, run.output[-2000:]


def test_energies_off_change_nothing(tmp_path):
    """A run that does not ask for energies is the run it was before energy yes existed: the
    same restart file to the byte (the pair's history per contact, the counters' state, their
    layout) and the same trajectory; with energy yes the trajectory is still the same to the bit
    (the booking reads the force, never changes it) and the restart file holds more. The
    global vector has the energies only when asked (f_c[9] out of range otherwise)."""
    def run(keyword, name):
        deck, _ = two_disks((2e5, 0.7, 0.7, 0.5), law(2e5, 0.7, 0.7)["tau_c"] / 100, spin=0.6)
        deck = deck.replace("group mobile type 1", "group mobile type 1\nset atom 1 vy 0.3\n"
                            f"fix c all contacts/mn local 1 {keyword}")
        # written mid-contact (it begins after step 10): the history holds a contact
        deck = deck.replace("thermo 0\nrun ", "thermo 0\nrun 15\nwrite_restart state.restart\n"
                            "run ")
        return run_lammps(HEADER.format(plugin=PLUGIN) + deck, tmp_path / name, header=False)
    for keyword, name in (("", "plain"), ("energy no", "off"), ("energy yes", "on")):
        run(keyword, name)
    read = lambda name, f: (tmp_path / name / f).read_bytes()
    assert read("off", "state.restart") == read("plain", "state.restart")
    assert len(read("on", "state.restart")) > len(read("plain", "state.restart"))
    for name in ("off", "on"):
        assert read(name, "final.txt") == read("plain", "final.txt")
    deck = "fix c all contacts/mn\nvariable e equal f_c[9]\nprint $(v_e)"
    out = run_lammps("region box block -3 3 -3 3 -0.5 0.5\ncreate_box 1 box\n"
                     "pair_style gran/mn kn 2e5 e 0.7 beta 0.7 mu 0.5\npair_coeff * *\n" + deck,
                     tmp_path / "vector", check=False)
    assert out.returncode != 0 and "out-of-range" in out.output, out.output[-2000:]


def pile(tmp_path, dt_over_tau, integrator="verlet", nprocs=1, time=2.0, restart_at=None):
    """Five unit disks dropped from heights 1.1 to 2.3 onto a row of bumps (wall_types) under
    unit gravity, moving sideways and spinning, mu = 0.5 (collisions, sliding, lasting contacts
    in the row's dimples): step, the budget kinetic + gravitational + stored + dissipated - work
    in flight, the sliding loss and the stored energy, every step."""
    kn, e, beta = 2e5, 0.7, 0.7
    dt = law(kn, e, beta)["tau_c"] * dt_over_tau
    disks = "\n".join(f"create_atoms 1 single {x!r} {y!r} 0" for x, y in
                      ((-2.2, 1.1), (-0.9, 1.4), (0.3, 1.7), (1.4, 2.0), (2.6, 2.3)))
    integrate = {"verlet": "nve/sphere disc", "ab2": "nve/ab2"}[integrator]
    f = {name: f"f_c[{k}]" for name, k in VECTOR.items()}
    deck = f"""
boundary p f p
region box block -3.5 3.5 -1 6 -0.5 0.5
create_box 2 box
{chr(10).join(f"create_atoms 2 single {x}.0 0 0" for x in range(-3, 4))}
{disks}
set type * diameter 1.0
set type * density/disc 1.2732395447351628
velocity all set 0 0 0
set type 1 vx 0.4 omega 0 0 1.0
group mobile type 1
pair_style gran/mn kn {kn} e {e} beta {beta} mu 0.5 wall_types 2
pair_coeff * *
timestep {dt!r}
fix integrate mobile {integrate}
fix gravity mobile gravity 1.0 vector 0 -1 0
fix flat all enforce2d
fix c all contacts/mn energy yes
{{outputs}}"""
    outputs = f"""compute spin mobile property/atom omegaz radius
variable rotational atom 0.25*mass*c_spin[2]^2*c_spin[1]^2
variable height atom mass*y
compute erot mobile reduce sum v_rotational
compute etrans mobile ke
compute gravitational mobile reduce sum v_height
variable budget equal c_etrans+c_erot+c_gravitational+{f['dissipated_normal']}+{f['dissipated_sticking']}+{f['dissipated_sliding']}+{f['stored']}-{f['work_in_flight']}
thermo_style custom step c_etrans
thermo_modify norm no
thermo 0
fix budget all print 1 "$(step) $(v_budget:%.17g) $({f['dissipated_sliding']}:%.17g) $({f['stored']}:%.17g) $({f['contacts_now']})" file budget.txt screen no
"""
    steps = round(time / dt)
    if restart_at is None:
        run_lammps(deck.format(outputs=outputs) + f"run {steps}\n", tmp_path, nprocs=nprocs)
        return np.loadtxt(tmp_path / "budget.txt", ndmin=2)
    first = round(restart_at / dt)
    run_lammps(deck.format(outputs=outputs) + f"run {first}\nwrite_restart state.restart\n",
               tmp_path, nprocs=nprocs)
    (tmp_path / "budget.txt").rename(tmp_path / "before.txt")
    run_lammps(f"""
plugin load {PLUGIN}
read_restart state.restart
comm_modify vel yes
neighbor 0.1 bin
timestep {dt!r}
fix integrate mobile {integrate}
fix gravity mobile gravity 1.0 vector 0 -1 0
fix flat all enforce2d
fix c all contacts/mn energy yes
{outputs}run {steps - first}
""", tmp_path, nprocs=nprocs, header=False)
    return np.vstack([np.loadtxt(tmp_path / "before.txt", ndmin=2),
                      np.loadtxt(tmp_path / "budget.txt", ndmin=2)])


@pytest.mark.parametrize("integrator", ["verlet", "ab2"])
def test_the_budget_of_a_pile_closes_at_second_order(tmp_path, integrator):
    """Five disks falling onto bumps, colliding, sliding and coming to rest: the budget keeps its
    initial value to the integrator's error, which is second order in dt (velocity Verlet: the
    exact residual (dt^2/8)(sum |F|^2/m + |T|^2/I, now - then); AB2: the trapezoidal rule's
    O(dt^2) at each begin and end, once the work in flight is counted): the largest residual
    over the run shrinks 4-fold when dt halves. Booking the power with the velocity the force saw
    (a first-order error that accumulates) or leaving out the work in flight (O(dt) jumps at
    each begin or end) would halve it only (ORDER_RATIO's lower bound 3). The residual is small
    against the energy that went (the disks' fall, several units)."""
    worst = []
    for dt_over_tau in (1 / 25, 1 / 50, 1 / 100):
        table = pile(tmp_path / f"dt{dt_over_tau}", dt_over_tau, integrator, time=3.0)
        residual = np.abs(table[:, 1] - table[0, 1])
        worst.append(residual.max())
        print(f"{integrator} dt=tau/{1 / dt_over_tau:.0f}: largest residual {worst[-1]:.3e}, "
              f"at the end {residual[-1]:.3e}, stored at the end {table[-1, 3]:.3e}, sliding "
              f"{table[-1, 2]:.3e}")
    ratios = [worst[0] / worst[1], worst[1] / worst[2]]
    print(f"ratios {ratios}")
    assert all(r >= SECOND_ORDER_RATIO for r in ratios), ratios
    assert worst[-1] <= 1e-3


def test_the_budget_is_the_same_on_two_ranks(tmp_path):
    """The pile on two ranks (the pairs across the boundary between them booked on one, their
    ghosts' shares brought home by reverse communication) gives the budget and the sliding loss
    of one rank to rounding amplified over the run (1e-9): a ghost's share lost or counted twice
    changes them by a contact's energy, 1e-2 and more."""
    one = pile(tmp_path / "one", 1 / 50, time=1.0)
    two = pile(tmp_path / "two", 1 / 50, nprocs=2, time=1.0)
    assert two.shape == one.shape
    assert one[-1, 2] != 0.0    # the disks have slid on each other or on the bumps by then
    assert two[:, 1:] == pytest.approx(one[:, 1:], rel=1e-9, abs=1e-12)


def test_no_contacts_keep_the_budget_at_rounding(tmp_path):
    """Disks falling freely, never touching: under a constant force velocity Verlet conserves
    kinetic + gravitational energy exactly, and nothing is booked: the budget stays at its
    initial value to rounding (1e-13 of it), and stored and dissipated stay 0."""
    table = pile(tmp_path, 1 / 50, time=0.25)
    assert np.all(table[:, 2:] == 0.0)
    assert table[:, 1] == pytest.approx(table[0, 1], rel=1e-13)


def test_the_collisional_scenes_budget(tmp_path):
    """The collisional flow (100 disks on a bumpy slope, periodic in x; inputs/lib/energy.lmp's
    budget with energies = yes), velocity Verlet: at each line where no contact is going on the
    exact residual (dt^2/8)(sum |F|^2/m + |T|^2/I) is 0 (gravity alone: VV is exact under a
    constant force), so e_budget is its first value to rounding, however many contacts began
    and ended, crossed the periodic boundary, changed hands at a rebuild of the neighbor lists
    (the pair (j, i) then keeps the last force with its normal flipped) or spanned the split of
    the run at average_start. A contact's tail lost or booked twice, or a normal kept unflipped
    at a rebuild, leaves a jump of the order of a collision's energy times dt/tau (1e-3 here).
    And the trajectory is that of energies = no, to the bit. The rows (contacts.txt, read by
    postprocess.io.read_rows with their energy columns) of the contacts ended by a quiet line
    hold all that was dissipated by then: each contact's total once, the global sum two halves
    of each (a half lost or counted twice differs by a collision's loss, 1e-2)."""
    common = dict(kn=2e5, run_time=3, average_start=1, output_interval=0.05,
                  integration="separate")
    run_scene("collisional_flow", tmp_path / "on", energies="yes", rows="yes", **common)
    run_scene("collisional_flow", tmp_path / "off", **common)
    on, off = energy_of(tmp_path / "on"), energy_of(tmp_path / "off")
    for name in ("e_trans", "e_rot", *SCHEMA["counters"]):
        assert np.array_equal(on[name], off[name]), name
    quiet = on["contacts_now"] == 0
    dissipated = on["dissipated_normal"] + on["dissipated_sticking"] + on["dissipated_sliding"]
    assert np.any(quiet & (dissipated > 1.0))    # lines after many collisions
    assert np.all(on["stored"][quiet] == 0.0)
    assert on["e_budget"][quiet] == pytest.approx(on["e_budget"][0], rel=1e-10)
    rows = read_rows(tmp_path / "on")
    dt = float(dict(line.split() for line in (tmp_path / "on" / "params.txt").read_text()
                    .splitlines())["dt"])
    last = np.flatnonzero(quiet & (dissipated > 1.0))[-1]
    ended = rows["start"] + rows["duration"] <= on["step"][last] * dt * (1 + 1e-12)
    assert np.sum(rows["dissipated"][ended]) == pytest.approx(dissipated[last], rel=1e-8)
    assert np.sum(rows["dissipated_sliding"][ended]) == pytest.approx(
        on["dissipated_sliding"][last], rel=1e-8, abs=1e-9)


def pile_3d(tmp_path, dt_over_tau, time=2.0):
    """pile() in 3D: eight unit spheres dropped onto a 7 x 3 grid of bumps (periodic in x and
    y), moving sideways and spinning; step, budget, sliding loss, stored energy every step and
    the number of contacts."""
    kn, e, beta = 2e5, 0.7, 0.7
    dt = law(kn, e, beta, "sphere")["tau_c"] * dt_over_tau
    bumps = "\n".join(f"create_atoms 2 single {x}.0 {y}.0 0" for x in range(-3, 4)
                      for y in (-1, 0, 1))
    spheres = "\n".join(f"create_atoms 1 single {x!r} {y!r} {z!r}" for x, y, z in (
        (-2.4, -0.6, 1.1), (-1.2, 0.5, 1.4), (0.1, -0.2, 1.6), (1.3, 0.7, 1.9),
        (2.5, -0.8, 2.1), (-0.6, 0.9, 2.5), (0.8, -0.9, 2.8), (2.0, 0.2, 3.1)))
    f = {name: f"f_c[{k}]" for name, k in VECTOR.items()}
    deck = HEADER.format(plugin=PLUGIN).replace("dimension 2", "dimension 3") + f"""
boundary p p f
region box block -3.5 3.5 -1.5 1.5 -1 6
create_box 2 box
{bumps}
{spheres}
set type * diameter 1.0
set type * density 1.0
velocity all set 0 0 0
set type 1 vx 0.4 vy -0.3 omega 0.5 0 1.0
group mobile type 1
pair_style gran/mn kn {kn} e {e} beta {beta} mu 0.5 wall_types 2
pair_coeff * *
timestep {dt!r}
fix integrate mobile nve/sphere
fix gravity mobile gravity 1.0 vector 0 0 -1
fix c all contacts/mn energy yes
variable height atom mass*z
compute erot mobile erotate/sphere
compute etrans mobile ke
compute gravitational mobile reduce sum v_height
variable budget equal c_etrans+c_erot+c_gravitational+{f['dissipated_normal']}+{f['dissipated_sticking']}+{f['dissipated_sliding']}+{f['stored']}-{f['work_in_flight']}
thermo_modify norm no
thermo 0
fix budget all print 1 "$(step) $(v_budget:%.17g) $({f['dissipated_sliding']}:%.17g) $({f['stored']}:%.17g) $({f['contacts_now']})" file budget.txt screen no
run {round(time / dt)}
"""
    return run_lammps(deck, tmp_path, header=False).table("budget.txt")


def test_the_budget_of_a_3d_pile(tmp_path):
    """The 3D overloads (u_t a vector in the tangent plane, the last force's normal and
    tangential vector kept): with no contact going on the budget is its initial value to
    rounding (velocity Verlet's residual vanishes with the contact forces), and its largest
    residual shrinks 4-fold when dt halves (ORDER_RATIO's lower bound 3: first order would halve
    it). A tail in the wrong frame or a 2D-only term leaves a jump of a collision's energy times
    dt/tau. (No pair here changes lists while in contact: the flip of the kept vectors then is
    checked in 2D only, by the collisional scene.)"""
    worst = []
    for dt_over_tau in (1 / 25, 1 / 50, 1 / 100):
        table = pile_3d(tmp_path / f"dt{dt_over_tau}", dt_over_tau)
        residual = np.abs(table[:, 1] - table[0, 1])
        quiet = table[:, 4] == 0
        assert np.any(quiet & (table[:, 0] > table[np.argmax(table[:, 4] > 0), 0]))
        assert np.all(residual[quiet] <= 1e-12 * abs(table[0, 1]) + 1e-12)
        worst.append(residual.max())
        print(f"3D dt=tau/{1 / dt_over_tau:.0f}: largest residual {worst[-1]:.3e}, sliding "
              f"{table[-1, 2]:.3e}")
    ratios = [worst[0] / worst[1], worst[1] / worst[2]]
    print(f"ratios {ratios}")
    assert all(r >= SECOND_ORDER_RATIO for r in ratios), ratios



def test_the_3d_chutes_budget_closes_at_second_order(tmp_path):
    """The 3D chute (inputs/chute_3d.lmp, its floor of fixed spheres; energies = yes, velocity
    Verlet), 100 spheres falling onto the base and starting to flow, 700 contacts between them
    and 300 with the base in 3 time units: the budget's residual, its root mean square over the
    run's lines, shrinks 4-fold when dt halves (ORDER_RATIO's lower bound 3). A contact's
    energies booked with the velocity the force saw, or its work in flight left out, is first
    order (ratio 2). The trajectories at the three dt part ways (a dense flow is chaotic): the
    mean over 150 lines, not one line, is what converges."""
    rms = []
    for fraction in (0.04, 0.02, 0.01):
        run_scene("chute_3d", tmp_path / f"dt{fraction}", energies="yes", spheres=100, kn=2e4,
                  dt_fraction=fraction, dt_cap=1, run_time=3, average_start=1,
                  output_interval=0.02)
        table = energy_of(tmp_path / f"dt{fraction}")
        assert table["begun_boundary"][-1] > 100 and table["begun_disk"][-1] > 300
        residual = table["e_budget"] - table["e_budget"][0]
        rms.append(np.sqrt(np.mean(residual ** 2)))
        print(f"dt = {fraction} tau_c: rms residual {rms[-1]:.3e}, dissipated "
              f"{table['dissipated_normal'][-1] + table['dissipated_sticking'][-1]:.3f}")
    ratios = [rms[0] / rms[1], rms[1] / rms[2]]
    print(f"ratios {ratios}")
    assert all(r >= SECOND_ORDER_RATIO for r in ratios), ratios

def test_the_budget_across_a_restart_file(tmp_path):
    """The pile written to a restart file in the middle of its collisions (t = 0.8) and continued
    from it: the per-atom energies (fix contacts/mn's state) and each contact's energy history
    (the pair's, with its last force) come back, so that at every step with no contact going
    on, before the restart and after, the budget is its first value to rounding. A contact's
    history not restored (its account started afresh) or the per-atom sums lost would leave a
    jump of the energy dissipated so far, of order 1."""
    table = pile(tmp_path, 1 / 50, time=2.0, restart_at=0.8)
    quiet = table[:, 4] == 0
    after = table[:, 0] > table[np.argmax(table[:, 4] > 0), 0]
    assert np.any(quiet & after & (np.arange(len(table)) > len(table) // 2))
    assert table[quiet, 1] == pytest.approx(table[0, 1], rel=1e-12)
    assert table[-1, 2] != 0.0



# The region of region_box and how it moves: a V at rest (y > |x|, the intersection of two
# planes at 45 degrees: a disk at its bottom touches both faces); the V rising at 0.1 (a lift:
# the disks come to rest in it and ride up); a box that wiggles (along x
# and y, the floor's peak acceleration 0.8 g: the disks are dragged and pushed); a drum that turns (a
# circle of radius 2.5 about (0, 2.5) at 1 radian a unit time: the disks are carried up).
REGION_MOTIONS = {
    "still": "region left plane 0 0 0 1 1 0 units box\nregion right plane 0 0 0 -1 1 0 units box\n"
             "region cup intersect 2 left right",
    "lift": "variable lift equal 0.1*step*dt\n"
            "region left plane 0 0 0 1 1 0 move NULL v_lift NULL units box\n"
            "region right plane 0 0 0 -1 1 0 move NULL v_lift NULL units box\n"
            "region cup intersect 2 left right",
    "wiggle": "variable wx equal 0.1*sin(2*PI*time)\nvariable wy equal 0.02*sin(2*PI*time)\n"
              "region cup block -2.5 2.5 0 5.5 -1 1 move v_wx v_wy NULL units box",
    "drum": "variable angle equal 1.0*time\n"
            "region cup cylinder z 0 2.5 2.5 -1 1 rotate v_angle 0 2.5 0 0 0 1 units box",
}


def region_box(tmp_path, dt_over_tau, integrator="verlet", motion="still", time=8.0,
               restart_at=None, nprocs=1):
    """Four unit disks in a region (fix wall/gran/region/mn; REGION_MOTIONS) under unit gravity,
    thrown sideways and spinning, mu = 0.5: disks slide along the floor into the corners, touch
    two faces at once, leave one face for the other (their contacts change slots), collide and
    come to rest. Step, the budget kinetic + gravitational + stored + dissipated - work in
    flight - work of the walls, the walls' work, the stored energy, the contacts, the
    boundary contacts begun and sum |F|^2/m + |T|^2/I, every step; and the disks at the end.
    restart_at: the run written to a restart file at that time and continued from it by
    another lmp (the lines of both, the step of the restart twice); nprocs: MPI ranks."""
    kn, e, beta = 2e5, 0.7, 0.7
    dt = law(kn, e, beta)["tau_c"] * dt_over_tau
    throws = ((-1.2, 2.2, 1.0, 2.0), (1.2, 2.3, -0.5, -1.0), (0.2, 1.4, 0.3, 0.5),
              (-0.4, 3.0, -0.5, 0.0))
    disks = "\n".join(f"create_atoms 1 single {x!r} {y!r} 0" for x, y, _, _ in throws)
    velocities = "\n".join(f"set atom {k + 1} vx {vx!r} omega 0 0 {w!r}"
                           for k, (_, _, vx, w) in enumerate(throws))
    integrate = {"verlet": "nve/sphere disc", "ab2": "nve/ab2"}[integrator]
    f = {name: f"f_c[{k}]" for name, k in VECTOR.items()}
    setup = f"""
boundary f f p
region box block -3 3 -0.5 6 -0.5 0.5
create_box 1 box
{disks}
set type 1 diameter 1.0
set type 1 density/disc 1.2732395447351628
velocity all set 0 0 0
{velocities}
pair_style gran/mn kn {kn} e {e} beta {beta} mu 0.5
pair_coeff * *
"""
    dynamics = f"""timestep {dt!r}
fix integrate all {integrate}
fix gravity all gravity 1.0 vector 0 -1 0
fix flat all enforce2d
{REGION_MOTIONS[motion]}
fix walls all wall/gran/region/mn cup
fix c all contacts/mn energy yes
compute spin all property/atom omegaz radius
variable rotational atom 0.25*mass*c_spin[2]^2*c_spin[1]^2
variable height atom mass*y
compute erot all reduce sum v_rotational
compute etrans all ke
compute gravitational all reduce sum v_height
compute torque all property/atom tqz
variable kicks atom (fx^2+fy^2)/mass+c_torque^2/(0.5*mass*c_spin[2]^2)
compute kicks all reduce sum v_kicks
variable budget equal c_etrans+c_erot+c_gravitational+{f['dissipated_normal']}+{f['dissipated_sticking']}+{f['dissipated_sliding']}+{f['stored']}-{f['work_in_flight']}-{f['work_of_walls']}
thermo_modify norm no
thermo 0
fix budget all print 1 "$(step) $(v_budget:%.17g) $({f['work_of_walls']}:%.17g) $({f['stored']}:%.17g) $({f['contacts_now']}) $({f['begun_boundary']}) $(c_kicks:%.17g)" file budget.txt screen no
"""
    final = (f"write_dump all custom final.txt id x y vx vy f_c[{VECTOR['contacts_now']}] "
             "modify sort id format float %.17g\n")
    steps = round(time / dt)
    if restart_at is None:
        run = run_lammps(setup + dynamics + f"run {steps}\n" + final, tmp_path, nprocs=nprocs)
        return run.table("budget.txt"), run.atoms()
    first = round(restart_at / dt)
    run_lammps(setup + dynamics + f"run {first}\nwrite_restart state.restart\n", tmp_path)
    (tmp_path / "budget.txt").rename(tmp_path / "before.txt")
    run = run_lammps(f"""
plugin load {PLUGIN}
read_restart state.restart
comm_modify vel yes
neighbor 0.1 bin
{dynamics}run {steps - first}
{final}""", tmp_path, header=False)
    return np.vstack([np.loadtxt(tmp_path / "before.txt", ndmin=2),
                      run.table("budget.txt")]), run.atoms()


def largest_residuals(tmp_path, integrator, motion):
    """The largest budget residual of region_box at dt = tau/25, /50, /100 (and the runs).
    Under velocity Verlet the booked work is the integrator's own: the residual is, at every
    step, exactly (dt^2/8)(sum |F|^2/m + |T|^2/I now - at the start) (docs/model.md section 9),
    checked here to rounding of the energies involved (1e-10 of them; measured 3e-12): a wall
    whose work, or a contact whose energy, was booked otherwise (a tail against the wrong face,
    a history left in a slot its contact has left, the wall's velocity of another step) would
    leave an error of the order of a contact's energy times dt/tau or more."""
    worst, runs = [], []
    for dt_over_tau in (1 / 25, 1 / 50, 1 / 100):
        table, atoms = region_box(tmp_path / f"dt{dt_over_tau}", dt_over_tau, integrator, motion)
        residual = np.abs(table[:, 1] - table[0, 1])
        if integrator == "verlet":
            dt = law(2e5, 0.7, 0.7)["tau_c"] * dt_over_tau
            closed_form = dt ** 2 / 8 * (table[:, 6] - table[0, 6])
            scale = abs(table[0, 1]) + np.abs(table[:, 2]).max()
            assert table[:, 1] - table[0, 1] == pytest.approx(closed_form, rel=0, abs=1e-10 * scale)
        worst.append(residual.max())
        runs.append((table, atoms))
        print(f"{motion} {integrator} dt=tau/{1 / dt_over_tau:.0f}: largest residual "
              f"{worst[-1]:.3e}, walls' work at the end {table[-1, 2]:+.4e} (largest "
              f"{np.abs(table[:, 2]).max():.3e}), boundary contacts begun {table[-1, 5]:.0f}")
    print(f"ratios {[worst[0] / worst[1], worst[1] / worst[2]]}")
    return worst, runs


@pytest.mark.parametrize("integrator", ["verlet", "ab2"])
def test_the_budget_of_disks_in_a_region_box_closes_at_second_order(tmp_path, integrator):
    """Four disks in a block region at rest (region_box): their contacts with its faces begin
    and end in any order, so a face's contact moves from slot to slot with its history, and a
    disk comes to rest in a corner on two faces at once. The budget keeps its initial value to
    the integrator's error, second order: its largest residual shrinks 4-fold when dt halves
    (ORDER_RATIO's lower bound 3; a contact's energy history left in its old slot when the
    contact moves, or a tail booked against the wrong face, would leave a jump of the order of
    a contact's energy, which does not shrink with dt). The walls do no work."""
    worst, runs = largest_residuals(tmp_path, integrator, "still")
    assert all(worst[k] / worst[k + 1] >= SECOND_ORDER_RATIO for k in range(2)), worst
    assert worst[-1] <= 1e-3
    for table, _ in runs:
        assert np.all(table[:, 2] == 0.0)
        assert table[-1, 5] > 4 * 10    # many more contacts with the faces than disks
    # a disk at rest at the bottom of the V, its centre within a radius of both faces (at some
    # dt: the pile may jam otherwise)
    assert any(np.any((atoms["y"] + atoms["x"] < 0.5 * np.sqrt(2))
                      & (atoms["y"] - atoms["x"] < 0.5 * np.sqrt(2))) for _, atoms in runs)


@pytest.mark.parametrize("integrator", ["verlet", "ab2"])
@pytest.mark.parametrize("motion", ["wiggle", "drum"])
def test_a_moving_regions_work_closes_the_budget(tmp_path, motion, integrator):
    """The disks of region_box in a box that wiggles or a drum that turns: the walls' forces
    work on the disks (fix contacts/mn's work_of_walls: each contact's force on the wall's
    velocity at the contact, booked with the integrator's step as the contact's own work), and
    the budget that counts it keeps its initial value to the integrator's error: velocity
    Verlet's closed form (largest_residuals), and under AB2 second order in dt (ratio >= 3;
    the runs part ways between dt, where collisions happen otherwise, so that the largest
    residual is not smooth in dt: the ratio is not checked under velocity Verlet, whose
    closed form is the sharper check). The walls' work is far larger than the residual: a
    budget without it, or with the wall's power taken at another step than the contact's (a
    first-order error), would not close so."""
    worst, runs = largest_residuals(tmp_path, integrator, motion)
    if integrator == "ab2":
        assert all(worst[k] / worst[k + 1] >= SECOND_ORDER_RATIO for k in range(2)), worst
    for table, _ in runs:
        assert np.abs(table[:, 2]).max() > 1e3 * worst[-1]



def test_a_region_walls_energies_across_a_restart_file(tmp_path):
    """Disks in the rising V of region_box written to a restart file at t = 8, while they
    rest in it, and continued from it (its displacement a function of the step, which the
    restart file keeps: LAMMPS's time starts anew from it): each face contact's energy history (its last force,
    in the fix's per-atom rows) and fix contacts/mn's sums, the walls' work among them, come
    back. The budget at the restart's step is the same before and after to rounding (1e-12 of
    it; the sums or the walls' work lost would change it by what was dissipated or done, of
    order 1), and after it the residual is velocity Verlet's closed form from there
    (the run's setup evaluates the forces anew; a contact's tail booked with no force kept, its
    history lost, would miss it by a contact's work over half a step). The disks then ride the
    lift at rest: its work is their gain of gravitational energy, 4 m g v_lift a unit time."""
    dt = law(2e5, 0.7, 0.7)["tau_c"] / 50
    table, _ = region_box(tmp_path, 1 / 50, motion="lift", time=9.0, restart_at=8.0)
    at = np.flatnonzero(table[1:, 0] == table[:-1, 0])
    assert len(at) == 1    # the restart's step, twice
    before, after = table[:at[0] + 1], table[at[0] + 1:]
    assert after[0, 4] > 0 and after[-1, 4] > 0    # contacts going on across the restart
    # at rest in the lift, the disks (mass 1 each) gain m g v_lift a unit time: the lift's work
    assert after[-1, 2] - after[0, 2] == pytest.approx(4 * 1.0 * 0.1 * 1.0, rel=1e-3)
    assert abs(after[0, 2]) > 0.1    # the walls had done work
    scale = abs(table[0, 1]) + np.abs(table[:, 2]).max()
    assert after[0, 1] == pytest.approx(before[-1, 1], rel=0, abs=1e-12 * scale)
    for part in (before, after):
        closed_form = dt ** 2 / 8 * (part[:, 6] - part[0, 6])
        assert part[:, 1] - part[0, 1] == pytest.approx(closed_form, rel=0, abs=1e-10 * scale)

def test_a_region_walls_energies_are_the_same_on_two_ranks(tmp_path):
    """The turning drum of region_box on two ranks (disks and their face contacts' histories
    moving between them, the walls' work summed over both) gives the budget, the walls' work
    and the stored energy of one rank to rounding amplified over the run (1e-9): a history
    lost on the way or a share counted on both ranks changes them by a contact's energy."""
    one, _ = region_box(tmp_path / "one", 1 / 50, motion="drum", time=2.0)
    two, _ = region_box(tmp_path / "two", 1 / 50, motion="drum", time=2.0, nprocs=2)
    assert two.shape == one.shape
    assert abs(one[-1, 2]) > 1.0    # the drum has worked on the disks
    assert two[:, 1:4] == pytest.approx(one[:, 1:4], rel=1e-9, abs=1e-12)


def test_a_region_walls_energies_off_change_nothing(tmp_path):
    """fix wall/gran/region/mn under fix contacts/mn without energies, with energy no and with
    energy yes (the turning drum, velocity Verlet and AB2): the same trajectory and counters to
    the bit (the booking reads the forces, never changes them), and without energies the same
    restart file to the byte (the fix's rows keep no energy history)."""
    def run(integrator, keyword):
        dt = law(2e5, 0.7, 0.7)["tau_c"] / 50
        deck = f"""
boundary f f p
region box block -3 3 -0.5 6 -0.5 0.5
create_box 1 box
create_atoms 1 single -1.2 2.2 0
create_atoms 1 single 0.2 1.4 0
set type 1 diameter 1.0
set type 1 density/disc 1.2732395447351628
set atom 1 vx 1.0 omega 0 0 2.0
pair_style gran/mn kn 2e5 e 0.7 beta 0.7 mu 0.5
pair_coeff * *
timestep {dt!r}
fix integrate all {integrator}
fix gravity all gravity 1.0 vector 0 -1 0
fix flat all enforce2d
{REGION_MOTIONS["drum"]}
fix walls all wall/gran/region/mn cup
fix c all contacts/mn local 1 {keyword}
thermo 0
run {round(2.0 / dt)}
write_restart state.restart
write_dump all custom final.txt id x y vx vy omegaz f_c[1] f_c[2] f_c[3] f_c[4] f_c[5] f_c[6] modify sort id format float %.17g
"""
        name = f"{integrator.split()[0].replace('/', '_')}{keyword.replace(' ', '_')}"
        run_lammps(deck, tmp_path / name)
        return lambda f: (tmp_path / name / f).read_bytes()
    for integrator in ("nve/sphere disc", "nve/ab2"):
        plain, off, on = (run(integrator, keyword) for keyword in ("", "energy no", "energy yes"))
        assert off("state.restart") == plain("state.restart")
        assert len(on("state.restart")) > len(plain("state.restart"))
        for energies in (off, on):
            assert energies("final.txt") == plain("final.txt")

def test_a_moving_regions_work_in_3d(tmp_path):
    """Five spheres in a box region that wiggles along x and z (3D: the wall's work on a sphere
    is its last force, normal and tangential vector, on the wall's velocity; velocity Verlet):
    at every step the budget's residual is its closed form (dt^2/8)(sum |F|^2/m + |T|^2/I now
    - at the start) to rounding (1e-10 of the energies; measured 8e-13), at two dt, while the
    walls do work of order 0.5: a tangential force left out of the wall's work, or the previous
    evaluation's normal taken for this one's, would leave an error of order dt/tau of it."""
    kn, e, beta = 2e5, 0.7, 0.7
    spheres = "\n".join(f"create_atoms 1 single {x!r} {y!r} {z!r}" for x, y, z in (
        (-1.2, -0.5, 0.9), (1.1, 0.6, 1.4), (0.1, -0.2, 2.0), (-0.6, 1.2, 2.6),
        (0.9, -1.1, 3.1)))
    for dt_over_tau in (1 / 25, 1 / 50):
        dt = law(kn, e, beta, "sphere")["tau_c"] * dt_over_tau
        deck = HEADER.format(plugin=PLUGIN).replace("dimension 2", "dimension 3") + f"""
boundary f f f
region box block -3 3 -3 3 -0.5 6
create_box 1 box
{spheres}
set type 1 diameter 1.0
set type 1 density 1.0
velocity all set 0 0 0
set type 1 vx 0.6 vy -0.4 omega 0.5 -1.0 1.5
pair_style gran/mn kn {kn} e {e} beta {beta} mu 0.5
pair_coeff * *
timestep {dt!r}
fix integrate all nve/sphere
fix gravity all gravity 1.0 vector 0 0 -1
variable wx equal 0.1*sin(2*PI*time)
variable wz equal 0.02*sin(2*PI*time)
region cup block -2.5 2.5 -2.5 2.5 0 5.5 move v_wx NULL v_wz units box
fix walls all wall/gran/region/mn cup
fix c all contacts/mn energy yes
compute erot all erotate/sphere
compute etrans all ke
variable height atom mass*z
compute gravitational all reduce sum v_height
compute spin all property/atom radius tqx tqy tqz
variable kicks atom (fx^2+fy^2+fz^2)/mass+(c_spin[2]^2+c_spin[3]^2+c_spin[4]^2)/(0.4*mass*c_spin[1]^2)
compute kicks all reduce sum v_kicks
variable budget equal c_etrans+c_erot+c_gravitational+f_c[{VECTOR['dissipated_normal']}]+f_c[{VECTOR['dissipated_sticking']}]+f_c[{VECTOR['dissipated_sliding']}]+f_c[{VECTOR['stored']}]-f_c[{VECTOR['work_of_walls']}]
thermo_modify norm no
thermo 0
fix budget all print 1 "$(step) $(v_budget:%.17g) $(f_c[{VECTOR['work_of_walls']}]:%.17g) $(c_kicks:%.17g) $(f_c[{VECTOR['begun_boundary']}])" file budget.txt screen no
run {round(3.0 / dt)}
"""
        table = run_lammps(deck, tmp_path / f"dt{dt_over_tau}", header=False).table("budget.txt")
        residual = table[:, 1] - table[0, 1]
        closed_form = dt ** 2 / 8 * (table[:, 3] - table[0, 3])
        scale = abs(table[0, 1]) + np.abs(table[:, 2]).max()
        print(f"3D wiggle dt=tau/{1 / dt_over_tau:.0f}: largest residual "
              f"{np.abs(residual).max():.3e}, off the closed form by "
              f"{np.abs(residual - closed_form).max():.3e}; walls' work {table[-1, 2]:+.4e}, "
              f"boundary contacts begun {table[-1, 4]:.0f}")
        assert residual == pytest.approx(closed_form, rel=0, abs=1e-10 * scale)
        assert np.abs(table[:, 2]).max() > 0.1
        assert table[-1, 4] > 5

# Three disks resting on a plane floor and one dropped onto two of them, energy yes: the
# floor's contacts go on across step RESTING_HALF (the dropped disk bounces on the others).
RESTING = """
boundary p f p
region box block -3 3 0 6 -0.5 0.5
create_box 1 box
create_atoms 1 single -1.0 0.5 0
create_atoms 1 single 0.0 0.5 0
create_atoms 1 single 1.0 0.5 0
create_atoms 1 single -0.5 1.4 0
set type 1 diameter 1.0
set type 1 density/disc 1.2732395447351628
set atom 4 vx 0.3 omega 0 0 1.0
pair_style gran/mn kn 2e5 e 0.7 beta 0.7 mu 0.5
pair_coeff * *
"""
RESTING_STYLES = """timestep 1e-4
fix integrate all nve/sphere disc
fix gravity all gravity 1.0 vector 0 -1 0
fix flat all enforce2d
fix floor all wall/gran/mn yplane 0.0 NULL
fix c all contacts/mn energy yes
thermo 0
"""
RESTING_HALF = 6000
RESTING_SECOND_HALF = (f"run {RESTING_HALF}\n"
                       f'print "RESULT energies {" ".join(f"$(f_c[{VECTOR[name]}]:%.17g)" for name in (*ENERGIES, "work_of_walls"))}"\n'
                       "write_dump all custom final.txt id x y vx vy omegaz modify sort id "
                       "format float %.17g\n")
# RESTING at step RESTING_HALF, written (`run`, then `write_restart`) by the plugin before fix
# contacts/mn kept the walls' work: its per-atom energies are one column shorter.
ENERGY_WITHOUT_WALL_WORK = (Path(__file__).resolve().parent / "restart_files"
                            / "resting_energy_without_wall_work.restart")


@pytest.mark.skipif(os.environ.get("GRANMN_LAMMPS_GENERATION", "debian12") != "debian12",
                    reason="the file is of LAMMPS 29 Sep 2021 (a restart file of another LAMMPS "
                           "continues into another trajectory, test_cylinder_wall.py)")
def test_an_energy_restart_file_of_the_plugin_before_the_walls_work_continues(tmp_path):
    """A restart file with energy yes written before fix contacts/mn kept the walls' work (its
    per-atom state one column shorter, read with that column 0: no wall moved) continues the run
    as this plugin's own split run does: the same energy sums, walls' work 0, and final state to
    the bit. A state read at another offset, or refused, would change or stop them."""
    split = run_lammps(RESTING + RESTING_STYLES + f"run {RESTING_HALF}\n" + RESTING_SECOND_HALF,
                       tmp_path / "split")
    continued = run_lammps(f"plugin load {PLUGIN}\nread_restart {ENERGY_WITHOUT_WALL_WORK}\n"
                           "neighbor 0.1 bin\ncomm_modify vel yes\n" + RESTING_STYLES
                           + RESTING_SECOND_HALF, tmp_path / "continued", header=False)
    energies = split.result("energies")
    print(f"energies at the end: {energies}")
    assert energies[-1] == 0.0 and sum(energies[:3]) > 0.01 and energies[3] > 0.0
    assert continued.result("energies") == energies
    assert ((continued.workdir / "final.txt").read_text()
            == (split.workdir / "final.txt").read_text())

def test_the_frictional_scenes_budget(tmp_path):
    """The frictional flow (its floor a plane wall fix, fix wall/gran/mn; energies = yes),
    velocity Verlet: at each line where no contact is going on the exact residual
    (dt^2/8)(sum |F|^2/m + |T|^2/I) is 0, so e_budget is its first value to rounding once the
    disks have hit the floor and one another. A floor contact's energies booked half, twice, a
    step late or not at all leave a jump of the order of its loss times dt/tau or more (1e-4
    and up here). And the trajectory is that of energies = no, to the bit."""
    common = dict(kn=2e5, run_time=4, average_start=0.5, output_interval=0.05)
    run_scene("frictional_flow", tmp_path / "on", energies="yes", **common)
    run_scene("frictional_flow", tmp_path / "off", **common)
    on, off = energy_of(tmp_path / "on"), energy_of(tmp_path / "off")
    for name in ("e_trans", "e_rot", *SCHEMA["counters"]):
        assert np.array_equal(on[name], off[name]), name
    quiet = on["contacts_now"] == 0
    dissipated = on["dissipated_normal"] + on["dissipated_sticking"] + on["dissipated_sliding"]
    assert on["begun_boundary"][-1] > 0    # the floor's contacts are in the budget
    assert np.any(quiet & (dissipated > 1.0))
    assert np.all(on["stored"][quiet] == 0.0)
    assert on["e_budget"][quiet] == pytest.approx(on["e_budget"][0], rel=1e-10)
