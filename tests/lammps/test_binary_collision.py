"""Binary collisions through lmp: restitution and duration against docs/model.md section 3."""
import re

import numpy as np
import pytest

from collision_decks import contact_interval, disk_on_boundary, two_disks
from granmn_run import (HEADER, ORDER_RATIO, PLUGIN, ab2_error_bound, convergence_ratio, law,
                        restitution_error_bound, run_lammps)

KN = [2 ** p * 1e5 for p in (-1, 8, 17)]


def collide(tmp_path, name, material, dt_over_tau, units="lj", **kwargs):
    tau = law(*material[:3])["tau_c"]
    dt = tau * dt_over_tau
    deck, contact = two_disks(material, dt, **kwargs)
    header = HEADER.format(plugin=PLUGIN).replace("units lj", f"units {units}")
    run = run_lammps(header + deck, tmp_path / name, header=False)
    a = run.atoms()
    (x1, x2), (y1, y2), (vx1, vx2), (vy1, vy2), (w1, w2) = (
        a["x"], a["y"], a["vx"], a["vy"], a["omegaz"])
    d2 = kwargs.get("d2", 1.0)
    # normal from 2 to 1 at the end of the contact, t = (-n_y, n_x)
    n = np.array([x1 - x2, y1 - y2])
    n /= np.linalg.norm(n)
    dv = np.array([vx1 - vx2, vy1 - vy2])
    v_n = n @ dv
    v_t = -n[1] * dv[0] + n[0] * dv[1] - (0.5 * w1 + 0.5 * d2 * w2)
    duration, _, _ = contact_interval(run.table("trace.txt"), contact, dt)
    return dict(v_n=v_n, v_t=v_t, duration=duration, tau=tau, dt=dt)


@pytest.mark.parametrize("kn", KN)
@pytest.mark.parametrize("e", [0.5, 0.7, 0.9])
def test_head_on_restitution_and_duration(tmp_path, kn, e):
    errors = []
    for dt_over_tau in (1 / 100, 1 / 200):
        c = collide(tmp_path, f"dt{dt_over_tau}", (kn, e, 0.7, 0.5), dt_over_tau)
        e_measured = c["v_n"] / 1.0    # approach speed 1
        error = e_measured - e
        bound = restitution_error_bound(e, dt_over_tau)
        print(f"kn={kn:g} e={e} dt=tau/{1/dt_over_tau:.0f}: e_measured={e_measured:.6f} "
              f"error={error:+.2e} bound={bound:.2e} duration/tau_c={c['duration']/c['tau']:.5f}")
        assert abs(error) <= bound
        # the contact starts half a step after a step; its end falls between steps too
        assert abs(c["duration"] - c["tau"]) <= c["dt"]
        errors.append(error)
    # first order in dt: halving dt halves the error (same phase of the contact start)
    assert 1.5 <= errors[0] / errors[1] <= 2.6, errors


def test_unequal_masses_keep_tau_c(tmp_path):
    """Diameters 1.0 and 0.8 (masses 1 and 0.64): with the 2M scaling the duration and the
    restitution do not depend on the masses."""
    for dt_over_tau in (1 / 100, 1 / 200):
        c = collide(tmp_path, f"dt{dt_over_tau}", (2e5, 0.7, 0.7, 0.5), dt_over_tau, d2=0.8)
        assert abs(c["duration"] - c["tau"]) <= c["dt"]
        assert abs(c["v_n"] - 0.7) <= restitution_error_bound(0.7, dt_over_tau)


@pytest.mark.parametrize("beta", [0.5, 0.7, 0.9])
def test_sticking_oblique_impact_has_tangential_restitution_beta(tmp_path, beta):
    """Spin-only slip and mu = 1000: the contact sticks and its tangential relative velocity
    reverses with factor beta. Tolerance: the restitution bound for the tangential mode, plus
    2 beta |ln beta| dt/tau_c because the tangential oscillation is cut where the normal
    contact ends (up to one step off), plus 1e-3 for the turn of the line of centres during
    the contact (tau_c v_t / sigma ~ 2e-4 at this stiffness)."""
    kn = 256e5
    for dt_over_tau in (1 / 100, 1 / 200):
        c = collide(tmp_path, f"dt{dt_over_tau}", (kn, 0.7, beta, 1000.0), dt_over_tau,
                    spin=0.6)
        vt_before = -(0.5 * 0.6 + 0.5 * 0.6)
        beta_measured = -c["v_t"] / vt_before
        bound = (restitution_error_bound(beta, dt_over_tau)
                 + 2 * beta * abs(np.log(beta)) * dt_over_tau + 1e-3)
        print(f"beta={beta} dt=tau/{1/dt_over_tau:.0f}: measured {beta_measured:.6f} "
              f"bound {bound:.2e}")
        assert abs(beta_measured - beta) <= bound
        assert abs(c["v_n"] - 0.7) <= restitution_error_bound(0.7, dt_over_tau) + 1e-3


@pytest.mark.parametrize("integrator", ["verlet", "ab2", "disc/mn verlet", "disc/mn ab2"])
def test_sticking_oblique_impact_converges_at_the_integrators_order(tmp_path, integrator):
    """The sticking oblique impact above with beta = e = 0.7 at dt = tau_c/50, /100, /200: e,
    beta and the duration converge at the integrator's order, first under velocity Verlet,
    second under fix nve/ab2, whose u_t follows the trapezoidal rule of its positions (with
    u_t advanced by v_t(t) dt, AB2's beta was first order: 0.665, 0.683, 0.691). Each value
    lies within the integrator's bound (granmn_run.py), plus 1e-3 for the turn of the line of
    centres; the duration within a step (Verlet) or the second-order bound (AB2). The same
    under fix nve/disc/mn in either scheme: its ab2 must make the pair take AB2's u_t rule."""
    scheme = integrator.split()[-1]
    e = 0.7
    fractions = (1 / 50, 1 / 100, 1 / 200)
    measured = []
    for fraction in fractions:
        c = collide(tmp_path, f"dt{fraction}", (256e5, e, e, 1e6), fraction, spin=0.6,
                    integrator=integrator)
        beta_measured = -c["v_t"] / -(0.5 * 0.6 + 0.5 * 0.6)
        measured.append((c["v_n"], beta_measured, c["duration"] / c["tau"]))
        print(f"{integrator} dt=tau_c/{1 / fraction:.0f}: e {measured[-1][0]:.6f} "
              f"beta {measured[-1][1]:.6f} duration/tau_c {measured[-1][2]:.6f}")
    for fraction, (e_measured, beta_measured, duration) in zip(fractions, measured):
        bound = (ab2_error_bound(fraction) if scheme == "ab2"
                 else restitution_error_bound(e, fraction))
        assert abs(e_measured - e) <= bound + 1e-3
        assert abs(beta_measured - e) <= bound + 1e-3
        assert abs(duration - 1) <= (ab2_error_bound(fraction) if scheme == "ab2" else fraction)
    low, high = ORDER_RATIO[scheme]
    for k, name in enumerate(("e", "beta", "duration")):
        ratio = convergence_ratio([m[k] for m in measured])
        print(f"{name}: convergence ratio {ratio:.2f}")
        assert low <= ratio <= high, (name, ratio)


UNITS = ["lj", "real", "metal", "si", "cgs", "electron", "micro", "nano"]


@pytest.mark.parametrize("units", UNITS)
def test_every_unit_system_gives_the_requested_restitutions_and_duration(tmp_path, units):
    """kn is a stiffness per unit mass (1/time^2 in the unit system's time), so the law gives
    mass x acceleration; LAMMPS turns force into acceleration with its ftm2v factor (1 only in
    lj units), which the styles divide out. The sticking oblique impact of the test above, with
    every quantity in the unit system's own units: e, beta and tau_c as in lj units."""
    dt_over_tau = 1 / 100
    c = collide(tmp_path, units, (256e5, 0.7, 0.7, 1000.0), dt_over_tau, units=units, spin=0.6)
    beta_measured = -c["v_t"] / -(0.5 * 0.6 + 0.5 * 0.6)
    bound_n = restitution_error_bound(0.7, dt_over_tau) + 1e-3
    bound_t = restitution_error_bound(0.7, dt_over_tau) + 2 * 0.7 * abs(np.log(0.7)) * dt_over_tau + 1e-3
    print(f"{units}: e {c['v_n']:.6f} beta {beta_measured:.6f} duration/tau_c "
          f"{c['duration'] / c['tau']:.5f}")
    assert abs(c["v_n"] - 0.7) <= bound_n
    assert abs(beta_measured - 0.7) <= bound_t
    assert abs(c["duration"] - c["tau"]) <= c["dt"]


PASSING = re.compile(r"atoms (\d+) and (\d+) have passed through each other at step (\d+).*"
                     r"relative speed of about (\S+) \(.*it takes kn > (\S+) to stop them")


def collision(material, speed, boundary):
    """Two disks meeting head-on at `speed`, or a disk falling at it onto a bump, at dt = 1/100
    of the contact's duration."""
    if boundary:
        return disk_on_boundary(material, law(*material[:3])["tau_w"] / 100, "bump",
                                v_n=speed)[0]
    return two_disks(material, law(*material[:3])["tau_c"] / 100, v_n=speed)[0]


@pytest.mark.parametrize("boundary", [False, True])
def test_disks_that_would_pass_through_each_other_stop_with_the_stiffness_that_holds_them(
        tmp_path, boundary):
    """At v_rel = 1000 and kn = 2e5 the spring cannot stop two disks within their radius (the
    undamped overlap v/sqrt(2 kn) = 1.58 > 1): their centres cross, the normal flips and they
    fly apart on swapped sides, as if they had bounced with e = -0.75. Like a disk that reaches
    the wall, this is an error naming both atoms, the step, the speed they met at (from the
    energy of the normal motion when it is found: between e and 1 times the true one, damping
    only takes energy away) and the kn that stops them within the smaller radius (the
    damped overlap at v is at most the speed found over omega, so that kn suffices: at 1.1
    times it the collision is an ordinary one, with its restitution to the first-order error
    of the step). Against a bump (mass scale m_i, omega^2 = kn) the same."""
    material = (2e5, 0.7, 0.7, 0.5)
    speed = 1000.0
    run = run_lammps(collision(material, speed, boundary), tmp_path / "passing", check=False)
    assert run.returncode != 0
    found = PASSING.search(run.output.replace("\n", " "))
    assert found, run.output[-2000:]
    ids, met_at, kn_needed = {found[1], found[2]}, float(found[4]), float(found[5])
    assert ids == {"1", "2"}
    assert 0.7 * speed <= met_at <= speed
    material = (1.1 * kn_needed,) + material[1:]
    held = run_lammps(collision(material, speed, boundary), tmp_path / "held").atoms()
    if boundary:
        rebound, expected = held["vy"][np.argmax(held["id"])], law(*material[:3])["e_w"]
    else:
        rebound, expected = held["vx"][1] - held["vx"][0], material[1]
    assert abs(rebound / speed - expected) <= restitution_error_bound(expected, 1 / 100)


def test_a_violent_collision_within_the_radius_is_no_error(tmp_path):
    """v_rel = 100 at kn = 2e5: the overlap peaks near 100/sqrt(4e5) = 0.16, well inside the
    radius 0.5: a collision like any other (e = 0.7 to the first-order error of the step)."""
    c = collide(tmp_path, "violent", (2e5, 0.7, 0.7, 0.5), 1 / 100, v_n=100.0)
    assert abs(c["v_n"] / 100.0 - 0.7) <= restitution_error_bound(0.7, 1 / 100)


def test_disks_that_pass_through_each_other_within_one_step_are_told_the_step_that_works(
        tmp_path):
    """kn = 2e5 stops disks meeting at v = 285 within v/sqrt(2 kn) = 0.45 < 0.5, but a stable
    step of 2.6e-3 (tau_c/1.9, warned about) moves them by 0.74: from apart to 0.59 deep within
    one step. The error says that the step is the cause and gives one with ten steps across
    the radius; at that step the collision is an ordinary one (e = 0.7 to the first-order error
    of the step, here dt/tau_c = 0.035)."""
    material = (2e5, 0.7, 0.7, 0.5)
    speed = 285.0
    deck, _ = two_disks(material, 2.6e-3, v_n=speed, phase=0.2)
    # the list rebuilt at every step: each disk moves by more than the skin in one
    run = run_lammps("neigh_modify delay 0\n" + deck, tmp_path / "coarse", check=False)
    found = re.search(r"atoms 1 and 2 have passed through each other .* they got there within "
                      r"one step .* use a time step below (\S+) \(ten steps",
                      run.output.replace("\n", " "))
    assert run.returncode != 0 and found, run.output[-2000:]
    dt = float(found[1])
    tau = law(*material[:3])["tau_c"]
    c = collide(tmp_path, "resolved", material, dt / tau, v_n=speed)
    assert abs(c["v_n"] / speed - 0.7) <= restitution_error_bound(0.7, dt / tau)
