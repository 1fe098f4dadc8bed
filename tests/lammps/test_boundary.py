"""A disk against an immobile boundary element: a bump (a wall-type atom of the pair style)
and the flat wall of fix wall/gran/mn. Both use m_i for 2M (docs/model.md section 2), so the contact
lasts tau_w and has restitution e_w."""
import numpy as np
import pytest

import test_cylinder_wall as walls
from collision_decks import contact_interval, disk_on_boundary
from granmn_run import (HEADER, ORDER_RATIO, PLUGIN, ab2_error_bound, convergence_ratio, law,
                        restitution_error_bound, run_lammps)


@pytest.mark.parametrize("boundary", ["bump", "wall"])
@pytest.mark.parametrize("e", [0.5, 0.7, 0.9])
def test_boundary_contact_duration_and_restitution(tmp_path, boundary, e):
    kn = 2e5
    ref = law(kn, e, 0.7)
    errors = []
    for dt_over_tau in (1 / 100, 1 / 200):
        dt = ref["tau_w"] * dt_over_tau
        deck, contact = disk_on_boundary((kn, e, 0.7, 0.5), dt, boundary)
        run = run_lammps(deck, tmp_path / f"dt{dt_over_tau}")
        atoms = run.atoms()
        mobile = np.argmax(atoms["id"])
        e_measured = atoms["vy"][mobile] / 1.0
        duration, _, _ = contact_interval(run.table("trace.txt"), contact, dt)
        error = e_measured - ref["e_w"]
        print(f"{boundary} e={e} dt=tau_w/{1/dt_over_tau:.0f}: e_w={ref['e_w']:.5f} "
              f"measured {e_measured:.5f} duration/tau_w {duration/ref['tau_w']:.5f}")
        assert abs(error) <= restitution_error_bound(ref["e_w"], dt_over_tau)
        assert abs(duration - ref["tau_w"]) <= dt
        # head-on: no tangential force, no spin
        assert abs(atoms["vx"][mobile]) < 1e-12
        errors.append(error)
    assert 1.5 <= errors[0] / errors[1] <= 2.6, errors
    if boundary == "bump":
        # the bump was not integrated: it has not moved
        assert atoms["y"][np.argmin(atoms["id"])] == 0.0


@pytest.mark.parametrize("integrator", ["verlet", "ab2"])
@pytest.mark.parametrize("boundary", ["bump", "wall"])
def test_sticking_oblique_bounce_converges_at_the_integrators_order(tmp_path, boundary,
                                                                    integrator):
    """A spinning disk (spin-only slip, mu = 1e6: it sticks) bouncing on the boundary with
    beta = e = 0.7. With beta = e the boundary's sticking tangential mode is its normal one
    (3 eta_t = eta_n and 3 kt = kn, docs/model.md section 3), so the normal and the tangential
    restitution are both e_w, and the contact lasts tau_w. At dt = tau_w/50, /100, /200 they
    converge at the integrator's order: first under velocity Verlet, second under fix nve/ab2
    (with u_t advanced by v_t(t) dt, AB2's tangential restitution was first order, -2.5 % at
    tau_w/100). Each value within the integrator's bound (granmn_run.py), plus 1e-3 on the bump
    for the turn of the line of centres."""
    kn, e, spin = 256e5, 0.7, 1.2
    ref = law(kn, e, e)
    fractions = (1 / 50, 1 / 100, 1 / 200)
    measured = []
    for fraction in fractions:
        dt = ref["tau_w"] * fraction
        deck, contact = disk_on_boundary((kn, e, e, 1e6), dt, boundary, spin=spin,
                                         integrator=integrator)
        run = run_lammps(deck, tmp_path / f"dt{fraction}")
        atoms = run.atoms()
        mobile, fixed = np.argmax(atoms["id"]), np.argmin(atoms["id"])
        if boundary == "bump":    # the normal from the bump to the disk, t = (-n_y, n_x)
            n = np.array([atoms["x"][mobile] - atoms["x"][fixed],
                          atoms["y"][mobile] - atoms["y"][fixed]])
            n /= np.linalg.norm(n)
        else:
            n = np.array([0.0, 1.0])
        v = np.array([atoms["vx"][mobile], atoms["vy"][mobile]])
        v_t = -n[1] * v[0] + n[0] * v[1] - 0.5 * atoms["omegaz"][mobile]
        duration, _, _ = contact_interval(run.table("trace.txt"), contact, dt)
        measured.append((n @ v / 1.0, -v_t / -(0.5 * spin), duration / ref["tau_w"]))
        print(f"{boundary} {integrator} dt=tau_w/{1 / fraction:.0f}: e_w={ref['e_w']:.6f} "
              f"measured {measured[-1][0]:.6f}, tangential {measured[-1][1]:.6f}, "
              f"duration/tau_w {measured[-1][2]:.6f}")
    geometry = 1e-3 if boundary == "bump" else 0.0
    for fraction, (e_measured, beta_measured, duration) in zip(fractions, measured):
        bound = (ab2_error_bound(fraction) if integrator == "ab2"
                 else restitution_error_bound(ref["e_w"], fraction))
        assert abs(e_measured - ref["e_w"]) <= bound + geometry
        assert abs(beta_measured - ref["e_w"]) <= bound + geometry
        assert abs(duration - 1) <= (ab2_error_bound(fraction) if integrator == "ab2" else fraction)
    low, high = ORDER_RATIO[integrator]
    for k, name in enumerate(("e_w", "tangential", "duration")):
        ratio = convergence_ratio([m[k] for m in measured])
        print(f"{name}: convergence ratio {ratio:.2f}")
        assert low <= ratio <= high, (name, ratio)


def test_pair_style_given_again_follows_its_new_wall_types(tmp_path):
    """Two type-2 disks at rest, overlapping by 0.1, not integrated (bumps stay where they
    are). While type 2 is a wall type, the pair is kept out of the neighbor list (bumps never
    interact): no force. Given again without wall_types, they are disks like any other and
    push each other apart with 2M kn delta = kn delta = 2e4 (unit masses, at rest: no
    damping); given a third time with wall_types 2, the force is gone again."""
    text = """
region box block -5 5 -5 5 -0.5 0.5
create_box 2 box
create_atoms 2 single -0.45 0 0
create_atoms 2 single 0.45 0 0
set type * diameter 1.0
set type * density/disc 1.2732395447351628
timestep 5e-5
variable fx1 equal fx[1]
"""
    for k, keywords in enumerate(["wall_types 2", "", "wall_types 2"]):
        text += (f"pair_style gran/mn kn 2e5 e 0.7 beta 0.7 mu 0.5 {keywords}\npair_coeff * *\n"
                 f"run 0\nprint \"RESULT fx{k} ${{fx1}}\"\n")
    run = run_lammps(text, tmp_path)
    assert run.result("fx0") == [0.0] and run.result("fx2") == [0.0]
    assert run.result("fx1")[0] == pytest.approx(-2e4, rel=1e-9)


def limit_damping_restitution(kn, e):
    """Restitution of a normal collision with the boundary when the normal force is clamped
    at zero: delta = (v0/w) exp(-g t) sin(w t) (g = eta_n/2, w^2 = kn - g^2) until
    kn delta + eta_n delta' = 0, where the disk leaves with delta'."""
    eta = law(kn, e, 0.7)["eta_n"]
    g, w = eta / 2, np.sqrt(kn - eta * eta / 4)
    phase = np.pi - np.arctan2(eta * w, kn - eta * g)    # w t at the release, in (pi/2, pi)
    return np.exp(-g * phase / w) * abs(np.cos(phase) - g / w * np.sin(phase))


@pytest.mark.parametrize("pair_options,wall_options,limited", [
    ("limit_damping", "coulomb_cutback", True),
    ("limit_damping coulomb_cutback", "", True),
    ("", "coulomb_cutback", False)])
def test_an_option_not_given_on_the_wall_fix_is_the_pair_styles(tmp_path, pair_options,
                                                                 wall_options, limited):
    """A disk falling head-on onto the wall at e = 0.5: with limit_damping (the pair's, also
    when the wall fix gives another option) it leaves when the normal force reaches zero, with
    0.646 of its speed (limit_damping_restitution), else with e_w = 0.616. dt = tau_w/400
    keeps the measured value within the first-order bound (0.006) of the right one, far from
    the other."""
    kn, e = 2e5, 0.5
    dt_over_tau = 1 / 400
    deck, _ = disk_on_boundary((kn, e, 0.7, 0.5), law(kn, e, 0.7)["tau_w"] * dt_over_tau, "wall")
    deck = deck.replace("mu 0.5 \n", f"mu 0.5 {pair_options}\n").replace(
        "yplane 0.0 NULL\n", f"yplane 0.0 NULL {wall_options}\n")
    rebound = run_lammps(deck, tmp_path).atoms()["vy"][0]
    expected = limit_damping_restitution(kn, e) if limited else law(kn, e, 0.7)["e_w"]
    print(f"{pair_options} / {wall_options}: rebound {rebound:.5f}, expected {expected:.5f}")
    bound = restitution_error_bound(expected, dt_over_tau)
    assert abs(limit_damping_restitution(kn, e) - law(kn, e, 0.7)["e_w"]) > 4 * bound
    assert abs(rebound - expected) <= bound


def test_compute_pair_local_reports_the_2d_contact_signed(tmp_path):
    """compute pair/local (the pair style's single()) in 2D. A disk (mass 1, radius 1/2) held
    against a bump with overlap 0.05, spinning in place at w for N steps: v_n = 0, v_t = -r w,
    u_t = v_t N dt, and the force loop's F_t = -m (k_t u_t + eta_t v_t) (mu large: no cap),
    seen in the disk's force along t = (0, 1). single() must report those as the signed 2D
    components (p1 F_t, p2 delta, p3 v_n, p4 v_t, p5 u_t), not 3D's magnitudes, and must not
    advance the stored u_t (a second evaluation reports the same). Rules out a 2D single()
    that reads u_t from the wrong slot of the history or loses its sign."""
    kn, e, beta, dt, steps, w, gap = 2e5, 0.7, 0.7, 1e-5, 40, 3.0, 0.95
    deck = f"""
region box block -3 3 -3 3 -0.5 0.5
create_box 2 box
create_atoms 2 single 0 0 0
create_atoms 1 single {gap!r} 0 0
set type * diameter 1.0
set type * density/disc 1.2732395447351628
set type 1 omega 0 0 {w!r}
pair_style gran/mn kn {kn!r} e {e!r} beta {beta!r} mu 1000 wall_types 2
pair_coeff * *
timestep {dt!r}
neigh_modify every 1 delay 0 check no
thermo 0
run {steps}
compute pair all pair/local p1 p2 p3 p4 p5
dump p all local 1 pair.txt c_pair[1] c_pair[2] c_pair[3] c_pair[4] c_pair[5]
dump_modify p format float %.17g
variable fy equal fy[2]
run 0
print "RESULT fy ${{fy}}"
undump p
dump again all local 1 again.txt c_pair[1] c_pair[2] c_pair[3] c_pair[4] c_pair[5]
dump_modify again format float %.17g
run 0
"""
    run = run_lammps(deck, tmp_path)
    rows = []
    for name in ("pair.txt", "again.txt"):
        lines = [l.split() for l in (tmp_path / name).read_text().splitlines()]
        rows += [[float(v) for v in l] for l in lines if len(l) == 5 and not l[0].startswith("I")]
    assert len(rows) == 2 and rows[0] == rows[1]
    ft, delta, vn, vt, ut = rows[0]
    coefficients = law(kn, e, beta)
    vt_expected = -0.5 * w
    ut_expected = vt_expected * steps * dt
    ft_expected = -(coefficients["kt"] * ut_expected + coefficients["eta_t"] * vt_expected)
    print(f"single(): F_t {ft!r} (expected {ft_expected!r}), u_t {ut!r} ({ut_expected!r})")
    assert delta == pytest.approx(1.0 - gap, rel=1e-12)
    assert abs(vn) <= 1e-15 and vt == pytest.approx(vt_expected, rel=1e-12)
    assert ut == pytest.approx(ut_expected, rel=1e-12)
    assert ft == pytest.approx(ft_expected, rel=1e-9)
    assert run.result("fy")[0] == pytest.approx(ft, rel=1e-12)


@pytest.mark.parametrize("wall,start,velocity", [
    ("yplane 0.0 NULL", "0 3.0 0", "vy -1.0"),       # the floor, from above
    ("yplane NULL 5.0", "0 2.0 0", "vy 1.0"),        # the ceiling, from below
    ("zcylinder NULL 5.0", "2.0 0 0", "vx 1.0"),     # the outer circle, from inside
    ("zcylinder 1.0 NULL", "4.0 0 0", "vx -1.0"),    # the inner circle, from outside
])
def test_a_wall_reached_from_beyond_the_neighbour_skin(tmp_path, wall, start, velocity):
    """fix wall/gran/mn visits only the atoms within the neighbour skin of a side at the last
    neighbour-list build (and those still holding a contact's state). A disk that starts 2.5
    from contact (25 skins of 0.1) and moves onto the wall at 1 is taken in only by the builds
    on its way: its bounce is bitwise the one of the same run with a skin of 3, where it is
    listed from the start (one disk: the skin changes nothing else), and it comes back at e_w.
    A list made only at the run's start would let the disk through the wall; one that took in
    only the atoms already in contact at a build would find the contact up to half a skin late
    (with the skin of 3, after the disk has passed through the wall)."""
    kn, e, beta = walls.KN, walls.E, walls.BETA
    dt = law(kn, e, beta)["tau_c"] / 100

    def bounce(skin):
        deck = (walls.header(2).replace("neighbor 0.1 bin", f"neighbor {skin} bin") +
                walls.box(2) + f"create_atoms 1 single {start}\n" + walls.styles(2) +
                f"""set atom 1 {velocity}
fix w all wall/gran/mn {wall}
timestep {dt!r}
thermo 0
run {int(round(3.0 / dt))}
""" + walls.FINAL)
        return run_lammps(deck, tmp_path / f"skin{skin}", header=False)

    near = bounce(3.0)
    assert "neighbor 3.0 bin" in (near.workdir / "in.deck").read_text()
    far = bounce(0.1)
    assert (far.workdir / "final.txt").read_text() == (near.workdir / "final.txt").read_text()
    atoms = far.atoms()
    component, speed = velocity.split()
    rebound = -atoms[component][0] / float(speed)
    e_w = law(kn, e, beta)["e_w"]
    print(f"{wall}: rebound {rebound:.5f}, e_w {e_w:.5f}")
    assert abs(rebound - e_w) <= restitution_error_bound(e_w, 1 / 100)


@pytest.mark.parametrize("wall", ["fix w all wall/gran/mn yplane 0.0 NULL",
                                  "region cup block -5 5 0 9 -0.5 0.5 units box\n"
                                  "fix w all wall/gran/region/mn cup"])
def test_a_disk_grown_into_the_floor_by_fix_adapt_is_pushed_off_it(tmp_path, wall):
    """A disk at rest, centre 0.45 above the floor, grows from diameter 0.2 to 1 under fix
    adapt (0.35 from the floor at first: outside a skin of 0.1). It does not move, so no
    neighbour-list build falls due: a wall fix that visits only the atoms near the wall at the
    last build would leave it 0.05 inside the floor with no force. Under a fix adapt the wall
    fixes visit every atom: the floor pushes it off, and it leaves upwards with its centre
    above 0.5 (half its final diameter)."""
    dt = law(2e5, 0.7, 0.7)["tau_c"] / 50
    header = HEADER.format(plugin=PLUGIN).replace("atom_style sphere", "atom_style sphere 1")
    deck = header.replace("boundary p p p\n", "") + f"""
boundary p f p
region box block -5 5 -1 10 -0.5 0.5
create_box 1 box
create_atoms 1 single 0 0.45 0
set type 1 diameter 0.2
set type 1 density/disc {4 / np.pi!r}
velocity all set 0 0 0
pair_style gran/mn kn 2e5 e 0.7 beta 0.7 mu 0.5
pair_coeff * *
{wall}
timestep {dt!r}
variable diameter equal 0.2+0.8*((step*dt<0.2)*step*dt/0.2+(step*dt>=0.2))
fix grow all adapt 1 atom diameter v_diameter
fix integrate all nve/sphere disc
thermo 0
run {int(round(1.0 / dt))}
write_dump all custom final.txt id x y vx vy modify sort id format float %.17g
"""
    atoms = run_lammps(deck, tmp_path, header=False).atoms()
    print(f"after growing: y {atoms['y'][0]:.6f}, vy {atoms['vy'][0]:.6f}")
    assert atoms["y"][0] > 0.5 and atoms["vy"][0] > 0.0
