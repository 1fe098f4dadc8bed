"""Binary collisions through lmp: restitution and duration against docs/model.md section 3."""
import numpy as np
import pytest

from collision_decks import contact_interval, two_disks
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


@pytest.mark.parametrize("integrator", ["verlet", "ab2"])
def test_sticking_oblique_impact_converges_at_the_integrators_order(tmp_path, integrator):
    """The sticking oblique impact above with beta = e = 0.7 at dt = tau_c/50, /100, /200: e,
    beta and the duration converge at the integrator's order, first under velocity Verlet,
    second under fix nve/ab2, whose u_t follows the trapezoidal rule of its positions (with
    u_t advanced by v_t(t) dt, AB2's beta was first order: 0.665, 0.683, 0.691). Each value
    lies within the integrator's bound (granmn_run.py), plus 1e-3 for the turn of the line of
    centres; the duration within a step (Verlet) or the second-order bound (AB2)."""
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
        bound = (ab2_error_bound(fraction) if integrator == "ab2"
                 else restitution_error_bound(e, fraction))
        assert abs(e_measured - e) <= bound + 1e-3
        assert abs(beta_measured - e) <= bound + 1e-3
        assert abs(duration - 1) <= (ab2_error_bound(fraction) if integrator == "ab2" else fraction)
    low, high = ORDER_RATIO[integrator]
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
